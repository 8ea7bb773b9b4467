"""Multi-tooth outputs: figure, files and summary section (pressure on every engaged
flank, load share per pair).

:func:`write_multitooth_outputs` writes ``multitooth.json``
(:meth:`~gearcontact.ltca.multitooth.MultiToothCase.summary`, no timings),
``multitooth.csv`` (one row per loaded cell of every pair: pair, meshing-frame point
(z = gear-axial position), radius about the gear axis, pressure, trimmed as
boundary-inadmissible) and ``multitooth.png``
(:func:`plot_multitooth`); used by ``gearcontact ltca --multi-tooth`` and the main job,
whose ``summary.md`` gets :func:`multitooth_section`.
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from ..halfspace.line_peak import inadmissible_cells  # noqa: E402
from ..figure_files import save_figure  # noqa: E402
from ..tca.export import write_csv  # noqa: E402
from .markdown import md_table, pct_diff  # noqa: E402

__all__ = ["multitooth_section", "plot_multitooth", "write_multitooth_outputs"]


def _wheel_coordinates(p) -> tuple[np.ndarray, np.ndarray]:
    """Gear-axial position z and radius about the gear axis of a pair's cells, mm.

    The meshing frame has the gear axis as z, so (z, radius) of a posed point do not
    change when the gear turns: every pair's patch lands on the same tooth outline."""
    xyz = p.cell_points_mm()
    return xyz[..., 2], np.hypot(xyz[..., 0], xyz[..., 1])


def plot_multitooth(case, path, *, title: str = "", published: dict | None = None) -> Path:
    """Left: the pressure of every engaged pair on the gear flank (gear-axial position vs
    radius, one marker outline per pair; every pair on its own tooth, drawn on one tooth
    outline). Right: load share per pair, rigid and with bending, beside the published
    shares."""
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.6),
                                  gridspec_kw={"width_ratios": [3, 2]})
    # colour scale up to the largest admissible cell (the trimmed edge cells saturate)
    vmax = max(p.peak.p_peak_admissible_mpa for p in case.pairs) or 1.0
    sc = None
    for i, p in enumerate(case.pairs):
        z, r = _wheel_coordinates(p)
        on = p.loads_n > 0.0
        sc = ax.scatter(z[on], r[on], c=p.pressure_mpa[on], s=6, cmap="inferno",
                        vmin=0.0, vmax=vmax, marker="s", linewidths=0)
        k = np.unravel_index(np.argmax(p.loads_n), p.loads_n.shape)
        ax.annotate(f"pair {p.offset:+d}: {case.load_share_pct[i]:.1f} %",
                    (z[k], r[k]), textcoords="offset points", xytext=(-110, -4), fontsize=8,
                    bbox={"boxstyle": "round", "fc": "white", "alpha": 0.85},
                    arrowprops={"arrowstyle": "-", "lw": 0.6})
    if sc is not None:
        fig.colorbar(sc, ax=ax, extend="max",
                     label="pressure (MPa), with bending\n(trimmed edge cells saturate)")
    ax.set_xlabel("gear-axial position z (mm)")
    ax.set_ylabel("radius about the gear axis (mm)")
    cp_pub = (published or {}).get("cp_max_mpa_at_design")
    ax.set_title(f"{title} {case.torque_nm:g} N·m: CP_max {case.cp_max_mpa:.0f}"
                 + (f" (published {cp_pub:g})" if cp_pub else "")
                 + f" MPa\ncell peak {case.p_peak_cell_mpa:.0f}, preview "
                 f"{case.preview_p_max_mpa:.0f} MPa", fontsize=9)
    ax.grid(alpha=0.3)
    labels = [f"{p.offset:+d}" for p in case.pairs]
    x = np.arange(len(case.pairs))
    ax2.bar(x - 0.27, case.load_share_rigid_pct, 0.27, label="rigid teeth")
    ax2.bar(x, case.load_share_pct, 0.27, label="with bending")
    pub = (published or {}).get("multi_tooth_load_share_pct")
    if pub:
        n = min(len(pub), len(x))
        ax2.bar(x[:n] + 0.27, pub[:n], 0.27, label="published", color="0.6")
    ax2.set_xticks(x, labels)
    ax2.set_xlabel("tooth pair (reference first)")
    ax2.set_ylabel("load share (%)")
    ax2.set_title(f"rotation {case.rotation_rigid_arcsec:.1f} -> {case.rotation_arcsec:.1f}"
                  " arcsec with bending", fontsize=9)
    ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3, axis="y")
    fig.tight_layout()
    path = save_figure(fig, path)
    plt.close(fig)
    return path


def write_multitooth_outputs(case, out_dir, *, figures: bool = True, title: str = "",
                             published: dict | None = None) -> list[Path]:
    """``multitooth.json``, ``multitooth.csv`` and (``figures``) ``multitooth.png``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / "multitooth.json", out / "multitooth.csv"]
    paths[0].write_text(json.dumps(case.summary(), indent=2))
    rows = []
    for p in case.pairs:
        xyz = p.cell_points_mm()
        r = np.hypot(xyz[..., 0], xyz[..., 1])
        pr = p.pressure_mpa
        trim = inadmissible_cells(p.loads_n > 0.0, p.off_flank)
        for j, i in zip(*np.nonzero(p.loads_n > 0.0)):
            rows.append([p.offset, *map(float, xyz[j, i]), float(r[j, i]), float(pr[j, i]),
                         int(trim[j, i])])
    write_csv(paths[1], ["pair", "x_mm", "y_mm", "z_mm", "gear_radius_mm", "pressure_mpa",
                         "trimmed"], rows)
    if figures:
        paths.append(plot_multitooth(case, out / "multitooth.png", title=title,
                                     published=published))
    return paths


def multitooth_section(case, pub: dict) -> list[str]:
    """Markdown of the multi-tooth section of ``summary.md``: ours beside the published
    load shares, rotation increase from bending, and CP_max vs the preview."""
    shares = pub.get("multi_tooth_load_share_pct")

    def fmt(values):
        return " / ".join(f"{v:.1f}" for v in values)

    ref = case.pairs[0]
    out = [f"## Multi-tooth loaded contact at P0, {case.torque_nm:g} N·m (rigid and with "
           "tooth bending)", "",
           f"All tooth pairs within reach at the phase of P0 in one torque-balanced LCP "
           f"(pairs {', '.join(f'{p.offset:+d}' for p in case.pairs)}, reference first), "
           "with rigid teeth and with the shell bending of both teeth "
           "(`gearcontact ltca --multi-tooth`; docs/bending.md). CP_max: the "
           "incomplete-ellipse line-contact peak after trimming the boundary-inadmissible "
           "edge cells (`gearcontact.halfspace.line_peak`).", ""]
    out.append(md_table(["quantity", "ours", "published"], [
        ["engaged pairs (bending)", sum(p.load_n > 0 for p in case.pairs),
         len(shares) if shares else None],
        ["load shares rigid (%)", fmt(case.load_share_rigid_pct), None],
        ["load shares with bending (%)", fmt(case.load_share_pct),
         fmt(shares) if shares else None],
        ["reference pair load with bending (N)", ref.load_n,
         pub.get("multi_tooth_reference_load_n")],
        ["mesh rotation rigid (arcsec)", case.rotation_rigid_arcsec,
         pub.get("mesh_rotation_rigid_arcsec_at_design")],
        ["mesh rotation with bending (arcsec)", case.rotation_arcsec,
         pub.get("mesh_rotation_bending_arcsec_at_design")],
        ["rotation increase from bending (%)",
         pct_diff(case.rotation_arcsec, case.rotation_rigid_arcsec),
         pub.get("mesh_rotation_bending_increase_pct")],
        ["CP_max (MPa)", case.cp_max_mpa, pub.get("cp_max_mpa_at_design")],
        ["preview p_max, reference pair at its load (MPa)", case.preview_p_max_mpa,
         pub.get("preview_p_max_mpa_at_design")],
        ["CP_max vs preview (%)", pct_diff(case.cp_max_mpa, case.preview_p_max_mpa),
         pct_diff(pub["cp_max_mpa_at_design"], pub["preview_p_max_mpa_at_design"])
         if "cp_max_mpa_at_design" in pub else None],
        ["raw cell peak (MPa)", case.p_peak_cell_mpa, None],
        ["trimmed edge cells / their load (N)",
         f"{sum(p.peak.trimmed_cells for p in case.pairs)} / "
         f"{sum(p.peak.trimmed_load_n for p in case.pairs):.0f}", None],
        ["converged", case.converged, None]]))
    out += ["", "Figure: ![multi-tooth](multitooth.png)", ""]
    return out
