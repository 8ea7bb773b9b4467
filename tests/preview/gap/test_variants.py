"""The lean gap variant: its golden model equals the published one bit for bit under its
gate contract (tau2 <= 2^34), the contract is tight, and scalar == vectorized model."""

import numpy as np
import pytest

from gearcontact.preview.gap.fast import gap_golden_batch
from gearcontact.preview.gap.golden import (GapVector, gap_golden, gap_golden_codes,
                                            gap_golden_terms)
from gearcontact.preview.gap.variants import (GAP_VARIANTS, LEAN_E_BITS, check_variant,
                                              lean_tau2_max, lean_tau_max_mm,
                                              residual_limit)
from gearcontact.contract.qformat import FixedPointOverflow
from gearcontact.preview.stimulus import gap_stimulus
from gearcontact.validation import InputRangeError

ONE = 1 << 19
RHO_INF = (1 << 64) - 1


def vectors(st):
    f = st.fields
    return [GapVector(f["r"][i], f["t"][i], f["p"][i], f["g"][i], f["nrm"][i],
                      int(f["tau2"][i])) for i in range(len(st))]


def with_tau2(vec, tau2):
    return GapVector(vec.r_code, vec.t_code, vec.p_code, vec.g_code, vec.n_code, int(tau2))


def batch(vec, variant):
    o = gap_golden_batch(vec.r_code[None], vec.t_code[None], vec.p_code[None], vec.g_code,
                         vec.n_code, vec.tau2_code, lanes=16, variant=variant)
    return (int(o.min_gap_code[0]), int(o.min_idx[0]), bool(o.valid[0]), bool(o.overflow[0]))


def test_contract_constants():
    assert GAP_VARIANTS == ("published", "lean")
    assert residual_limit("published") == 0 and residual_limit("lean") == 1 << 17
    assert LEAN_E_BITS == 18                       # the DSP48E1 B port
    assert lean_tau2_max() == 1 << 34 and lean_tau_max_mm() == 2.0
    with pytest.raises(InputRangeError, match="variant"):
        check_variant("tiny")
    with pytest.raises(InputRangeError, match="variant"):
        gap_golden_codes(vectors(gap_stimulus(0, 0))[0], variant="tiny")


def groups(st):
    """Runs of consecutive passes sharing samples and gate (the stimulus' pose groups)."""
    f = st.fields
    start = 0
    for i in range(1, len(st) + 1):
        if i == len(st) or not (np.array_equal(f["g"][i], f["g"][start])
                                and np.array_equal(f["nrm"][i], f["nrm"][start])
                                and f["tau2"][i] == f["tau2"][start]):
            yield {k: f[k][start:i] for k in ("r", "t", "p")}, f["g"][start], \
                f["nrm"][start], int(f["tau2"][start])
            start = i


def group_batch(pose, g, n, tau2, variant):
    o = gap_golden_batch(pose["r"], pose["t"], pose["p"], g, n, tau2, lanes=16,
                         variant=variant)
    return np.stack([o.min_gap_code, o.min_idx, o.valid, o.overflow])


def test_lean_equals_published_under_the_gate_contract():
    """2,011 passes (corner cases + seeded random incl. raw whole-range codes), gate
    clipped to the contract: outputs equal, although samples do saturate."""
    st = gap_stimulus(2000, seed=3)
    differs_unclipped = 0
    for pose, g, n, tau2 in groups(st):
        clipped = min(tau2, lean_tau2_max())
        assert (group_batch(pose, g, n, clipped, "lean")
                == group_batch(pose, g, n, clipped, "published")).all()
        differs_unclipped += int((group_batch(pose, g, n, tau2, "lean")
                                  != group_batch(pose, g, n, tau2, "published")).any(0).sum())
    assert differs_unclipped > 0                   # the contract matters beyond it
    saturated = 0
    for vec in vectors(st)[:200]:
        try:
            _, _, rho = gap_golden_terms(vec, variant="lean")
        except FixedPointOverflow:                 # p' overflow: no terms
            continue
        saturated += int((rho == np.uint64(RHO_INF)).sum())
    assert saturated > 200                         # the saturation path is exercised


def test_contract_is_tight():
    """A sample whose residual component is exactly 2^17 codes (2 mm): rho = 2^34 fails a
    gate of 2^34 in both variants, passes 2^34 + 1 only in the published one."""
    g = np.array([[-(2 << 16), 0, 0]] * 16)        # p' = 0: d = (2 mm, 0, 0), e = d
    g[1:] = [[100 << 16, 0, 0]]                    # the others far off
    n = np.array([[0, 0, ONE]] * 16)
    vec = GapVector(np.eye(3, dtype=np.int64) * ONE, np.zeros(3, np.int64),
                    np.zeros(3, np.int64), g, n, lean_tau2_max())
    _, _, rho = gap_golden_terms(vec)
    assert rho[0] == 1 << 34
    for variant in GAP_VARIANTS:
        assert not gap_golden_codes(vec, variant=variant).valid
    wider = with_tau2(vec, lean_tau2_max() + 1)
    assert gap_golden_codes(wider).valid and gap_golden_codes(wider).min_idx == 0
    assert not gap_golden_codes(wider, variant="lean").valid
    # one code less residual: e = 2^17 - 1 fits 18 bits, both gate it in
    g[0] = [-(2 << 16) + 1, 0, 0]
    inside = GapVector(vec.r_code, vec.t_code, vec.p_code, g, n, lean_tau2_max())
    assert gap_golden_codes(inside) == gap_golden_codes(inside, variant="lean")
    assert gap_golden_codes(inside).valid


def test_lean_scalar_equals_vectorized():
    """Scalar lean model == numba lean model, gates up to 2^63 (saturations decide)."""
    st = gap_stimulus(150, seed=11)
    for vec in vectors(st):
        s = gap_golden_codes(vec, variant="lean")
        assert (s.min_gap_code, s.min_idx, s.valid, s.overflow) == batch(vec, "lean")


def test_real_api_takes_the_variant():
    rng = np.random.default_rng(2)
    g = rng.uniform(-3, 3, (16, 3))
    n = rng.normal(size=(16, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    args = (np.eye(3), np.zeros(3), np.array([0.1, 0.2, 0.3]), g, n)
    a = gap_golden(*args, tau_mm=2.0)
    b = gap_golden(*args, tau_mm=2.0, variant="lean")
    assert a == b and a.valid
