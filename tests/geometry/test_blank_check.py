"""The check of typed machine settings against the blank they are meant to cut
(geometry.blank_check; docs/machine_settings.md sec. 2, "The check when a pair is
loaded").

Truths: the files typed from a source that is right pass (the published summary sheet,
tests/geometry/summary_sheets/, against its printed blank; the ISO 23509 F.2 example
examples/machine_settings/iso23509_f2_machine.toml, the standard settings of its blank
typed to 4 decimals, against its blank tables; their left-hand twins), and the same
files with one sign word flipped are caught, the flipped key named: the flip is the
truth (each slip is undone by construction, so the named key is known in advance).
Tolerances: the typed settings' rounding propagated (module docstring of
geometry.blank_check); for the sheet the print's rounding (its inches to 0.0005 in, its
angles to 0.5'), as tests/geometry/test_flank_angles.py propagates it.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

import pytest

from gearcontact.geometry.blank_check import GROSS_SPIRAL_DEG, check_flanks, check_pair_blank
from gearcontact.geometry.blank_statement import StatedBlank, stated_blank
from gearcontact.geometry.machine import mirror_setup, setup_from_tables
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.typed_settings import typed_resolution
from gearcontact.validation import InputRangeError

from .test_flank_angles import _pitch_apex_in

ROOT = Path(__file__).resolve().parents[2]
F2_MACHINE = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"
SHEET = Path(__file__).with_name("summary_sheets") / "hypoid_10x41_no16_gear.toml"
IN = 25.4
MINUTE = 0.5 / 60.0                 # half a printed minute of arc, deg
THOU = 0.0005 * IN                  # half a unit of the print's 3 decimals in inches, mm


def _flip(setups, member, key, fn):
    """``setups`` with ``key`` of every flank of ``member`` changed by ``fn`` (a sheet
    word misread: the same word is typed into both flanks' tables of a member)."""
    return tuple(dataclasses.replace(s, settings=dataclasses.replace(
        s.settings, **{key: fn(getattr(s.settings, key))})) if s.member == member else s
        for s in setups)


def test_typed_resolution():
    # half a unit of the last typed decimal; a zero is exact (a set-up choice)
    assert typed_resolution(94.9385) == pytest.approx(5e-5, rel=1e-12)
    assert typed_resolution(-80.4732) == pytest.approx(5e-5, rel=1e-12)
    assert typed_resolution(20.0) == pytest.approx(0.05, rel=1e-12)
    assert typed_resolution(2.785714) == pytest.approx(5e-7, rel=1e-12)
    assert typed_resolution(0.0) == 0.0


# ------------------------------------------------------------------ the F.2 example

@pytest.fixture(scope="module")
def f2():
    return load_pair(F2_MACHINE)


def test_f2_example_agrees_within_its_typing(f2):
    # the F.2 blank's 35 deg, 20 deg, 81.273 mm against the settings typed to 4
    # decimals: the propagated tolerance of the spiral angle is the worst case of
    # tests/cli/test_design_mean_point.py's hand computation (5.51e-5 deg from S_r and q
    # to +-5e-5; cone distance 1.63e-4 mm), here by finite differences (10 %: the
    # machine root's 5e-5 deg enters here as well, and the differences are one-sided)
    got = check_pair_blank(f2)
    assert got.agrees and not got.gross and got.warnings() == []
    gear = {c.quantity: c for c in got.flanks[0].comparisons}
    assert gear["spiral angle"].tolerance == pytest.approx(5.51e-5, rel=0.1)
    assert gear["mean cone distance"].tolerance == pytest.approx(1.63e-4, rel=0.1)
    assert gear["hand"].measured == "left"
    for f in got.flanks[2:]:     # the pinion: its pressure angle within the model bound
        assert {c.quantity for c in f.comparisons} == {"pressure angle", "root depth", "hand"}


def test_left_hand_twin_agrees(f2):
    # a left-hand pair types its members' own settings (the mirrored ones,
    # machine.mirror_setup; docs sec. 2): the same check passes
    twin = dataclasses.replace(f2, pinion_hand="left",
                               machine=tuple(mirror_setup(s) for s in f2.machine))
    got = check_pair_blank(twin)
    assert got.agrees, got.warnings()
    assert {c.measured for f in got.flanks for c in f.comparisons if c.quantity == "hand"} \
        == {"left", "right"}


@pytest.mark.parametrize("name", ["iso23509_f3", "hypoid_11x41_rear_axle"])
def test_standard_settings_agree_with_their_blank(name):
    # the settings design --machine-settings writes from an ISO 23509 blank (full
    # precision: the tolerances are the solve's 1e-7 and the root datum's bound) agree
    # with that blank, and so do their left-hand twins (truth: the blank they are built
    # from, tests/geometry/test_flank_angles.py to 1e-9)
    from gearcontact.geometry.basic_settings import standard_machine_pair

    pair = standard_machine_pair(load_pair(ROOT / "examples" / f"{name}.toml"))
    twin = dataclasses.replace(pair, pinion_hand="left",
                               machine=tuple(mirror_setup(s) for s in pair.machine))
    for cut in (pair, twin):
        got = check_pair_blank(cut)
        assert got.agrees, got.warnings()


F2_SLIPS = [
    # (member, key, slip, gross: exit 2 from the CLI)
    ("gear", "cradle_angle_deg", lambda x: -x, True),        # hand (E_m = 0)
    ("pinion", "cradle_angle_deg", lambda x: -x, True),      # hand
    ("gear", "sliding_base_mm", lambda x: -x, False),        # mean point not reached
    ("pinion", "sliding_base_mm", lambda x: -x, False),      # root depth 6.7 / 9.7 mm
    ("pinion", "ratio_of_roll", lambda x: 1.0 / x, False),   # mean point not reached
]


@pytest.mark.parametrize("member,key,slip,gross", F2_SLIPS,
                         ids=[f"{m}-{k}" for m, k, _, _ in F2_SLIPS])
def test_f2_sign_slip_is_caught_and_named(f2, member, key, slip, gross):
    # one sign word flipped on both flanks of a member: those flanks disagree, the
    # others agree, and each is named with the flipped key. (The F.2 gear's blank
    # offset and MCTB are 0 and its ratio of roll 0, formate: no sign to slip.)
    got = check_pair_blank(dataclasses.replace(f2, machine=_flip(f2.machine, member, key,
                                                                 slip)))
    assert not got.hand_slip
    for f in got.flanks:
        if f.member == member:
            assert not f.agrees and f.slip == f"machine.{member}.{f.side}.{key}"
        else:
            assert f.agrees and f.slip == ""
    assert got.gross == gross
    lines = got.warnings()
    assert len(lines) == 2 and all(f"machine.{member}." in line and key in line
                                   for line in lines)
    if gross:
        with pytest.raises(InputRangeError, match=rf"machine\.{member}\.drive\.{key}"):
            got.raise_if_gross()
    else:
        got.raise_if_gross()


def test_f2_hand_slip_is_named(f2):
    # the blank's hand word flipped ([design] pinion_hand): every flank's hand is the
    # other, and every flank agrees with the other hand: the key is design.pinion_hand
    got = check_pair_blank(dataclasses.replace(f2, pinion_hand="left"))
    assert got.hand_slip and got.gross
    assert all(not f.agrees for f in got.flanks)
    with pytest.raises(InputRangeError, match=r"design\.pinion_hand = 'left'"):
        got.raise_if_gross()


# ---------------------------------------------------------------- the published sheet

def _sheet():
    data = tomllib.loads(SHEET.read_text(encoding="utf-8"))
    p = data["printed"]
    setups = tuple(setup_from_tables("gear", side, data["machine"]["gear"][side],
                                     data["blade"]["gear"][side]) for side in ("drive", "coast"))
    d = math.radians(p["gear_pitch_angle_deg"])
    # the print's rounding of each setting: lengths printed to 0.001 in; angles to the
    # minute; MCTB = (MD + the pitch apex from the crossing point) x 25.4, the apex from
    # crown to crossing point, outer cone distance, addendum (0.0005 in each) and pitch
    # angle (0.5') (summary_sheets/README.md); the ratio Nc/75 x 75/41 to its 6
    # decimals; the point radii (D +- W)/2 from D and W to 0.0005 in
    apex = (THOU * (1.0 + abs(math.cos(d)) + abs(math.sin(d)))
            + IN * p["cone_distance_in"] * math.sin(d) * math.radians(MINUTE))
    rounding = {"radial_distance_mm": THOU, "cradle_angle_deg": MINUTE,
                "machine_root_angle_deg": MINUTE, "machine_centre_to_back_mm": THOU + apex,
                "sliding_base_mm": THOU, "blank_offset_mm": THOU,
                "ratio_of_roll": 5e-7 * 75.0 / p["gear_teeth"], "blade_angle_deg": MINUTE,
                "point_radius_mm": THOU}
    r_m = IN * (p["cone_distance_in"] - 0.5 * p["face_width_in"])
    stated = StatedBlank(
        pitch_angle_deg={"gear": p["gear_pitch_angle_deg"]},
        mean_cone_distance_mm={"gear": r_m},
        # mean dedendum: whole depth at mid face - chordal addendum there (printed)
        dedendum_mm={"gear": IN * (p["whole_depth_mid_in"]
                                   - p["mean_normal_chordal_addendum_in"])},
        spiral_angle_gear_deg=p["gear_spiral_angle_deg"],
        pressure_angle_deg={"drive": p["gear_pressure_angle_convex_deg"],
                            "coast": p["gear_pressure_angle_concave_deg"]},
        gear_hand=p["gear_hand"], cutter_radius_mm=IN * 0.5 * p["cutter_diameter_in"],
        # the stated values' own print rounding: angles 0.5', the mean cone distance
        # 4.274 - 1.250/2 in (0.0005 + 0.00025 in), the cutter diameter 0.0005 in
        rounding={"spiral_angle_deg": MINUTE, "pressure_angle_deg": MINUTE,
                  "cone_distance_mm": 1.5 * THOU, "cutter_radius_mm": 0.5 * THOU},
        setting_rounding=rounding, hand_key="printed.gear_hand", hand_value=p["gear_hand"],
        # the typed MCTB is MD + the pitch apex's offset from the crossing point (README)
        mctb_datum_mm={"gear": IN * _pitch_apex_in(p)})
    return setups, stated


@pytest.fixture(scope="module")
def sheet():
    return _sheet()


def test_sheet_agrees_with_its_print(sheet):
    setups, stated = sheet
    got = check_flanks(setups, stated)
    assert got.agrees, got.warnings()
    rows = {c.quantity: c for c in got.flanks[0].comparisons}
    # the measured values of test_flank_angles.py, now within the print's rounding
    # propagated by finite differences (README: 0.048 deg / 0.1196 mm by hand)
    assert rows["spiral angle"].measured == pytest.approx(26.9433, abs=5e-4)
    assert rows["mean cone distance"].measured == pytest.approx(92.7535, abs=5e-4)
    assert rows["hand"].measured == "right"


SHEET_SLIPS = [
    ("blank_offset_mm", True),      # DN -> UP: generating spiral angle 37.68 deg
    ("cradle_angle_deg", True),     # the hand, and (E_m != 0) the spiral angle
    ("sliding_base_mm", False),     # WITH = + -> -: the root 3.6 mm behind the tip plane
]


@pytest.mark.parametrize("key,gross", SHEET_SLIPS, ids=[k for k, _ in SHEET_SLIPS])
def test_sheet_sign_slip_is_caught_and_named(sheet, key, gross):
    setups, stated = sheet
    got = check_flanks(_flip(setups, "gear", key, lambda x: -x), stated)
    assert [f.slip for f in got.flanks] == [f"machine.gear.{s}.{key}" for s in ("drive", "coast")]
    assert got.gross == gross
    if key == "blank_offset_mm":
        # the drive flank does not reach the mean point (reported); the coast flank does
        assert "does not reach" in got.flanks[0].missing
        rows = {c.quantity: c for c in got.flanks[1].comparisons}
        assert rows["spiral angle"].measured == pytest.approx(37.68, abs=0.01)  # README
        assert rows["spiral angle"].measured - rows["spiral angle"].stated > GROSS_SPIRAL_DEG


def test_sheet_hand_slip_is_named(sheet):
    setups, stated = sheet
    got = check_flanks(setups, dataclasses.replace(stated, gear_hand="left", hand_value="left"))
    assert got.hand_slip and got.gross
    with pytest.raises(InputRangeError, match=r"printed\.gear_hand = 'left'"):
        got.raise_if_gross()


def test_sheet_ratio_of_roll_reciprocal_is_caught_and_named(sheet):
    # the gear's ratio of roll typed as its reciprocal (0.998168 -> 1.001835, 0.37 %):
    # the generating gear's angles do not depend on the work's roll and the root depth
    # moves by hundredths of a millimetre, but the generating roll's pitch point
    # (flank_angles.pitch_offset) leaves the mean point: -2.81 / -3.10 mm along the
    # normal against -0.54 / -0.25 mm as printed (docs/machine_settings.md sec. 2),
    # beyond the tolerance (the print's rounding propagated, 0.19 mm, plus the model
    # bound, a tenth of the mean dedendum, 0.75 mm). Caught on both flanks as the only
    # quantity outside, named by the slip that undoes it (truth: the flip); a warning
    setups, stated = sheet
    assert check_flanks(setups, stated).agrees
    got = check_flanks(_flip(setups, "gear", "ratio_of_roll", lambda x: 1.0 / x), stated)
    assert [f.slip for f in got.flanks] == [f"machine.gear.{s}.ratio_of_roll"
                                            for s in ("drive", "coast")]
    for f in got.flanks:
        assert [c.quantity for c in f.comparisons if not c.within] == ["pitch point"]
    assert not got.gross and not got.hand_slip
    assert all("likely machine.gear." in line and "ratio_of_roll" in line
               for line in got.warnings())


def test_sheet_md_word_flipped_is_caught_and_named(sheet):
    # "MD -0.240" read as +0.240: the typed X_D is MD plus the pitch apex's offset from
    # the crossing point (0.2354 in, README), so the slip is X_D -> X_D + 2 x 0.240 in,
    # not a sign change of the typed value: caught (the tooth moves 12.2 mm along the
    # work axis, the flanks miss the mean point) and named by the MD word read from the
    # crossing point (StatedBlank.mctb_datum_mm; truth: the flip)
    setups, stated = sheet
    got = check_flanks(_flip(setups, "gear", "machine_centre_to_back_mm",
                             lambda x: x + 2.0 * 0.240 * IN), stated)
    assert not any(f.agrees for f in got.flanks)
    assert [f.slip for f in got.flanks] == [f"machine.gear.{s}.machine_centre_to_back_mm"
                                            for s in ("drive", "coast")]
    datum = f"X_D = MD {stated.mctb_datum_mm['gear']:+.4f} mm"       # +5.98 mm
    assert all(f"MD sign, MD read from the crossing point ({datum}" in line
               for line in got.warnings())
    assert not got.gross


SERIES_SLIPS = [
    # (typed modified roll (2C, 6D), key): a value inside the window where the typed
    # sheet agrees and the flipped one is caught (docs/machine_settings.md sec. 2: 2C
    # about roll 0 changes the roll rate at the mean point's roll, -1.84 / +4.46 deg,
    # the generating pitch point moves ~57 mm per unit 2C on the coast flank; outside
    # the window the typed value itself is outside, or the flip is not seen)
    ((0.018,), "modified_roll_2c_per_rad"),
    ((0.0, 0.5), "modified_roll_6d_per_rad2"),
]


@pytest.mark.parametrize("typed,key", SERIES_SLIPS, ids=[k for _, k in SERIES_SLIPS])
def test_sheet_modified_roll_sign_slip_is_caught_and_named(sheet, typed, key):
    # the sheet typed with a modified roll term agrees; the term's sign flipped is caught
    # on the coast flank (its mean point generated at +4.46 deg of roll, the drive's at
    # -1.84 deg moves a third as much) and the key is named: the best explanation for
    # 6D; for 2C the MCTB's sign (-0.1176 mm typed) moves the pitch point as far and fits
    # better, so 2C is named beside it (truth: the flip; both are in the warning)
    setups, stated = sheet
    with_term = _flip(setups, "gear", "modified_roll", lambda _: typed)
    assert check_flanks(with_term, stated).agrees
    got = check_flanks(_flip(with_term, "gear", "modified_roll",
                             lambda t: tuple(-x for x in t)), stated)
    drive, coast = got.flanks
    assert drive.agrees and not coast.agrees and not got.gross
    named = f"machine.gear.coast.{key}"
    assert named == coast.slip or named in coast.slip_also
    assert named in got.warnings()[0]


@pytest.fixture(scope="module")
def hypoid_generated():
    # the settings design --machine-settings writes for the 11 x 41 hypoid with the gear
    # generated (full precision): the gear's pitch apex lies 0.29 mm from the crossing
    # point, the pinion's 15.3 mm
    from gearcontact.geometry.basic_settings import standard_machine_pair

    return standard_machine_pair(load_pair(ROOT / "examples" / "hypoid_11x41_rear_axle.toml"),
                                 gear_generation="generated")


def test_generated_hypoid_agrees_with_its_blank(hypoid_generated):
    # the generated gear rolls on the crown gear of its pitch plane: its pitch point of
    # generation is the mean point (flank_angles.pitch_offset, 1e-9 mm: a closed form in
    # double precision, tests/geometry/test_flank_angles.py)
    got = check_pair_blank(hypoid_generated)
    assert got.agrees, got.warnings()
    for f in got.flanks[:2]:
        rows = {c.quantity: c for c in f.comparisons}
        assert rows["pitch point"].measured == pytest.approx(0.0, abs=1e-9)


HYPOID_SLIPS = [
    # (member, key, slip from the stated datum, what is seen)
    ("gear", "ratio_of_roll", lambda x, a: 1.0 / x),   # 1.0637 -> 0.9401: mean point missed
    ("gear", "machine_centre_to_back_mm",               # MD read from the crossing point:
     lambda x, a: 2.0 * a - x),                         # X_D 0 -> 0.573 mm, pitch point 2.4 / 1.2 mm
    ("pinion", "machine_centre_to_back_mm",             # X_D -17.04 -> -13.58 mm: root
     lambda x, a: 2.0 * a - x),                         # depth 2.74 / 2.66 against 3.86 mm
]


@pytest.mark.parametrize("member,key,slip", HYPOID_SLIPS,
                         ids=[f"{m}-{k}" for m, k, _ in HYPOID_SLIPS])
def test_generated_hypoid_slip_is_caught_and_named(hypoid_generated, member, key, slip):
    # one word misread on both flanks of a member: caught and the key named (truth: the
    # flip), the other member agrees; a warning (no hand or spiral angle changes)
    a = stated_blank(hypoid_generated).mctb_datum_mm[member]
    got = check_pair_blank(dataclasses.replace(hypoid_generated, machine=_flip(
        hypoid_generated.machine, member, key, lambda x: slip(x, a))))
    for f in got.flanks:
        if f.member == member:
            assert not f.agrees and f.slip == f"machine.{member}.{f.side}.{key}"
        else:
            assert f.agrees
    assert not got.gross


def test_a_cutter_circle_off_the_root_line_is_reported(f2):
    # the blank's nominal cutter radius 90 mm: the F.2 gear's cutter centre lies 93.6 mm
    # off the root line, the circle does not cross it (flank_angles refuses the
    # measurement); the check reports both gear flanks, the pinion's are checked
    got = check_pair_blank(dataclasses.replace(
        f2, cutter=dataclasses.replace(f2.cutter, radius_mm=90.0)))
    assert [f.agrees for f in got.flanks] == [False, False, True, True]
    assert "does not cross the root line" in got.flanks[0].missing
    assert not got.gross


@pytest.mark.parametrize("case", ["as typed", "gear sliding base", "cutter radius 90"])
def test_the_printed_measurements_give_the_same_check(f2, case):
    # design measures each flank once (flank_angles.measure_pair_mean_points, the table
    # it prints) and the check takes those measurements: the same check, value for
    # value, as the check's own measurement (truth: the check measuring itself; exact,
    # the same solves from the same starts), for agreeing flanks, flanks missing their
    # mean point, and a nominal cutter circle off the root line
    from gearcontact.geometry.flank_angles import measure_pair_mean_points

    pair = {"as typed": f2,
            "gear sliding base": dataclasses.replace(f2, machine=_flip(
                f2.machine, "gear", "sliding_base_mm", lambda x: -x)),
            "cutter radius 90": dataclasses.replace(
                f2, cutter=dataclasses.replace(f2.cutter, radius_mm=90.0))}[case]
    assert check_pair_blank(pair, measured=measure_pair_mean_points(pair)) \
        == check_pair_blank(pair)
    with pytest.raises(InputRangeError, match="one measured flank per set-up"):
        check_pair_blank(pair, measured=measure_pair_mean_points(pair)[:2])
