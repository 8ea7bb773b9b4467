"""The edge check while the surface contact is inside both flanks.

A surface mating point found inside both flanks' boxes is a stationary point of the
gap, not necessarily the first touch of the two teeth: an edge of either flank (its
toe, heel, root or tip; a kink line of a relieved flank) can touch the other flank
before it. :func:`edge_first` decides it at one phase and returns the contact that
touches first (docs/machine_settings.md sec. 5, "The edge check while the surface
contact is inside (session 29)"):

1. **The screen** (:func:`edge_gaps`): with both members posed at the surface contact
   (pinion phase ``phi1``, gear turn ``phi2*``), each edge is sampled at
   :data:`SCREEN_SAMPLES` even points, and for each the extra gear turn ``delta`` that
   brings it onto the other flank (its continuation beyond the box included) is solved
   (:func:`edge_turns`). Its turn gap ``g`` (``-delta`` if the gear is pushed towards
   +phi2, else ``delta``) is negative where the point touches before the surface
   contact. Between samples ``h`` apart, ``g >= min(g_k, g_k+1) - M h^2 / 8`` for
   ``|g''| <= M``; ``M h^2`` is taken as :data:`CURVATURE_FACTOR` times the larger
   |second difference| at the interval's ends. Only points that touch the other flank
   inside its box count: an interval whose touches' box margin, bounded the same way
   from above, stays below 0 holds none (+inf). A sample whose Newton solve fails does
   not touch (the rule of :mod:`.edge_contact`'s search); an interval with one such end
   is bounded from its solved end ``a`` and that end's other neighbour ``a'`` (the
   slope's error within ``M h / 2``): ``g >= min(g_a, 2 g_a - g_a' - M h^2)``, the
   margin likewise from above.
   An edge whose bound is -inf (too few solved samples for a curvature bound) is
   screened once more at :data:`FINE_SAMPLES`. An edge whose smallest interval bound is
   positive cannot touch first and is ruled out. Where both flanks have a kernel form (:func:`~.gap_kernel.kernel_surface`) the
   screen runs compiled (:func:`.screen_kernel.screen`, the same procedure; the numpy
   path here otherwise).
2. **The exact solve** (:func:`~.edge_contact.solve_edge_contact`) over the edges the
   screen did not rule out: the edge contact replaces the surface contact only if it
   touches first by more than :data:`EDGE_LEAD_RAD` of gear turn.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from .edge_contact import (FlankEdge, edge_parameters, edge_span, flank_edges, is_kink,
                           solve_edge_contact)
from .edge_kernel import EDGE_CODES, EDGE_KINK
from .gap_kernel import kernel_surface
from .screen_kernel import screen
from .stencil import evaluate_many
from .types import MatingPoint

__all__ = ["SCREEN_SAMPLES", "FINE_SAMPLES", "CURVATURE_FACTOR", "EDGE_LEAD_RAD", "EdgeGap", "interval_bounds",
           "edge_turns", "edge_gaps", "edge_first", "leads"]

#: Even samples of each edge in the screen (both ends included).
SCREEN_SAMPLES = 17
#: Even samples of an edge screened again because its bound at fewer samples is -inf
#: (too few solved samples for a curvature bound; a quarter of the spacing).
FINE_SAMPLES = 65
#: The bound on ``|d''|`` of an edge: this factor times its largest sampled second
#: difference over ``h^2`` (declared, docs sec. 5; tested against dense sampling).
CURVATURE_FACTOR = 4.0
#: Halvings of an interval the screen cannot rule out (its ``M`` kept).
REFINE_LEVELS = 8
#: An edge contact replaces the surface contact only when it touches first by more than
#: this gear turn, rad (~2e-4 arcsec; the point solves' tolerance 1e-10 mm is ~1e-12 rad).
EDGE_LEAD_RAD = 1e-9
#: Tolerance of the screen's point solves, mm.
SCREEN_TOL_MM = 1e-9


@dataclass(frozen=True)
class EdgeGap:
    """The screen of one edge at one surface contact.

    Attributes
    ----------
    edge : FlankEdge
    s_mm : ndarray (N,)
        Samples of the edge's free parameter, mm.
    gap_rad : ndarray (N,)
        Turn gap ``g`` of each sample, rad (NaN: not solved).
    margin_mm : ndarray (N,)
        Signed distance of each sample's touch inside the other flank's box, mm.
    lower_rad : float
        Lower bound of ``g`` over the edge's points that touch the other flank inside
        its box, rad (+inf: none can; -inf: a sample is NaN).
    """

    edge: FlankEdge
    s_mm: np.ndarray
    gap_rad: np.ndarray
    margin_mm: np.ndarray
    lower_rad: float

    @property
    def ruled_out(self) -> bool:
        """The edge cannot touch before the surface contact (its bound is positive)."""
        return bool(self.lower_rad > 0.0)


def _local_d2(d: np.ndarray) -> np.ndarray:
    """Per interval ``[s_k, s_k+1]`` the larger |second difference| at its two ends (an
    end of the edge, or one whose difference takes a sample not solved, takes the other
    end's; NaN if neither has one)."""
    d2 = np.abs(np.diff(d, 2))
    at = np.concatenate([[np.nan], d2, [np.nan]])      # at every sample
    return np.fmax(at[:-1], at[1:])


def interval_bounds(gap: np.ndarray, margin_mm: np.ndarray, *, curvature=None,
                    margin_curvature=None) -> np.ndarray:
    """Per interval of an evenly sampled edge: a lower bound of the turn gap ``g`` over
    the interval's points that touch the other flank inside its box, +inf if none can,
    -inf if unknown (module docstring).

    ``gap``: ``g`` at the samples (rad); ``margin_mm``: the signed distance of each
    sample's touch inside the other flank's box (parameters, mm); NaN: a sample not
    solved, which touches nothing (as in :mod:`.edge_contact`'s search).
    ``curvature``, ``margin_curvature``: per interval ``M h^2`` of ``g`` and of the margin
    (default :data:`CURVATURE_FACTOR` times the larger |second difference| at the
    interval's ends).
    """
    d, m = np.asarray(gap, float), np.asarray(margin_mm, float)
    cd = CURVATURE_FACTOR * _local_d2(d) if curvature is None else curvature
    cm = CURVATURE_FACTOR * _local_d2(m) if margin_curvature is None else margin_curvature
    lower = np.minimum(d[:-1], d[1:]) - cd / 8.0
    reach = np.fmax(m[:-1], m[1:]) + cm / 8.0
    out = np.where(reach < 0.0, np.inf, lower)
    solved = np.isfinite(d)
    both = solved[:-1] & solved[1:]
    # both ends solved: the bound (unknown if no second difference is); none: no touch
    out = np.where(both, np.where(np.isnan(out), -np.inf, out), np.inf)
    # one end solved: the solved stretch from it, extrapolated with the difference to its
    # other neighbour (the slope within M h / 2): g >= min(g_a, 2 g_a - g_a' - M h^2)
    for k in np.flatnonzero(solved[:-1] ^ solved[1:]):
        a, a2 = (k, k - 1) if solved[k] else (k + 1, k + 2)
        if not (0 <= a2 < d.size and solved[a2]):
            out[k] = -np.inf
            continue
        j = a2                   # the second difference nearest the solved end
        c_g = CURVATURE_FACTOR * abs(d[j - 1] - 2 * d[j] + d[j + 1]) \
            if 0 < j < d.size - 1 and np.isfinite(d[j - 1:j + 2]).all() else np.nan
        c_m = CURVATURE_FACTOR * abs(m[j - 1] - 2 * m[j] + m[j + 1]) \
            if 0 < j < d.size - 1 and np.isfinite(m[j - 1:j + 2]).all() else np.nan
        if not (np.isfinite(c_g) and np.isfinite(c_m)):
            out[k] = -np.inf
        elif max(m[a], 2 * m[a] - m[a2] + c_m) < 0.0:
            out[k] = np.inf
        else:
            out[k] = min(d[a], 2 * d[a] - d[a2] - c_g)
    return out


def _refined_bounds(turns, spans: list, gaps: list, margins: list, abs_: list) -> list:
    """Every edge's lower bound with each interval whose bound is finite and not
    positive halved :data:`REFINE_LEVELS` times, its ``M`` (of ``g`` and of the margin)
    kept: each half's ``M h^2`` a quarter of its parent's. ``turns(items)``: the
    ``(g, margin, ab)`` of ``(edge index, s[, ab0, g0])`` items (all edges' midpoints of
    a level at once, each started from the mean of its interval's ends)."""
    lowest = []
    work = []       # per open interval: edge, (a, g, m, ab) of both ends, M_g h^2, M_m h^2
    for e, (s, gap, margin, ab) in enumerate(zip(spans, gaps, margins, abs_)):
        cd, cm = CURVATURE_FACTOR * _local_d2(gap), CURVATURE_FACTOR * _local_d2(margin)
        bounds = interval_bounds(gap, margin, curvature=cd, margin_curvature=cm)
        open_ = np.isfinite(bounds) & (bounds <= 0.0)
        lowest.append(float(bounds[~open_].min(initial=np.inf)))
        work += [(e, (s[k], gap[k], margin[k], ab[k]), (s[k + 1], gap[k + 1], margin[k + 1],
                                                        ab[k + 1]), cd[k], cm[k], bounds[k])
                 for k in np.flatnonzero(open_)]
    for _ in range(REFINE_LEVELS):
        if not work:
            break
        items = []
        for e, lo, hi, *_ in work:
            mid = np.array([0.5 * (lo[0] + hi[0])])
            ab0, g0 = 0.5 * (lo[3] + hi[3]), 0.5 * (lo[1] + hi[1])
            items.append((e, mid, ab0[None], np.array([g0])) if np.isfinite(ab0).all()
                         and np.isfinite(g0) else (e, mid))
        halves = []
        for (e, lo, hi, cd, cm, _), (gm, mm, abm) in zip(work, turns(items)):
            mid = (0.5 * (lo[0] + hi[0]), gm[0], mm[0], abm[0])
            for a, b in ((lo, mid), (mid, hi)):
                bound = interval_bounds(np.array([a[1], b[1]]), np.array([a[2], b[2]]),
                                        curvature=np.array([cd / 4.0]),
                                        margin_curvature=np.array([cm / 4.0]))[0]
                if np.isfinite(bound) and bound <= 0.0:
                    halves.append((e, a, b, cd / 4.0, cm / 4.0, bound))
                else:
                    lowest[e] = min(lowest[e], bound)
        work = halves
    for w in work:
        lowest[w[0]] = min(lowest[w[0]], w[-1])
    return lowest


def _rot_z(p: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1], p[:, 2]])


def edge_turns(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
               edge: FlankEdge, s_mm: np.ndarray, *, forward: bool
               ) -> tuple[np.ndarray, np.ndarray]:
    """The turn gap ``g`` (rad) and the touch's box margin (mm) of the points ``s_mm`` of
    one edge, both members posed at the surface contact ``mp`` (module docstring).

    For each edge point, the extra gear turn ``delta`` that brings it onto the other
    flank (its continuation beyond the box included) is solved by Newton's method on
    ``S(a, b) = P(delta)`` (the other posed flank; the edge point turned with the gear,
    about the gear axis), vectorized over the points, started from the tangent-plane
    prediction at the contact; ``g = -delta`` (``forward``) or ``delta``: negative where
    the point touches before the surface contact. NaN where Newton does not converge
    within 20 steps to 1e-9 mm.
    """
    return _turns(pinion, gear, kin, mp, [(edge, s_mm)], forward=forward)[0][:2]


def _turns(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
           items: list, *, forward: bool) -> list:
    """:func:`edge_turns` of several ``(edge, s_mm)`` or ``(edge, s_mm, ab0, g0)`` (Newton
    started from the other flank's parameters ``ab0`` and the turn gap ``g0`` instead of
    the contact's) at once: one Newton iteration per member for all its edges' points (a
    point whose iterate leaves the other flank's box by more than the box's size, or
    turns by more than 1 rad, is given up). Per item ``(g, margin, ab)``."""
    flank = {"pinion": pinion, "gear": gear}
    poses = {"pinion": kin.pinion_pose(mp.phi1_rad), "gear": kin.gear_pose(mp.phi2_rad)}
    out: list = [None] * len(items)
    for own, other in (("pinion", "gear"), ("gear", "pinion")):
        mine = [k for k, item in enumerate(items) if item[0].member == own]
        if not mine:
            continue
        uv = np.array([edge_parameters(flank[own], items[k][0].name, float(t))
                       for k in mine for t in items[k][1]])
        rot, c = poses[own]
        q = evaluate_many(flank[own], uv[:, 0], uv[:, 1])[0] @ rot.T + c - poses["gear"][1]
        # a pinion point turns with the gear's inverse in the gear's frame, a gear point
        # with the gear (about the gear axis, z, through the gear pose's offset)
        turn = -kin.gear_axis[2] if own == "pinion" else kin.gear_axis[2]
        at = np.asarray((mp.u2, mp.v2) if other == "gear" else (mp.u1, mp.v1), float)
        ab0 = np.concatenate([items[k][2] if len(items[k]) > 2
                              else np.tile(at, (len(items[k][1]), 1)) for k in mine])
        g0 = np.concatenate([items[k][3] if len(items[k]) > 2
                             else np.zeros(len(items[k][1])) for k in mine])
        delta, ab = _turn_newton(flank[other], poses[other], poses["gear"][1], q, turn,
                                 ab0, -g0 if forward else g0)
        (u0, u1), (v0, v1) = flank[other].u_range, flank[other].v_range
        margin = np.minimum.reduce([ab[:, 0] - u0, u1 - ab[:, 0], ab[:, 1] - v0,
                                    v1 - ab[:, 1]])
        margin = np.where(np.isfinite(delta), margin, np.nan)
        gap = -delta if forward else delta
        start = 0
        for k in mine:
            n = len(items[k][1])
            out[k] = (gap[start:start + n], margin[start:start + n], ab[start:start + n])
            start += n
    return out


def _solve_each(jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Batched 3 x 3 solves; a singular system's row NaN (the point is given up)."""
    try:
        return np.linalg.solve(jac, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:
        out = np.full(rhs.shape, np.nan)
        for k in range(len(rhs)):
            try:
                out[k] = np.linalg.solve(jac[k], rhs[k])
            except np.linalg.LinAlgError:
                pass
        return out


def _turn_newton(other: Surface, pose, centre: np.ndarray, q: np.ndarray, turn: float,
                 ab0: np.ndarray, delta0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton on ``S(a, b) = Rz(turn delta) q`` for every point ``q`` (gear-centred
    meshing frame; ``S`` the other flank posed by ``pose``): ``(delta, (a, b))``, delta
    NaN where not converged within 20 steps to :data:`SCREEN_TOL_MM`."""
    rot_o, c_o = pose
    c_o = c_o - centre
    (u0, u1), (v0, v1) = other.u_range, other.v_range
    size = max(u1 - u0, v1 - v0)
    ab = np.array(ab0, float)
    delta = np.array(delta0, float)
    done = np.zeros(len(q), dtype=bool)
    active = np.ones(len(q), dtype=bool)
    for _ in range(20):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        r, r_u, r_v = evaluate_many(other, ab[idx, 0], ab[idx, 1])
        p = _rot_z(q[idx], turn * delta[idx])
        res = r @ rot_o.T + c_o - p
        ok = np.abs(res).max(axis=1) < SCREEN_TOL_MM
        done[idx[ok]] = True
        active[idx[ok]] = False
        idx, r_u, r_v, p, res = idx[~ok], r_u[~ok], r_v[~ok], p[~ok], res[~ok]
        if idx.size == 0:
            break
        dp = turn * np.column_stack([-p[:, 1], p[:, 0], np.zeros(len(p))])
        jac = np.stack([r_u @ rot_o.T, r_v @ rot_o.T, -dp], axis=2)
        step = _solve_each(jac, -res)
        ab[idx] += step[:, :2]
        delta[idx] += step[:, 2]
        lost = (~np.isfinite(step).all(axis=1) | (np.abs(delta[idx]) > 1.0)
                | (ab[idx, 0] < u0 - size) | (ab[idx, 0] > u1 + size)
                | (ab[idx, 1] < v0 - size) | (ab[idx, 1] > v1 + size))
        active[idx[lost]] = False
    return np.where(done, delta, np.nan), ab


def edge_gaps(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint, *,
              forward: bool, edges=None, samples: int = SCREEN_SAMPLES,
              memo: dict | None = None) -> list[EdgeGap]:
    """The screen of every candidate edge at the surface contact ``mp``.

    Parameters
    ----------
    pinion, gear : Surface
        The two flanks.
    kin : MeshKinematics
        Kinematics with assembly errors.
    mp : MatingPoint
        A surface mating point (both members posed there).
    forward : bool
        The gear is pushed towards +phi2 (the first touch is the largest turn).
    edges : sequence of FlankEdge, optional
        Default :func:`~.edge_contact.flank_edges`.
    samples : int
        Even samples per edge (>= 4). An edge whose bound is -inf is screened again at
        :data:`FINE_SAMPLES` when ``samples`` is fewer (module docstring); its
        :class:`EdgeGap` is then the finer screen's.
    memo : dict, optional
        Filled with each edge's touches (by label and sample count); a later call with
        it starts each sample's Newton there (one dict along a path).

    Returns
    -------
    list of EdgeGap
    """
    if int(samples) < 4:
        raise ValueError(f"samples = {samples!r} must be >= 4")
    if edges is None:
        edges = flank_edges(pinion, gear)
    out = _screen(pinion, gear, kin, mp, forward=forward, edges=edges, samples=samples,
                  memo=memo)
    again = [k for k, got in enumerate(out) if got.lower_rad == -np.inf]
    if again and int(samples) < FINE_SAMPLES:
        finer = _screen(pinion, gear, kin, mp, forward=forward,
                        edges=[out[k].edge for k in again], samples=FINE_SAMPLES, memo=memo)
        for k, got in zip(again, finer):
            out[k] = got
    return out


def _screen(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint, *,
            forward: bool, edges, samples: int, memo: dict | None) -> list[EdgeGap]:
    """:func:`edge_gaps` at ``samples`` per edge, without the finer screen."""
    flank = {"pinion": pinion, "gear": gear}
    spans = [np.linspace(*edge_span(flank[edge.member], edge.name), int(samples))
             for edge in edges]
    compiled = _compiled_screen(pinion, gear, kin, mp, edges, spans, forward=forward,
                                memo=memo)
    if compiled is not None:
        return [EdgeGap(*row) for row in zip(edges, spans, *compiled)]
    items = []
    for edge, s in zip(edges, spans):
        at = np.array((mp.u2, mp.v2) if edge.member == "pinion" else (mp.u1, mp.v1), float)
        ab0, g0 = (None, None) if memo is None else memo.get((edge.label, s.size), (None, None))
        if ab0 is None:
            items.append((edge, s))
            continue
        known = np.isfinite(ab0).all(axis=1) & np.isfinite(g0)
        items.append((edge, s, np.where(known[:, None], ab0, at), np.where(known, g0, 0.0)))
    turns = _turns(pinion, gear, kin, mp, items, forward=forward)
    if memo is not None:
        for edge, s, (gap, _, ab) in zip(edges, spans, turns):
            memo[(edge.label, s.size)] = (ab, gap)
    gaps, margins = [t[0] for t in turns], [t[1] for t in turns]
    lower = _refined_bounds(
        lambda items: _turns(pinion, gear, kin, mp, [(edges[i[0]], *i[1:]) for i in items],
                             forward=forward), spans, gaps, margins, [t[2] for t in turns])
    return [EdgeGap(*row) for row in zip(edges, spans, gaps, margins, lower)]


def _compiled_screen(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
                     edges, spans: list, *, forward: bool, memo: dict | None):
    """``(gaps, margins, lower bounds)`` of :func:`edge_gaps` from the compiled screen
    (:func:`.screen_kernel.screen`, the same procedure), or None when a flank has no
    kernel form (:func:`~.gap_kernel.kernel_surface`)."""
    forms = kernel_surface(pinion), kernel_surface(gear)
    if forms[0] is None or forms[1] is None or len({s.size for s in spans}) > 1:
        return None
    flank = {"pinion": pinion, "gear": gear}
    poses = (kin.pinion_pose(mp.phi1_rad), kin.gear_pose(mp.phi2_rad))
    centre = poses[1][1]
    boxes = np.array([[*f.u_range, *f.v_range] for f in (pinion, gear)], float)
    rots = np.ascontiguousarray(np.stack([poses[0][0], poses[1][0]]), dtype=float)
    cs = np.ascontiguousarray(np.stack([poses[0][1] - centre, poses[1][1] - centre]),
                              dtype=float)
    turns = np.array([-kin.gear_axis[2], kin.gear_axis[2]], float)
    at = np.array([[mp.u2, mp.v2], [mp.u1, mp.v1]], float)
    members = np.array([0 if e.member == "pinion" else 1 for e in edges], np.int64)
    codes, kinks = np.empty(len(edges), np.int64), np.full(len(edges), -1, np.int64)
    for k, e in enumerate(edges):
        own = flank[e.member]
        if is_kink(own, e.name):
            codes[k], kinks[k] = EDGE_KINK, [c.name for c in own.kinks].index(e.name)
        else:
            codes[k] = EDGE_CODES[e.name]
    n = spans[0].size if spans else 0
    s_all = np.array(spans, float).reshape(len(edges), n)
    start_ab = np.full((len(edges), n, 2), np.nan)
    start_g = np.full((len(edges), n), np.nan)
    for k, e in enumerate(edges):
        ab0, g0 = (None, None) if memo is None else memo.get((e.label, n), (None, None))
        if ab0 is not None:
            start_ab[k], start_g[k] = ab0, g0
    gap, margin = np.empty((len(edges), n)), np.empty((len(edges), n))
    ab, lower = np.empty((len(edges), n, 2)), np.empty(len(edges))
    screen(forms[0], forms[1], boxes, rots, cs, turns, at, members, codes, kinks, s_all,
           start_ab, start_g, bool(forward), SCREEN_TOL_MM, 20, CURVATURE_FACTOR,
           REFINE_LEVELS, gap, margin, ab, lower)
    if memo is not None:
        for k, e in enumerate(edges):
            memo[(e.label, n)] = (ab[k], gap[k])
    return list(gap), list(margin), [float(x) for x in lower]


def edge_first(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint, *,
               forward: bool, tol_mm: float = 1e-10, memo: dict | None = None) -> MatingPoint:
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
    memo : dict, optional
        The screen's Newton starts (:func:`edge_gaps`).

    Returns
    -------
    MatingPoint
        ``mp`` (the same object) if no edge touches first, else the edge contact.
    """
    open_edges = [g.edge for g in edge_gaps(pinion, gear, kin, mp, forward=forward,
                                            memo=memo) if not g.ruled_out]
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
