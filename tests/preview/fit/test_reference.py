"""Tests of the fp64 stage-C reference (truth: exact quadratic gap fields)."""

import math

import numpy as np
import pytest

from gearcontact.preview.fit.pinv import baked_pinv
from gearcontact.preview.fit.reference import (HALF, fit_curvatures, fitted_coefficients,
                                              principal_curvatures, quadratic_weights)
from gearcontact.contract.stencil import STENCIL_SIDE
from gearcontact.validation import InputRangeError


def _angle_diff(a, b):
    """Difference of two axis directions modulo 180 deg, in [0, 90]."""
    d = abs(a - b) % 180.0
    return min(d, 180.0 - d)


def test_exact_quadratics_recovered(quadratics):
    # Truth: the field is an exact quadratic, least squares reproduces it exactly up to
    # fp64 rounding (|g| <= ~5 mm, cond(A^T A) ~ 40) -> 1e-10 relative is ~1e5 eps.
    for g, a, b, ang, c in quadratics(300, seed=1):
        fit = fit_curvatures(g)
        assert fit.A_minus_per_mm == pytest.approx(a, rel=1e-10)
        assert fit.B_minus_per_mm == pytest.approx(b, rel=1e-10)
        np.testing.assert_allclose(fit.coefficients[3:], c, rtol=0, atol=1e-12)
        assert fit.A_minus_per_mm >= fit.B_minus_per_mm
        assert fit.elliptic
        # residual of an exact quadratic is rounding noise only
        assert fit.residual_rms_mm < 1e-13
        if (a - b) / a > 1e-3:
            # the axis is defined; its error ~ eps/(A-B) relative, 1e-7 deg is ample
            assert _angle_diff(fit.angle_deg, ang) < 1e-7
        assert -90.0 < fit.angle_deg <= 90.0


def test_fitted_coefficients_of_many_stencils(quadratics):
    """The batched fit (the preview's and the twin's tables) on an array of stencils:
    the exact quadratics' c3, c4, c5 (1e-12 absolute, as above), row for row."""
    cases = list(quadratics(20, seed=3))
    gaps = np.array([g for g, *_ in cases]).reshape(4, 5, -1)
    c = fitted_coefficients(gaps)
    assert c.shape == (4, 5, 3)
    np.testing.assert_allclose(c.reshape(20, 3), [cc for *_, cc in cases], rtol=0, atol=1e-12)


def test_quadratic_coefficients_against_the_exact_sum(quadratics):
    """c3, c4, c5 against ``sum_i M_ji g_i`` summed exactly (fractions; M the baked
    weights, g the samples as given) on near-cylindrical gear-like stencils: offset
    0.1 mm, slopes 0.05, A- 1e-3 .. 1e-2, B- 2e-4 .. 1e-3 1/mm (the chain vectors'
    worst cases of the BLAS sum), samples on the stencil ROM's 2^-21 mm grid (so that
    g_i - g0 is exact). Bound: the rounding of the eight operations a product passes
    through (its multiply, the add of the skew term, three levels of groups, two of
    lanes, + total g0: gamma_8 ~ 8 u) on sum_i |pair_ji d_i| + |skew_ji e_i| + |total_j
    g0|, the second differences' scale. B- from the rounded coefficients against B- from
    the exact sums (rounded to doubles, the same closed form): an eigenvalue of
    [[c3, c4/2], [c4/2, c5]] moves by at most the coefficients' errors (Weyl:
    |dc3| + |dc4| + |dc5|), plus the closed form's roundings on both sides (det / A-:
    ~4 u A- each, 16 u A- allowed). Measured: 3.5e-14 of B- at worst; the tap-by-tap
    BLAS sum, whose rounding is ~1e-16 of sum_i |M_ji g_i| (the offset and slopes),
    1.7e-12 on the same stencils (docs/export.md, "fp64 equivalence")."""
    from fractions import Fraction
    m = baked_pinv().weights[3:6]
    w = quadratic_weights()
    u = 2.0 ** -53
    rng = np.random.default_rng(11)
    elliptic = 0
    for g, *_ in quadratics(200, seed=5, lo=2e-4, hi=1e-2, offset_mm=0.1, slope=0.05):
        # higher-order terms of 1e-6 mm, on the stencil ROM's grid
        g = np.ldexp(np.round(np.ldexp(g + rng.uniform(-1e-6, 1e-6, g.shape), 21)), -21)
        exact = [sum(Fraction(float(a)) * Fraction(float(x)) for a, x in zip(row, g))
                 for row in m]
        c = fitted_coefficients(g)
        g0 = g[HALF]
        e = g[:HALF:-1] - g0
        d = (g[:HALF] - g0) + e
        bound = 8 * u * ((np.abs(w.pair * d) + np.abs(w.skew * e)).sum(axis=1)
                         + np.abs(w.total * g0))
        assert all(abs(Fraction(float(x)) - y) <= b for x, y, b in zip(c, exact, bound))
        a_ref, b_ref, _ = principal_curvatures(*map(float, exact))
        if b_ref > 0:
            elliptic += 1
            assert abs(principal_curvatures(*c)[1] - b_ref) <= bound.sum() + 16 * u * a_ref
    assert elliptic >= 150


def test_rotation_by_90_deg_is_invariant(quadratics):
    # Rotating the sampled field by 90 deg maps the 7x7 grid onto itself
    # (s, t) -> (-t, s): eigenvalues must be unchanged (1e-12 relative, fp64) and the
    # A- axis must turn by 90 deg.
    for g, a, b, ang, _ in quadratics(50, seed=2):
        grid = g.reshape(STENCIL_SIDE, STENCIL_SIDE)   # [j (t), k (s)]
        rot = np.rot90(grid).ravel()
        f0, f1 = fit_curvatures(g), fit_curvatures(rot)
        assert f1.A_minus_per_mm == pytest.approx(f0.A_minus_per_mm, rel=1e-12)
        assert f1.B_minus_per_mm == pytest.approx(f0.B_minus_per_mm, rel=1e-12)
        if (a - b) / a > 1e-3:
            assert _angle_diff(f1.angle_deg, f0.angle_deg + 90.0) < 1e-7 or \
                _angle_diff(f1.angle_deg, f0.angle_deg - 90.0) < 1e-7


def test_other_spacing(quadratic):
    g, c = quadratic(0.2, 0.01, 30.0, 0.01, 0.02, -0.03, spacing_mm=0.25)
    fit = fit_curvatures(g, spacing_mm=0.25)
    assert fit.A_minus_per_mm == pytest.approx(0.2, rel=1e-10)
    assert fit.B_minus_per_mm == pytest.approx(0.01, rel=1e-10)
    assert fit.angle_deg == pytest.approx(30.0, abs=1e-8)


def test_saddle_and_flat_are_not_elliptic(quadratic):
    g, _ = quadratic(0.1, -0.05, 10.0)
    fit = fit_curvatures(g)
    assert not fit.elliptic
    assert fit.B_minus_per_mm == pytest.approx(-0.05, rel=1e-10)
    assert not fit_curvatures(np.zeros(49)).elliptic


def test_principal_curvatures_closed_form():
    # [[2, 1], [1, 2]]: eigenvalues 3 and 1, A- axis at 45 deg (exact)
    a, b, ang = principal_curvatures(2.0, 2.0, 2.0)
    assert (a, b) == pytest.approx((3.0, 1.0), rel=1e-15)
    assert ang == pytest.approx(45.0, abs=1e-12)
    # cancellation-free small eigenvalue: A = 1, B = 1e-9 at 30 deg, 1e-6 relative
    co, si = math.cos(math.radians(30)), math.sin(math.radians(30))
    a, b, _ = principal_curvatures(co * co + 1e-9 * si * si, 2 * (1 - 1e-9) * si * co,
                                   si * si + 1e-9 * co * co)
    assert b == pytest.approx(1e-9, rel=1e-6)
    # both negative (concave): still ordered
    a, b, _ = principal_curvatures(-1.0, 0.0, -2.0)
    assert (a, b) == (-1.0, -2.0)


def test_principal_curvatures_root_of_squares_and_its_fallback():
    """The root from the squares (the common range) and ``hypot`` where the squares
    would overflow: numpy's symmetric eigen-solver (LAPACK) as the truth, 1e-14
    relative (a few roundings; LAPACK's own error is of the same order), on 200 seeded
    matrices with entries from 1e-6 to 1e3; and [[1e200, 0], [0, -1e-200]], whose
    (c3 - c5)^2 overflows (the root of the squares alone gives inf and -0), exactly."""
    rng = np.random.default_rng(3)
    for c3, c4, c5 in 10.0 ** rng.uniform(-6, 3, (200, 3)) * rng.choice([-1, 1], (200, 3)):
        a, b, _ = principal_curvatures(c3, c4, c5)
        lo, hi = np.linalg.eigvalsh([[c3, 0.5 * c4], [0.5 * c4, c5]])
        scale = max(abs(lo), abs(hi))
        assert abs(a - hi) <= 1e-14 * scale and abs(b - lo) <= 1e-14 * scale
    assert principal_curvatures(1e200, 0.0, -1e-200)[:2] == (1e200, -1e-200)


@pytest.mark.parametrize("bad, field", [
    (np.zeros(48), "gaps_mm.shape"),
    (np.zeros((7, 7)), "gaps_mm.shape"),
    (np.r_[np.zeros(10), np.nan, np.zeros(38)], r"gaps_mm\[10\]"),
    (np.r_[np.inf, np.zeros(48)], r"gaps_mm\[0\]"),
])
def test_bad_input_names_field(bad, field):
    with pytest.raises(InputRangeError, match=field):
        fit_curvatures(bad)


def test_bad_spacing():
    with pytest.raises(InputRangeError, match="spacing_mm"):
        fit_curvatures(np.zeros(49), spacing_mm=-0.5)
