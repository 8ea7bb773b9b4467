"""Figures of the generated flanks (matplotlib, Agg canvas; no pyplot global state).

:func:`plot_flanks_in_mesh` draws the gear and pinion flank sheets of one side posed in
the meshing frame at a mesh phase, with the mean point P0 (or a TCA mating point) -
the "two flank sheets in mesh" figure of the TCA report.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..figure_files import save_figure
from ..validation import InputRangeError
from .flank import FlankSet
from .formate import SIDES
from .sampling import sample_grid

__all__ = ["plot_flanks_in_mesh", "plot_setting_residual"]


def plot_flanks_in_mesh(flanks: FlankSet, *, side: str = "drive", phi2_rad: float | None = None,
                        point_mm=None, n_u: int = 16, n_v: int = 22,
                        path: str | Path | None = None) -> Figure:
    """3-D view of the gear and pinion flanks of ``side`` in mesh.

    Parameters
    ----------
    flanks : FlankSet
    side : str
        "drive" or "coast".
    phi2_rad : float, optional
        Gear rotation, rad; the pinion is posed at ``phi1 = u phi2`` (nominal
        kinematics). Default: the conjugate mean contact of ``side``.
    point_mm : array-like (3,), optional
        Point to mark in the meshing frame, mm (e.g. the TCA mating point P0); default
        the conjugate contact at the pinion mean point.
    n_u, n_v : int
        Sampling of the sheets (default the 16 x 22 flank grid).
    path : str or Path, optional
        If given, the figure is also written there (PNG at 150 dpi).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if side not in SIDES:
        raise InputRangeError("side", side, f"one of {SIDES}")
    mean = flanks.mean_contact[side]
    phi2 = mean["phi2_rad"] if phi2_rad is None else float(phi2_rad)
    kin = flanks.kinematics
    fig = Figure(figsize=(7.0, 5.5))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")
    for member, colour, pose in (("gear", "tab:blue", kin.gear_pose(phi2)),
                                 ("pinion", "tab:orange", kin.pinion_pose(kin.ratio * phi2))):
        grid = sample_grid(flanks.flank(member, side), n_u, n_v)
        R, t = pose
        X = grid.positions_mm @ R.T + t
        ax.plot_surface(X[..., 0], X[..., 1], X[..., 2], color=colour, alpha=0.55,
                        linewidth=0.2, edgecolor="k", label=f"{member} {side}")
    if point_mm is None:
        g = flanks.flank("gear", side).point(*mean["gear_uv"])
        R, t = kin.gear_pose(phi2)
        point_mm = R @ g.r + t
    p = np.asarray(point_mm, dtype=float)
    ax.scatter([p[0]], [p[1]], [p[2]], color="k", s=30, depthshade=False)
    ax.text(p[0], p[1], p[2], "  P0")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    kind = "hypoid" if flanks.blank.offset_mm > 0.0 else "spiral bevel"
    ax.set_title(f"{flanks.blank.pinion_teeth}/{flanks.blank.gear_teeth} {kind}, {side} "
                 f"flanks in mesh (phi2 = {np.degrees(phi2):.3f} deg)")
    ax.legend(loc="upper left")
    ax.set_box_aspect((np.ptp(ax.get_xlim3d()), np.ptp(ax.get_ylim3d()), np.ptp(ax.get_zlim3d())))
    if path is not None:
        save_figure(fig, path, dpi=150)
    return fig


def plot_setting_residual(fit) -> Figure:
    """Maps of the residual of the fitted pinion flanks against their targets, one panel
    per side (:class:`~.easeoff_settings.EaseOffSettings`): generated minus target along the
    target's outward normal, um, over the flank (axial position v, radial height u), or
    at the measured points of a side fitted to scattered points."""
    sides = list(fit.sides.values())
    fig = Figure(figsize=(5.0 * len(sides), 4.2))
    FigureCanvasAgg(fig)
    lim = max(max(float(np.abs(r.residual_um).max()) for r in sides), 1e-3)
    for k, r in enumerate(sides):
        ax = fig.add_subplot(1, len(sides), k + 1)
        if r.points is None:
            m = ax.pcolormesh(r.v_mm, r.u_mm, r.residual_um, cmap="RdBu_r", vmin=-lim,
                              vmax=lim, shading="gouraud")
            m.set_rasterized(True)  # an image inside the SVG (gouraud triangles as
            # vectors: 57 MB for s0003's map)
        else:       # scattered measured points: the residual at each
            m = ax.scatter(r.v_mm, r.u_mm, c=r.residual_um, cmap="RdBu_r", vmin=-lim,
                           vmax=lim, s=18, edgecolors="k", linewidths=0.3)
        fig.colorbar(m, ax=ax, label="residual (um)")
        at = "" if r.points is None else f" at {len(r.points.line)} points"
        ax.set_title(f"pinion {r.side}: max {r.max_um:.3f} um, RMS {r.rms_um:.3f} um{at}\n"
                     f"(ease-off max {r.easeoff_max_um:.1f} um)", fontsize=9)
        ax.set_xlabel("axial position v (mm), toe -> heel")
        ax.set_ylabel("height above root u (mm)")
    fig.tight_layout()
    return fig
