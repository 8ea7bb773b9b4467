"""Blades of a face-milling cutter: profile, Toprem / Flankrem reliefs and tip edge round.

The blade frame is the cutter frame ``S_t`` of :mod:`.machine` (docs/machine_settings.md
sec. 1): a blade is a surface of revolution about ``z_t``; its profile in the axial
half-plane at blade angle ``theta`` has the arc length ``l`` from the tip and the
profile angle ``alpha(l)``,

    x = rho(l) e_rho - z(l) z_t,   rho' = -sigma sin(alpha),   z' = cos(alpha),
    n = sigma cos(alpha) e_rho - sin(alpha) z_t

(``sigma`` = +1 inside blade, -1 outside blade; ``n`` out of the cut tooth into the
slot). A curved blade (profile radius ``r_b``) has ``alpha(l) = alpha_0 + (l - l_ref) /
r_b``; a higher-order profile adds ``c_3 s^2 / 2 + c_4 s^3 / 6`` (``s = l - l_ref``),
integrated by Gauss-Legendre quadrature.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 20-21
(head-cutter blade surfaces).
H. J. Stadtfeld, *Handbook of Bevel and Hypoid Gears: Calculation, Manufacturing,
Optimization*, Rochester Institute of Technology, 1993 (blade profiles beyond the
straight line: curved blades, Toprem and Flankrem reliefs, ground on a blade grinder).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..validation import InputRangeError, check_finite, check_range

__all__ = ["BladeSegment", "BladeSettings", "EdgeRound", "MAX_POINT_RADIUS_MM", "MAX_RELIEF_DEG",
           "blade_point", "blade_profile", "blade_segments", "blade_through_point", "edge_round"]

#: Largest Toprem / Flankrem relief angle, degrees (blade grinders give a few degrees).
MAX_RELIEF_DEG = 10.0

#: Largest blade point radius, mm: a cutter of 2 m diameter, the bound of the radial
#: distance (:class:`~.machine.MachineSettings`); a larger radius is a slip (a length in
#: um, a wrong exponent) whose flank would overflow in the envelope solve.
MAX_POINT_RADIUS_MM = 1000.0


@dataclass(frozen=True)
class BladeSettings:
    """One blade of a face-milling cutter (``[blade.<member>.<flank>]``).

    Parameters
    ----------
    kind : str
        ``"inside"`` (the blade nearer the cutter axis, cutting the slot wall that faces
        away from the axis: a gear's convex flank, a generated pinion's convex flank) or
        ``"outside"``.
    blade_angle_deg : float
        Profile angle alpha_0 of the blade to the cutter axis, degrees, in [0, 45).
    point_radius_mm : float
        Radius of the blade tip (the cutting edge at the tip plane), mm, in (0,
        :data:`MAX_POINT_RADIUS_MM`].
    edge_radius_mm : float
        Tip edge radius, mm, in [0, point_radius_mm / 2]: the flank starts above the
        edge round.
    profile_radius_mm : float
        Blade profile curvature radius r_b, mm; 0 = straight blade; else |r_b| >= 10 mm.
    profile_reference_mm : float
        Arc length from the tip at which the blade angle alpha_0 holds (curved blades), mm.
    profile_cubic_per_mm2 : float
        c_3 = d^2 alpha / dl^2 at ``l_ref``, 1/mm^2, |c_3| <= 1 (higher-order profile,
        module docstring; 0 = none; 1 /mm^2 is a 0.17 mm offset 1 mm from ``l_ref``).
    profile_quartic_per_mm3 : float
        c_4 = d^3 alpha / dl^3, 1/mm^3, |c_4| <= 1; > 0 adds curvature on both sides
        of ``l_ref`` (a quartic relief towards the tip and the top of the blade).
    """

    kind: str
    blade_angle_deg: float
    point_radius_mm: float
    edge_radius_mm: float = 0.0
    profile_radius_mm: float = 0.0
    profile_reference_mm: float = 0.0
    profile_cubic_per_mm2: float = 0.0
    profile_quartic_per_mm3: float = 0.0
    toprem_angle_deg: float = 0.0
    toprem_depth_mm: float = 0.0
    flankrem_angle_deg: float = 0.0
    flankrem_depth_mm: float = 0.0
    where: str = field(default="blade", compare=False, repr=False)

    def __post_init__(self):
        w = self.where
        if self.kind not in ("inside", "outside"):
            raise InputRangeError(f"{w}.kind", self.kind, "'inside' or 'outside'")
        check_range(f"{w}.blade_angle_deg", self.blade_angle_deg, 0.0, 45.0, hi_open=True)
        check_range(f"{w}.point_radius_mm", self.point_radius_mm, 0.0, MAX_POINT_RADIUS_MM,
                    lo_open=True)
        if check_finite(f"{w}.edge_radius_mm", self.edge_radius_mm) > 0.5 * self.point_radius_mm:
            # the range's upper end is the other key's: name it (a point radius in m?)
            raise InputRangeError(f"{w}.edge_radius_mm", self.edge_radius_mm, (
                f"[0, {0.5 * self.point_radius_mm:.6g}]: at most half the point radius "
                f"{w}.point_radius_mm = {self.point_radius_mm!r} (both in mm)"))
        check_range(f"{w}.edge_radius_mm", self.edge_radius_mm, 0.0, 0.5 * self.point_radius_mm)
        r = check_finite(f"{w}.profile_radius_mm", self.profile_radius_mm)
        if r != 0.0 and abs(r) < 10.0:
            raise InputRangeError(f"{w}.profile_radius_mm", r,
                                  "0 (straight blade) or |r| >= 10 mm")
        check_range(f"{w}.profile_reference_mm", self.profile_reference_mm, 0.0, 50.0)
        check_range(f"{w}.profile_cubic_per_mm2", self.profile_cubic_per_mm2, -1.0, 1.0)
        check_range(f"{w}.profile_quartic_per_mm3", self.profile_quartic_per_mm3, -1.0, 1.0)
        for name in ("toprem", "flankrem"):
            check_range(f"{w}.{name}_angle_deg", getattr(self, f"{name}_angle_deg"), 0.0,
                        MAX_RELIEF_DEG)
            check_range(f"{w}.{name}_depth_mm", getattr(self, f"{name}_depth_mm"), 0.0, 50.0)
        if self.relieved:
            _check_reliefs(self)

    @property
    def sigma(self) -> float:
        """+1 for an inside blade, -1 for an outside blade."""
        return 1.0 if self.kind == "inside" else -1.0

    @property
    def relieved(self) -> bool:
        """True for a blade with a Toprem or a Flankrem (a kinked profile)."""
        return self.toprem_angle_deg != 0.0 or self.flankrem_angle_deg != 0.0

    @property
    def higher_order(self) -> bool:
        """True for a blade with a cubic or quartic profile term."""
        return self.profile_cubic_per_mm2 != 0.0 or self.profile_quartic_per_mm3 != 0.0



def blade_profile(blade: BladeSettings, l_mm):
    """Profile of a blade at arc length ``l`` from its tip (arrays).

    Returns
    -------
    rho, z, alpha, dalpha : ndarray
        Radius and depth behind the tip plane (mm), profile angle (rad) and
        ``d alpha / d l`` (1/mm) (module docstring).
    """
    l_mm = np.asarray(l_mm, dtype=float)
    a0, sig = math.radians(blade.blade_angle_deg), blade.sigma
    if blade.relieved:
        return _relieved_profile(blade, l_mm)
    if blade.higher_order:
        return _higher_order_profile(blade, l_mm)
    if blade.profile_radius_mm == 0.0:
        ca, sa = math.cos(a0), math.sin(a0)
        return (blade.point_radius_mm - sig * sa * l_mm, ca * l_mm, np.full_like(l_mm, a0),
                np.zeros_like(l_mm))
    k = 1.0 / blade.profile_radius_mm
    alpha = a0 + k * (l_mm - blade.profile_reference_mm)
    alpha_tip = a0 - k * blade.profile_reference_mm
    # rho' = -sigma sin(alpha), z' = cos(alpha), integrated in closed form; the
    # differences of cosines and sines as products (no cancellation as r_b grows:
    # a fit steps the curvature through 0)
    half = np.sin(0.5 * k * l_mm) / k
    mid = 0.5 * (alpha + alpha_tip)
    rho = blade.point_radius_mm - 2.0 * sig * np.sin(mid) * half
    z = 2.0 * np.cos(mid) * half
    return rho, z, alpha, np.full_like(l_mm, k)


#: Gauss-Legendre nodes and weights on [0, 1] for the higher-order profile: the
#: integrands sin/cos of a cubic in l vary by < 1 rad over a blade, so 16 nodes
#: integrate them to rounding (tested against adaptive quadrature, 1e-12 mm).
_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(16)
_GAUSS = (0.5 * (_GAUSS_X + 1.0), 0.5 * _GAUSS_W)


def _profile_angle(blade: BladeSettings, l_mm):
    """``(alpha, d alpha / dl)`` of the profile at arc length ``l`` (module docstring)."""
    s = l_mm - blade.profile_reference_mm
    k = 0.0 if blade.profile_radius_mm == 0.0 else 1.0 / blade.profile_radius_mm
    c3, c4 = blade.profile_cubic_per_mm2, blade.profile_quartic_per_mm3
    return (math.radians(blade.blade_angle_deg) + s * (k + s * (c3 / 2.0 + s * c4 / 6.0)),
            k + s * (c3 + s * c4 / 2.0))


def _higher_order_profile(blade: BladeSettings, l_mm):
    """:func:`blade_profile` of a blade with cubic / quartic terms: ``rho`` and ``z`` by
    Gauss-Legendre quadrature of ``rho' = -sigma sin(alpha)``, ``z' = cos(alpha)``."""
    x, w = _GAUSS
    a_nodes, _ = _profile_angle(blade, l_mm[..., None] * x)
    rho = blade.point_radius_mm - blade.sigma * l_mm * (np.sin(a_nodes) @ w)
    z = l_mm * (np.cos(a_nodes) @ w)
    alpha, dalpha = _profile_angle(blade, l_mm)
    return rho, z, alpha, dalpha


def blade_through_point(blade: BladeSettings, *, rho_mm: float, z_mm: float) -> BladeSettings:
    """``blade``'s profile (its angle, curvature and higher-order terms at its reference)
    slid along itself and moved radially so that its reference point lies at radius
    ``rho_mm`` and depth ``z_mm`` (> 0) behind the tip plane: the reference arc length
    solves ``z(l_ref) = z_mm`` (monotone while ``|alpha| < 90 deg``), then the point
    radius puts ``rho(l_ref) = rho_mm``."""
    from scipy.optimize import brentq   # here: scipy.optimize costs 0.3 s per process

    if not z_mm > 0.0:      # a point at or above the tip plane: no blade profile holds it
        raise InputRangeError(f"{blade.where} reference point depth (mm)", z_mm,
                              "> 0: behind the cutter's tip plane, where the blade cuts "
                              "(the flank point it is placed through lies above the blade "
                              "tips: settings that do not cut their blank's tooth)")

    def depth(l_ref):
        placed = dataclasses.replace(blade, profile_reference_mm=l_ref)
        return float(blade_profile(placed, l_ref)[1]) - z_mm

    l_ref = (z_mm / math.cos(math.radians(blade.blade_angle_deg))
             if _straight(blade) else brentq(depth, 0.0, 3.0 * z_mm + 1.0, xtol=1e-14))
    placed = dataclasses.replace(blade, profile_reference_mm=l_ref)
    rho = float(blade_profile(placed, l_ref)[0])
    return dataclasses.replace(placed, point_radius_mm=blade.point_radius_mm + rho_mm - rho)


def blade_point(blade: BladeSettings, l_mm, theta_rad):
    """Point and unit normal of the blade surface in the cutter frame ``S_t``:
    ``(x, n)``, arrays (..., 3) (module docstring)."""
    rho, z, alpha, _ = blade_profile(blade, l_mm)
    th = np.asarray(theta_rad, dtype=float)
    c, s = np.cos(th), np.sin(th)
    x = np.stack([rho * c, rho * s, -z + 0.0 * th], axis=-1)
    sc, sa = blade.sigma * np.cos(alpha), np.sin(alpha)
    n = np.stack([sc * c, sc * s, -sa + 0.0 * th], axis=-1)
    return x, n


@dataclass(frozen=True)
class EdgeRound:
    """The tip edge round of a blade, in the cutter frame ``S_t``: a circle of radius
    ``radius_mm`` in the axial half-plane, tangent to the tip plane (at its bottom,
    ``z = 0``) and to the blade profile (at arc length ``top_length_mm`` from the tip,
    profile angle ``top_angle_rad``), its centre at radius ``centre_radius_mm`` and depth
    ``radius_mm`` behind the tip plane. Revolved about ``z_t`` it is the torus that cuts
    the root fillet. ``s`` is the arc length on the round from its bottom (the root) up
    to the profile, ``s_top = r_e (pi/2 - alpha_top)``; there the profile angle is
    ``alpha(s) = pi/2 - s / r_e`` and the point and normal are those of the profile
    (module docstring) with the same ``sigma``: tangent-continuous at ``s_top``."""

    radius_mm: float
    centre_radius_mm: float
    top_length_mm: float
    top_angle_rad: float
    sigma: float

    @property
    def top_arc_mm(self) -> float:
        """``s_top``, the arc length of the round from the tip plane to the profile, mm."""
        return self.radius_mm * (0.5 * math.pi - self.top_angle_rad)

    def point(self, s_mm, theta_rad):
        """Point and unit normal (out of the cut tooth) on the round at arc length ``s``
        from its bottom and blade angle ``theta``: ``(x, n)``, arrays (..., 3), ``S_t``."""
        alpha = 0.5 * math.pi - np.asarray(s_mm, dtype=float) / self.radius_mm
        sc, sa = self.sigma * np.cos(alpha), np.sin(alpha)
        rho = self.centre_radius_mm - self.radius_mm * sc
        z = self.radius_mm * (1.0 - sa)
        th = np.asarray(theta_rad, dtype=float)
        c, s = np.cos(th), np.sin(th)
        return (np.stack([rho * c, rho * s, -z + 0.0 * th], axis=-1),
                np.stack([sc * c, sc * s, -sa + 0.0 * th], axis=-1))


def edge_round(blade: BladeSettings) -> EdgeRound:
    """The :class:`EdgeRound` of ``blade``: the circle of the edge radius tangent to the
    tip plane and to the profile. The tangent point solves ``z(l) + r_e sin(alpha(l)) =
    r_e`` (centre at depth ``r_e``): ``l = r_e (1 - sin alpha) / cos alpha`` on a
    straight blade, by root finding on a curved one (``z + r_e sin(alpha)`` grows with
    ``l`` while ``alpha`` < 90 deg).

    Raises
    ------
    InputRangeError
        A zero edge radius (a sharp tip cuts no fillet: the flank runs to the root).
    """
    r_e = blade.edge_radius_mm
    if blade.relieved and r_e > 0.0:    # the round is tangent to the tip segment
        return edge_round(blade_segments(blade)[0].blade)
    if r_e <= 0.0:
        raise InputRangeError(f"{blade.where}.edge_radius_mm", r_e,
                              "> 0 for a root fillet (a sharp blade tip cuts no fillet surface:"
                              " the flank runs into the root)")
    a0 = math.radians(blade.blade_angle_deg)
    l_top = r_e * (1.0 - math.sin(a0)) / math.cos(a0)
    if blade.profile_radius_mm != 0.0 or blade.higher_order:
        from scipy.optimize import brentq   # here: scipy.optimize costs 0.3 s per process

        def gap(l_mm):
            _, z, alpha, _ = blade_profile(blade, l_mm)
            return float(z) + r_e * math.sin(float(alpha)) - r_e

        l_top = brentq(gap, 0.0, 4.0 * l_top + r_e, xtol=1e-15)
    rho, _, alpha, _ = (float(x) for x in blade_profile(blade, l_top))
    return EdgeRound(radius_mm=r_e, centre_radius_mm=rho + blade.sigma * r_e * math.cos(alpha),
                     top_length_mm=l_top, top_angle_rad=alpha, sigma=blade.sigma)


def _straight(blade: BladeSettings) -> bool:
    return blade.profile_radius_mm == 0.0 and not blade.higher_order and not blade.relieved


def _arc_at_depth(blade: BladeSettings, z_mm: float) -> float:
    """Arc length from the tip of the smooth ``blade`` at depth ``z_mm`` behind the tip
    plane (``z`` grows with ``l`` while ``|alpha| < 90 deg``)."""
    if _straight(blade):
        return z_mm / math.cos(math.radians(blade.blade_angle_deg))
    from scipy.optimize import brentq   # here: scipy.optimize costs 0.3 s per process

    return brentq(lambda l: float(blade_profile(blade, l)[1]) - z_mm, 0.0, 3.0 * z_mm + 1.0,
                  xtol=1e-14)


@dataclass(frozen=True)
class BladeSegment:
    """One smooth piece of a relieved blade's profile (docs/machine_settings.md sec. 1).

    Attributes
    ----------
    name : str
        ``"toprem"`` (from the tip to the Toprem kink), ``"main"`` or ``"flankrem"``
        (from the Flankrem kink to the top).
    blade : BladeSettings
        The smooth blade whose profile the segment follows; its profile continued past
        the segment's kinks is the blade that piece of the flank is generated with.
    depth_mm : tuple of float
        Depths behind the tip plane where the segment starts and ends (inf: the top).
    arc_mm : float
        Arc length from the relieved blade's tip where the segment starts, mm.
    own_arc_mm : float
        The same point's arc length on ``blade`` (from its own tip), mm.
    """

    name: str
    blade: BladeSettings
    depth_mm: tuple
    arc_mm: float
    own_arc_mm: float


def _smooth(blade: BladeSettings, **changes) -> BladeSettings:
    return dataclasses.replace(blade, toprem_angle_deg=0.0, toprem_depth_mm=0.0,
                               flankrem_angle_deg=0.0, flankrem_depth_mm=0.0, **changes)


def _relief_blade(main: BladeSettings, depth_mm: float, relief_deg: float, name: str):
    """The straight blade of a relief segment: the main profile's tangent at
    ``depth_mm`` turned by ``relief_deg`` away from the slot (into the cut tooth): the
    profile angle drops by it on the tip side (Toprem) and grows on the top side
    (Flankrem), module docstring of :func:`blade_segments`."""
    rho, _, alpha, _ = (float(x) for x in blade_profile(main, _arc_at_depth(main, depth_mm)))
    angle = math.degrees(alpha) + (-relief_deg if name == "toprem" else relief_deg)
    if not 0.0 <= angle < 45.0:
        key, a = f"{main.where}.{name}_angle_deg", math.degrees(alpha)
        raise InputRangeError(key, relief_deg,
                              f"[0, {a:.4f}] deg (the Toprem segment's profile angle "
                              f"{a:.4f} - relief must stay >= 0)" if name == "toprem" else
                              f"[0, {45.0 - a:.4f}) deg (the Flankrem segment's profile "
                              f"angle {a:.4f} + relief must stay < 45)")
    straight = BladeSettings(main.kind, angle, main.point_radius_mm, where=main.where)
    try:
        return blade_through_point(straight, rho_mm=rho, z_mm=depth_mm)
    except InputRangeError:
        # the segment's reference arc (its depth along the straight blade) left the
        # blade's 50 mm: name the key the user typed, not the derived one
        reach = 50.0 * math.cos(math.radians(angle))
        raise InputRangeError(f"{main.where}.{name}_depth_mm", depth_mm,
                              f"(0, {reach:.4f}] mm (the {name} segment's arc from the "
                              f"tip plane, depth / cos({angle:.4f} deg), stays within "
                              "the blade's 50 mm)") from None


def blade_segments(blade: BladeSettings) -> tuple:
    """The smooth :class:`BladeSegment` pieces of ``blade``, tip to top.

    Toprem: from the tip plane to the depth ``z_T = toprem_depth_mm`` the profile is the
    straight line through the main profile's point at ``z_T`` at the profile angle
    ``alpha(z_T) - delta_T``; Flankrem: from ``z_F`` upwards, the straight line at
    ``alpha(z_F) + delta_F``. Both turn the profile into the cut tooth (material
    removed, growing as ``s sin(delta)`` with the arc ``s`` from the kink); the main
    segment is the blade's own profile (its point radius that of the main profile
    continued to the tip plane). The tip segment carries the edge radius (the round is
    tangent to it), the others none. A blade without relief is one ``"main"`` segment.
    """
    got = blade.__dict__.get("_segments")
    if got is None:
        got = _segments(blade)
        object.__setattr__(blade, "_segments", got)
    return got


def _segments(blade: BladeSettings) -> tuple:
    main = _smooth(blade)
    if not blade.relieved:
        return (BladeSegment("main", main, (0.0, math.inf), 0.0, 0.0),)
    segs, arc, start = [], 0.0, 0.0
    top = math.inf
    if blade.flankrem_angle_deg != 0.0:
        top = blade.flankrem_depth_mm
    if blade.toprem_angle_deg != 0.0:
        z_t = blade.toprem_depth_mm
        tip = dataclasses.replace(_relief_blade(main, z_t, blade.toprem_angle_deg, "toprem"),
                                  edge_radius_mm=blade.edge_radius_mm)
        segs.append(BladeSegment("toprem", tip, (0.0, z_t), 0.0, 0.0))
        arc, start = _arc_at_depth(tip, z_t), z_t
    own = _arc_at_depth(main, start) if start > 0.0 else 0.0
    segs.append(BladeSegment("main", _smooth(blade, edge_radius_mm=0.0) if segs else main,
                             (start, top), arc, own))
    if top < math.inf:
        up = _relief_blade(main, top, blade.flankrem_angle_deg, "flankrem")
        segs.append(BladeSegment("flankrem", _smooth(up, edge_radius_mm=0.0), (top, math.inf),
                                 arc + _arc_at_depth(main, top) - own, _arc_at_depth(up, top)))
    return tuple(segs)


def _relieved_profile(blade: BladeSettings, l_mm):
    """:func:`blade_profile` of a relieved blade: each segment's smooth profile over its
    arc (:func:`blade_segments`)."""
    out = None
    for seg in blade_segments(blade):
        got = blade_profile(seg.blade, l_mm - seg.arc_mm + seg.own_arc_mm)
        out = got if out is None else tuple(np.where(l_mm >= seg.arc_mm, g, o)
                                            for g, o in zip(got, out))
    return out


def _check_reliefs(blade: BladeSettings) -> None:
    """Cross-checks of the relief keys (their ranges are checked by the caller)."""
    w = blade.where
    for name in ("toprem", "flankrem"):
        if getattr(blade, f"{name}_angle_deg") != 0.0 and getattr(blade, f"{name}_depth_mm") <= 0.0:
            raise InputRangeError(f"{w}.{name}_depth_mm", getattr(blade, f"{name}_depth_mm"),
                                  f"(0, 50] mm with {name}_angle_deg > 0 (the kink's depth "
                                  "behind the blade tip plane)")
    if (blade.toprem_angle_deg != 0.0 and blade.flankrem_angle_deg != 0.0
            and not blade.flankrem_depth_mm > blade.toprem_depth_mm):
        raise InputRangeError(f"{w}.flankrem_depth_mm", blade.flankrem_depth_mm,
                              f"> toprem_depth_mm = {blade.toprem_depth_mm} mm (the Flankrem "
                              "kink lies above the Toprem kink)")
    segs = blade_segments(blade)
    if blade.edge_radius_mm > 0.0:
        tip = segs[0]
        rnd = edge_round(tip.blade)
        z_top = float(blade_profile(tip.blade, rnd.top_length_mm)[1])
        if not z_top < tip.depth_mm[1]:
            key = "toprem" if tip.name == "toprem" else "flankrem"
            raise InputRangeError(f"{w}.{key}_depth_mm", getattr(blade, f"{key}_depth_mm"),
                                  f"> {z_top:.4f} mm (the depth where the edge round of "
                                  f"radius {blade.edge_radius_mm} mm meets the profile)")
