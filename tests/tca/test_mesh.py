"""Mesh cycle (neighbouring pairs, TE0 envelope) on the closed-form sphere/torus pair.

Truth: pair j at phase phi1 is pair 0 at phi1 + 2 pi j / z1 (rigid rotation of both
teeth), so each pair's TE0 comes from the independent brentq root of
tests/tca/analytic.py at the shifted phase.
"""

import numpy as np
import pytest

from gearcontact.tca.mesh import mesh_cycle
from gearcontact.tca.solve import ARCSEC_PER_RAD, ContactGuess

from .analytic import sphere_torus_case

Z1 = 40   # pitch 9 deg: the analytic contact exists over +-20 deg


@pytest.fixture(scope="module")
def cycle():
    case = sphere_torus_case()
    start = ContactGuess(np.pi / 2, 0.0, case.tube_angle, 0.0, 0.0, 0.0)
    return case, mesh_cycle(case.pinion, case.gear, case.kin, pinion_teeth=Z1,
                            start=start, phases=31, pairs=1, center="start")


def test_pairs_are_shifted_truths_and_envelope(cycle):
    case, cyc = cycle
    pitch = 2 * np.pi / Z1
    assert len(cyc.phi1_rad) == 31
    assert cyc.phi1_rad[-1] - cyc.phi1_rad[0] == pytest.approx(pitch, rel=1e-12)
    phi2_ref = case.truth(0.0)[0]
    te_truth = np.empty((3, 31))
    for a, j in enumerate(cyc.pair_offsets):
        for k, phi in enumerate(cyc.phi1_rad):
            shifted = phi + j * pitch
            te_truth[a, k] = (case.truth(shifted)[0] - phi2_ref - shifted / case.kin.ratio)
    te_truth *= ARCSEC_PER_RAD
    # TE0 to 1e-12 rad from the Newton tolerance: 1e-6 arcsec
    np.testing.assert_allclose(cyc.te0_pairs_arcsec, te_truth, atol=1e-6)
    # the sphere meets the torus from behind its normal: gear pushed forwards
    mp = cyc.contact[cyc.mean_index]
    assert cyc.envelope_is_max == bool(mp.normal @ np.cross([0, 0, 1.0], mp.point_mm) < 0)
    env = te_truth.max(axis=0) if cyc.envelope_is_max else te_truth.min(axis=0)
    np.testing.assert_allclose(cyc.envelope_arcsec, env, atol=1e-6)
    assert cyc.te0_pp_arcsec == pytest.approx(env.max() - env.min(), abs=2e-6)
    assert (cyc.pairs_in_contact == 3).all()


def test_transmitting_contact_geometry(cycle):
    case, cyc = cycle
    pitch = 2 * np.pi / Z1
    for k in (0, 10, 30):
        j = cyc.active_pair[k]
        _, point, normal, k_max, k_min = case.truth(cyc.phi1_rad[k] + j * pitch)
        np.testing.assert_allclose(cyc.contact[k].point_mm, point, atol=1e-9)
        assert cyc.curvature[k].kappa_min_per_mm == pytest.approx(k_min, rel=1e-10)
        assert cyc.ellipse[k].semi_minor_mm == pytest.approx(
            np.sqrt(2 * 6.35e-3 / k_max), rel=1e-10)


def test_short_path_is_reported():
    case = sphere_torus_case()
    start = ContactGuess(np.pi / 2, 0.0, case.tube_angle, 0.0, 0.0, 0.0)
    from .analytic import Torus
    g = case.gear
    narrow = Torus(g.center, g.frame, g.core_radius, g.tube_radius, g.u_range, (-0.01, 0.01))
    with pytest.raises(ValueError, match="contact ratio < 1"):
        mesh_cycle(case.pinion, narrow, case.kin, pinion_teeth=Z1, start=start,
                   phases=11, pairs=1, center="start")
