"""The fillet-foundation compliance of a gear tooth: Sainsot, Velex & Duverger's 2-D
closed form, the independent truth of the root's share of the bending deflection
(docs/bending.md sec. 11).

A tooth loaded by a force F (per face width b) along its flank normal deflects as a
cantilever on its root section and, on top of that, because the body under the root
section deforms: the section translates and turns. Weber (1949) took the body as an
elastic half-plane loaded by the root section's stresses (linear bending plus constant
shear) and gave the deflection of the load point along the load; Sainsot, Velex &
Duverger (2004) replaced the half-plane by the gear body between the root circle r_f
and the bore r_int (Muskhelishvili's complex potentials for the ring, then a fit over
the tooth and body proportions)::

    delta_f / F = cos^2(alpha_m) / (E b) * [ L* (u_f / S_f)^2 + M* (u_f / S_f)
                                             + P* (1 + Q* tan^2(alpha_m)) ]

- ``S_f``: tooth thickness at the root circle (the arc between the two fillets' ends
  on it, ``S_f = 2 r_f theta_f``), ``theta_f`` its half angle;
- ``u_f``: distance from the root circle, along the tooth's centre line, to the point
  where the line of the load crosses it;
- ``alpha_m``: angle between the load and the normal to the centre line (the load's
  radial component compresses the root: the ``Q*`` term);
- ``X* = A / theta_f^2 + B h_f^2 + C h_f / theta_f + D / theta_f + E h_f + F`` for
  X = L, M, P, Q with ``h_f = r_f / r_int`` and the fitted coefficients of
  :data:`SAINSOT_COEFFICIENTS` (the paper's table; Poisson's ratio 0.3).

It is a 2-D formula (plane elasticity of the transverse section; the modulus E of the
paper's form, nu = 0.3 built into the fit): a 3-D tooth under a load over its face is
in plane strain only away from the face ends (its body then stiffer by up to
1 / (1 - nu^2) = 1.10), and softer near the free ends, where the section is in plane
stress; docs/bending.md sec. 11 states what else differs for the teeth compared.

References
----------
P. Sainsot, P. Velex, O. Duverger, "Contribution of gear body to tooth deflections - a
new bidimensional analytical formula", *J. Mech. Des.* 126(4), 2004, 748-752
(eq. 9 and table 1 of the fitted coefficients).
C. Weber, "The deformation of loaded gears and the effect on their load-carrying
capacity", Sponsored Research (Germany), British Dept. of Scientific and Industrial
Research, Report No. 3, 1949 (the half-plane foundation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..validation import InputRangeError, check_positive, check_range

__all__ = ["SAINSOT_COEFFICIENTS", "FoundationCoefficients", "foundation_coefficients",
           "fillet_foundation_compliance_mm_per_n"]

#: (A, B, C, D, E, F) of L*, M*, P*, Q* (Sainsot et al. 2004, table 1), dimensionless
#: (theta_f in rad).
SAINSOT_COEFFICIENTS = {
    "L": (-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045),
    "M": (60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086),
    "P": (-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236),
    "Q": (-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904),
}


@dataclass(frozen=True)
class FoundationCoefficients:
    """L*, M*, P*, Q* of one tooth and body (dimensionless), with their arguments."""

    l_star: float
    m_star: float
    p_star: float
    q_star: float
    h_f: float
    theta_f_rad: float


def foundation_coefficients(*, root_radius_mm: float, bore_radius_mm: float,
                            root_half_angle_rad: float) -> FoundationCoefficients:
    """The fitted L*, M*, P*, Q* at ``h_f = r_f / r_int`` and ``theta_f``.

    Parameters
    ----------
    root_radius_mm : float, keyword-only
        Root circle radius r_f, mm (> 0).
    bore_radius_mm : float, keyword-only
        Radius r_int of the body's inner (held) boundary, mm, in (0, r_f).
    root_half_angle_rad : float, keyword-only
        Half the tooth's angle at the root circle theta_f, rad, in (0, pi/2).

    Raises
    ------
    InputRangeError
        Out of range, or so far outside the fit's proportions that L*, M* or P* is not
        positive (the s0003 hypoid gear's normal section: theta_f = 0.005 rad, h_f =
        1.008 gives P* = -7.1).
    """
    r_f = check_positive("root_radius_mm", root_radius_mm)
    r_int = check_range("bore_radius_mm", bore_radius_mm, 0.0, r_f, lo_open=True,
                        hi_open=True)
    t = check_range("root_half_angle_rad", root_half_angle_rad, 0.0, 0.5 * math.pi,
                    lo_open=True, hi_open=True)
    h = r_f / r_int

    def fit(c):
        a, b, cc, d, e, f = c
        return a / t ** 2 + b * h ** 2 + cc * h / t + d / t + e * h + f

    got = {k: fit(c) for k, c in SAINSOT_COEFFICIENTS.items()}
    if min(got["L"], got["M"], got["P"]) <= 0.0:
        # far outside the proportions of the fit (a very thin tooth angle: the 1/theta^2
        # terms take over) the fitted functions change sign: no compliance to give
        raise InputRangeError("root_half_angle_rad", t,
                              f"a tooth and body inside the fit's domain (with h_f = "
                              f"{h:.4g}: L*, M*, P* = {got['L']:.3g}, {got['M']:.3g}, "
                              f"{got['P']:.3g}, all must be > 0)")
    return FoundationCoefficients(l_star=got["L"], m_star=got["M"], p_star=got["P"],
                                  q_star=got["Q"], h_f=h, theta_f_rad=t)


def fillet_foundation_compliance_mm_per_n(*, load_angle_rad: float, load_height_mm: float,
                                          root_thickness_mm: float, root_radius_mm: float,
                                          bore_radius_mm: float, face_width_mm: float,
                                          youngs_modulus_mpa: float) -> float:
    """Deflection of the load point along the load per unit load, mm/N (module docstring).

    Parameters
    ----------
    load_angle_rad : float, keyword-only
        alpha_m, rad, in (-pi/2, pi/2).
    load_height_mm : float, keyword-only
        u_f, mm (>= 0): from the root circle along the centre line to the load line.
    root_thickness_mm : float, keyword-only
        S_f, mm (> 0); ``theta_f = S_f / (2 r_f)``.
    root_radius_mm, bore_radius_mm : float, keyword-only
        r_f and r_int, mm (:func:`foundation_coefficients`).
    face_width_mm : float, keyword-only
        b, mm (> 0): the length of the face the load is spread over.
    youngs_modulus_mpa : float, keyword-only
        E, MPa (> 0).
    """
    a = check_range("load_angle_rad", load_angle_rad, -0.5 * math.pi, 0.5 * math.pi,
                    lo_open=True, hi_open=True)
    u = check_range("load_height_mm", load_height_mm, 0.0, math.inf)
    s = check_positive("root_thickness_mm", root_thickness_mm)
    r_f = check_positive("root_radius_mm", root_radius_mm)
    b = check_positive("face_width_mm", face_width_mm)
    e = check_positive("youngs_modulus_mpa", youngs_modulus_mpa)
    c = foundation_coefficients(root_radius_mm=r_f, bore_radius_mm=bore_radius_mm,
                                root_half_angle_rad=s / (2.0 * r_f))
    x = u / s
    return math.cos(a) ** 2 / (e * b) * (c.l_star * x * x + c.m_star * x
                                         + c.p_star * (1.0 + c.q_star * math.tan(a) ** 2))
