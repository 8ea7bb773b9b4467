"""Cradle machine: blade profiles, generating kinematics, settings validation, TOML tables.

Truths: the circular blade profile (a circle of radius r_b, tangent angle alpha_0 at
l_ref), rolling of a pitch cone on the cradle plane (R_a = 1/sin(gamma_m): zero
velocity along the pitch line, Litvin & Fuentes 2004, sec. 20.3), the modified-roll
Taylor series (phi''(0) = -2C R_a, phi'''(0) = -6D R_a by definition), and the analytic
velocity against a central difference of the position.
"""

import dataclasses
import math
import tomllib

import numpy as np
import pytest

from gearcontact.geometry.basic_settings import complementary_pinion_setups, formate_gear_setups
from gearcontact.geometry.machine import (BladeSettings, MachineKinematics, MachineSettings,
                                          blade_point, blade_profile)
from gearcontact.geometry.pair import load_pair, pair_to_toml, parse_pair
from gearcontact.validation import InputRangeError

F2 = "examples/iso23509_f2_spiral_bevel.toml"


def test_straight_blade_is_a_cone_with_its_normal():
    b = BladeSettings(kind="outside", blade_angle_deg=22.0, point_radius_mm=50.0)
    l = np.linspace(0.0, 8.0, 9)
    rho, z, alpha, _ = blade_profile(b, l)
    a = math.radians(22.0)
    # outside blade: radius grows behind the tip by tan(alpha) per mm of depth
    assert np.allclose(rho, 50.0 + l * math.sin(a), atol=1e-13)
    assert np.allclose(z, l * math.cos(a), atol=1e-13)
    x, n = blade_point(b, l, 0.3)
    t = np.gradient(x, l, axis=0)   # exact for a straight profile
    assert np.abs(np.einsum("ij,ij->i", t, n)).max() < 1e-13
    assert np.allclose(np.linalg.norm(n, axis=-1), 1.0, atol=1e-15)


@pytest.mark.parametrize("radius", [150.0, -150.0])
def test_curved_blade_is_a_circle(radius):
    # the profile (rho, z) of a curved blade lies on one circle of radius |r_b|, and at
    # l_ref its tangent makes alpha_0 with the cutter axis (1e-12 mm / rad: closed form)
    b = BladeSettings(kind="inside", blade_angle_deg=20.0, point_radius_mm=60.0,
                      profile_radius_mm=radius, profile_reference_mm=3.0)
    l = np.linspace(0.0, 8.0, 17)
    rho, z, alpha, _ = blade_profile(b, l)
    # centre on the normal side at distance r_b: (rho, z) - r_b * (-n) in the (rho, -z) plane
    n_rho, n_z = np.cos(alpha), np.sin(alpha)   # normal (sigma cos, -sin) with -z up
    c_rho, c_z = rho - radius * n_rho, z - radius * n_z
    assert np.ptp(c_rho) < 1e-10 and np.ptp(c_z) < 1e-10
    assert np.allclose(np.hypot(rho - c_rho, z - c_z), abs(radius), atol=1e-10)
    k = int(np.argmin(np.abs(l - 3.0)))
    assert alpha[k] == pytest.approx(math.radians(20.0), abs=1e-15)


def test_rolling_cone_has_zero_velocity_on_the_pitch_line():
    # R_a = 1/sin(gamma_m): the work's pitch cone (apex at the machine centre, pitch
    # angle gamma_m) rolls on the cradle plane; points of the cradle plane on x_m (the
    # instantaneous axis) do not move relative to the work (|v| < 1e-12 mm/rad)
    g = 35.0
    st = MachineSettings(radial_distance_mm=0.0, cradle_angle_deg=0.0,
                         machine_root_angle_deg=g, ratio_of_roll=1.0 / math.sin(math.radians(g)))
    kin = MachineKinematics(st)
    pts = np.array([[10.0, 0.0, 0.0], [55.0, 0.0, 0.0], [80.0, 0.0, 0.0]])
    _, _, v = kin.to_work(pts, np.tile([0.0, 0.0, 1.0], (3, 1)), 0.0)
    assert np.abs(v).max() < 1e-12
    # off the line they do move (the test is not vacuous)
    _, _, v = kin.to_work(np.array([50.0, 5.0, 0.0]), np.array([0.0, 0.0, 1.0]), 0.0)
    assert np.linalg.norm(v) > 1.0


def test_modified_roll_and_helical_motion_and_velocity():
    st = MachineSettings(radial_distance_mm=60.0, cradle_angle_deg=40.0,
                         machine_root_angle_deg=-2.0, machine_centre_to_back_mm=1.5,
                         sliding_base_mm=-3.0, blank_offset_mm=12.0, ratio_of_roll=4.2,
                         modified_roll=(0.05, -0.3, 0.7), tilt_deg=15.0, swivel_deg=-70.0,
                         helical_motion=(2.0, -1.0))
    kin = MachineKinematics(st)
    h = 1e-4
    psi = np.array([-h, 0.0, h])
    phi, dphi = kin.work_rotation(psi)
    # phi = Ra (psi - 2C psi^2/2 - 6D psi^3/6 - ...): phi'(0) = Ra, phi''(0) = -2C Ra
    assert dphi[1] == pytest.approx(4.2, abs=1e-15)
    assert (phi[2] - 2 * phi[1] + phi[0]) / h**2 == pytest.approx(-0.05 * 4.2, rel=1e-6)
    # analytic dX_w/dpsi (rotation, modified roll, helical motion) = central difference
    # of the position (truncation ~h^2 |X'''| ~ 1e-6 mm/rad; 1e-5 required)
    x_t = np.array([30.0, 4.0, -2.0])
    n_t = np.array([0.0, 0.6, 0.8])
    for p0 in (0.0, 0.2, -0.35):
        x_p = kin.to_work(x_t, n_t, p0 + 1e-4)[0]
        x_m = kin.to_work(x_t, n_t, p0 - 1e-4)[0]
        v = kin.to_work(x_t, n_t, p0)[2]
        assert np.allclose((x_p - x_m) / 2e-4, v, atol=1e-5)


@pytest.mark.parametrize("field, value, allowed", [
    ("tilt_deg", 75.0, "60"), ("machine_root_angle_deg", 95.0, "90"),
    ("radial_distance_mm", -1.0, "0"), ("ratio_of_roll", float("nan"), "finite")])
def test_settings_out_of_range_name_field_value_range(field, value, allowed):
    base = dict(radial_distance_mm=50.0, cradle_angle_deg=10.0, machine_root_angle_deg=20.0)
    with pytest.raises(InputRangeError) as err:
        MachineSettings(**{**base, field: value}, where="machine.pinion.drive")
    msg = str(err.value)
    assert f"machine.pinion.drive.{field}" in msg and allowed in msg


def _f2_machine_pair():
    pair = load_pair(F2)
    setups = tuple(formate_gear_setups(pair).values()) + tuple(
        complementary_pinion_setups(pair).values())
    return dataclasses.replace(pair, machine=setups)


def test_pair_tables_round_trip():
    pair = _f2_machine_pair()
    text = pair_to_toml(pair)
    assert "[machine.pinion.coast]" in text and "[blade.gear.drive]" in text
    assert "[easeoff." not in text
    back = parse_pair(tomllib.loads(text))
    assert back.machine == pair.machine   # floats written at full precision


def test_pair_tables_validated_before_work():
    doc = tomllib.loads(pair_to_toml(_f2_machine_pair()))
    bad = {**doc, "machine": {**doc["machine"], "pinion": {
        **doc["machine"]["pinion"], "drive": {**doc["machine"]["pinion"]["drive"],
                                              "tilt_deg": 80.0}}}}
    with pytest.raises(InputRangeError, match=r"machine\.pinion\.drive\.tilt_deg.*80"):
        parse_pair(bad)
    bad = {**doc, "blade": {**doc["blade"], "gear": {
        **doc["blade"]["gear"], "coast": {**doc["blade"]["gear"]["coast"], "kind": "middle"}}}}
    with pytest.raises(InputRangeError, match=r"blade\.gear\.coast\.kind"):
        parse_pair(bad)
    missing = {**doc, "blade": {k: v for k, v in doc["blade"].items() if k != "pinion"}}
    with pytest.raises(InputRangeError, match=r"\[blade\.pinion\.drive\]"):
        parse_pair(missing)
    both = {**doc, "easeoff": {"drive": {"profile_crowning_um_per_mm2": 1.0}}}
    with pytest.raises(InputRangeError, match="not both"):
        parse_pair(both)
    typo = {**doc, "machine": {**doc["machine"], "gear": {
        **doc["machine"]["gear"], "drive": {**doc["machine"]["gear"]["drive"],
                                           "radial_distanse_mm": 1.0}}}}
    with pytest.raises(InputRangeError, match="radial_distanse_mm"):
        parse_pair(typo)


def test_mirrored_settings_cut_the_mirrored_flanks():
    # a left-hand member is the mirror image (y -> -y) of its right-hand twin; its
    # settings (mirror_setup: cradle angle, swivel, blank offset, 2C, 24E and V_1 change
    # sign) run through the machine chain directly, with the reflected blank, must cut
    # the reflected flanks: formate gear to 1e-11 mm, generated pinion with modified
    # roll and helical motion at every node to 1e-9 mm (exact envelope solves)
    from gearcontact.geometry.generated import formate_gear_flank, generated_pinion_flank
    from gearcontact.geometry.machine import mirror_setup

    pair = load_pair("s0003-centred")
    b = pair.blank
    P = b.pitch_point_mm
    mb = dataclasses.replace(b, pitch_point_mm=(P[0], -P[1], P[2]))
    M = np.diag([1.0, -1.0, 1.0])
    g = formate_gear_setups(pair)["drive"]
    right = formate_gear_flank(g, b, gear_face_width_mm=pair.gear_face_width_mm)
    left = formate_gear_flank(mirror_setup(g), mb, gear_face_width_mm=pair.gear_face_width_mm)
    U, V = np.meshgrid(np.linspace(*right.u_range, 5), np.linspace(*right.v_range, 6))
    assert np.abs(left.evaluate(U, V).r - right.evaluate(U, V).r @ M).max() < 1e-11
    p = complementary_pinion_setups(pair)["coast"]
    p = dataclasses.replace(p, settings=dataclasses.replace(
        p.settings, modified_roll=(0.01, 0.02, 0.05), helical_motion=(0.05, 0.02)))
    assert mirror_setup(p).settings.modified_roll == (-0.01, 0.02, -0.05)
    assert mirror_setup(p).settings.helical_motion == (-0.05, 0.02)
    kw = dict(pinion_face_width_mm=pair.pinion_face_width_mm, n_u=10, n_v=12)
    _, n_right = generated_pinion_flank(p, b, **kw)
    _, n_left = generated_pinion_flank(mirror_setup(p), mb, **kw)
    assert np.abs(n_left.x_mm - n_right.x_mm @ M).max() < 1e-9
    assert np.abs(n_left.psi_rad + n_right.psi_rad).max() < 1e-10


# ------------------------------------------------------------- higher-order blade profile

_HO = dict(blade_angle_deg=20.0, point_radius_mm=60.0, profile_radius_mm=150.0,
           profile_reference_mm=3.0, profile_cubic_per_mm2=0.01,
           profile_quartic_per_mm3=0.004)


@pytest.mark.parametrize("kind", ["inside", "outside"])
def test_higher_order_blade_against_quadrature_and_differences(kind):
    from scipy.integrate import quad
    b = BladeSettings(kind=kind, **_HO)
    sig, a0 = b.sigma, math.radians(20.0)

    def alpha(t):   # the defining series, typed independently of the module
        s = t - 3.0
        return a0 + s / 150.0 + 0.01 * s**2 / 2 + 0.004 * s**3 / 6

    l = np.linspace(-0.4, 12.0, 11)
    rho, z, a, da = blade_profile(b, l)
    # rho, z against adaptive quadrature of rho' = -sigma sin(alpha), z' = cos(alpha)
    # (quad reaches ~1e-14 mm; 1e-12 mm asserted: 16 Gauss nodes integrate to rounding)
    q_rho = [60.0 - sig * quad(lambda t: math.sin(alpha(t)), 0.0, x, epsabs=1e-14)[0] for x in l]
    q_z = [quad(lambda t: math.cos(alpha(t)), 0.0, x, epsabs=1e-14)[0] for x in l]
    assert np.allclose(rho, q_rho, atol=1e-12, rtol=0) and np.allclose(z, q_z, atol=1e-12, rtol=0)
    assert np.allclose(a, [alpha(x) for x in l], atol=1e-15, rtol=0)
    # the exact second derivative d alpha/dl (the profile curvature) against a central
    # difference of alpha (truncation h^2 c_4 / 6 ~ 7e-11 with h = 1e-4; 1e-8 asserted),
    # and the first derivatives of the profile against a central difference of rho, z
    h = 1e-4
    ap, am = blade_profile(b, l + h)[2], blade_profile(b, l - h)[2]
    assert np.allclose(da, (ap - am) / (2 * h), atol=1e-8, rtol=0)
    rp, zp, _, _ = blade_profile(b, l + h)
    rm, zm, _, _ = blade_profile(b, l - h)
    assert np.allclose((rp - rm) / (2 * h), -sig * np.sin(a), atol=1e-8, rtol=0)
    assert np.allclose((zp - zm) / (2 * h), np.cos(a), atol=1e-8, rtol=0)
    # the normal of blade_point is normal to the profile (central difference, 1e-8)
    x_p, _ = blade_point(b, l + h, 0.3)
    x_m, _ = blade_point(b, l - h, 0.3)
    _, n = blade_point(b, l, 0.3)
    assert np.abs(np.einsum("ij,ij->i", (x_p - x_m) / (2 * h), n)).max() < 1e-8


def test_higher_order_terms_vanishing_give_the_circle():
    # a cubic term of 1e-300 takes the quadrature path: it equals the closed-form
    # circle to rounding (1e-13 mm over 12 mm of blade)
    circ = BladeSettings(kind="inside", **{**_HO, "profile_cubic_per_mm2": 0.0,
                                           "profile_quartic_per_mm3": 0.0})
    tiny = dataclasses.replace(circ, profile_cubic_per_mm2=1e-300)
    assert tiny.higher_order and not circ.higher_order
    l = np.linspace(0.0, 12.0, 13)
    assert np.allclose(np.array(blade_profile(tiny, l)), np.array(blade_profile(circ, l)),
                       atol=1e-13, rtol=0)


def test_blade_through_point_keeps_the_profile_shape():
    from gearcontact.geometry.machine import blade_through_point
    b = BladeSettings(kind="outside", **_HO)
    placed = blade_through_point(b, rho_mm=61.2, z_mm=4.5)
    rho, z, a, da = (float(x) for x in blade_profile(placed, placed.profile_reference_mm))
    assert (rho, z) == (pytest.approx(61.2, abs=1e-12), pytest.approx(4.5, abs=1e-12))
    # the same angle and curvature at the reference: the profile slid, not reshaped
    assert a == pytest.approx(math.radians(20.0), abs=1e-15)
    assert da == pytest.approx(1.0 / 150.0, abs=1e-15)


@pytest.mark.parametrize("key, value, allowed", [
    ("profile_cubic_per_mm2", 1.5, "1"), ("profile_quartic_per_mm3", -2.0, "1"),
    ("profile_quartic_per_mm3", float("inf"), "finite")])
def test_higher_order_terms_out_of_range_name_the_key(key, value, allowed):
    with pytest.raises(InputRangeError) as err:
        BladeSettings(kind="inside", blade_angle_deg=20.0, point_radius_mm=60.0,
                      **{key: value}, where="blade.pinion.coast")
    assert f"blade.pinion.coast.{key}" in str(err.value) and allowed in str(err.value)


def test_higher_order_blade_tables_round_trip_and_formate_refusal():
    from gearcontact.geometry.generated import formate_gear_flank
    from gearcontact.geometry.machine import setup_to_tables
    pair = _f2_machine_pair()
    # written only when non-zero: a circular blade's table is unchanged
    assert "profile_quartic_per_mm3" not in pair_to_toml(pair)
    ho = dataclasses.replace(pair.machine[3].blade, profile_quartic_per_mm3=2e-4,
                             profile_cubic_per_mm2=-1e-3)
    machine = pair.machine[:3] + (dataclasses.replace(pair.machine[3], blade=ho),)
    ho_pair = dataclasses.replace(pair, machine=machine + pair.machine[4:])
    assert setup_to_tables(machine[3])[1]["profile_quartic_per_mm3"] == 2e-4
    back = parse_pair(tomllib.loads(pair_to_toml(ho_pair)))
    assert back.machine == ho_pair.machine
    gear = dataclasses.replace(pair.machine[0], blade=dataclasses.replace(
        pair.machine[0].blade, profile_quartic_per_mm3=1e-4))
    with pytest.raises(InputRangeError, match=r"blade\.gear\.drive\.profile_quartic_per_mm3"):
        formate_gear_flank(gear, pair.blank, gear_face_width_mm=pair.gear_face_width_mm)
