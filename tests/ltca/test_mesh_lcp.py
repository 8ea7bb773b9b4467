"""The coupled multi-pair LCP with tooth bending blocks (gearcontact.ltca.mesh_lcp).

Independent truths (the rigid-tooth solver itself is checked in test_lte.py):

* a uniform bending compliance ``c`` on a pair (rank-one factor ``sqrt(c) 1``) adds
  ``c W`` to every cell's displacement: the pressures are those of the rigid pair and the
  approach grows by exactly ``c W`` (Johnson 1985: a rigid-body shift of the indenter);
* two pairs with uniform bending ``c_1``, ``c_2``: the nested root find on the load
  split built on :func:`gearcontact.halfspace.lcp.solve_lcp` with ``delta_j + c_j W_j``
  (a different algorithm for the same equations);
* zero-compliance limit: a zero factor gives the rigid solution (1e-9), no factor the
  rigid code path bit for bit;
* a non-uniform symmetric positive factor: torque balance exact, complementarity
  residual below the solver's tolerance, load shares sum to 100 %;
* bad factors -> InputRangeError naming the field.
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcontact.halfspace.lcp import solve_lcp
from gearcontact.ltca.mesh_lcp import PairBlock, solve_mesh_lcp
from gearcontact.validation import InputRangeError

#: Relative agreement of two converged solvers of the same LCP (tolerance 1e-8 on the
#: load change; residual_tol 1e-6), as in test_lte.py.
SOLVER_RTOL = 1e-6


def uniform_factor(shape, c):
    return np.full(tuple(shape) + (1,), np.sqrt(c))


def test_uniform_bending_shifts_the_approach(make_hertz):
    pb = make_hertz(10, 8)
    c, w = 3e-6, 1000.0
    rigid = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], w)
    bent = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0,
                                     bending_factor=uniform_factor(pb.gap_mm.shape, c))], w)
    assert bent.converged and rigid.converged
    assert bent.rotation_rad == pytest.approx(rigid.rotation_rad + c * w, rel=SOLVER_RTOL)
    np.testing.assert_allclose(bent.loads_n[0], rigid.loads_n[0], rtol=0,
                               atol=SOLVER_RTOL * rigid.loads_n[0].max())


def test_two_pairs_with_bending_against_nested_root_find(make_hertz):
    p1, p2 = make_hertz(10, 8), make_hertz(3, 8)
    l1, l2, g2, torque = 40.0, 35.0, 0.002, 40000.0
    c1, c2 = 2e-6, 6e-6
    res = solve_mesh_lcp(
        [PairBlock(p1.gap_mm, p1.grid, l1, bending_factor=uniform_factor(p1.gap_mm.shape, c1)),
         PairBlock(p2.gap_mm, p2.grid, l2, g2,
                   bending_factor=uniform_factor(p2.gap_mm.shape, c2))], torque)

    def mismatch(w1):
        w2 = (torque - l1 * w1) / l2
        d1 = solve_lcp(p1.gap_mm, p1.grid, w1, warn_coarse=False).delta_mm + c1 * w1
        d2 = solve_lcp(p2.gap_mm, p2.grid, w2, warn_coarse=False).delta_mm + c2 * w2
        return d1 / l1 - (d2 + g2) / l2

    w1 = brentq(mismatch, 0.3 * torque / l1, 0.99 * torque / l1, xtol=1e-10)
    w2 = (torque - l1 * w1) / l2
    assert res.converged
    np.testing.assert_allclose(res.pair_loads_n, [w1, w2], rtol=SOLVER_RTOL)
    theta = (solve_lcp(p1.gap_mm, p1.grid, w1, warn_coarse=False).delta_mm + c1 * w1) / l1
    assert res.rotation_rad == pytest.approx(theta, rel=SOLVER_RTOL)
    assert res.pair_loads_n @ [l1, l2] == pytest.approx(torque, rel=1e-12)


def test_zero_compliance_limit_is_rigid(make_hertz):
    p1, p2 = make_hertz(10, 8), make_hertz(3, 8)
    rigid_blocks = [PairBlock(p1.gap_mm, p1.grid, 40.0), PairBlock(p2.gap_mm, p2.grid, 35.0, 0.002)]
    zero_blocks = [PairBlock(b.gap_mm, b.grid, b.lever_mm, b.offset_mm,
                             bending_factor=np.zeros(b.gap_mm.shape + (3,)))
                   for b in rigid_blocks]
    rigid = solve_mesh_lcp(rigid_blocks, 40000.0)
    zero = solve_mesh_lcp(zero_blocks, 40000.0)
    assert zero.rotation_rad == pytest.approx(rigid.rotation_rad, rel=1e-9)
    np.testing.assert_allclose(zero.pair_loads_n, rigid.pair_loads_n, rtol=1e-9)
    again = solve_mesh_lcp(rigid_blocks, 40000.0)   # no factor: the rigid path, bit for bit
    assert again.rotation_rad == rigid.rotation_rad
    assert all((a == b).all() for a, b in zip(again.loads_n, rigid.loads_n))


def test_general_factor_balance_and_complementarity(make_hertz):
    rng = np.random.default_rng(3)
    p1, p2 = make_hertz(10, 8), make_hertz(3, 8)
    blocks = []
    for pb, lever, off in ((p1, 40.0, 0.0), (p2, 35.0, 0.001)):
        f = 1e-3 * np.abs(rng.normal(size=pb.gap_mm.shape + (4,)))
        blocks.append(PairBlock(pb.gap_mm, pb.grid, lever, off, bending_factor=f))
    res = solve_mesh_lcp(blocks, 40000.0)
    assert res.converged and res.complementarity_residual < 1e-6
    assert res.torque_residual < 1e-12
    share = res.pair_loads_n * [40.0, 35.0] / 40000.0
    assert share.sum() == pytest.approx(1.0, rel=1e-12)
    # the gap with the bending displacement: >= 0 everywhere, 0 on the contact set
    for b, w in zip(blocks, res.loads_n):
        f2 = b.bending_factor.reshape(-1, 4)
        bend = (f2 @ (f2.T @ w.ravel())).reshape(w.shape)
        assert bend.min() > 0.0


def test_bad_factor(make_hertz):
    pb = make_hertz(3, 8)
    with pytest.raises(InputRangeError, match="bending_factor"):
        PairBlock(pb.gap_mm, pb.grid, 1.0, bending_factor=np.zeros((2, 2, 1)))
    bad = np.zeros(pb.gap_mm.shape + (1,))
    bad[0, 0, 0] = np.nan
    with pytest.raises(InputRangeError, match="bending_factor"):
        PairBlock(pb.gap_mm, pb.grid, 1.0, bending_factor=bad)


def _handover_problem():
    """The two-pair LCP of the 12/12 design-space pair's hand-over phase at 3.225 N·m
    (tests/ltca/data/README.md): blocks, torque (N·mm), E* (MPa), tol, the warm start
    of the previous phase and the preview's rotation guess."""
    from pathlib import Path

    from gearcontact.halfspace.grid import TangentGrid

    d = np.load(Path(__file__).parent / "data" / "handover_12x12_3225nmm.npz")
    blocks, warm = [], []
    for i in range(int(d["n_blocks"])):
        nx, ny, dx, dy, x0, y0 = d[f"grid_{i}"]
        grid = TangentGrid.uniform(int(nx), int(ny), dx_mm=dx, dy_mm=dy, x0_mm=x0, y0_mm=y0)
        lever, offset = d[f"lever_offset_{i}"]
        blocks.append(PairBlock(d[f"gap_mm_{i}"], grid, float(lever), float(offset)))
        warm.append(d[f"warm_{i}"] if d[f"warm_{i}"].size else None)
    return (blocks, float(d["torque_nmm"]), float(d["e_star_mpa"]), float(d["tol"]), warm,
            float(d["rotation_guess_rad"]))


def test_a_start_that_stalls_is_solved_from_the_cold_start():
    """Issue 28 audit: `twin --speed-sweep` on the 12/12 pair stopped with exit 4 (the
    table twin's loaded TE at T/20 'did not converge'): from the preview's rotation
    guess the CG stalled at a non-complementary point (residual 0.67) at the hand-over.
    The LCP of rigid pairs is a strictly convex QP with one solution, so the answer
    cannot depend on the start: the guessed start must give the cold start's solution
    (rotation and pair loads within the solvers' agreement, SOLVER_RTOL), with the
    torque balanced (1e-9) and the complementarity residual within residual_tol."""
    blocks, torque, e_star, tol, warm, guess = _handover_problem()
    cold = solve_mesh_lcp(blocks, torque, e_star_mpa=e_star, tol=tol)
    assert cold.converged, cold.message
    for kw in ({"rotation_guess_rad": guess}, {"warm_start": warm, "rotation_guess_rad": guess}):
        res = solve_mesh_lcp(blocks, torque, e_star_mpa=e_star, tol=tol, **kw)
        assert res.converged, res.message
        assert res.complementarity_residual <= 1e-6
        assert res.torque_residual <= 1e-9
        assert res.rotation_rad == pytest.approx(cold.rotation_rad, rel=SOLVER_RTOL)
        np.testing.assert_allclose(res.pair_loads_n, cold.pair_loads_n,
                                   rtol=SOLVER_RTOL, atol=SOLVER_RTOL * torque / 50.0)
