"""``gearcontact tca``: unloaded tooth contact analysis of a pair.

Writes into ``--out`` (created if missing): ``tca.json`` (summary), ``te0.csv``,
``contact_path.csv``, ``gap_stencil.csv`` (49-sample hardware stencil),
``gap_field.csv`` (80 x 80 host field), ``phase_table.json``, ``phase_table.bin`` and
the figures ``te0.png`` and ``contact_pattern.png``.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..geometry.pair import load_pair
from ..tca.analysis import analyze_pair
from ..tca.curvature import contact_ellipse, relative_curvature
from ..tca.phase_table import encode_binary, write_json
from ..tca.plots import plot_contact_pattern, plot_te0
from ..tca.stencil import write_stencil_csv


def register(sub) -> None:
    p = sub.add_parser("tca", help="unloaded TCA: contact path, TE0, gap stencil, phase table",
                       description=__doc__.split("\n\n")[1])
    p.add_argument("--pair", default="s0003", help="preset name or TOML file (default s0003)")
    p.add_argument("--out", required=True, type=Path, help="output directory")
    p.add_argument("--side", default="drive", choices=("drive", "coast"))
    p.add_argument("--phases", type=int, default=61,
                   help="mesh phases per pinion pitch, both ends included (default 61)")
    p.add_argument("--pairs", type=int, default=2,
                   help="neighbouring tooth pairs on each side (default 2)")
    p.add_argument("--table-records", type=int, default=16,
                   help="maximum records of the binary phase table (default 16)")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run)


def _csv(path: Path, header: list[str], rows) -> None:
    lines = [",".join(header)]
    for row in rows:
        lines.append(",".join(f"{x:.12g}" if isinstance(x, float) else str(x) for x in row))
    path.write_text("\n".join(lines) + "\n")


def run(args) -> int:
    if args.phases < 3:
        raise ValueError(f"--phases = {args.phases} must be >= 3")
    pair = load_pair(args.pair)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    res, flanks = analyze_pair(pair, side=args.side, phases=args.phases, pairs=args.pairs,
                               progress=not args.quiet)
    cyc, mp, rc, ell = res.cycle, res.mean_point, res.mean_curvature, res.mean_ellipse
    pinion, gear = flanks.flank("pinion", args.side), flanks.flank("gear", args.side)
    kin = pair.kinematics()
    blank = pair.blank.as_dict()

    # te0.csv: per phase of the pitch, every pair and the envelope
    _csv(out / "te0.csv",
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
                     e.angle_deg])
    _csv(out / "contact_path.csv",
         ["phi1_deg", "phi2_deg", "x_mm", "y_mm", "z_mm", "nx", "ny", "nz",
          "pinion_u_mm", "pinion_v_mm", "gear_u_mm", "gear_v_mm", "te0_arcsec",
          "A_minus_per_mm", "B_minus_per_mm", "paint_semi_major_mm", "paint_semi_minor_mm",
          "ellipse_angle_deg"], rows)

    write_stencil_csv(res.stencil, out / "gap_stencil.csv")
    f = res.gap_field
    _csv(out / "gap_field.csv", ["s_mm", "t_mm", "gap_mm"],
         zip(map(float, f.s_mm.ravel()), map(float, f.t_mm.ravel()),
             map(float, f.gap_mm.ravel())))
    write_json(res.table, out / "phase_table.json")
    binary = encode_binary(res.table, max_records=args.table_records)
    (out / "phase_table.bin").write_bytes(binary)

    edges = sorted({p.edge_where for p in cyc.path.points if p.edge})
    summary = {
        "pair": pair.name, "side": args.side,
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
        "stencil": {"frame": res.stencil.frame_name,
                    "samples_off_flank": int((~res.stencil.on_flank).sum())},
        "gap_field": {"frame": f.frame_name, "shape": list(f.gap_mm.shape),
                      "spacing_mm": [float(f.s_mm[0, 1] - f.s_mm[0, 0]),
                                     float(f.t_mm[1, 0] - f.t_mm[0, 0])],
                      "nodes_off_flank": int((~f.on_flank).sum())},
        "phase_table_bin_bytes": len(binary),
        "assembly": {k: getattr(pair.assembly, k) for k in ("E_mm", "P_mm", "G_mm", "alpha_deg")},
        "timings_s": res.timings_s,
    }
    (out / "tca.json").write_text(json.dumps(summary, indent=2))
    if not args.no_figures:
        plot_te0(cyc, out / "te0.png", title=f"{pair.name} {args.side}: unloaded TE")
        plot_contact_pattern(pinion, gear, kin, cyc, out / "contact_pattern.png",
                             title=f"{pair.name} {args.side}")
    print(f"{pair.name} {args.side}: TE0 p-p {cyc.te0_pp_arcsec:.3f} arcsec, "
          f"A- {rc.A_minus_per_mm:.5g} B- {rc.B_minus_per_mm:.5g} 1/mm, paint ellipse "
          f"{2 * ell.semi_major_mm:.2f} x {2 * ell.semi_minor_mm:.3f} mm at "
          f"{ell.angle_deg:.1f} deg -> {out}")
    return 0
