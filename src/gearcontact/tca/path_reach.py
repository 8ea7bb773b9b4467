"""Path angles the local synthesis can reach: a closed-form range, checked before any TCA.

The ease-off synthesis (:mod:`.synthesis`) prescribes at the bearing centre the paint
ellipse length ``2a``, the TE0 level and, optionally, the direction of the contact path.
Its unknowns are the second-order terms of the ease-off (profile and lengthwise
crowning, bias). To first order they fix all three targets (Litvin & Fuentes 2004,
sec. 21.8, local synthesis; the same relations here in the ease-off's own terms):

* the conjugate flanks touch along lines; at phase ``phi1`` the line through ``n nu``
  (``t`` its direction, ``nu`` the unit normal to it in the tangent plane, ``n`` moving at
  ``dn/dphi1 = 1 / (ratio |grad phi2|)``, ``phi2(u, v)`` the conjugate phase of a pinion
  point) carries the ease-off ``E = q^T H q / 2`` as its separation, and the eased
  contact is where ``E`` is least on it: ``t^T H q = 0``, the on-flank path, whose
  direction ``d`` is normal to ``H t``;
* with ``H = [[a, b], [b, c]]`` in ``(t, nu)``: the paint ellipse at the paint thickness
  ``delta`` has ``a = 8 delta / (2a)^2`` (the curvature along the contact line, the
  conjugate pair's being zero); the least ``E`` on the line at ``n`` is
  ``n^2 det(H) / (2 a)``, so that TE0 peak-to-peak over one pinion pitch (pairs one
  pitch ``Delta N`` apart, the gear lever ``h2``) is ``det(H) / a * Delta N^2 / (8 h2)``;
* the bias ``b`` is then free and turns the path: ``b = -a tan(psi)``, ``psi`` the path's
  angle from ``nu`` towards ``t``, and ``c = (det(H) + b^2) / a``.

The path angle the synthesis judges (:attr:`~.design_point.DesignPoint.path_angle_deg`)
is that of the contact path on the gear flank (Litvin's local synthesis prescribes the
path on the gear tooth surface), projected on the tangent plane: the on-flank motion
``d dn/dphi1 / cos(psi)`` over the pinion plus the relative rotation of the point (the
pinion's minus the gear's). As ``psi`` runs over (-90, 90) deg it turns once round all
directions; near the ends (a path along the contact line) the crownings and the bias
grow without bound. A ``psi`` is reachable when both crownings are positive and the
ease-off (centred at the target bearing centre, zero at the mean node as
:func:`~.design_point.centred_coefficients` writes it) stays within half the pair's
relief limit over the flank (:attr:`~gearcontact.geometry.flank.FlankSet.easeoff_limit_um`,
which the eased flanks enforce). Half, not all: towards the contact line's direction one
crowning falls towards zero (F3 drive, 0.2 deg inside the edge at 0.8 of the limit: a
profile crowning of 0.065 um/mm^2, a tenth of the free-bias design's), the bearing
spreads to the flank's edges and the search no longer converges (not met after 10 min);
at half the limit the synthesis meets the angles at both edges (tests/tca/
test_path_reach.py). The bearing may reach an edge over the pitch: the synthesis' full
TCA has edge contact (the s0003 tip-edge preset's own path angle is met).

The reachable path angles are the image of that ``psi`` interval: one arc of directions,
:class:`PathAngleRange`. Measured (docs/synthesis.md): over the reachable designs of
s0003 and the F.3 example the closed form gives the TCA's path angle on the gear flank
to 0.4 deg; on F.3 drive the synthesis (TCA in the loop) from the closed-form start meets
0, 30 and 60 deg with crownings and bias within 1-5 % of the closed form's.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 21.8.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..geometry.formate import SIDES
from ..validation import InputRangeError
from .curvature import PAINT_THICKNESS_MM, flank_frame
from .synthesis_targets import PATTERN_RATIO_RANGE, TE0_RANGE_ARCSEC

__all__ = ["PathAngleRange", "path_angle_range", "check_path_angle", "check_targets",
           "overlap_path_angle", "overlap_choice", "short_overlap", "te0_unreachable",
           "OVERLAP_MARGIN"]

_ARCSEC = np.pi / (180.0 * 3600.0)
#: Finite-difference step of the exact node solves, mm (the node equations are solved
#: to ~1e-12: the derivatives are good to ~1e-8 relative).
_STEP_MM = 0.02
#: Grid of the on-flank path angle psi, deg: 0.05 deg steps over (-90, 90).
_PSI_DEG = np.linspace(-89.95, 89.95, 3599)
#: Share of the relief limit the first-order design may use (module docstring: the
#: synthesis must meet the angles at the range's edges, tests/tca/test_path_reach.py).
_ROOM = 0.5


@dataclass(frozen=True)
class PathAngleRange:
    """Path angles the synthesis can reach on one side (:func:`path_angle_range`).

    Attributes
    ----------
    side : str
    lo_deg, hi_deg : float
        The reachable arc of directions, from ``lo_deg`` turning positive to ``hi_deg``
        (``lo_deg`` in (-90, 90], ``lo_deg <= hi_deg < lo_deg + 180``): a path angle is
        reachable if it equals some angle of ``[lo_deg, hi_deg]`` modulo 180 deg.
    contact_line_deg : float
        Meshing-frame direction of the contact line at the bearing centre (the direction
        no ease-off reaches), deg in (-90, 90].
    free_bias_deg : float
        The path angle with zero bias (first order), deg in (-90, 90].
    angles_deg, coefficients : ndarray
        Over the reachable arc: the path angle (unwrapped, increasing) and the
        first-order profile crowning, lengthwise crowning and bias (um/mm^2, (n, 3)) that
        give it (:meth:`start`).
    pitch_uv_mm : ndarray (n, 2)
        Over the reachable arc: the first-order motion ``(du, dv)`` of the contact point
        on the pinion flank over one pinion pitch (the contact-line spacing over
        ``cos(psi)`` along the path), mm.
    centre_uv_mm : (float, float)
        The bearing centre (pinion u, v), mm.
    """

    side: str
    lo_deg: float
    hi_deg: float
    contact_line_deg: float
    free_bias_deg: float
    angles_deg: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    coefficients: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)), repr=False)
    pitch_uv_mm: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)), repr=False)
    centre_uv_mm: tuple = (float("nan"), float("nan"))

    def start(self, angle_deg: float) -> tuple[float, float, float]:
        """First-order (profile crowning, lengthwise crowning, bias), um/mm^2, of the
        reachable path angle nearest ``angle_deg``: the synthesis' start for it (the
        least squares cannot cross the contact line's direction from the zero-bias
        start: its angle residual takes the short way round)."""
        k = int(np.argmin(np.abs(_fold(self.angles_deg - angle_deg))))
        return tuple(float(x) for x in self.coefficients[k])

    def contains(self, angle_deg: float) -> bool:
        """``angle_deg`` (an axis direction, deg) is in the reachable arc."""
        return bool((float(angle_deg) - self.lo_deg) % 180.0 <= self.hi_deg - self.lo_deg)

    def describe(self) -> str:
        """The arc as intervals of (-90, 90] deg."""
        lo, hi = self.lo_deg, self.hi_deg
        if not np.isfinite(lo):
            return "none (no path angle is reachable)"
        if hi <= 90.0:
            return f"[{lo:.1f}, {hi:.1f}] deg"
        return f"[{lo:.1f}, 90] or (-90, {hi - 180.0:.1f}] deg"


def _fold(angle_deg):
    """Axis directions in (-90, 90] deg."""
    a = (np.asarray(angle_deg, float) + 90.0) % 180.0 - 90.0
    return np.where(a == -90.0, 90.0, a)


def path_angle_range(pair, *, side: str, targets, flanks, room: float = _ROOM
                     ) -> PathAngleRange:
    """The path angles the ease-off synthesis of ``side`` can reach (module docstring).

    Parameters
    ----------
    pair : GearPair
        The pair (its ease-off is not used).
    side : str
    targets : SynthesisTargets
        Bearing centre, TE0 level and paint-ellipse length (the path angle is not used).
    flanks : FlankSet
        ``build_flanks(pair)``: the conjugate pinion's exact node solves and the gear
        flank (no TCA).
    room : float
        Share of the relief limit a reachable design may use (default ``_ROOM``, module
        docstring).

    Returns
    -------
    PathAngleRange

    Raises
    ------
    InputRangeError
        Bad side.
    """
    if side not in SIDES:
        raise InputRangeError("side", side, f"one of {SIDES}")
    conj, gear = flanks.pinion_conjugate.side(side), flanks.flank("gear", side)
    kin = pair.kinematics(with_errors=False)
    bx = conj.boundary
    uc = bx.u_root + targets.centre_profile * (bx.u_tip - bx.u_root)
    vc = bx.v_toe + targets.centre_face * (bx.v_heel - bx.v_toe)
    h = _STEP_MM
    us = np.array([uc, uc + h, uc - h, uc, uc])
    vs = np.array([vc, vc, vc, vc + h, vc - h])
    ms = conj.exact(us, vs)
    phi2 = float(ms.phi2_rad[0])
    phi1 = pair.ratio * phi2
    rot1, tr1 = kin.pinion_pose(phi1)
    rot2 = kin.gear_pose(phi2)[0]
    x1 = np.asarray(ms.x1_mm)
    r_u = rot1 @ (x1[1] - x1[2]) / (2.0 * h)
    r_v = rot1 @ (x1[3] - x1[4]) / (2.0 * h)
    grad_uv = np.array([ms.phi2_rad[1] - ms.phi2_rad[2], ms.phi2_rad[3] - ms.phi2_rad[4]]) \
        / (2.0 * h)
    u2, v2 = gear.surface_parameters(ms.h_mm[0], ms.theta_rad[0])
    frame = flank_frame(gear.point(float(u2), float(v2)), rot2)
    basis, normal = frame[:, :2], frame[:, 2]
    handed = float(np.sign(np.cross(frame[:, 0], frame[:, 1]) @ normal))
    handed *= -1.0 if pair.pinion_hand == "left" else 1.0
    m = basis.T @ np.column_stack([r_u, r_v])              # q = m (du, dv), mm
    grad_q = np.linalg.solve(m.T, grad_uv)                  # grad phi2 in q, rad/mm
    nu = grad_q / np.linalg.norm(grad_q)
    t = np.array([-nu[1], nu[0]])
    dn_dphi1 = 1.0 / (pair.ratio * np.linalg.norm(grad_q))  # mm/rad
    point = rot1 @ x1[0] + tr1
    # the on-flank path of the gear (the design point's path angle): the pinion-flank
    # motion plus the relative rotation of the point (pinion's minus gear's), mm/rad
    x2 = rot2.T @ (point - kin.gear_pose(phi2)[1])          # gear body frame, mm
    spin = basis.T @ ((kin.pinion_pose(phi1 + 1e-6)[0] - kin.pinion_pose(phi1 - 1e-6)[0])
                      @ x1[0] - (kin.gear_pose(phi2 + 1e-6 / pair.ratio)[0]
                                 - kin.gear_pose(phi2 - 1e-6 / pair.ratio)[0]) @ x2) / 2e-6
    lever = abs(normal @ np.cross(kin.gear_axis, point))    # gear lever h2, mm
    dN = 2.0 * np.pi / pair.pinion_teeth * dn_dphi1         # contact-line spacing, mm
    a = 8.0 * PAINT_THICKNESS_MM / (targets.pattern_length_ratio * pair.gear_face_width_mm) ** 2
    det_over_a = 8.0 * lever * targets.te0_pp_arcsec * _ARCSEC / dN ** 2
    psi = np.radians(_PSI_DEG)
    b = -a * np.tan(psi)
    c = det_over_a + b * b / a
    rot = np.column_stack([t, nu])
    # H in (u, v) per psi, um/mm^2: m^T R [[a, b], [b, c]] R^T m
    h_tn = np.stack([np.stack([np.full_like(b, a), b], -1), np.stack([b, c], -1)], -2)
    h_uv = 1e3 * np.einsum("ji,jk,nkl,ml,mo->nio", m, rot, h_tn, rot, m)
    pc, lc, tw = 0.5 * h_uv[:, 0, 0], 0.5 * h_uv[:, 1, 1], h_uv[:, 0, 1]
    # relief of the centred ease-off, E = Q(x - centre) - Q(mean - centre) (the mean node
    # carries E = 0, .design_point.centred_coefficients): H is positive definite, so |E|
    # is largest at a corner of the flank box or, as -E, at the centre
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]

    def quad(du, dv):
        return pc * du * du + lc * dv * dv + tw * du * dv

    at_mean = quad(u_m - uc, v_m - vc)
    relief = np.max([np.abs(quad(u - uc, v - vc) - at_mean)
                     for u in (bx.u_root, bx.u_tip) for v in (bx.v_toe, bx.v_heel)], axis=0)
    relief_ok = np.maximum(relief, at_mean) <= room * flanks.easeoff_limit_um
    d = np.outer(np.cos(psi), nu) + np.outer(np.sin(psi), t)
    on_flank = d * (dn_dphi1 / np.cos(psi))[:, None]        # mm/rad, tangent plane
    motion = on_flank + spin
    theta = np.unwrap(np.radians(handed * np.degrees(np.arctan2(motion[:, 1], motion[:, 0]))),
                      period=np.pi)
    theta = np.degrees(theta)
    ok = relief_ok & (pc > 0.0) & (lc > 0.0)
    line_deg = float(_fold(handed * np.degrees(np.arctan2(t[1], t[0]))))
    free = float(_fold(theta[int(np.argmin(np.where(ok, np.abs(tw), np.inf)))])) \
        if ok.any() else float("nan")
    if not ok.any():
        return PathAngleRange(side, float("nan"), float("nan"), line_deg, free)
    # the longest run of reachable psi (one interval in practice)
    runs, start = [], None
    for i, flag in enumerate(np.append(ok, False)):
        if flag and start is None:
            start = i
        elif not flag and start is not None:
            runs.append((start, i - 1))
            start = None
    i0, i1 = max(runs, key=lambda r: r[1] - r[0])
    sel = slice(i0, i1 + 1)
    # (du, dv) over one pitch: dN / cos(psi) along d in the tangent plane, mapped by m^-1
    pitch_uv = np.linalg.solve(m, (d * (dN / np.cos(psi))[:, None]).T).T
    angles, coeffs, pitch_uv = theta[sel], np.column_stack([pc, lc, tw])[sel], pitch_uv[sel]
    if angles[-1] < angles[0]:
        angles, coeffs, pitch_uv = angles[::-1], coeffs[::-1], pitch_uv[::-1]
    shift = float(_fold(angles[0])) - angles[0]
    return PathAngleRange(side, float(angles[0] + shift), float(angles[-1] + shift), line_deg,
                          free, angles + shift, coeffs, pitch_uv, (float(uc), float(vc)))


def check_path_angle(pair, *, targets, flanks, sides=SIDES) -> dict:
    """Refuse a path-angle target that the synthesis cannot reach on one of ``sides``,
    before any TCA (:func:`path_angle_range`); returns the range of each side (empty
    without a path-angle target).

    Raises
    ------
    InputRangeError
        Naming ``path_angle_deg``, its value and the reachable range of the side.
    """
    if targets.path_angle_deg is None:
        return {}
    return check_targets(pair, targets=targets, flanks=flanks, sides=sides)


def check_targets(pair, *, targets, flanks, sides=SIDES) -> dict:
    """Refuse targets the ease-off synthesis cannot reach on one of ``sides``, before any
    TCA; returns the :func:`path_angle_range` of each side.

    First the TE0 level and the pattern length: where no path angle at all is
    reachable at them, the first-order design of every one exceeding the whole relief
    limit the eased flanks enforce or losing a crowning (a high TE0 or a short pattern
    crowns hard; the whole limit, not the half a path-angle target is held to: the
    free-bias synthesis of s0003 drive meets TE0 30 arcsec at the pattern 0.35, where
    every first-order design needs more than half of it: 20.4 arcsec fills the half), the one to change is named with the reachable
    bound (:func:`_level_error`); then a path-angle target outside the side's range
    (:func:`check_path_angle`).

    Raises
    ------
    InputRangeError
        Naming ``te0_pp_arcsec``, ``pattern_length_ratio`` or ``path_angle_deg``, its
        value and what the side reaches.
    """
    out = {}
    for side in sides:
        if not _reaches(pair, side, targets, flanks):
            raise _level_error(pair, side=side, targets=targets, flanks=flanks)
        r = out[side] = path_angle_range(pair, side=side, targets=targets, flanks=flanks)
        if targets.path_angle_deg is not None and not r.contains(targets.path_angle_deg):
            raise InputRangeError(
                "path_angle_deg", targets.path_angle_deg,
                f"{r.describe()} on the {side} side of {pair.name} (the path angles the "
                f"ease-off synthesis reaches within the relief limit; the "
                f"contact line runs at {r.contact_line_deg:.1f} deg, docs/synthesis.md)")
    return out


#: Bisection steps of the reachable TE0 level and pattern length (:func:`_level_bounds`;
#: on a log scale over their ranges: a bound to 0.5 % of it or better).
_LEVEL_BISECTIONS = 10


def _reaches(pair, side, targets, flanks, **change) -> bool:
    """Some path angle's first-order design at ``targets`` with the fields ``change``
    keeps both crownings and stays within the whole relief limit (:func:`check_targets`)."""
    t = dataclasses.replace(targets, path_angle_deg=None, **change)
    return bool(len(path_angle_range(pair, side=side, targets=t, flanks=flanks,
                                     room=1.0).angles_deg))


def _bisect(reaches, good: float, bad: float) -> float:
    """The reachable end of ``[good, bad]`` (``reaches(good)``, not ``reaches(bad)``)
    nearest the unreachable one, on a log scale."""
    for _ in range(_LEVEL_BISECTIONS):
        mid = float(np.sqrt(good * bad))
        good, bad = (mid, bad) if reaches(mid) else (good, mid)
    return good


def _inside_3g(x: float, *, up: bool) -> float:
    """``x`` to three significant digits, rounded into the reachable side (down for an
    upper bound, ``up`` for a lower one), so that the bound printed is reachable."""
    e = 10.0 ** (math.floor(math.log10(x)) - 2)
    return float((math.ceil(x / e) if up else math.floor(x / e)) * e)


def _level_error(pair, *, side: str, targets, flanks) -> InputRangeError:
    """The refusal of a TE0 level and pattern length at which no path angle is
    reachable: the TE0 bound at the pattern length (TE0 sets the crowning across the
    contact lines, so relief grows with it), else the pattern-length bound at the TE0
    level (a longer pattern crowns less along the lines)."""
    lo_te0, hi_ratio = TE0_RANGE_ARCSEC[0], PATTERN_RATIO_RANGE[1]
    te0, ratio = targets.te0_pp_arcsec, targets.pattern_length_ratio
    where = (f"on the {side} side of {pair.name} (the first-order ease-off of every path "
             "angle exceeds the relief limit or loses a crowning, docs/synthesis.md)")
    if te0 > lo_te0 and _reaches(pair, side, targets, flanks, te0_pp_arcsec=lo_te0):
        bound = _bisect(lambda x: _reaches(pair, side, targets, flanks, te0_pp_arcsec=x),
                        lo_te0, te0)
        most = _inside_3g(bound, up=False)
        return InputRangeError("te0_pp_arcsec", te0, f"<= {most:.3g} arcsec with the "
                               f"pattern length ratio {ratio:g} {where}")
    if ratio < hi_ratio and _reaches(pair, side, targets, flanks,
                                     pattern_length_ratio=hi_ratio):
        bound = _bisect(lambda x: _reaches(pair, side, targets, flanks,
                                           pattern_length_ratio=x), hi_ratio, ratio)
        least = _inside_3g(bound, up=True)
        return InputRangeError("pattern_length_ratio", ratio,
                               f">= {least:.3g} with TE0 {te0:g} arcsec {where}")
    return InputRangeError("te0_pp_arcsec", te0, f"none with the pattern length ratio "
                           f"{ratio:g} (nor at {lo_te0:g} arcsec with any up to {hi_ratio:g}) "
                           f"{where}")


#: Bisection steps of the flank extent along a path in :func:`overlap_path_angle`
#: (the extent to 2^-16 of the box diagonal, far below the one-step resolution of the TCA).
_EXTENT_BISECTIONS = 16
#: Every how many psi grid points (0.05 deg) :func:`overlap_path_angle` evaluates.
_OVERLAP_STRIDE = 20


def overlap_path_angle(reach: PathAngleRange, *, flanks, side: str) -> tuple[float, float]:
    """The reachable path angle whose first-order path gives the longest surface
    contact per pinion pitch, and that length in pitches (NaN, NaN when no angle is
    reachable).

    The surface contact of one pair lasts while its contact point is on both flanks:
    along a straight path through the bearing centre (``reach.pitch_uv_mm`` per pitch)
    its span is the path's extent inside the pinion's active box whose conjugate gear
    point lies on the gear flank (exact node solves, bisection), over the motion per
    pitch. Below one pitch the contact passes between pairs through an edge contact
    (:func:`te0_unreachable`)."""
    if not len(reach.angles_deg):
        return float("nan"), float("nan")
    conj, gear = flanks.pinion_conjugate.side(side), flanks.flank("gear", side)
    box, gear_box = conj.boundary, gear.boundary
    pick = np.arange(0, len(reach.angles_deg), _OVERLAP_STRIDE)
    step = reach.pitch_uv_mm[pick]
    per_pitch = np.linalg.norm(step, axis=1)
    uc, vc = reach.centre_uv_mm
    extent = np.zeros(len(pick))
    for sign in (1.0, -1.0):
        d = sign * step / per_pitch[:, None]                 # unit (u, v) direction
        with np.errstate(divide="ignore"):
            to_box = np.min([np.where(d[:, 0] > 0, (box.u_tip - uc) / d[:, 0], np.inf),
                             np.where(d[:, 0] < 0, (box.u_root - uc) / d[:, 0], np.inf),
                             np.where(d[:, 1] > 0, (box.v_heel - vc) / d[:, 1], np.inf),
                             np.where(d[:, 1] < 0, (box.v_toe - vc) / d[:, 1], np.inf)],
                            axis=0)
        lo, hi = np.zeros(len(pick)), to_box
        on = _on_gear(conj, gear_box, gear, uc + hi * d[:, 0], vc + hi * d[:, 1])
        lo = np.where(on, hi, lo)
        for _ in range(_EXTENT_BISECTIONS):
            mid = 0.5 * (lo + hi)
            ok = _on_gear(conj, gear_box, gear, uc + mid * d[:, 0], vc + mid * d[:, 1])
            lo, hi = np.where(ok, mid, lo), np.where(ok, hi, mid)
        extent += lo
    ratio = extent / per_pitch
    k = int(np.argmax(ratio))
    return float(_fold(reach.angles_deg[pick[k]])), float(ratio[k])


def overlap_choice(pair, *, side: str, targets, flanks) -> tuple[float, float, bool]:
    """The path angle the synthesis turns a short zero-bias path to: the reachable one of
    the longest overlap (:func:`overlap_path_angle`, folded into the targets' range
    (-89.9, 90] deg), its surface contact in pitches, and whether that overlaps (at
    least ``1 + OVERLAP_MARGIN``; else TE0 is unreachable, :func:`te0_unreachable`)."""
    reach = path_angle_range(pair, side=side, targets=targets, flanks=flanks)
    angle, ratio = overlap_path_angle(reach, flanks=flanks, side=side)
    return float(np.clip(angle, -89.9, 90.0)), ratio, bool(ratio >= 1.0 + OVERLAP_MARGIN)


def _on_gear(conj, gear_box, gear, u, v) -> np.ndarray:
    """Whether the gear point conjugate to each pinion point (u, v) is on the gear flank."""
    ms = conj.exact(np.asarray(u, float), np.asarray(v, float))
    return np.asarray(gear_box.contains(*gear.surface_parameters(ms.h_mm, ms.theta_rad)),
                      bool)


#: Margin of a surface contact ratio above 1 (in pitches) within which it does not
#: count as an overlap: one phase step of the synthesis' TCA (31 phases) for the TCA's
#: count, and for the closed form (:func:`overlap_path_angle`, 1.71
#: against the TCA's 1.73 on the 20/20 miter) as well.
OVERLAP_MARGIN = 1.0 / 30.0


def short_overlap(point, phases: int) -> float | None:
    """The surface contact ratio of ``point`` if it is short of a pitch even counted
    generously (one phase step added), else None (None also without a point)."""
    if point is None or not np.isfinite(point.surface_contact_ratio):
        return None
    ratio = point.surface_contact_ratio
    return ratio if ratio + 1.0 / (int(phases) - 1) < 1.0 else None


def te0_unreachable(ratio: float, te0_pp_arcsec: float, *, side: str,
                    best: tuple[float, float]) -> str:
    """Why the TE0 target cannot be set by the ease-off on ``side``: the zero-bias
    path's surface contact lasts ``ratio`` pitches and the best reachable path angle
    ``best = (angle, ratio)`` (:func:`overlap_path_angle`) gives no
    overlap either.

    TE0 is a crowning's level only where neighbouring pairs' parabolic TE curves cross
    on the flanks, i.e. where one pair's surface contact lasts at least a pinion pitch
    (:attr:`~.design_point.DesignPoint.surface_contact_ratio`). Where it lasts less the
    contact passes to the next pair through an edge contact, and TE0 over the pitch is
    that contact's. The synthesis then stops after the decoupled rounds, which still
    meet the bearing centre and the pattern length (docs/synthesis.md)."""
    angle, most = best
    where = (f"; the longest reachable, along {angle:.1f} deg, lasts {most:.2f}"
             if np.isfinite(most) else "; no path angle is reachable")
    return (f"TE0 {te0_pp_arcsec:g} arcsec on the {side} side: one pair's surface "
            f"contact lasts {ratio:.2f} of a pinion pitch along the path of the bearing"
            f"{where} (< 1: the contact passes to the next pair through an edge contact, "
            "whose TE the ease-off does not set; a wider face or more teeth give more "
            "overlap, docs/synthesis.md)")
