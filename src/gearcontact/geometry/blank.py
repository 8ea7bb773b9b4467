"""Pitch-cone (blank) design of a hypoid pair, ISO 23509 "Method 1" for Sigma = 90 deg.

Given the hypoid offset E, the ratio u = z2/z1, the gear mean pitch radius r2 (or the
gear mean cone distance R2), the pinion mean spiral angle beta1 and the cutter radius
r_c0, the pitch cones are fixed by (docs/geometry.md sec. 2; ISO 23509:2016 clause 6.2.2)

- cone tangency: ``cos(zeta_m) = sin(delta1)/cos(delta2)``,
  ``cos(eta) = sin(delta2)/cos(delta1)``;
- offset angle in the pitch plane: ``sin(zeta_mp) = sin(zeta_m)/cos(delta1)``;
- offset: ``E = r2 sin(zeta_m) + r1 sin(eta)``;
- spiral angles and ratio: ``beta1 - beta2 = zeta_mp``, ``u = r2 cos(beta2)/(r1 cos(beta1))``;
- the limit radius of curvature equals the cutter radius, ``rho_lim = r_c0``
  (face milling, ISO 23509 eq. (32), (33), (40)).

ISO 23509 iterates on approximate intermediate quantities (hypoid dimension factor K1,
...); here the same closed system is solved exactly (nested one-dimensional root
finding: the offset equation for zeta_m inside, ``rho_lim = r_c0`` for eta outside),
so beta1 is met exactly instead of to ISO's 0.01 convergence tolerance.

Tooth proportions follow ISO 23509 clause 7 with the depth factors of the pair:
``h_mw = k_d m_mn``, ``h_am2 = c_ham h_mw``, ``h_am1 = h_mw - h_am2``, ``c = k_c h_mw``,
``h_fm2 = h_am1 + c``, ``h_fm1 = h_am2 + c`` (uniform depth along the face).

Meshing-frame placement (docs/geometry.md sec. 1): the gear axis is +z through the origin,
the pinion axis is x through C1 = (0, -E, 0). The pitch point is
``P = (r2 cos zeta_m, -r2 sin zeta_m, r1 cos eta)``; the gear pitch apex lies on the
gear axis at ``z = P_z - R2 cos(delta2)`` and the pinion pitch apex on the pinion axis at
``x = P_x - R1 cos(delta1)`` (the gear body lies on the +z side of its face, the pinion
body on the +x side of its apex).

References
----------
ISO 23509:2016, *Bevel and hypoid gear geometry*, clauses 6.2.2 (Method 1) and 7,
Annex F.3 (sample hypoid pair).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., Cambridge
University Press, 2004, ch. 21 (hypoid pitch cones).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError, check_positive, check_range

__all__ = ["BlankDesign", "design_blank", "gear_top_land_mm", "limit_pressure_angle_rad",
           "limit_radius_mm"]

#: Largest gear mean pitch radius / mean cone distance accepted, mm.
MAX_GEAR_SIZE_MM = 5000.0
_SCAN_POINTS = 160  # samples used to bracket the roots (root isolation, then brentq)


@dataclass(frozen=True)
class BlankDesign:
    """Pitch-cone data of a hypoid pair at the mean point (index 1 pinion, 2 gear).

    Angles in degrees, lengths in mm. ``pitch_point_mm``, ``gear_apex_z_mm`` and
    ``pinion_apex_x_mm`` are in the meshing frame of :mod:`.kinematics`.
    """

    pinion_teeth: int
    gear_teeth: int
    ratio: float
    offset_mm: float
    pitch_angle_pinion_deg: float
    pitch_angle_gear_deg: float
    spiral_angle_pinion_deg: float
    spiral_angle_gear_deg: float
    mean_cone_distance_pinion_mm: float
    mean_cone_distance_gear_mm: float
    mean_pitch_radius_pinion_mm: float
    mean_pitch_radius_gear_mm: float
    offset_angle_axial_pinion_deg: float      # zeta_m
    offset_angle_axial_gear_deg: float        # eta
    offset_angle_pitch_plane_deg: float       # zeta_mp
    limit_pressure_angle_deg: float           # alpha_lim
    limit_radius_mm: float                    # rho_lim (= cutter radius)
    cutter_radius_mm: float
    mean_normal_module_mm: float
    working_depth_mm: float
    clearance_mm: float
    addendum_pinion_mm: float
    addendum_gear_mm: float
    dedendum_pinion_mm: float
    dedendum_gear_mm: float
    pressure_angle_drive_deg: float           # gear convex / pinion concave
    pressure_angle_coast_deg: float           # gear concave / pinion convex
    pitch_point_mm: tuple[float, float, float]
    gear_apex_z_mm: float
    pinion_apex_x_mm: float

    def as_dict(self) -> dict:
        """Plain-JSON view (lists for tuples, None for non-finite) plus grouped CLI keys."""
        def plain(v):
            if isinstance(v, tuple):
                return list(v)
            if isinstance(v, float) and not np.isfinite(v):
                return None  # e.g. rho_lim of a spiral bevel pair (no limit radius)
            return v
        out = {k: plain(v) for k, v in self.__dict__.items()}
        out["pitch_angles_deg"] = [self.pitch_angle_pinion_deg, self.pitch_angle_gear_deg]
        out["spiral_angles_deg"] = [self.spiral_angle_pinion_deg, self.spiral_angle_gear_deg]
        out["mean_cone_distances_mm"] = [self.mean_cone_distance_pinion_mm,
                                         self.mean_cone_distance_gear_mm]
        return out


def limit_pressure_angle_rad(d1: float, d2: float, zmp: float, b1: float, b2: float,
                             R1: float, R2: float) -> float:
    """Limit pressure angle alpha_lim (rad), ISO 23509 eq. (32); angles in rad, R in mm."""
    t1, t2 = np.tan(d1), np.tan(d2)
    return float(np.arctan(-t1 * t2 / np.cos(zmp)
                           * (R1 * np.sin(b1) - R2 * np.sin(b2)) / (R1 * t1 + R2 * t2)))


def limit_radius_mm(d1: float, d2: float, b1: float, b2: float, R1: float, R2: float,
                    alpha_lim: float) -> float:
    """Limit radius of curvature rho_lim (mm), ISO 23509 eq. (33); angles in rad."""
    num = (np.tan(b1) - np.tan(b2)) / np.cos(alpha_lim)
    den = (-np.tan(alpha_lim) * (np.tan(b1) / (R1 * np.tan(d1)) + np.tan(b2) / (R2 * np.tan(d2)))
           + 1.0 / (R1 * np.cos(b1)) - 1.0 / (R2 * np.cos(b2)))
    return float(num / den)


@dataclass(frozen=True)
class _Cones:
    d1: float
    d2: float
    zm: float
    eta: float
    zmp: float
    b2: float
    r1: float
    r2: float
    R1: float
    R2: float


def _cones(zm: float, eta: float, *, b1: float, u: float, r2: float | None,
           R2: float | None) -> _Cones:
    """Pitch cones from the two offset angles (all angles rad); see module docstring."""
    ce, cz = np.cos(eta), np.cos(zm)
    c2 = np.sqrt(np.sin(eta) ** 2 / (1.0 - (ce * cz) ** 2))
    d2 = np.arccos(c2)
    d1 = np.arcsin(cz * c2)
    zmp = np.arcsin(np.minimum(1.0, np.sin(zm) / np.cos(d1)))
    b2 = b1 - zmp
    r2v = r2 if r2 is not None else R2 * np.sin(d2)
    r1 = r2v * np.cos(b2) / (u * np.cos(b1))
    return _Cones(d1, d2, zm, eta, zmp, b2, r1, r2v, r1 / np.sin(d1), r2v / np.sin(d2))


def design_blank(*, pinion_teeth: int, gear_teeth: int, offset_mm: float,
                 pinion_spiral_angle_deg: float, cutter_radius_mm: float,
                 gear_mean_pitch_radius_mm: float | None = None,
                 gear_mean_cone_distance_mm: float | None = None,
                 shaft_angle_deg: float = 90.0,
                 working_depth_factor: float = 2.0, clearance_factor: float = 0.125,
                 gear_addendum_factor: float = 0.35,
                 pressure_angle_drive_deg: float = 20.0,
                 pressure_angle_coast_deg: float = 20.0,
                 limit_pressure_angle_factor: float = 1.0) -> BlankDesign:
    """Design the pitch cones and mean tooth proportions (ISO 23509 Method 1).

    Parameters
    ----------
    pinion_teeth, gear_teeth : int
        Tooth numbers z1 (>= 5) and z2 (>= z1; z2 = z1 is a miter pair).
    offset_mm : float
        Hypoid offset E, mm (>= 0; 0 gives a spiral bevel pair).
    pinion_spiral_angle_deg : float
        Pinion mean spiral angle beta1 (ISO beta_Delta1), degrees, in (0, 70).
    cutter_radius_mm : float
        Nominal cutter radius r_c0, mm; closes the design through rho_lim = r_c0.
    gear_mean_pitch_radius_mm, gear_mean_cone_distance_mm : float
        Exactly one of r2 = d_m2/2 or R2, mm.
    shaft_angle_deg : float
        Shaft angle Sigma, degrees; only 90 is supported.
    working_depth_factor, clearance_factor, gear_addendum_factor : float
        k_d (h_mw = k_d m_mn), k_c (c = k_c h_mw) and c_ham (h_am2 = c_ham h_mw),
        dimensionless (ISO 23509 clause 7).
    pressure_angle_drive_deg, pressure_angle_coast_deg : float
        Nominal design pressure angles alpha_dD, alpha_dC, degrees.
    limit_pressure_angle_factor : float
        f_alim: the generated pressure angles are alpha_nD = alpha_dD + f alpha_lim and
        alpha_nC = alpha_dC - f alpha_lim (ISO 23509 eq. (64), (65)).

    Returns
    -------
    BlankDesign

    Raises
    ------
    InputRangeError
        For impossible designs: too few teeth, an offset too large for the gear, a
        spiral angle inconsistent with the offset, or no cone set with rho_lim = r_c0.
    """
    if int(pinion_teeth) != pinion_teeth or pinion_teeth < 5:
        raise InputRangeError("pinion_teeth", pinion_teeth, "an integer >= 5")
    if int(gear_teeth) != gear_teeth or gear_teeth < pinion_teeth:
        raise InputRangeError("gear_teeth", gear_teeth,
                              f"an integer >= pinion_teeth = {pinion_teeth} (1:1 is a miter pair)")
    if abs(float(shaft_angle_deg) - 90.0) > 1e-12:
        raise InputRangeError("shaft_angle_deg", shaft_angle_deg, "exactly 90 (Method 1, Sigma = 90 deg)")
    E = check_range("offset_mm", offset_mm, 0.0, np.inf)
    b1 = np.radians(check_range("pinion_spiral_angle_deg", pinion_spiral_angle_deg, 0.0, 70.0,
                                lo_open=True))
    rc0 = check_positive("cutter_radius_mm", cutter_radius_mm)
    if (gear_mean_pitch_radius_mm is None) == (gear_mean_cone_distance_mm is None):
        raise InputRangeError("gear_mean_pitch_radius_mm / gear_mean_cone_distance_mm",
                              (gear_mean_pitch_radius_mm, gear_mean_cone_distance_mm),
                              "exactly one of the two given")
    # upper bound: a 5 m gear is beyond any bevel-gear cutting machine, and far beyond
    # it the cone equations lose all precision (NaN inside the root search)
    r2 = None if gear_mean_pitch_radius_mm is None else check_range(
        "gear_mean_pitch_radius_mm", gear_mean_pitch_radius_mm, 0.0, MAX_GEAR_SIZE_MM,
        lo_open=True)
    R2 = None if gear_mean_cone_distance_mm is None else check_range(
        "gear_mean_cone_distance_mm", gear_mean_cone_distance_mm, 0.0, MAX_GEAR_SIZE_MM,
        lo_open=True)
    size = r2 if r2 is not None else R2
    if E >= 0.5 * size:
        raise InputRangeError("offset_mm", offset_mm,
                              f"[0, {0.5 * size:g}) mm (less than half the gear mean pitch "
                              "radius / cone distance)")
    k_d = check_positive("working_depth_factor", working_depth_factor)
    k_c = check_range("clearance_factor", clearance_factor, 0.0, 0.5)
    c_ham = check_range("gear_addendum_factor", gear_addendum_factor, 0.0, 1.0, lo_open=True,
                        hi_open=True)
    a_d = check_range("pressure_angle_drive_deg", pressure_angle_drive_deg, 5.0, 40.0)
    a_c = check_range("pressure_angle_coast_deg", pressure_angle_coast_deg, 5.0, 40.0)
    f_lim = check_range("limit_pressure_angle_factor", limit_pressure_angle_factor, 0.0, 1.0)
    u = gear_teeth / pinion_teeth

    if E == 0.0:
        cones, alim = _bevel_cones(b1=b1, u=u, r2=r2, R2=R2), 0.0
    else:
        try:
            cones, alim = _solve_hypoid(E=E, b1=b1, u=u, r2=r2, R2=R2, rc0=rc0)
        except _NoCones:
            raise _blame_no_cones(E=E, b1=b1, z1=int(pinion_teeth), z2=int(gear_teeth), r2=r2,
                                  R2=R2, rc0=rc0) from None

    m_mn = 2.0 * cones.r2 * np.cos(cones.b2) / gear_teeth
    h_mw = k_d * m_mn
    h_am2 = c_ham * h_mw
    h_am1 = h_mw - h_am2
    c = k_c * h_mw
    alim_deg = float(np.degrees(alim))
    P = (cones.r2 * np.cos(cones.zm), -cones.r2 * np.sin(cones.zm), cones.r1 * np.cos(cones.eta))
    return BlankDesign(
        pinion_teeth=int(pinion_teeth), gear_teeth=int(gear_teeth), ratio=u, offset_mm=E,
        pitch_angle_pinion_deg=float(np.degrees(cones.d1)),
        pitch_angle_gear_deg=float(np.degrees(cones.d2)),
        spiral_angle_pinion_deg=float(np.degrees(b1)),
        spiral_angle_gear_deg=float(np.degrees(cones.b2)),
        mean_cone_distance_pinion_mm=float(cones.R1), mean_cone_distance_gear_mm=float(cones.R2),
        mean_pitch_radius_pinion_mm=float(cones.r1), mean_pitch_radius_gear_mm=float(cones.r2),
        offset_angle_axial_pinion_deg=float(np.degrees(cones.zm)),
        offset_angle_axial_gear_deg=float(np.degrees(cones.eta)),
        offset_angle_pitch_plane_deg=float(np.degrees(cones.zmp)),
        limit_pressure_angle_deg=alim_deg,
        limit_radius_mm=float(rc0 if E > 0 else np.inf), cutter_radius_mm=rc0,
        mean_normal_module_mm=float(m_mn), working_depth_mm=float(h_mw), clearance_mm=float(c),
        addendum_pinion_mm=float(h_am1), addendum_gear_mm=float(h_am2),
        dedendum_pinion_mm=float(h_am2 + c), dedendum_gear_mm=float(h_am1 + c),
        pressure_angle_drive_deg=a_d + f_lim * alim_deg,
        pressure_angle_coast_deg=a_c - f_lim * alim_deg,
        pitch_point_mm=tuple(float(x) for x in P),
        gear_apex_z_mm=float(P[2] - cones.R2 * np.cos(cones.d2)),
        pinion_apex_x_mm=float(P[0] - cones.R1 * np.cos(cones.d1)),
    )


def gear_top_land_mm(blank: BlankDesign, point_width_mm: float) -> float:
    """Mean normal top land of the formate gear tooth, mm (negative: pointed teeth).

    Rack approximation of the mean normal section: the gear slot is the blade profile,
    ``W`` wide at the root and widening by ``tan(alpha_nD) + tan(alpha_nC)`` per mm of
    height; with the normal circular pitch ``pi m_mn`` the tooth left between two slots
    has at the gear tip (height ``h_fm2 + h_am2`` above the root) the top land
    ``s_a2 = pi m_mn - W - (h_fm2 + h_am2) (tan alpha_nD + tan alpha_nC)``.
    (The conjugate pinion's top land is, in the same approximation,
    ``W + c (tan alpha_nD + tan alpha_nC) > 0``: never pointed.)
    """
    t = np.tan(np.radians(blank.pressure_angle_drive_deg)) + np.tan(
        np.radians(blank.pressure_angle_coast_deg))
    return float(np.pi * blank.mean_normal_module_mm - point_width_mm
                 - (blank.dedendum_gear_mm + blank.addendum_gear_mm) * t)


def _bevel_cones(*, b1: float, u: float, r2: float | None, R2: float | None) -> _Cones:
    """Spiral bevel limit (E = 0): tan(delta1) = 1/u, equal spiral angles (ISO Method 0)."""
    d1 = float(np.arctan(1.0 / u))
    d2 = 0.5 * np.pi - d1
    r2v = r2 if r2 is not None else R2 * np.sin(d2)
    r1 = r2v / u
    return _Cones(d1, d2, 0.0, 0.0, 0.0, b1, r1, r2v, r1 / np.sin(d1), r2v / np.sin(d2))


class _NoCones(ArithmeticError):
    """No pitch cones with rho_lim = r_c0 for the given data (diagnosed by the caller)."""


#: Ratios above this are unusual for hypoids (issue 28's design space is 1-10): when no
#: pitch cones exist there, the gear tooth number is blamed before the spiral angle.
_USUAL_MAX_RATIO = 10.0
#: Spiral angles tried when no pitch cones exist, deg (which input to blame).
_TRY_SPIRAL_DEG = (20.0, 30.0, 40.0, 50.0, 60.0)


def _blame_no_cones(*, E, b1, z1, z2, r2, R2, rc0) -> InputRangeError:
    """The input error for "no pitch cones with rho_lim = r_c0": the gear tooth number
    for a ratio above ``_USUAL_MAX_RATIO`` (naming the largest with cones at this spiral
    angle, by bisection), else the spiral angle when another one has cones (naming
    it), else the gear tooth number, else the offset."""
    kw = dict(E=E, r2=r2, R2=R2, rc0=rc0)

    def has(beta_rad, teeth):
        try:
            with np.errstate(all="ignore"):
                _solve_hypoid(b1=beta_rad, u=teeth / z1, **kw)
        except (_NoCones, InputRangeError):
            return False
        return True

    def fewer_teeth() -> InputRangeError:
        lo, hi = z1, z2   # has(lo) and not has(hi)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (mid, hi) if has(b1, mid) else (lo, mid)
        return InputRangeError("gear_teeth", z2,
                               f"<= {lo} (ratio {lo / z1:.4g}): beyond it no hypoid pitch "
                               f"cones with rho_lim = r_c0 exist at offset {E:g} mm and this "
                               "spiral angle")

    ratio_ok = has(b1, z1)
    if z2 / z1 > _USUAL_MAX_RATIO and ratio_ok:  # an unusual ratio: blame the teeth first
        return fewer_teeth()
    ok = [b for b in _TRY_SPIRAL_DEG if has(np.radians(b), z2)]
    if ok:
        best = min(ok, key=lambda b: abs(b - np.degrees(b1)))
        return InputRangeError("pinion_spiral_angle_deg / cutter_radius_mm",
                               (float(np.degrees(b1)), rc0),
                               "a combination for which pitch cones with rho_lim = r_c0 exist "
                               f"(e.g. pinion_spiral_angle_deg = {best:g}, or another cutter "
                               "radius)")
    if ratio_ok:
        return fewer_teeth()
    return InputRangeError("offset_mm", E, "a smaller offset: no hypoid pitch cones with "
                           "rho_lim = r_c0 exist for these teeth at any spiral angle tried")


def _sign_changes(x: np.ndarray, f: np.ndarray) -> list[tuple[float, float]]:
    """Brackets ``(x[i], x[i + 1])`` where the finite values ``f`` change sign."""
    ok = np.isfinite(f[:-1]) & np.isfinite(f[1:]) & (f[:-1] * f[1:] <= 0.0)
    return [(float(x[i]), float(x[i + 1])) for i in np.flatnonzero(ok)]


def _root(f, lo: float, hi: float) -> float | None:
    """The root of ``f`` in the bracket ``[lo, hi]`` (brentq), or None when ``f`` is
    undefined (NaN) somewhere brentq evaluates it (a division by zero on the way there
    is that case, not a warning)."""
    from scipy.optimize import brentq   # here: scipy.optimize costs 0.3 s per process

    try:
        with np.errstate(divide="ignore", invalid="ignore"):
            return brentq(f, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=200)
    except ValueError:
        return None


def _solve_hypoid(*, E: float, b1: float, u: float, r2: float | None, R2: float | None,
                  rc0: float) -> tuple[_Cones, float]:
    """Solve offset equation and rho_lim = r_c0 for (zeta_m, eta); returns cones, alpha_lim."""
    kw = dict(b1=b1, u=u, r2=r2, R2=R2)

    def zeta_for(eta: float) -> float | None:
        def off(zm):
            c = _cones(zm, eta, **kw)
            return c.r2 * np.sin(zm) + c.r1 * np.sin(eta) - E
        grid = np.linspace(1e-9, 0.5 * np.pi - 1e-6, _SCAN_POINTS)
        with np.errstate(all="ignore"):
            vals = off(grid)  # vectorized scan
        ok = np.isfinite(vals[:-1]) & np.isfinite(vals[1:]) & (vals[:-1] * vals[1:] <= 0.0)
        if not ok.any():
            return None
        i = int(np.argmax(ok))  # the smallest pinion offset angle that meets the offset
        # _root: a cone of the bracket may be flat (sin(delta) = 0 in the cone distances
        # the offset equation does not use): no RuntimeWarning on the user's screen
        return _root(off, grid[i], grid[i + 1])

    def residual(eta: float) -> float:
        zm = zeta_for(eta)
        if zm is None:
            return np.nan
        c = _cones(zm, eta, **kw)
        if not (c.b2 > -0.5 * np.pi and np.isfinite(c.R1)):
            return np.nan
        alim = limit_pressure_angle_rad(c.d1, c.d2, c.zmp, b1, c.b2, c.R1, c.R2)
        return limit_radius_mm(c.d1, c.d2, b1, c.b2, c.R1, c.R2, alim) - rc0

    etas = np.linspace(1e-6, np.radians(45.0), _SCAN_POINTS)
    with np.errstate(all="ignore"):
        vals = np.array([residual(e) for e in etas])
    roots = []
    for lo, hi in _sign_changes(etas, vals):
        root = _root(residual, lo, hi)
        if root is None:
            # undefined (NaN) inside the bracket: a sign change across a gap of the
            # domain; look for a root in the defined parts of a finer scan
            fine = np.linspace(lo, hi, _SCAN_POINTS)
            with np.errstate(all="ignore"):
                fine_vals = np.array([residual(e) for e in fine])
            sub = [r for a, b in _sign_changes(fine, fine_vals)
                   if (r := _root(residual, a, b)) is not None]
            if not sub:
                continue
            root = sub[0]
        if abs(residual(root)) < 1e-6 * rc0:  # a sign change through a pole is no root
            roots.append(root)
    if not roots:
        raise _NoCones()
    eta = roots[0]  # the smallest wheel offset angle: the ISO iteration's branch
    c = _cones(zeta_for(eta), eta, **kw)
    if c.b2 <= 0.0:
        raise InputRangeError("pinion_spiral_angle_deg", float(np.degrees(b1)),
                              f"> offset angle zeta_mp = {np.degrees(c.zmp):.3f} deg "
                              "(gear spiral angle beta2 = beta1 - zeta_mp must be > 0)")
    alim = limit_pressure_angle_rad(c.d1, c.d2, c.zmp, b1, c.b2, c.R1, c.R2)
    return c, alim
