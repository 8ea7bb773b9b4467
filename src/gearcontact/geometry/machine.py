"""Cradle-type face-milling machine: blades, basic machine settings and their kinematics.

One flank of one member is cut (single indexing, face milling) by one blade of a
face-milling cutter mounted on the cradle of a generator (docs/machine_settings.md has
the figure and the sign table). Frames:

- cutter ``S_t``: origin at the cutter centre in the plane of the blade tips, ``z_t``
  the cutter axis pointing out of the cutter towards the work. A blade is a surface of
  revolution about ``z_t``; its profile in the axial half-plane at blade angle
  ``theta`` (``e_rho = cos(theta) x_t + sin(theta) y_t``) is, with the arc length ``l``
  from the tip and the profile angle ``alpha(l)`` (straight blade: ``alpha`` constant),

      x = rho(l) e_rho - z(l) z_t,   rho' = -sigma sin(alpha),   z' = cos(alpha),
      n = sigma cos(alpha) e_rho - sin(alpha) z_t

  (``sigma`` = +1 inside blade, -1 outside blade; ``n`` the unit normal out of the cut
  tooth into the slot). A curved blade (profile radius ``r_b``) has
  ``alpha(l) = alpha_0 + (l - l_ref) / r_b`` (``r_b > 0``: the blade bulges into the
  slot, a crowned profile on the cut tooth; ``alpha_0`` holds at ``l_ref``). A blade
  with a higher-order profile adds the cubic and quartic terms ``c_3``, ``c_4`` of
  the profile about ``l_ref`` (``s = l - l_ref``):

      alpha(l) = alpha_0 + s / r_b + c_3 s^2 / 2 + c_4 s^3 / 6

  (the profile's curvature ``1/r_b + c_3 s + c_4 s^2 / 2`` varies along the blade; the
  normal offset from the tangent at ``l_ref`` is ``s^2/(2 r_b) + c_3 s^3/6 + c_4 s^4/24``
  to first order, positive into the slot), integrated by Gauss-Legendre quadrature.
- machine ``S_m``: origin at the machine centre (the cradle axis meets the plane of
  the blade tips), ``z_m`` the cradle axis towards the work, ``x_m`` the projection of
  the work axis onto the cradle plane, ``y_m = z_m x x_m``.
- cradle: turned by the roll ``psi`` about ``z_m``; the cutter centre lies at radial
  distance ``S_r`` and cradle angle ``q`` (from ``x_m``, about ``z_m``); the cutter
  axis is tilted by ``i`` from the cradle axis towards the cradle-plane direction at
  angle ``q + j`` (``j`` = swivel): ``T_0 = Rz(q + j) Ry(i)``.
- work ``S_w``: origin at the work's pitch apex, ``z_w`` the work axis (apex -> back),
  ``x_w = (sin gamma_m, 0, -cos gamma_m)`` (the radial direction in the plane of the
  two axes, towards the cradle plane) at zero roll; the work axis is
  ``w = (cos gamma_m, 0, sin gamma_m)`` (``gamma_m`` = machine root angle) and the apex
  lies at ``A = X_D w + (X_B + V(psi)) z_m + E_m y_m`` (machine centre to back, sliding
  base with helical motion ``V``, blank offset).

Generating motion (Litvin & Fuentes 2004, sec. 20.3 / 21.4; Fan 2006): the cradle
turns by ``psi`` and the work by ``phi(psi) = R_a (psi - sum_k c_k psi^k / k!)`` about
``z_w`` (``R_a`` ratio of roll work/cradle, ``c_2 = 2C``, ``c_3 = 6D``, ... the
modified-roll coefficients as printed), so that a cutter point maps to the work as

    X_w(l, theta, psi) = Rz(-phi) B^T (Rz(psi) (C_0 + T_0 x_t) - A(psi))

(``B`` = columns ``x_w, y_w, w`` in ``S_m``). The generated flank is the envelope of
the blade surface in this motion: ``n_w . dX_w/dpsi = 0`` (equation of meshing,
Litvin & Fuentes 2004, sec. 6.1). ``R_a = 0`` without helical motion is a formate cut
(the flank is the blade surface itself).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 20-21
(face-milled spiral bevel and hypoid gears: head-cutter surfaces, machine-tool settings,
modified roll, tilted head cutter).
Q. Fan, "Computerized modeling and simulation of spiral bevel and hypoid gears
manufactured by Gleason face hobbing process", *ASME J. Mech. Des.* 128 (2006) 1315-1327
(universal generation model: radial, cradle angle, tilt, swivel, machine root, blank
offset, sliding base, helical motion, modified roll).
H. J. Stadtfeld, *Handbook of Bevel and Hypoid Gears: Calculation, Manufacturing,
Optimization*, Rochester Institute of Technology, 1993 (blade profiles beyond the
straight line: curved blades, Toprem and Flankrem reliefs, ground on a blade grinder).
Y.-P. Shih, Z.-H. Fong, "Flank modification methodology for face-hobbing hypoid gears
based on ease-off topology", *ASME J. Mech. Des.* 129 (2007) 1294-1302.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..validation import InputRangeError, check_finite, check_positive, check_range

__all__ = ["BLADE_KEYS", "BladeSettings", "EdgeRound", "HELICAL_KEYS", "MACHINE_KEYS", "MEMBERS",
           "MODIFIED_ROLL_KEYS", "MachineKinematics", "MachineSettings", "MachineSetup",
           "blade_point", "blade_profile", "blade_through_point", "edge_round", "mirror_setup",
           "setup_from_tables", "setup_to_tables"]

#: Members of a pair, in the order used by the pair format.
MEMBERS = ("gear", "pinion")

#: Largest |psi| (rad) the generating roll may reach; beyond it the cutter is far off
#: the work for any practical set-up (the modified-roll polynomial is a local series).
MAX_ROLL_RAD = 1.5


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
        Radius of the blade tip (the cutting edge at the tip plane), mm, > 0.
    edge_radius_mm : float
        Tip edge radius, mm, >= 0: the flank starts above the edge round.
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
    where: str = field(default="blade", compare=False, repr=False)

    def __post_init__(self):
        w = self.where
        if self.kind not in ("inside", "outside"):
            raise InputRangeError(f"{w}.kind", self.kind, "'inside' or 'outside'")
        check_range(f"{w}.blade_angle_deg", self.blade_angle_deg, 0.0, 45.0, hi_open=True)
        check_positive(f"{w}.point_radius_mm", self.point_radius_mm)
        check_range(f"{w}.edge_radius_mm", self.edge_radius_mm, 0.0, 0.5 * self.point_radius_mm)
        r = check_finite(f"{w}.profile_radius_mm", self.profile_radius_mm)
        if r != 0.0 and abs(r) < 10.0:
            raise InputRangeError(f"{w}.profile_radius_mm", r,
                                  "0 (straight blade) or |r| >= 10 mm")
        check_range(f"{w}.profile_reference_mm", self.profile_reference_mm, 0.0, 50.0)
        check_range(f"{w}.profile_cubic_per_mm2", self.profile_cubic_per_mm2, -1.0, 1.0)
        check_range(f"{w}.profile_quartic_per_mm3", self.profile_quartic_per_mm3, -1.0, 1.0)

    @property
    def sigma(self) -> float:
        """+1 for an inside blade, -1 for an outside blade."""
        return 1.0 if self.kind == "inside" else -1.0

    @property
    def higher_order(self) -> bool:
        """True for a blade with a cubic or quartic profile term."""
        return self.profile_cubic_per_mm2 != 0.0 or self.profile_quartic_per_mm3 != 0.0


@dataclass(frozen=True)
class MachineSettings:
    """Basic machine settings of a cradle-type generator (``[machine.<member>.<flank>]``).

    Lengths in mm, angles in degrees (signs: module docstring and
    docs/machine_settings.md).

    Parameters
    ----------
    radial_distance_mm : float
        S_r, cradle axis to cutter centre, mm, >= 0.
    cradle_angle_deg : float
        q, from x_m about z_m, degrees, in (-180, 180].
    machine_root_angle_deg : float
        gamma_m, work axis to cradle plane, degrees, in [-10, 90].
    machine_centre_to_back_mm : float
        X_D, apex position along the work axis from the machine centre, mm.
    sliding_base_mm : float
        X_B, along the cradle axis, mm.
    blank_offset_mm : float
        E_m, along y_m, mm.
    ratio_of_roll : float
        R_a = work rotation / cradle rotation; 0 = formate (no roll).
    modified_roll : tuple of float
        (2C, 6D, 24E, 120F): ``phi = R_a (psi - 2C psi^2/2 - 6D psi^3/6 - ...)``,
        1/rad^(k-1), each in [-100, 100].
    tilt_deg, swivel_deg : float
        Cutter tilt i in [0, 60] and swivel j in (-180, 180], degrees.
    helical_motion : tuple of float
        (V_1, V_2): sliding base during the roll ``V(psi) = V_1 psi + V_2 psi^2 / 2``,
        mm/rad^k, each in [-1000, 1000].
    """

    radial_distance_mm: float
    cradle_angle_deg: float
    machine_root_angle_deg: float
    machine_centre_to_back_mm: float = 0.0
    sliding_base_mm: float = 0.0
    blank_offset_mm: float = 0.0
    ratio_of_roll: float = 0.0
    modified_roll: tuple = ()
    tilt_deg: float = 0.0
    swivel_deg: float = 0.0
    helical_motion: tuple = ()
    where: str = field(default="machine", compare=False, repr=False)

    def __post_init__(self):
        w = self.where
        check_range(f"{w}.radial_distance_mm", self.radial_distance_mm, 0.0, 1000.0)
        check_range(f"{w}.cradle_angle_deg", self.cradle_angle_deg, -180.0, 180.0,
                    lo_open=True)
        check_range(f"{w}.machine_root_angle_deg", self.machine_root_angle_deg, -10.0, 90.0)
        for name in ("machine_centre_to_back_mm", "sliding_base_mm", "blank_offset_mm"):
            check_range(f"{w}.{name}", getattr(self, name), -1000.0, 1000.0)
        check_range(f"{w}.ratio_of_roll", self.ratio_of_roll, -100.0, 100.0)
        check_range(f"{w}.tilt_deg", self.tilt_deg, 0.0, 60.0)
        check_range(f"{w}.swivel_deg", self.swivel_deg, -180.0, 180.0, lo_open=True)
        for name, keys, lim in (("modified_roll", MODIFIED_ROLL_KEYS, 100.0),
                                ("helical_motion", HELICAL_KEYS, 1000.0)):
            vals = getattr(self, name)
            if len(vals) > len(keys):
                raise InputRangeError(f"{w}.{name}", list(vals),
                                      f"at most {len(keys)} coefficients ({', '.join(keys)})")
            for key, x in zip(keys, vals):
                check_range(f"{w}.{key}", x, -lim, lim)
            object.__setattr__(self, name, tuple(float(x) for x in vals))

    @property
    def formate(self) -> bool:
        """True for a formate cut: no roll and no helical motion."""
        return self.ratio_of_roll == 0.0 and not any(self.helical_motion)


@dataclass(frozen=True)
class MachineSetup:
    """The machine settings and the blade that cut one flank (``member``, ``side``)."""

    member: str
    side: str
    settings: MachineSettings
    blade: BladeSettings


def mirror_setup(setup: MachineSetup) -> MachineSetup:
    """The set-up of the mirror image (``y_m -> -y_m``, the plane of the cradle axis and
    the work axis): the cradle and the work turn the other way (``psi -> -psi``,
    ``phi -> -phi``), so the cradle angle, swivel and blank offset change sign, and so
    do the even-order modified-roll terms (2C, 24E) and the odd-order helical term
    (V_1); the ratio of roll, machine root, tilt, MCTB and sliding base stay. A
    left-hand pair's settings are those of its right-hand twin mirrored."""
    st = setup.settings
    flip = lambda vals, first: tuple(-x if (k + first) % 2 == 0 else x  # noqa: E731
                                     for k, x in enumerate(vals))
    return dataclasses.replace(setup, settings=dataclasses.replace(
        st, cradle_angle_deg=-st.cradle_angle_deg if st.cradle_angle_deg != 180.0 else 180.0,
        swivel_deg=-st.swivel_deg if st.swivel_deg != 180.0 else 180.0,
        blank_offset_mm=-st.blank_offset_mm, modified_roll=flip(st.modified_roll, 2),
        helical_motion=flip(st.helical_motion, 2)))


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

    def depth(l_ref):
        placed = dataclasses.replace(blade, profile_reference_mm=l_ref)
        return float(blade_profile(placed, l_ref)[1]) - z_mm

    l_ref = brentq(depth, 0.0, 3.0 * z_mm + 1.0, xtol=1e-14)
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


def _rz(angle):
    """Rotation matrices about z, (..., 3, 3)."""
    a = np.asarray(angle, dtype=float)
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1),
                     np.stack([z, z, o], -1)], -2)


def _series(psi, coeffs, first: int):
    """``sum_k coeffs[k] psi^(k + first) / (k + first)!`` and its psi-derivative."""
    val, der = np.zeros_like(psi), np.zeros_like(psi)
    for k, c in enumerate(coeffs):
        p = k + first
        val = val + c * psi ** p / math.factorial(p)
        der = der + c * psi ** (p - 1) / math.factorial(p - 1)
    return val, der


@dataclass(frozen=True, eq=False)
class MachineKinematics:
    """Cutter -> work motion of one machine set-up (module docstring).

    Parameters
    ----------
    settings : MachineSettings
    """

    settings: MachineSettings

    @property
    def _fixed(self):
        got = self.__dict__.get("_fixed_cache")
        if got is None:
            st = self.settings
            q, i, j = (math.radians(x) for x in (st.cradle_angle_deg, st.tilt_deg,
                                                  st.swivel_deg))
            g = math.radians(st.machine_root_angle_deg)
            c0 = st.radial_distance_mm * np.array([math.cos(q), math.sin(q), 0.0])
            ry = np.array([[math.cos(i), 0.0, math.sin(i)], [0.0, 1.0, 0.0],
                           [-math.sin(i), 0.0, math.cos(i)]])
            t0 = _rz(q + j) @ ry
            w = np.array([math.cos(g), 0.0, math.sin(g)])
            b = np.column_stack([[math.sin(g), 0.0, -math.cos(g)], [0.0, 1.0, 0.0], w])
            a0 = (st.machine_centre_to_back_mm * w + st.sliding_base_mm * np.array([0, 0, 1.0])
                  + st.blank_offset_mm * np.array([0, 1.0, 0]))
            got = (c0, t0, b, a0)
            object.__setattr__(self, "_fixed_cache", got)
        return got

    def work_rotation(self, psi_rad):
        """``(phi, dphi/dpsi)`` of the work for cradle roll ``psi`` (rad)."""
        st = self.settings
        psi = np.asarray(psi_rad, dtype=float)
        mod, dmod = _series(psi, st.modified_roll, 2)
        return st.ratio_of_roll * (psi - mod), st.ratio_of_roll * (1.0 - dmod)

    def cutter_to_machine(self, x_t):
        """Cutter-frame points (..., 3) in the machine frame at zero roll."""
        c0, t0, _, _ = self._fixed
        return np.asarray(x_t) @ t0.T + c0

    def to_work(self, x_t, n_t, psi_rad):
        """Cutter point and normal -> work frame at roll ``psi``, with the velocity.

        Returns
        -------
        x_w, n_w, v_w : ndarray (..., 3)
            Point (mm), unit normal and ``dX_w/dpsi`` at fixed cutter point (mm/rad).
        """
        c0, t0, b, a0 = self._fixed
        x_t, n_t, psi = np.asarray(x_t, dtype=float), np.asarray(n_t, dtype=float), np.asarray(
            psi_rad, dtype=float)
        shape = np.broadcast_shapes(x_t.shape[:-1], n_t.shape[:-1], psi.shape)
        psi = np.broadcast_to(psi, shape)
        x0 = np.broadcast_to(x_t @ t0.T + c0, shape + (3,))   # machine frame, zero roll
        n0 = np.broadcast_to(n_t @ t0.T, shape + (3,))
        c, s = np.cos(psi)[..., None], np.sin(psi)[..., None]
        hel, dhel = _series(psi, self.settings.helical_motion, 1)
        # cradle roll about z_m, then the apex (with helical motion) and the work axes
        xm = np.concatenate([c * x0[..., :1] - s * x0[..., 1:2], s * x0[..., :1] + c * x0[..., 1:2],
                             x0[..., 2:] - hel[..., None]], axis=-1) - a0
        nm = np.concatenate([c * n0[..., :1] - s * n0[..., 1:2], s * n0[..., :1] + c * n0[..., 1:2],
                             n0[..., 2:]], axis=-1)
        dxm = np.concatenate([-(xm[..., 1:2] + a0[1]), xm[..., :1] + a0[0],
                              -dhel[..., None]], axis=-1)
        phi, dphi = self.work_rotation(psi)
        cw, sw = np.cos(phi)[..., None], np.sin(phi)[..., None]

        def work(v):  # Rz(-phi) B^T v
            y = v @ b
            return np.concatenate([cw * y[..., :1] + sw * y[..., 1:2],
                                   -sw * y[..., :1] + cw * y[..., 1:2], y[..., 2:]], axis=-1)

        x_w, n_w, dx = work(xm), work(nm), work(dxm)
        v_w = dx + dphi[..., None] * np.concatenate([x_w[..., 1:2], -x_w[..., :1],
                                                     np.zeros_like(x_w[..., :1])], axis=-1)
        return x_w, n_w, v_w


# --------------------------------------------------------------------------- TOML

#: ``[machine.<member>.<flank>]`` keys -> (MachineSettings field, required). The
#: modified-roll and helical-motion series are spelled out key by key (printed values).
MACHINE_KEYS = {
    "radial_distance_mm": ("radial_distance_mm", True),
    "cradle_angle_deg": ("cradle_angle_deg", True),
    "machine_root_angle_deg": ("machine_root_angle_deg", True),
    "machine_centre_to_back_mm": ("machine_centre_to_back_mm", False),
    "sliding_base_mm": ("sliding_base_mm", False),
    "blank_offset_mm": ("blank_offset_mm", False),
    "ratio_of_roll": ("ratio_of_roll", False),
    "tilt_deg": ("tilt_deg", False),
    "swivel_deg": ("swivel_deg", False),
}
#: Modified roll 2C, 6D, 24E, 120F (1/rad, 1/rad^2, ...) and helical motion (mm/rad^k).
MODIFIED_ROLL_KEYS = ("modified_roll_2c_per_rad", "modified_roll_6d_per_rad2",
                      "modified_roll_24e_per_rad3", "modified_roll_120f_per_rad4")
HELICAL_KEYS = ("helical_motion_mm_per_rad", "helical_motion_mm_per_rad2")
#: ``[blade.<member>.<flank>]`` keys -> required.
BLADE_KEYS = {"kind": True, "blade_angle_deg": True, "point_radius_mm": True,
              "edge_radius_mm": False, "profile_radius_mm": False,
              "profile_reference_mm": False, "profile_cubic_per_mm2": False,
              "profile_quartic_per_mm3": False}
#: Blade keys written only when non-zero (a circular blade's table stays as it was).
_HIGHER_ORDER_KEYS = ("profile_cubic_per_mm2", "profile_quartic_per_mm3")


def _series_from(table: dict, keys: tuple) -> tuple:
    vals = [float(table.get(k, 0.0)) for k in keys]
    while vals and vals[-1] == 0.0:
        vals.pop()
    return tuple(vals)


def setup_from_tables(member: str, side: str, machine: dict, blade: dict) -> MachineSetup:
    """The :class:`MachineSetup` of typed (already type-checked) TOML tables
    ``[machine.<member>.<side>]`` and ``[blade.<member>.<side>]``; every value is
    range-checked here, naming the dotted key."""
    where = f"machine.{member}.{side}"
    settings = MachineSettings(
        **{field_: machine[key] for key, (field_, _) in MACHINE_KEYS.items() if key in machine},
        modified_roll=_series_from(machine, MODIFIED_ROLL_KEYS),
        helical_motion=_series_from(machine, HELICAL_KEYS), where=where)
    return MachineSetup(member, side, settings,
                        BladeSettings(**blade, where=f"blade.{member}.{side}"))


def setup_to_tables(setup: MachineSetup) -> tuple[dict, dict]:
    """``(machine table, blade table)`` of ``setup`` (inverse of :func:`setup_from_tables`)."""
    st, b = setup.settings, setup.blade
    machine = {key: float(getattr(st, field_)) for key, (field_, _) in MACHINE_KEYS.items()}
    for keys, vals in ((MODIFIED_ROLL_KEYS, st.modified_roll), (HELICAL_KEYS, st.helical_motion)):
        machine.update({k: float(v) for k, v in zip(keys, vals)})
    blade = {"kind": b.kind, **{k: float(getattr(b, k)) for k in BLADE_KEYS if k != "kind"
                                and (k not in _HIGHER_ORDER_KEYS or getattr(b, k) != 0.0)}}
    return machine, blade
