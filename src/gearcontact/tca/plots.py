"""TCA figures (matplotlib, Agg backend): contact pattern and path, TE0 over the mesh.

Flank views use the usual axial-plane projection of gear-contact practice (Litvin &
Fuentes 2004, sec. 15.7): a point of a member's body frame is drawn at
(axial coordinate, distance from the axis). The gear axis is body z, the pinion axis
body x (:mod:`gearcontact.geometry.kinematics`).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402

from ..figure_files import save_figure  # noqa: E402
from ..geometry.kinematics import MeshKinematics  # noqa: E402
from ..geometry.surface import Surface  # noqa: E402
from .mesh import MeshCycle  # noqa: E402

__all__ = ["axial_projection", "contact_pattern_figure", "plot_contact_pattern", "plot_te0"]


def axial_projection(points_body: np.ndarray, member: str) -> np.ndarray:
    """(N, 2) axial-plane coordinates in mm of body-frame points: ``(radius, axial)``
    for the gear (its face runs radially), ``(axial, radius)`` for the pinion."""
    p = np.atleast_2d(points_body)
    if member == "gear":
        return np.column_stack([np.hypot(p[:, 0], p[:, 1]), p[:, 2]])
    if member == "pinion":
        return np.column_stack([p[:, 0], np.hypot(p[:, 1], p[:, 2])])
    raise ValueError(f"member = {member!r} is not 'gear' or 'pinion'")


def _boundary(surface: Surface, n: int = 40) -> np.ndarray:
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    u = np.linspace(u0, u1, n)
    v = np.linspace(v0, v1, n)
    loop = ([(a, v0) for a in u] + [(u1, b) for b in v] + [(a, v1) for a in u[::-1]]
            + [(u0, b) for b in v[::-1]])
    return np.array([surface.point(a, b).r for a, b in loop])


def _to_body(kin: MeshKinematics, member: str, mp, x_f: np.ndarray) -> np.ndarray:
    rot, t = (kin.gear_pose(mp.phi2_rad) if member == "gear"
              else kin.pinion_pose(mp.phi1_rad))
    return (np.atleast_2d(x_f) - t) @ rot


def plot_contact_pattern(pinion: Surface, gear: Surface, kin: MeshKinematics,
                         cycle: MeshCycle, path, *, title: str = "",
                         edges=()) -> Path:
    """:func:`contact_pattern_figure` as a PNG at ``path``."""
    fig = contact_pattern_figure(pinion, gear, kin, cycle, title=title, edges=edges)
    out = save_figure(fig, path, dpi=130)
    plt.close(fig)
    return out


def contact_pattern_figure(pinion: Surface, gear: Surface, kin: MeshKinematics,
                           cycle: MeshCycle, *, title: str = "", edges=()) -> Figure:
    """Contact pattern and path on both flanks (gear above, pinion below).

    The pattern is the union of the paint ellipses of the transmitting contact over
    one pinion pitch (every tooth carries the same pattern); the thin line is the whole
    interior path of one pair, the thick line its transmitting part; P0 is marked.
    ``edges`` (per phase, ``""`` or the edge reached; :mod:`gearcontact.tca.edges`)
    draws the ellipses of edge phases in red and names the edges in the legend;
    transmitting contacts that are an edge touching the other flank
    (:mod:`gearcontact.tca.edge_contact`) are marked with crosses. The paint is clipped
    to the flank boundary (its outline in the projection, the clip path of every
    ellipse): an ellipse of an edge phase reaches past the edge it runs on, and paint
    cannot lie off the flank.
    """
    fig, axes = plt.subplots(2, 1, figsize=(9, 7.5))
    theta = np.linspace(0.0, 2 * np.pi, 49)
    paint = cycle.ellipse[0].paint_mm
    pts = [mp for mp in cycle.path.points if not mp.edge]
    labels = {"gear": ("distance from gear axis (mm)", "gear axial coordinate (mm)"),
              "pinion": ("pinion axial coordinate (mm)", "distance from pinion axis (mm)")}
    for ax, member, surf in ((axes[0], "gear", gear), (axes[1], "pinion", pinion)):
        outline = axial_projection(_boundary(surf), member)
        ax.plot(*outline.T, color="0.3", lw=1.0, label="flank boundary")
        clip = Polygon(outline, closed=True, transform=ax.transData)
        marks = tuple(edges) or ("",) * len(cycle.contact)
        named = sorted({e for e in marks if e})
        for mp, rc, ell, edge in zip(cycle.contact, cycle.curvature, cycle.ellipse, marks):
            if mp.edge or not np.isfinite(ell.semi_major_mm):
                continue
            ring = (mp.point_mm + np.outer(ell.semi_major_mm * np.cos(theta), rc.dir_min)
                    + np.outer(ell.semi_minor_mm * np.sin(theta), rc.dir_max))
            xy = axial_projection(_to_body(kin, member, mp, ring), member)
            for patch in ax.fill(xy[:, 0], xy[:, 1], color="tab:red" if edge else "tab:orange",
                                 alpha=0.12, lw=0):
                patch.set_clip_path(clip)
        if named:
            ax.fill([], [], color="tab:red", alpha=0.3,
                    label=f"edge contact ({', '.join(named)}: "
                          f"{sum(1 for e in marks if e)} of {len(marks)} phases)")
        trace = np.vstack([axial_projection(_to_body(kin, member, mp, mp.point_mm), member)
                           for mp in pts])
        ax.plot(trace[:, 0], trace[:, 1], color="tab:red", lw=0.8, label="contact path")
        active = np.vstack([axial_projection(_to_body(kin, member, mp, mp.point_mm), member)
                            for mp in cycle.contact if not mp.edge])
        ax.plot(active[:, 0], active[:, 1], color="tab:red", lw=2.5,
                label="transmitting (one pitch)")
        touching = [mp for mp in cycle.contact if mp.edge_contact]
        if touching:
            xy = np.vstack([axial_projection(_to_body(kin, member, mp, mp.point_mm), member)
                            for mp in touching])
            ax.plot(xy[:, 0], xy[:, 1], "kx", ms=5,
                    label="edge touching the other flank ("
                          + ", ".join(sorted({mp.edge_contact for mp in touching})) + ")")
        ref = cycle.reference_point
        p0 = axial_projection(_to_body(kin, member, ref, ref.point_mm), member)[0]
        ax.plot(*p0, "k+", ms=10, mew=2, label="P0")
        ax.set_aspect("equal")
        ax.set_xlabel(labels[member][0])
        ax.set_ylabel(labels[member][1])
        ax.set_title(f"{member} flank: contact pattern at {paint * 1e3:.2f} um paint")
        ax.grid(alpha=0.3)
    # below the panels: inside, the legend covers the flank boundary and the pattern
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=3,
               fontsize=8)
    if title:
        fig.suptitle(title)
    fig.tight_layout(rect=(0.0, 0.08, 1.0, 1.0))
    return fig


def plot_te0(cycle: MeshCycle, path, *, title: str = "") -> Path:
    """TE0 of each tooth pair along the mesh phase with the envelope; PNG at ``path``."""
    n = cycle.step_index
    p = cycle.path
    te = p.te0_arcsec
    phi = np.degrees(p.phi1_rad)
    fig, ax = plt.subplots(figsize=(8, 4.2))
    pitch_deg = 360.0 / cycle.pinion_teeth
    for j in cycle.pair_offsets:
        # pair j at phase phi is pair 0 at phi + j * pitch
        ax.plot(phi - j * pitch_deg, te, lw=1.0, alpha=0.7, label=f"pair {j:+d}")
    env_phi = np.degrees(cycle.phi1_rad)
    ax.plot(env_phi, cycle.envelope_arcsec, color="k", lw=2.2,
            label=f"envelope, p-p {cycle.te0_pp_arcsec:.2f} arcsec")
    ax.axvspan(env_phi[0], env_phi[-1], color="0.9", zorder=0, label="one pinion pitch")
    lo, hi = np.nanmin(cycle.envelope_arcsec), np.nanmax(cycle.envelope_arcsec)
    pad = max(hi - lo, 1.0)
    if cycle.envelope_is_max:       # the other pairs lie below the envelope
        ax.set_ylim(lo - 1.5 * pad, hi + 0.5 * pad)
    else:
        ax.set_ylim(lo - 0.5 * pad, hi + 1.5 * pad)
    ax.set_xlim(env_phi[0] - pitch_deg, env_phi[-1] + pitch_deg)
    ax.set_xlabel("pinion rotation phi1 (deg)")
    ax.set_ylabel("TE0 (arcsec)")
    ax.set_title(title or f"unloaded transmission error ({n + 1} phases per pitch)")
    ax.grid(alpha=0.3)
    # beside the axes: inside, it covers the neighbouring pairs' curves
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    out = save_figure(fig, path, dpi=130, tight=True)
    plt.close(fig)
    return out
