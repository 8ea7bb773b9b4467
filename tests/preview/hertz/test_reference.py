"""fp64 stage-D reference: formulas, invariants, envelope and error handling.

Truths: the analytic Hamrock-Brewe and circular Hertz solutions
(gearcontact.analytic.hertz, tested there against quadrature), exact scaling laws.
"""

import math

import numpy as np
import pytest

from gearcontact.analytic.hertz import circular_hertz, hamrock_brewe_hertz
from gearcontact.preview.hertz.reference import (ENVELOPE, HertzPreview, hertz_preview,
                                                 hertz_preview_array)
from gearcontact.validation import InputRangeError

from .conftest import E_PRIMES, accuracy_domain

EP = E_PRIMES["steel"]


def test_matches_analytic_hamrock_brewe():
    p = hertz_preview(0.5, 0.01, 1500.0, e_prime_mpa=EP)
    h = hamrock_brewe_hertz(0.5, 0.01, 1500.0, e_prime_mpa=EP)
    # the same kernel: bit-identical
    assert (p.a_mm, p.b_mm, p.k, p.p_max_mpa, p.approach_mm, p.alpha) == \
        (h.a_mm, h.b_mm, h.k, h.p_max_mpa, h.approach_mm, h.alpha)
    assert p.R_x_mm == 50.0 and p.R_y_mm == 1.0 and p.alpha == 50.0
    assert isinstance(p, HertzPreview)


def test_circular_limit():
    p = hertz_preview(0.04, 0.04, 800.0, e_prime_mpa=EP)
    c = circular_hertz(0.04, 800.0, e_prime_mpa=EP)
    assert p.alpha == 1.0 and p.k == 1.0 and p.a_mm == p.b_mm
    # HB is exact at alpha = 1 (E_e = F = pi/2); fp64 rounding only
    assert p.a_mm == pytest.approx(c.a_mm, rel=1e-14)
    assert p.p_max_mpa == pytest.approx(c.p_max_mpa, rel=1e-14)
    assert p.approach_mm == pytest.approx(c.approach_mm, rel=1e-14)


def test_load_scaling_and_swap():
    A, B, W = accuracy_domain(200, seed=3)
    for a, b, w in zip(A, B, W):
        p1 = hertz_preview(a, b, w / 8.0, e_prime_mpa=EP)
        p8 = hertz_preview(a, b, w, e_prime_mpa=EP)
        # p_max ~ W^(1/3), a, b ~ W^(1/3), delta ~ W^(2/3): fp64 rounding only (1e-12)
        assert p8.p_max_mpa == pytest.approx(2.0 * p1.p_max_mpa, rel=1e-12)
        assert p8.a_mm == pytest.approx(2.0 * p1.a_mm, rel=1e-12)
        assert p8.approach_mm == pytest.approx(4.0 * p1.approach_mm, rel=1e-12)
        assert hertz_preview(b, a, w, e_prime_mpa=EP) == p8         # swap: identical


def test_array_matches_scalar():
    A, B, W = accuracy_domain(500, seed=4)
    arr = hertz_preview_array(A, B, W, e_prime_mpa=EP)
    for i in range(0, 500, 7):
        p = hertz_preview(A[i], B[i], W[i], e_prime_mpa=EP)
        for f in ("a_mm", "b_mm", "k", "p_max_mpa", "alpha", "R_x_mm", "R_y_mm",
                  "approach_mm"):
            # numpy cbrt/power vs math pow/exp: a few ulp -> 1e-14
            assert arr[f][i] == pytest.approx(getattr(p, f), rel=1e-14), f


@pytest.mark.parametrize("args,field", [
    ((0.0, 0.1, 10.0, EP), "A_minus"), ((0.1, -0.1, 10.0, EP), "B_minus"),
    ((math.nan, 0.1, 10.0, EP), "A_minus"), ((0.1, math.inf, 10.0, EP), "B_minus"),
    ((0.1, 0.2, 0.0, EP), "load_n"), ((0.1, 0.2, -3.0, EP), "load_n"),
    ((0.1, 0.2, 3.0, 0.0), "e_prime_mpa"),
    ((0.1, 17.0, 10.0, EP), "B_minus"), ((1e-4, 0.01, 10.0, EP), "A_minus"),
    ((0.1, 0.2, 2.0 ** 17 + 1, EP), "load_n"), ((0.1, 0.2, 0.5, EP), "load_n"),
    ((0.1, 0.2, 10.0, 3e6), "e_prime_mpa"), ((0.01, 1.29, 10.0, EP), "alpha = B_max/A_min")])
def test_bad_inputs_name_the_field(args, field):
    with pytest.raises(InputRangeError) as ei:
        hertz_preview(args[0], args[1], args[2], e_prime_mpa=args[3])
    assert ei.value.field == field


def test_envelope_switch_and_array_errors():
    # beyond the LUT range the plain HB formulas still evaluate with envelope=False
    p = hertz_preview(0.001, 0.5, 10.0, e_prime_mpa=EP, envelope=False)
    assert p.alpha == pytest.approx(500.0, rel=1e-15)
    assert ENVELOPE["alpha"] == (1.0, 128.0)
    with pytest.raises(InputRangeError, match=r"load_n\[2\]"):
        hertz_preview_array([0.1] * 3, [0.2] * 3, [10.0, 10.0, -1.0], e_prime_mpa=EP)
    with pytest.raises(InputRangeError, match="alpha"):
        hertz_preview_array([0.1, 0.005], [0.2, 1.0], [10.0, 10.0], e_prime_mpa=EP)
    with pytest.raises(InputRangeError, match=r"A_minus\[1\]"):
        hertz_preview_array([0.1, np.nan], [0.2, 0.2], 10.0, e_prime_mpa=EP)
