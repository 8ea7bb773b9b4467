"""Tests of the baked fit ROM (truth: closed-form Savitzky-Golay weights of degree 2, an
independent least-squares solve of degree 6, exact polynomials of degree <= 6)."""

import numpy as np
import pytest

from gearcontact.preview.fit.golden import encode_gaps, golden_fit
from gearcontact.preview.fit.pinv import (ACC, FIT_DEGREE, N_TAPS, ROM_WORD, ROM_WORD_BITS,
                                          WEIGHT, bake_pseudo_inverse, baked_pinv,
                                          coefficient_error_bound, design_matrix,
                                          pseudo_inverse)
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.contract.qformat import STENCIL_GAP, FixedPointOverflow
from gearcontact.validation import InputRangeError


def test_fit_operator_is_the_quadratic_part_of_a_left_inverse():
    # M A = [I 0] (A the 49 x 28 degree-6 design): the ROM reads the quadratic part of
    # the degree-6 polynomial and nothing of its terms of degree 3..6. fp64 QR solve with
    # cond(A) = 2.0e3: measured 1.3e-14, 1e-12 is generous.
    m = pseudo_inverse()
    a = design_matrix()
    assert FIT_DEGREE == 6 and a.shape == (N_TAPS, 28)
    assert np.abs(m @ a - np.eye(6, 28)).max() < 1e-12


def test_rom_is_an_independent_degree_6_least_squares_solve():
    # Truth built here without the package's design matrix: the tensor Vandermonde
    # matrix of numpy (s^i t^j, i, j <= 6), cut to i + j <= 6, solved by SVD least
    # squares (lstsq); its rows for 1, s, t, s^2, st, t^2 are the ROM's weights.
    # Measured 1.1e-12 apart (two fp64 solves, weights up to 6.4 1/mm^2).
    s, t = stencil_coordinates()
    v = np.polynomial.polynomial.polyvander2d(s, t, [6, 6])     # column 7 i + j: s^i t^j
    keep = [(i, j) for i in range(7) for j in range(7) if i + j <= 6]
    full = np.linalg.lstsq(v[:, [7 * i + j for i, j in keep]], np.eye(N_TAPS),
                           rcond=None)[0]
    rows = [keep.index(ij) for ij in ((0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2))]
    np.testing.assert_allclose(baked_pinv().weights, full[rows], rtol=0, atol=1e-10)


def test_quadratic_rows_match_closed_form_savitzky_golay():
    # Truth (degree 2): on the separable 7x7 grid s = k h, t = j h (k, j in -3..3) the
    # columns 1, s, t, s^2 - <s^2>, st, t^2 - <t^2> are orthogonal, so (h = 0.5 mm)
    # c3 = sum (k^2 - 4) g / (h^2 * 7 * 84) = (k^2 - 4)/147, c4 = k j / (h^2 * 28^2)
    # = k j / 196, c1 = k / (h * 7 * 28) = k / 98. Tolerance: fp64 solve, 1e-15.
    m = pseudo_inverse(0.5, degree=2)
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
    # |acc_j| <= 2^31 * sum_i |W_ji| must fit ACC = Q(72,41); the documented design
    # bound 49 * 2^31 * 2^31 < 2^71 covers any Q(32,20) weight.
    assert ACC.bits == STENCIL_GAP.bits + ROM_WORD_BITS == 72
    assert ACC.frac == STENCIL_GAP.frac + WEIGHT.frac == 41
    assert max(baked_pinv().weight_l1_codes) * 2**31 <= ACC.max_code
    assert 49 * 2**31 * 2**31 <= ACC.max_code


def test_quantized_weights_reproduce_exact_polynomials():
    # Mq A p = p[:6] + E p with |E_jk| <= 49 * 2^-21 * max|A_ik| (each weight off by at
    # most half an LSB of Q(32,20)); measured max |E| = 3.8e-6 for the baked stencil
    # (the constant term into c3: 4 LSB of Q(32,20)).
    rom = baked_pinv()
    a = design_matrix()
    assert rom.reproduction_error.shape == (6, 28)
    bound = N_TAPS * 2.0**-21 * np.abs(a).max()
    assert np.abs(rom.reproduction_error).max() <= bound
    assert np.abs(rom.reproduction_error).max() < 4e-6
    rng = np.random.default_rng(7)
    for _ in range(50):
        p = rng.uniform(-1, 1, 28)
        got = rom.quantized_weights @ (a @ p)
        assert np.all(np.abs(got - p[:6]) <= bound * np.abs(p).sum() + 1e-15)


def test_quartic_and_sextic_terms_no_longer_leak():
    # Exact polynomials of total degree <= 6 (random coefficients, each term up to
    # 10 um at the window's edge |s| = 0.6 mm) through the golden datapath: the fitted
    # c0..c5 are the polynomial's own to coefficient_error_bound (gap rounding to
    # STENCIL_GAP, weight rounding, coefficient rounding). Measured: at most 0.51 of the
    # bound over 200 polynomials. The degree-2 ROM (the former one) reads the same
    # samples up to 4.0e4 x its bound: the terms of degree 4 and 6 fold into c0, c3..c5.
    rng = np.random.default_rng(28)
    a = design_matrix()
    deg = np.concatenate([[n] * (n + 1) for n in range(7)])
    rom2 = bake_pseudo_inverse(degree=2)
    worst6 = worst2 = 0.0
    for _ in range(200):
        p = rng.uniform(-1, 1, 28) * 1e-2 / 0.6 ** deg
        g = a @ p
        codes = encode_gaps(g)
        got6 = np.array(golden_fit(codes).coefficients)
        worst6 = max(worst6, (np.abs(got6 - p[:6]) / coefficient_error_bound(g)).max())
        got2 = np.array(golden_fit(codes, rom=rom2).coefficients)
        worst2 = max(worst2, (np.abs(got2 - p[:6])
                              / coefficient_error_bound(g, rom=rom2)).max())
    assert worst6 <= 1.0, worst6
    assert worst2 > 1e4, worst2


def test_coefficient_error_bound_positive_and_validated():
    s, t = stencil_coordinates()
    b = coefficient_error_bound(0.1 * s * s)
    assert b.shape == (6,) and (b > 0).all()
    # c3: |Mq_3|_1 2^-22 (88.3 1/mm^2: 2.1e-5) + sum |dM_3i| |g_i| (< 49 2^-21 0.036 mm
    # = 8.4e-7) + 2^-21 (4.8e-7) = 2.2e-5 1/mm; looser than 2.3e-5 means a bug
    assert b[3] < 2.3e-5
    with pytest.raises(InputRangeError, match="gaps_mm"):
        coefficient_error_bound(np.zeros(48))


def test_tiny_spacing_overflows_weights():
    # weights of c3 scale as 1/h^2: h = 1e-3 mm gives |w| ~ 2.6e5 > 2048 -> must raise
    with pytest.raises(FixedPointOverflow, match=r"M\["):
        bake_pseudo_inverse(spacing_mm=1e-3)
    with pytest.raises(InputRangeError, match="spacing_mm"):
        design_matrix(0.0)
    with pytest.raises(InputRangeError, match="degree"):
        design_matrix(degree=7)      # s^7 is a combination of 1..s^6 on 7 grid columns
