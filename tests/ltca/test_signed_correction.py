"""The coupled LCP with a signed (possibly indefinite) bending correction
(gearcontact.ltca.mesh_lcp, gearcontact.ltca.tooth_bending.SignedFactor; docs/bending.md
sec. 13, session 27, criteria 2 and 3, declared before they were built).

Independent truths:

* a dense symmetric indefinite matrix with a spectrum well above the compression's cut
  is reproduced by its signed factor to round-off (1e-12 of its largest entry: no
  eigenvalue is dropped; eigh's backward error is ~1e-15);
* a uniform correction ``c`` (either sign; the total positive definite on the contact)
  adds ``c W`` to every cell's displacement, so the pressures are the rigid pair's and
  the approach moves by exactly ``c W`` (a rigid-body shift, Johnson 1985), whether the
  correction is given dense or as a signed factor;
* two pairs with uniform signed corrections ``c_1 < 0 < c_2`` against the nested root
  find on :func:`gearcontact.halfspace.lcp.solve_lcp` (another algorithm for the same
  equations);
* a correction that makes the total indefinite on the contact (``c`` ten times the rigid
  pair's approach per newton, negative: the uniform mode's energy then is negative) is
  refused by name, :class:`IndefiniteCompliance`, with its least eigenvalue negative;
* the dense matrix that check factors is the solver's own operator (FFT Love plus the
  signed factor) on the cells it is taken on.
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcontact.errors import CheckFailed
from gearcontact.halfspace.lcp import resolve_e_star, solve_lcp
from gearcontact.ltca.mesh_lcp import (IndefiniteCompliance, PairBlock, contact_eigenvalues,
                                       solve_mesh_lcp)
from gearcontact.ltca.tooth_bending import SignedFactor
from gearcontact.validation import InputRangeError

#: Two converged solvers of one LCP (tol 1e-8 on the load change; residual 1e-6), as
#: test_mesh_lcp.py.
SOLVER_RTOL = 1e-6


def uniform(shape, c) -> np.ndarray:
    n = int(np.prod(shape))
    return np.full((n, n), float(c))


def test_signed_factor_reproduces_a_dense_indefinite_matrix():
    rng = np.random.default_rng(7)
    q, _ = np.linalg.qr(rng.normal(size=(30, 30)))
    lam = np.concatenate([np.linspace(1.0, 3.0, 18), -np.linspace(0.5, 2.0, 12)]) * 1e-6
    g = (q * lam) @ q.T
    sf = SignedFactor.from_dense(g, (5, 6))
    assert sf.positive.shape == (5, 6, 18) and sf.negative.shape == (5, 6, 12)
    assert np.abs(sf.matrix() - g).max() <= 1e-12 * np.abs(g).max()


def test_a_replaced_block_keeps_one_correction(make_hertz):
    """The dense correction is merged into the bending factor once: a block copied with
    dataclasses.replace (as the multi-tooth LTCA re-solves its blocks) holds the same
    matrix, not twice it (1e-12 of its largest entry)."""
    from dataclasses import replace

    pb = make_hertz(3, 8)
    g = uniform(pb.gap_mm.shape, -1e-6)
    block = PairBlock(pb.gap_mm, pb.grid, 1.0, correction_mm_per_n=g)
    again = replace(block, gap_mm=pb.gap_mm + 1e-3)
    assert block.correction_mm_per_n is None
    assert np.abs(again.bending_factor.matrix() - g).max() <= 1e-12 * np.abs(g).max()


def test_bad_correction(make_hertz):
    pb = make_hertz(3, 8)
    n = pb.gap_mm.size
    with pytest.raises(InputRangeError, match="correction matrix"):
        PairBlock(pb.gap_mm, pb.grid, 1.0, correction_mm_per_n=np.zeros((n, n - 1)))
    g = np.zeros((n, n))
    g[0, 1] = 1e-6
    with pytest.raises(InputRangeError, match="asymmetry"):
        PairBlock(pb.gap_mm, pb.grid, 1.0, correction_mm_per_n=g)


@pytest.mark.parametrize("sign", [-1.0, 1.0])
def test_uniform_correction_shifts_the_approach(make_hertz, sign):
    pb = make_hertz(10, 8)
    w = 1000.0
    rigid = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], w)
    c = sign * 0.3 * rigid.rotation_rad / w      # |c| W = 30 % of the rigid approach
    dense = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0,
                                      correction_mm_per_n=uniform(pb.gap_mm.shape, c))], w)
    sf = SignedFactor.from_dense(uniform(pb.gap_mm.shape, c), pb.gap_mm.shape)
    factor = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0, bending_factor=sf)], w)
    for res in (dense, factor):
        assert res.converged and rigid.converged
        assert res.rotation_rad == pytest.approx(rigid.rotation_rad + c * w, rel=SOLVER_RTOL)
        np.testing.assert_allclose(res.loads_n[0], rigid.loads_n[0], rtol=0,
                                   atol=SOLVER_RTOL * rigid.loads_n[0].max())
        assert "positive definite" in res.message


def test_two_pairs_with_signed_corrections_against_nested_root_find(make_hertz):
    p1, p2 = make_hertz(10, 8), make_hertz(3, 8)
    l1, l2, g2, torque = 40.0, 35.0, 0.002, 40000.0
    c1, c2 = -1e-6, 4e-6   # c1 W1 ~ -20 % of pair 1's half-space approach
    res = solve_mesh_lcp(
        [PairBlock(p1.gap_mm, p1.grid, l1, correction_mm_per_n=uniform(p1.gap_mm.shape, c1)),
         PairBlock(p2.gap_mm, p2.grid, l2, g2,
                   correction_mm_per_n=uniform(p2.gap_mm.shape, c2))], torque)

    def approach(p, w, c):
        return solve_lcp(p.gap_mm, p.grid, w, warn_coarse=False).delta_mm + c * w

    def mismatch(w1):
        w2 = (torque - l1 * w1) / l2
        return approach(p1, w1, c1) / l1 - (approach(p2, w2, c2) + g2) / l2

    w1 = brentq(mismatch, 0.3 * torque / l1, 0.99 * torque / l1, xtol=1e-10)
    w2 = (torque - l1 * w1) / l2
    assert res.converged
    np.testing.assert_allclose(res.pair_loads_n, [w1, w2], rtol=SOLVER_RTOL)
    assert res.rotation_rad == pytest.approx(approach(p1, w1, c1) / l1, rel=SOLVER_RTOL)
    assert approach(p1, w1, c1) < solve_lcp(p1.gap_mm, p1.grid, w1, warn_coarse=False).delta_mm


def test_an_indefinite_total_is_refused_by_name(make_hertz):
    pb = make_hertz(10, 8)
    w = 1000.0
    rigid = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], w)
    c = -10.0 * rigid.rotation_rad / w
    block = PairBlock(pb.gap_mm, pb.grid, 1.0, correction_mm_per_n=uniform(pb.gap_mm.shape, c))
    with pytest.raises(IndefiniteCompliance, match="not positive definite") as err:
        solve_mesh_lcp([block], w)
    assert isinstance(err.value, CheckFailed)
    n = err.value.contact_cells
    assert err.value.pair == 0 and n > 0
    # Weyl: lambda_min(C_S + c 1 1^T) lies in [lambda_min(C_S) + c n, lambda_min(C_S)],
    # lambda_min(C_S) > 0 (Love's operator is positive definite); the refused one is
    # negative, so it lies in [c n, 0)
    assert c * n <= err.value.least_eigenvalue_mm_per_n < 0.0
    # the public check on the rigid solution's contact cells finds it indefinite too,
    # and the half-space alone positive definite there
    e_star = resolve_e_star(None, None)
    assert contact_eigenvalues([block], rigid, e_star_mpa=e_star)[0] < 0.0
    assert contact_eigenvalues([PairBlock(pb.gap_mm, pb.grid, 1.0)], rigid,
                               e_star_mpa=e_star)[0] > 0.0


def test_the_checked_matrix_is_the_solvers_operator(make_hertz):
    """The dense compliance the positive-definiteness check factors, on 300 random cells,
    applied to random loads there, against the LCP's own operator (the FFT Love
    operator plus the signed factor, SignedBlockCompliance): equal within the operator's
    single-precision storage of the factors (float32, 6e-8 relative per entry; 1e-6 of
    the largest displacement allowed; the half-space parts alone agree to 6e-16)."""
    from gearcontact.ltca.mesh_lcp import SignedBlockCompliance, _contact_matrix

    pb = make_hertz(10, 8)
    ny, nx = pb.gap_mm.shape
    rng = np.random.default_rng(0)
    q, _ = np.linalg.qr(rng.normal(size=(ny * nx, 6)))
    corr = (q * np.array([3, 2, 1, -1, -2, -3]) * 1e-5) @ q.T
    block = PairBlock(pb.gap_mm, pb.grid, 1.0, correction_mm_per_n=corr)
    e_star = resolve_e_star(None, None)
    idx = rng.choice(ny * nx, 300, replace=False)
    x = np.zeros((1, ny, nx))
    x.reshape(-1)[idx] = rng.random(300)
    sf = block.bending_factor
    op = SignedBlockCompliance((ny, nx), [(float(pb.grid.dx_mm[0]), float(pb.grid.dy_mm[0]))],
                               e_star_mpa=e_star, low_rank=sf.positive[None],
                               negative=sf.negative[None])
    want = op.evaluate_disp(x).reshape(-1)[idx]
    got = _contact_matrix(block, idx, e_star) @ x.reshape(-1)[idx]
    assert np.abs(got - want).max() <= 1e-6 * np.abs(want).max()
