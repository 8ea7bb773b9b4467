"""Mesh cycle (neighbouring pairs, TE0 envelope) on the closed-form sphere/torus pair.

Truth: pair j at phase phi1 is pair 0 at phi1 + 2 pi j / z1 (rigid rotation of both
teeth), so each pair's TE0 comes from the independent brentq root of
tests/tca/analytic.py at the shifted phase.
"""

import numpy as np
import pytest

from gearcontact.tca.mesh import mesh_cycle
from gearcontact.tca.types import ARCSEC_PER_RAD, ContactGuess

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
                   phases=11, pairs=1, center="start", edge_contact=False)
    # with edge contact the band's edge circles keep touching the sphere: no gap
    cyc = mesh_cycle(case.pinion, narrow, case.kin, pinion_teeth=Z1, start=start,
                     phases=11, pairs=1, center="start")
    assert np.isfinite(cyc.envelope_arcsec).all()
    assert any(mp.edge_contact for mp in cyc.contact)


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_coarse_phase_grid_follows_the_paths_to_their_ends(s0003_centred, side):
    """7 phases per pitch (substeps of the continuation): the contact path of pair 0
    reaches as far as with 61 phases, to within one coarse step, and its points are
    the fine path's at the shared phases."""
    s0003_pair, s0003_flanks = s0003_centred
    pin, gear = s0003_flanks.flank("pinion", side), s0003_flanks.flank("gear", side)
    kin = s0003_pair.kinematics()
    mean = s0003_flanks.mean_contact[side]
    phi2 = float(mean["phi2_rad"])
    start = ContactGuess(*map(float, mean["pinion_uv"]), *map(float, mean["gear_uv"]),
                         s0003_pair.ratio * phi2, phi2)
    pitch = 2.0 * np.pi / s0003_pair.pinion_teeth
    fine, coarse = (mesh_cycle(pin, gear, kin, pinion_teeth=s0003_pair.pinion_teeth,
                               start=start, phases=k, center="start") for k in (61, 7))
    ends = []
    for cyc in (fine, coarse):
        phi = cyc.path.phi1_rad[~cyc.path.edge] - cyc.path.phi1_ref_rad
        ends.append((phi.min() / pitch, phi.max() / pitch))
    assert ends[1][0] <= ends[0][0] + 1 / 6 + 1e-9 and ends[1][1] >= ends[0][1] - 1 / 6 - 1e-9
    # the same grid points (every 10th fine phase), away from the ends
    shared = coarse.path.te0_arcsec[~coarse.path.edge]
    def key(path, phi):
        return np.round((phi - path.phi1_ref_rad) / pitch * 60).astype(int)

    fine_te = dict(zip(key(fine.path, fine.path.phi1_rad), fine.path.te0_arcsec))
    keys = key(coarse.path, coarse.path.phi1_rad[~coarse.path.edge])
    assert np.allclose(shared, [fine_te[k] for k in keys], atol=1e-6)
