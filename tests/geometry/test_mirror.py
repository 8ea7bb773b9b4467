"""Left-hand pairs: the mirror image (y -> -y) of the right-hand pair, to rounding."""

from dataclasses import replace

import numpy as np
import pytest

from gearcontact.geometry.flank import build_flanks, with_easeoff
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.kinematics import AssemblyErrors, MeshKinematics
from gearcontact.geometry.mirror import MIRROR
from gearcontact.geometry.sampling import sample_grid

_FIELDS = {"r": 1e-12, "r_u": 1e-10, "r_v": 1e-10, "n": 1e-10,
           "r_uu": 1e-8, "r_uv": 1e-8, "r_vv": 1e-8}


def _unit(x):
    return x / np.linalg.norm(x)


@pytest.fixture(scope="module")
def left(s0003_centred):
    s0003 = s0003_centred[0]
    pair = replace(s0003, pinion_hand="left")
    return pair, build_flanks(pair)


@pytest.mark.parametrize("hand", ["right", "left"])
def test_with_easeoff_is_build_flanks_bit_for_bit(s0003_centred, left, hand):
    """Another ease-off applied to a built flank set (geometry.flank.with_easeoff: what
    analyze does with the synthesis' flanks instead of building them again) is
    build_flanks of that pair bit for bit, for both hands (a left-hand set eases its
    right-hand twin and mirrors it, as build_flanks does: pi - (pi - psi) is not
    always psi)."""
    pair, base = s0003_centred if hand == "right" else left
    c = pair.easeoff_drive
    varied = replace(pair, easeoff_drive=replace(
        c, profile_crowning_um_per_mm2=1.25 * c.profile_crowning_um_per_mm2 + 0.5,
        bias_um_per_mm2=c.bias_um_per_mm2 + 0.05))
    got, want = with_easeoff(base, varied), build_flanks(varied)
    for side in SIDES:
        g, w = got.pinion.side(side), want.pinion.side(side)
        np.testing.assert_array_equal(g.psi_nodes, w.psi_nodes)
        assert g.normal_sign == w.normal_sign
    assert not np.array_equal(got.pinion.drive.psi_nodes, base.pinion.drive.psi_nodes)


def test_left_hand_flanks_are_the_mirror_image(s0003_centred, left):
    # Every Surface quantity of the left-hand flank at (u, v) is M times the right-hand
    # one (the second fundamental form, hence the principal curvatures, is invariant).
    # Gear: closed form with the reflected cutter frame -> rounding. Pinion: quintic
    # spline of pi - psi vs pi - spline(psi): rounding of psi (~1e-16 rad) amplified by
    # k derivatives ~ R / h^k (R ~ 40 mm, node spacing h ~ 0.02-0.05 mm): tolerances
    # 1e-12 mm (r), 1e-10 (first), 1e-8 1/mm (second; measured 1.3e-10).
    flanks = s0003_centred[1]
    _, lh = left
    for member in ("gear", "pinion"):
        for side in SIDES:
            a, b = flanks.flank(member, side), lh.flank(member, side)
            assert a.u_range == b.u_range and a.v_range == b.v_range
            for u in np.linspace(*a.u_range, 5):
                for v in np.linspace(*a.v_range, 5):
                    p, q = a.point(u, v), b.point(u, v)
                    for f, tol in _FIELDS.items():
                        assert np.allclose(MIRROR @ getattr(p, f), getattr(q, f), rtol=0,
                                           atol=tol), (member, side, f)
            ka = sample_grid(a, 8, 8).curvatures_per_mm
            kb = sample_grid(b, 8, 8).curvatures_per_mm
            assert np.abs(ka - kb).max() < 1e-8   # 1/mm, rounding of the above


def test_left_hand_pinion_is_left_handed(left):
    # ISO/AGMA hand (as tests/geometry/test_flank.py::test_hands): right-hand <=>
    # t_out . (axis x e_r) > 0 with the tooth trace t_out heel-wards at the pitch point.
    # The pinion axis of the left-hand pair runs through (0, +E, 0).
    pair, lh = left
    b = lh.blank
    P = np.array(b.pitch_point_mm)
    assert P[1] > 0   # mirrored: the pitch point lies on the +y side
    t = _unit(lh.kinematics.relative_velocity(P))
    g2 = _unit(P - np.array([0.0, 0.0, b.gear_apex_z_mm]))
    t = t if t @ g2 > 0 else -t
    z, x = np.array([0, 0, 1.0]), np.array([1.0, 0, 0])
    e_r2 = _unit(P * [1, 1, 0])
    e_r1 = _unit((P - [0, pair.offset_mm, 0]) * [0, 1, 1])
    assert t @ np.cross(z, e_r2) > 0     # gear: right hand
    assert t @ np.cross(x, e_r1) < 0     # pinion: left hand


def test_left_hand_kinematics_mirror():
    # v12 is a velocity: v_L(M X) = M v_R(X); poses: R_L(phi) = M R_R(phi) M and the
    # pinion centre reflected, with assembly errors (rounding only: 1e-12).
    err = AssemblyErrors(E_mm=0.1, P_mm=-0.05, G_mm=0.07, alpha_deg=0.03)
    rh = MeshKinematics(offset_mm=25.4, ratio=41 / 11, errors=err)
    lh = MeshKinematics(offset_mm=25.4, ratio=41 / 11, errors=err, hand="left")
    X = np.random.default_rng(3).uniform(-80, 80, (20, 3))
    assert np.allclose(lh.relative_velocity(X @ MIRROR), rh.relative_velocity(X) @ MIRROR,
                       rtol=0, atol=1e-12)
    for phi in (-0.4, 0.0, 0.9):
        for pose in ("gear_pose", "pinion_pose"):
            (Rr, tr), (Rl, tl) = getattr(rh, pose)(phi), getattr(lh, pose)(phi)
            assert np.allclose(Rl, MIRROR @ Rr @ MIRROR, rtol=0, atol=1e-15)
            assert np.allclose(tl, MIRROR @ tr, rtol=0, atol=1e-15)


def test_left_hand_tca_is_the_mirror_image(s0003_centred, left):
    # The whole TCA of the mirrored pair (assembly errors of s0003-centred: none) meets
    # the right-hand one: per phase TE0 (Newton stops at 1e-11 mm, i.e. ~1e-7 arcsec),
    # contact points mirrored (1e-6 mm), relative principal curvatures (1e-9 1/mm).
    # Measured: 1.2e-10 arcsec on TE0.
    from gearcontact.tca.analysis import analyze_pair
    s0003, flanks = s0003_centred
    pair, lh = left
    a = analyze_pair(s0003, side="drive", flanks=flanks, phases=21)[0]
    b = analyze_pair(pair, side="drive", flanks=lh, phases=21)[0]
    ta, tb = a.table, b.table
    assert np.array_equal(np.isnan(ta.te0_arcsec), np.isnan(tb.te0_arcsec))
    assert np.nanmax(np.abs(ta.te0_arcsec - tb.te0_arcsec)) < 1e-6
    assert a.table.te0_pp_arcsec == pytest.approx(b.table.te0_pp_arcsec, abs=1e-6)
    assert np.nanmax(np.abs(ta.point_mm @ MIRROR - tb.point_mm)) < 1e-6
    for f in ("A_minus_per_mm", "B_minus_per_mm"):
        assert np.nanmax(np.abs(getattr(ta, f) - getattr(tb, f))) < 1e-9
    assert np.allclose(MIRROR @ a.mean_point.point_mm, b.mean_point.point_mm, atol=1e-6)
    ca, cb = a.mean_curvature, b.mean_curvature
    assert ca.kappa_max_per_mm == pytest.approx(cb.kappa_max_per_mm, abs=1e-9)
    assert ca.kappa_min_per_mm == pytest.approx(cb.kappa_min_per_mm, abs=1e-9)


@pytest.mark.parametrize("side", SIDES)
def test_left_hand_conjugate_nodes_meet_the_mirrored_meshing_equation(left, side):
    # The reflected node solutions of the left-hand conjugate flank satisfy the equation
    # of meshing of the left-hand kinematics, f = N_f . v12(X_f) (1e-9 mm/rad, as the
    # right-hand nodes), and its exact solves lie on its (mirrored) spline sheet
    # (5e-5 mm, the interpolation tolerance of test_conjugate.py).
    _, lh = left
    c = lh.pinion_conjugate.side(side)
    n = c.nodes
    f = np.einsum("...i,...i->...", n.n_f, lh.kinematics.relative_velocity(n.x_f_mm))
    assert np.abs(f).max() < 1e-9
    rng = np.random.default_rng(5)
    u, v = rng.uniform(*c.u_range, 50), rng.uniform(*c.v_range, 50)
    ex, s = c.exact(u, v), c.evaluate(u, v)
    assert np.linalg.norm(s.r - ex.x1_mm, axis=-1).max() < 5e-5
    assert np.linalg.norm(s.n - ex.n1, axis=-1).max() < 1e-7


def _design_point(pair, flanks, side="drive"):
    from gearcontact.tca.design_point import conjugate_contact, evaluate_design_point
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    gear = flanks.flank("gear", side)
    start = conjugate_contact(flanks.pinion_conjugate.side(side), gear, pair, u_m, v_m)
    return evaluate_design_point(flanks.flank("pinion", side), gear, pair, start,
                                 torque_nm=64.5, phases=21)


def test_left_hand_design_point_reports_the_right_hand_angles(s0003_centred, left):
    # The synthesis' design point (TE0 vertex, paint ellipse, path direction) of the mirror
    # image is the same bearing: the path and ellipse angles, measured in the flank frame
    # (l, p, n) that the reflection turns left-handed, must come out with the right-hand
    # pair's sign (a --path-angle-deg target means the same bearing for both hands).
    # Tolerance 1e-6 deg: the mirrored TCA agrees to rounding (test above, 1e-6 mm on
    # the contact points over a path step of ~1 mm).
    s0003, flanks = s0003_centred
    pair, lh = left
    a, b = _design_point(s0003, flanks), _design_point(pair, lh)
    # not trivially 0 (measured 0.825 deg on the gear flank: a sign error would put the
    # hands 1.65 deg apart, 1e6 times the tolerance)
    assert np.isfinite(a.path_angle_deg) and abs(a.path_angle_deg) > 0.5
    assert b.path_angle_deg == pytest.approx(a.path_angle_deg, abs=1e-6)
    assert b.ellipse_angle_deg == pytest.approx(a.ellipse_angle_deg, abs=1e-6)
    assert b.te0_pp_arcsec == pytest.approx(a.te0_pp_arcsec, abs=1e-6)
    assert np.allclose(MIRROR @ a.point_mm, b.point_mm, atol=1e-6)
