"""Single-patch statistics against the Hertzian patch (Johnson 1985 ch. 4).

For p = p0 sqrt(1 - rho^2) over the contact ellipse: mean = W / (pi a b) = 2/3 p0, and
the area fraction with p >= q is 1 - (q/p0)^2, so p90 = sqrt(0.9) p0 = 0.9487 p0.
Tolerances: mean 2 % (the stair-cased contact area at 16 cells per semi-axis is ~1 %
off), p90 1 % (percentile of ~800 cells), peak 1 % at the centre cell, ellipse
semi-axes within one cell, orientation within 1 degree.
"""

import warnings

import matplotlib
import numpy as np
import pytest

from gearcontact.analytic.hertz import exact_elliptic_hertz
from gearcontact.halfspace.grid import TangentGrid
from gearcontact.halfspace.patch import (ContactAtEdgeWarning, PatchContact, plot_patch,
                                       solve_patch)

from hertz_problems import A_PER_MM, E_STAR_MPA, LOAD_N

matplotlib.use("Agg")


@pytest.mark.parametrize("ratio", [1.0, 10.0, 50.0])
def test_patch_statistics_match_hertz(make_hertz, ratio):
    prob = make_hertz(ratio, 16)
    hz, grid = prob.hertz, prob.grid
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # neither coarse nor edge warnings here
        patch = solve_patch(prob.gap_mm, grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    assert isinstance(patch, PatchContact) and patch.converged
    p0 = hz.p_max_mpa
    assert patch.p_peak_mpa == pytest.approx(p0, rel=0.01)
    assert (patch.peak_x_mm, patch.peak_y_mm) == pytest.approx((0.0, 0.0), abs=1e-12)
    assert patch.p_mean_mpa == pytest.approx(2.0 / 3.0 * p0, rel=0.02)
    assert patch.p90_mpa == pytest.approx(np.sqrt(0.9) * p0, rel=0.01)
    assert patch.contact_area_mm2 == pytest.approx(np.pi * hz.a_mm * hz.b_mm, rel=0.02)
    assert patch.delta_mm == pytest.approx(hz.approach_mm, rel=0.005)
    assert patch.edge_sides == () and not patch.touches_edge
    e = patch.ellipse
    assert abs(e.semi_major_mm - hz.a_mm) <= grid.dx_mm[0]
    assert abs(e.semi_minor_mm - hz.b_mm) <= grid.dy_mm[0]
    assert patch.cells_per_semi_axis == pytest.approx(16.0, abs=1.0)
    assert patch.summary()["n_contact_cells"] == patch.n_contact_cells


def test_rotated_ellipse_is_recovered():
    # Gap A x'^2 + B y'^2 in axes turned by 30 deg: the fitted ellipse must turn too.
    theta, ratio = np.radians(30.0), 4.0
    hz = exact_elliptic_hertz(A_PER_MM, ratio * A_PER_MM, LOAD_N,
                              e_prime_mpa=2 * E_STAR_MPA)
    d = hz.b_mm / 10
    n = 2 * int(np.ceil(1.2 * hz.a_mm / d)) + 1
    grid = TangentGrid.centered(n, n, dx_mm=d, dy_mm=d)
    X, Y = grid.mesh()
    xr, yr = X * np.cos(theta) + Y * np.sin(theta), -X * np.sin(theta) + Y * np.cos(theta)
    patch = solve_patch(A_PER_MM * xr ** 2 + ratio * A_PER_MM * yr ** 2, grid, LOAD_N,
                        e_star_mpa=E_STAR_MPA)
    e = patch.ellipse
    assert np.degrees(e.angle_rad) == pytest.approx(30.0, abs=1.0)
    assert abs(e.semi_major_mm - hz.a_mm) <= d
    assert abs(e.semi_minor_mm - hz.b_mm) <= d
    assert patch.p_peak_mpa == pytest.approx(hz.p_max_mpa, rel=0.01)


def test_contact_reaching_field_edge_is_flagged():
    hz = exact_elliptic_hertz(A_PER_MM, A_PER_MM, LOAD_N, e_prime_mpa=2 * E_STAR_MPA)
    d = hz.a_mm / 12
    grid = TangentGrid.uniform(26, 31, dx_mm=d, dy_mm=d, x0_mm=-0.5 * hz.a_mm,
                               y0_mm=-15 * d)
    X, Y = grid.mesh()
    with pytest.warns(ContactAtEdgeWarning, match="x_min"):
        patch = solve_patch(A_PER_MM * (X ** 2 + Y ** 2), grid, LOAD_N,
                            e_star_mpa=E_STAR_MPA)
    assert patch.edge_sides == ("x_min",) and patch.touches_edge
    assert patch.converged


def test_plot_patch_draws_the_ellipse(make_hertz):
    prob = make_hertz(10.0, 8)
    patch = solve_patch(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    ax = plot_patch(patch)
    x, y = ax.lines[0].get_data()
    e = patch.ellipse
    rho = ((x - e.center_x_mm) / e.semi_major_mm) ** 2 + \
        ((y - e.center_y_mm) / e.semi_minor_mm) ** 2  # angle 0 for this problem
    assert np.allclose(rho, 1.0, atol=1e-9)
    matplotlib.pyplot.close(ax.figure)


def test_plot_patch_clips_the_colour_scale_only_for_edge_spikes(make_hertz):
    # a Hertz patch (peak = p_max, p90 below it but within EDGE_SPIKE_RATIO) keeps the
    # full scale; a patch truncated by the field edge (the half-space edge spike of a
    # flat-ended punch: peak >> p90) gets the scale clipped at EDGE_SPIKE_CLIP x p90
    from gearcontact.halfspace.patch import EDGE_SPIKE_CLIP, EDGE_SPIKE_RATIO
    prob = make_hertz(1.0, 8)
    patch = solve_patch(prob.gap_mm, prob.grid, LOAD_N, e_star_mpa=E_STAR_MPA)
    assert patch.p_peak_mpa <= EDGE_SPIKE_RATIO * patch.p90_mpa
    ax = plot_patch(patch)
    assert ax.collections[0].norm.vmax == pytest.approx(patch.p_peak_mpa, rel=1e-12)
    matplotlib.pyplot.close(ax.figure)
    hz = exact_elliptic_hertz(A_PER_MM, A_PER_MM, LOAD_N, e_prime_mpa=2 * E_STAR_MPA)
    d = hz.a_mm / 12
    grid = TangentGrid.uniform(26, 31, dx_mm=d, dy_mm=d, x0_mm=-0.5 * hz.a_mm,
                               y0_mm=-15 * d)
    X, Y = grid.mesh()
    with pytest.warns(ContactAtEdgeWarning):
        cut = solve_patch(A_PER_MM * (X ** 2 + Y ** 2), grid, 4 * LOAD_N,
                          e_star_mpa=E_STAR_MPA)
    assert cut.p_peak_mpa > EDGE_SPIKE_RATIO * cut.p90_mpa
    ax = plot_patch(cut)
    assert ax.collections[0].norm.vmax == pytest.approx(EDGE_SPIKE_CLIP * cut.p90_mpa)
    matplotlib.pyplot.close(ax.figure)
