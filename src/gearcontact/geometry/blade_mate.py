"""The mate of a blade: the same surface of revolution with the material on its other
side, seen from a cutter facing the other way (the pinion cutter of a typed gear's
generating surface, :mod:`.typed_pinion`), and a blade's profile re-centred at another
arc length (the same curve, its terms about a new reference).

Profile (docs/machine_settings.md sec. 1): ``alpha(l) = alpha_0 + s/r_b + c_3 s^2/2 +
c_4 s^3/6``, ``s = l - l_ref``, ``rho' = -sigma sin(alpha)``, ``z' = cos(alpha)``. The
mate cutter's axis is the blade's reversed and its tip plane lies ``shift`` behind the
blade's (depth ``z' = shift - z``); its arc length runs the other way, ``l' = l_s - l``
(``z(l_s) = shift``), so ``d rho/dl' = +sigma sin(alpha)``: a blade of the other kind
(``sigma' = -sigma``) with ``alpha'(l') = alpha(l_s - l')``, i.e. about the same point
``s' = -s``: the same ``alpha_0`` and ``c_3``, ``r_b' = -r_b``, ``c_4' = -c_4``. Its normal
``n' = -n`` (out of the other member's tooth). A straight blade's mate is the same cone,
its point radius ``rho(shift) = rho_0 - sigma shift tan(alpha_0)``.
"""

from __future__ import annotations

import dataclasses
import math

from ..validation import InputRangeError
from .blade import BladeSettings, _arc_at_depth, _straight, blade_profile, blade_through_point

__all__ = ["mate_blade", "recentred_blade"]


def recentred_blade(blade: BladeSettings, l_mm: float, *, add_curvature_per_mm: float = 0.0
                    ) -> BladeSettings:
    """``blade`` (smooth: no relief) with its profile terms taken about the arc length
    ``l_mm`` from its tip (``alpha`` and its first three derivatives there: the
    polynomial re-expanded, exact), the point radius unchanged (the same profile to
    rounding); with ``add_curvature_per_mm`` (1/mm) added to the curvature about that
    point, the profile slid so that it keeps its point and normal there
    (:func:`~.blade.blade_through_point`). A term out of the blade's ranges is an input
    error naming it (``blade.*``)."""
    s = l_mm - blade.profile_reference_mm
    k = 0.0 if blade.profile_radius_mm == 0.0 else 1.0 / blade.profile_radius_mm
    c3, c4 = blade.profile_cubic_per_mm2, blade.profile_quartic_per_mm3
    alpha = math.radians(blade.blade_angle_deg) + s * (k + s * (c3 / 2.0 + s * c4 / 6.0))
    k_new = k + s * (c3 + s * c4 / 2.0) + add_curvature_per_mm
    about = dataclasses.replace(blade, blade_angle_deg=math.degrees(alpha),
                                profile_radius_mm=0.0 if k_new == 0.0 else 1.0 / k_new,
                                profile_reference_mm=float(l_mm),
                                profile_cubic_per_mm2=c3 + s * c4)
    if add_curvature_per_mm == 0.0:
        return about
    rho, z, _, _ = blade_profile(blade, l_mm)      # the pivot keeps its place
    return blade_through_point(about, rho_mm=float(rho), z_mm=float(z))


def mate_blade(blade: BladeSettings, *, shift_mm: float, where: str = "blade") -> BladeSettings:
    """The mate of ``blade``'s main profile (module docstring) on a cutter whose axis is
    reversed and whose tip plane lies ``shift_mm`` (> 0) behind ``blade``'s, with the
    edge radius of ``blade`` (a relief of ``blade`` is not carried: the main profile
    generates). ``where`` names ``blade``'s table in an input error (a mate term out of
    the blade ranges)."""
    kind = "outside" if blade.kind == "inside" else "inside"
    smooth = dataclasses.replace(blade, toprem_angle_deg=0.0, toprem_depth_mm=0.0,
                                 flankrem_angle_deg=0.0, flankrem_depth_mm=0.0)
    if _straight(smooth):
        alpha = math.radians(blade.blade_angle_deg)
        return BladeSettings(kind=kind, blade_angle_deg=blade.blade_angle_deg,
                             point_radius_mm=blade.point_radius_mm
                             - blade.sigma * shift_mm * math.tan(alpha),
                             edge_radius_mm=blade.edge_radius_mm)
    l_s = _arc_at_depth(smooth, shift_mm)
    # the reference: the typed one where it lies above the mate's tip, else mid-way
    l_c = smooth.profile_reference_mm if smooth.profile_reference_mm < l_s else 0.5 * l_s
    try:
        about = smooth if l_c == smooth.profile_reference_mm else recentred_blade(smooth, l_c)
        rho_c, z_c, _, _ = blade_profile(about, l_c)
        k = 0.0 if about.profile_radius_mm == 0.0 else 1.0 / about.profile_radius_mm
        mate = BladeSettings(kind=kind, blade_angle_deg=about.blade_angle_deg,
                             point_radius_mm=float(rho_c),
                             edge_radius_mm=blade.edge_radius_mm,
                             profile_radius_mm=0.0 if k == 0.0 else -1.0 / k,
                             profile_cubic_per_mm2=about.profile_cubic_per_mm2,
                             profile_quartic_per_mm3=0.0 - about.profile_quartic_per_mm3)
        return blade_through_point(mate, rho_mm=float(rho_c), z_mm=shift_mm - float(z_c))
    except InputRangeError as exc:
        raise InputRangeError(f"{where}.{exc.field.rsplit('.', 1)[-1]}", exc.value,
                              f"{exc.allowed} (for the mate blade that cuts the other "
                              "member, docs/machine_settings.md sec. 5)") from exc
