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
