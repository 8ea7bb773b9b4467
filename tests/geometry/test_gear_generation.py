"""geometry.gear_generation: the generated gear where the formate gear undercuts its
conjugate pinion (issue 28 item 1: ratios 1-10, the 1:1 miter pair).

Independent truths:
(a) the switch rule keeps every pair that generated before formate (s0003, the examples);
(b) on the generated gear's pitch cone, the mean section's flank point is the crown
    gear's tooth point rolled onto the cone: the development of the pitch cone onto the
    pitch plane (an isometry) maps the cutter circle of radius rho about the cutter
    centre C to the gear's tooth trace, so the point's azimuth from the mean point P is
    theta / sin(delta2) (theta: angle at the apex between OP and the circle point at
    the mean cone distance), its spiral angle the circle's angle to the radius there, its
    pressure angle the blade angle (plane geometry of place_cutter, no envelope);
(c) for a spiral bevel pair (offset 0) the conjugate pinion of the generated gear is the
    pinion the same crown gear generates (basic_settings.crown_pinion_setups: the blade
    surfaces rolled with the pinion, a different frame chain and solver);
(d) TCA on the unmodified conjugate flanks: line contact, TE0 = 0.
"""

import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from gear_sheets import face_node_arc_mm

from gearcontact.geometry.basic_settings import crown_pinion_setups
from gearcontact.geometry.cutter import place_cutter
from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry import gear_generation as gear_generation_module
from gearcontact.geometry.gear_generation import gear_generation, generated_gear_sheets
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.generated import generated_pinion_flank
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.line_contact import line_contact
from gearcontact.tca.types import ContactGuess

_ROOT = Path(__file__).resolve().parents[2]
_F2 = _ROOT / "examples" / "iso23509_f2_spiral_bevel.toml"


def _spiral_bevel(z1: int, z2: int):
    """Issue 28's miter reproduction: ISO 23509 F.2 with other tooth numbers and a
    25 mm face (F.2's gear addendum factor kept: a long pinion addendum)."""
    pair = load_pair(_F2)
    return replace(pair, pinion_teeth=z1, gear_teeth=z2, gear_face_width_mm=25.0,
                   pinion_face_width_mm=25.0)


@pytest.fixture(scope="module")
def miter():
    return _spiral_bevel(20, 20)


@pytest.mark.parametrize("name", ["s0003", "iso23509_f3", "hypoid_11x41_rear_axle",
                                  "iso23509_f2_spiral_bevel"])
def test_pairs_that_generated_before_keep_the_formate_gear(name):
    pair = load_pair(name if name == "s0003" else _ROOT / "examples" / f"{name}.toml")
    assert gear_generation(pair)[0] == "formate"


def test_the_miter_pair_gets_the_generated_gear(miter):
    # the formate gear undercuts its pinion (77 % of the gear addendum without partner)
    assert gear_generation(miter)[0] == "generated"


def _crown_trace(pair, side):
    """Azimuth offset from P (rad), spiral angle (deg) of the crown gear's tooth trace at
    the mean cone distance, from the cutter circle in the pitch plane (module doc (b))."""
    b = pair.blank
    pl, inside, outside = place_cutter(b, point_width_mm=pair.cutter.point_width_mm)
    rho = (inside if side == "drive" else outside).radius_pitch_mm
    apex = np.array([0.0, 0.0, b.gear_apex_z_mm])
    gen = np.asarray(b.pitch_point_mm) - apex
    r_m = float(np.linalg.norm(gen))
    gen /= r_m
    lat = np.cross(pl.axis, gen)
    c = np.array([(pl.centre_mm - apex) @ gen, (pl.centre_mm - apex) @ lat])
    # intersection of |x| = R_m and |x - c| = rho nearest P = (R_m, 0)
    d = float(np.linalg.norm(c))
    a = (r_m ** 2 - rho ** 2 + d ** 2) / (2.0 * d)
    h = math.sqrt(r_m ** 2 - a ** 2)
    e = c / d
    pts = [a * e + s * h * np.array([-e[1], e[0]]) for s in (1.0, -1.0)]
    x = min(pts, key=lambda p: np.linalg.norm(p - [r_m, 0.0]))
    t = np.array([-(x - c)[1], (x - c)[0]])
    beta = math.degrees(math.acos(abs(t @ x) / (np.linalg.norm(t) * r_m)))
    return math.atan2(x[1], x[0]) / math.sin(math.radians(b.pitch_angle_gear_deg)), beta


@pytest.mark.parametrize("side", SIDES)
def test_generated_gear_is_the_crown_gear_rolled_onto_the_pitch_cone(miter, side):
    # (b): azimuth to 1e-9 rad, spiral and pressure angle to 1e-6 deg (the envelope is
    # solved to 1e-10 mm and sampled by a quintic spline good to 1e-10 mm; measured
    # 1e-12 deg). The 35 deg of the blank hold at P, between the two flanks: the inside
    # and outside blade circles cross the mean section at 32.97 and 37.06 deg
    b = miter.blank
    sheet = generated_gear_sheets(miter)[side]
    p = sheet.point(b.dedendum_gear_mm, 0.0)
    P = np.asarray(b.pitch_point_mm)
    dpsi = math.atan2(p.r[1], p.r[0]) - math.atan2(P[1], P[0])
    want_dpsi, want_beta = _crown_trace(miter, side)
    assert abs(abs(dpsi) - abs(want_dpsi)) < 1e-9
    # on the pitch cone at the mean cone distance
    apex = np.array([0.0, 0.0, b.gear_apex_z_mm])
    gen = (p.r - apex) / np.linalg.norm(p.r - apex)
    assert np.linalg.norm(p.r - apex) == pytest.approx(b.mean_cone_distance_gear_mm, abs=1e-9)
    d2 = math.radians(b.pitch_angle_gear_deg)
    assert math.acos(gen[2]) == pytest.approx(d2, abs=1e-12)
    az = math.atan2(p.r[1], p.r[0])
    normal = np.array([math.cos(d2) * math.cos(az), math.cos(d2) * math.sin(az), -math.sin(d2)])
    alpha = math.degrees(math.asin(abs(p.n @ normal)))
    trace = np.cross(normal, p.n - (p.n @ normal) * normal)
    beta = math.degrees(math.acos(abs(trace @ gen) / np.linalg.norm(trace)))
    assert alpha == pytest.approx(b.pressure_angle_drive_deg if side == "drive"
                                  else b.pressure_angle_coast_deg, abs=1e-6)
    assert beta == pytest.approx(want_beta, abs=1e-6)


@pytest.fixture(scope="module")
def miter_flanks(miter):
    return build_flanks(miter, n_u=30, n_v=40)


@pytest.mark.parametrize("side", SIDES)
def test_conjugate_pinion_is_the_crown_gears_pinion(miter, miter_flanks, side):
    # (c): exact conjugate points against the crown-gear pinion's spline (30 x 40
    # nodes, error ~3e-9 mm), up to one turn about the pinion axis (the angular position
    # of a machined pinion is a mounting choice): 1e-6 mm wherever the generating gear
    # point lies on the gear's face (measured 1e-8 mm). The pinion's corners beyond it
    # are generated by the gear sheet continued past the face: where the gear's own
    # envelope ends there (coast toe, blade tip), by Taylor rows, 0.66 um off the crown
    # pinion at the coast toe-root corner (module gear_generation)
    conj = miter_flanks.pinion_conjugate.side(side)
    assert miter_flanks.gear_generation == "generated"
    crown, _ = generated_pinion_flank(crown_pinion_setups(miter)[side], miter.blank,
                                      pinion_face_width_mm=miter.pinion_face_width_mm,
                                      n_u=30, n_v=40)
    (u0, u1), (v0, v1) = conj.u_range, conj.v_range
    (c0, c1) = crown.u_range
    U, V = np.meshgrid(np.linspace(max(u0, c0), min(u1, c1), 9), np.linspace(v0, v1, 11))
    ex = conj.exact(U, V)
    gear = miter_flanks.gear.side(side)
    on_face = gear.boundary.contains(*gear.surface_parameters(ex.h_mm, ex.theta_rad))
    assert on_face.mean() > 0.8
    dpsi = np.arctan2(ex.x1_mm[..., 2], ex.x1_mm[..., 1]) - crown.psi(U, V)
    dpsi = np.angle(np.exp(1j * (dpsi - dpsi[on_face][0])))
    assert np.ptp((dpsi * conj.cone.radius_mm(U, V))[on_face]) < 1e-6


def test_the_checks_generated_sheets_are_built_once(miter, miter_flanks, monkeypatch):
    # issue 28: design's check builds the generated gear sheets; build_flanks given the
    # check's result reuses them (one generation, the same objects) and its flanks are
    # bit for bit those built from scratch (miter_flanks, built without the check)
    calls = []
    made = gear_generation_module.generated_gear_sheets
    monkeypatch.setattr(gear_generation_module, "generated_gear_sheets",
                        lambda pair: calls.append(pair) or made(pair))
    checked = check_generation(miter)
    fs = build_flanks(replace(miter, name="renamed"), n_u=30, n_v=40,
                      checked=checked)
    assert len(calls) == 1
    for side in SIDES:
        assert fs.gear.side(side) is checked[side]["gear_flank"]
        for member in ("gear", "pinion", "pinion_conjugate"):
            a, b = getattr(fs, member).side(side), getattr(miter_flanks, member).side(side)
            assert np.array_equal(a.psi_nodes, b.psi_nodes)
            assert np.array_equal(a.u_nodes, b.u_nodes) and np.array_equal(a.v_nodes, b.v_nodes)
    assert fs.mean_contact == miter_flanks.mean_contact
    assert fs.pinion_normal_thickness_mm == miter_flanks.pinion_normal_thickness_mm
    # a check made for another geometry is refused, naming both pairs, before any work
    other = replace(miter, gear_face_width_mm=24.0, pinion_face_width_mm=24.0)
    with pytest.raises(ValueError, match="does not hold the flank geometry"):
        build_flanks(other, n_u=30, n_v=40, checked=checked)
    assert len(calls) == 1


def test_tca_of_the_unmodified_generated_pair_is_line_contact(miter, miter_flanks):
    # (d): TE0 = 0 to 1e-4 arcsec (as tests/geometry/test_generated.py for the machined
    # pairs) on at least 15 of 21 phases of one pitch
    fs, side = miter_flanks, "drive"
    m = fs.mean_contact[side]
    start = ContactGuess(*m["pinion_uv"], *m["gear_uv"], miter.ratio * m["phi2_rad"],
                         m["phi2_rad"])
    r = line_contact(fs.pinion_conjugate.side(side), fs.gear.side(side),
                     miter.kinematics(with_errors=False), start,
                     pinion_teeth=miter.pinion_teeth, phases=21)
    assert np.isfinite(r.te0_arcsec).sum() >= 15
    assert r.te0_max_abs_arcsec < 1e-4


def test_design_names_the_gear_generation(tmp_path, miter):
    from gearcontact.geometry.pair import pair_to_toml
    path = tmp_path / "miter.toml"
    path.write_text(pair_to_toml(miter))
    run = subprocess.run([sys.executable, "-m", "gearcontact", "design", "--pair", str(path)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "gear flanks: generated (the blade rolled on the crown gear" in run.stdout
    assert "ratio of roll 1/sin(delta2) = 1.4142" in run.stdout     # 1/sin(45 deg)


def test_standard_settings_of_the_miter_pair_cut_the_generated_gear(miter):
    # the settings --machine-settings writes for a pair whose default gear is generated:
    # the gear's are generated_gear_setups' (the settings the default flanks roll),
    # ratio of roll 1/sin(delta2) = sqrt(2) for the miter (closed form, to 1e-12: float
    # rounding); without crowning the pinion's are exactly the crown gear's pinion
    # (module doc (c): the pinion exactly conjugate to the generated gear)
    from gearcontact.geometry.basic_settings import generated_gear_setups, standard_setups

    std = standard_setups(miter, lengthwise_crowning_um=0.0, blade_profile_crowning_um=0.0,
                          gear_generation="generated")
    gear, crown = generated_gear_setups(miter), crown_pinion_setups(miter)
    for side in SIDES:
        assert std["gear", side] == gear[side]
        assert std["pinion", side] == crown[side]
        assert abs(std["gear", side].settings.ratio_of_roll - math.sqrt(2.0)) < 1e-12


def test_an_unknown_gear_generation_is_refused(miter):
    # (a hypoid's generated gear has settings: tests/geometry/test_basic_settings.py)
    from gearcontact.geometry.basic_settings import member_setups
    from gearcontact.validation import InputRangeError

    with pytest.raises(InputRangeError, match="gear_generation"):
        member_setups(miter, "machine")


def test_design_machine_settings_of_the_miter_pair_write_the_generated_gear(tmp_path, miter):
    # through the CLI (~6 s): the written pair's gear flanks, cut from its settings at
    # the machine path's 120 x 150 nodes, against the default generated gear's exact
    # envelope nodes on the face (the nodes of generated_gear_sheets: node solves to
    # 1e-10): 1e-8 mm along the arc (measured 7e-14 drive, 4.4e-9 coast: the written
    # sheet's spline error near the coast root); design on the written file exits 0
    from gearcontact.cli import main
    from gearcontact.geometry.generated import generated_gear_flank
    from gearcontact.geometry.pair import pair_to_toml

    path = tmp_path / "miter.toml"
    path.write_text(pair_to_toml(miter))
    out = tmp_path / "out"
    assert main(["design", "--pair", str(path), "--machine-settings", "--out", str(out)]) == 0
    written = load_pair(out / "machine_settings.toml")
    setups = {(s.member, s.side): s for s in written.machine}
    ref = generated_gear_sheets(miter)
    for side in SIDES:
        assert setups["gear", side].settings.ratio_of_roll == pytest.approx(
            1.0 / math.sin(math.radians(miter.blank.pitch_angle_gear_deg)), abs=1e-12)
        cut, _ = generated_gear_flank(setups["gear", side], written.blank,
                                      gear_face_width_mm=written.gear_face_width_mm)
        arc = face_node_arc_mm(cut, ref[side])
        assert arc.size > 500
        assert np.abs(arc).max() < 1e-8
    assert main(["design", "--pair", str(out / "machine_settings.toml")]) == 0


@pytest.mark.slow
def test_analyze_builds_the_generated_sheets_once(tmp_path, monkeypatch):
    # issue 28: run_analysis checks the 20/30 pair (design's checks: the generated
    # gear's sheets), synthesizes its ease-off and reaches the TCA with one generation
    # of the sheets (before: two, about 10-20 s of the miter's run); the TCA gets the
    # flanks the synthesis built, on the check's gear sheets (the same objects). 11 s
    # at load ~2 (slow: the synthesis and two flank builds)
    import gearcontact.report.analyze as analyze

    calls, seen = [], []
    made = gear_generation_module.generated_gear_sheets
    monkeypatch.setattr(gear_generation_module, "generated_gear_sheets",
                        lambda pair: calls.append(made(pair)) or calls[-1])

    class Reached(Exception):
        pass

    def analyze_pair(pair, *, flanks, **_):
        seen.append(flanks)
        raise Reached

    monkeypatch.setattr(analyze, "analyze_pair", analyze_pair)
    pair = replace(_spiral_bevel(20, 30), gear_addendum_factor=0.33889)
    with pytest.raises(Reached):
        analyze.run_analysis(pair, out_dir=tmp_path, progress=False, figures=False)
    assert len(calls) == 1
    (flanks,) = seen
    assert flanks.gear_generation == "generated"
    assert all(flanks.gear.side(side) is calls[0][side] for side in SIDES)
