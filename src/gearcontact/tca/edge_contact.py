"""Edge-to-surface contact: a boundary curve of one flank touching the other flank.

When the surface-to-surface mating point of a phase lies beyond a flank boundary
(misalignment, short face, strong ease-off), the teeth still touch: an *edge* of one
flank - toe, heel, tip (top-land edge) or root (fillet limit) - meets the other flank's
surface. The gear then rests where the first point of an edge reaches the other surface
(Litvin & Fuentes 2004, sec. 15.7 "edge contact"; Simon 2007):

for each point ``s`` of the edge ``C(s)`` of member ``M`` (``u`` or ``v`` held at its box
limit, the other parameter ``s`` free), the gear rotation ``phi2(s)`` that brings the
point onto the other member's surface solves the three equations

.. math::  \\mathbf X_1 - \\mathbf X_2 = 0

in the other member's parameters ``(a, b)`` and ``phi2`` (pinion phase held; Newton's
method with the analytic Jacobian ``[r_a, r_b, -w_2 x (X_2 - c_2)]``). The contact is the
extreme of ``phi2(s)`` over the edge in the direction the gear is pushed (the first
point to touch; the same rule that picks the transmitting pair of the envelope in
:mod:`gearcontact.tca.mesh`): a bounded 1-D minimisation (Brent) after sampling the
edge, over the edge points that touch the other flank only (a bracket end beyond its
boundary is moved to the crossing). At an interior extreme ``d phi2 / ds = 0``, i.e.
the edge tangent lies in the touched surface's tangent plane; at an end of the edge the
contact is a corner. When the surface mating point reaches the edge from inside, it
satisfies both systems, so the edge solution continues the surface one with continuous
TE0 (tested).

The result is a :class:`~gearcontact.tca.types.MatingPoint` whose ``edge_contact`` names
the edge (``"pinion toe"``) and whose ``normal`` is the touched surface's normal
oriented like every mating normal (out of the gear tooth, into the pinion tooth). Edge
contact is singular (no contact ellipse across the edge); downstream the loaded contact
is solved on the real gap field around the edge point, whose cells beyond the edge
carry no material.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., Cambridge
University Press, 2004, sec. 15.7.
V. Simon, "Load distribution in spiral bevel gears", *J. Mech. Des.* 129 (2007) 201-209
(edge contact of misaligned bevel gears).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from .edge_kernel import EDGE_CODES, EDGE_KINK, edge_newton
from .gap_kernel import kernel_surface
from .mating import _cross, posed_point, solve_mating_point
from .types import ContactGuess, EdgeContact, MatingPoint, TcaConvergenceError

__all__ = ["EDGE_NAMES", "FlankEdge", "FLANK_EDGES", "edge_parameters", "edge_span",
           "flank_edges", "is_kink", "pushes_forward", "edge_directions", "inward_slope",
           "solve_edge_contact", "contact_state"]

#: Edges of a flank's parameter box (``u`` root -> tip, ``v`` toe -> heel).
EDGE_NAMES = ("toe", "heel", "root", "tip")

#: Samples along an edge before the 1-D refinement (the extreme of ``phi2(s)`` is
#: bracketed by the best sample's neighbours).
EDGE_SAMPLES = 7


@dataclass(frozen=True)
class FlankEdge:
    """One boundary curve of a member's flank.

    Attributes
    ----------
    member : str
        ``"pinion"`` or ``"gear"``.
    name : str
        One of :data:`EDGE_NAMES`.
    """

    member: str
    name: str

    @property
    def label(self) -> str:
        """``"<member> <edge>"``, the name used in every output."""
        return f"{self.member} {self.name}"


#: All eight candidate edges (each member's four, touching the other's surface).
FLANK_EDGES = tuple(FlankEdge(m, e) for m in ("pinion", "gear") for e in EDGE_NAMES)


def _kink(surface: Surface, name: str):
    """The :class:`~gearcontact.geometry.kinked.KinkLine` ``name`` of ``surface``, or None."""
    for kink in getattr(surface, "kinks", ()):
        if kink.name == name:
            return kink
    return None


def is_kink(surface: Surface, name: str) -> bool:
    """True if ``name`` is a blade-relief kink line of ``surface`` (an interior ridge of
    a :class:`~gearcontact.geometry.kinked.KinkedFlank`, docs/machine_settings.md
    sec. 1), not a boundary of its box."""
    return _kink(surface, name) is not None


def flank_edges(pinion: Surface, gear: Surface) -> tuple[FlankEdge, ...]:
    """The candidate edges of a flank pair: the eight box edges and every kink line of a
    relieved flank that crosses its box (a convex ridge: a curve of the flank that can
    touch the other flank first, like an edge, with material on both sides)."""
    kinks = tuple(FlankEdge(member, kink.name) for member, surface in
                  (("pinion", pinion), ("gear", gear)) for kink in getattr(surface, "kinks", ())
                  if np.isfinite(kink.u_nodes).any())
    return FLANK_EDGES + kinks


def edge_span(surface: Surface, name: str) -> tuple[float, float]:
    """Range of the free parameter ``s`` along the edge ``name``, mm (a kink line: its
    ``v``)."""
    if is_kink(surface, name):
        return tuple(map(float, surface.v_range))
    if name in ("toe", "heel"):
        return tuple(map(float, surface.u_range))
    if name in ("root", "tip"):
        return tuple(map(float, surface.v_range))
    raise ValueError(f"edge = {name!r} is not one of {EDGE_NAMES}")


def edge_parameters(surface: Surface, name: str, s: float) -> tuple[float, float]:
    """Flank parameters ``(u, v)`` of the point ``s`` of the edge ``name`` (a kink line:
    ``(u_k(s), s)``, held in the box where the kink leaves it)."""
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    kink = _kink(surface, name)
    if kink is not None:
        return float(np.clip(kink.u(s), u0, u1)), float(s)
    return {"toe": (s, v0), "heel": (s, v1), "root": (u0, s), "tip": (u1, s)}[name]


def pushes_forward(gear: Surface, kin: MeshKinematics, guess: ContactGuess) -> bool:
    """True if a contact at ``guess`` pushes the gear towards +phi2 (its normal, out of
    the gear tooth, opposes the gear's velocity): the gear then rests on the contact
    of *largest* phi2 (:mod:`gearcontact.tca.mesh`)."""
    _, x2, n2 = posed_point(gear, kin.gear_pose(guess.phi2_rad), guess.u2, guess.v2)
    t2 = kin.gear_pose(guess.phi2_rad)[1]
    return bool(n2 @ np.cross(kin.gear_axis, x2 - t2) < 0.0)


def _inside(surface: Surface, a: float, b: float, tol: float = 1e-9) -> bool:
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    return u0 - tol <= a <= u1 + tol and v0 - tol <= b <= v1 + tol


class _EdgeSolver:
    """``phi2(s)`` of one edge at one pinion phase (3 x 3 Newton per point)."""

    def __init__(self, pinion: Surface, gear: Surface, kin: MeshKinematics, phi1: float,
                 edge: FlankEdge, *, tol_mm: float, max_iter: int):
        self.pinion, self.gear, self.kin, self.phi1 = pinion, gear, kin, float(phi1)
        self.edge, self.tol, self.max_iter = edge, tol_mm, max_iter
        self.own = pinion if edge.member == "pinion" else gear
        self.other = gear if edge.member == "pinion" else pinion
        self.pose1 = kin.pinion_pose(self.phi1)
        # solutions by (s, start): the refinement asks again for points it has (the
        # bracket ends, the boundary crossing's ends and root); a repeated Newton solve
        # returns the same bits, so it is looked up
        self._solved: dict = {}
        self._compiled = self._compiled_arguments()

    def _compiled_arguments(self) -> tuple | None:
        """The fixed arguments of the compiled Newton (:func:`.edge_kernel.edge_newton`)
        when a flank of the pair is relieved (its ridge search, module docstring of
        :mod:`.edge_kernel`) and both have a kernel form, else None (the Python
        iteration of :meth:`_newton`; a smooth pair's results stay bit for bit)."""
        if not (getattr(self.pinion, "kinks", ()) or getattr(self.gear, "kinks", ())):
            return None
        own, other = kernel_surface(self.own), kernel_surface(self.other)
        if own is None or other is None:
            return None
        name = self.edge.name
        if is_kink(self.own, name):
            code, kink = EDGE_KINK, [k.name for k in self.own.kinks].index(name)
        else:
            code, kink = EDGE_CODES[name], -1
        box = np.array([*self.own.u_range, *self.own.v_range], float)
        rot1, t1 = (np.ascontiguousarray(a, dtype=float) for a in self.pose1)
        return (*own, *other, code, kink, box), (
            self.edge.member == "pinion", rot1, t1, float(self.kin.gear_axis[2]),
            float(self.kin.gear_pose(0.0)[1][2]), float(self.tol), int(self.max_iter))

    def solve(self, s: float, y0: np.ndarray) -> np.ndarray | None:
        """``(a, b, phi2)`` with edge point ``s`` on the other surface, or None."""
        y0 = np.asarray(y0, float)
        key = (float(s), y0.tobytes())
        if key not in self._solved:
            self._solved[key] = self._newton(s, y0)
        return self._solved[key]

    def _newton(self, s: float, y0: np.ndarray) -> np.ndarray | None:
        if self._compiled is not None:
            head, tail = self._compiled
            y = np.empty(3)
            got = edge_newton(*head, float(s), np.ascontiguousarray(y0), *tail, y)
            return y if got else None
        kin, w2 = self.kin, self.kin.gear_axis
        ue, ve = edge_parameters(self.own, self.edge.name, s)
        y = np.array(y0, float)
        on_pinion = self.edge.member == "pinion"
        if on_pinion:   # the edge point is fixed (pinion phase held)
            x1 = posed_point(self.pinion, self.pose1, ue, ve)[1]
        else:
            sp_edge = self.gear.point(ue, ve)
        tol = self.tol
        jac = np.empty((3, 3))
        for _ in range(self.max_iter):
            rot2, c2 = kin.gear_pose(y[2])
            if on_pinion:
                sp = self.gear.point(y[0], y[1])
                x2 = rot2 @ sp.r + c2
                res = x1 - x2
                jac[:, 0], jac[:, 1] = -(rot2 @ sp.r_u), -(rot2 @ sp.r_v)
            else:
                sp = self.pinion.point(y[0], y[1])
                x1 = self.pose1[0] @ sp.r + self.pose1[1]
                x2 = rot2 @ sp_edge.r + c2
                res = x1 - x2
                jac[:, 0], jac[:, 1] = self.pose1[0] @ sp.r_u, self.pose1[0] @ sp.r_v
            jac[:, 2] = -_cross(w2, x2 - c2)
            if abs(res[0]) < tol and abs(res[1]) < tol and abs(res[2]) < tol:
                return y
            try:
                step = np.linalg.solve(jac, -res)
            except np.linalg.LinAlgError:
                return None
            # a step of more than a tooth or a tenth of a radian: no touch nearby
            if np.abs(step[:2]).max() > 50.0 or abs(step[2]) > 0.1:
                return None
            y = y + step
        return None

    def feasible(self, y: np.ndarray | None) -> bool:
        return y is not None and _inside(self.other, y[0], y[1])

    def mating_point(self, s: float, y: np.ndarray) -> MatingPoint:
        """The contact state of edge point ``s`` touching at ``y``."""
        ue, ve = edge_parameters(self.own, self.edge.name, s)
        pose2 = self.kin.gear_pose(y[2])
        if self.edge.member == "pinion":
            u1, v1, u2, v2 = ue, ve, y[0], y[1]
            _, x, n = posed_point(self.gear, pose2, u2, v2)
        else:
            u1, v1, u2, v2 = y[0], y[1], ue, ve
            _, x, n1 = posed_point(self.pinion, self.pose1, u1, v1)
            n = -n1     # the common normal points into the pinion tooth
        return MatingPoint(self.phi1, float(y[2]), float(u1), float(v1), float(u2),
                           float(v2), x, n, edge_contact=self.edge.label)


def edge_directions(pinion: Surface, gear: Surface, kin: MeshKinematics,
                    mp: MatingPoint) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Posed unit directions of an edge contact (meshing frame).

    Returns ``(along, inward, n_other)``: the edge's tangent (its free parameter
    increasing), the unit step on the edge's own flank perpendicular to the edge and
    into that flank, and the touched flank's normal out of its tooth.
    """
    member, _, name = mp.edge_contact.partition(" ")
    if member == "pinion":
        own, uv, rot, n_other = pinion, (mp.u1, mp.v1), kin.pinion_pose(mp.phi1_rad)[0], mp.normal
    else:
        own, uv, rot, n_other = gear, (mp.u2, mp.v2), kin.gear_pose(mp.phi2_rad)[0], -mp.normal
    if is_kink(own, name):
        along, inward = _kink_directions(own, name, *uv)
        return rot @ along, rot @ inward[1], np.asarray(n_other, float)
    sp = own.point(*uv)
    along, across, sign = {"toe": (sp.r_u, sp.r_v, 1.0), "heel": (sp.r_u, sp.r_v, -1.0),
                           "root": (sp.r_v, sp.r_u, 1.0), "tip": (sp.r_v, sp.r_u, -1.0)}[name]
    t = along / np.linalg.norm(along)
    inward = sign * (across - (across @ t) * t)
    return rot @ t, rot @ (inward / np.linalg.norm(inward)), np.asarray(n_other, float)


def inward_slope(pinion: Surface, gear: Surface, kin: MeshKinematics,
                 mp: MatingPoint) -> float:
    """Slope of the separation from the edge into its own flank at an edge contact.

    ``(d X_own / d q) . n_other`` for a unit step ``q`` on the own flank perpendicular
    to the edge, inwards, with ``n_other`` the touched flank's normal out of its
    tooth. Positive: the flank behind the edge recedes from the other flank, so the
    edge is the first point to touch; negative: the flank surface inside the edge
    touches first (the surface contact is back on the flanks).
    """
    member, _, name = mp.edge_contact.partition(" ")
    own = pinion if member == "pinion" else gear
    if is_kink(own, name):   # a ridge: the first to touch while both sides recede
        uv = (mp.u1, mp.v1) if member == "pinion" else (mp.u2, mp.v2)
        rot = (kin.pinion_pose(mp.phi1_rad) if member == "pinion"
               else kin.gear_pose(mp.phi2_rad))[0]
        n_other = mp.normal if member == "pinion" else -np.asarray(mp.normal)
        return float(min((rot @ w) @ n_other for w in _kink_directions(own, name, *uv)[1]))
    _, inward, n_other = edge_directions(pinion, gear, kin, mp)
    return float(inward @ n_other)


def _kink_directions(surface: Surface, name: str, u: float, v: float):
    """Body-frame unit tangent of a kink line at ``(u, v)`` (``v`` increasing) and the
    unit steps into the pieces below and above it (each piece's own derivatives,
    perpendicular to the kink)."""
    kink = _kink(surface, name)
    dv = 1e-4 * (surface.v_range[1] - surface.v_range[0])
    slope = float((kink.u(v + dv) - kink.u(v - dv)) / (2.0 * dv))
    inward = []
    for k, sign in ((kink.lower, -1.0), (kink.lower + 1, 1.0)):
        sc = surface.v_scales[k]
        sp = surface.pieces[k].point(u, sc * v)
        t = sp.r_u * slope + sc * sp.r_v
        t = t / np.linalg.norm(t)
        w = sign * (sp.r_u - (sp.r_u @ t) * t)
        inward.append(w / np.linalg.norm(w))
    return t, inward


def _guess_y(edge: FlankEdge, guess: ContactGuess) -> np.ndarray:
    if edge.member == "pinion":
        return np.array([guess.u2, guess.v2, guess.phi2_rad])
    return np.array([guess.u1, guess.v1, guess.phi2_rad])


def _guess_s(surface: Surface, edge: FlankEdge, guess: ContactGuess) -> float:
    u, v = (guess.u1, guess.v1) if edge.member == "pinion" else (guess.u2, guess.v2)
    lo, hi = edge_span(surface, edge.name)
    return float(np.clip(u if edge.name in ("toe", "heel") else v, lo, hi))


def _edge_samples(solver: _EdgeSolver, guess: ContactGuess, forward: bool,
                  samples: int, memo: dict | None = None
                  ) -> tuple[float, np.ndarray, np.ndarray, list] | None:
    """Sample ``phi2(s)`` along one edge: ``(best score, samples s, scores, solutions)``,
    or None if no sample of the edge meets the other flank. ``memo`` (per edge: sample
    ``s`` -> ``(phi1, y)`` of an earlier phase) gives each sample its own Newton start,
    turned by the nominal ratio."""
    lo, hi = edge_span(solver.own, solver.edge.name)
    s0 = _guess_s(solver.own, solver.edge, guess)
    # the guess's own position and its close neighbours join the even samples: the
    # edge contact of the previous phase continues there even where the touching part
    # of the edge is short (an edge crossing the other flank's boundary)
    near = 0.02 * (hi - lo)
    ss = np.unique(np.clip(np.concatenate([np.linspace(lo, hi, int(samples)),
                                           [s0 - near, s0, s0 + near]]), lo, hi))
    ys: list = [None] * len(ss)
    k0 = int(np.argmin(np.abs(ss - s0)))
    # chain the Newton starts outwards from the sample nearest the guess
    known = {} if memo is None else memo.setdefault(solver.edge.label, {})
    ratio = solver.kin.ratio
    for order in (range(k0, len(ss)), range(k0 - 1, -1, -1)):
        y_prev = _guess_y(solver.edge, guess)
        for k in order:
            y = None
            if float(ss[k]) in known:
                phi1_old, y_old = known[float(ss[k])]
                y = solver.solve(ss[k], y_old + np.array(
                    [0.0, 0.0, (solver.phi1 - phi1_old) / ratio]))
            if y is None and y_prev is not None:
                y = solver.solve(ss[k], y_prev)
            ys[k] = y
            if y is not None:
                y_prev = y
                known[float(ss[k])] = (solver.phi1, y)
    sign = 1.0 if forward else -1.0
    score = np.array([sign * y[2] if solver.feasible(y) else -np.inf for y in ys])
    if not np.isfinite(score).any():
        return None
    return float(score.max()), ss, score, ys


def _edge_extreme(solver: _EdgeSolver, forward: bool, sampled) -> tuple[float, np.ndarray]:
    """``(s, y)`` of the first point of one edge to touch: the best sample refined by a
    bounded Brent search one even sample spacing either side of it, over the stretch of
    the edge that touches the other flank (a bracket end that does not is moved to the
    boundary crossing, or to the last touching point)."""
    _, ss, score, ys = sampled
    sign = 1.0 if forward else -1.0
    k = int(np.argmax(score))
    # bracket: one even sample spacing either side of the best sample (the samples near
    # the last contact are closer together than the extreme may have moved)
    lo, hi = edge_span(solver.own, solver.edge.name)
    h = (hi - lo) / (EDGE_SAMPLES - 1)
    y_best = ys[k]
    # where a bracket end touches beyond the other flank (or not at all), the extreme can
    # be the crossing of the two flanks' boundaries: its point (margin 0) by Brent's root
    # search; and the bracket ends there, so that the 1-D search sees only touching points
    # (an untouching stretch is a plateau that drew the bounded search away from the
    # extreme: the 13/26 drive's pinion heel, docs/machine_settings.md sec. 5)
    candidates = [(ss[k], y_best)]
    ends = []
    for end in (max(ss[k] - h, lo), min(ss[k] + h, hi)):
        if end == ss[k] or solver.feasible(solver.solve(end, y_best)):
            ends.append(end)
            if end != ss[k]:
                candidates.append((end, solver.solve(end, y_best)))
            continue
        crossing = _boundary_crossing(solver, ss[k], end, y_best)
        if crossing is not None:
            candidates.append(crossing)
            ends.append(crossing[0])
        else:
            ends.append(_last_touching(solver, ss[k], end, y_best))
    a, b = sorted(ends)
    cache = {}

    def objective(s):
        y = solver.solve(s, y_best)
        cache[float(s)] = y
        # infeasible points (beyond the other flank) rank below the best sample
        return -sign * y[2] if solver.feasible(y) else -score[k] + 1.0

    if b > a:
        opt = minimize_scalar(objective, bounds=(a, b), method="bounded",
                              options={"xatol": 1e-5})
        s_opt = float(opt.x)
        # the bounded search never evaluates the bracket ends: an extreme at an end of
        # the edge (a corner contact) is the end sample itself
        candidates.append((s_opt, cache[s_opt] if s_opt in cache
                           else solver.solve(s_opt, y_best)))
    candidates = [(sv, y) for sv, y in candidates if solver.feasible(y)]
    return max(candidates, key=lambda sy: sign * sy[1][2])


def _last_touching(solver: _EdgeSolver, s_in: float, s_out: float, y_in: np.ndarray,
                   *, steps: int = 40) -> float:
    """The edge point nearest ``s_out`` that still touches the other flank, between
    ``s_in`` (touching) and ``s_out`` (not: its Newton solve fails), by bisection on
    feasibility (``steps`` halvings)."""
    for _ in range(steps):
        mid = 0.5 * (s_in + s_out)
        if solver.feasible(solver.solve(mid, y_in)):
            s_in = mid
        else:
            s_out = mid
    return s_in


def _margin(surface: Surface, y: np.ndarray) -> float:
    """Signed distance of the touched point's parameters inside ``surface``'s box, mm."""
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    return float(min(y[0] - u0, u1 - y[0], y[1] - v0, v1 - y[1]))


def _boundary_crossing(solver: _EdgeSolver, s_in: float, s_out: float,
                       y_in: np.ndarray) -> tuple[float, np.ndarray] | None:
    """The edge point between ``s_in`` (touching inside the other flank) and ``s_out``
    (beyond it) whose touch lies on the other flank's boundary (margin 0)."""
    def margin(s):
        y = solver.solve(s, y_in)
        return -1.0 if y is None else _margin(solver.other, y)

    if margin(s_out) >= 0.0:
        return None
    try:
        s_b = brentq(margin, s_in, s_out, xtol=1e-9)
    except ValueError:
        return None
    y = solver.solve(s_b, y_in)
    if y is None:
        return None
    return s_b, y           # feasible within the box tolerance (1e-9 mm)


#: Edges refined after sampling (the best by their sampled first touch).
EDGES_REFINED = 2


def solve_edge_contact(pinion: Surface, gear: Surface, kin: MeshKinematics, phi1_rad: float,
                       *, guess: ContactGuess, forward: bool, edges=None,
                       samples: int = EDGE_SAMPLES, tol_mm: float = 1e-10,
                       max_iter: int = 15, memo: dict | None = None) -> MatingPoint | None:
    """The first edge-to-surface contact of one tooth pair at the pinion phase ``phi1``.

    Parameters
    ----------
    pinion, gear : Surface
        The two flanks (body frames, normals out of the tooth).
    kin : MeshKinematics
        Kinematics with assembly errors.
    phi1_rad : float
        Pinion phase, rad (held).
    guess : ContactGuess
        A nearby contact state (Newton starts; its ``phi1`` is ignored).
    forward : bool
        The pinion pushes the gear towards +phi2 (:func:`pushes_forward`): the contact
        is the edge point of largest ``phi2``; else of smallest.
    edges : sequence of FlankEdge
        Candidate edges (default :func:`flank_edges`: all eight and the kink lines).
    samples : int
        Even points per edge before the 1-D refinement (>= 3); the
        :data:`EDGES_REFINED` edges whose samples touch first are refined.
    tol_mm : float
        Newton tolerance of the point-on-surface equations, mm.
    memo : dict, optional
        Newton starts kept between calls (pass the same dict along a path: each edge
        sample then starts from its solution at the previous phase).

    Returns
    -------
    MatingPoint or None
        With ``edge_contact`` naming the edge (``te0_arcsec`` 0: the path sets it);
        None if no edge point meets the other flank inside its boundary.
    """
    if int(samples) < 3:
        raise ValueError(f"samples = {samples!r} must be >= 3")
    if edges is None:
        edges = flank_edges(pinion, gear)
    sampled = []
    for edge in edges:
        solver = _EdgeSolver(pinion, gear, kin, phi1_rad, edge, tol_mm=tol_mm,
                             max_iter=max_iter)
        hit = _edge_samples(solver, guess, forward, samples, memo)
        if hit is not None:
            sampled.append((hit[0], solver, hit))
    if not sampled:
        return None
    sampled.sort(key=lambda item: -item[0])
    sign = 1.0 if forward else -1.0
    refined = [(solver, _edge_extreme(solver, forward, hit))
               for _, solver, hit in sampled[:EDGES_REFINED]]
    solver, (s, y) = max(refined, key=lambda item: sign * item[1][1][2])
    return solver.mating_point(s, y)


def contact_state(pinion: Surface, gear: Surface, kin: MeshKinematics, guess: ContactGuess,
                  *, fixed: str = "phi1", forward: bool | None = None,
                  tol_mm: float = 1e-10, max_iter: int = 40) -> MatingPoint:
    """The contact at ``guess``: the surface mating point, or, if that lies beyond a
    flank boundary (or its Newton solve fails), the edge contact at ``guess.phi1``.

    ``forward`` defaults to :func:`pushes_forward` at ``guess``.

    Raises
    ------
    EdgeContact, TcaConvergenceError
        The surface solve's error, if no edge touches either.
    """
    try:
        return solve_mating_point(pinion, gear, kin, guess, fixed=fixed, tol_mm=tol_mm,
                                  max_iter=max_iter)
    except (EdgeContact, TcaConvergenceError) as exc:
        error = exc
    if forward is None:
        forward = pushes_forward(gear, kin, guess)
    mp = solve_edge_contact(pinion, gear, kin, guess.phi1_rad, guess=guess, forward=forward)
    if mp is None:
        raise error
    return mp
