"""Figures of the loaded-contact evaluation (matplotlib, Agg backend, PNG)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
from matplotlib.collections import QuadMesh  # noqa: E402
import numpy as np  # noqa: E402

from ..ltca.pair_ltca import preview_ellipse  # noqa: E402
from ..halfspace.patch import EDGE_SPIKE_CLIP, plot_patch  # noqa: E402
from ..figure_files import save_figure  # noqa: E402

__all__ = ["plot_pressure_maps", "plot_pressure_vs_load"]


def plot_pressure_maps(cases, path, *, title: str = "") -> Path:
    """One panel per torque: LCP pressure map (principal frame, s along the long axis)
    with the Hertzian preview ellipse overlaid (cyan) and the cell peak marked (green +).

    Each panel shows the loaded cells and the preview ellipse with a margin (not the
    whole computational grid), at true scale. Where the peak is an edge spike the colour
    scale stops at ``EDGE_SPIKE_CLIP`` x p90 (:func:`gearcontact.halfspace.patch.plot_patch`)
    and the colour bar says so.
    """
    n = len(cases)
    fig, axes = plt.subplots(n, 1, figsize=(9, 1.9 * n + 0.6), squeeze=False)
    for ax, c in zip(axes[:, 0], cases):
        plot_patch(c.patch, ax, ellipse=preview_ellipse(c.preview, c.patch.grid))
        for mesh in ax.collections:     # the cell map as an image inside the SVG (5 MB
            if isinstance(mesh, QuadMesh):  # of vector quads otherwise)
                mesh.set_rasterized(True)
                if mesh.norm.vmax is not None and mesh.norm.vmax < c.patch.p_peak_mpa:
                    mesh.colorbar.set_label(f"pressure (MPa),\nscale ends at "
                                            f"{EDGE_SPIKE_CLIP:g} p90", fontsize=8)
                else:
                    mesh.colorbar.set_label("pressure (MPa)", fontsize=8)
        for line in ax.lines:           # the peak marker: white is lost on the bright
            if line.get_marker() == "+":    # clipped cells
                line.set_color("tab:green")
        _frame_loaded_cells(ax, c.patch)
        edge = ", edge contact" if c.edge_contact else ""
        ax.set_title(f"{c.torque_nm:g} N·m, W = {c.load_n:.0f} N: LCP peak "
                     f"{c.patch.p_peak_mpa:.0f} MPa, p90 {c.patch.p90_mpa:.0f} MPa; "
                     f"preview p_max {c.preview.p_max_mpa:.0f} MPa{edge}",
                     fontsize=9)
        ax.set_xlabel("s along the long axis (mm)")
        ax.set_ylabel("t (mm)")
    fig.suptitle(f"{title}: LCP contact pressure; cyan: preview ellipse, green +: LCP peak")
    fig.tight_layout()
    path = save_figure(fig, path)
    plt.close(fig)
    return path


def _frame_loaded_cells(ax, patch, margin: float = 0.08) -> None:
    """Limit ``ax`` to the loaded cells and the drawn ellipse, plus ``margin`` of the
    span on each side (the grid around them is empty)."""
    g = patch.grid
    jj, ii = np.nonzero(patch.lcp.contact_mask)
    xs = [g.x_mm[ii] - g.dx_mm[ii] / 2, g.x_mm[ii] + g.dx_mm[ii] / 2]
    ys = [g.y_mm[jj] - g.dy_mm[jj] / 2, g.y_mm[jj] + g.dy_mm[jj] / 2]
    for line in ax.lines:       # the ellipse outline and the peak marker
        xs.append(np.asarray(line.get_xdata(), dtype=float))
        ys.append(np.asarray(line.get_ydata(), dtype=float))
    x, y = np.concatenate(xs), np.concatenate(ys)
    dx, dy = np.ptp(x), np.ptp(y)
    ax.set_xlim(x.min() - margin * dx, x.max() + margin * dx)
    ax.set_ylim(y.min() - margin * dy, y.max() + margin * dy)


def plot_pressure_vs_load(cases, path, *, title: str = "", published: dict | None = None
                          ) -> Path:
    """Log-log preview p_max and LCP mean / p90 / peak against the normal load, with the
    Hertzian law p ~ W^(1/3) through the preview at the smallest load and, when
    ``published`` values are given, the published preview p_max at the design torque."""
    w = np.array([c.load_n for c in cases])
    pre = np.array([c.preview.p_max_mpa for c in cases])
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.loglog(w, pre, "o-", color="C0", label="preview p_max (Hertz)")
    ax.loglog(w, [c.patch.p_mean_mpa for c in cases], "s--", color="C1", label="LCP mean")
    ax.loglog(w, [c.patch.p90_mpa for c in cases], "^--", color="C2", label="LCP p90")
    ax.loglog(w, [c.patch.p_peak_mpa for c in cases], "v:", color="C3", label="LCP peak")
    ww = np.geomspace(w.min() * 0.8, w.max() * 1.25, 50)
    ax.loglog(ww, pre[0] * (ww / w[0]) ** (1.0 / 3.0), color="0.5", lw=0.8,
              label="W^(1/3)")
    pub = published or {}
    if "preview_p_max_mpa_at_design" in pub:
        w_pub = pub["loads_n"][f"{pub['design_torque_nm']:g}"]
        ax.loglog([w_pub], [pub["preview_p_max_mpa_at_design"]], "*", color="C0", ms=11,
                  mfc="none", label=f"published preview p_max at {pub['design_torque_nm']:g} "
                                    "N·m")
    ax.set_xlabel("normal load W (N)")
    ax.set_ylabel("pressure (MPa)")
    ax.grid(True, which="both", alpha=0.3)
    # legend beside the axes: inside it covers the curves
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    ax.set_title(f"{title}: preview vs LCP over load")
    fig.tight_layout()
    path = save_figure(fig, path, tight=True)
    plt.close(fig)
    return path
