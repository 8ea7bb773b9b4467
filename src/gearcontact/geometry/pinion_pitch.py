"""The pitch point of a pinion's generating roll that its blank's standard settings give
(docs/machine_settings.md sec. 2, "The pinion's pitch point"): what a typed pinion
sheet's pitch point (:func:`~.flank_angles.pitch_offset`) would be compared with.
:mod:`.blank_check` does not compare it: with a model bound of a tenth of the dedendum
the comparison warned on the pinion that ``design --machine-settings`` fits to s0003's
ease-off and caught no slip that the mean point and root depth do not (docs).

A gear's generating gear rolls on the gear's pitch cone, so its pitch point of
generation is the mean point (0). A hypoid pinion's is not: the standard settings
(:mod:`.basic_settings`) roll the pinion with the generating gear of its mate, the
gear itself (a formate gear's complementary pinion: cradle axis = gear axis, ratio of
roll ``z2/z1``) or the crown gear of the gear's pitch plane (a generated gear's pinion:
the crown gear turns at ``sin(delta2)`` of the gear's rate about the pitch plane's
normal through the gear's apex, the pinion at ``u``). Either relative motion is that
of one mesh with the pinion; per unit gear rate, in the meshing frame of
:mod:`.kinematics`,

    v(X) = w1 x (X - C1) - w_m x (X - A_m),   Omega = w1 - w_m,

``w1 = -u x`` about the pinion axis through ``C1 = (0, -E, 0)``; ``w_m = z`` through the
origin (the gear) or ``w_m = z - (z . g2) g2`` through the gear's apex ``A2`` (the crown
gear, ``g2`` the gear's pitch generatrix through the pitch point ``P``: the gear rolls on
it, ``v(P)`` is the gear's). At ``P`` the relative velocity lies along the tooth trace
(ISO 23509's pitch-point condition), so a flank point at ``P`` would have its pitch
point of generation there. But a flank's mean point ``Q`` (on the pinion's pitch cone
at the mean cone distance) lies half a tooth thickness or space from ``P`` about the
pinion axis, and where it is generated (the phase at which ``n . v(Q) = 0``, the
equation of meshing with the mate's generating gear) a hypoid's ``Q`` is off the gear's
pitch cone: ``v(Q)`` leaves the pinion cone's tangent plane by ``w x (Q - P)`` and has
profile sliding, ``s = (v(Q) . p) / (Omega . t)`` (:func:`~.flank_angles.pitch_offset`)
from ``Q`` along ``n``. For a spiral bevel pair (``E = 0``) the pitch cones roll on one
another along the whole pitch line and ``s = 0``.

The standard settings' mismatches (cutter radius, circular blade,
:func:`~.basic_settings.standard_setups`) keep the mean node's point and normal, and the
equation of meshing there; ``s`` depends on the point, the normal and the relative
motion only, so the localized pinion's ``s`` is the unlocalized one's. A typed pinion
is compared at its own mean point and normal (:func:`expected_pitch_offset`): what the
standard roll would give there, so a different blade angle, cutter radius or tilt (a
different flank at ``Q``) is not taken for a different roll; what is left is the roll
itself (the ratio of roll, the modified roll at the mean point's roll, the cradle's
placement). Litvin's local synthesis as :mod:`gearcontact.tca.setting_synthesis` writes
it keeps the roll's value and slope at the mean point's roll, so it keeps ``s``.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 2
(relative velocity), sec. 20.2 (generation by one generating surface), ch. 21.
ISO 23509:2016, *Bevel and hypoid gear geometry* (the pitch point).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .flank_angles import MeanPointAngles, profile_pitch_offset

__all__ = ["StandardRoll", "expected_pitch_offset", "standard_roll"]

#: Phases tried about the pinion axis for the equation of meshing (rad, one turn): the
#: roots are bracketed on this grid, then refined (brentq to 1e-14 rad).
_PHASES = np.linspace(-math.pi, math.pi, 181)


@dataclass(frozen=True)
class StandardRoll:
    """The relative motion of a pinion and the generating gear of its blank's standard
    settings (module docstring), in the meshing frame of the right-hand twin, per unit
    gear rate.

    Attributes
    ----------
    mate : str
        ``"gear"`` (a formate gear's complementary pinion) or ``"crown gear"`` (a
        generated gear's pinion).
    pinion_apex_mm, pinion_centre_mm : ndarray (3,)
        The pinion's pitch apex (the work frame's origin) and ``C1`` on its axis, mm.
    pinion_omega : ndarray (3,)
        ``w1 = -u x``, rad per rad of the gear.
    mate_point_mm, mate_omega : ndarray (3,)
        A point of the mate's axis (mm) and its angular velocity ``w_m``.
    pitch_point_mm : ndarray (3,)
        The blank's pitch point ``P``, mm: the root of the equation of meshing nearest it
        is the mean point's phase.
    pinion_hand : str
        The pair's; a left-hand pinion is compared as its right-hand twin (the mirror
        image ``y -> -y``, which leaves ``s`` as it is).
    """

    mate: str
    pinion_apex_mm: np.ndarray
    pinion_centre_mm: np.ndarray
    pinion_omega: np.ndarray
    mate_point_mm: np.ndarray
    mate_omega: np.ndarray
    pitch_point_mm: np.ndarray
    pinion_hand: str = "right"


def standard_roll(pair, *, gear_generated: bool) -> StandardRoll:
    """The :class:`StandardRoll` of ``pair``'s blank: the gear's (``gear_generated``
    False: :func:`~.basic_settings.complementary_pinion_setups`) or the crown gear's
    (True: :func:`~.basic_settings.crown_pinion_setups`)."""
    b = pair.blank
    p = np.array(b.pitch_point_mm, dtype=float)
    z = np.array([0.0, 0.0, 1.0])
    if gear_generated:
        apex = np.array([0.0, 0.0, b.gear_apex_z_mm])
        g2 = (p - apex) / np.linalg.norm(p - apex)
        mate, point, omega = "crown gear", apex, z - (z @ g2) * g2
    else:
        mate, point, omega = "gear", np.zeros(3), z
    return StandardRoll(
        mate=mate, pinion_apex_mm=np.array([b.pinion_apex_x_mm, -pair.offset_mm, 0.0]),
        pinion_centre_mm=np.array([0.0, -pair.offset_mm, 0.0]),
        pinion_omega=np.array([-pair.ratio, 0.0, 0.0]), mate_point_mm=point,
        mate_omega=omega, pitch_point_mm=p, pinion_hand=pair.pinion_hand)


def _work_to_mesh(chi: float) -> np.ndarray:
    """Columns: the work frame's ``x_w, y_w, z_w`` in the meshing frame with the pinion
    turned by ``chi`` about its axis (``z_w`` = the pinion axis = ``x``)."""
    c, s = math.cos(chi), math.sin(chi)
    return np.array([[0.0, 0.0, 1.0], [c, -s, 0.0], [s, c, 0.0]])


def expected_pitch_offset(roll: StandardRoll, at: MeanPointAngles, *,
                          pitch_angle_deg: float) -> float:
    """The pitch point of generation (:func:`~.flank_angles.pitch_offset`, mm along the
    flank's normal) that the standard roll ``roll`` gives at a pinion flank's point
    ``at`` on its pitch cone (:func:`~.flank_angles.measure_mean_point`: work frame) with
    the flank's normal there: the phase about the pinion axis at which the mate's
    generating gear generates the point (``n . v = 0``, the root nearest the blank's
    pitch point), and ``s`` of that relative motion (module docstring).

    Raises
    ------
    ValueError
        No phase generates the point (the normal never meets the relative velocity at
        right angles: not a flank of this blank).
    """
    q = np.array(at.point_mm, dtype=float)
    n = np.array(at.normal, dtype=float)
    phi = at.azimuth_rad
    if roll.pinion_hand == "left":           # the right-hand twin's point and normal
        q[1], n[1], phi = -q[1], -n[1], -phi
    omega = roll.pinion_omega - roll.mate_omega

    def motion(chi):
        m = _work_to_mesh(chi)
        x = roll.pinion_apex_mm + m @ q
        v = (np.cross(roll.pinion_omega, x - roll.pinion_centre_mm)
             - np.cross(roll.mate_omega, x - roll.mate_point_mm))
        return m, x, v

    def meshing(chi):
        m, _, v = motion(chi)
        return float((m @ n) @ v)

    f = np.array([meshing(c) for c in _PHASES])
    roots = [brentq(meshing, a, b, xtol=1e-14)
             for a, b, fa, fb in zip(_PHASES, _PHASES[1:], f, f[1:]) if fa * fb <= 0.0]
    if not roots:
        raise ValueError("no phase of the standard roll generates the pinion's mean point")
    chi = min(roots, key=lambda c: float(np.linalg.norm(motion(c)[1] - roll.pitch_point_mm)))
    m, _, v = motion(chi)
    return profile_pitch_offset(m.T @ v, m.T @ omega, n, pitch_angle_deg=pitch_angle_deg,
                                azimuth_rad=phi)
