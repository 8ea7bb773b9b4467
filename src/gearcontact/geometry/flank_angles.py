"""Spiral angle, pressure angle and depth of a flank cut from machine settings, at a
point of its pitch cone: the check of typed settings against the blank they should cut.

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

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.1,
ch. 21 (envelopes; face-milled spiral bevel gears).
ANSI/AGMA 2005-D03, *Design Manual for Bevel Gears* (hand of spiral).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..validation import check_positive, check_range
from .conjugate import UndercutError
from .machine import MachineKinematics, MachineSetup, blade_point, blade_profile

__all__ = ["MeanPointAngles", "measure_mean_point"]

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


def _distance(z) -> float:
    """Roll plus azimuth (rad) of a solution ``(l, theta, [psi,] phi)``: the branch cut
    nearest the set-up's zero roll in the machine's axial plane is kept."""
    return float(np.sum(np.abs(z[2:])))


def measure_mean_point(setup: MachineSetup, *, pitch_angle_deg: float,
                       cone_distance_mm: float) -> MeanPointAngles:
    """The flank ``setup`` cuts, at cone distance ``cone_distance_mm`` on the pitch cone
    of angle ``pitch_angle_deg`` (apex at the work frame's origin).

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
    for psi0 in _PSI0 if generated else (0.0,):
        for phi0 in _PHI0:
            x_c = t0.T @ (b @ cone(phi0) + a0 - c0)     # zero roll: nearest blade point
            z0 = [max(-x_c[2], 0.1) / math.cos(alpha), math.atan2(x_c[1], x_c[0])]
            z0 += [psi0, phi0] if generated else [phi0]
            sol = least_squares(residual, z0, xtol=1e-15, ftol=1e-15, gtol=1e-15,
                                max_nfev=60)
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
        point_mm=x_w, normal=n_w)
