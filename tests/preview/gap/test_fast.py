"""Vectorized golden (numba) is bit-identical to the scalar golden model."""

import numpy as np
import pytest

from gearcontact.preview.gap.fast import gap_golden_batch, gap_golden_points
from gearcontact.preview.gap.golden import (DEFAULT_FORMAT, GapFormat, GapVector,
                                            gap_golden, gap_golden_codes)
from gearcontact.validation import InputRangeError

ONE = 1 << 19


def random_codes(rng, m, n, *, spread_code, fmt=DEFAULT_FORMAT):
    """Seeded codes incl. coarse (tie-prone) samples and random rotations."""
    g = rng.integers(-spread_code, spread_code, (n, 3))
    g[: n // 4] = (g[: n // 4] >> 12) << 12             # coarse grid: equal rho/|gamma|
    if n >= 8:
        g[4:8] = g[0:4]                                 # exact duplicates: lane ties
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    nrm[: n // 8] = [0, 0, 1.0]                         # +1.0 components
    n_code = np.floor(nrm * (1 << fmt.normal_frac) + 0.5).astype(np.int64)
    q, _ = np.linalg.qr(rng.normal(size=(m, 3, 3)))
    q *= np.sign(np.linalg.det(q))[:, None, None]
    r_code = np.floor(q * (1 << fmt.normal_frac) + 0.5).astype(np.int64)
    t_code = rng.integers(-spread_code, spread_code, (m, 3))
    p_code = rng.integers(-spread_code, spread_code, (m, 3))
    return r_code, t_code, p_code, g, n_code


@pytest.mark.parametrize("lanes, n, tau2", [(16, 16, 1 << 34), (8, 61, 1 << 33),
                                            (64, 200, 1 << 36), (16, 37, 1)])
def test_batch_bit_identical_to_scalar(lanes, n, tau2):
    rng = np.random.default_rng(lanes * 1000 + n)
    m = 60
    r, t, p, g, nc = random_codes(rng, m, n, spread_code=3 << 16)
    b = gap_golden_batch(r, t, p, g, nc, tau2, lanes=lanes)
    for k in range(m):
        s = gap_golden_codes(GapVector(r[k], t[k], p[k], g, nc, tau2), lanes=lanes)
        assert (s.min_gap_code, s.min_idx, s.valid, s.overflow) == \
            (b.min_gap_code[k], b.min_idx[k], b.valid[k], b.overflow[k])
    if tau2 == 1:
        assert not b.valid.any()                        # gate rejects every lane
    else:
        assert b.valid.mean() > 0.5                     # the comparison is not vacuous


@pytest.mark.parametrize("rf", [19, 24])
def test_batch_overflow_and_wide_format(rf):
    # cf = 24: rho e_shift path, cw = 32; rf = 19 stays on the float64-exact path,
    # rf = 24 (|n.d| up to 3 2^56) takes the int64 path
    fmt = GapFormat(coord_frac=24, normal_frac=rf)
    rng = np.random.default_rng(5)
    r, t, p, g, nc = random_codes(rng, 20, 40, spread_code=3 << 24, fmt=fmt)
    p[0] = [fmt.coord.max_code, 0, 0]
    t[0] = [fmt.coord.max_code, 0, 0]
    r[0] = np.eye(3, dtype=np.int64) << rf              # p' = 2 max -> overflow
    tau2 = 1 << 40
    b = gap_golden_batch(r, t, p, g, nc, tau2, lanes=8, fmt=fmt)
    assert b.overflow[0] and not b.valid[0]
    for k in range(20):
        s = gap_golden_codes(GapVector(r[k], t[k], p[k], g, nc, tau2), lanes=8, fmt=fmt)
        assert (s.min_gap_code, s.min_idx, s.valid, s.overflow) == \
            (b.min_gap_code[k], b.min_idx[k], b.valid[k], b.overflow[k])


@pytest.mark.parametrize("cf", [6, 7])
def test_batch_bit_identical_at_narrow_coordinate_words(cf):
    # cw = 8 + cf = 14, 15 bits: the narrow end of the published precision figure
    fmt = GapFormat(coord_frac=cf)
    rng = np.random.default_rng(100 + cf)
    r, t, p, g, nc = random_codes(rng, 20, 40, spread_code=3 << cf, fmt=fmt)
    tau2 = 1 << (2 * cf + 2)                            # tau = 2 mm
    b = gap_golden_batch(r, t, p, g, nc, tau2, lanes=8, fmt=fmt)
    for k in range(20):
        s = gap_golden_codes(GapVector(r[k], t[k], p[k], g, nc, tau2), lanes=8, fmt=fmt)
        assert (s.min_gap_code, s.min_idx, s.valid, s.overflow) == \
            (b.min_gap_code[k], b.min_idx[k], b.valid[k], b.overflow[k])
    assert b.valid.any()                                # not vacuous


def test_batch_rejects_out_of_contract_codes():
    g = np.zeros((4, 3), np.int64)
    n = np.tile([0, 0, ONE], (4, 1))
    with pytest.raises(InputRangeError):
        gap_golden_batch(np.eye(3, dtype=np.int64) * (ONE + 1), [0, 0, 0], [[0, 0, 0]],
                         g, n, 1 << 32)
    with pytest.raises(InputRangeError):
        gap_golden_batch(np.eye(3, dtype=np.int64) * ONE, [0, 0, 0], [[1 << 23, 0, 0]],
                         g, n, 1 << 32)
    with pytest.raises(InputRangeError):
        gap_golden_batch(np.eye(3, dtype=np.int64) * ONE, [0, 0, 0], [[0, 0, 0]],
                         g, n, 1 << 32, lanes=12)


def test_points_api_matches_scalar_real_api():
    rng = np.random.default_rng(11)
    g = rng.uniform(-2, 2, (40, 3))
    n = rng.normal(size=(40, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    q *= np.sign(np.linalg.det(q))
    t = np.array([0.2, -0.1, 0.05])
    pts = rng.uniform(-2, 2, (25, 3))
    pts[0] = q.T @ [127.9, 0.0, 0.0]                    # p'_x = 128.1 mm: overflow flag
    res = gap_golden_points(q, t, pts, g, n, tau_mm=0.7, lanes=8)
    assert res.overflow[0] and not res.valid[0] and np.isnan(res.min_gap_mm[0])
    for k in range(1, 25):
        one = gap_golden(q, t, pts[k], g, n, tau_mm=0.7, lanes=8)
        assert (one.min_gap_code, one.min_idx, one.valid) == \
            (res.min_gap_code[k], res.min_idx[k], res.valid[k])
        assert one.min_gap_mm == res.min_gap_mm[k] or not one.valid
    assert res.valid[1:].sum() >= 10                    # most points gate in
