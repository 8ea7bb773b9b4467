"""Tests of the baked pseudo-inverse ROM (truth: closed-form Savitzky-Golay weights)."""

import numpy as np
import pytest

from gearcontact.preview.fit.pinv import (ACC, N_TAPS, ROM_WORD, ROM_WORD_BITS, WEIGHT,
                                          bake_pseudo_inverse, baked_pinv,
                                          coefficient_error_bound, design_matrix,
                                          pseudo_inverse)
from gearcontact.contract.stencil import STENCIL_SPACING_MM, stencil_coordinates
from gearcontact.contract.qformat import GAP, FixedPointOverflow
from gearcontact.validation import InputRangeError


def test_pseudo_inverse_is_left_inverse():
    # M A = I up to fp64 rounding of a 6x6 solve with cond ~ 40: 1e-12 is generous.
    m = pseudo_inverse()
    assert np.abs(m @ design_matrix() - np.eye(6)).max() < 1e-12


def test_quadratic_rows_match_closed_form_savitzky_golay():
    # Truth: on the separable 7x7 grid s = k h, t = j h (k, j in -3..3) the columns
    # 1, s, t, s^2 - <s^2>, st, t^2 - <t^2> are orthogonal, so (h = 0.5 mm)
    # c3 = sum (k^2 - 4) g / (h^2 * 7 * 84) = (k^2 - 4)/147, c4 = k j / (h^2 * 28^2)
    # = k j / 196, c1 = k / (h * 7 * 28) = k / 98. Tolerance: fp64 solve, 1e-15.
    m = pseudo_inverse(0.5)
    k = np.arange(49) % 7 - 3
    j = np.arange(49) // 7 - 3
    np.testing.assert_allclose(m[3], (k * k - 4) / 147.0, atol=1e-15)
    np.testing.assert_allclose(m[5], (j * j - 4) / 147.0, atol=1e-15)
    np.testing.assert_allclose(m[4], k * j / 196.0, atol=1e-15)
    np.testing.assert_allclose(m[1], k / 98.0, atol=1e-15)


def test_rom_codes_are_round_half_up_and_40_bit_words():
    rom = baked_pinv()
    codes = rom.weight_codes_array
    assert codes.shape == (6, N_TAPS)
    # exact: round half up of M * 2^20 (no ties occur for these rationals)
    np.testing.assert_array_equal(codes, np.floor(rom.weights * 2.0**20 + 0.5))
    assert WEIGHT.fits(codes).all()
    for row_c, row_w in zip(rom.weight_codes, rom.rom_words):
        for c, w in zip(row_c, row_w):
            assert 0 <= w < 1 << ROM_WORD_BITS
            assert ROM_WORD.from_bits(w) == c
            # the 8 guard bits (and bit 31) replicate the sign: a sign-extended Q(32,20)
            top = w >> 31
            assert top in (0, (1 << 9) - 1)


def test_accumulator_cannot_wrap():
    # |acc_j| <= 2^31 * sum_i |W_ji| must fit ACC = Q(72,36); the documented design
    # bound 49 * 2^31 * 2^31 < 2^71 covers any Q(32,20) weight.
    assert ACC.bits == GAP.bits + ROM_WORD_BITS == 72
    assert max(baked_pinv().weight_l1_codes) * 2**31 <= ACC.max_code
    assert 49 * 2**31 * 2**31 <= ACC.max_code


def test_quantized_weights_reproduce_exact_quadratics():
    # Mq A p = p + E p with |E_jk| <= 49 * 2^-21 * max|A_ik| (each weight off by at most
    # half an LSB of Q(32,20)); measured max |E| = 6.7e-6 for the baked stencil.
    rom = baked_pinv()
    bound = N_TAPS * 2.0**-21 * np.abs(design_matrix()).max()
    assert np.abs(rom.reproduction_error).max() <= bound
    assert np.abs(rom.reproduction_error).max() < 7e-6
    rng = np.random.default_rng(7)
    a = design_matrix()
    for _ in range(50):
        p = rng.uniform(-1, 1, 6)
        got = rom.quantized_weights @ (a @ p)
        assert np.all(np.abs(got - p) <= bound * np.abs(p).sum() + 1e-15)


def test_coefficient_error_bound_positive_and_validated():
    s, t = stencil_coordinates()
    b = coefficient_error_bound(0.1 * s * s)
    assert b.shape == (6,) and (b > 0).all()
    # quadratic rows: |Mq|_1 * 2^-17 + ... ~ 0.95 * 7.6e-6; looser than 1e-5 means a bug
    # curvature-coefficient bound scales as 1/h^2: 1e-5 at h = 0.5 mm
    assert b[3] < 1e-5 * (0.5 / STENCIL_SPACING_MM) ** 2
    with pytest.raises(InputRangeError, match="gaps_mm"):
        coefficient_error_bound(np.zeros(48))


def test_tiny_spacing_overflows_weights():
    # weights of c3 scale as 1/h^2: h = 1e-3 mm gives |w| ~ 8e4 > 2048 -> must raise
    with pytest.raises(FixedPointOverflow, match=r"M\["):
        bake_pseudo_inverse(spacing_mm=1e-3)
    with pytest.raises(InputRangeError, match="spacing_mm"):
        design_matrix(0.0)
