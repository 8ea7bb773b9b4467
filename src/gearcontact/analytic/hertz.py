"""Elliptical Hertz contact: the exact elliptic-integral solution and Hamrock–Brewe forms.

The gap near the point contact is ``g = A s^2 + B t^2`` with ``A``, ``B`` half the
relative principal curvatures in 1/mm (docs/hertz.md sec. 1); loads in N, E' = 2 E* in
MPa, lengths in mm, pressures in MPa.

* :func:`exact_elliptic_hertz` — exact, complete elliptic integrals in Carlson's
  symmetric form (docs/hertz.md sec. 2; Johnson 1985, sec. 4.2);
* :func:`hamrock_brewe_hertz` / :func:`hamrock_brewe_terms` — the simplified closed forms
  of Hamrock & Brewe (1983), the one implementation in the package (docs/hertz.md
  sec. 3; docs/spec.md sec. 6, Algorithm 3);
* :func:`circular_hertz` — the axisymmetric case ``A = B`` (docs/hertz.md sec. 4);
* :func:`line_contact_hertz` / :func:`line_contact_terms` — two-dimensional Hertz
  contact of a cylinder of length L (a contact ellipse longer than the flank, truncated
  by it; docs/hertz.md sec. 6), and :func:`line_contact_approach_mm`, the approach of
  that finite line on the two elastic half-spaces (docs/cylindrical.md sec. 10).

References are listed in docs/hertz.md sec. 5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import elliprd, elliprf

from ..validation import InputRangeError, check_array_finite, check_positive

__all__ = ["HertzContact", "LineContactHertz", "line_contact_hertz", "line_contact_terms",
           "line_contact_approach_mm", "exact_elliptic_hertz", "exact_ellipticity",
           "exact_curvature_ratio", "hamrock_brewe_hertz",
           "hamrock_brewe_hertz_array", "hamrock_brewe_terms", "circular_hertz",
           "hamrock_brewe_error_table", "HB_ERROR_RATIOS"]

_HALF_PI = 0.5 * math.pi
_HB_E = _HALF_PI - 1.0           # (pi/2 - 1), Hamrock–Brewe constant, dimensionless
_HB_K_EXP = 2.0 / math.pi        # k = alpha^(2/pi)
_THIRD = 1.0 / 3.0
_SIX_OVER_PI = 6.0 / math.pi
_THREE_OVER_PI = 3.0 / math.pi
_THREE_OVER_2PI = 1.5 / math.pi
_log = math.log
_exp = math.exp
_cbrt = math.cbrt          # Python >= 3.11


@dataclass(frozen=True)
class HertzContact:
    """Solution of an elliptical (or circular) Hertz point contact.

    Attributes
    ----------
    a_mm : float
        Major semi-axis of the contact ellipse, mm (along the A_min direction).
    b_mm : float
        Minor semi-axis, mm (``a_mm >= b_mm``).
    k : float
        Ellipticity ratio ``a/b >= 1``, dimensionless.
    p_max_mpa : float
        Peak (central) Hertzian pressure ``3W/(2 pi a b)``, MPa.
    approach_mm : float
        Rigid-body approach (mutual compression) delta of distant points, mm.
    eccentricity : float
        ``e = sqrt(1 - b^2/a^2)``, dimensionless, in [0, 1).
    elliptic_k : float
        Complete elliptic integral of the first kind K(e) (exact) or its Hamrock–Brewe
        approximation F, dimensionless.
    elliptic_e : float
        Complete elliptic integral of the second kind E(e) (exact) or its
        Hamrock–Brewe approximation E_e, dimensionless.
    r_eff_mm : float
        Hamrock's curvature-sum radius R, ``1/R = 1/R_x + 1/R_y``, mm.
    alpha : float
        Radius ratio ``R_x/R_y = B_max/A_min >= 1``, dimensionless.
    load_n : float
        Normal load W, N.
    """

    a_mm: float
    b_mm: float
    k: float
    p_max_mpa: float
    approach_mm: float
    eccentricity: float
    elliptic_k: float
    elliptic_e: float
    r_eff_mm: float
    alpha: float
    load_n: float

    @property
    def compliance_mm_per_n(self) -> float:
        """Contact compliance d(delta)/dW = 2 delta/(3 W), mm/N (delta ~ W^(2/3))."""
        return 2.0 * self.approach_mm / (3.0 * self.load_n)

    def pressure_mpa(self, x_mm, y_mm):
        """Hertz pressure ``p_max sqrt(1 - x^2/a^2 - y^2/b^2)``, 0 outside the ellipse.

        Parameters
        ----------
        x_mm, y_mm : float or array_like
            Coordinates from the contact centre along the major (A_min) and minor
            principal directions, mm.

        Returns
        -------
        float or ndarray
            Pressure in MPa (Johnson 1985, eq. 4.36).
        """
        u = 1.0 - (np.asarray(x_mm, dtype=float) / self.a_mm) ** 2 \
            - (np.asarray(y_mm, dtype=float) / self.b_mm) ** 2
        p = self.p_max_mpa * np.sqrt(np.maximum(u, 0.0))
        return float(p) if p.ndim == 0 else p

    @property
    def mean_pressure_mpa(self) -> float:
        """Mean contact pressure W/(pi a b) = (2/3) p_max, MPa."""
        return self.load_n / (math.pi * self.a_mm * self.b_mm)


def _check_inputs(A_per_mm, B_per_mm, load_n, e_prime_mpa):
    a = check_positive("A_per_mm", A_per_mm)
    b = check_positive("B_per_mm", B_per_mm)
    w = check_positive("load_n", load_n)
    e = check_positive("e_prime_mpa", e_prime_mpa)
    return (a, b, w, e) if a <= b else (b, a, w, e)


# ----------------------------------------------------------------------------------
# circular
# ----------------------------------------------------------------------------------
def circular_hertz(curvature_per_mm: float, load_n: float, *,
                   e_prime_mpa: float) -> HertzContact:
    """Axisymmetric Hertz contact for a gap ``g = A r^2`` (Johnson 1985, eqs. 4.22–4.23).

    Parameters
    ----------
    curvature_per_mm : float
        ``A = B`` in 1/mm (half the relative curvature; relative radius
        ``R_J = 1/(2A)``, e.g. a ball of radius r on a flat: ``A = 1/(2r)``).
    load_n : float
        Normal load W, N.
    e_prime_mpa : float
        Effective modulus E' = 2 E*, MPa.

    Returns
    -------
    HertzContact
        ``a = b = (3 W R_J/(4 E*))^(1/3)``, ``k = 1``, ``p_max = 3W/(2 pi a^2)``,
        ``delta = a^2/R_J``, ``K = E = pi/2``.
    """
    A = check_positive("curvature_per_mm", curvature_per_mm)
    w = check_positive("load_n", load_n)
    ep = check_positive("e_prime_mpa", e_prime_mpa)
    r_j = 0.5 / A
    e_star = 0.5 * ep
    a = (3.0 * w * r_j / (4.0 * e_star)) ** _THIRD
    return HertzContact(a_mm=a, b_mm=a, k=1.0, p_max_mpa=3.0 * w / (2.0 * math.pi * a * a),
                        approach_mm=a * a / r_j, eccentricity=0.0, elliptic_k=_HALF_PI,
                        elliptic_e=_HALF_PI, r_eff_mm=0.5 * r_j, alpha=1.0, load_n=w)


# ----------------------------------------------------------------------------------
# line contact
# ----------------------------------------------------------------------------------
@dataclass(frozen=True)
class LineContactHertz:
    """Hertz line contact of a cylinder of finite length (plane strain, no end effects).

    Attributes
    ----------
    p_max_mpa : float
        Peak pressure ``p0 = sqrt(W E* / (pi R L))``, MPa.
    b_mm : float
        Half-width of the contact strip ``b = sqrt(4 W R / (pi E* L))``, mm.
    half_length_mm : float
        ``L/2``, mm (the strip spans the whole length).
    load_per_length_n_per_mm : float
        ``q = W/L``, N/mm.
    radius_mm : float
        Reduced radius across the line ``R``, mm.
    load_n : float
        Normal load W, N.
    """

    p_max_mpa: float
    b_mm: float
    half_length_mm: float
    load_per_length_n_per_mm: float
    radius_mm: float
    load_n: float


def line_contact_hertz(radius_mm: float, load_n: float, length_mm: float, *,
                       e_prime_mpa: float) -> LineContactHertz:
    """Hertz line contact: load ``W`` spread over a contact line of length ``L``.

    The pressure across the strip is the semi-ellipse ``p0 sqrt(1 - x^2/b^2)`` with
    ``p0 = sqrt(W E* / (pi R L))`` and ``b = sqrt(4 W R / (pi E* L))`` (Johnson 1985,
    sec. 4.3, with the load per length P = W/L), so that ``pi p0 b L / 2 = W``. This is
    the contact of an elliptic Hertz gap whose ellipse is longer than the flank: the
    flank truncates it to L and the load is carried along the whole line.

    Parameters
    ----------
    radius_mm : float
        Reduced radius across the line, ``R = 1/(2 A)`` for the half relative curvature
        ``A`` across it, mm (> 0).
    load_n : float
        Normal load W, N (> 0).
    length_mm : float
        Contact length L, mm (> 0).
    e_prime_mpa : float
        Effective modulus E' = 2 E*, MPa (> 0).

    Returns
    -------
    LineContactHertz
    """
    r = check_positive("radius_mm", radius_mm)
    w = check_positive("load_n", load_n)
    length = check_positive("length_mm", length_mm)
    p0, b = line_contact_terms(0.5 / r, w, length, check_positive("e_prime_mpa", e_prime_mpa))
    return LineContactHertz(p_max_mpa=p0, b_mm=b, half_length_mm=0.5 * length,
                            load_per_length_n_per_mm=w / length, radius_mm=r, load_n=w)


def line_contact_terms(b_max: float, load_n: float, length_mm: float, e_prime_mpa: float):
    """Unchecked scalar kernel of :func:`line_contact_hertz` (pure ``math``; the twin
    compiles it): ``(p0 MPa, b mm)`` of the load ``W`` (N) on a line of length ``L``
    (mm) with the half relative curvature ``B_max = 1/(2R)`` (1/mm) across it::

        p0 = sqrt(W E' B_max / (pi L)),   b = 2 W / (pi L p0)

    The caller guarantees positive finite inputs."""
    p0 = math.sqrt(load_n * e_prime_mpa * b_max / (math.pi * length_mm))
    return p0, 2.0 * load_n / (math.pi * length_mm * p0)


def line_contact_approach_mm(load_n: float, length_mm: float, b_mm: float,
                             e_prime_mpa: float) -> float:
    """Approach (mm) of a Hertz line contact of finite length on two elastic half-spaces
    (unchecked, pure ``math``; the twin's line law compiles it)::

        delta = 4 W / (pi E' L) (ln(4 L / b) - 3/4)

    The load ``W`` (N) spread evenly along the line of length ``L`` (mm) with the
    semi-elliptic pressure of half-width ``b`` (mm) across it (:func:`line_contact_terms`);
    ``delta`` is the energy mean of the surface displacement, ``integral(p u dA) / W``:
    the Boussinesq displacement ``u = 1/(pi E*) integral(p / r dA)`` (Johnson 1985,
    eq. 3.20, E' = 2 E*) of the strip, with ``integral(dy / r) = 2 ln(L / |x|)`` along
    a line far from its ends (``L >> b``) averaged over it (``2 ln(2 L / |x|) - 2``), and
    the semicircle's logarithmic energy ``E[ln|x - x'|] = ln(b / 2) - 1/4`` across. Unlike
    the point contact's ``kappa W^(2/3)`` it depends on the length: a 2-D line has no
    finite approach (Johnson 1985, sec. 5.6), a finite one on the 3-D half-space has.
    The rigid cylinder of length L, whose pressure rises towards its ends, approaches by
    3.2-3.4 % more on the half-space LCP (tests/analytic/test_hertz.py). ``0 < b < 4 L
    e^(-3/4)`` and positive finite inputs are the caller's guarantee."""
    return (4.0 * load_n / (math.pi * e_prime_mpa * length_mm)
            * (math.log(4.0 * length_mm / b_mm) - 0.75))


# ----------------------------------------------------------------------------------
# exact elliptic
# ----------------------------------------------------------------------------------
def _ratio_of_p(p: float) -> float:
    """Curvature ratio B/A as a function of p = 1 - e^2 = (b/a)^2 (Johnson eq. 4.40).

    ``B/A = (E/(1-m) - K)/(K - E)``; with Carlson's forms this is
    ``(3 R_F/R_D - 1)/p`` where ``R_F = R_F(0, p, 1)``, ``R_D = R_D(0, p, 1)``.
    """
    return (3.0 * float(elliprf(0.0, p, 1.0)) / float(elliprd(0.0, p, 1.0)) - 1.0) / p


def _solve_p(lam: float) -> float:
    """``p = (b/a)^2`` of the exact solution for the curvature ratio ``lam > 1``
    (Brent's method on Johnson's eq. 4.40, relative tolerance 4 eps)."""
    from scipy.optimize import brentq   # here: scipy.optimize costs 0.3 s per process

    # k = a/b <= lam for lam >= 1 (k ~ lam^0.64), so p = 1/k^2 lies in [1/lam^2, 1).
    lo = 0.5 / (lam * lam)
    while _ratio_of_p(lo) <= lam:          # defensive widening; never taken in practice
        lo *= 0.25
    return brentq(lambda q: _ratio_of_p(q) - lam, lo, 1.0, xtol=1e-300,
                  rtol=4.0 * np.finfo(float).eps, maxiter=200)


def exact_ellipticity(alpha: float) -> tuple[float, float]:
    """Ellipticity ``k = a/b`` and ``E(e)`` of the exact Hertz solution for ``alpha``.

    Both depend on the curvature ratio ``alpha = B_max/A_min`` only (Johnson 1985,
    eq. 4.40). With them Hamrock's form ``a = (6 k^2 E W R/(pi E'))^(1/3)`` is exact
    (it is the identity ``a^3 = W R_D/(pi E' A_min)`` of :func:`exact_elliptic_hertz`
    rewritten with ``R = 1/(2 A_min (1 + alpha))``); the simplified forms replace
    these two functions by ``alpha^(2/pi)`` and ``1 + (pi/2 - 1)/alpha``.

    Parameters
    ----------
    alpha : float
        Radius ratio ``R_x/R_y >= 1``, dimensionless.

    Returns
    -------
    (k, E) : tuple of float
        ``k >= 1`` and the complete elliptic integral of the second kind ``E(m)``,
        ``m = 1 - 1/k^2`` (``(1, pi/2)`` at ``alpha = 1``), dimensionless.

    Raises
    ------
    InputRangeError
        ``alpha`` not finite or below 1.
    """
    lam = float(alpha)
    if not (math.isfinite(lam) and lam >= 1.0):
        raise InputRangeError("alpha", alpha, "a finite number >= 1")
    if lam == 1.0:
        return 1.0, _HALF_PI
    p = _solve_p(lam)
    rf = float(elliprf(0.0, p, 1.0))
    rd = float(elliprd(0.0, p, 1.0))
    return 1.0 / math.sqrt(p), rf - (1.0 - p) * rd / 3.0


def exact_curvature_ratio(axis_ratio: float) -> float:
    """Curvature ratio ``alpha = B_max/A_min`` whose exact Hertz ellipse has the axis
    ratio ``k = a/b`` (the inverse of :func:`exact_ellipticity`, explicit: Johnson 1985,
    eq. 4.40 evaluated at ``p = 1/k^2``; no equation to solve).

    Parameters
    ----------
    axis_ratio : float
        Ellipticity ``k = a/b >= 1``, dimensionless.

    Returns
    -------
    float
        ``alpha >= 1`` (1 at ``k = 1``), dimensionless.

    Raises
    ------
    InputRangeError
        ``axis_ratio`` not finite or below 1.
    """
    k = float(axis_ratio)
    if not (math.isfinite(k) and k >= 1.0):
        raise InputRangeError("axis_ratio", axis_ratio, "a finite number >= 1")
    return 1.0 if k == 1.0 else _ratio_of_p(1.0 / (k * k))


def exact_elliptic_hertz(A_per_mm: float, B_per_mm: float, load_n: float, *,
                         e_prime_mpa: float) -> HertzContact:
    """Exact Hertz solution of an elliptical point contact (complete elliptic integrals).

    Solves the eccentricity equation (Johnson 1985, eq. 4.40)

        B_max/A_min = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)),   m = e^2,

    by Brent's method in ``p = (b/a)^2`` to a relative tolerance of 4 eps (~9e-16), then

        a^3 = W R_D(0,p,1)/(pi E' A_min)   [= 3 W (K - E)/(pi E' e^2 A_min)],
        b = a sqrt(p),  p_max = 3W/(2 pi a b),  delta = 3 W K/(pi a E')

    (Johnson eqs. 4.39–4.41 with E* = E'/2; Harris & Kotzalas 2006, eqs. 6.31–6.41).
    ``A == B`` reduces exactly to :func:`circular_hertz`.

    Parameters
    ----------
    A_per_mm, B_per_mm : float
        Half relative principal curvatures (gap ``A s^2 + B t^2``), 1/mm, > 0; order is
        irrelevant (they are sorted).
    load_n : float
        Normal load W, N, > 0.
    e_prime_mpa : float
        Effective modulus E' = 2 E*, MPa, > 0.

    Returns
    -------
    HertzContact

    Raises
    ------
    InputRangeError
        Non-positive or non-finite curvature, load or modulus (naming the field).
    """
    a_min, b_max, w, ep = _check_inputs(A_per_mm, B_per_mm, load_n, e_prime_mpa)
    if a_min == b_max:
        return circular_hertz(a_min, w, e_prime_mpa=ep)
    lam = b_max / a_min
    p = _solve_p(lam)
    m = 1.0 - p
    rf = float(elliprf(0.0, p, 1.0))
    rd = float(elliprd(0.0, p, 1.0))
    kk = rf                                  # K(m)
    ee = rf - m * rd / 3.0                   # E(m)
    a = (w * rd / (math.pi * ep * a_min)) ** _THIRD
    b = a * math.sqrt(p)
    p0 = 3.0 * w / (2.0 * math.pi * a * b)
    delta = 3.0 * w * kk / (math.pi * a * ep)
    r_eff = 0.5 / (a_min + b_max)
    return HertzContact(a_mm=a, b_mm=b, k=a / b, p_max_mpa=p0, approach_mm=delta,
                        eccentricity=math.sqrt(m), elliptic_k=kk, elliptic_e=ee,
                        r_eff_mm=r_eff, alpha=lam, load_n=w)


# ----------------------------------------------------------------------------------
# Hamrock–Brewe
# ----------------------------------------------------------------------------------
def hamrock_brewe_terms(a_min: float, b_max: float, load_n: float, e_prime_mpa: float):
    """Unchecked scalar kernel of the simplified Hamrock–Brewe forms (pure ``math``).

    The caller guarantees ``0 < a_min <= b_max`` (1/mm), ``load_n > 0`` (N) and
    ``e_prime_mpa > 0`` (MPa), all finite. This is the single implementation of the
    formulas in the package; :func:`hamrock_brewe_hertz` and the stage D fp64 preview
    validate and then call it.

    Returns
    -------
    tuple of float
        ``(a_mm, b_mm, k, p_max_mpa, approach_mm, alpha, E_e, F, R_mm)``.
    """
    alpha = b_max / a_min                       # R_x/R_y
    r_eff = 0.5 / (a_min + b_max)               # 1/R = 2 A_min + 2 B_max
    ln_alpha = _log(alpha)
    k = _exp(_HB_K_EXP * ln_alpha)              # alpha^(2/pi)
    e_e = 1.0 + _HB_E / alpha
    f = _HALF_PI + _HB_E * ln_alpha
    a = _cbrt(_SIX_OVER_PI * k * k * e_e * load_n * r_eff / e_prime_mpa)
    b = a / k
    p_max = _THREE_OVER_2PI * load_n / (a * b)  # 3W/(2 pi a b)
    # delta = F (9/(2 E_e R) (W/(pi k E'))^2)^(1/3), rewritten with a as 3 W F/(pi a E')
    # (algebraically identical; saves the second cube root)
    delta = _THREE_OVER_PI * load_n * f / (a * e_prime_mpa)
    return a, b, k, p_max, delta, alpha, e_e, f, r_eff


def hamrock_brewe_hertz(A_per_mm: float, B_per_mm: float, load_n: float, *,
                        e_prime_mpa: float) -> HertzContact:
    """Simplified Hamrock–Brewe elliptical Hertz contact (docs/spec.md sec. 6, Algorithm 3).

    ``alpha = R_x/R_y``, ``k = alpha^(2/pi)``, ``E_e = 1 + (pi/2 - 1)/alpha``,
    ``F = pi/2 + (pi/2 - 1) ln alpha``, ``a = (6 k^2 E_e W R/(pi E'))^(1/3)``,
    ``b = a/k``, ``p_max = 3W/(2 pi a b)``,
    ``delta = F (9/(2 E_e R) (W/(pi k E'))^2)^(1/3)`` (Hamrock & Brewe 1983).
    Deviation from the exact solution: see :func:`hamrock_brewe_error_table`.

    Parameters
    ----------
    A_per_mm, B_per_mm : float
        Half relative principal curvatures, 1/mm, > 0 (sorted internally).
    load_n : float
        Normal load W, N, > 0.
    e_prime_mpa : float
        Effective modulus E' = 2 E*, MPa, > 0.

    Returns
    -------
    HertzContact

    Raises
    ------
    InputRangeError
        Non-positive or non-finite input (naming the field).
    """
    a_min, b_max, w, ep = _check_inputs(A_per_mm, B_per_mm, load_n, e_prime_mpa)
    a, b, k, p_max, delta, alpha, e_e, f, r_eff = hamrock_brewe_terms(a_min, b_max, w, ep)
    return HertzContact(a_mm=a, b_mm=b, k=k, p_max_mpa=p_max, approach_mm=delta,
                        eccentricity=math.sqrt(1.0 - 1.0 / (k * k)), elliptic_k=f,
                        elliptic_e=e_e, r_eff_mm=r_eff, alpha=alpha, load_n=w)


def hamrock_brewe_hertz_array(A_per_mm, B_per_mm, load_n, *, e_prime_mpa) -> dict:
    """Vectorized :func:`hamrock_brewe_hertz` over broadcastable numpy arrays.

    Parameters
    ----------
    A_per_mm, B_per_mm : array_like
        Half relative principal curvatures, 1/mm, > 0 (sorted elementwise).
    load_n : array_like
        Normal loads W, N, > 0.
    e_prime_mpa : float or array_like
        Effective modulus E' = 2 E*, MPa, > 0.

    Returns
    -------
    dict of str -> ndarray
        Keys ``a_mm, b_mm, k, p_max_mpa, approach_mm, alpha, elliptic_e, elliptic_k,
        r_eff_mm`` (same formulas as :func:`hamrock_brewe_terms`, numpy ufuncs).

    Raises
    ------
    InputRangeError
        First non-finite or non-positive entry, naming field and index.
    """
    arrs = []
    for name, v in (("A_per_mm", A_per_mm), ("B_per_mm", B_per_mm), ("load_n", load_n),
                    ("e_prime_mpa", e_prime_mpa)):
        x = check_array_finite(name, v)
        bad = ~(x > 0.0)
        if bad.any():
            idx = tuple(int(i) for i in np.argwhere(bad)[0])
            raise InputRangeError(f"{name}[{', '.join(map(str, idx))}]"
                                  if x.ndim else name, x[idx], "a finite number > 0")
        arrs.append(x)
    A, B, w, ep = np.broadcast_arrays(*arrs)
    a_min = np.minimum(A, B)
    b_max = np.maximum(A, B)
    alpha = b_max / a_min
    r_eff = 0.5 / (a_min + b_max)
    k = alpha ** _HB_K_EXP
    e_e = 1.0 + _HB_E / alpha
    f = _HALF_PI + _HB_E * np.log(alpha)
    a = np.cbrt(6.0 * k * k * e_e * w * r_eff / (math.pi * ep))
    b = a / k
    p_max = 3.0 * w / (2.0 * math.pi * a * b)
    delta = 3.0 * w * f / (math.pi * a * ep)          # = F (9/(2 E_e R) (W/(pi k E'))^2)^(1/3)
    return {"a_mm": a, "b_mm": b, "k": k, "p_max_mpa": p_max, "approach_mm": delta,
            "alpha": alpha, "elliptic_e": e_e, "elliptic_k": f, "r_eff_mm": r_eff}


#: Default curvature ratios of :func:`hamrock_brewe_error_table` (1 .. 100, log-spaced
#: plus the integers 2..10 where the deviation peaks).
HB_ERROR_RATIOS = tuple(sorted(set(
    [float(x) for x in np.round(np.geomspace(1.0, 100.0, 41), 10)]
    + [float(x) for x in range(2, 11)])))


def hamrock_brewe_error_table(ratios=HB_ERROR_RATIOS, *, load_n: float = 1000.0,
                              e_prime_mpa: float = 229_670.0,
                              a_min_per_mm: float = 0.01) -> list[dict]:
    """Relative deviation of the simplified Hamrock–Brewe forms from exact Hertz.

    For each curvature ratio ``alpha = B_max/A_min`` the signed relative errors
    ``(HB - exact)/exact`` of k, a, b, p_max and the approach, and of the contact
    stiffness ``dW/d(delta) = 3 W/(2 delta)`` at the same load (``delta_exact/delta_HB
    - 1``), are returned. The
    errors are independent of load, modulus and size (both solutions scale
    identically), so the defaults only fix a representative point.

    Documented envelope over alpha in [1, 100] (measured with this function and
    asserted in ``tests/analytic/test_hertz.py``): |err k| <= 3.81 % (peak at
    alpha ~ 8), |err a| <= 2.69 % (alpha ~ 7), |err b| <= 1.20 % (alpha ~ 9),
    |err p_max| <= 1.62 % (alpha ~ 5), |err delta| <= 4.1 % (largest at alpha = 100).
    All errors vanish at alpha = 1 and k, a, b, p_max are nearly exact (< 0.03 %)
    near alpha = 50, where the error changes sign (cf. Hamrock & Brewe 1983, who
    quote a few percent).

    Parameters
    ----------
    ratios : sequence of float
        Curvature ratios >= 1 (dimensionless).
    load_n : float
        Load W, N.
    e_prime_mpa : float
        Effective modulus, MPa.
    a_min_per_mm : float
        The smaller half-curvature A_min, 1/mm.

    Returns
    -------
    list of dict
        Rows ``{"ratio", "err_k", "err_a", "err_b", "err_p_max", "err_approach",
        "err_stiffness"}``. Beyond ratio 100 see :mod:`.hertz_range`.
    """
    rows = []
    for lam in ratios:
        lam = float(lam)
        if not (math.isfinite(lam) and lam >= 1.0):
            raise InputRangeError("ratios", lam, "finite numbers >= 1")
        ex = exact_elliptic_hertz(a_min_per_mm, lam * a_min_per_mm, load_n,
                                  e_prime_mpa=e_prime_mpa)
        hb = hamrock_brewe_hertz(a_min_per_mm, lam * a_min_per_mm, load_n,
                                 e_prime_mpa=e_prime_mpa)
        rows.append({"ratio": lam,
                     "err_k": hb.k / ex.k - 1.0,
                     "err_a": hb.a_mm / ex.a_mm - 1.0,
                     "err_b": hb.b_mm / ex.b_mm - 1.0,
                     "err_p_max": hb.p_max_mpa / ex.p_max_mpa - 1.0,
                     "err_approach": hb.approach_mm / ex.approach_mm - 1.0,
                     "err_stiffness": ex.approach_mm / hb.approach_mm - 1.0})
    return rows
