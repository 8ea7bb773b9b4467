"""The vectorized golden model is bit-identical to the scalar one (codes and flags)."""

import numpy as np
import pytest

from gearcontact.preview.hertz import formats as F
from gearcontact.preview.hertz.golden import hertz_golden
from gearcontact.preview.hertz.golden_vec import hertz_golden_array

from .test_golden import CORNERS

FIELDS = ("a_code", "b_code", "p_max_code", "k_code", "A_min_code", "B_max_code",
          "R_x_code", "R_y_code", "alpha_code", "flags")


def _vectors(n, seed):
    """Seeded random codes: 60 % inside the envelope (log-uniform, ratios up to 140 so
    some exceed the LUT), 40 % anywhere in the 32-bit code space (flag paths)."""
    rng = np.random.default_rng(seed)
    k = int(0.6 * n)
    a = np.exp(rng.uniform(np.log(F.CURV_MIN_CODE), np.log(F.CURV_MAX_CODE), k))
    b = np.minimum(a * np.exp(rng.uniform(0, np.log(140.0), k)), F.CURV_MAX_CODE)
    w = np.exp(rng.uniform(np.log(F.LOAD_MIN_CODE), np.log(F.LOAD_MAX_CODE), k))
    e = np.exp(rng.uniform(np.log(F.E_PRIME_MIN_CODE), np.log(F.E_PRIME_MAX_CODE), k))
    lo, hi = -(1 << 31), (1 << 31) - 1
    rest = [rng.integers(lo, hi, n - k, endpoint=True) for _ in range(4)]
    cols = [np.concatenate([x.astype(np.int64), r]) for x, r in zip((a, b, w, e), rest)]
    swap = rng.random(n) < 0.5
    cols[0], cols[1] = np.where(swap, cols[1], cols[0]), np.where(swap, cols[0], cols[1])
    return cols


def test_bit_identical_random_and_corners():
    A, B, W, E = _vectors(20_000, seed=2024)
    corners = np.array(CORNERS, dtype=np.int64).T
    A, B, W, E = (np.concatenate([x, c]) for x, c in zip((A, B, W, E), corners))
    vec = hertz_golden_array(A, B, W, e_prime_code=E)
    got = np.stack([getattr(vec, f) for f in FIELDS])
    want = np.array([[getattr(hertz_golden(int(a), int(b), int(w), e_prime_code=int(e)), f)
                      for f in FIELDS] for a, b, w, e in zip(A, B, W, E)],
                    dtype=np.int64).T
    assert np.array_equal(got, want)                        # every code and flag
    assert (vec.flags == 0).sum() > 10_000                  # the valid path is covered
    assert (vec.flags == F.FLAG_ALPHA_RANGE).sum() > 50     # and the LUT-range flag


def test_shapes_and_broadcast():
    A = np.full((3, 4), 1 << 14)
    v = hertz_golden_array(A, 1 << 16, 1 << 12, e_prime_code=229_670)
    assert v.a_code.shape == (3, 4) and v.valid.all()
    s = hertz_golden(1 << 14, 1 << 16, 1 << 12, e_prime_code=229_670)
    assert int(v.p_max_code[2, 3]) == s.p_max_code


@pytest.mark.slow
def test_bit_identical_long_sweep():
    """200 000 further seeded vectors (about 30 s of scalar model on 2 cores)."""
    A, B, W, E = _vectors(200_000, seed=77)
    vec = hertz_golden_array(A, B, W, e_prime_code=E)
    for i in range(A.size):
        s = hertz_golden(int(A[i]), int(B[i]), int(W[i]), e_prime_code=int(E[i]))
        assert tuple(int(getattr(vec, f)[i]) for f in FIELDS) == \
            tuple(getattr(s, f) for f in FIELDS), i


def test_exact_form_bit_identical_random_and_corners():
    """hertz_form="exact": same comparison as above on 5 000 vectors plus the corners
    (the EEX dividend path of the kernel against the scalar model)."""
    A, B, W, E = _vectors(5_000, seed=2026)
    corners = np.array(CORNERS, dtype=np.int64).T
    A, B, W, E = (np.concatenate([x, c]) for x, c in zip((A, B, W, E), corners))
    vec = hertz_golden_array(A, B, W, e_prime_code=E, hertz_form="exact")
    got = np.stack([getattr(vec, f) for f in FIELDS])
    want = np.array([[getattr(hertz_golden(int(a), int(b), int(w), e_prime_code=int(e),
                                           hertz_form="exact"), f)
                      for f in FIELDS] for a, b, w, e in zip(A, B, W, E)],
                    dtype=np.int64).T
    assert np.array_equal(got, want)
    assert (vec.flags == 0).sum() > 2_500
    # and the two forms really differ on the valid path (k differs beyond alpha = 1)
    hb = hertz_golden_array(A, B, W, e_prime_code=E)
    assert (hb.k_code[vec.valid] != vec.k_code[vec.valid]).mean() > 0.9
