"""Files of an unloaded TCA: the data and figures ``gearcontact tca`` writes.

``write_tca_outputs`` writes into one directory: ``tca.json`` (summary), ``te0.csv``,
``contact_path.csv``, ``gap_stencil.csv`` (49-sample hardware stencil, format of
:mod:`gearcontact.contract.stencil`), ``gap_field.csv`` (80 x 80 host field),
``phase_table.json``, ``phase_table.bin`` and the figures ``te0.png``,
``contact_pattern.png`` and ``flanks_in_mesh.png`` (the geometry's flank-sheet view at
P0). Used by the ``tca`` and ``analyze`` commands. ``write_line_contact_outputs``
writes the ``tca.json`` of a conjugate pair (line contact, :mod:`.line_contact`).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..preview.fit.reference import fit_curvatures
from .curvature import contact_ellipse, relative_curvature
from .phase_table import encode_binary, write_json
from .stencil import write_stencil_csv

__all__ = ["write_tca_outputs", "write_line_contact_outputs", "write_csv", "without_timings", "TIMING_KEYS"]

#: Keys of result dicts that hold wall-clock timings. Result files leave them out (two
#: identical runs give byte-identical files); the command line records them in run.json.
TIMING_KEYS = ("timings_s", "solve_ms", "field_ms", "solve_ms_per_phase",
               "field_ms_per_phase")


def without_timings(doc: dict) -> tuple[dict, dict]:
    """``(doc without the TIMING_KEYS, the timings removed)``."""
    clean = {k: v for k, v in doc.items() if k not in TIMING_KEYS}
    return clean, {k: doc[k] for k in TIMING_KEYS if k in doc}


def write_csv(path: Path, header: list[str], rows) -> None:
    """Write a CSV with a header row; floats with 12 significant digits."""
    lines = [",".join(header)]
    for row in rows:
        lines.append(",".join(f"{x:.12g}" if isinstance(x, float) else str(x) for x in row))
    path.write_text("\n".join(lines) + "\n")


def write_tca_outputs(res, flanks, pair, out, *, side: str | None = None,
                      table_records: int = 16, figures: bool = True) -> dict:
    """Write the TCA files of ``res`` (a :class:`~.analysis.TcaAnalysis` of ``pair``'s
    ``side`` on ``flanks``) into the directory ``out`` (created if missing).

    Returns the ``tca.json`` summary dict.
    """
    side = pair.design_side if side is None else side
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    cyc, mp, rc, ell = res.cycle, res.mean_point, res.mean_curvature, res.mean_ellipse
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    kin = pair.kinematics()
    blank = pair.blank.as_dict()

    # te0.csv: per phase of the pitch, every pair and the envelope
    write_csv(out / "te0.csv",
         ["phi1_deg"] + [f"te0_pair{j:+d}_arcsec" for j in cyc.pair_offsets]
         + ["te0_arcsec", "active_pair", "pairs_in_contact"],
         [[float(np.degrees(cyc.phi1_rad[k]))]
          + [float(x) for x in cyc.te0_pairs_arcsec[:, k]]
          + [float(cyc.envelope_arcsec[k]), int(cyc.active_pair[k]),
             int(cyc.pairs_in_contact[k])] for k in range(len(cyc.phi1_rad))])

    # contact_path.csv: the whole interior path of one tooth pair
    rows = []
    for p in cyc.path.points:
        if p.edge:
            continue
        c = relative_curvature(pinion, gear, kin, p)
        e = contact_ellipse(c)
        rows.append([float(np.degrees(p.phi1_rad)), float(np.degrees(p.phi2_rad)),
                     *map(float, p.point_mm), *map(float, p.normal), float(p.u1),
                     float(p.v1), float(p.u2), float(p.v2), float(p.te0_arcsec),
                     c.A_minus_per_mm, c.B_minus_per_mm, e.semi_major_mm, e.semi_minor_mm,
                     e.angle_deg, p.edge_contact])
    write_csv(out / "contact_path.csv",
         ["phi1_deg", "phi2_deg", "x_mm", "y_mm", "z_mm", "nx", "ny", "nz",
          "pinion_u_mm", "pinion_v_mm", "gear_u_mm", "gear_v_mm", "te0_arcsec",
          "A_minus_per_mm", "B_minus_per_mm", "paint_semi_major_mm", "paint_semi_minor_mm",
          "ellipse_angle_deg", "edge_contact"], rows)

    write_stencil_csv(res.stencil, out / "gap_stencil.csv")
    f = res.gap_field
    write_csv(out / "gap_field.csv", ["s_mm", "t_mm", "gap_mm"],
         zip(map(float, f.s_mm.ravel()), map(float, f.t_mm.ravel()),
             map(float, f.gap_mm.ravel())))
    write_json(res.table, out / "phase_table.json", edges=res.edges)
    binary = encode_binary(res.table, max_records=table_records)
    (out / "phase_table.bin").write_bytes(binary)

    edges = sorted({p.edge_where for p in cyc.path.points if p.edge})
    stage_c = fit_curvatures(res.stencil.gap_mm.ravel())
    summary = {
        "pair": pair.name, "side": side,
        "te0_pp_arcsec": cyc.te0_pp_arcsec,
        "mating_point_mm": [float(x) for x in mp.point_mm],
        "normal": [float(x) for x in mp.normal],
        "A_minus": rc.A_minus_per_mm, "B_minus": rc.B_minus_per_mm,
        "kappa_rel_per_mm": [rc.kappa_max_per_mm, rc.kappa_min_per_mm],
        "paint_ellipse": {"paint_mm": ell.paint_mm, "semi_major_mm": ell.semi_major_mm,
                          "semi_minor_mm": ell.semi_minor_mm, "ratio": ell.ratio,
                          "angle_from_lengthwise_deg": ell.angle_deg},
        "pitch_angles_deg": blank["pitch_angles_deg"],
        "spiral_angles_deg": blank["spiral_angles_deg"],
        "phases_per_pitch": len(cyc.phi1_rad),
        "pairs_in_contact_max": int(cyc.pairs_in_contact.max()),
        "pattern_on_flank": bool(res.pattern_on_flank.all()),
        "path_edges": edges,
        # per phase of the pitch: "" inside, else the flank edge reached (tca.edges)
        "edge_phases": res.edge_counts,
        "phase_edges": list(res.edges),
        # per phase of the pitch: "surface" (flank on flank) or the flank edge touching
        # the other flank (tca.edge_contact)
        "phase_contact": [p.edge_contact or "surface" for p in cyc.contact],
        "edge_contact_phases": res.edge_contact_counts,
        "mean_point_contact": mp.edge_contact or "surface",
        "stencil": {"frame": res.stencil.frame_name,
                    "samples_off_flank": int((~res.stencil.on_flank).sum()),
                    # blade-relief kinks the samples straddle (no quadric across them)
                    "kinks": list(res.stencil.kinks),
                    "off_flank_fill": "osculating quadric (1/2) q^T B q at P0",
                    # what stage C (fp64 reference) reads from this stencil
                    "stage_c_A_minus": stage_c.A_minus_per_mm,
                    "stage_c_B_minus": stage_c.B_minus_per_mm},
        "gap_field": {"frame": f.frame_name, "shape": list(f.gap_mm.shape),
                      "spacing_mm": [float(f.s_mm[0, 1] - f.s_mm[0, 0]),
                                     float(f.t_mm[1, 0] - f.t_mm[0, 0])],
                      "nodes_off_flank": int((~f.on_flank).sum())},
        "phase_table_bin_bytes": len(binary),
        "assembly": {k: getattr(pair.assembly, k) for k in ("E_mm", "P_mm", "G_mm", "alpha_deg")},
    }   # no timings: identical runs give identical files (res.timings_s has them)
    (out / "tca.json").write_text(json.dumps(summary, indent=2))
    if figures:
        # matplotlib only here (0.5 s of CPU per process): .plots chooses Agg first
        from .plots import plot_contact_pattern, plot_te0
        import matplotlib.pyplot as plt  # noqa: I001 (after .plots: Agg chosen there)

        from ..geometry.plots import plot_flanks_in_mesh

        fig = plot_flanks_in_mesh(flanks, side=side, phi2_rad=mp.phi2_rad,
                                  point_mm=mp.point_mm, path=out / "flanks_in_mesh.png")
        plt.close(fig)
        plot_te0(cyc, out / "te0.png", title=f"{pair.name} {side}: unloaded TE")
        plot_contact_pattern(pinion, gear, kin, cyc, out / "contact_pattern.png",
                             title=f"{pair.name} {side}", edges=res.edges)
    return summary


def write_line_contact_outputs(result, out, *, pair_name: str, side: str | None) -> dict:
    """Write ``tca.json`` of a line contact into the directory ``out`` (created if
    missing): ``pair``, ``side`` (as requested; ``None`` for the design side) and
    :meth:`~.line_contact.LineContactResult.as_dict`. Returns that dict."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    doc = {"pair": pair_name, "side": side, **result.as_dict()}
    (out / "tca.json").write_text(json.dumps(doc, indent=2))
    return doc
