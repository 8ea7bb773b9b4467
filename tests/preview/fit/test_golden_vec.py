"""The compiled fit kernel is bit-identical to the scalar golden model.

Truths: the scalar :func:`golden_fit` (exact Python ints, bit-by-bit non-restoring
isqrt) and :func:`math.isqrt`. Tolerance: none -- every code and flag must be equal.
"""

import math

import numpy as np
import pytest

from gearcontact.preview.fit import golden as G
from gearcontact.preview.fit.golden import golden_fit, golden_fit_batch
from gearcontact.preview.fit.golden_vec import _isqrt, fit_kernel
from gearcontact.preview.fit.pinv import baked_pinv
from gearcontact.contract.qformat import STENCIL_GAP, FixedPointOverflow
from gearcontact.preview.stimulus import fit_stimulus

from .test_golden import corner_stencils, random_stencils


def _stencils():
    """10 000 stencils over every magnitude 2^0..2^31, 2 000 stimulus stencils (with
    its corner cases), and the directed corner stencils of the scalar tests."""
    return np.concatenate([random_stencils(10_000, seed=4242),
                           fit_stimulus(2_000, seed=11).fields["gaps"],
                           corner_stencils()])


def test_kernel_bit_identical_to_scalar_golden():
    codes = _stencils()
    batch = golden_fit_batch(codes)
    for k in range(len(codes)):
        assert batch[k] == golden_fit([int(x) for x in codes[k]], bitwise=True), k
    # every flag path is exercised
    seen = set(np.unique(batch.flags).tolist())
    assert {0, G.FLAG_COEFF_OVERFLOW, G.FLAG_D_OVERFLOW, G.FLAG_NOT_ELLIPTIC} <= seen


def test_kernel_equals_batch_entry_point():
    codes = random_stencils(500, seed=3)
    c, a, b, f = fit_kernel(codes, baked_pinv().weight_codes_array, coeff_shift=21,
                            d_max_code=G.D_FMT.max_code)
    batch = golden_fit_batch(codes)
    assert np.array_equal(c, batch.c_codes) and np.array_equal(f, batch.flags)
    assert np.array_equal(a, batch.a_minus_codes)
    assert np.array_equal(b, batch.b_minus_codes)


def test_kernel_flag_values_mirror_the_scalar_model():
    from gearcontact.preview.fit import golden_vec as V
    assert (V._FLAG_COEFF, V._FLAG_D, V._FLAG_CURV, V._FLAG_NOT_ELLIPTIC) == (
        G.FLAG_COEFF_OVERFLOW, G.FLAG_D_OVERFLOW, G.FLAG_CURV_OVERFLOW,
        G.FLAG_NOT_ELLIPTIC)


def test_isqrt_is_the_exact_floor():
    rng = np.random.default_rng(5)
    cases = [0, 1, 2, 3, 4, 2**62, 2**63 - 1]
    for r in (1, 2, 3, 46340, 2**31 - 1, 2**31, 3037000499):
        cases += [r * r - 1, r * r, r * r + 1]
    cases += [int(x) >> int(s) for x, s in zip(rng.integers(0, 2**63, 5000, dtype=np.int64),
                                                 rng.integers(0, 63, 5000))]
    for d in cases:
        if 0 <= d < 2**63:
            assert _isqrt(np.int64(d)) == math.isqrt(d) == G.isqrt_nonrestoring(d), d


def test_out_of_range_code_is_named():
    codes = np.zeros((3, 49), np.int64)
    codes[2, 17] = STENCIL_GAP.max_code + 1
    with pytest.raises(FixedPointOverflow, match=r"gap_codes\[2, 17\]"):
        golden_fit_batch(codes)
    codes[2, 17] = STENCIL_GAP.min_code - 1
    with pytest.raises(FixedPointOverflow, match=r"gap_codes\[2, 17\]"):
        golden_fit_batch(codes)


def test_non_int64_input_takes_the_checked_path():
    codes = random_stencils(50, seed=9)
    assert np.array_equal(golden_fit_batch(codes.astype(np.int32)).c_codes,
                          golden_fit_batch(codes).c_codes)
    assert len(golden_fit_batch(np.zeros((0, 49), np.int64))) == 0
