"""The edge check while the surface contact is inside both flanks.

A surface mating point found inside both flanks' boxes is a stationary point of the
gap, not necessarily the first touch of the two teeth: an edge of either flank (its
toe, heel, root or tip; a kink line of a relieved flank) can touch the other flank
before it. :func:`edge_first` decides it at one phase and returns the contact that
touches first (docs/machine_settings.md sec. 5, "The edge check while the surface
contact is inside (session 29)"):

1. **The screen** (:func:`edge_gaps`): with both members posed at the surface contact
   (pinion phase ``phi1``, gear turn ``phi2*``), the separation of each edge from the
   other flank along the common normal ``n`` of the contact,
   ``d(s) = (X_1 - X_2) . n`` (``X_1`` on the pinion, ``X_2`` on the gear, on one line
   along ``n``; ``n`` out of the gear tooth), is sampled at :data:`SCREEN_SAMPLES`
   even points of the edge (the other flank's continuation beyond its box included).
   An edge point with ``d < 0`` lies in the other tooth's material: the gear must turn
   further to clear it, so the edge touches first. Between samples ``h`` apart,
   ``d >= min(d_k, d_k+1) - M h^2 / 8`` for ``|d''| <= M``; ``M`` is taken as
   :data:`CURVATURE_FACTOR` times the largest sampled second difference over ``h^2``,
   so the edge's lower bound is ``min d - CURVATURE_FACTOR max|D2 d| / 8``. An edge
   whose bound is positive cannot touch first and is ruled out; an edge with a sample
   whose line misses the other flank (Newton not converged) is not.
2. **The exact solve** (:func:`~.edge_contact.solve_edge_contact`) over the edges the
   screen did not rule out: the edge contact replaces the surface contact only if it
   touches first by more than :data:`EDGE_LEAD_RAD` of gear turn.

The screen needs the other flank met once by each line along ``n`` near the edge (its
normals within 90 degrees of ``n``: any tooth flank in mesh).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from .edge_contact import FlankEdge, edge_parameters, edge_span, flank_edges, solve_edge_contact
from .stencil import _intersect_many, evaluate_many
from .types import MatingPoint

__all__ = ["SCREEN_SAMPLES", "CURVATURE_FACTOR", "EDGE_LEAD_RAD", "EdgeGap", "interval_bounds_mm",
           "edge_gaps", "edge_first", "leads"]

#: Even samples of each edge in the screen (both ends included).
SCREEN_SAMPLES = 17
#: The bound on ``|d''|`` of an edge: this factor times its largest sampled second
#: difference over ``h^2`` (declared, docs sec. 5; tested against dense sampling).
CURVATURE_FACTOR = 4.0
#: The reach of an interval into the other flank's box is widened by this factor times
#: its samples' larger ``|d| tan(theta)`` (the motion's circle against its tangent, and
#: the flank's curvature between the two hits; declared, docs sec. 5).
SHIFT_FACTOR = 1.5
#: An edge contact replaces the surface contact only when it touches first by more than
#: this gear turn, rad (~2e-4 arcsec; the point solves' tolerance 1e-10 mm is ~1e-12 rad).
EDGE_LEAD_RAD = 1e-9
#: Tolerance of the line intersections of the screen, mm.
SCREEN_TOL_MM = 1e-9


@dataclass(frozen=True)
class EdgeGap:
    """The screen of one edge at one surface contact.

    Attributes
    ----------
    edge : FlankEdge
    s_mm : ndarray (N,)
        Samples of the edge's free parameter, mm.
    gap_mm : ndarray (N,)
        Separation ``d`` from the other flank along the contact normal, mm (NaN: the
        line missed the other flank).
    margin_mm : ndarray (N,)
        Signed distance of each line's hit inside the other flank's box, mm.
    lower_mm : float
        Lower bound of ``d`` over the edge's points that can touch the other flank
        inside its box, mm (+inf: none can; -inf: a sample is NaN).
    """

    edge: FlankEdge
    s_mm: np.ndarray
    gap_mm: np.ndarray
    margin_mm: np.ndarray
    lower_mm: float

    @property
    def ruled_out(self) -> bool:
        """The edge cannot touch before the surface contact (its bound is positive)."""
        return bool(self.lower_mm > 0.0)


def _local_d2(d: np.ndarray) -> np.ndarray:
    """Per interval ``[s_k, s_k+1]`` the larger |second difference| at its two ends
    (an end of the edge takes its neighbour's)."""
    d2 = np.abs(np.diff(d, 2))
    at = np.concatenate([d2[:1], d2, d2[-1:]])      # at every sample
    return np.maximum(at[:-1], at[1:])


def interval_bounds_mm(gap_mm: np.ndarray, margin_mm: np.ndarray,
                       tan_mm: np.ndarray) -> np.ndarray:
    """Per interval of an evenly sampled edge: a lower bound of the separation ``d`` over
    the interval's points that can touch the other flank inside its box, +inf if none
    can, -inf if a sample is NaN (module docstring).

    ``gap_mm``: ``d`` at the samples; ``margin_mm``: the signed distance of each
    sample's line hit inside the other flank's box (parameters, mm); ``tan_mm``:
    ``|d| tan(theta)`` per sample, how far the point's touch along its relative motion
    lies from its line hit (``theta`` between ``n`` and that motion).
    """
    d, m = np.asarray(gap_mm, float), np.asarray(margin_mm, float)
    shift = np.asarray(tan_mm, float)
    lower = np.minimum(d[:-1], d[1:]) - CURVATURE_FACTOR * _local_d2(d) / 8.0
    reach = (np.maximum(m[:-1], m[1:]) + CURVATURE_FACTOR * _local_d2(m) / 8.0
             + SHIFT_FACTOR * np.maximum(shift[:-1], shift[1:]))
    out = np.where(reach < 0.0, np.inf, lower)
    bad = ~np.isfinite(d) | ~np.isfinite(m)
    # a NaN sample leaves its intervals and those whose curvature it enters unknown
    near = np.convolve(bad.astype(float), np.ones(4), mode="full")[2:-1] > 0.0 \
        if d.size > 3 else np.full(d.size - 1, bad.any())
    return np.where(near[:d.size - 1], -np.inf, out)


def edge_gaps(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint, *,
              edges=None, samples: int = SCREEN_SAMPLES) -> list[EdgeGap]:
    """The screen of every candidate edge at the surface contact ``mp``.

    Parameters
    ----------
    pinion, gear : Surface
        The two flanks.
    kin : MeshKinematics
        Kinematics with assembly errors.
    mp : MatingPoint
        A surface mating point (both members posed there).
    edges : sequence of FlankEdge, optional
        Default :func:`~.edge_contact.flank_edges`.
    samples : int
        Even samples per edge (>= 4).

    Returns
    -------
    list of EdgeGap
    """
    if int(samples) < 4:
        raise ValueError(f"samples = {samples!r} must be >= 4")
    if edges is None:
        edges = flank_edges(pinion, gear)
    poses = {"pinion": kin.pinion_pose(mp.phi1_rad), "gear": kin.gear_pose(mp.phi2_rad)}
    uv_at = {"pinion": (mp.u1, mp.v1), "gear": (mp.u2, mp.v2)}
    flank = {"pinion": pinion, "gear": gear}
    n = np.asarray(mp.normal, float)
    x0 = np.asarray(mp.point_mm, float)
    tangents = {}
    for member in flank:        # the tangent-plane prediction of each line's start
        rot = poses[member][0]
        _, r_u, r_v = evaluate_many(flank[member], np.array([uv_at[member][0]]),
                                    np.array([uv_at[member][1]]))
        tangents[member] = np.column_stack([rot @ r_u[0], rot @ r_v[0], -n])
    out = []
    for edge in edges:
        own, other = edge.member, "gear" if edge.member == "pinion" else "pinion"
        lo, hi = edge_span(flank[own], edge.name)
        s = np.linspace(lo, hi, int(samples))
        uv = np.array([edge_parameters(flank[own], edge.name, float(t)) for t in s])
        r = evaluate_many(flank[own], uv[:, 0], uv[:, 1])[0]
        rot, c = poses[own]
        q = r @ rot.T + c
        step = np.linalg.solve(tangents[other], (q - x0).T).T
        (u0, u1), (v0, v1) = flank[other].u_range, flank[other].v_range
        uv0 = np.clip(np.asarray(uv_at[other], float) + step[:, :2], (u0, v0), (u1, v1))
        hit = np.empty_like(uv0)
        lam, _ = _intersect_many(flank[other], poses[other], q, n, uv0, clamp=False,
                                 tol_mm=SCREEN_TOL_MM, uv_out=hit)
        # the line q + lam n meets the other flank: d = (X_1 - X_2) . n
        gap = -lam if own == "pinion" else lam
        margin = np.minimum.reduce([hit[:, 0] - u0, u1 - hit[:, 0], hit[:, 1] - v0,
                                    v1 - hit[:, 1]])
        # the relative motion of the edge point: its circle about the gear axis
        motion = np.cross(kin.gear_axis, q - poses["gear"][1])
        cos = np.abs(motion @ n) / np.linalg.norm(motion, axis=1)
        shift = np.abs(gap) * np.sqrt(np.maximum(0.0, 1.0 - cos ** 2)) / cos
        bounds = interval_bounds_mm(gap, margin, shift)
        out.append(EdgeGap(edge, s, gap, margin, float(bounds.min())))
    return out


def edge_first(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint, *,
               forward: bool, tol_mm: float = 1e-10) -> MatingPoint:
    """The first contact at the phase of the surface mating point ``mp``: ``mp`` itself,
    or an edge contact that touches before it (module docstring).

    Parameters
    ----------
    pinion, gear, kin, mp
        As :func:`edge_gaps` (``mp`` a surface mating point inside both flanks).
    forward : bool
        The gear is pushed towards +phi2 (the first touch is the largest turn).
    tol_mm : float
        Tolerance of the exact edge solve's point equations, mm.

    Returns
    -------
    MatingPoint
        ``mp`` (the same object) if no edge touches first, else the edge contact.
    """
    open_edges = [g.edge for g in edge_gaps(pinion, gear, kin, mp) if not g.ruled_out]
    if not open_edges:
        return mp
    edge = solve_edge_contact(pinion, gear, kin, mp.phi1_rad, guess=mp.as_guess(),
                              forward=forward, edges=open_edges, tol_mm=tol_mm)
    if edge is not None and leads(edge, mp, forward=forward):
        return edge
    return mp


def leads(a: MatingPoint, b: MatingPoint, *, forward: bool) -> bool:
    """``a`` touches before ``b`` by more than :data:`EDGE_LEAD_RAD` of gear turn."""
    lead = a.phi2_rad - b.phi2_rad
    return bool((lead if forward else -lead) > EDGE_LEAD_RAD)
