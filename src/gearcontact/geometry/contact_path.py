"""The contact path of a crowned bevel or hypoid pair inside its active flanks and the
contact ratio it gives, before any flank work (docs/geometry.md sec. 7.7; the check is
:func:`~.contact_ratio.check_contact_ratio`).

A crowned pair touches, at each gear rotation, where the ease-off is least on the
contact line of the conjugate pair; the locus of those points is the contact path, and
a tooth pair is in interior contact while its point lies inside both flanks. The virtual
cylindrical gears of ISO 10300-1 (:mod:`.contact_ratio`) take the path's length as the
diagonal of the transverse and face spans; on narrow, low-spiral faces the path leaves
through toe or heel, or runs along the profile from tip to root, and is shorter.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 9.2
(TCA of localized contact), sec. 21.8 (local synthesis).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import RectBivariateSpline

from .conjugate import section_guesses

__all__ = ["Bearing", "PathContactRatio", "path_contact_ratio"]

#: The ease-off synthesis' default targets, defined here (geometry is below tca) and
#: taken by ``tca.synthesis_targets.SynthesisTargets`` and ``design``'s options: TE0
#: peak-to-peak, arcsec; paint-ellipse length over the gear face width.
SYNTHESIS_TE0_ARCSEC, SYNTHESIS_PATTERN_RATIO = 3.0, 0.35



@dataclass(frozen=True)
class Bearing:
    """The ease-off a pair will carry on one side where its file has no table: the
    bearing its ease-off synthesis is predicted to make (``tca.predicted_bearing``, above
    geometry: passed in by the command), checked by :func:`path_contact_ratio` in place
    of the pair's coefficients.

    Attributes
    ----------
    coefficients : EaseOffCoefficients or None
        About the pinion's mean node, as the pair's tables (um/mm, um/mm^2); None: the
        synthesis' zero-twist first-order bearing at the targets below
        (:func:`_synthesis_hessian`; at the default targets :data:`DEFAULT_BEARING`),
        whatever coefficients the pair holds.
    source : str
        What it is, for the refusal's message (e.g. ``"the synthesis' first-order
        bearing along the overlap path angle 30.1 deg"``).
    te0_pp_arcsec : float
        The synthesis' TE0 target of a bearing without coefficients, arcsec (the
        parabola's level: the crowning across the contact lines).
    pattern_length_ratio : float
        Its paint-ellipse length over the gear face width (the crowning along them).
    """

    coefficients: object
    source: str
    te0_pp_arcsec: float = SYNTHESIS_TE0_ARCSEC
    pattern_length_ratio: float = SYNTHESIS_PATTERN_RATIO


@dataclass(frozen=True)
class PathContactRatio:
    """Contact ratio of a crowned pair from its contact path inside the active flanks
    (:func:`path_contact_ratio`).

    Attributes
    ----------
    total : float
        eps_p, the mean number of tooth pairs whose mating point lies inside both flanks
        (1).
    side : str
    ends : tuple of str
        The edges through which the path leaves the flanks, at the start and the end of
        the mesh (``"pinion root"``, ``"pinion tip"``, ``"pinion toe"``, ``"pinion heel"``,
        ``"gear toe"``, ``"gear heel"``, ...), or ``"last contact line"`` where it reaches
        the box's first or last contact line (a corner) inside.
    path_angle_deg : float
        Direction of the path at the bearing centre on the pinion flank, deg from the
        lengthwise direction towards the tip (the (v, u) parameter plane, mm).
    line_contact : float
        The conjugate pair's contact ratio: the ``phi2`` range of the whole active box
        in gear pitches (every contact line inside; the limit of a vanishing crowning
        across the lines).
    bearing : str
        The ease-off whose path it is: ``"the pair's table"``, :data:`DEFAULT_BEARING`
        or a :class:`Bearing`'s ``source``.
    """

    total: float
    side: str
    ends: tuple[str, str]
    path_angle_deg: float
    line_contact: float
    bearing: str = "the pair's table"


#: What :func:`path_contact_ratio` checks for a pair without a table and no
#: :class:`Bearing` given.
DEFAULT_BEARING = "the synthesis' first-order bearing at its default targets"


#: Exact node solves over the active box behind :func:`path_contact_ratio`: profile x
#: lengthwise lines of the bicubic spline of phi2 (and of the gear's lengthwise
#: parameter) over the box (17 x 17 lines, and twice the continuation steps, give the
#: same eps_p to 1e-4 on five design-space pairs; 9 x 9 to 5e-3).
_PATH_GRID = (13, 13)
#: Levels of phi2 over the box's phi2 range at which the path point is solved (the
#: measure of the interior levels is good to 1 / _PATH_LEVELS of the line-contact ratio).
_PATH_LEVELS = 300


def path_contact_ratio(pair, *, boxes: dict, side: str | None = None,
                       bearing: Bearing | None = None) -> PathContactRatio:
    """Contact ratio of ``pair`` from its contact path inside the flanks (docs/geometry.md
    sec. 7.7): the mean number of pairs whose mating point lies inside both flanks.

    A crowned pair touches, at each gear rotation phi2, where the ease-off E is least on
    the contact line of the conjugate pair, the level line ``phi2(u, v) = const`` of the
    pinion flank (Litvin & Fuentes 2004, sec. 9.2: the eased flanks' mating point is the
    point of least separation on the line the conjugate flanks would touch along). The
    path is the locus ``grad E = lambda grad phi2`` (a straight line through the
    ease-off's vertex in the direction ``H^-1 grad phi2`` where phi2 is linear, ``H`` the
    ease-off's Hessian); a tooth pair is in interior contact while that point lies in
    the pinion's active box (:func:`~.conjugate.pinion_active_box`: gear tip and root
    lines, pinion toe and heel) and inside the gear's face. The contact ratio is the
    phi2 range of those points in gear pitches: ``eps_p = z2 dphi2 / (2 pi)``. A path
    steeper than the diagonal of the box leaves through toe or heel before it reaches
    tip or root, which the virtual cylindrical gears cannot see.

    ``phi2(u, v)`` comes from exact solves of the node equations (the solver of
    :func:`~.generation.check_generation`, no node grid) on ``_PATH_GRID`` lines of the
    box, interpolated by a bicubic spline; the path point is solved (a Lagrange
    condition, Newton) on ``_PATH_LEVELS`` levels of phi2 (1-3 s). The ease-off is the
    pair's five-term table of ``side``; a table without a positive-definite crowning
    (none given: ``analyze`` synthesizes one, ``tca.synthesis``) counts as the
    synthesis' first-order bearing at its default targets (:func:`_synthesis_hessian`,
    vertex at the box centre): on the three examples its path ratio is that of the
    synthesized ease-off within 1 % (F.3 2.928 against 2.952, F.2 1.444 / 1.444, 11/41
    2.036 / 2.036; path angles within 0.1 deg). ``bearing`` replaces the pair's
    coefficients of ``side``: the bearing the synthesis is predicted to make where it
    turns the path or takes a path-angle target (``tca.predicted_bearing``,
    docs/geometry.md sec. 7.7).

    Parameters
    ----------
    pair : GearPair
        Right-hand (the left-hand pair's twin, as :func:`~.generation.check_generation`
        checks it), without machine settings.
    boxes : dict
        :func:`~.generation.check_generation`'s ``{side: {"active_box", "solver", ...}}``.
    side : str, optional
        Default the pair's design side.
    bearing : Bearing, optional
        The ease-off of ``side`` to check instead of the pair's.

    Returns
    -------
    PathContactRatio
    """
    side = pair.design_side if side is None else side
    solver, box = boxes[side]["solver"], boxes[side]["active_box"]
    nodes, us, vs = _box_nodes(solver, box, pair.blank)
    hu, hv = 0.5 * (box.u_tip - box.u_root), 0.5 * (box.v_heel - box.v_toe)
    uc, vc = box.u_root + hu, box.v_toe + hv
    xs, ys = (us - uc) / hu, (vs - vc) / hv
    phi = _Field(xs, ys, nodes[..., 2])
    # the node solution at the box centre: the guess of the exact solves there
    guess = np.array([RectBivariateSpline(xs, ys, nodes[..., k]).ev(0.0, 0.0)
                      for k in range(3)])
    gear = solver.gear
    v2 = _Field(xs, ys, gear.surface_parameters(nodes[..., 0], nodes[..., 1])[1])
    g_box = gear.boundary
    lo, hi = float(nodes[..., 2].min()), float(nodes[..., 2].max())
    step = (hi - lo) / _PATH_LEVELS

    def where(p):
        """The edge beyond which p lies, or "" inside both flanks."""
        if p[0] < -1.0 or p[0] > 1.0:
            return "pinion " + ("root" if p[0] < -1.0 else "tip")
        if p[1] < -1.0 or p[1] > 1.0:
            return "pinion " + ("toe" if p[1] < -1.0 else "heel")
        g = v2.value(p)
        if g < g_box.v_toe or g > g_box.v_heel:
            return "gear " + ("toe" if g < g_box.v_toe else "heel")
        return ""

    coeffs = (bearing.coefficients if bearing is not None
              else pair.easeoff_drive if side == "drive" else pair.easeoff_coast)
    levels = ((SYNTHESIS_TE0_ARCSEC, SYNTHESIS_PATTERN_RATIO) if bearing is None
              else (bearing.te0_pp_arcsec, bearing.pattern_length_ratio))
    b, h, start, own = _easeoff_in_box(coeffs, pair, solver, (uc, vc), (hu, hv), guess,
                                       levels)
    c0 = phi.value(start)
    inside, ends, steps = 0, [], []
    for sign in (-1.0, 1.0):
        # "last contact line": the path reaches the box's last phi2 level inside
        p, lam, entered, end = start.copy(), 0.0, False, "last contact line"
        prev = p
        for k in range(2 * _PATH_LEVELS):
            c = c0 + sign * k * step
            if not lo <= c <= hi:
                break
            got = _path_point(phi, b, h, c, p, lam)
            # no solution on this level: the path point left the box's spline (an exit
            # between two levels); named by the point extrapolated from the last two
            edge = where(2.0 * p - prev) if got is None else where(got[0])
            if got is None and entered:
                end = edge or _nearest_edge(p)
                break
            if got is None:
                break
            prev, (p, lam) = p, got
            if k == 1:
                steps.append(p)
            if not edge:
                inside += k > 0 or sign < 0.0   # the start level once
                entered = True
            elif entered or np.max(np.abs(p)) > 2.0:
                end = edge
                break
        ends.append(end)
        if len(steps) < len(ends):      # no neighbour level on this side
            steps.append(start)
    d = steps[1] - steps[0]      # the path's chord over the start's neighbour levels
    angle = math.degrees(math.atan2(d[0] * hu, d[1] * hv))
    angle = (angle + 90.0) % 180.0 - 90.0
    angle = 90.0 if angle == -90.0 else angle
    z2 = pair.gear_teeth
    return PathContactRatio(
        total=inside * step * z2 / (2.0 * math.pi), side=side, ends=(ends[0], ends[1]),
        path_angle_deg=angle, line_contact=(hi - lo) * z2 / (2.0 * math.pi),
        bearing=(bearing.source if bearing is not None
                 else "the pair's table" if own else DEFAULT_BEARING))


def _nearest_edge(p) -> str:
    """The pinion box edge nearest the normalized point p."""
    if abs(p[0]) >= abs(p[1]):
        return "pinion " + ("root" if p[0] < 0.0 else "tip")
    return "pinion " + ("toe" if p[1] < 0.0 else "heel")


def _box_nodes(solver, box, blank):
    """Node solutions ``(h, theta, phi2)`` (``_PATH_GRID`` + (3,)) on the lines of the
    active box, by continuation from the mean point: along the face at the mean height
    (:func:`~.conjugate.section_guesses`), then along the profile up and down."""
    n_u, n_v = _PATH_GRID
    us = np.linspace(box.u_root, box.u_tip, n_u)
    vs = np.linspace(box.v_toe, box.v_heel, n_v)
    u_m, v_m = float(solver.cone.root_offset_mm), float(blank.pitch_point_mm[0])
    q_m, _ = section_guesses(solver, vs, u_m, v_m, substeps=1)
    out = np.empty((n_u, n_v, 3))
    for order in (np.flatnonzero(us >= u_m), np.flatnonzero(us < u_m)[::-1]):
        q, u_prev = q_m, u_m
        for i in order:
            for u in np.linspace(u_prev, us[i], 3)[1:]:
                s = solver.solve(np.full(n_v, u), vs, q)
                q = np.stack([s.h_mm, s.theta_rad, s.phi2_rad], axis=-1)
            out[i], u_prev = q, us[i]
    return out, us, vs


class _Field:
    """Bicubic spline of a field over the box's normalized coordinates, continued beyond
    the box by its first-order Taylor polynomial at the nearest box point (the Newton
    steps of :func:`_path_point` may leave the box)."""

    def __init__(self, xs, ys, values):
        self._s = RectBivariateSpline(xs, ys, values, kx=3, ky=3)

    def _at(self, p, dx=0, dy=0):
        return float(self._s.ev(p[0], p[1], dx=dx, dy=dy))

    def value(self, p) -> float:
        q = np.clip(p, -1.0, 1.0)
        return self._at(q) + float(self.grad(q) @ (np.asarray(p) - q))

    def grad(self, p) -> np.ndarray:
        q = np.clip(p, -1.0, 1.0)
        return np.array([self._at(q, 1, 0), self._at(q, 0, 1)])

    def hessian(self, p) -> np.ndarray:
        if np.any(np.abs(p) > 1.0):
            return np.zeros((2, 2))
        cross = self._at(p, 1, 1)
        return np.array([[self._at(p, 2, 0), cross], [cross, self._at(p, 0, 2)]])


def _path_point(phi, b, h, level, p, lam):
    """The point of least ease-off ``E = b.p + p^T h p / 2`` on the level line
    ``phi = level`` (Newton on ``grad E = lam grad phi, phi = level`` from ``(p, lam)``),
    or None if Newton does not converge."""
    for _ in range(30):
        g, hess = phi.grad(p), phi.hessian(p)
        f = np.append(b + h @ p - lam * g, phi.value(p) - level)
        jac = np.zeros((3, 3))
        jac[:2, :2], jac[:2, 2], jac[2, :2] = h - lam * hess, -g, g
        try:
            step = np.linalg.solve(jac, -f)
        except np.linalg.LinAlgError:
            return None
        p, lam = p + step[:2], lam + step[2]
        if np.max(np.abs(step[:2])) < 1e-12:
            return p, lam
    return None


def _easeoff_in_box(c, pair, solver, centre, half, guess, levels):
    """Gradient at the box centre, Hessian (um or any unit) and vertex (clipped to the
    box) of the ease-off coefficients ``c`` in the box's normalized coordinates
    ``((u - uc) / hu, (v - vc) / hv)``, and whether they were used: where their Hessian
    is not positive definite (no table) the synthesis' bearing at the targets
    ``levels`` = (TE0 arcsec, pattern-length ratio) (:func:`_synthesis_hessian`) with
    its vertex at the box centre."""
    u_m, v_m = float(solver.cone.root_offset_mm), float(pair.blank.pitch_point_mm[0])
    scale = np.diag(half)
    h_uv = np.zeros((2, 2)) if c is None else np.array(
        [[2.0 * c.profile_crowning_um_per_mm2, c.bias_um_per_mm2],
         [c.bias_um_per_mm2, 2.0 * c.lengthwise_crowning_um_per_mm2]])
    if c is None or not (h_uv[0, 0] > 0.0 and np.linalg.det(h_uv) > 0.0):
        h_uv = _synthesis_hessian(pair, solver, centre, half, guess, *levels)
        return np.zeros(2), scale @ h_uv @ scale, np.zeros(2), False
    g_uv = np.array([c.profile_angle_um_per_mm, c.spiral_angle_um_per_mm]) + h_uv @ (
        np.asarray(centre) - (u_m, v_m))
    g, h = scale @ g_uv, scale @ h_uv @ scale
    return g, h, np.clip(np.linalg.solve(h, -g), -1.0, 1.0), True


#: The paint thickness of ``tca.curvature`` (checked equal by
#: tests/geometry/test_contact_ratio.py), mm.
_PAINT_MM = 6.35e-3
#: Finite-difference step of the exact solves at the bearing centre, mm.
_STEP_MM = 0.02


def _synthesis_hessian(pair, solver, centre, half, guess, te0_pp_arcsec=SYNTHESIS_TE0_ARCSEC,
                       pattern_length_ratio=SYNTHESIS_PATTERN_RATIO) -> np.ndarray:
    """Hessian (1/mm) in the pinion's (u, v) of the first-order bearing the ease-off
    synthesis makes of a pair without a table at its targets ``te0_pp_arcsec`` and
    ``pattern_length_ratio`` (Litvin & Fuentes 2004, sec. 21.8; the
    relations of ``tca.path_reach``): at the box centre, in the tangent plane's frame
    ``(t, nu)`` of the contact line, ``H = [[a, b], [b, c]]`` with the paint ellipse's
    curvature along the line ``a = 8 delta / (2a)^2`` (``2a`` the ratio times the gear
    face), the TE0 level ``det H = a 8 h2 TE0 / dN^2`` (``dN`` the contact lines'
    spacing per pitch, ``h2`` the gear's lever: the parabolic TE of one pair is
    ``n^2 det H / (2 a)`` at the distance ``n`` of its line from the vertex) and the
    bias ``b`` that leaves no twist term in (u, v) (the synthesis draws it towards
    zero): of the quadratic's two roots the one with the least relief at the box's
    corners (the synthesis keeps the relief within its limit). Both targets turn the
    path (its direction is normal to ``H t``, ``tan psi = -b / a``, and ``b`` depends on
    ``c / a``), so they move eps_p.
    On the examples the ratio of profile to lengthwise crowning is that of their
    synthesized ease-off within 5 % (F.3 39.9 against 38.3)."""
    uc, vc = centre
    us = uc + _STEP_MM * np.array([0.0, 1.0, -1.0, 0.0, 0.0])
    vs = vc + _STEP_MM * np.array([0.0, 0.0, 0.0, 1.0, -1.0])
    s = solver.solve(us, vs, guess)
    r_u = (s.x1_mm[1] - s.x1_mm[2]) / (2.0 * _STEP_MM)
    r_v = (s.x1_mm[3] - s.x1_mm[4]) / (2.0 * _STEP_MM)
    e1 = r_v / np.linalg.norm(r_v)
    e2 = r_u - (r_u @ e1) * e1
    e2 /= np.linalg.norm(e2)
    m = np.array([[e1 @ r_u, e1 @ r_v], [e2 @ r_u, e2 @ r_v]])     # q = m (du, dv)
    grad_uv = np.array([s.phi2_rad[1] - s.phi2_rad[2], s.phi2_rad[3] - s.phi2_rad[4]]) \
        / (2.0 * _STEP_MM)
    grad_q = np.linalg.solve(m.T, grad_uv)
    nu = grad_q / np.linalg.norm(grad_q)
    n = np.column_stack([[-nu[1], nu[0]], nu]).T @ m        # (t, nu) = n (du, dv)
    spacing = 2.0 * math.pi / (pair.gear_teeth * np.linalg.norm(grad_q))   # dN, mm
    lever = abs(float(s.n_f[0] @ np.cross(solver.kin.gear_axis, s.x_f_mm[0])))
    a = 8.0 * _PAINT_MM / (pattern_length_ratio * pair.gear_face_width_mm) ** 2
    k = 8.0 * lever * math.radians(te0_pp_arcsec / 3600.0) / spacing ** 2
    # no (u, v) twist: n[:, 0]^T H n[:, 1] = 0 with c = k + b^2 / a, a quadratic in b
    (pt, pn), (rt, rn) = n[:, 0], n[:, 1]
    roots = np.roots([pn * rn / a, pt * rn + pn * rt, a * pt * rt + k * pn * rn])
    real = roots[np.isreal(roots)].real
    if not real.size:   # no bias leaves no twist: the least twist
        real = np.array([-(pt * rn + pn * rt) / (2.0 * pn * rn / a)])
    scale = np.diag(half)

    def hessian(b):
        return n.T @ np.array([[a, b], [b, k + b * b / a]]) @ n

    # of the two, the bearing with the least relief at the box's corners (the other
    # exceeds the relief limit many times: F.3 208 um lengthwise against 15 um)
    return min((hessian(b) for b in real), key=lambda h: np.trace(scale @ h @ scale))
