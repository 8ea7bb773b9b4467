"""Tests of the stage-C golden model.

Truths: math.isqrt (integer square root), exact Python-int arithmetic of the scalar
model (the batch model must equal it bit for bit), exact quadratic gap fields with a
rigorous quantization bound, and the timing contract of docs/spec.md sec. 6.
"""

import math

import numpy as np
import pytest

from gearcontact.preview.fit.golden import (
    FIT_CYCLES, FIT_LATCH_CYCLES, FIT_MAC_CYCLES, FLAG_COEFF_OVERFLOW, FLAG_CURV_OVERFLOW,
    FLAG_D_OVERFLOW, FLAG_NOT_ELLIPTIC, chain_cycles, decode_curvature, encode_gaps,
    golden_fit, golden_fit_batch, isqrt_nonrestoring, isqrt_nonrestoring_array)
from gearcontact.preview.fit.pinv import coefficient_error_bound
from gearcontact.preview.fit.reference import fit_curvatures
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.contract.qformat import CURVATURE, STENCIL_GAP, FixedPointOverflow
from gearcontact.validation import InputRangeError
from gearcontact.contract.stencil import STENCIL_SPACING_MM

LSB = CURVATURE.lsb


def corner_stencils():
    """Directed corner stencils (codes): zero, extremes, impulses, alternations."""
    out = [np.zeros(49, dtype=np.int64),
           np.full(49, STENCIL_GAP.max_code), np.full(49, STENCIL_GAP.min_code),
           np.where(np.arange(49) % 2, STENCIL_GAP.max_code, STENCIL_GAP.min_code)]
    for i in (0, 3, 24, 48):
        for v in (STENCIL_GAP.max_code, STENCIL_GAP.min_code, 1, -1):
            imp = np.zeros(49, dtype=np.int64)
            imp[i] = v
            out.append(imp)
    return np.array(out, dtype=np.int64)


def random_stencils(n, seed):
    """Seeded random code stencils over all magnitudes 2^0 .. 2^31 (every flag path)."""
    rng = np.random.default_rng(seed)
    mag = 2 ** rng.integers(0, 32, size=(n, 1)).astype(object)
    hi = np.array([int(m) for m in mag[:, 0]], dtype=np.int64)
    u = rng.random((n, 49))
    codes = np.floor(u * (2 * hi[:, None]) - hi[:, None]).astype(np.int64)
    return np.clip(codes, STENCIL_GAP.min_code, STENCIL_GAP.max_code)


# ----------------------------------------------------------------------------- isqrt

def _isqrt_cases(seed):
    rng = np.random.default_rng(seed)
    edge = [0, 1, 2, 3, 4, 5, 8, 9, 15, 16, 2**62, 2**63 - 1, 2**64 - 1, 2**62 - 1]
    for r in (1, 2, 3, 3037000499, 2**31, 2**32 - 1, 12345678):
        edge += [r * r - 1, r * r, r * r + 1, r * r + 2 * r]
    rand = [int(x) >> int(s) for x, s in zip(rng.integers(0, 2**63, 20000, dtype=np.int64),
                                               rng.integers(0, 63, 20000))]
    return [e for e in edge if 0 <= e < 2**64], rand


def test_isqrt_nonrestoring_equals_math_isqrt():
    edge, rand = _isqrt_cases(11)
    for d in edge + rand:
        assert isqrt_nonrestoring(d) == math.isqrt(d), d


def test_isqrt_array_equals_math_isqrt():
    edge, rand = _isqrt_cases(12)
    d = np.array([e for e in edge if e < 2**63] + rand, dtype=np.int64)
    got = isqrt_nonrestoring_array(d)
    assert [int(x) for x in got] == [math.isqrt(int(x)) for x in d]


def test_isqrt_rejects_out_of_range():
    with pytest.raises(InputRangeError):
        isqrt_nonrestoring(-1)
    with pytest.raises(InputRangeError):
        isqrt_nonrestoring(2**64)


# ----------------------------------------------------------------- bit-exactness

def test_scalar_bitwise_fast_and_batch_are_identical():
    # >= 10k seeded random stencils over every magnitude, plus corners; every flag path
    # must be exercised for the comparison to mean something.
    codes = np.concatenate([corner_stencils(), random_stencils(10000, seed=5)])
    batch = golden_fit_batch(codes)
    seen = set()
    for k in range(len(codes)):
        row = [int(x) for x in codes[k]]
        ref = golden_fit(row, bitwise=False)
        assert batch[k] == ref, k
        seen.add(ref.flags)
    for k in range(0, len(codes), 7):      # bit-by-bit isqrt on a seventh (speed)
        assert golden_fit([int(x) for x in codes[k]], bitwise=True) == batch[k]
    assert {0, FLAG_COEFF_OVERFLOW, FLAG_NOT_ELLIPTIC} <= seen


def test_overflow_paths_and_zeroed_outputs():
    # Every field keeps its samples inside STENCIL_GAP's +-1024 mm (an offset c0 lets
    # the curvature grow: the window holds 0.72 mm^2 of s^2 + t^2 at its corners).
    # c0 = -1000 mm, c3 = c5 = 1900, c4 = 600 1/mm (all fit Q(32,20)), samples in
    # [-1000, 584] mm: d = 600^2 fits Q(64,40) but A- = 1900 + 300 = 2200 > 2048 =
    # CURVATURE max -> CURV overflow
    s, t = stencil_coordinates()
    g_curv = -1000.0 + 1900.0 * s * s + 600.0 * s * t + 1900.0 * t * t
    r = golden_fit(encode_gaps(g_curv))
    assert r.flags == FLAG_CURV_OVERFLOW and r.overflow
    assert (r.a_minus_code, r.b_minus_code, r.c_codes) == (0, 0, (0,) * 6)
    # c3 = 1500, c5 = -1500 (samples within +-540 mm): e = 3000, d = 9e6 > 2^23 (Q(64,40)
    # max) -> D overflow
    g_d = 1500.0 * (s * s - t * t)
    assert golden_fit(encode_gaps(g_d)).flags == FLAG_D_OVERFLOW
    # c3 = 3000 1/mm does not fit the Q(32,20) coefficient (max 2048) -> COEFF overflow
    # (c0 = -1000 mm: samples in [-1000, 80] mm)
    g_c = -1000.0 + 3000.0 * s * s + t * t
    assert golden_fit(encode_gaps(g_c)).flags == FLAG_COEFF_OVERFLOW
    for gg in (g_curv, g_d, g_c):
        codes = encode_gaps(gg)
        assert golden_fit_batch(codes[None])[0] == golden_fit(codes)


def test_saddle_and_zero_flagged(quadratic):
    g, _ = quadratic(0.1, -0.05, 20.0)
    r = golden_fit(encode_gaps(g))
    assert r.flags == FLAG_NOT_ELLIPTIC and not r.elliptic
    assert r.b_minus_code < 0 < r.a_minus_code
    z = golden_fit(np.zeros(49, dtype=np.int64))
    assert z.flags == FLAG_NOT_ELLIPTIC and z.a_minus_code == z.b_minus_code == 0


# -------------------------------------------------------------------- accuracy

def _eigen_bound(g):
    """|A_golden - A_exact| bound: Weyl with the Frobenius coefficient error + 1 LSB."""
    dc = coefficient_error_bound(g)
    return math.sqrt(dc[3] ** 2 + dc[4] ** 2 / 2 + dc[5] ** 2) + LSB


def test_golden_within_quantization_bound(quadratics):
    # Truth: exact quadratic fields with A-, B- in [1e-3, 1] 1/mm plus constant and
    # linear terms; the bound is rigorous (gap, weight and coefficient rounding through
    # Weyl's inequality, plus the floor isqrt and the final half-up shift <= 1 LSB).
    worst = 0.0
    for g, a, b, _, _ in quadratics(500, seed=3):
        r = golden_fit(encode_gaps(g))
        bound = _eigen_bound(g)
        assert r.flags == 0
        assert abs(r.A_minus_per_mm - a) <= bound
        assert abs(r.B_minus_per_mm - b) <= bound
        assert r.a_minus_code >= r.b_minus_code
        worst = max(worst, abs(r.A_minus_per_mm - a) / bound, abs(r.B_minus_per_mm - b) / bound)
    # the bound is tight to within two orders of magnitude, not vacuous
    assert worst > 0.01
    # absolute scale: the bound is ~1e-5 1/mm for these fields
    # the bound scales as 1/h^2 (weights of the quadratic terms): 2e-5 at h = 0.5 mm
    assert _eigen_bound(next(quadratics(1, seed=3))[0]) < 2e-5 * (0.5 / STENCIL_SPACING_MM) ** 2


def test_decoded_coefficients(quadratic):
    # c3..c5 decode within the coefficient bound of pinv (rigorous)
    g, c = quadratic(0.4, 0.02, 33.0, 0.01, -0.02, 0.03)
    r = golden_fit(encode_gaps(g))
    dc = coefficient_error_bound(g)
    assert np.all(np.abs(np.array(r.coefficients[3:]) - np.array(c)) <= dc[3:])
    assert np.all(np.abs(np.array(r.coefficients[:3]) - [0.01, -0.02, 0.03]) <= dc[:3])


def test_golden_tracks_reference_and_rotation(quadratic):
    # rotating the field (grid rotation by 90 deg) keeps the golden eigenvalues within
    # twice the single-fit bound of each other (both within the bound of the truth)
    for ang in (0.0, 17.0, 45.0, -63.0):
        g, _ = quadratic(0.35, 0.004, ang, 0.02, -0.01, 0.03)
        rot = np.rot90(g.reshape(7, 7)).ravel()
        r0, r1 = golden_fit(encode_gaps(g)), golden_fit(encode_gaps(rot))
        bound = _eigen_bound(g)
        ref = fit_curvatures(g)
        assert abs(r0.A_minus_per_mm - ref.A_minus_per_mm) <= bound
        assert abs(r1.B_minus_per_mm - r0.B_minus_per_mm) <= 2 * bound


def test_tiny_curvature_is_resolved(quadratic):
    # A- = B- = 1e-3 1/mm = 1049 LSB: golden must land within the bound (~8 LSB)
    g, _ = quadratic(1e-3, 1e-3, 0.0)
    r = golden_fit(encode_gaps(g))
    assert r.flags == 0
    assert abs(r.A_minus_per_mm - 1e-3) <= _eigen_bound(g)


# -------------------------------------------------------------- encode / validation

def test_encode_rounds_half_up_and_names_sample():
    g = np.zeros(49)
    g[5] = 1.5 * STENCIL_GAP.lsb      # tie -> up
    g[6] = -1.5 * STENCIL_GAP.lsb     # tie -> up (towards +inf)
    c = encode_gaps(g)
    assert (c[5], c[6]) == (2, -1)
    g[17] = 1100.0                # beyond STENCIL_GAP's +-1024 mm (inside GAP's range)
    with pytest.raises(FixedPointOverflow, match=r"gaps_mm\[17\]"):
        encode_gaps(g)
    g[17] = np.nan
    with pytest.raises(FixedPointOverflow, match=r"gaps_mm\[17\]"):
        encode_gaps(g)
    with pytest.raises(InputRangeError, match="gaps_mm.shape"):
        encode_gaps(np.zeros(50))
    assert decode_curvature(1 << 20) == 1.0


def test_golden_input_validation():
    with pytest.raises(InputRangeError, match="gap_codes.shape"):
        golden_fit([0] * 48)
    with pytest.raises(FixedPointOverflow, match=r"gap_codes\[3\]"):
        golden_fit([0, 0, 0, 2**31] + [0] * 45)
    with pytest.raises(InputRangeError, match=r"gap_codes\[0\]"):
        golden_fit([0.5] + [0] * 48)
    with pytest.raises(InputRangeError, match="gap_codes.shape"):
        golden_fit_batch(np.zeros(49, dtype=np.int64))


def test_timing_model():
    # docs/spec.md sec. 6: 49-cycle MAC stream + 3-cycle latch; chain with the 756-cycle D = 806
    assert (FIT_MAC_CYCLES, FIT_LATCH_CYCLES, FIT_CYCLES) == (49, 3, 52)
    assert chain_cycles(756) == 806
    with pytest.raises(InputRangeError):
        chain_cycles(1)
