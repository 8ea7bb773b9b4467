"""The twin's fp64 cube root (:mod:`gearcontact.analytic.cube_root`).

Truth: the exact cube root in rational arithmetic (no libm): ``y`` is within ``k`` ulp
of ``x^(1/3)`` iff ``(y - k ulp)^3 <= x <= (y + k ulp)^3``. The C twin of the function
(``gc_hertz_fp64.c``) is compared with it bit for bit in tests/export/test_c_library.py.
"""

import math
import random
import sys
from fractions import Fraction

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
