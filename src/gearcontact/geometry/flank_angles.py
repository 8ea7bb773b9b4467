"""Spiral angle, pressure angle and depth of a flank cut from machine settings, at a
point of its pitch cone (:func:`measure_mean_point`), and the angles a summary sheet
prints, the generating gear's in the cradle plane (:func:`measure_generating_angles`,
:func:`measure_pair_mean_points`): the check of typed settings against the blank.

A summary sheet prints the blank (pitch angle, cone distance, spiral angle, pressure
angles) next to the settings; typed in (docs/machine_settings.md sec. 2), the settings
must cut that tooth. In the member's work frame ``S_w`` of :mod:`.machine` (origin at
the pitch apex, ``z_w`` the work axis) the pitch cone is ``|X| sin(delta) = X_z
tan(delta)``; the flank point on it at cone distance ``A`` solves

    X_w(l, theta, psi) = A (sin(delta) cos(phi), sin(delta) sin(phi), cos(delta)),
    n_w . dX_w/dpsi = 0                          (the equation of meshing)

for the blade arc length ``l``, the blade angular position ``theta``, the roll ``psi``
and the azimuth ``phi`` (a formate cut: ``psi = 0`` and no meshing equation, the flank
is the blade surface). There the tooth trace (the flank's section by the pitch cone)
has the tangent ``t = n x N`` (``N`` the pitch cone's normal); the spiral angle is its
angle to the cone's generatrix, the normal pressure angle the angle of the flank's
normal ``n`` to the cone's tangent plane, ``sin(alpha_n) = |n . N|``, and the hand
follows AGMA's definition (the outer half of the tooth inclined clockwise from the
axial plane, seen looking at the face of the gear, is right hand; Litvin & Fuentes
2004, ch. 21 for the generation).

A summary sheet's spiral and pressure angles are not the pitch cone's: they are the
**generating gear's**, in the cradle plane (``z_m = 0``, the plane of the blade tips,
which holds the root line of a tilted-root gear, machine root angle = root angle). At
zero roll the work's axial plane through the cradle axis is ``y_m = E_m``; it cuts the
cradle plane in the root line. The spiral angle is the angle between the nominal
cutter circle (radius ``r_c``, the cutter diameter printed / 2, about the cutter centre
``C`` in the cradle plane) and the root line where the circle crosses it next to the
foot of the mean point, ``x_m = A_m cos(delta - gamma_m) + X_D cos(gamma_m)``:

    cos(beta) = |C_y - E_m| / r_c = |S_r sin(q) - E_m| / r_c

and the pressure angle is the generating gear's profile angle: the angle of the flank's
normal at the mean point to the cradle plane at the roll that generates that point,
``sin(alpha) = |n . z_m|`` (there the flank's normal is the blade's, Litvin & Fuentes
2004, sec. 6.1; at tilt 0 the blade angle). Gear machine settings are computed from
these definitions in SpyGO (``AGMAcomputationHypoid``: ``S sin q = r_c0 cos(beta_m2)``,
``S cos q = CM - r_c0 sin(beta_m2)`` with ``CM`` the mean point's foot on the root line,
machine root = root angle, blade angle = pressure angle - tilt) and in the ZAKgear
radial / cradle-angle calculator (inputs: cone distance to mid face, cutter diameter,
spiral angle); a published gear summary sheet agrees with them
(tests/geometry/summary_sheets/README.md, docs/machine_settings.md sec. 2). For a
pinion no print definition was found (the sheet's pinion page is not at hand; its
pinion is cut "Fixed", each flank by its own cutter): :func:`measure_generating_angles`
takes gear set-ups only.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.1,
ch. 21 (envelopes; face-milled spiral bevel gears).
ANSI/AGMA 2005-D03, *Design Manual for Bevel Gears* (hand of spiral).
SpyGO (Python hypoid geometry, contact analysis and Gleason-type settings),
https://github.com/eGrabovic/SpyGO, ``hypoid/main/utils.py``, ``AGMAcomputationHypoid``
(read in the fork https://github.com/haomjc/SpyGO at commit 417ac9a).
ZAKgear, spiral bevel radial / cradle angle calculator,
http://www.zakgear.com/spiral_bevel_radial.html.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..validation import InputRangeError, check_positive, check_range
from .conjugate import UndercutError
from .machine import MachineKinematics, MachineSetup, blade_point, blade_profile

__all__ = ["FlankMeanPoint", "GeneratingGearAngles", "MeanPointAngles", "PINION_UNDEFINED",
           "generating_circle", "measure_generating_angles", "measure_mean_point",
           "measure_pair_mean_points", "pitch_offset", "profile_pitch_offset", "require_machine"]

#: Starts of the solve, roll (rad) x azimuth (rad): the solution nearest zero roll and
#: the machine's axial plane is kept (:func:`_distance`; others belong to another turn
#: of the cradle or to the blade's second crossing of the cone).
_PSI0 = (0.0, -0.3, 0.3)
_PHI0 = (0.0, -0.15, 0.15, -0.4, 0.4)
_TOL = 1e-9           # residual of the solved point, mm


@dataclass(frozen=True)
class MeanPointAngles:
    """The flank of one set-up at a point of its pitch cone.

    Attributes
    ----------
    spiral_angle_deg : float
        Angle of the tooth trace to the pitch cone's generatrix, degrees, >= 0.
    hand : str
        ``"right"`` or ``"left"`` (module docstring).
    pressure_angle_deg : float
        Normal pressure angle against the pitch cone's tangent plane, degrees.
    depth_mm : float
        Depth of the generating blade point behind the cutter's tip plane, mm.
    blade_length_mm, roll_rad, azimuth_rad : float
        The solution ``l``, ``psi`` and ``phi``.
    point_mm, normal : ndarray (3,)
        The flank point and its unit normal (out of the cut tooth) in ``S_w``.
    blade_position_rad : float
        The solution ``theta`` (the blade's angular position about the cutter axis).
    """

    spiral_angle_deg: float
    hand: str
    pressure_angle_deg: float
    depth_mm: float
    blade_length_mm: float
    roll_rad: float
    azimuth_rad: float
    point_mm: np.ndarray
    normal: np.ndarray
    blade_position_rad: float = 0.0


def _distance(z) -> float:
    """Roll plus azimuth (rad) of a solution ``(l, theta, [psi,] phi)``: the branch cut
    nearest the set-up's zero roll in the machine's axial plane is kept."""
    return float(np.sum(np.abs(z[2:])))


def measure_mean_point(setup: MachineSetup, *, pitch_angle_deg: float,
                       cone_distance_mm: float,
                       start: MeanPointAngles | None = None) -> MeanPointAngles:
    """The flank ``setup`` cuts, at cone distance ``cone_distance_mm`` on the pitch cone
    of angle ``pitch_angle_deg`` (apex at the work frame's origin).

    ``start``: the solution of a nearby set-up (a setting moved by its rounding,
    :mod:`.blank_check`): the solve starts from it alone instead of the grid of starts,
    and keeps that branch.

    Raises
    ------
    InputRangeError
        A pitch angle outside (0, 90] degrees or a cone distance <= 0.
    UndercutError
        No point of the flank at that cone distance on the pitch cone (the settings do
        not cut that tooth).
    """
    check_range("pitch_angle_deg", pitch_angle_deg, 0.0, 90.0, lo_open=True)
    check_positive("cone_distance_mm", cone_distance_mm)
    kin, blade = MachineKinematics(setup.settings), setup.blade
    generated = not setup.settings.formate
    d = math.radians(pitch_angle_deg)
    sd, cd = math.sin(d), math.cos(d)

    def cone(phi):
        return cone_distance_mm * np.array([sd * math.cos(phi), sd * math.sin(phi), cd])

    def flank(z):
        l, th, psi = z[0], z[1], z[2] if generated else 0.0
        x_t, n_t = blade_point(blade, l, th)
        return kin.to_work(x_t, n_t, psi)

    def residual(z):
        x_w, n_w, v_w = flank(z)
        r = x_w - cone(z[-1])
        return np.append(r, n_w @ v_w) if generated else r

    c0, t0, b, a0 = kin._fixed
    alpha = math.radians(blade.blade_angle_deg)
    best = None
    if start is not None:
        starts = [[start.blade_length_mm, start.blade_position_rad]
                  + ([start.roll_rad, start.azimuth_rad] if generated else [start.azimuth_rad])]
    else:
        starts = []
        for psi0 in _PSI0 if generated else (0.0,):
            for phi0 in _PHI0:
                x_c = t0.T @ (b @ cone(phi0) + a0 - c0)     # zero roll: nearest blade point
                z0 = [max(-x_c[2], 0.1) / math.cos(alpha), math.atan2(x_c[1], x_c[0])]
                starts.append(z0 + ([psi0, phi0] if generated else [phi0]))
    for z0 in starts:
        sol = least_squares(residual, z0, xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=60)
        ok = np.max(np.abs(sol.fun)) < _TOL and sol.x[0] > 0.0
        if ok and (best is None or _distance(sol.x) < _distance(best.x)):
            best = sol
    if best is None:
        raise UndercutError(f"{setup.member} {setup.side} flank at cone distance "
                            f"{cone_distance_mm:.4f} mm", "no solution",
                            "a point of the flank on the pitch cone (check the settings "
                            "against the blank)")
    z = best.x
    x_w, n_w, _ = flank(z)
    phi = z[-1]
    g = np.array([sd * math.cos(phi), sd * math.sin(phi), cd])     # generatrix
    e_phi = np.array([-math.sin(phi), math.cos(phi), 0.0])
    t = np.cross(n_w, np.cross(g, e_phi))
    t = t if t @ g > 0.0 else -t                                   # towards the heel
    return MeanPointAngles(
        spiral_angle_deg=math.degrees(math.atan2(abs(t @ e_phi), t @ g)),
        hand="right" if t @ e_phi > 0.0 else "left",
        pressure_angle_deg=math.degrees(math.asin(min(1.0, abs(n_w @ np.cross(g, e_phi))))),
        depth_mm=float(blade_profile(blade, z[0])[1]), blade_length_mm=float(z[0]),
        roll_rad=float(z[2]) if generated else 0.0, azimuth_rad=float(phi),
        point_mm=x_w, normal=n_w, blade_position_rad=float(z[1]))


@dataclass(frozen=True)
class GeneratingGearAngles:
    """The generating gear of one flank at the blank's mean point: what a summary sheet
    prints (module docstring), beside the cut flank's pitch-cone values.

    Attributes
    ----------
    spiral_angle_deg : float
        Angle between the nominal cutter circle and the root line where it crosses the
        root line, in the cradle plane, degrees, in [0, 90].
    pressure_angle_deg : float
        Angle of the flank's normal at the mean point to the cradle plane at the roll
        that generates the point, degrees, in [0, 90].
    cone_distance_mm : float
        Pitch cone distance of the point whose foot on the root line is that crossing:
        the mean point of the generating gear, mm.
    crossing_beyond_mean_mm : float
        The crossing's distance along the root line beyond the foot of the mean point
        given (towards the heel), mm.
    pitch_cone : MeanPointAngles
        The cut flank at the mean point on the pitch cone (:func:`measure_mean_point`).
    pitch_offset_mm : float or None
        The generating roll's pitch point against the mean point, mm: the distance along
        the flank's normal ``n`` from the mean point to where the generating gear rolls
        on the work without profile sliding (:func:`pitch_offset`); None where the work
        does not roll (ratio of roll 0: formate, or helical motion alone).
    """

    spiral_angle_deg: float
    pressure_angle_deg: float
    cone_distance_mm: float
    crossing_beyond_mean_mm: float
    pitch_cone: MeanPointAngles
    pitch_offset_mm: float | None = None


def measure_generating_angles(setup: MachineSetup, *, pitch_angle_deg: float,
                              cone_distance_mm: float,
                              cutter_radius_mm: float,
                              start: MeanPointAngles | None = None) -> GeneratingGearAngles:
    """The spiral angle, pressure angle and mean cone distance of the generating gear of
    the gear flank ``setup`` cuts, as a summary sheet prints them (module docstring),
    at the mean point of cone distance ``cone_distance_mm`` on the pitch cone of angle
    ``pitch_angle_deg``.

    Parameters
    ----------
    setup : MachineSetup
        A gear flank (``setup.member == "gear"``), formate or generated. A tilted
        cutter's circle is taken about its centre in the cradle plane, as SpyGO builds a
        tilted gear's settings (not checked against a print).
    pitch_angle_deg : float
        The gear's pitch angle, degrees, in (0, 90].
    cone_distance_mm : float
        The blank's mean cone distance, mm, > 0: the point whose generating roll gives
        the pressure angle, and whose foot on the root line picks the crossing (the
        nearer of the circle's two).
    cutter_radius_mm : float
        Nominal cutter radius ``r_c``, mm, > 0: the printed cutter diameter / 2 (the
        pair's ``[cutter] radius_mm``); the circle must reach the root line.
    start : MeanPointAngles, optional
        Passed to :func:`measure_mean_point`.

    Returns
    -------
    GeneratingGearAngles

    Raises
    ------
    InputRangeError
        A pinion set-up (no print definition found, module docstring), a nominal cutter
        circle that does not reach the root line, or the ranges of
        :func:`measure_mean_point`.
    UndercutError
        No point of the flank at that cone distance on the pitch cone.

    References
    ----------
    SpyGO ``AGMAcomputationHypoid`` and the ZAKgear radial / cradle-angle calculator
    (module docstring; docs/machine_settings.md sec. 2).
    """
    if setup.member != "gear":
        raise InputRangeError(f"{setup.side} set-up member", setup.member,
                              "'gear' (a summary sheet's generating-gear angles are "
                              "defined for the gear member; no print definition of the "
                              "pinion's was found, docs/machine_settings.md sec. 2)")
    check_positive("cutter_radius_mm", cutter_radius_mm)
    at = measure_mean_point(setup, pitch_angle_deg=pitch_angle_deg,
                            cone_distance_mm=cone_distance_mm, start=start)
    spiral, cone, beyond = generating_circle(setup, pitch_angle_deg=pitch_angle_deg,
                                             cone_distance_mm=cone_distance_mm,
                                             cutter_radius_mm=cutter_radius_mm)
    st = setup.settings
    kin = MachineKinematics(st)
    # the cradle plane's normal in the work at the generating roll (a cutter-frame
    # vector that to_work carries to z_m; the cradle roll leaves z_m)
    t0 = kin._fixed[1]
    _, z_m, _ = kin.to_work(np.zeros(3), t0.T @ np.array([0.0, 0.0, 1.0]), at.roll_rad)
    return GeneratingGearAngles(
        spiral_angle_deg=spiral,
        pressure_angle_deg=math.degrees(math.asin(min(1.0, abs(float(at.normal @ z_m))))),
        cone_distance_mm=cone, crossing_beyond_mean_mm=beyond, pitch_cone=at,
        pitch_offset_mm=None if st.ratio_of_roll == 0.0 else pitch_offset(
            setup, at, pitch_angle_deg=pitch_angle_deg))


def generating_circle(setup: MachineSetup, *, pitch_angle_deg: float,
                      cone_distance_mm: float, cutter_radius_mm: float
                      ) -> tuple[float, float, float]:
    """``(spiral angle deg, mean cone distance mm, crossing beyond the mean point mm)`` of
    :func:`measure_generating_angles`: the nominal cutter circle against the root line in
    the cradle plane (module docstring), closed form in the settings, no solve (what
    :mod:`.blank_check` screens a slip's candidate with before solving).

    Raises
    ------
    InputRangeError
        A nominal cutter circle that does not reach the root line.
    """
    r_c = check_positive("cutter_radius_mm", cutter_radius_mm)
    st = setup.settings
    c = MachineKinematics(st).cutter_to_machine(np.zeros(3))  # cutter centre, cradle plane
    off = float(c[1]) - st.blank_offset_mm          # from the root line
    if not abs(off) < r_c:
        raise InputRangeError("cutter_radius_mm", cutter_radius_mm,
                              f"> {abs(off):.4f} mm, the cutter centre's distance from the "
                              f"root line of the {setup.side} settings (the nominal cutter "
                              "circle must cross it)")
    g = math.radians(st.machine_root_angle_deg)
    along = math.cos(math.radians(pitch_angle_deg) - g)  # pitch generatrix -> root line
    x_foot = cone_distance_mm * along + st.machine_centre_to_back_mm * math.cos(g)
    half = math.sqrt(r_c ** 2 - off ** 2)
    x_cross = min((float(c[0]) - half, float(c[0]) + half), key=lambda x: abs(x - x_foot))
    return (math.degrees(math.acos(abs(off) / r_c)),
            cone_distance_mm + (x_cross - x_foot) / along, x_cross - x_foot)


def pitch_offset(setup: MachineSetup, at: MeanPointAngles, *, pitch_angle_deg: float) -> float:
    """The pitch point of the generating roll against the point ``at`` of a generated
    flank on its pitch cone, mm.

    At the roll ``psi`` that generates the point ``P`` the generating gear (the cradle
    and the cutter) moves against the work with the relative velocity field
    ``v(X) = v_P + Omega x (X - P)`` per radian of cradle roll (``Omega = z_m -
    phi'(psi) z_w`` in the work frame, ``phi'`` the work's roll rate with the modified
    roll). Its component across the tooth trace, along the profile direction ``p = n x
    t`` (``t`` the tooth trace on the pitch cone, ``n`` the flank's normal), is the
    profile sliding; ``n . v = 0`` (the equation of meshing). Where it vanishes the
    generating gear rolls on the work: its pitch point, which the ratio of roll places
    (ISO 23509's pitch-point condition, the relative velocity at the pitch point along
    the tooth trace). Moved by ``s`` along ``n`` the profile sliding is ``v_P . p + s
    (Omega x n) . p = v_P . p - s Omega . t``, so the pitch point lies at

        s = (v_P . p) / (Omega . t)

    from ``P`` along ``n`` (mm, signed): 0 where the roll is the blank's (a pinion
    rolled with its mate's generating gear, a gear on the crown gear of its pitch plane;
    docs/machine_settings.md sec. 2 has the measured values).

    Parameters
    ----------
    setup : MachineSetup
        A generated flank whose work rolls (ratio of roll != 0).
    at : MeanPointAngles
        Its point on the pitch cone (:func:`measure_mean_point`).
    pitch_angle_deg : float
        The pitch angle of that cone, degrees.

    Returns
    -------
    float
        ``s``, mm.

    Raises
    ------
    InputRangeError
        A ratio of roll 0 (the work does not roll: no pitch point).

    References
    ----------
    F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 2
    (relative velocity), sec. 6.1 (equation of meshing). ISO 23509:2016 (the pitch point
    of a hypoid pair: the relative velocity there along the tooth trace).
    """
    if setup.settings.ratio_of_roll == 0.0:
        raise InputRangeError(f"{setup.member} {setup.side} set-up ratio_of_roll", 0.0,
                              "a rolled flank, != 0 (the work does not roll: no pitch point)")
    kin = MachineKinematics(setup.settings)
    x_t, n_t = blade_point(setup.blade, at.blade_length_mm, at.blade_position_rad)
    _, n, v = kin.to_work(x_t, n_t, at.roll_rad)
    _, z_m, _ = kin.to_work(np.zeros(3), kin._fixed[1].T @ np.array([0.0, 0.0, 1.0]),
                            at.roll_rad)
    omega = z_m - float(kin.work_rotation(at.roll_rad)[1]) * np.array([0.0, 0.0, 1.0])
    return profile_pitch_offset(v, omega, n, pitch_angle_deg=pitch_angle_deg,
                                azimuth_rad=at.azimuth_rad)


def profile_pitch_offset(velocity: np.ndarray, omega: np.ndarray, normal: np.ndarray, *,
                         pitch_angle_deg: float, azimuth_rad: float) -> float:
    """``s = (v . p) / (Omega . t)`` (:func:`pitch_offset`), mm: where the profile sliding
    of the rigid relative motion ``v(X) = velocity + omega x (X - P)`` (work frame, any
    common scale and sign) vanishes on the normal line of the flank point ``P`` of unit
    normal ``normal`` at azimuth ``azimuth_rad`` on the pitch cone of ``pitch_angle_deg``
    (``t`` the tooth trace there, ``p = n x t``)."""
    d, phi = math.radians(pitch_angle_deg), azimuth_rad
    g = np.array([math.sin(d) * math.cos(phi), math.sin(d) * math.sin(phi), math.cos(d)])
    n = np.asarray(normal, dtype=float)
    t = np.cross(n, np.cross(g, np.array([-math.sin(phi), math.cos(phi), 0.0])))
    t /= np.linalg.norm(t)
    return float(np.asarray(velocity) @ np.cross(n, t)) / float(np.asarray(omega) @ t)


#: Why a pinion flank has no generating-gear angles (module docstring).
PINION_UNDEFINED = ("the generating gear's angles are the gear's only: no summary-sheet "
                    "definition of a pinion's was found (docs/machine_settings.md sec. 2)")


@dataclass(frozen=True)
class FlankMeanPoint:
    """One flank of a pair cut from machine settings at its member's mean point.

    Attributes
    ----------
    member, side : str
        ``"gear"`` / ``"pinion"``, ``"drive"`` / ``"coast"``.
    cone_distance_mm : float
        The blank's mean cone distance of the member, mm (the pitch-cone point).
    pitch_cone : MeanPointAngles or None
        The flank there (:func:`measure_mean_point`); None where the flank does not
        reach it.
    generating_gear : GeneratingGearAngles or None
        The gear's generating gear (:func:`measure_generating_angles`); None for a
        pinion and where the flank does not reach the point.
    missing : str
        Why a value is None ("" when both are given).
    cutter_circle : str
        Where the nominal cutter circle does not cross a gear flank's root line: the
        allowed range of its radius (``generating_gear`` None), "" otherwise.
    """

    member: str
    side: str
    cone_distance_mm: float
    pitch_cone: MeanPointAngles | None
    generating_gear: GeneratingGearAngles | None
    missing: str
    cutter_circle: str = ""


def require_machine(pair) -> None:
    """Raise :class:`~gearcontact.validation.InputRangeError` for a pair without machine
    settings (the ``[machine.*]`` / ``[blade.*]`` tables)."""
    if not pair.machine:
        raise InputRangeError("[machine.*]", None, "a pair cut from machine settings "
                              "(the [machine.*] / [blade.*] tables)")


def measure_pair_mean_points(pair) -> tuple[FlankMeanPoint, ...]:
    """All flanks of ``pair`` (a :class:`~.pair.GearPair` cut from machine settings) at
    the mean points of its blank (ISO 23509: pitch angles, mean cone distances) and, for
    the gear, the generating gear of a summary sheet with the nominal cutter radius
    ``[cutter] radius_mm``. A flank that does not reach its mean point, or a nominal
    cutter circle that does not cross a gear flank's root line, is reported
    (``missing``), not refused: the typed settings do not cut that blank.

    Raises
    ------
    InputRangeError
        A pair without machine settings.
    """
    require_machine(pair)
    b = pair.blank
    out = []
    for setup in pair.machine:
        circle = ""
        gear = setup.member == "gear"
        cone = dict(pitch_angle_deg=b.pitch_angle_gear_deg if gear else b.pitch_angle_pinion_deg,
                    cone_distance_mm=b.mean_cone_distance_gear_mm if gear
                    else b.mean_cone_distance_pinion_mm)
        try:
            if gear:
                gen = measure_generating_angles(setup, **cone,
                                                cutter_radius_mm=pair.cutter.radius_mm)
                at, missing = gen.pitch_cone, ""
            else:
                gen, missing = None, PINION_UNDEFINED
                at = measure_mean_point(setup, **cone)
        except UndercutError:
            at = gen = None
            missing = (f"the {setup.member} {setup.side} flank does not reach the blank's mean "
                       f"point (cone distance {cone['cone_distance_mm']:.4f} mm on the pitch "
                       "cone): the settings do not cut this blank")
        except InputRangeError as exc:
            if exc.field != "cutter_radius_mm":
                raise
            at, gen, circle = measure_mean_point(setup, **cone), None, exc.allowed
            missing = (f"[cutter] radius_mm = {pair.cutter.radius_mm:g}: its circle does not "
                       f"cross the root line ({exc.allowed})")
        out.append(FlankMeanPoint(setup.member, setup.side, cone["cone_distance_mm"], at, gen,
                                  missing, circle))
    return tuple(out)
