"""The global touch of a row's posed flanks: the least gap over the whole flank, not
only around the row's field (:func:`gearcontact.ltca.patch_field.touch_search`).

The gap ``g(s, t)`` of a posed pair (:func:`gearcontact.tca.stencil.gap_at` on the row's
frame, the flanks' continuation beyond their parameter boxes evaluated) is smooth; its
least value over the flank region ``D`` (the points of the row's plane whose normal
line meets both flanks inside their parameter boxes) lies either at an interior local
minimum of ``g`` or on the border of ``D``, which is made of the images of the eight
edges of the two members' parameter boxes (and their corners). A pattern search from
the field's least node (:func:`.patch_field.touch_search`) finds the minimum of its own
basin, and may stall on a border that cuts its windows obliquely (its points cannot
follow the border; docs/twin.md "The touch made global"); where the row's field lies
wholly off the flank there is no field node to descend from and the search is this
module's alone. Here:

* :func:`edge_touch_mm`: each edge, its parameter nudged :data:`EDGE_NUDGE` inside its
  box, sampled at :data:`EDGE_SAMPLES` points posed and projected on the row's plane
  (a point of a member's flank projects exactly to the plane point whose normal line
  meets it), the gap there (``inf`` where the other member is off its box); every
  sampled local minimum whose bound (its gap less its larger rise to a neighbour: a
  convex ``g`` along the edge cannot fall further within the neighbouring intervals)
  lies below the best so far is refined by windows of :data:`EDGE_SIDE` points along
  the edge, moved while the least is at a window's end and shrunk 4 times until a
  window's step is at most ``fine_mm``. A corner between a pinion and a gear edge is
  approached from both edges (the infeasible side is ``inf``). All edges' windows
  share one gap evaluation per step (its cost is mostly per call).
* :func:`interior_seeds`: a :data:`SCAN_SIDE` x :data:`SCAN_SIDE` scan of the pinion
  flank's projection on the row's plane (the projected edge samples' bounding box);
  its local minima with all 8 neighbours on the flank (a minimum next to the border
  is the edges') whose bound (gap less twice the larger neighbour rise, the tangent
  plane argument of :func:`.patch_field.touch_bounds_mm`) lies below the best so far,
  returned as seeds for the 2-D refinement of :mod:`.patch_field`.

Assumed: every basin of ``g`` on ``D`` and every local minimum along an edge spans
more than a sample spacing (the scan's cell, 1/(EDGE_SAMPLES - 1) of an edge): a
narrower one may be missed. Measured against a 241 x 241 scan refined around its
least points on F.2, MITER_PAIR and s0003 coast: docs/twin.md.

References
----------
T. G. Kolda, R. M. Lewis, V. Torczon, "Optimization by direct search: new perspectives
on some classical and modern methods", *SIAM Review* 45 (2003) 385-482 (near a
constraint a pattern's directions must conform to its border, else the search can
stall short of the constrained minimum).
"""

from __future__ import annotations

import numpy as np

from ..tca.stencil import gap_at

__all__ = ["EDGE_NUDGE", "EDGE_SAMPLES", "EDGE_SIDE", "SCAN_SIDE", "edge_touch_mm",
           "edge_samples", "flank_gaps_mm",
           "interior_seeds"]

#: Samples along each of the 8 edges of the two members' parameter boxes.
EDGE_SAMPLES = 64
#: Points of a refinement window along an edge (its ends one step either way of the
#: centre times (EDGE_SIDE - 1) / 2).
EDGE_SIDE = 9
#: Relative nudge of an edge's fixed parameter into its box (the box test is strict);
#: 1e-9 of a parameter range moves the point by about 1e-8 mm on these flanks.
EDGE_NUDGE = 1e-9
#: Points per side of the interior scan of the pinion flank's projection.
SCAN_SIDE = 41
#: Moves of an edge window before it shrinks, per level.
EDGE_MOVES = 16


def flank_gaps_mm(fields, pc, s_mm, t_mm) -> np.ndarray:
    """Gap (mm) of the row's posed flanks at plane points ``(s_mm, t_mm)`` of its frame
    (any equal shapes), ``inf`` off the flank."""
    pinion, gear, kin = fields.args
    f = gap_at(pinion, gear, kin, fields.points[pc.field_key], s_mm, t_mm, frame="patch",
               axes=fields.frames[pc.field_key][1], allow_outside=True)
    return np.where(f.on_flank, f.gap_mm, np.inf)


def _edges(fields, pc):
    """The 8 edges as ``(surface, rotation, centre, fixed axis, fixed value)``: the
    pinion's and the gear's boxes, each at both ends of ``u`` and of ``v``, nudged in."""
    pinion, gear, kin = fields.args
    mp = fields.points[pc.field_key]
    out = []
    for surf, (rot, c) in ((pinion, kin.pinion_pose(mp.phi1_rad)),
                           (gear, kin.gear_pose(mp.phi2_rad))):
        for axis, (lo, hi) in enumerate((surf.u_range, surf.v_range)):
            nudge = EDGE_NUDGE * (hi - lo)
            out += [(surf, rot, c, axis, lo + nudge), (surf, rot, c, axis, hi - nudge)]
    return out


def _edge_points(fields, pc, edge, w) -> np.ndarray:
    """Plane points ``(n, 2)`` (mm) of an edge at fractions ``w`` of its free parameter."""
    surf, rot, c, axis, fixed = edge
    lo, hi = (surf.v_range, surf.u_range)[axis]
    free = lo + (hi - lo) * np.asarray(w, float)
    uv = [(fixed, x) if axis == 0 else (x, fixed) for x in free]
    r = np.array([surf.point(u, v).r for u, v in uv]) @ rot.T + c
    axes = fields.frames[pc.field_key][1]
    return (r - fields.points[pc.field_key].point_mm) @ axes[:, :2]


def _rises(g: np.ndarray) -> np.ndarray:
    """Per sample of a 1-D array, the larger absolute difference to a finite neighbour
    (0 without one)."""
    with np.errstate(invalid="ignore"):
        d = np.abs(np.diff(g))
    d = np.where(np.isfinite(d), d, 0.0)
    return np.maximum(np.pad(d, (1, 0)), np.pad(d, (0, 1)))


def edge_samples(fields, pc) -> tuple[list, np.ndarray, list[np.ndarray]]:
    """``(edges, w, points)``: the 8 edges (:func:`_edges`), the fractions of their
    :data:`EDGE_SAMPLES` samples and each edge's plane points ``(EDGE_SAMPLES, 2)``
    (mm), the first four the pinion's."""
    edges = _edges(fields, pc)
    w = np.linspace(0.0, 1.0, EDGE_SAMPLES)
    return edges, w, [_edge_points(fields, pc, e, w) for e in edges]


def edge_touch_mm(fields, pc, samples, *, best_mm: float, fine_mm: float) -> float:
    """The least gap (mm) along the 8 edges of the flank region (module docstring) from
    candidates whose bound is below ``best_mm``, refined to a step of ``fine_mm`` (mm);
    ``inf`` if none is. ``samples``: :func:`edge_samples`."""
    edges, w, pts = samples
    flat = np.concatenate(pts)
    g_all = flank_gaps_mm(fields, pc, flat[:, 0], flat[:, 1]).reshape(len(edges), -1)
    cands = []                              # [edge, fraction, gap, half-span, mm per unit]
    for e, (g, p) in enumerate(zip(g_all, pts)):
        length = float(np.sum(np.hypot(*np.diff(p, axis=0).T)))
        padded = np.pad(g, 1, constant_values=np.inf)
        minima = np.isfinite(g) & (g <= padded[:-2]) & (g <= padded[2:])
        for i in np.flatnonzero(minima & (g - _rises(g) < best_mm)):
            cands.append([e, float(w[i]), float(g[i]), 1.0 / (EDGE_SAMPLES - 1), length])
    best = min([c[2] for c in cands], default=np.inf)
    u = np.linspace(-1.0, 1.0, EDGE_SIDE)
    half = (EDGE_SIDE - 1) / 2.0
    while cands:
        for _ in range(EDGE_MOVES):
            ws = [np.clip(c[1] + c[3] * u, 0.0, 1.0) for c in cands]
            flat = np.concatenate([_edge_points(fields, pc, edges[c[0]], x)
                                   for c, x in zip(cands, ws)])
            g = flank_gaps_mm(fields, pc, flat[:, 0], flat[:, 1]).reshape(len(cands), -1)
            moving = False
            for c, x, gg in zip(cands, ws, g):
                k = int(np.argmin(gg))
                if gg[k] < c[2]:
                    c[1], c[2] = float(x[k]), float(gg[k])
                    moving |= k in (0, EDGE_SIDE - 1) and 0.0 < x[k] < 1.0
            if not moving:
                break
        best = min(best, min(c[2] for c in cands))
        cands = [c for c in cands if c[3] * c[4] / half > fine_mm]
        for c in cands:
            c[3] /= 4.0
    return best


def interior_seeds(fields, pc, samples, *, best_mm: float) -> list[tuple[float, float,
                                                                           float, float,
                                                                           float]]:
    """Seeds ``(gap, s, t, h_s, h_t)`` (mm) of the interior minima of the flank region
    (module docstring) whose bound lies below ``best_mm``, least first: the scan's node
    and its cell. ``samples``: :func:`edge_samples` (its pinion edges span the scan)."""
    rim = np.concatenate(samples[2][:4])
    sa = np.linspace(rim[:, 0].min(), rim[:, 0].max(), SCAN_SIDE)
    ta = np.linspace(rim[:, 1].min(), rim[:, 1].max(), SCAN_SIDE)
    s, t = np.meshgrid(sa, ta)
    g = flank_gaps_mm(fields, pc, s, t)
    p = np.pad(g, 1, constant_values=np.inf)
    n = SCAN_SIDE
    around = np.array([p[1 + dj:1 + dj + n, 1 + di:1 + di + n]
                       for dj in (-1, 0, 1) for di in (-1, 0, 1) if dj or di])
    interior = np.isfinite(around).all(axis=0) & np.isfinite(g)
    with np.errstate(invalid="ignore"):
        rise = np.max(np.abs(around - g), axis=0, initial=0.0, where=interior)
    seeds = interior & (g <= around.min(axis=0)) & (g - 2.0 * rise < best_mm)
    out = [(float(g[j, i]), float(sa[i]), float(ta[j]), float(sa[1] - sa[0]),
            float(ta[1] - ta[0])) for j, i in zip(*np.nonzero(seeds))]
    return sorted(out)
