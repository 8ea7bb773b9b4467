"""One result type for the contact-solver family (issue 24, item 3).

Truth: the solvers' own definitions of their statuses (an iteration cap of one CG step
on a Hertzian patch cannot converge: MAX_ITER; the same patch with the default cap
converges), the one-block identity of the two LCP drivers (``solve_mesh_lcp`` with
lever 1 and no offset is the problem ``solve_lcp`` solves: the same CG on the same
stack, so the loads agree bit for bit), and the deprecation promise (the old names are
the new type and warn).
"""

import warnings

import numpy as np
import pytest

from gearcontact.halfspace import ContactResult, SolveStatus, TangentGrid, solve_lcp
from gearcontact.halfspace.compliance import BlockCompliance
from gearcontact.halfspace.constrained_cg import constrained_cg
from gearcontact.ltca.mesh_lcp import PairBlock, solve_mesh_lcp

N, D, LOAD_N = 32, 0.01, 50.0


@pytest.fixture(scope="module")
def hertz():
    """A paraboloid gap (R = 10 mm) on a 32 x 32 field of 10 um cells."""
    grid = TangentGrid.centered(N, N, dx_mm=D, dy_mm=D)
    x, y = grid.mesh()
    return grid, 0.05 * (x ** 2 + y ** 2)


@pytest.mark.parametrize("solver", ["pk_cg", "nnls", "active_set"])
def test_every_solver_returns_the_one_type(hertz, solver):
    grid, gap = hertz
    res = solve_lcp(gap, grid, LOAD_N, solver=solver, warn_coarse=False)
    assert type(res) is ContactResult and res.status is SolveStatus.CONVERGED
    assert res.solver == solver and res.converged
    assert res.n_contact_cells == int(res.contact_mask.sum()) > 0
    # the torque-pair fields stay empty for a one-body solve
    assert res.rotation_rad is None and res.contact_masks is None and res.x_stack is None


def test_max_iter_status(hertz):
    grid, gap = hertz
    res = solve_lcp(gap, grid, LOAD_N, max_iter=1, warn_coarse=False)
    assert res.status is SolveStatus.MAX_ITER and not res.converged
    mesh = solve_mesh_lcp([PairBlock(gap, grid, 1.0)], LOAD_N, max_iter=1)
    assert mesh.status is SolveStatus.MAX_ITER and not mesh.converged
    # a str enum: files show the value
    assert f"{SolveStatus.MAX_ITER}" == "max_iter"


def test_one_block_mesh_is_the_single_body_solve(hertz):
    grid, gap = hertz
    one = solve_lcp(gap, grid, LOAD_N, warn_coarse=False)
    mesh = solve_mesh_lcp([PairBlock(gap, grid, 1.0)], LOAD_N)
    assert type(mesh) is ContactResult and mesh.converged
    assert mesh.n_contact_cells == one.n_contact_cells
    # same CG, different cold starts: within the solver tolerance 1e-8 of the load
    np.testing.assert_allclose(mesh.loads_n[0], one.loads_n, rtol=0, atol=1e-6 * LOAD_N)
    assert mesh.rotation_rad == pytest.approx(one.delta_mm, rel=1e-6)
    assert mesh.torque_nmm == LOAD_N and mesh.delta_mm is None


def test_constrained_cg_fields_and_deprecated_aliases(hertz):
    grid, gap = hertz
    op = BlockCompliance(gap.shape, [(D, D)], e_star_mpa=1.15e5)
    out = constrained_cg(op, gap[None], np.ones((1, N, N)), LOAD_N, tol=1e-8,
                         max_iter=2000)
    assert type(out) is ContactResult and out.converged
    assert out.x_stack.sum() == pytest.approx(LOAD_N, rel=1e-12)  # the constraint
    with pytest.warns(DeprecationWarning, match="x_stack"):
        assert out.x is out.x_stack
    with pytest.warns(DeprecationWarning, match="u_stack_mm"):
        assert out.u is out.u_stack_mm


@pytest.mark.parametrize("module, name", [
    ("gearcontact.halfspace", "LcpResult"),
    ("gearcontact.halfspace.lcp", "LcpResult"),
    ("gearcontact.halfspace.constrained_cg", "CgOutcome"),
    ("gearcontact.ltca.mesh_lcp", "MeshLcpResult"),
])
def test_old_result_names_warn(module, name):
    import importlib

    mod = importlib.import_module(module)
    with pytest.warns(DeprecationWarning, match=f"{name} is deprecated.*ContactResult"):
        old = getattr(mod, name)
    assert old is ContactResult
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(AttributeError):
            getattr(mod, "NoSuchResult")
