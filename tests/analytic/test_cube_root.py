"""The twin's fp64 cube root (:mod:`gearcontact.analytic.cube_root`).

Truth: the exact cube root in rational arithmetic (no libm): ``y`` is within ``k`` ulp
of ``x^(1/3)`` iff ``(y - k ulp)^3 <= x <= (y + k ulp)^3``. The C twin of the function
(``gc_hertz_fp64.c``) is compared with it bit for bit in tests/export/test_c_library.py.
"""

import math
import random
import sys
from fractions import Fraction

import numpy as np
import pytest
from numba import njit

from gearcontact.analytic.cube_root import cbrt_fraction, cbrt_positive, seed_coefficients


def _ulps(x: float, y: float) -> int:
    """The least k <= 6 with (y - k ulp)^3 <= x <= (y + k ulp)^3 (7 if none)."""
    ulp, fx, fy = Fraction(math.ulp(y)), Fraction(x), Fraction(y)
    return next((k for k in range(7) if (fy - k * ulp) ** 3 <= fx <= (fy + k * ulp) ** 3), 7)


def _inputs():
    rng = random.Random(11)
    xs = [math.ldexp(1.0, e) for e in range(-1022, 1024, 7)]
    xs += [float(n ** 3) for n in range(1, 60)] + [sys.float_info.min, sys.float_info.max]
    xs += [math.ldexp(1.0 + rng.random(), rng.randint(-1022, 1023)) for _ in range(3000)]
    return xs


def test_within_5_ulp_of_the_exact_root():
    """Every positive normal input of the sample (powers of two over the range, perfect
    cubes, the extremes, 3,000 random): within 5 ulp (the proof's bound, in
    gc_hertz_fp64.c); measured at most 4."""
    worst = max(_ulps(x, cbrt_positive(x)) for x in _inputs())
    assert worst <= 5, worst


def test_numba_compiles_the_same_bits():
    """Compiled by numba (as the twin's law takes it) every result equals the Python
    function's: the same IEEE operations in the same order, frexp and ldexp exact."""
    compiled = njit(cbrt_positive)
    assert all(compiled(x) == cbrt_positive(x) for x in _inputs())


def test_seed_error_below_2_pow_minus_18():
    """The seed polynomial against the exact root at 1,025 points of [1, 2] (relative
    error < 2^-18, the premise of the one Halley step), and 2^(r/3) to 2^-50."""
    poly, scale = seed_coefficients()
    for k in range(1025):
        m = Fraction(1) + Fraction(k, 1024)
        y = Fraction(0)
        for c in reversed(poly):
            y = y * (m - Fraction(3, 2)) + Fraction(c)
        assert abs(y ** 3 / m - 1) < Fraction(3, 2 ** 18)    # |y/m^(1/3) - 1| < 2^-18
    for r in range(3):
        assert abs(Fraction(scale[r]) - cbrt_fraction(Fraction(2 ** r))) <= Fraction(1, 2 ** 50)


@pytest.mark.parametrize("x", [0.0, 5e-324, 1e-310, math.inf])
def test_outside_the_normal_range_the_library_root(x):
    """Zero, subnormals and infinity go to the library's cube root (numpy's here)."""
    assert cbrt_positive(x) == pytest.approx(math.cbrt(x), rel=1e-15)


def _roots_ulps(codes):
    """Error in ulp of the compiled cube root of ``codes / 256`` against numpy's long
    double cube root (64-bit significand: 2^-11 ulp of a double, so the measured
    error is good to ~0.001 ulp)."""
    compiled = njit(cbrt_positive)

    @njit
    def roots(x):
        out = np.empty_like(x)
        for i in range(x.shape[0]):
            out[i] = compiled(x[i])
        return out

    x = codes.astype(np.float64) / 256.0
    y = roots(x)
    exact = np.cbrt(codes.astype(np.longdouble) / np.longdouble(256))
    return np.abs((y.astype(np.longdouble) - exact) / np.spacing(y).astype(np.longdouble))


needs_long_double = pytest.mark.skipif(np.finfo(np.longdouble).nmant < 63,
                                       reason="needs x87 long double (64-bit significand)")
#: The twin's golden kappa takes the cube root of the quantized evaluation load
#: W_code / 256, W_code in [2^8, 2^25] (1 N .. 2^17 N, :data:`gearcontact.twin.
#: contact_law.W_EVAL_MIN_N` and the datapath's load envelope).
KAPPA_LOAD_CODES = (2 ** 8, 2 ** 25)


@needs_long_double
def test_within_5_ulp_on_the_golden_kappa_loads():
    """Over the golden kappa's domain (W = W_code / 256, both ends and 100,000 random
    codes): within 5 ulp of the exact root (the proof's bound; measured 2.16 ulp)."""
    lo, hi = KAPPA_LOAD_CODES
    codes = np.concatenate([np.arange(lo, lo + 1000), np.arange(hi - 1000, hi + 1),
                            np.random.default_rng(3).integers(lo, hi + 1, 100_000)])
    assert _roots_ulps(codes).max() <= 5


@pytest.mark.slow
@needs_long_double
def test_within_5_ulp_on_every_golden_kappa_load():
    """Every one of the 2^25 - 2^8 + 1 codes (~60 s; measured 2.46 ulp)."""
    lo, hi = KAPPA_LOAD_CODES
    worst = max(float(_roots_ulps(np.arange(s, min(s + 2 ** 22, hi + 1))).max())
                for s in range(lo, hi + 1, 2 ** 22))
    assert worst <= 5, worst
