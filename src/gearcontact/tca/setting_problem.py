"""The fixed part of the local synthesis of the pinion settings
(:mod:`.setting_synthesis`): the base pinion, the mean point M and its generation, the
three corrections pivoting on it, and Litvin's quantities at M by a local TCA.

The base pinion is the one conjugate to the pair's gear
(:func:`~gearcontact.geometry.basic_settings.member_setups`). For a hypoid whose gear is
generated it is the crown gear's pinion, point contact with TE0 = 0 along a path, and M
the point of that path on the pinion's mean section (or on another section,
``SynthesisProblem(pivot_uv=...)``). For a formate gear (hypoid or
spiral bevel: the complementary pinion) and a generated spiral bevel gear (the crown
gear's pinion) it is line-contact conjugate: every flank point lies on a contact line,
and M is the blank's mean point on the pinion (the point the standard crowning keeps).
Each correction (:func:`corrected_setup`: roll curvature about M's roll
:func:`roll_about`, blade curvature, cutter radius) keeps M, its normal and the nominal
ratio there.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 20-21.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..geometry.basic_settings import (STANDARD_CROWNING, crown_profile, crowning_corrections,
                                       member_setups, mismatch_radius)
from ..geometry.flank import build_machine_flanks
from ..geometry.formate import SIDES
from ..geometry.generated import EnvelopeSolver, generated_pinion_flank, mean_contact_guess
from ..geometry.machine import MachineSetup
from ..geometry.typed_pinion import typed_gear_pinion_setups
from ..validation import InputRangeError, check_range
from .analysis import pattern_on_flank
from .curvature import contact_ellipse, relative_curvature
from .design_point import DesignPoint, design_point_at
from .mating import solve_mating_point
from .solve import solve_tca
from .stencil import gap_at
from .types import ContactGuess, EdgeContact

__all__ = ["MeanPointContact", "PatternRun", "SynthesisProblem", "corrected_setup",
           "line_room_mm", "local_slope", "local_tca", "mean_point_contact", "path_points_inside",
           "pattern_run", "roll_about"]

_REPORT_TORQUE_NM = 64.5


def roll_about(settings, *, psi_m: float, roll_curvature: float):
    """``settings`` with cradle angle, ratio of roll and 2C such that the work roll as a
    function of the cradle's position keeps its value and slope at the roll ``psi_m`` of
    ``settings`` and gets the second derivative ``-R_a0 roll_curvature`` there (``R_a0``:
    the linear roll of ``settings``, which must have no modified roll).

    The cradle angle changed by ``d`` with the swivel kept is the cradle rolled by ``d``
    (the cutter turns rigidly about the cradle axis), so the new roll, in the base's
    cradle position ``psi``, is ``W(psi) = R_a (s - C s^2/2)``, ``s = psi - d``. The three
    conditions at ``psi_m`` give ``R_a C = R_a0 c``, ``R_a = R_a0 (1 + c s_m)`` and
    ``s_m + c s_m^2/2 = psi_m`` (``c = roll_curvature``, ``s_m = psi_m - d``): closed form,
    ``d = O(c psi_m^2)``. A 2C about ``psi = 0`` alone would move the mean node (its roll
    ``psi_m`` is not 0); a cubic about 0 keeping it needs a 6D of order ``3 c / psi_m``."""
    if any(settings.modified_roll) or any(settings.helical_motion):
        raise InputRangeError("modified_roll", settings.modified_roll,
                              "a linear roll (no modified roll, no helical motion) as base")
    r0, p, c = settings.ratio_of_roll, float(psi_m), float(roll_curvature)
    if 1.0 + 2.0 * c * p <= 0.0:
        raise InputRangeError("roll_curvature", c, f"1 + 2 c psi_m > 0 (psi_m = {p:.6g} rad)")
    s_m = 2.0 * p / (1.0 + math.sqrt(1.0 + 2.0 * c * p))     # root of s + c s^2/2 = psi_m
    r_a = r0 * (1.0 + c * s_m)
    q = settings.cradle_angle_deg + math.degrees(p - s_m)
    q = (q + 180.0) % 360.0 - 180.0 if (q + 180.0) % 360.0 != 0.0 else 180.0
    return dataclasses.replace(settings, cradle_angle_deg=q, ratio_of_roll=float(r_a),
                               modified_roll=(float(r0 * c / r_a),) if c else ())


def _generation_at(setup: MachineSetup, blank, cone, uv) -> tuple[float, float, float]:
    """(l, theta, psi) of the blade point and roll that generate the pinion node ``uv``."""
    solver = EnvelopeSolver(setup, blank, cone)
    m = solver.solve(uv[0], uv[1], solver.initial_guess(*uv))
    return float(m.l_mm), float(m.theta_rad), float(m.psi_rad)


def corrected_setup(base: MachineSetup, x, *, mean) -> MachineSetup:
    """The pinion ``base`` (straight blade, linear roll) with the corrections ``x``
    (:data:`~.setting_synthesis.PARAMETER_NAMES`), all pivoting on the generation ``mean = (l, theta, psi)``
    of the mean point (:class:`SynthesisProblem`)."""
    l_m, th_m, psi_m = mean
    c_roll, k_blade, delta = (float(v) for v in x)
    setup = mismatch_radius(base, delta_mm=delta, theta_rad=th_m) if delta else base
    if k_blade:
        setup = dataclasses.replace(setup, blade=crown_profile(
            setup.blade, radius_mm=1.0 / k_blade, at_length_mm=l_m))
    return dataclasses.replace(setup, settings=roll_about(setup.settings, psi_m=psi_m,
                                                          roll_curvature=c_roll))


#: Phase step of the local TCA at M, in pinion pitches (five phases, -2..2 steps: the TE
#: curvature by the five-point difference, the path tangent by the central one).
_LOCAL_STEP_PITCH = 1.0 / 30.0
_ARCSEC = math.pi / (180.0 * 3600.0)


@dataclass(frozen=True)
class MeanPointContact:
    """Litvin's quantities at the mean point M (:func:`mean_point_contact`).

    Attributes
    ----------
    point : DesignPoint
        At M: paint and Hertz ellipses and the path angle on the gear flank; its
        ``te0_pp_arcsec`` is the parabolic level ``te_level_arcsec``.
    te_curvature_arcsec_per_rad2 : float
        ``d^2 TE0 / d phi1^2`` at M (TE0 in arcsec of gear rotation, phi1 in rad).
    te_slope_arcsec_per_rad : float
        ``d TE0 / d phi1`` at M (0 for tangency with the nominal ratio at M).
    te_level_arcsec : float
        Peak-to-peak over one pinion pitch of the parabola of that curvature,
        ``|TE''| (pi / z1)^2 / 2`` (pairs changing at half a pitch either side of M).
    """

    point: DesignPoint
    te_curvature_arcsec_per_rad2: float
    te_slope_arcsec_per_rad: float
    te_level_arcsec: float


def local_tca(pinion, gear, pair, start: ContactGuess):
    """``(kinematics, h, path)``: the TCA over five phases about ``start`` (-2..2 steps
    of ``h``, :data:`_LOCAL_STEP_PITCH` of a pinion pitch, rad), edges off."""
    kin = pair.kinematics()
    h = 2.0 * math.pi / pair.pinion_teeth * _LOCAL_STEP_PITCH
    path = solve_tca(pinion, gear, kin, start.phi1_rad + h * np.arange(-2, 3), start=start,
                     start_fixed="phi1", edges=False)
    return kin, h, path


def local_slope(values, h: float) -> float:
    """The five-point central difference at the middle of :func:`local_tca`'s five
    phases (``values`` at -2..2 steps of ``h``): ``d value / d phi1``, per rad."""
    y = values
    return float((y[0] - 8.0 * y[1] + 8.0 * y[3] - y[4]) / (12.0 * h))


def mean_point_contact(pinion, gear, pair, start: ContactGuess, *,
                       torque_nm: float = _REPORT_TORQUE_NM) -> MeanPointContact:
    """Contact of ``pinion`` and ``gear`` at the mean point: a local TCA over five phases
    (``start``, the exact contact at M, and two steps of :data:`_LOCAL_STEP_PITCH` either
    side), from which the TE curvature, the parabolic TE level and the path direction at M
    follow (Litvin & Fuentes 2004, sec. 21.8: the second-order conditions of local
    synthesis are posed at M, not at the TE vertex of a whole pitch)."""
    kin, h, path = local_tca(pinion, gear, pair, start)
    te = np.asarray(path.te0_arcsec, dtype=float)
    if not np.all(np.isfinite(te)):
        raise ArithmeticError("the contact leaves a flank within two local steps of M")
    curv = float((-te[0] + 16.0 * te[1] - 30.0 * te[2] + 16.0 * te[3] - te[4]) / (12.0 * h * h))
    slope = local_slope(te, h)
    level = 0.5 * abs(curv) * (math.pi / pair.pinion_teeth) ** 2
    a, mp, b = path.points[1], path.points[2], path.points[3]
    tangent = kin.gear_pose(mp.phi2_rad)[0] @ (gear.point(b.u2, b.v2).r
                                               - gear.point(a.u2, a.v2).r)
    dp = design_point_at(pair, pinion, gear, mp, te0_pp_arcsec=level, torque_nm=torque_nm,
                         path_tangent=tangent)
    return MeanPointContact(dp, curv, slope, level)


def _path_point_at(pinion, gear, pair, guess: ContactGuess, *, v1_mm: float):
    """The mating point of the path through ``guess`` whose pinion ``v1`` is ``v1_mm``
    within 1e-6 mm: secant on the phase, started from a local TCA over +-2 steps of
    :data:`_LOCAL_STEP_PITCH` (the system with ``v1`` held is singular where TE0 is
    constant along the path, as on the crown gear's pinion)."""
    kin, _, path = local_tca(pinion, gear, pair, guess)
    k = int(np.argmin([abs(p.v1 - v1_mm) for p in path.points]))
    prev, mp = path.points[k - 1 if k else 1], path.points[k]
    for _ in range(20):
        if abs(mp.v1 - v1_mm) < 1e-6:
            return mp
        slope = (mp.v1 - prev.v1) / (mp.phi1_rad - prev.phi1_rad)
        prev, mp = mp, solve_mating_point(pinion, gear, kin, dataclasses.replace(
            mp.as_guess(), phi1_rad=mp.phi1_rad - (mp.v1 - v1_mm) / slope))
    raise ArithmeticError(f"no point of the contact path at v1 = {v1_mm:.4f} mm (secant "
                          f"stopped at {mp.v1:.4f} mm)")


#: Margin of a pivot off the mean section (:func:`_path_point_inside`): inside the pinion
#: flank box by this fraction of its working depth (root, tip) and of its face (toe,
#: heel), so that the paint ellipse of M has room on the flank.
PIVOT_MARGIN = 0.1
#: Phase range searched for the base's contact path on the flank, pinion pitches either
#: side of the mean node's phase (in steps of :data:`_LOCAL_STEP_PITCH`).
_PATH_SEARCH_PITCHES = 2


def path_points_inside(pinion, gear, pair, guess: ContactGuess, *,
                       margin: float = PIVOT_MARGIN) -> list:
    """The sampled points of the contact path through ``guess``'s phase region that lie
    inside the pinion flank box by ``margin`` of its depth and face ([] if none): the
    first phase within :data:`_PATH_SEARCH_PITCHES` of ``guess`` (steps of
    :data:`_LOCAL_STEP_PITCH`, the nearer first) whose mating point is on the flank
    starts a TCA (surface contact, edges off) over as many pitches either side, sampled
    at the same step."""
    kin = pair.kinematics()
    h = 2.0 * math.pi / pair.pinion_teeth * _LOCAL_STEP_PITCH
    steps = int(round(_PATH_SEARCH_PITCHES / _LOCAL_STEP_PITCH))
    for k in sorted(range(-steps, steps + 1), key=lambda j: (abs(j), j)):
        try:
            mp = solve_mating_point(pinion, gear, kin, dataclasses.replace(
                guess, phi1_rad=guess.phi1_rad + k * h))
            break
        except (EdgeContact, ArithmeticError):
            continue
    else:
        return []
    path = solve_tca(pinion, gear, kin, mp.phi1_rad + h * np.arange(-steps, steps + 1),
                     start=mp.as_guess(), start_fixed="phi1", edges=False)
    (u0, u1), (v0, v1) = pinion.u_range, pinion.v_range
    du, dv = margin * (u1 - u0), margin * (v1 - v0)
    return [p for p in path.points if not p.edge and u0 + du <= p.u1 <= u1 - du
            and v0 + dv <= p.v1 <= v1 - dv]


def _path_point_inside(pinion, gear, pair, guess: ContactGuess, *, v1_mm: float,
                       margin: float = PIVOT_MARGIN):
    """The point of the contact path through ``guess``'s phase region nearest the
    section ``v1_mm`` among those inside the pinion flank box by ``margin`` of its depth
    and face (:func:`path_points_inside`), or None."""
    inside = path_points_inside(pinion, gear, pair, guess, margin=margin)
    return min(inside, key=lambda p: abs(p.v1 - v1_mm)) if inside else None


def _path_point_on_section(pinion, gear, pair, guess: ContactGuess, *, uv,
                           margin: float = PIVOT_MARGIN):
    """The point of the contact path through ``guess`` (a point-contact base's M) on the
    pinion section ``v`` of ``uv`` (mm; ``u`` is not read: the path fixes it), where it
    lies inside the pinion flank box by ``margin`` of its depth and face
    (:func:`_path_point_at`); otherwise the reason, in words (that pivot is no flank
    point of the path)."""
    (u0, u1), (v0, v1) = pinion.u_range, pinion.v_range
    du, dv = margin * (u1 - u0), margin * (v1 - v0)
    v_c = float(uv[1])
    if not v0 + dv <= v_c <= v1 - dv:
        return (f"the pinion section v = {v_c:.4f} mm lies outside the flank's face "
                f"({v0:.4f}, {v1:.4f}) mm by {margin:g} of it")
    try:
        mp = _path_point_at(pinion, gear, pair, guess, v1_mm=v_c)
    except (EdgeContact, ArithmeticError) as exc:
        return (f"the base's contact path does not reach the pinion section v = {v_c:.4f} "
                f"mm on the flank ({exc})")
    if mp.edge or not u0 + du <= mp.u1 <= u1 - du:
        return (f"the base's contact path crosses the pinion section v = {v_c:.4f} mm at "
                f"u = {mp.u1:.4f} mm, outside the working depth ({u0:.4f}, {u1:.4f}) mm by "
                f"{margin:g} of it")
    return mp


def _depth_pivot(pinion, gear, pair, mean: ContactGuess, *, fraction: float) -> ContactGuess:
    """The contact of the pinion flank point at ``fraction`` of its working depth (the
    flank box from the active root, 0, to the tip, 1) on the section of ``mean`` (the
    mean node's contact): :func:`_flank_pivot` there."""
    check_range("pivot_depth", fraction, 0.02, 0.98)
    (u_root, u_tip), v_m = pinion.u_range, mean.v1
    return _flank_pivot(pinion, gear, pair, mean,
                        uv=(float(u_root + fraction * (u_tip - u_root)), float(v_m)))


def _flank_pivot(pinion, gear, pair, mean: ContactGuess, *, uv) -> ContactGuess:
    """The contact of the pinion flank point ``uv`` (mm), found from ``mean`` (the mean
    node's contact) by :func:`~gearcontact.geometry.generated.mean_contact_guess` (exact
    for a line-contact pinion: every flank point lies on a contact line); the gear phase
    is the pinion's over the ratio, as
    :func:`~gearcontact.geometry.flank.build_machine_flanks` starts it."""
    (u0, u1), (v0, v1) = pinion.u_range, pinion.v_range
    u_c, v_c = (float(t) for t in uv)
    if not (u0 < u_c < u1 and v0 < v_c < v1):
        raise InputRangeError("pivot_uv", (u_c, v_c), f"inside the pinion flank box u in "
                              f"({u0:.4g}, {u1:.4g}), v in ({v0:.4g}, {v1:.4g}) mm")
    touch = mean_contact_guess(pinion, gear, pair.kinematics(with_errors=False),
                               pinion_uv=(u_c, v_c), gear_uv=(mean.u2, mean.v2))
    return ContactGuess(u_c, v_c, *touch["gear_uv"], touch["phi1_rad"],
                        touch["phi1_rad"] / pair.ratio)


#: Resolution of :func:`line_room_mm`, mm (its bisection's stop).
_ROOM_TOL_MM = 0.01


def line_room_mm(pinion, gear, kin, mp) -> float:
    """The room of the contact line at the interior mating point ``mp``: the largest
    ``t`` (mm, to :data:`_ROOM_TOL_MM`) such that the tangent-plane points ``+-t`` along
    the paint ellipse's major axis (the ``"principal"`` frame of :func:`~.stencil.gap_at`;
    the contact line of a line-contact base) project along the common normal into both flank
    boxes (:func:`~.stencil.gap_at`, as :func:`~.analysis.pattern_on_flank` tests the
    ellipse outline); 0 if ``mp`` itself is on an edge. A coarse scan over the flank's
    diagonal in 64 steps, then bisection on each side."""
    (u0, u1), (v0, v1) = pinion.u_range, pinion.v_range
    reach = float(np.hypot(u1 - u0, v1 - v0))

    def inside(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return gap_at(pinion, gear, kin, mp, t, np.zeros_like(t), frame="principal").on_flank

    room = []
    for sign in (1.0, -1.0):
        steps = sign * reach * np.arange(1, 65) / 64.0
        ok = inside(steps)
        if ok.all():
            room.append(reach)
            continue
        k = int(np.argmin(ok))          # the first sample off a flank
        lo, hi = (0.0 if k == 0 else abs(steps[k - 1])), abs(steps[k])
        while hi - lo > _ROOM_TOL_MM:
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if inside(sign * mid)[0] else (lo, mid)
        room.append(lo)
    return float(min(room))


@dataclass(frozen=True)
class PatternRun:
    """The run of one tooth pair's contact path whose paint ellipse lies on both flanks
    (:func:`pattern_run`).

    Attributes
    ----------
    pitches : float
        Its length in pinion pitches (phase span over the pitch angle ``2 pi / z1``); 0
        where no surface contact of the path has the ellipse on both flanks.
    middle_offset_pitch : float
        Its middle phase minus the reference phase, pinion pitches (NaN for a run of
        length 0).
    middle_uv : (float, float)
        The pinion flank point (u, v) of the path at its middle phase (the path point
        nearest it), mm (NaN for a run of length 0).
    path_pitches : float
        The length, pinion pitches, of the run of surface contacts (on both flanks, the
        ellipse anywhere) that contains it.
    """

    pitches: float
    middle_offset_pitch: float
    middle_uv: tuple
    path_pitches: float = float("nan")


def pattern_run(pinion, gear, kin, path, *, phi1_rad: float, pinion_teeth: int):
    """The run of ``path`` (one tooth pair's :class:`~.types.TcaPath`) around the phase
    ``phi1_rad`` whose points are surface contacts with the paint ellipse on both flanks
    (:func:`~.analysis.pattern_on_flank` on each point): the run containing the such
    point nearest ``phi1_rad`` in phase; where no surface contact has the ellipse on both
    flanks, a run of length 0 (no middle: NaN) in the surface contacts' run through the
    one nearest ``phi1_rad`` (docs/machine_settings.md sec. 5, lever 4 of "The candidate
    choice for a point-contact base"); None if the path has no surface contact."""
    pts = [p for p in path.points if not p.edge and not p.edge_contact]
    if not pts:
        return None
    pts.sort(key=lambda p: p.phi1_rad)
    ells = [contact_ellipse(relative_curvature(pinion, gear, kin, p)) for p in pts]
    ok = pattern_on_flank(pinion, gear, kin, _Points(pts, ells))
    phase = np.array([p.phi1_rad for p in pts])
    step = float(np.median(np.diff(phase))) if len(pts) > 1 else 0.0
    pitch = 2.0 * math.pi / pinion_teeth
    if not ok.any():        # a run of length 0 in the path through the nearest contact
        p_lo, p_hi = _run_through(int(np.argmin(np.abs(phase - phi1_rad))),
                                  np.ones(len(pts), dtype=bool), phase, step)
        return PatternRun(0.0, math.nan, (math.nan, math.nan),
                          float((phase[p_hi] - phase[p_lo]) / pitch))
    k = int(np.argmin(np.where(ok, np.abs(phase - phi1_rad), np.inf)))
    lo, hi = _run_through(k, ok, phase, step)
    p_lo, p_hi = _run_through(k, np.ones(len(pts), dtype=bool), phase, step)
    middle = 0.5 * (phase[lo] + phase[hi])
    m = lo + int(np.argmin(np.abs(phase[lo:hi + 1] - middle)))
    return PatternRun(float((phase[hi] - phase[lo]) / pitch),
                      float((middle - phi1_rad) / pitch), (float(pts[m].u1), float(pts[m].v1)),
                      float((phase[p_hi] - phase[p_lo]) / pitch))


def _run_through(k, good, phase, step):
    """The ends of the run of ``good`` points through ``k``, one phase ``step`` apart."""
    lo = hi = k
    while lo > 0 and good[lo - 1] and phase[lo] - phase[lo - 1] < 1.5 * step:
        lo -= 1
    while hi < len(phase) - 1 and good[hi + 1] and phase[hi + 1] - phase[hi] < 1.5 * step:
        hi += 1
    return lo, hi


@dataclass(frozen=True)
class _Points:
    """Contacts and their ellipses, as :func:`~.analysis.pattern_on_flank` reads a
    cycle."""

    contact: list
    ellipse: list


class SynthesisProblem:
    """The fixed part of the synthesis of one pair: the gear flanks, the base pinion
    (:func:`~gearcontact.geometry.basic_settings.member_setups` of ``gear_generation``:
    the complementary pinion of a formate gear, the crown gear's pinion of a generated
    one), the mean point M of each side, its generation and its exact contact, and the
    pinion's mounting turn, so that :meth:`flank` gives the mounted pinion flank of any
    corrections.

    Point contact (:attr:`point_contact`: a hypoid, offset != 0, whose gear is
    generated): M is the point of the base pinion's contact path on the pinion's mean
    section (``v`` of the blank's mean point, :func:`_path_point_at`): the crown gear's
    pinion of a hypoid has point contact with TE0 = 0 along a path, which passes near,
    not through, the pinion's mean node (13/26 hypoid: 0.68 / 2.30 mm above it, drive /
    coast). Line contact (a formate gear, or a generated gear with offset 0): the base
    pinion touches the gear along a line through every flank point, so M is the
    blank's mean point on the pinion, the node ``(root offset, pitch point x)`` that
    :func:`~gearcontact.geometry.flank.build_machine_flanks` starts the TCA from and
    whose generation the standard crowning keeps in place; its exact contact is that
    flank set's mean contact. The corrections pivot on the generation of M, so the
    corrected pinion keeps M, its normal and the nominal ratio there: tangency at M.

    Where a point-contact base's path does not reach the mean section on the flank (the
    10 x 41 print's gear, drive: it leaves at the root 1.9 mm before it), M is the path's
    point nearest the mean section among those inside the flank box by
    :data:`PIVOT_MARGIN` of its depth and face (:func:`_path_point_inside`); a side
    whose path has no such point has no M (:attr:`off_flank`).

    A typed gear (``gear``: ``{side: MachineSetup}`` of the gear as the user typed it,
    right-hand; ``gear_generation`` is then its own: formate if both sides are) replaces
    the blank's: the base pinion is its uncrowned pinion
    (:func:`~gearcontact.geometry.typed_pinion.typed_gear_pinion_setups`: point contact
    with TE0 = 0 along a path for a generated hypoid gear, M on that path as above; the
    complementary pinion of a formate gear, M the mean node). A typed generated gear
    with offset 0 pivots on the mean node, as the blank's own (line contact only where
    its cradle is the blank's: docs/machine_settings.md sec. 7). The blank's own gear
    typed gives the base of ``gear_generation`` to rounding.

    ``pivot_depth`` (a fraction of the pinion flank's working depth, from its active
    root, 0, to its tip, 1, in [0.02, 0.98], or ``{side: fraction}``) moves the pivot of
    a line-contact base along the mean section to that depth (:func:`_depth_pivot`:
    any flank point of a line-contact pinion lies on a contact line, so the pivot may
    be any; docs/machine_settings.md sec. 5, "The pivot's depth"); None keeps the mean
    node, the standard crowning's pivot. A point-contact base ignores it (its pivot must
    lie on its contact path). ``pivot_uv`` (``{side: (u, v)}``, mm, inside the pinion
    flank box) puts the pivot of a line-contact base at that flank point (before
    ``pivot_depth``; :func:`_flank_pivot`), and that of a point-contact base at its
    contact path's point on the pinion section ``v`` (:func:`_path_point_on_section`:
    inside the flank box by :data:`PIVOT_MARGIN`, else the side is :attr:`off_flank`,
    the reason named). :attr:`pivot` names where M is, per side.

    The mounting turn is the one :func:`~gearcontact.geometry.flank.build_machine_flanks`
    gives the base pinion (the corrections keep M, so the same turn mounts every
    corrected pinion).
    """

    def __init__(self, pair, *, gear_generation: str = "generated", gear: dict | None = None,
                 n_u: int = 40, n_v: int = 50, pivot_depth: float | dict | None = None,
                 pivot_uv: dict | None = None):
        if pair.pinion_hand != "right":
            raise InputRangeError("pinion_hand", pair.pinion_hand, "'right' (synthesize the "
                                  "right-hand twin and mirror its settings)")
        if gear is None:
            self.gear_setups, self.base = member_setups(pair, gear_generation)
        else:       # a typed gear and its uncrowned pinion (typed_pinion)
            gear_generation = ("formate" if all(g.settings.formate for g in gear.values())
                               else "generated")
            self.gear_setups = {side: gear[side] for side in SIDES}
            self.base = typed_gear_pinion_setups(pair, gear)
        #: the base pinion has point contact (the crown gear's pinion of a hypoid, or of
        #: a typed generated hypoid gear), not line contact (module docstring)
        self.point_contact = gear_generation == "generated" and pair.offset_mm != 0.0
        self.pair, self.n_u, self.n_v = pair, int(n_u), int(n_v)
        blank = pair.blank
        fs = build_machine_flanks(dataclasses.replace(
            pair, machine=tuple(self.gear_setups[s] for s in SIDES)
            + tuple(self.base[s] for s in SIDES), easeoff_tables=("drive", "coast")),
            n_u=n_u, n_v=n_v)
        d = pair.design_side
        self.turn = 0.0
        self.turn = float(fs.pinion.side(d).psi_nodes[0, 0]
                          - self._generated(self.base[d]).psi_nodes[0, 0])
        self.gear = {side: fs.gear.side(side) for side in SIDES}
        #: the pinion sheet's cone (both sides), mm
        self.cone = fs.pinion.side(d).cone
        self.start, self.mean_uv, self.means = {}, {}, {}
        #: side -> where M lies, in words (the head comment's)
        self.pivot = {}
        depth = pivot_depth if isinstance(pivot_depth, dict) else dict.fromkeys(SIDES,
                                                                              pivot_depth)
        at_uv = dict(pivot_uv or {})
        #: side -> why it has no M (point contact whose path has no point inside the
        #: pinion flank by PIVOT_MARGIN); such a side has no start, M or standard
        #: corrections
        self.off_flank = {}
        for side in SIDES:
            m = fs.mean_contact[side]
            guess = ContactGuess(*m["pinion_uv"], *m["gear_uv"], pair.ratio * m["phi2_rad"],
                                 m["phi2_rad"])
            if self.point_contact:
                v_m = float(blank.pitch_point_mm[0])
                try:
                    mp = _path_point_at(fs.pinion.side(side), self.gear[side], pair, guess,
                                        v1_mm=v_m)
                    self.pivot[side] = "the base's contact path on the pinion mean section"
                except EdgeContact as exc:
                    # the path's point nearest the mean section inside the flank
                    mp = _path_point_inside(fs.pinion.side(side), self.gear[side], pair,
                                            guess, v1_mm=v_m)
                    if mp is None:
                        self.off_flank[side] = (
                            "the base pinion's contact path does not reach the pinion's "
                            f"mean section on the flank (from the mean node's phase: {exc})"
                            f" and no point of it lies inside the flank by {PIVOT_MARGIN:g}"
                            " of its depth and face; M, the pivot, is not a point of the "
                            "flank (docs/machine_settings.md sec. 5)")
                        continue
                    self.pivot[side] = (
                        f"the base's contact path {mp.v1 - v_m:+.2f} mm off the pinion "
                        "mean section (the path does not reach it on the flank): its point "
                        f"nearest it inside the flank by {PIVOT_MARGIN:g} of the depth and "
                        "face")
                if at_uv.get(side) is not None:     # the path's point on a given section
                    mp = _path_point_on_section(fs.pinion.side(side), self.gear[side], pair,
                                                mp.as_guess(), uv=at_uv[side])
                    if isinstance(mp, str):     # no pivot there: the side has no M
                        self.off_flank[side] = mp
                        self.pivot.pop(side)
                        continue
                    self.pivot[side] = (
                        "the base's contact path on the pinion section v = {1:.6f} mm "
                        "(given (u, v) = ({0:.6f}, {1:.6f}) mm)".format(*at_uv[side]))
                self.start[side] = mp.as_guess()
                self.mean_uv[side] = (float(mp.u1), float(mp.v1))
            elif at_uv.get(side) is not None:     # line contact: a given flank point
                self.start[side] = _flank_pivot(fs.pinion.side(side), self.gear[side], pair,
                                                guess, uv=at_uv[side])
                self.mean_uv[side] = (self.start[side].u1, self.start[side].v1)
                self.pivot[side] = ("the pinion flank point (u, v) = ({:.6f}, {:.6f}) mm"
                                    .format(*self.mean_uv[side]))
            elif depth.get(side) is None:     # line contact: the mean node is on a line
                self.start[side] = guess
                self.mean_uv[side] = tuple(float(t) for t in m["pinion_uv"])
                self.pivot[side] = "the blank's mean node"
            else:       # line contact: any flank point is; the pivot at the given depth
                self.start[side] = _depth_pivot(fs.pinion.side(side), self.gear[side], pair,
                                                guess, fraction=float(depth[side]))
                self.mean_uv[side] = (self.start[side].u1, self.start[side].v1)
                self.pivot[side] = (f"{float(depth[side]):.2f} of the pinion's working "
                                    "depth on the mean section")
            self.means[side] = _generation_at(self.base[side], blank, self.cone,
                                              self.mean_uv[side])
        # the standard crowning (25 / 10 um, standard_setups): the search's start
        self.standard = {side: np.array([0.0, *crowning_corrections(
            pair, self.base[side], l_mm=self.means[side][0], **STANDARD_CROWNING)])[[0, 2, 1]]
            for side in SIDES if side not in self.off_flank}

    def setup(self, side: str, x) -> MachineSetup:
        """The pinion settings of ``side`` with the corrections ``x``."""
        return corrected_setup(self.base[side], x, mean=self.means[side])

    def _generated(self, setup):
        f = generated_pinion_flank(setup, self.pair.blank,
                                   pinion_face_width_mm=self.pair.pinion_face_width_mm,
                                   n_u=self.n_u, n_v=self.n_v)[0]
        return dataclasses.replace(f, psi_nodes=f.psi_nodes + self.turn)

    def flank(self, side: str, x):
        """The mounted pinion flank of ``side`` with the corrections ``x``."""
        return self._generated(self.setup(side, x))

    def line_room_mm(self, side: str, x) -> float:
        """:func:`line_room_mm` at M of the corrections ``x`` (their contact at M's
        phase)."""
        kin = self.pair.kinematics()
        flank, gear = self.flank(side, x), self.gear[side]
        return line_room_mm(flank, gear, kin, solve_mating_point(flank, gear, kin,
                                                                 self.start[side]))

    def contact(self, side: str, x) -> MeanPointContact:
        """:func:`mean_point_contact` of the corrections ``x``."""
        return mean_point_contact(self.flank(side, x), self.gear[side], self.pair,
                                  self.start[side])
