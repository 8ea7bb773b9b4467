"""Love influence operators: dense vs FFT, symmetry, and closed-form displacements."""

import numpy as np
import pytest

from gearcontact.halfspace.grid import TangentGrid
from gearcontact.halfspace.influence import (
    FftInfluence,
    StackedFftInfluence,
    boussinesq_inverse,
    dense_influence_matrix,
    fft_influence,
    love_rectangle_displacement,
)
from gearcontact.validation import InputRangeError

E_STAR = 114_835.0  # MPa, steel on steel


@pytest.mark.parametrize("nx,ny,dx,dy", [(13, 9, 0.02, 0.03), (16, 16, 0.01, 0.01),
                                         (31, 7, 0.05, 0.004)])
def test_fft_operator_equals_dense(nx, ny, dx, dy):
    # Same linear operator, two evaluations: agreement to round-off (1e-12 relative
    # leaves ~1000x margin over the FFT's ~1e-15 log N error).
    grid = TangentGrid.uniform(nx, ny, dx_mm=dx, dy_mm=dy)
    c = dense_influence_matrix(grid, e_star_mpa=E_STAR)
    w = np.random.default_rng(nx * ny).random(grid.shape)
    u_dense = (c @ w.ravel()).reshape(grid.shape)
    u_fft = fft_influence(grid, e_star_mpa=E_STAR)(w)
    assert np.abs(u_fft - u_dense).max() <= 1e-12 * np.abs(u_dense).max()


def test_dense_matrix_symmetric_positive_definite_on_uniform_grid():
    # Reciprocity of the collocation matrix on equal cells: exact up to round-off.
    grid = TangentGrid.uniform(11, 8, dx_mm=0.02, dy_mm=0.05)
    c = dense_influence_matrix(grid, e_star_mpa=E_STAR)
    assert np.abs(c - c.T).max() <= 1e-14 * c.max()
    assert np.linalg.eigvalsh(c).min() > 0.0


def test_uniform_pressure_on_large_patch_matches_closed_form_at_centre():
    # Cells tiling a 2a x 2b rectangle under uniform p superpose exactly to Love's
    # rectangle (Johnson 1985 eq. 3.25, textbook log form evaluated here independently):
    # u(0,0) = 4p/(pi E*) [a ln((b + r)/a) + b ln((a + r)/b)], r = sqrt(a^2 + b^2).
    nx, ny, dx, dy, p = 41, 29, 0.025, 0.04, 700.0
    grid = TangentGrid.centered(nx, ny, dx_mm=dx, dy_mm=dy)
    u = fft_influence(grid, e_star_mpa=E_STAR)(np.full(grid.shape, p * dx * dy))
    a, b = nx * dx / 2, ny * dy / 2
    r = np.hypot(a, b)
    u0 = 4 * p / (np.pi * E_STAR) * (a * np.log((b + r) / a) + b * np.log((a + r) / b))
    assert u[ny // 2, nx // 2] == pytest.approx(u0, rel=1e-12)


def test_far_field_tends_to_boussinesq_point_load():
    # Boussinesq: u = P / (pi E* r); a square cell of side 2c at distance r differs by
    # O((c/r)^2) -- at r = 40c the relative difference must be below 1e-3.
    c, r, load = 0.01, 0.4, 2.0
    u = love_rectangle_displacement(r, 0.0, c, c, e_star_mpa=E_STAR,
                                    pressure_mpa=load / (4 * c * c))
    assert u == pytest.approx(load / (np.pi * E_STAR * r), rel=1e-3)


def test_uniform_circle_centre_displacement():
    # Uniform p on a circle of radius R: u(0) = 2 p R / E* (both bodies; Johnson 1985
    # sec. 3.4). The stair-cased circle of 80 cells per radius is off by O(1/80): 0.5 %.
    n, radius, p = 161, 1.0, 100.0
    grid = TangentGrid.centered(n, n, dx_mm=2 * radius / 160, dy_mm=2 * radius / 160)
    X, Y = grid.mesh()
    w = np.where(X ** 2 + Y ** 2 <= radius ** 2, p, 0.0) * grid.cell_area_mm2
    u = fft_influence(grid, e_star_mpa=E_STAR)(w)
    assert u[n // 2, n // 2] == pytest.approx(2 * p * radius / E_STAR, rel=5e-3)


def test_kernel_transform_is_cached():
    a = FftInfluence((20, 30), dx_mm=0.01, dy_mm=0.02, e_star_mpa=E_STAR)
    b = FftInfluence((20, 30), dx_mm=0.01, dy_mm=0.02, e_star_mpa=E_STAR)
    assert a._khat is b._khat


def test_fft_on_non_uniform_grid_raises():
    grid = TangentGrid.from_edges([0.0, 0.1, 0.3, 0.4], [0.0, 0.1])
    with pytest.raises(InputRangeError, match="uniform"):
        fft_influence(grid, e_star_mpa=E_STAR)


def test_dense_matrix_on_non_uniform_grid_matches_love_per_cell():
    # Any grid: the column of cell m is Love's displacement for that cell / its area.
    grid = TangentGrid.from_edges([0.0, 0.05, 0.2, 0.22, 0.5], [-0.1, 0.0, 0.3])
    c = dense_influence_matrix(grid, e_star_mpa=E_STAR)
    X, Y = grid.mesh()
    m = 6  # j = 1, i = 2
    j, i = divmod(m, grid.nx)
    u = love_rectangle_displacement(X - grid.x_mm[i], Y - grid.y_mm[j],
                                    grid.dx_mm[i] / 2, grid.dy_mm[j] / 2,
                                    e_star_mpa=E_STAR) / (grid.dx_mm[i] * grid.dy_mm[j])
    np.testing.assert_allclose(c[:, m], u.ravel(), rtol=1e-14)


def test_approx_inverse_is_exact_and_finite_on_a_single_cell():
    # A 1x1 field has no non-zero wavenumber: the preconditioner's symbol there is the
    # exact inverse of the self-influence C_ii (dense 1x1 matrix), to round-off.
    grid = TangentGrid.uniform(1, 1, dx_mm=0.02, dy_mm=0.03)
    c_ii = dense_influence_matrix(grid, e_star_mpa=E_STAR)[0, 0]
    op = fft_influence(grid, e_star_mpa=E_STAR)
    w = op.approx_inverse(np.full((1, 1), 2e-4))
    assert np.isfinite(w).all()
    assert w[0, 0] == pytest.approx(2e-4 / c_ii, rel=1e-12)


@pytest.mark.parametrize("shape", [(1, 1), (1, 6), (5, 1), (7, 9)])
def test_approx_inverse_symmetric_positive_definite(shape):
    # As a matrix on the field (any padding), the preconditioner must be SPD for CG:
    # symmetric to round-off (1e-12 relative) with a positive smallest eigenvalue.
    n = shape[0] * shape[1]
    for pad in (shape, (2 * shape[0], 2 * shape[1] + 1)):
        m = np.column_stack([boussinesq_inverse(e.reshape(shape), dx_mm=0.02, dy_mm=0.03,
                                                e_star_mpa=E_STAR, padded_shape=pad).ravel()
                             for e in np.eye(n)])
        assert np.abs(m - m.T).max() <= 1e-12 * np.abs(m).max()
        assert np.linalg.eigvalsh(0.5 * (m + m.T)).min() > 0.0


def test_window_operators_slice_the_parent_kernel_exactly():
    # Windows (on_shape) reuse the largest kernel quadrant computed for the cell size;
    # each must still equal its own dense operator to round-off (1e-12 relative).
    op = FftInfluence((40, 33), dx_mm=0.011, dy_mm=0.017, e_star_mpa=E_STAR)
    rng = np.random.default_rng(7)
    for shape in [(40, 33), (9, 21), (1, 5), (17, 1)]:
        grid = TangentGrid.uniform(shape[1], shape[0], dx_mm=0.011, dy_mm=0.017)
        w = rng.random(shape)
        u_dense = (dense_influence_matrix(grid, e_star_mpa=E_STAR) @ w.ravel()
                   ).reshape(shape)
        u_fft = op.on_shape(shape)(w)
        assert np.abs(u_fft - u_dense).max() <= 1e-12 * np.abs(u_dense).max()


@pytest.mark.parametrize("shape", [(40, 40), (7, 9), (1, 1), (1, 5), (6, 1)])
def test_stacked_operator_equals_one_operator_per_field(shape):
    # The batched, padding-pruned transforms compute the same linear maps as
    # FftInfluence and boussinesq_inverse field by field: agreement to round-off
    # (1e-12 relative); fields outside ``live`` get exactly 0.
    cells, scales = [(0.02, 0.03), (0.011, 0.05), (0.3, 0.01)], [2.0, 3.0, 0.5]
    op = StackedFftInfluence(shape, cells, e_star_mpa=E_STAR, scales=scales)
    x = np.random.default_rng(3).random((3,) + shape)
    u, z = op.apply(x), op.approx_inverse(x)
    for k, ((dx, dy), s) in enumerate(zip(cells, scales)):
        one = FftInfluence(shape, dx_mm=dx, dy_mm=dy, e_star_mpa=E_STAR)
        assert np.abs(u[k] - one(x[k]) / s).max() <= 1e-12 * np.abs(u[k]).max()
        assert np.abs(z[k] - s * one.approx_inverse(x[k])).max() <= 1e-12 * np.abs(z[k]).max()
    live = np.array([True, False, True])
    part = op.apply(np.where(live[:, None, None], x, 0.0), live=live)
    assert np.abs(part[[0, 2]] - u[[0, 2]]).max() <= 1e-12 * np.abs(u).max()
    assert not part[1].any()
