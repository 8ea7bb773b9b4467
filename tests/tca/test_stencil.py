"""Gap field and hardware stencil on the closed-form sphere/torus pair.

Truths: (1) each gap sample is checked against an independent line/sphere (closed
form) and line/torus (scalar root) intersection; (2) a quadratic least-squares fit of
the 80 x 80 field recovers the shape-operator curvatures A-, B-.
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcontact.contract.stencil import STENCIL_SPACING_MM, stencil_coordinates
from gearcontact.tca.curvature import contact_ellipse, relative_curvature
from gearcontact.tca.mating import solve_mating_point
from gearcontact.tca.types import ContactGuess
from gearcontact.contract.stencil import read_stencil_csv
from gearcontact.tca.stencil import gap_at, gap_field_80, hardware_stencil, write_stencil_csv

from .analytic import Torus, sphere_torus_case


@pytest.fixture(scope="module")
def case_mp():
    case = sphere_torus_case()
    start = ContactGuess(np.pi / 2, 0.0, case.tube_angle, 0.0, np.radians(4.0), 0.007)
    return case, solve_mating_point(case.pinion, case.gear, case.kin, start)


def _true_gap(case, mp, q, n):
    rot1, t1 = case.kin.pinion_pose(mp.phi1_rad)
    centre = rot1 @ case.pinion.center + t1
    d = q - centre
    # |d + lam n|^2 = Rs^2, root on the near side (lam ~ 0)
    b = d @ n
    lam1 = -b - np.sqrt(b * b - (d @ d - case.pinion.radius ** 2))
    rot2, t2 = case.kin.gear_pose(mp.phi2_rad)
    c2 = rot2 @ case.gear.center + t2
    axis = rot2 @ case.gear.frame[:, 2]

    def torus(lam):
        x = q + lam * n - c2
        h = x @ axis
        rho = np.linalg.norm(x - h * axis)
        return np.hypot(rho - case.gear.core_radius, h) - case.gear.tube_radius

    lam2 = brentq(torus, -2.0, 2.0, xtol=1e-15)
    return lam1 - lam2


def test_stencil_samples_match_independent_intersections(case_mp, tmp_path):
    case, mp = case_mp
    st = hardware_stencil(case.pinion, case.gear, case.kin, mp)
    assert st.on_flank.all() and st.frame_name == "flank"
    e_s, e_t, n = st.frame.T
    for s, t, g in zip(st.s_mm, st.t_mm, st.gap_mm):
        q = mp.point_mm + s * e_s + t * e_t
        # both intersections converge to 1e-11 mm; brentq to 1e-15: 1e-9 mm is ample
        assert g == pytest.approx(_true_gap(case, mp, q, n), abs=1e-9)
    path = write_stencil_csv(st, tmp_path / "gap_stencil.csv")
    lines = path.read_text().splitlines()
    assert lines[0] == "s_mm,t_mm,gap_mm" and len(lines) == 50
    # the format owner's reader checks the baked grid to 1e-9 mm
    g = read_stencil_csv(path)
    np.testing.assert_allclose(g, st.gap_mm, rtol=1e-11, atol=1e-15)
    s0, t0 = stencil_coordinates(STENCIL_SPACING_MM)
    np.testing.assert_array_equal(st.s_mm, s0)
    np.testing.assert_array_equal(st.t_mm, t0)


def test_gap_field_fit_recovers_shape_operator_curvatures(case_mp):
    case, mp = case_mp
    rc = relative_curvature(case.pinion, case.gear, case.kin, mp)
    field = gap_field_80(case.pinion, case.gear, case.kin, mp)
    assert field.gap_mm.shape == (80, 80) and field.on_flank.all()
    ell = contact_ellipse(rc)
    assert field.s_mm.max() == pytest.approx(2 * ell.semi_major_mm * 79 / 80)
    s, t, g = (a.ravel() for a in (field.s_mm, field.t_mm, field.gap_mm))
    design = np.column_stack([np.ones_like(s), s, t, s * s, s * t, t * t])
    c = np.linalg.lstsq(design, g, rcond=None)[0]
    a, b, cc = c[3:]
    h, r = a + cc, np.hypot(a - cc, b)
    # quartic terms of the exact gap bias the fitted quadratic by ~(kappa L)^2/10
    # (< 0.1 % here, L = half extent); 0.5 % states that bound with margin
    assert (h + r) / 2 == pytest.approx(rc.A_minus_per_mm, rel=5e-3)
    assert (h - r) / 2 == pytest.approx(rc.B_minus_per_mm, rel=5e-3)
    # principal frame: the cross term vanishes (symmetry), the gap is zero at P0
    assert abs(b) < 1e-6 * abs(a)


def test_off_flank_points_are_nan_unless_allowed(case_mp):
    case, mp = case_mp
    g = case.gear
    small = Torus(g.center, g.frame, g.core_radius, g.tube_radius, g.u_range,
                  (mp.v2 - 0.01, mp.v2 + 0.01))
    s = np.array([0.0, 0.1, 3.0])
    t = np.zeros(3)
    field = gap_at(case.pinion, small, case.kin, mp, s, t, frame="flank")
    assert field.on_flank.tolist() == [True, True, False]
    assert np.isfinite(field.gap_mm[:2]).all() and np.isnan(field.gap_mm[2])
    ext = gap_at(case.pinion, small, case.kin, mp, s, t, frame="flank", allow_outside=True)
    assert ext.on_flank.tolist() == [True, True, False] and np.isfinite(ext.gap_mm).all()
    assert ext.gap_mm[2] == pytest.approx(
        gap_at(case.pinion, case.gear, case.kin, mp, s, t, frame="flank").gap_mm[2], abs=1e-10)


def test_quadric_fill_of_off_flank_stencil_samples(case_mp):
    """A window over the flank edge is the osculating quadric (1/2) q^T B q at every
    sample; for the torus the flank frame is the principal frame (l = parallel =
    kappa_min), so B = diag(kappa_min, kappa_max). on_flank still records the edge."""
    case, mp = case_mp
    for lo, hi in ((-0.01, 0.01), (-0.003, 0.05)):     # both sides cut; one side cut
        st = hardware_stencil(case.pinion, _cut_torus(case, mp, lo, hi), case.kin, mp,
                              off_flank="quadric")
        assert 0 < st.on_flank.sum() < 49
        _, _, _, k_max, k_min = case.truth(mp.phi1_rad)
        expected = 0.5 * (k_min * st.s_mm ** 2 + k_max * st.t_mm ** 2)
        np.testing.assert_allclose(st.gap_mm, expected, rtol=1e-10, atol=1e-16)
    small = _cut_torus(case, mp, -0.01, 0.01)
    with pytest.raises(ValueError, match="off the flank"):
        write_stencil_csv(hardware_stencil(case.pinion, small, case.kin, mp), "/dev/null")


def _cut_torus(case, mp, lo, hi):
    """The gear torus cut to tube angles v2 + [lo, hi] (a flank edge across the
    stencil)."""
    g = case.gear
    return Torus(g.center, g.frame, g.core_radius, g.tube_radius, g.u_range,
                 (mp.v2 + lo, mp.v2 + hi))


def test_stage_c_reads_the_shape_operator_on_a_window_over_the_edge(case_mp):
    """Truth: the torus/sphere shape-operator curvatures (closed form). Stage C's fp64
    fit of a window cut by the flank edge on one side gives them to 1e-9 relative
    (rounding of the pseudo-inverse); the whole window on the flank carries the true
    gap, whose quartic terms bias the fit (measured 0.13 % on A-, 0.06 % on B- here;
    bound 1 %)."""
    from gearcontact.preview.fit.reference import fit_curvatures

    case, mp = case_mp
    _, _, _, k_max, k_min = case.truth(mp.phi1_rad)
    cut = hardware_stencil(case.pinion, _cut_torus(case, mp, -0.003, 0.05), case.kin, mp,
                           off_flank="quadric")
    fit = fit_curvatures(cut.gap_mm)
    assert fit.A_minus_per_mm == pytest.approx(k_max / 2, rel=1e-9)
    assert fit.B_minus_per_mm == pytest.approx(k_min / 2, rel=1e-9)
    whole = fit_curvatures(hardware_stencil(case.pinion, case.gear, case.kin, mp).gap_mm)
    assert whole.A_minus_per_mm == pytest.approx(k_max / 2, rel=1e-2)
    assert whole.B_minus_per_mm == pytest.approx(k_min / 2, rel=1e-2)
