"""Does the mating tip clear an undercut tooth? The penetration of the mate's tip corners
into the undercut member's tooth over the ideal mesh, in the transverse section.

An undercut member's involute starts where the rack tip's trochoid crosses it
(:mod:`.trochoid`); below, the trochoid has cut the tooth back. A mate whose tip would
reach below that form circle on the line of action does not touch the member there as
long as its tip corners pass through the space the rack cut: the path of contact then
simply starts at d_Ff (:func:`.iso21771.involute_geometry`). The rack, whose straight
flank ends at the depth h_FfP* m_n (about the standard addendum), is the limiting mate;
a mate with a longer addendum may cut into the undercut root: interference.

:func:`mating_tip_penetration_mm` moves the mate at the centre distance a_w with the
conjugate ratio (member turned by φ counter-clockwise, mate by -φ z / z_mate, both
flanks closed: the member's tooth on the line of centres at φ = 0, the mate's space
facing it) and measures, for the mate's two tip corners, how far inside the member's
tooth they come: ``(Θ(R) - |θ|) R`` at the corner's radius R and polar angle θ (relative
to the nearest tooth centre), Θ the tooth's half angle, the involute's
``half - inv(arccos(r_b / R))`` above d_Ff and the retained trochoid's polar angle below.
Positive is interference; a tip touching the involute (the start of the path on a
member without undercut) gives ~0.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 10
(undercutting, the rack as the limiting generating tool).
G. Niemann, H. Winter, *Maschinenelemente* Band II, 2nd ed., Springer, 1989, ch. 21
(interference of the mating tip with the root: "Eingriffsstörung").
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import CheckFailed
from .trochoid import GeneratedForm, tip_envelope

__all__ = ["mating_tip_penetration_mm"]

#: Phase samples over four member pitches (the refinement below polishes the best one).
_PHASES = 4001
#: Samples of the retained trochoid for its polar angle against the radius.
_FILLET_SAMPLES = 4001


def _inv(a):
    return np.tan(a) - a


def mating_tip_penetration_mm(form: GeneratedForm, *, teeth: int, base_radius_mm: float,
                              half_angle_rad: float, tip_radius_mm: float, mate_teeth: int,
                              mate_tip_radius_mm: float, mate_tip_half_angle_rad: float,
                              centre_distance_mm: float) -> float:
    """Largest penetration (mm; > 0 inside the tooth) of the mate's tip corners into the
    member of ``form`` over the mesh (module docstring).

    Parameters
    ----------
    form : GeneratedForm
        The member's rack generation (:func:`.trochoid.generated_form`).
    teeth, mate_teeth : int
    base_radius_mm, tip_radius_mm : float
        The member's r_b and r_a, mm.
    half_angle_rad : float
        The member's involute polar angle at the base circle, ``(π/2 + 2 x tan α_n)/z +
        inv α_t`` (the tooth centred on +x).
    mate_tip_radius_mm, mate_tip_half_angle_rad : float
        The mate's tip radius and half the transverse tip thickness angle.
    centre_distance_mm : float
        a_w, mm.

    Raises
    ------
    CheckFailed
        The retained trochoid's radius is not increasing from the root up (its polar
        angle would not be a function of the radius).
    """
    z, z2 = teeth, mate_teeth
    rb, r_ff = base_radius_mm, 0.5 * form.form_diameter_mm
    g, _, _ = tip_envelope(form.rack, np.linspace(-0.5 * math.pi, form.fillet_end_rad,
                                                  _FILLET_SAMPLES))
    rad, ang = np.hypot(g[:, 0], g[:, 1]), np.arctan2(g[:, 1], g[:, 0])
    if np.any(np.diff(rad) <= 0.0):
        raise CheckFailed("the undercut trochoid's radius is not increasing from the root "
                          "to the crossing")
    pitch = 2.0 * math.pi / z

    def penetration(phi):
        phi = np.atleast_1d(phi)[:, None]
        out = np.full(phi.shape[0], -np.inf)
        for k in (-1, 0):
            a = (math.pi + math.pi / z2 + 2.0 * math.pi * k / z2
                 + np.array([-mate_tip_half_angle_rad, mate_tip_half_angle_rad])[None, :]
                 - phi * z / z2)
            x = centre_distance_mm + mate_tip_radius_mm * np.cos(a)
            y = mate_tip_radius_mm * np.sin(a)
            px, py = np.cos(phi) * x + np.sin(phi) * y, np.cos(phi) * y - np.sin(phi) * x
            r = np.hypot(px, py)
            rel = np.abs((np.arctan2(py, px) + 0.5 * pitch) % pitch - 0.5 * pitch)
            half = np.interp(r, rad, ang)
            up = r >= r_ff
            half[up] = half_angle_rad - _inv(np.arccos(np.minimum(rb / r[up], 1.0)))
            depth = np.where(r <= tip_radius_mm, (half - rel) * r, -np.inf)
            out = np.maximum(out, depth.max(axis=1))
        return out

    phis = np.linspace(-2.0 * pitch, 2.0 * pitch, _PHASES)
    pen = penetration(phis)
    i = int(np.argmax(pen))
    lo, hi = phis[max(i - 1, 0)], phis[min(i + 1, len(phis) - 1)]
    from scipy.optimize import minimize_scalar   # lazy: reading a pair loads no solver
    best = minimize_scalar(lambda p: -float(penetration(p)[0]), bounds=(lo, hi),
                           method="bounded", options={"xatol": 1e-12})
    return max(float(pen[i]), -float(best.fun))
