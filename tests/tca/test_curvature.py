"""Relative curvatures and contact ellipse against the closed-form sphere/torus pair.

Truth (tests/tca/analytic.py): kappa_max = 1/r + 1/Rs along the torus meridian,
kappa_min = cos u/(Rt + r cos u) + 1/Rs along its parallel (the gear's v direction).
"""

import numpy as np
import pytest

from gearcontact.tca.curvature import (PAINT_THICKNESS_MM, contact_ellipse,
                                       relative_curvature)
from gearcontact.tca.solve import solve_tca
from gearcontact.tca.types import ContactGuess

from .analytic import sphere_torus_case


@pytest.fixture(scope="module")
def case_path():
    case = sphere_torus_case()
    start = ContactGuess(np.pi / 2, 0.0, case.tube_angle, 0.0, 0.0, 0.0)
    phis = np.radians(np.linspace(-15.0, 15.0, 7))
    return case, solve_tca(case.pinion, case.gear, case.kin, phis, start=start)


def test_principal_relative_curvatures(case_path):
    case, path = case_path
    for mp in path.points:
        _, _, _, k_max, k_min = case.truth(mp.phi1_rad)
        rc = relative_curvature(case.pinion, case.gear, case.kin, mp)
        # the shape operator is exact: only round-off (1e-12 relative) remains
        assert rc.kappa_max_per_mm == pytest.approx(k_max, rel=1e-10)
        assert rc.kappa_min_per_mm == pytest.approx(k_min, rel=1e-10)
        assert rc.A_minus_per_mm == pytest.approx(k_max / 2, rel=1e-10)
        assert rc.B_minus_per_mm == pytest.approx(k_min / 2, rel=1e-10)
        # kappa_min lies along the torus parallel = the gear's posed r_v direction
        rot = case.kin.gear_pose(mp.phi2_rad)[0]
        rv = rot @ case.gear.point(mp.u2, mp.v2).r_v
        assert abs(rc.dir_min @ rv) / np.linalg.norm(rv) == pytest.approx(1.0, abs=1e-12)
        assert abs(rc.dir_max @ rc.dir_min) < 1e-12
        assert abs(rc.dir_max @ mp.normal) < 1e-12


def test_contact_ellipse_axes_and_orientation(case_path):
    case, path = case_path
    mp = path.points[3]
    _, _, _, k_max, k_min = case.truth(mp.phi1_rad)
    ell = contact_ellipse(relative_curvature(case.pinion, case.gear, case.kin, mp))
    assert ell.semi_major_mm == pytest.approx(np.sqrt(2 * PAINT_THICKNESS_MM / k_min), rel=1e-10)
    assert ell.semi_minor_mm == pytest.approx(np.sqrt(2 * PAINT_THICKNESS_MM / k_max), rel=1e-10)
    # the major axis is along the lengthwise (v) direction of this gear flank
    assert ell.angle_deg == pytest.approx(0.0, abs=1e-9)
    assert ell.ratio == pytest.approx(np.sqrt(k_max / k_min), rel=1e-10)


def test_edge_phase_has_no_curvature(case_path):
    from gearcontact.tca.types import MatingPoint
    case, _ = case_path
    with pytest.raises(ValueError, match="edge-contact phase"):
        relative_curvature(case.pinion, case.gear, case.kin,
                           MatingPoint.edge_phase(0.3, "gear v max"))
