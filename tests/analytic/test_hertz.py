"""Tests of gearcontact.analytic.hertz against independent truth.

Truths used: hand-evaluated circular Hertz (Johnson 1985, eqs. 4.22-4.23), direct
numerical quadrature of the Hertz displacement integrals for an ellipsoidal pressure
(Johnson 1985, eq. 3.59 ff. -- no elliptic functions involved), scipy's ellipk/ellipe,
and invariants (scaling laws, symmetry).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import ellipe, ellipk

from gearcontact.analytic.hertz import (circular_hertz, exact_elliptic_hertz, exact_ellipticity,
                                        hamrock_brewe_error_table, hamrock_brewe_hertz,
                                        hamrock_brewe_hertz_array, line_contact_hertz)
from gearcontact.materials import STEEL, effective_modulus_mpa
from gearcontact.validation import InputRangeError

E_PRIME = effective_modulus_mpa(STEEL)   # 229,670 MPa for steel/steel


def test_effective_modulus_steel():
    # E' = 2E/(1-nu^2) = 2*209000/0.91 = 459340/2 ... = 229,670.3 MPa (docs/spec.md sec. 6).
    assert E_PRIME == pytest.approx(229_670.33, rel=1e-7)


def test_circular_steel_ball_hand_numbers():
    # Steel ball r = 10 mm on a steel flat, W = 1000 N. By hand:
    #   E* = 209000/(2*0.91) = 114,835.16 MPa, R = 10 mm,
    #   a^3 = 3 W R/(4 E*) = 30000/459,340.66 = 0.0653111 mm^3 -> a = 0.402713 mm,
    #   p0 = 3W/(2 pi a^2), delta = a^2/R.
    e_star = 209_000.0 / (2.0 * (1.0 - 0.3 ** 2))
    a_hand = (3.0 * 1000.0 * 10.0 / (4.0 * e_star)) ** (1.0 / 3.0)
    assert a_hand == pytest.approx(0.402713, rel=1e-5)   # printed 6 digits
    c = circular_hertz(1.0 / (2.0 * 10.0), 1000.0, e_prime_mpa=2.0 * e_star)
    # 1e-12: the same closed form evaluated in a different order, fp64 rounding only.
    assert c.a_mm == pytest.approx(a_hand, rel=1e-12)
    assert c.b_mm == c.a_mm and c.k == 1.0
    assert c.p_max_mpa == pytest.approx(3000.0 / (2 * math.pi * a_hand ** 2), rel=1e-12)
    assert c.approach_mm == pytest.approx(a_hand ** 2 / 10.0, rel=1e-12)
    assert c.p_max_mpa == pytest.approx(2944.09, rel=2e-6)   # 6-digit hand value
    # Johnson eq. 4.23: p0 = (6 W E*^2/(pi^3 R^2))^(1/3); rounding-level agreement.
    assert c.p_max_mpa == pytest.approx(
        (6 * 1000.0 * e_star ** 2 / (math.pi ** 3 * 100.0)) ** (1 / 3), rel=1e-12)


def test_exact_reduces_to_circular():
    c = circular_hertz(0.02, 500.0, e_prime_mpa=E_PRIME)
    e = exact_elliptic_hertz(0.02, 0.02, 500.0, e_prime_mpa=E_PRIME)
    assert e == c                                  # exact special case, bit-identical
    # continuity: ratio 1 + 1e-8 -> relative change O(1e-8); 1e-7 leaves 10x margin.
    n = exact_elliptic_hertz(0.02, 0.02 * (1 + 1e-8), 500.0, e_prime_mpa=E_PRIME)
    for f in ("a_mm", "b_mm", "p_max_mpa", "approach_mm"):
        assert getattr(n, f) == pytest.approx(getattr(c, f), rel=1e-7)


def test_hamrock_brewe_circular_is_exact():
    # alpha = 1: k = 1, E_e = 1 + (pi/2 - 1) = pi/2 = E(0), F = pi/2 = K(0) -> exact.
    c = circular_hertz(0.05, 2000.0, e_prime_mpa=E_PRIME)
    h = hamrock_brewe_hertz(0.05, 0.05, 2000.0, e_prime_mpa=E_PRIME)
    for f in ("a_mm", "b_mm", "p_max_mpa", "approach_mm", "k"):
        assert getattr(h, f) == pytest.approx(getattr(c, f), rel=1e-14)  # fp rounding


def _quadrature_curvatures(h, e_prime):
    """A, B, delta implied by an ellipsoidal pressure p0 sqrt(1-x^2/a^2-y^2/b^2).

    Johnson (1985) eq. 3.59ff: inside the ellipse
    u_z = (p0 a b/(2E*)) int_0^inf (1 - x^2/(a^2+w) - y^2/(b^2+w)) dw/sqrt((a^2+w)(b^2+w)w),
    so delta = u_z(0,0) and A, B are the x^2, y^2 coefficients. Substituting w = u^2
    removes the endpoint singularity.
    """
    a, b = h.a_mm, h.b_mm
    pre = h.p_max_mpa * a * b / e_prime          # p0 a b/(2 E*) with E* = E'/2
    opts = dict(epsabs=0.0, epsrel=1e-13, limit=400)
    ia = quad(lambda u: 2.0 / ((a * a + u * u) ** 1.5 * math.sqrt(b * b + u * u)),
              0, np.inf, **opts)[0]
    ib = quad(lambda u: 2.0 / ((b * b + u * u) ** 1.5 * math.sqrt(a * a + u * u)),
              0, np.inf, **opts)[0]
    idl = quad(lambda u: 2.0 / math.sqrt((a * a + u * u) * (b * b + u * u)),
               0, np.inf, **opts)[0]
    return pre * ia, pre * ib, pre * idl


@pytest.mark.parametrize("ratio", [1.001, 1.5, 3.0, 7.0, 20.0, 100.0, 1000.0])
def test_exact_against_quadrature(ratio):
    A = 0.0123
    h = exact_elliptic_hertz(A, ratio * A, 2500.0, e_prime_mpa=E_PRIME)
    qa, qb, qd = _quadrature_curvatures(h, E_PRIME)
    # quad at epsrel 1e-13 on smooth integrands; 1e-9 bounds quadrature + solver error.
    assert qa == pytest.approx(A, rel=1e-9)
    assert qb == pytest.approx(ratio * A, rel=1e-9)
    assert qd == pytest.approx(h.approach_mm, rel=1e-9)
    # load balance W = (2/3) pi a b p0 (definition of p0), rounding only.
    assert 2 / 3 * math.pi * h.a_mm * h.b_mm * h.p_max_mpa == pytest.approx(2500.0,
                                                                            rel=1e-13)


@pytest.mark.parametrize("ratio", [1.5, 8.0, 300.0])
def test_exact_elliptic_integrals_match_scipy(ratio):
    h = exact_elliptic_hertz(0.01, 0.01 * ratio, 100.0, e_prime_mpa=E_PRIME)
    m = h.eccentricity ** 2
    # Carlson forms vs scipy's ellipk/ellipe (parameter m = e^2): ~1e-13 expected
    # (ellipk loses digits as m -> 1; 1e-10 covers m up to 1 - 1e-5).
    assert h.elliptic_k == pytest.approx(float(ellipk(m)), rel=1e-10)
    assert h.elliptic_e == pytest.approx(float(ellipe(m)), rel=1e-10)
    # Johnson eq. 4.40 written with ellipk/ellipe
    lam = ((ellipe(m) / (1 - m)) - ellipk(m)) / (ellipk(m) - ellipe(m))
    assert lam == pytest.approx(ratio, rel=1e-9)


def test_exact_scaling_laws_and_symmetry():
    # a ~ W^(1/3), p ~ W^(1/3), delta ~ W^(2/3); a ~ E'^(-1/3); swap invariance.
    h1 = exact_elliptic_hertz(0.01, 0.05, 1000.0, e_prime_mpa=E_PRIME)
    h8 = exact_elliptic_hertz(0.05, 0.01, 8000.0, e_prime_mpa=E_PRIME)
    assert h8.a_mm == pytest.approx(2 * h1.a_mm, rel=1e-13)       # rounding only
    assert h8.p_max_mpa == pytest.approx(2 * h1.p_max_mpa, rel=1e-13)
    assert h8.approach_mm == pytest.approx(4 * h1.approach_mm, rel=1e-13)
    assert h8.k == pytest.approx(h1.k, rel=1e-15)


def test_hb_error_envelope():
    rows = hamrock_brewe_error_table()
    worst = {key: max(abs(r[key]) for r in rows)
             for key in ("err_k", "err_a", "err_b", "err_p_max", "err_approach")}
    # Documented envelope (docs/geometry.md sec. 5 and the docstring), each bound is the
    # measured maximum rounded up in the last quoted digit.
    assert 0.036 < worst["err_k"] <= 0.0381
    assert 0.025 < worst["err_a"] <= 0.0269
    assert 0.011 < worst["err_b"] <= 0.0120
    assert 0.015 < worst["err_p_max"] <= 0.0162
    assert worst["err_approach"] <= 0.0411
    peak_k = max(rows, key=lambda r: abs(r["err_k"]))["ratio"]
    peak_p = max(rows, key=lambda r: abs(r["err_p_max"]))["ratio"]
    assert 5.0 <= peak_k <= 10.0 and 4.0 <= peak_p <= 10.0
    near50 = min(rows, key=lambda r: abs(r["ratio"] - 50.0))
    assert abs(near50["err_k"]) < 1e-3 and abs(near50["err_p_max"]) < 1e-3
    assert rows[0]["ratio"] == 1.0 and abs(rows[0]["err_k"]) < 1e-15


def test_hb_array_matches_scalar():
    rng = np.random.default_rng(1)
    A = rng.uniform(1e-3, 1.0, 200)
    B = rng.uniform(1e-3, 1.0, 200)
    W = rng.uniform(10, 2e4, 200)
    arr = hamrock_brewe_hertz_array(A, B, W, e_prime_mpa=E_PRIME)
    for i in range(200):
        h = hamrock_brewe_hertz(A[i], B[i], W[i], e_prime_mpa=E_PRIME)
        # numpy cbrt vs ** (1/3) and vector pow: a few ulp; 1e-14 relative.
        assert arr["a_mm"][i] == pytest.approx(h.a_mm, rel=1e-14)
        assert arr["p_max_mpa"][i] == pytest.approx(h.p_max_mpa, rel=1e-14)
        assert arr["k"][i] == pytest.approx(h.k, rel=1e-14)
        assert arr["approach_mm"][i] == pytest.approx(h.approach_mm, rel=1e-14)


@pytest.mark.parametrize("fn", [exact_elliptic_hertz, hamrock_brewe_hertz])
@pytest.mark.parametrize("args,field", [
    ((0.0, 0.1, 10.0), "A_per_mm"), ((-0.1, 0.1, 10.0), "A_per_mm"),
    ((0.1, math.nan, 10.0), "B_per_mm"), ((0.1, math.inf, 10.0), "B_per_mm"),
    ((0.1, 0.2, 0.0), "load_n"), ((0.1, 0.2, -5.0), "load_n")])
def test_bad_inputs(fn, args, field):
    with pytest.raises(InputRangeError) as ei:
        fn(*args, e_prime_mpa=E_PRIME)
    assert ei.value.field == field


def test_bad_inputs_array_and_circular():
    with pytest.raises(InputRangeError, match=r"load_n\[1\]"):
        hamrock_brewe_hertz_array([0.1, 0.1], [0.2, 0.2], [1.0, -1.0],
                                  e_prime_mpa=E_PRIME)
    with pytest.raises(InputRangeError, match="e_prime_mpa"):
        circular_hertz(0.1, 1.0, e_prime_mpa=0.0)
    with pytest.raises(InputRangeError, match="ratios"):
        hamrock_brewe_error_table([0.5])


def test_pressure_field_integrates_to_load():
    from scipy.integrate import dblquad
    h = exact_elliptic_hertz(0.01, 0.2, 1200.0, e_prime_mpa=E_PRIME)
    a, b = h.a_mm, h.b_mm
    total = dblquad(lambda y, x: h.pressure_mpa(x, y), -a, a,
                    lambda x: -b * math.sqrt(max(0.0, 1 - (x / a) ** 2)),
                    lambda x: b * math.sqrt(max(0.0, 1 - (x / a) ** 2)),
                    epsabs=0.0, epsrel=1e-10)[0]
    # integral of the Hertz ellipsoid = (2/3) pi a b p0 = W; quadrature tolerance 1e-7
    assert total == pytest.approx(1200.0, rel=1e-7)
    assert h.pressure_mpa(0.0, 0.0) == h.p_max_mpa
    assert h.pressure_mpa(1.01 * a, 0.0) == 0.0 and h.pressure_mpa(0.0, 1.01 * b) == 0.0
    grid = h.pressure_mpa(np.array([0.0, 0.5 * a]), np.array([0.0, 0.0]))
    assert grid[1] == pytest.approx(h.p_max_mpa * math.sqrt(0.75), rel=1e-15)


@pytest.mark.parametrize("ratio", [1.0, 1.0001, 2.0, 8.0, 128.0])
def test_exact_ellipticity_is_the_hamrock_form_made_exact(ratio):
    """k and E of exact_ellipticity put into Hamrock's a = (6 k^2 E W R/(pi E'))^(1/3),
    b = a/k reproduce exact_elliptic_hertz (to rounding, 1e-13), and E = scipy's
    ellipe(1 - 1/k^2)."""
    k, e = exact_ellipticity(ratio)
    a_min, w, ep = 0.02, 700.0, 229_670.0
    ex = exact_elliptic_hertz(a_min, ratio * a_min, w, e_prime_mpa=ep)
    r = 0.5 / (a_min + ratio * a_min)
    a = (6.0 * k * k * e * w * r / (math.pi * ep)) ** (1.0 / 3.0)
    assert a == pytest.approx(ex.a_mm, rel=1e-13)
    assert a / k == pytest.approx(ex.b_mm, rel=1e-13)
    assert e == pytest.approx(float(ellipe(1.0 - 1.0 / (k * k))), rel=1e-13)


def test_exact_ellipticity_bad_alpha():
    for bad in (0.999, float("nan"), float("inf")):
        with pytest.raises(InputRangeError, match="alpha"):
            exact_ellipticity(bad)


@pytest.mark.parametrize("ratio, tol", [(1e3, 3e-4), (1e4, 3e-5), (1e5, 3e-6)])
def test_line_contact_is_the_long_ellipse_limit(ratio, tol):
    # Independent truth: the exact elliptic solution (Carlson integrals). Along the
    # centre strip of a long Hertz ellipse the pressure is a semi-ellipse of peak p0 and
    # half-width b carrying q = pi p0 b / 2 per mm; the Hertz line contact with that
    # load per length and R = 1/(2 B_max) must give the same p0 and b as ratio -> inf.
    # Measured deviation 0.23/ratio (2.2e-3 at 100, 2.3e-5 at 1e4): tol ~ 1.3x that.
    B = 0.1
    ex = exact_elliptic_hertz(B / ratio, B, 1000.0, e_prime_mpa=E_PRIME)
    q = math.pi * ex.p_max_mpa * ex.b_mm / 2.0
    lc = line_contact_hertz(0.5 / B, q * 10.0, 10.0, e_prime_mpa=E_PRIME)
    assert lc.p_max_mpa == pytest.approx(ex.p_max_mpa, rel=tol)
    assert lc.b_mm == pytest.approx(ex.b_mm, rel=tol)


def test_line_contact_closed_forms_and_inputs():
    # Johnson 1985 sec. 4.3 by hand: W = 1000 N, L = 10 mm, R = 10 mm, E* = 114 835 MPa:
    # p0 = sqrt(100 * 114835 / (10 pi)) = 604.6 MPa, b = sqrt(4 * 100 * 10 / (pi E*))
    lc = line_contact_hertz(10.0, 1000.0, 10.0, e_prime_mpa=E_PRIME)
    assert lc.p_max_mpa == pytest.approx(math.sqrt(100.0 * E_PRIME / 2 / (10.0 * math.pi)),
                                         rel=1e-14)
    assert lc.b_mm == pytest.approx(math.sqrt(4000.0 / (math.pi * E_PRIME / 2)), rel=1e-14)
    assert lc.half_length_mm == 5.0 and lc.load_per_length_n_per_mm == 100.0
    # equilibrium: the semi-elliptic strip carries the load
    assert math.pi * lc.p_max_mpa * lc.b_mm * 10.0 / 2.0 == pytest.approx(1000.0, rel=1e-14)
    for args, field in (((0.0, 1.0, 1.0), "radius_mm"), ((1.0, -1.0, 1.0), "load_n"),
                        ((1.0, 1.0, math.nan), "length_mm")):
        with pytest.raises(InputRangeError, match=field):
            line_contact_hertz(*args, e_prime_mpa=E_PRIME)


@pytest.mark.parametrize("radius, length, load", [(10.0, 20.0, 5000.0), (20.0, 30.0, 2000.0)])
def test_line_contact_approach_against_the_halfspace_lcp(radius, length, load):
    """The finite line's approach ``4 W/(pi E' L) (ln(4L/b) - 3/4)`` (the energy mean of
    the Boussinesq displacement of the uniform strip) against an independent solver: the
    half-space LCP (Love's rectangles, gearcontact.halfspace) of a rigid cylinder of
    length L, gap x^2/(2R), pressed by W. The LCP's pressure rises towards the line's
    sharp ends (its mid-line peak sits 4.5 % below p0), which adds to the approach:
    measured +3.4 % and +3.2 % at 48 x 200 cells (96 x 400: +3.3 %, the grid's share
    < 0.1 %), so the bound is 0 < LCP / formula - 1 < 5 %. The formula itself: the
    approach of the line contact's b at W (line_contact_terms) and the W ln W growth
    of a line (b ~ W^(1/2) at fixed L)."""
    from gearcontact.analytic.hertz import line_contact_approach_mm, line_contact_terms
    from gearcontact.halfspace.grid import TangentGrid
    from gearcontact.halfspace.lcp import solve_lcp

    p0, b = line_contact_terms(0.5 / radius, load, length, E_PRIME)
    assert 0.5 * math.pi * p0 * b * length == pytest.approx(load, rel=1e-14)
    x = np.linspace(-2.5 * b, 2.5 * b, 49)
    y = np.linspace(-0.5 * length, 0.5 * length, 201)
    xc = 0.5 * (x[1:] + x[:-1])
    gap = np.broadcast_to(xc[None, :] ** 2 / (2.0 * radius), (200, 48)).copy()
    res = solve_lcp(gap, TangentGrid.from_edges(x, y), load, e_star_mpa=0.5 * E_PRIME,
                    tol=1e-10)
    delta = line_contact_approach_mm(load, length, b, E_PRIME)
    assert 0.0 < res.delta_mm / delta - 1.0 < 0.05
    _, b2 = line_contact_terms(0.5 / radius, 2.0 * load, length, E_PRIME)
    assert b2 == pytest.approx(math.sqrt(2.0) * b, rel=1e-14)
    want = 2.0 * delta * (1.0 - math.log(2.0) / 2.0 / (math.log(4.0 * length / b) - 0.75))
    assert line_contact_approach_mm(2.0 * load, length, b2, E_PRIME) == pytest.approx(
        want, rel=1e-13)
