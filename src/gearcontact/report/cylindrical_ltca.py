"""Files of the loaded contact of a cylindrical pair at the pitch-point phase
(:mod:`gearcontact.ltca.cylindrical_ltca`; docs/cylindrical.md sec. 12): what
``gearcontact ltca`` writes for a ``kind = "cylindrical"`` pair.

:func:`write_cylindrical_ltca_outputs` writes into one directory ``ltca.json`` (torque,
normal load, the phase, TE0 and loaded TE there, the gear rotation the load adds and the
normal approach, mesh stiffness, p_max and whether it sits on a sharp edge, and per pair
its contact, normal load, share, lever, loaded length, peak pressure), ``line_load.csv``
(the rows of the loaded TE's ``line_load.csv`` at this phase:
:func:`~gearcontact.report.cylindrical_lte.line_load_rows`), ``pressure_map.csv`` (per
loaded pair and cell: axial position on the pinion face, position across the line,
pressure) and ``pressure_map.png`` (one pressure map per loaded pair, its line load
beside). No timings: identical runs write identical files.
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from ..figure_files import save_figure  # noqa: E402
from ..ltca.cylindrical_ltca import CylindricalPhaseContact  # noqa: E402
from ..tca.cylindrical_tip import TIP_EDGES  # noqa: E402
from ..tca.export import write_csv  # noqa: E402
from ..tca.types import ARCSEC_PER_RAD  # noqa: E402
from .cylindrical_lte import LINE_LOAD_COLUMNS, line_load_rows  # noqa: E402

__all__ = ["cylindrical_ltca_summary", "plot_cylindrical_ltca",
           "write_cylindrical_ltca_outputs"]


def _loaded(c: CylindricalPhaseContact) -> list[int]:
    """Indices of the pairs carrying load at the phase (line, tip edge or beyond rows)."""
    k = c.phase
    return [p for p in range(len(c.lte.pair_offsets))
            if c.lte.load_share[p, k] > 0.0 or c.lte.beyond_load_share[p, k].any()]


def cylindrical_ltca_summary(c: CylindricalPhaseContact, pair, *, side: str) -> dict:
    """The ``ltca.json`` dict."""
    lte, k = c.lte, c.phase
    pairs = []
    for p in _loaded(c):
        on = lte.phase_pressure_mpa[p]
        pairs.append({
            "pair": lte.pair_offsets[p], "contact": str(lte.edge_label[p, k]) or "line",
            "load_n": float(c.load_n[p]), "load_share": float(lte.load_share[p, k]),
            "lever_mm": float(lte.lever_mm[p, k]),
            "loaded_length_mm": float(lte.loaded_length_mm[p, k]),
            "line_end_loaded": bool(lte.line_end_loaded[p, k]),
            "max_line_load_n_per_mm": float(lte.line_load_n_per_mm[p, k].max()),
            "p_max_mpa": float(on.max()),
            "beyond_line": {e.label: {"load_n": float(c.beyond_load_n[p, i]),
                                      "lever_mm": float(lte.beyond_lever_mm[p, k, i])}
                            for i, e in enumerate(TIP_EDGES) if c.beyond_load_n[p, i] > 0.0}})
    return {
        "pair": pair.name, "kind": "cylindrical", "side": side,
        "teeth": "bending" if lte.bending else "rigid",
        "phase": "pitch point of pair 0", "phase_index": k,
        "phases_per_pitch": len(lte.phi1_rad), "phi1_deg": float(np.degrees(c.phi1_rad)),
        "torque_gear_nm": lte.torque_nm, "normal_load_n": lte.normal_load_n,
        "torque_from_loads_nm": c.torque_from_loads_nm,
        "te0_arcsec": float(lte.te0_arcsec[k]), "lte_arcsec": float(lte.lte_arcsec[k]),
        "rotation_rad": c.rotation_rad, "rotation_arcsec": c.rotation_rad * ARCSEC_PER_RAD,
        "approach_mm": c.approach_mm, "gear_lever_mm": c.gear_lever_mm,
        "mesh_stiffness_n_per_mm_um": float(lte.stiffness_n_per_mm_um[k]),
        "p_max_mpa": c.p_max_mpa,
        # a peak on a sharp edge (a loaded line end, a tip edge) is the half-space's
        # singular pressure there, which grows with the grid (docs/cylindrical.md sec. 7)
        "p_max_on_edge": bool(lte.peak_at_edge[k]),
        "pairs_loaded": len(pairs), "pairs": pairs,
        "face_width_mm": lte.face_width_mm,
        "grid_dx_mm": lte.grid_dx_mm, "grid_dy_mm": lte.grid_dy_mm,
        "cells_along": len(lte.z_mm), "cells_across": int(lte.phase_pressure_mpa.shape[-1]),
        "edge_touch": lte.edge_touch, "converged": lte.converged,
        "lcp_iterations": int(lte.iterations[k]),
    }


def plot_cylindrical_ltca(c: CylindricalPhaseContact, path, *, title: str = "") -> Path:
    """One pressure map per loaded pair (axial position on the pinion face vs position
    across the line, one colour scale), its line load along the face below."""
    lte, loaded = c.lte, _loaded(c)
    fig, axes = plt.subplots(2, len(loaded), figsize=(3.6 * len(loaded) + 1.0, 6.5),
                             squeeze=False, gridspec_kw={"height_ratios": [3, 1]})
    x, z = c.across_mm, lte.z_mm
    vmax = max(c.p_max_mpa, 1e-12)
    for col, p in enumerate(loaded):
        ax, ax2 = axes[0, col], axes[1, col]
        im = ax.pcolormesh(x, z, lte.phase_pressure_mpa[p], shading="nearest", cmap="inferno",
                           vmin=0.0, vmax=vmax)
        ax.set_title(f"pair {lte.pair_offsets[p]:+d} ({str(lte.edge_label[p, c.phase]) or 'line'})"
                     f"\nshare {lte.load_share[p, c.phase]:.3f}", fontsize=9)
        ax.set_xlabel("across the line (mm)")
        ax2.plot(z, lte.line_load_n_per_mm[p, c.phase], "C0.-", ms=3)
        ax2.set_xlabel("pinion face z (mm)")
        ax2.grid(alpha=0.3)
        if col == 0:
            ax.set_ylabel("pinion face z (mm)")
            ax2.set_ylabel("line load (N/mm)")
    fig.colorbar(im, ax=axes[0, :].tolist(), label="pressure (MPa)")
    fig.suptitle(title or "loaded contact at the pitch point", fontsize=10)
    return save_figure(fig, path)


def write_cylindrical_ltca_outputs(c: CylindricalPhaseContact, pair, out, *, side: str,
                                   figures: bool = True) -> dict:
    """Write the files of the module docstring into ``out`` (created if missing); returns
    the ``ltca.json`` dict."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    lte = c.lte
    write_csv(out / "line_load.csv", LINE_LOAD_COLUMNS, line_load_rows(lte, [c.phase]))
    write_csv(out / "pressure_map.csv",
              ["pair", "pinion_z_mm", "across_mm", "pressure_mpa"],
              [[lte.pair_offsets[p], float(z), float(x), float(lte.phase_pressure_mpa[p, i, m])]
               for p in _loaded(c) for i, z in enumerate(lte.z_mm)
               for m, x in enumerate(c.across_mm)])
    summary = cylindrical_ltca_summary(c, pair, side=side)
    (out / "ltca.json").write_text(json.dumps(summary, indent=2))
    if figures:
        plot_cylindrical_ltca(c, out / "pressure_map.png",
                              title=f"{pair.name} {side}: loaded contact at the pitch point, "
                                    f"{lte.torque_nm:g} N·m ({summary['teeth']})")
    return summary
