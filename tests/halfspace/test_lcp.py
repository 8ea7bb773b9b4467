"""LCP solvers against exact elliptical Hertz and against each other.

Truth: :func:`gearcontact.analytic.hertz.exact_elliptic_hertz` (Johnson 1985 sec. 4.2).
Tolerances (issue 4): at >= 16 cells per semi-axis the peak pressure within 1 % (the
collocation error measured here is ~0.04 %), the contact semi-axes within one cell
(the contact edge is resolved to a cell), the approach within 0.5 %. Solver agreement
<= 1e-6 relative; load balance exact to 1e-10 relative (round-off is ~1e-16).
"""

import warnings

import numpy as np
import pytest

from gearcontact.halfspace import constrained_cg, lcp
from gearcontact.halfspace.ellipse import CoarseGridWarning
from gearcontact.halfspace.grid import TangentGrid
from gearcontact.halfspace.influence import dense_influence_matrix
from gearcontact.halfspace.lcp import LcpConvergenceError, solve_lcp
from gearcontact.validation import InputRangeError

from hertz_problems import E_STAR_MPA, LOAD_N, hertz_problem

RATIOS = (1.0, 10.0, 50.0)


def _check_against_hertz(res, prob):
    hz, grid = prob.hertz, prob.grid
    assert res.converged, res.message
    assert res.pressure_mpa.max() == pytest.approx(hz.p_max_mpa, rel=0.01)
    assert res.delta_mm == pytest.approx(hz.approach_mm, rel=0.005)
    jc, ic = grid.ny // 2, grid.nx // 2
    dx, dy = grid.dx_mm[0], grid.dy_mm[0]
    a_num = res.contact_mask[jc].sum() * dx / 2  # contact length along x through 0
    b_num = res.contact_mask[:, ic].sum() * dy / 2
    assert abs(a_num - hz.a_mm) <= dx
    assert abs(b_num - hz.b_mm) <= dy
    # exact load balance and a small natural complementarity residual
    assert abs(res.loads_n.sum() - LOAD_N) <= 1e-10 * LOAD_N
    assert res.load_residual <= 1e-10
    assert res.complementarity_residual <= 1e-8
    assert np.all(res.loads_n >= 0.0)


def _agree(r1, r2, rel=1e-6):
    pmax = r1.pressure_mpa.max()
    assert np.abs(r1.pressure_mpa - r2.pressure_mpa).max() <= rel * pmax
    assert r1.delta_mm == pytest.approx(r2.delta_mm, rel=rel)


@pytest.mark.parametrize("ratio", RATIOS)
@pytest.mark.parametrize("solver", ["pk_cg", "active_set"])
def test_hertz_at_16_cells(make_hertz, ratio, solver):
    prob = make_hertz(ratio, 16)
    _check_against_hertz(solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver=solver,
                                   e_star_mpa=E_STAR_MPA), prob)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", RATIOS)
def test_hertz_at_16_cells_nnls(make_hertz, ratio):
    # ~20 s per problem: the reference NNLS on ~1,800 candidate cells.
    prob = make_hertz(ratio, 16)
    _check_against_hertz(solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver="nnls",
                                   e_star_mpa=E_STAR_MPA), prob)


@pytest.mark.parametrize("ratio", RATIOS)
def test_all_solvers_agree_on_moderate_grid(make_hertz, ratio):
    # 8 cells per semi-axis (~200 contact cells) keeps the NNLS reference fast; the
    # Hertz truth is looser here (peak 2 %, approach 1 %: coarser collocation).
    prob = make_hertz(ratio, 8)
    res = {s: solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver=s, e_star_mpa=E_STAR_MPA)
           for s in lcp.SOLVERS}
    for r in res.values():
        assert r.converged, r.message
        assert r.pressure_mpa.max() == pytest.approx(prob.hertz.p_max_mpa, rel=0.02)
        assert r.delta_mm == pytest.approx(prob.hertz.approach_mm, rel=0.01)
        assert abs(r.loads_n.sum() - LOAD_N) <= 1e-10 * LOAD_N
    _agree(res["nnls"], res["active_set"], rel=1e-9)  # both direct: round-off only
    _agree(res["pk_cg"], res["nnls"])
    assert np.array_equal(res["pk_cg"].contact_mask, res["nnls"].contact_mask)


@pytest.mark.parametrize("solver", lcp.SOLVERS)
def test_symmetric_problem_gives_symmetric_pressure(make_hertz, solver):
    prob = make_hertz(10.0, 8)
    p = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver=solver,
                  e_star_mpa=E_STAR_MPA).pressure_mpa
    tol = 1e-9 * p.max()  # the gap is symmetric to round-off; so must be the solution
    assert np.abs(p - p[::-1, :]).max() <= tol
    assert np.abs(p - p[:, ::-1]).max() <= tol


def test_windowed_pk_cg_on_large_grid_matches_direct(make_hertz):
    # On a +-3 semi-axis grid the solver works in a window; the certificate
    # (delta <= window bound) makes it the whole-grid solution.
    big = make_hertz(1.0, 12, extent=3.0)
    res = solve_lcp(big.gap_mm, big.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    j0, j1, i0, i1 = res.window
    assert (j1 - j0) * (i1 - i0) < big.grid.size
    assert "certified" in res.message
    ref = solve_lcp(big.gap_mm, big.grid, LOAD_N, solver="active_set",
                    e_star_mpa=E_STAR_MPA)
    _agree(res, ref)


def test_window_growth_path_gives_same_answer(make_hertz, monkeypatch):
    prob = make_hertz(10.0, 10, extent=3.0)
    ref = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    monkeypatch.setattr(lcp, "_WINDOW_FACTOR", 1.0)  # start below the approach
    for solver in ("pk_cg", "active_set"):
        res = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver=solver,
                        e_star_mpa=E_STAR_MPA)
        assert "grown" in res.message and res.converged
        _agree(res, ref)


def test_warm_start_reduces_pk_cg_iterations(make_hertz):
    prob = make_hertz(10.0, 12, extent=2.0)
    r1 = solve_lcp(prob.gap_mm, prob.grid, 1.02 * LOAD_N, e_star_mpa=E_STAR_MPA)
    cold = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    warm = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA,
                     warm_start=r1)
    assert warm.converged and warm.iterations < cold.iterations
    _agree(warm, cold)


def test_active_set_on_non_uniform_grid():
    # Graded grid (fine core of 16 cells per radius, coarser rim): LU on the
    # non-symmetric collocation block; same Hertz tolerances as the uniform case.
    prob = hertz_problem(1.0, 16)
    a = prob.hertz.a_mm
    core = np.linspace(-1.1 * a, 1.1 * a, 2 * 18 + 2)
    rim = np.array([1.25, 1.45, 1.7]) * a
    edges = np.concatenate([-rim[::-1], core, rim])
    grid = TangentGrid.from_edges(edges, edges)
    X, Y = grid.mesh()
    gap = (X ** 2 + Y ** 2) / 40.0
    res = solve_lcp(gap, grid, LOAD_N, solver="active_set", e_star_mpa=E_STAR_MPA)
    assert res.converged, res.message
    assert res.pressure_mpa.max() == pytest.approx(prob.hertz.p_max_mpa, rel=0.01)
    assert res.delta_mm == pytest.approx(prob.hertz.approach_mm, rel=0.005)
    assert abs(res.loads_n.sum() - LOAD_N) <= 1e-10 * LOAD_N
    with pytest.raises(InputRangeError, match="uniform"):
        solve_lcp(gap, grid, LOAD_N, solver="pk_cg", e_star_mpa=E_STAR_MPA)


def test_materials_give_e_star(make_hertz):
    from gearcontact.materials import STEEL
    prob = make_hertz(1.0, 8)
    r1 = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, materials=(STEEL, STEEL))
    r2 = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    assert r1.delta_mm == pytest.approx(r2.delta_mm, rel=1e-12)


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("load", [0.0, -5.0, float("nan"), float("inf")])
def test_non_positive_load_raises(make_hertz, load):
    prob = make_hertz(1.0, 8)
    with pytest.raises(InputRangeError, match="load_n"):
        solve_lcp(prob.gap_mm, prob.grid, load)


def test_nan_in_gap_raises_with_index(make_hertz):
    prob = make_hertz(1.0, 8)
    gap = prob.gap_mm.copy()
    gap[3, 5] = np.nan
    with pytest.raises(InputRangeError, match=r"gap_mm\[3, 5\]"):
        solve_lcp(gap, prob.grid, LOAD_N)


def test_wrong_shape_and_unknown_solver_raise(make_hertz):
    prob = make_hertz(1.0, 8)
    with pytest.raises(InputRangeError, match="shape"):
        solve_lcp(prob.gap_mm.T[:-1], prob.grid, LOAD_N)
    with pytest.raises(InputRangeError, match="solver"):
        solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver="simplex")


@pytest.mark.parametrize("solver", lcp.SOLVERS)
def test_non_convergence_reports_status_and_raises_on_request(make_hertz, solver):
    prob = make_hertz(10.0, 8)
    res = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver=solver, max_iter=1)
    assert not res.converged and res.status in ("max_iter", "failed") and res.message
    with pytest.raises(LcpConvergenceError) as info:
        solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver=solver, max_iter=1,
                  raise_on_failure=True)
    assert info.value.result.status == res.status


def test_coarse_grid_warns_with_cells_per_semi_axis(make_hertz):
    prob = make_hertz(1.0, 3)
    with pytest.warns(CoarseGridWarning, match=r"\d+\.\d cells per minor semi-axis"):
        solve_lcp(prob.gap_mm, prob.grid, LOAD_N)
    fine = make_hertz(1.0, 8)
    with warnings.catch_warnings():
        warnings.simplefilter("error", CoarseGridWarning)
        solve_lcp(fine.gap_mm, fine.grid, LOAD_N)


def test_preconditioner_cuts_iterations_same_answer(make_hertz):
    # The FFT preconditioner changes the path, not the solution (1e-6 agreement); on
    # this 800-cell problem it needs well under half the plain PK iterations.
    prob = make_hertz(10.0, 16, extent=2.0)
    pre = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    plain = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA,
                      precondition=False)
    assert pre.converged and plain.converged
    assert pre.iterations <= 0.5 * plain.iterations
    _agree(pre, plain)


def test_pk_cg_gap_margin_fallback_to_whole_window(make_hertz, monkeypatch):
    # Warm start from a much smaller patch with no margin around the contact box: the
    # growth must come from the whole-window check at convergence; same solution.
    prob = make_hertz(1.0, 12, extent=2.0)
    ref = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    small = solve_lcp(prob.gap_mm, prob.grid, 0.3 * LOAD_N, e_star_mpa=E_STAR_MPA)
    monkeypatch.setattr(constrained_cg, "_MARGIN", 0)
    res = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA,
                    warm_start=small)
    assert res.converged, res.message
    _agree(res, ref)
    assert np.array_equal(res.contact_mask, ref.contact_mask)


def test_linear_algebra_failure_is_reported_not_raised(make_hertz, monkeypatch):
    prob = make_hertz(1.0, 8)

    def broken(*args, **kwargs):
        raise np.linalg.LinAlgError("matrix is not positive definite")

    monkeypatch.setattr(lcp, "_bordered_solve", broken)
    res = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver="active_set")
    assert res.status == "failed" and "not positive definite" in res.message
    with pytest.raises(LcpConvergenceError):
        solve_lcp(prob.gap_mm, prob.grid, LOAD_N, solver="active_set",
                  raise_on_failure=True)


# ------------------------------------------------------------------ single-cell contact
def _check_single_cell(res, gap, grid, load, cell):
    # One contacting cell carries all of W: p = W / cell area, and the approach is the
    # cell's gap plus its self-displacement, delta = h_min + C_ii W (C_ii: Love's closed
    # form at the centre of a loaded cell, the dense 1x1 matrix). Exact up to round-off
    # (1e-12 relative); every other cell stays open.
    c_ii = dense_influence_matrix(grid.sub(slice(0, 1), slice(0, 1)),
                                  e_star_mpa=E_STAR_MPA)[0, 0]
    assert res.converged, res.message
    assert res.n_contact_cells == 1 and res.contact_mask[cell]
    assert np.all(np.isfinite(res.pressure_mpa))
    assert res.pressure_mpa[cell] == pytest.approx(load / grid.cell_area_mm2[cell],
                                                   rel=1e-12)
    assert res.delta_mm == pytest.approx(float(gap.min()) + c_ii * load, rel=1e-12)
    assert res.load_residual <= 1e-12


@pytest.mark.parametrize("solver", lcp.SOLVERS)
@pytest.mark.parametrize("load", [1e-3, 1e-9])
def test_tiny_load_on_hertz_gap_contacts_one_cell(make_hertz, solver, load):
    # At 1e-3 N (1e-6 W) the Hertz radius is 1 % of the 8-cell one: the contact is the
    # centre cell alone, and the pk_cg preconditioner works on a 1x1 box (it returned
    # NaN there before the 1x1 symbol was made finite).
    prob = make_hertz(1.0, 8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CoarseGridWarning)
        res = solve_lcp(prob.gap_mm, prob.grid, load, solver=solver,
                        e_star_mpa=E_STAR_MPA)
    cell = (prob.grid.ny // 2, prob.grid.nx // 2)
    _check_single_cell(res, prob.gap_mm, prob.grid, load, cell)


@pytest.mark.parametrize("solver", lcp.SOLVERS)
@pytest.mark.parametrize("cell", [(5, 7), (0, 0), (22, 11)])
def test_isolated_minimum_cell_carries_the_whole_load(solver, cell):
    # A flat gap 1 um above one isolated cell (interior, corner, edge): under 1 N the
    # cell sinks C_ii W ~ 0.15 um < 1 um, so it alone is in contact.
    grid = TangentGrid.centered(23, 23, dx_mm=0.01, dy_mm=0.015)
    gap = np.full(grid.shape, 1e-3)
    gap[cell] = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CoarseGridWarning)
        res = solve_lcp(gap, grid, 1.0, solver=solver, e_star_mpa=E_STAR_MPA)
    _check_single_cell(res, gap, grid, 1.0, cell)


def test_pk_cg_incremental_displacement_matches_recomputed(make_hertz, monkeypatch):
    # pk_cg updates C w from the step's C t and adds clipped / re-admitted cells one by
    # one from the real-space kernel (both fire on this problem); recomputing C w by FFT
    # at every step (_REFRESH = 1) follows the same iterates up to round-off: same
    # iteration count, pressures within 1e-9 of p_max (the solver tolerance is 1e-8 W).
    prob = make_hertz(10.0, 12, extent=2.0)
    fast = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    monkeypatch.setattr(constrained_cg, "_REFRESH", 1)
    exact = solve_lcp(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    assert fast.converged and exact.converged
    assert fast.iterations == exact.iterations
    _agree(fast, exact, rel=1e-9)
