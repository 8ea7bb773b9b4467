"""Files of the loaded TE of a cylindrical pair and its Harris map (docs/cylindrical.md
sec. 7): what ``gearcontact lte`` writes for a ``kind = "cylindrical"`` pair.

:func:`write_cylindrical_lte_outputs` writes into one directory ``lte.json`` (summary;
``teeth`` names the tooth model, and with a rigid-tooth run beside a bending one its
key ``rigid`` holds the rigid loaded TE and stiffness), ``lte.csv`` (per phase: TE0,
loaded TE, load share per pair, peak pressure, mesh stiffness; the rigid loaded TE and
stiffness beside them), ``line_load.csv`` (per phase, loaded pair and face cell:
``contact``: line, a tip edge touching beyond the path with no line, or one beyond a
helical line in the zone (``"pinion tip beyond line"``), the lever of its normal, load per
unit face width and the peak pressure across the line), ``harris_map.csv`` (loaded TE
p-p per tip relief and torque) and the figures ``lte.png`` and ``harris_map.png``. No timings:
identical runs write identical files.
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from ..analytic.iso6336 import (cylindrical_pair_stiffness,  # noqa: E402
                                reduced_mass_kg_per_mm)
from ..figure_files import save_figure  # noqa: E402
from ..ltca.cylindrical_lte import CylindricalLoadedTE, HarrisMap  # noqa: E402
from ..tca.cylindrical_tip import TIP_EDGES  # noqa: E402
from ..tca.export import write_csv  # noqa: E402

__all__ = ["LINE_LOAD_COLUMNS", "cylindrical_lte_summary", "iso_method_b",
           "iso_reduced_mass_kg_per_mm", "line_load_rows", "plot_cylindrical_lte",
           "plot_harris_map", "write_cylindrical_lte_outputs"]


def iso_method_b(pair):
    """ISO 6336-1 Method B single and mesh stiffness
    (:func:`~gearcontact.analytic.iso6336.cylindrical_pair_stiffness`) of a cylindrical
    pair from its ISO 21771 geometry: teeth, helix angles, transverse contact ratio,
    profile shifts, dedendum factor and the rack's pressure angle."""
    g = pair.geometry
    return cylindrical_pair_stiffness(
        pinion_teeth=pair.pinion_teeth, gear_teeth=pair.gear_teeth,
        helix_angle_deg=g.helix_angle_deg, base_helix_angle_deg=g.base_helix_angle_deg,
        transverse_contact_ratio=g.transverse_contact_ratio,
        profile_shift_pinion=g.profile_shift_pinion, profile_shift_gear=g.profile_shift_gear,
        dedendum_per_module=pair.dedendum_factor,
        rack_pressure_angle_deg=g.normal_pressure_angle_deg)


def iso_reduced_mass_kg_per_mm(pair) -> float:
    """ISO 6336-1's reduced mass per face width of a cylindrical pair, kg/mm
    (:func:`~gearcontact.analytic.iso6336.reduced_mass_kg_per_mm`: solid discs, the
    pinion's mean diameter (d_a1 + d_f1) / 2)."""
    g = pair.geometry
    return reduced_mass_kg_per_mm(
        mean_diameter_pinion_mm=0.5 * (g.tip_diameter_pinion_mm + g.root_diameter_pinion_mm),
        base_diameter_pinion_mm=g.base_diameter_pinion_mm, ratio=pair.ratio)


def _iso(pair, lte: CylindricalLoadedTE, rigid: CylindricalLoadedTE | None) -> dict:
    """ISO 6336-1 Method B c' and c_gamma_alpha beside the computed stiffness (and the
    rigid-tooth one), with the tangential line load F_t / b at the gear's reference
    circle (the standard holds from 100 N/mm; docs/cylindrical.md sec. 7)."""
    g = pair.geometry
    iso = iso_method_b(pair)
    c_ga = iso.c_gamma_alpha_n_per_mm_um
    ft_b = 2e3 * lte.torque_nm / (g.reference_diameter_gear_mm * g.face_width_mm)
    out = {"line_load_ft_per_b_n_per_mm": ft_b, "within_validity": ft_b >= 100.0,
           "c_single_n_per_mm_um": iso.c_n_per_mm_um,
           "c_gamma_alpha_n_per_mm_um": c_ga,
           "c_gamma_beta_n_per_mm_um": iso.c_gamma_beta_n_per_mm_um,
           "mean_stiffness_over_c_gamma_alpha": lte.mean_stiffness_n_per_mm_um / c_ga}
    if rigid is not None:
        out["rigid_mean_stiffness_over_c_gamma_alpha"] = rigid.mean_stiffness_n_per_mm_um / c_ga
    out["note"] = (
        ("contact, shell bending of both teeth and their fillet and rim: a theory like "
         "the standard's c'_th, which C_M = 0.8 corrects to measured gears (the model "
         "lands near c_gamma_alpha / C_M on the 20/40 spur pair)" if lte.bending else
         "rigid teeth: contact flattening only, where the standard adds bending and "
         "foundation")
        + "; it holds from F_t / b = 100 N/mm for full lines of contact (below, or with "
          "crowning and relief, the secant stiffness falls: docs/cylindrical.md sec. 7)")
    return out


def _teeth(bending: bool) -> str:
    return "bending" if bending else "rigid"


def cylindrical_lte_summary(lte: CylindricalLoadedTE, harris: HarrisMap | None, pair, *,
                            side: str, rigid: CylindricalLoadedTE | None = None) -> dict:
    """The ``lte.json`` dict (``rigid``: the rigid-tooth run beside a bending one)."""
    out = {
        "pair": pair.name, "kind": "cylindrical", "side": side, "teeth": _teeth(lte.bending),
        "phases_per_pitch": len(lte.phi1_rad), "torque_gear_nm": lte.torque_nm,
        "normal_load_n": lte.normal_load_n,
        "te0_pp_arcsec": float(lte.te0_arcsec.max() - lte.te0_arcsec.min()),
        "lte_pp_arcsec": lte.lte_pp_arcsec,
        "lte_mean_arcsec": float(np.mean(lte.lte_arcsec[:-1])),
        "max_pressure_mpa": float(lte.max_pressure_mpa.max()),
        # a peak on a sharp edge (a loaded line end, a tip edge) is the half-space's
        # singular pressure there, which grows with the grid (docs/cylindrical.md sec. 7)
        "max_pressure_on_edge": bool(lte.peak_at_edge[int(np.argmax(lte.max_pressure_mpa))]),
        "pressure_peak_on_edge_phases": int(lte.peak_at_edge.sum()),
        "max_line_load_n_per_mm": float(lte.line_load_n_per_mm.max()),
        "mean_line_load_n_per_mm": lte.normal_load_n / lte.face_width_mm,
        "mesh_stiffness_mean_n_per_mm_um": lte.mean_stiffness_n_per_mm_um,
        "mesh_stiffness_min_max_n_per_mm_um": [float(lte.stiffness_n_per_mm_um.min()),
                                               float(lte.stiffness_n_per_mm_um.max())],
        "mesh_stiffness_definition": "secant F_n / (b delta), delta the normal approach "
                                     "from the unloaded rest (docs/cylindrical.md sec. 7)",
        "iso6336_method_b": _iso(pair, lte, rigid),
        "max_load_share": float(lte.load_share.max()),
        # pairs loaded at a tip edge beyond their line (premature / prolonged contact)
        "tip_contact_phases": 0 if lte.edge_label is None else int(
            ((lte.edge_label != "") & (lte.load_share > 0.0)).any(axis=0).sum()),
        # tip edges beyond a helical line in the zone carrying (sections past the path end)
        "beyond_line_tip_phases": 0 if lte.beyond_load_share is None else int(
            (lte.beyond_load_share > 0.0).any(axis=(0, 2)).sum()),
        "beyond_line_max_load_share": 0.0 if lte.beyond_load_share is None else float(
            lte.beyond_load_share.max()),
        "grid_dx_mm": lte.grid_dx_mm, "grid_dy_mm": lte.grid_dy_mm,
        "edge_touch": lte.edge_touch, "converged": lte.converged,
        "lcp_iterations_max": int(lte.iterations.max()),
    }
    if rigid is not None:
        out["rigid"] = {
            "lte_pp_arcsec": rigid.lte_pp_arcsec,
            "lte_mean_arcsec": float(np.mean(rigid.lte_arcsec[:-1])),
            "max_pressure_mpa": float(rigid.max_pressure_mpa.max()),
            "mesh_stiffness_mean_n_per_mm_um": rigid.mean_stiffness_n_per_mm_um,
            "mesh_stiffness_min_max_n_per_mm_um": [float(rigid.stiffness_n_per_mm_um.min()),
                                                   float(rigid.stiffness_n_per_mm_um.max())],
            "max_load_share": float(rigid.load_share.max()), "converged": rigid.converged}
    if harris is not None:
        out["harris_map"] = {
            "torques_gear_nm": harris.torques_nm.tolist(),
            "tip_reliefs_um": harris.tip_reliefs_um.tolist(),
            "lte_pp_arcsec": harris.lte_pp_arcsec.tolist(),
            "te0_pp_arcsec": harris.te0_pp_arcsec.tolist(),
            "mean_stiffness_n_per_mm_um": harris.mean_stiffness_n_per_mm_um.tolist(),
            "teeth": _teeth(harris.bending),
            "edge_touch": harris.edge_touch, "converged": harris.converged}
    return out


def plot_cylindrical_lte(lte: CylindricalLoadedTE, path, *, title: str = "",
                         rigid: CylindricalLoadedTE | None = None) -> Path:
    """TE0 and loaded TE over the pitch (top; the rigid-tooth one dashed when given), load
    share per pair and the mesh stiffness (bottom)."""
    phi = np.degrees(lte.phi1_rad)
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    ax.plot(phi, lte.te0_arcsec, "k-", label=f"TE0 (p-p {np.ptp(lte.te0_arcsec):.2f})")
    ax.plot(phi, lte.lte_arcsec, "C0.-", ms=3,
            label=f"loaded TE, {_teeth(lte.bending)}, {lte.torque_nm:g} N·m "
                  f"(p-p {lte.lte_pp_arcsec:.2f})")
    if rigid is not None:
        ax.plot(phi, rigid.lte_arcsec, "C1--", lw=1.0,
                label=f"loaded TE, rigid teeth (p-p {rigid.lte_pp_arcsec:.2f})")
    ax.set_ylabel("TE (arcsec)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    for j, s in zip(lte.pair_offsets, lte.load_share):
        if s.max() > 0.0:
            ax2.plot(phi, s, lw=1.2, label=f"pair {j:+d}")
    ax2.set_ylabel("load share")
    ax2.set_xlabel("pinion rotation phi1 (deg)")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8, loc="upper left")
    right = ax2.twinx()
    right.plot(phi, lte.stiffness_n_per_mm_um, "k--", lw=1.0,
               label=f"stiffness, {_teeth(lte.bending)}")
    if rigid is not None:
        right.plot(phi, rigid.stiffness_n_per_mm_um, "k:", lw=1.0,
                   label="stiffness, rigid teeth")
    right.set_ylabel("mesh stiffness (N/(mm·µm))")
    right.legend(fontsize=8, loc="upper right")
    if title:
        ax.set_title(title)
    return save_figure(fig, path, tight=True)


def plot_harris_map(harris: HarrisMap, path, *, title: str = "") -> Path:
    """Loaded TE p-p vs gear torque, one curve per tip relief."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for c, pp in zip(harris.tip_reliefs_um, harris.lte_pp_arcsec):
        ax.plot(harris.torques_nm, pp, "o-", ms=4, label=f"C_a {c:g} µm")
    ax.set_xlabel("gear torque (N·m)")
    ax.set_ylabel("loaded TE p-p (arcsec)")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or f"Harris map ({_teeth(harris.bending)})")
    return save_figure(fig, path, tight=True)


#: Columns of ``line_load.csv`` (:func:`line_load_rows`).
LINE_LOAD_COLUMNS = ["phi1_deg", "pair", "contact", "lever_mm", "pinion_z_mm", "load_n_per_mm",
                     "peak_pressure_mpa"]


def line_load_rows(lte: CylindricalLoadedTE, phases) -> list[list]:
    """Rows of ``line_load.csv`` (:data:`LINE_LOAD_COLUMNS`) at the phase indices
    ``phases``: per loaded pair and face cell its contact (line, a tip edge, a tip edge
    beyond the line), lever, load per unit face width and peak pressure across."""
    phi = np.degrees(lte.phi1_rad)
    rows = []
    beyond = lte.beyond_rows if lte.beyond_rows is not None else \
        np.full(lte.line_load_n_per_mm.shape, -1)
    for k in phases:
        for p, j in enumerate(lte.pair_offsets):
            kind = (lte.edge_label[p, k] if lte.edge_label is not None else "") or "line"
            # the line's (or tip edge's) cells, then those of a tip edge beyond the line
            for e, label, share, lever in [(-1, kind, lte.load_share[p, k], lte.lever_mm[p, k])] \
                    + [(e, f"{edge.label} beyond line", lte.beyond_load_share[p, k, e],
                        lte.beyond_lever_mm[p, k, e]) for e, edge in enumerate(TIP_EDGES)
                       if lte.beyond_load_share is not None]:
                if share <= 0.0:
                    continue
                rows += [[float(phi[k]), j, label, float(lever), float(z), float(w), float(pm)]
                         for z, w, pm, b in zip(lte.z_mm, lte.line_load_n_per_mm[p, k],
                                                lte.line_pressure_mpa[p, k], beyond[p, k])
                         if b == e]
    return rows


def write_cylindrical_lte_outputs(lte: CylindricalLoadedTE, harris: HarrisMap | None, pair,
                                  out, *, side: str, figures: bool = True,
                                  rigid: CylindricalLoadedTE | None = None) -> dict:
    """Write the files of the module docstring into ``out`` (created if missing; the Harris
    map's files only with ``harris``; the rigid columns and key only with ``rigid``, the
    rigid-tooth run on the same cycle); returns the ``lte.json`` dict."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    phi = np.degrees(lte.phi1_rad)
    extra = ["lte_rigid_arcsec", "mesh_stiffness_rigid_n_per_mm_um"] if rigid is not None else []
    write_csv(out / "lte.csv",
              ["phi1_deg", "te0_arcsec", "lte_arcsec"]
              + [f"load_share_pair{j:+d}" for j in lte.pair_offsets]
              + ["max_pressure_mpa", "mesh_stiffness_n_per_mm_um"] + extra,
              [[float(phi[k]), float(lte.te0_arcsec[k]), float(lte.lte_arcsec[k])]
               + [float(s) for s in lte.load_share[:, k]]
               + [float(lte.max_pressure_mpa[k]), float(lte.stiffness_n_per_mm_um[k])]
               + ([float(rigid.lte_arcsec[k]), float(rigid.stiffness_n_per_mm_um[k])]
                  if rigid is not None else [])
               for k in range(len(phi))])
    write_csv(out / "line_load.csv", LINE_LOAD_COLUMNS,
              line_load_rows(lte, range(len(phi))))
    if harris is not None:
        write_csv(out / "harris_map.csv",
                  ["tip_relief_um", "te0_pp_arcsec"]
                  + [f"lte_pp_{t:g}nm_arcsec" for t in harris.torques_nm],
                  [[float(c), float(harris.te0_pp_arcsec[r])]
                   + [float(x) for x in harris.lte_pp_arcsec[r]]
                   for r, c in enumerate(harris.tip_reliefs_um)])
    summary = cylindrical_lte_summary(lte, harris, pair, side=side, rigid=rigid)
    (out / "lte.json").write_text(json.dumps(summary, indent=2))
    if figures:
        label = f"{pair.name} {side}"
        plot_cylindrical_lte(lte, out / "lte.png", rigid=rigid,
                             title=f"{label}: loaded TE ({_teeth(lte.bending)})")
        if harris is not None:
            plot_harris_map(harris, out / "harris_map.png",
                            title=f"{label}: Harris map ({_teeth(harris.bending)})")
    return summary
