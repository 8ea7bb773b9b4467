"""Contact ratio of a bevel or hypoid pair from its virtual cylindrical gears, in closed
form: the check ``design`` runs before any flank work (docs/geometry.md sec. 7.7).

The virtual cylindrical gears of ISO 10300-1:2014 (Method B) replace the
pair at its mean section by a helical pair in the transverse section of the mean
spiral angle ``beta_vm = (beta_m1 + beta_m2) / 2`` (the mean of pinion and gear for a
hypoid; ``beta_m`` for a spiral bevel pair)::

    d_v      = d_m / cos(delta)                     reference diameters (back cones)
    alpha_vet = atan(tan(alpha_e) / cos(beta_vm))   transverse pressure angle
    d_vb     = d_v cos(alpha_vet),  d_va = d_v + 2 h_am
    g_vai    = min(sqrt(d_vai^2 - d_vbi^2) / 2 - d_vi sin(alpha_vet) / 2,
                   d_vj sin(alpha_vet) / 2)                     reach of member i's tip
    g_va     = g_va1 + g_va2         (ISO 21771 eq. for the path length, each reach
                                      capped at the mate's interference point)
    eps_va   = g_va cos(beta_vm) / (pi m_mn cos(alpha_vet))      transverse
    eps_vb   = b sin(beta_vm) / (pi m_mn)                        face (overlap)
    eps_vg   = sqrt(eps_va^2 + eps_vb^2)                          ISO 10300-1 Method B

``alpha_e`` is the effective pressure angle of the flank in mesh (ISO 23509: the
nominal angle plus or minus ``f_alim alpha_lim``, the blank's
``pressure_angle_drive_deg`` / ``pressure_angle_coast_deg``), ``h_am`` the mean
addenda, ``b`` the gear face width and ``m_mn`` the mean normal module. The root
sum of squares, not the cylindrical gears' sum ``eps_alpha + eps_beta``, is Method B's
total for a crowned (localized) bearing: the path of a crowned pair crosses the
flank diagonally, its length the diagonal of the transverse and face spans.

:func:`check_contact_ratio` refuses ``eps_vg < MIN_CONTACT_RATIO`` (1.55): not a fit
but the measured worst over-estimate of the TCA's contact ratio (narrow, low-spiral
hypoid faces: TCA / eps_vg down to 0.69) with a 7 % margin over a gap; docs/geometry.md
sec. 7.7 has the 17 pairs measured.

References
----------
ISO 10300-1:2014, *Calculation of load capacity of bevel gears — Part 1*: virtual
cylindrical gears, Method B. ISO 21771:2007, length of path of contact. ISO 23509:2016,
effective pressure angles ``alpha_eD``, ``alpha_eC`` (``geometry.blank``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..validation import InputRangeError

__all__ = ["MIN_CONTACT_RATIO", "VirtualContactRatio", "check_contact_ratio",
           "virtual_contact_ratio"]


@dataclass(frozen=True)
class VirtualContactRatio:
    """Contact ratios of the virtual cylindrical gears of a pair (ISO 10300-1, Method B).

    Attributes
    ----------
    transverse : float
        eps_va, transverse contact ratio (1).
    face : float
        eps_vb, face (overlap) ratio (1).
    total : float
        eps_vg = sqrt(eps_va^2 + eps_vb^2) (1).
    spiral_angle_deg : float
        beta_vm, the mean spiral angle of the virtual gears, deg.
    transverse_pressure_angle_deg : float
        alpha_vet, deg.
    """

    transverse: float
    face: float
    total: float
    spiral_angle_deg: float
    transverse_pressure_angle_deg: float


def virtual_contact_ratio(blank, *, gear_face_width_mm: float,
                          side: str = "drive") -> VirtualContactRatio:
    """The contact ratios of ``blank``'s virtual cylindrical gears (module docstring).

    Parameters
    ----------
    blank : BlankDesign
        Pitch-cone data at the mean point (:func:`~.blank.design_blank`).
    gear_face_width_mm : float, keyword-only
        Gear face width b, mm.
    side : str, keyword-only
        ``"drive"`` or ``"coast"``: which effective pressure angle is in mesh.

    Returns
    -------
    VirtualContactRatio
    """
    if side not in ("drive", "coast"):
        raise ValueError(f"side = {side!r} is not 'drive' or 'coast'")
    alpha_e = math.radians(blank.pressure_angle_drive_deg if side == "drive"
                           else blank.pressure_angle_coast_deg)
    beta = math.radians(0.5 * (blank.spiral_angle_pinion_deg + blank.spiral_angle_gear_deg))
    mn = blank.mean_normal_module_mm
    alpha_t = math.atan(math.tan(alpha_e) / math.cos(beta))
    d_v1 = 2.0 * blank.mean_pitch_radius_pinion_mm / math.cos(
        math.radians(blank.pitch_angle_pinion_deg))
    d_v2 = 2.0 * blank.mean_pitch_radius_gear_mm / math.cos(
        math.radians(blank.pitch_angle_gear_deg))

    def reach(d_v: float, h_a: float, d_mate: float) -> float:
        # path from the pitch point to where this member's tip leaves the mate, mm; at
        # most to the mate's interference point T (its base circle's tangent point):
        # beyond T the mate is undercut and has no flank to contact
        tip = 0.5 * math.sqrt((d_v + 2.0 * h_a) ** 2 - (d_v * math.cos(alpha_t)) ** 2)
        return min(tip - 0.5 * d_v * math.sin(alpha_t), 0.5 * d_mate * math.sin(alpha_t))

    g_va = (reach(d_v1, blank.addendum_pinion_mm, d_v2)
            + reach(d_v2, blank.addendum_gear_mm, d_v1))
    eps_a = g_va * math.cos(beta) / (math.pi * mn * math.cos(alpha_t))
    eps_b = float(gear_face_width_mm) * math.sin(beta) / (math.pi * mn)
    return VirtualContactRatio(eps_a, eps_b, math.hypot(eps_a, eps_b), math.degrees(beta),
                               math.degrees(alpha_t))


#: Refusal threshold on eps_vg. Not a fit: the closed form over-estimates the TCA's
#: measured contact ratio by up to 1 / 0.69 (a 10/15 hypoid, E = 0.3 r2, beta1 20 deg,
#: face 0.15 R_m: eps_vg 1.524, TCA 1.05), and 1.55 x 0.69 = 1.07 keeps a 7 % margin
#: over a gap at the worst pair measured (docs/geometry.md sec. 7.7).
MIN_CONTACT_RATIO = 1.55

#: The standard face-width limit F <= 0.3 R_e, R_e = R_m + F/2, as a fraction of R_m.
_FACE_LIMIT = 0.3 / 0.85


def check_contact_ratio(pair, *, threshold: float = MIN_CONTACT_RATIO) -> VirtualContactRatio:
    """Refuse ``pair`` if its virtual contact ratio eps_vg (:func:`virtual_contact_ratio`,
    design side) is below ``threshold``, before any flank work.

    The error names the field that fixes it, with a value found from the closed form:
    the gear face width that gives ``eps_vg = threshold`` if it is within the standard
    limit ``F <= 0.3 R_e``; else the pinion spiral angle (bisection over
    ``beta_1 < 60 deg`` on the ISO 23509 blank); else the tooth numbers.

    Raises
    ------
    InputRangeError
        ``eps_vg < threshold``.
    """
    def ratio(p):
        return virtual_contact_ratio(p.blank, gear_face_width_mm=p.gear_face_width_mm,
                                     side=p.design_side)

    got = ratio(pair)
    if got.total >= threshold:
        return got
    why = (f"the virtual contact ratio eps_vg = {got.total:.3f} (eps_va {got.transverse:.3f}, "
           f"eps_vb {got.face:.3f}; ISO 10300-1) is below {threshold:g}, the closed form's margin "
           "over a gap in the unloaded mesh (contact ratio < 1)")
    if got.transverse < threshold:
        need = math.sqrt(threshold ** 2 - got.transverse ** 2)
        face = need * math.pi * pair.blank.mean_normal_module_mm / math.sin(
            math.radians(got.spiral_angle_deg))
        if face <= _FACE_LIMIT * pair.blank.mean_cone_distance_gear_mm:
            raise InputRangeError("design.gear_face_width_mm", pair.gear_face_width_mm,
                                  f">= {face:.3f} mm ({why})")
    beta = _spiral_angle_fix(pair, ratio, threshold)
    if beta is not None:
        raise InputRangeError("pinion_spiral_angle_deg", pair.pinion_spiral_angle_deg,
                              f">= {beta:.2f} deg ({why})")
    raise InputRangeError("pinion_teeth / gear_teeth", (pair.pinion_teeth, pair.gear_teeth),
                          f"more teeth ({why}; no face width or spiral angle fixes it)")


def _spiral_angle_fix(pair, ratio, threshold) -> float | None:
    """The smallest pinion spiral angle (deg, up to 60) at which ``ratio`` reaches
    ``threshold`` (bisection to 0.01 deg), or None."""
    def ok(beta):
        try:
            return ratio(replace(pair, pinion_spiral_angle_deg=beta)).total >= threshold
        except InputRangeError:
            return False
    lo, hi = pair.pinion_spiral_angle_deg, 60.0
    if not ok(hi):
        return None
    while hi - lo > 0.01:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi
