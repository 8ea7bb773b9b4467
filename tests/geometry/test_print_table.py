"""A summary sheet's gear page typed verbatim into a pair file (``[print.gear]``,
geometry.print_table; docs/machine_settings.md sec. 2 "Typing a print", sec. 3).

Truths: the published page (summary_sheets/README.md): the pair file
summary_sheets/hypoid_10x41_no16_pair.toml holds its words and numbers as printed
(checked here against the sheet's own [printed] table), and loading it gives exactly the
gear tables the sheet's test data typed by hand (hypoid_10x41_no16_gear.toml); the
console script's ``design`` prints the generating gear's spiral and pressure angles the
print prints, within the print's rounding as test_flank_angles.py derives it (its
constants, not copies). The MD datum's comparison against the pair's blank: the print's
chain by hand arithmetic (test_print_words.py) against the blank's apex. The
typed-settings check of the gear states what the page prints with the print's rounding,
as test_blank_check.py states the sheet by hand (the same numbers); the page typed
correctly agrees, and a word misread is named by its print key (the flip is the truth).
Every refusal names the key as typed (the value typed wrong is the truth).
"""

from __future__ import annotations

import dataclasses
import json
import math
import re
import tomllib
import warnings
from pathlib import Path

import pytest
from console_script import run_console

from gearcontact.geometry.blank_check import check_pair_blank
from gearcontact.geometry.blank_statement import printed_stated_blank
from gearcontact.geometry.machine import setup_from_tables
from gearcontact.geometry.pair import pair_to_toml, parse_pair
from gearcontact.geometry.print_table import PrintBlankNote
from gearcontact.geometry.print_words import degrees_minutes
from gearcontact.validation import InputRangeError

from .test_flank_angles import (GENERATING_CONE_TOL_MM, GENERATING_PRESSURE_TOL_DEG,
                                GENERATING_SPIRAL_TOL_DEG, IN, _pitch_apex_in)

SHEETS = Path(__file__).with_name("summary_sheets")
SHEET = SHEETS / "hypoid_10x41_no16_gear.toml"
PAIR = SHEETS / "hypoid_10x41_no16_pair.toml"
SIDES = ("drive", "coast")


@pytest.fixture(scope="module")
def sheet():
    return tomllib.loads(SHEET.read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def doc():
    return tomllib.loads(PAIR.read_text(encoding="utf-8"))


def _load(doc):
    """``parse_pair`` of ``doc`` without the datum warning (tested on its own)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PrintBlankNote)
        return parse_pair(doc, name="sheet")


@pytest.fixture(scope="module")
def pair(doc):
    return _load(doc)


def _with(doc, **changes):
    """``doc`` with ``[print.gear]`` keys changed (None: removed)."""
    printed = {k: v for k, v in {**doc["print"]["gear"], **changes}.items() if v is not None}
    return {**doc, "print": {"gear": printed}}


def test_the_file_holds_the_page_as_printed(doc, sheet):
    # transcription: every [print.gear] value is the sheet's [printed] one (its words
    # verbatim, the numbers in the print's inches); the pitch angle as printed in degrees
    # and minutes where the sheet wrote decimal degrees (6 decimals: 5e-7)
    p = sheet["printed"]
    for key, value in doc["print"]["gear"].items():
        if key in ("gear_pitch_angle_deg", "gear_spiral_angle_deg",
                   "gear_pressure_angle_convex_deg", "gear_pressure_angle_concave_deg"):
            assert degrees_minutes(key, value) == pytest.approx(p[key], abs=5e-7), key
        elif key == "gear_hand":                  # printed "RIGHT"
            assert value.lower() == p[key]
        else:
            assert value == p[key], key
    # the blank tables from the printed blank (the file's comments give the arithmetic):
    # exact conversions x 25.4, the depth factors to their 6 typed decimals
    d, c = doc["design"], doc["cutter"]
    assert doc["teeth"] == {"pinion": p["pinion_teeth"], "gear": p["gear_teeth"]}
    assert doc["axes"]["offset_mm"] == pytest.approx(IN * p["pinion_offset_in"], abs=1e-12)
    assert d["gear_mean_cone_distance_mm"] == pytest.approx(
        IN * (p["cone_distance_in"] - 0.5 * p["face_width_in"]), abs=1e-12)
    assert d["pinion_spiral_angle_deg"] == p["pinion_spiral_angle_deg"]
    assert d["pinion_hand"] == {"right": "left", "left": "right"}[p["gear_hand"]]
    assert d["gear_face_width_mm"] == pytest.approx(IN * p["face_width_in"], abs=1e-12)
    assert c["radius_mm"] == pytest.approx(IN * p["cutter_diameter_in"] / 2, abs=1e-12)
    assert (c["pressure_angle_drive_deg"], c["pressure_angle_coast_deg"]) == (
        p["gear_pressure_angle_convex_deg"], p["gear_pressure_angle_concave_deg"])


def test_the_mean_depths_are_the_printed_mid_face_ones(pair, sheet):
    # the format's uniform depths typed from the print's mid-face numbers: the blank's
    # mean gear addendum is the printed chordal addendum at mid face, its mean whole
    # depth the printed whole depth at mid face (0.3476 in), its clearance the printed
    # whole - working depth; to the factors' 6 typed decimals (1e-6 relative, 1e-5 mm)
    p, b = sheet["printed"], pair.blank
    assert b.addendum_gear_mm == pytest.approx(IN * p["mean_normal_chordal_addendum_in"],
                                               abs=1e-5)
    assert b.addendum_gear_mm + b.dedendum_gear_mm == pytest.approx(
        IN * p["whole_depth_mid_in"], abs=1e-5)
    assert b.clearance_mm == pytest.approx(IN * (p["whole_depth_in"] - p["working_depth_in"]),
                                           abs=1e-5)


def test_loading_the_print_gives_the_typed_sheet_exactly(pair, sheet):
    # the published page typed verbatim and the sheet's tables typed by hand (the
    # existing test data) cut the same gear: the same MachineSetup bit for bit
    typed = tuple(setup_from_tables("gear", side, sheet["machine"]["gear"][side],
                                    sheet["blade"]["gear"][side]) for side in SIDES)
    assert tuple(s for s in pair.machine if s.member == "gear") == typed
    assert dict(pair.print_gear)["sliding_base"] == "WITH 0.070"


def test_the_pairs_blank_is_compared_with_the_print_once(doc, sheet):
    # the MD's datum comes from the print's chain (the pitch apex 0.2354 in between,
    # test_print_words.py by hand); the pair's ISO 23509 blank puts its apex elsewhere
    # and designs another spiral and pitch angle (74.898 against 74D 49M, measured): one
    # note on load lists what differs beyond the print's rounding, the pair's values
    # beside the printed ones (truth: the pair's own blank values and the print's
    # numbers; the datum's rounding by hand: 0.0005 in on each length of the chain, 0.5'
    # on the pitch angle, 0.044 mm). The pressure angles and the mean cone distance
    # were typed from the print ([cutter], [design]): not listed. The gear is still cut
    # about the print's apex (test_loading_the_print_gives_the_typed_sheet_exactly)
    p = sheet["printed"]
    d = math.radians(p["gear_pitch_angle_deg"])
    tol = IN * (0.0005 * (1 + math.cos(d) + math.sin(d))
                + (p["cone_distance_in"] * math.sin(d) + p["gear_addendum_in"] * math.cos(d))
                * math.radians(0.5 / 60))
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        got = parse_pair(doc, name="sheet")
    notes = [str(w.message) for w in seen if issubclass(w.category, PrintBlankNote)]
    assert len(notes) == 1 and len(seen) == 1
    b = got.blank
    assert re.search(
        rf"gear spiral angle {b.spiral_angle_gear_deg:.4f} deg, printed 26\.9500 "
        rf".*gear pitch angle {b.pitch_angle_gear_deg:.4f} deg, printed "
        rf"{p['gear_pitch_angle_deg']:.4f} .*print\.gear\.gear_crown_to_crossing_point_in"
        rf".*-0\.322 mm, rounding {tol:.3f} mm", notes[0]), notes[0]
    assert "pressure angle" not in notes[0] and "cone distance" not in notes[0].split(
        "the MD's datum")[0]
    assert IN * _pitch_apex_in(p) - got.blank.gear_apex_z_mm == pytest.approx(-0.322,
                                                                              abs=5e-4)


def test_the_check_states_the_printed_blank_with_the_prints_rounding(pair):
    # the statement the gear is checked against is the one test_blank_check.py builds by
    # hand from the sheet's [printed] table (the printed blank, the print's rounding:
    # inches to 0.0005, angles to 0.5', the ratio's 6 decimals): the same numbers. Two
    # settings' rounding differ by construction, each checked against its own hand
    # arithmetic: the point radii (D -+ W) / 2 take half of D's and W's half units
    # (0.000275 in; the hand-built sheet takes 0.0005 in), the MCTB's apex chain adds
    # the addendum's term |a_o cos d| m (2.4e-6 in) the hand-built sheet leaves out
    from .test_blank_check import _sheet

    _, want = _sheet()
    got = printed_stated_blank(pair)
    for name in ("spiral_angle_gear_deg", "pressure_angle_deg", "gear_hand",
                 "cutter_radius_mm"):
        assert getattr(got, name) == pytest.approx(getattr(want, name), abs=1e-12), name
    # the printed pitch angle "74D 49M" against the sheet's decimal 74.816667 (6 decimals)
    assert got.pitch_angle_deg["gear"] == pytest.approx(want.pitch_angle_deg["gear"], abs=5e-7)
    assert got.mean_cone_distance_mm["gear"] == pytest.approx(
        want.mean_cone_distance_mm["gear"], abs=1e-12)
    # the datum: the sheet's decimal pitch angle moves the apex by 1e-7 in
    assert got.mctb_datum_mm["gear"] == pytest.approx(want.mctb_datum_mm["gear"], abs=1e-5)
    for key, value in want.rounding.items():
        assert got.rounding[key] == pytest.approx(value, rel=1e-12), key
    d = math.radians(74 + 49 / 60)
    own = {"point_radius_mm": IN * 0.5 * (0.0005 + 0.00005),
           "machine_centre_to_back_mm": want.setting_rounding["machine_centre_to_back_mm"]
           + IN * 0.064 * math.cos(d) * math.radians(0.5 / 60)}
    assert set(got.setting_rounding) == set(want.setting_rounding)
    for key, value in want.setting_rounding.items():
        assert got.setting_rounding[key] == pytest.approx(own.get(key, value), rel=1e-6), key
    # the root datum's dedendum: the pair's blank's, the print's mid-face numbers typed
    # into [design] (test_the_mean_depths_are_the_printed_mid_face_ones: 1e-5 mm)
    assert got.dedendum_mm["gear"] == pytest.approx(want.dedendum_mm["gear"], abs=1e-5)


def test_the_typed_page_agrees_with_what_it_prints(pair):
    # the page typed correctly: every flank agrees, no warning; the gear's generating
    # spiral angle 26.943 deg against the printed 26D 57M within the print's rounding
    # propagated (the README's hand propagation: 0.048 deg; by finite differences, as
    # test_blank_check.py's sheet, 0.0481: 5 %), the mean cone distance against the
    # printed 4.274 - 1.250 / 2 in (the README's hand propagation 0.1196 mm; by finite
    # differences test_blank_check.py's sheet has 0.124: 10 %)
    got = check_pair_blank(pair)
    assert got.agrees and got.warnings() == [], got.warnings()
    for f in got.flanks[:2]:
        rows = {c.quantity: c for c in f.comparisons}
        assert rows["spiral angle"].stated == pytest.approx(26 + 57 / 60, abs=1e-12)
        assert rows["spiral angle"].tolerance == pytest.approx(0.048, rel=0.05)
        assert rows["mean cone distance"].stated == pytest.approx(IN * (4.274 - 1.250 / 2),
                                                                  abs=1e-12)
        assert rows["mean cone distance"].tolerance == pytest.approx(0.1196, rel=0.1)


def test_design_prints_the_printed_generating_angles():
    # the console script as a user runs it, on the pair file: the generating gear's
    # spiral angle and pressure angles against the printed 26D 57M, 18D 0M (convex,
    # drive) and 24D 30M (concave, coast), the mean cone distance against the printed
    # 4.274 - 1.250 / 2 in; tolerances the print's rounding propagated
    # (test_flank_angles.py). design measures at the pair's blank's mean point (pitch
    # angle 74.898 deg, the print's 74.817): the spiral angle moves by 2e-5 deg and the
    # cone distance by 0.013 mm against test_flank_angles' measurement at the printed
    # mean point (measured), inside the tolerances with margin. The typed-settings
    # check ran on the converted tables against the printed blank (its stated values)
    code, out, err = run_console("design", "--pair", PAIR, "--json")
    assert code == 0, err
    got = json.loads(out)
    gear = got["mean_point_angles"]["gear"]
    for side, printed in (("drive", 18.0), ("coast", 24.5)):
        g = gear[side]["generating_gear"]
        assert g["spiral_angle_deg"] == pytest.approx(26 + 57 / 60,
                                                      abs=GENERATING_SPIRAL_TOL_DEG), side
        assert g["pressure_angle_deg"] == pytest.approx(printed,
                                                        abs=GENERATING_PRESSURE_TOL_DEG), side
        assert g["cone_distance_mm"] == pytest.approx(IN * (4.274 - 1.250 / 2),
                                                      abs=GENERATING_CONE_TOL_MM), side
    # the check states the printed 26D 57M, not the pair's ISO 23509 26.799 deg: no
    # warning for a gear flank, the pair's blank against the page one note
    assert got["blank_check"]["agrees"]
    for side in SIDES:
        check = got["blank_check"]["flanks"]["gear"][side]["comparisons"]
        rows = {c["quantity"]: c for c in check}
        assert rows["spiral angle"]["stated"] == pytest.approx(26 + 57 / 60, abs=1e-12)
    assert got["spiral_angle_gear_deg"] == pytest.approx(26.799, abs=5e-4)
    lines = err.splitlines()
    assert [line for line in lines if "warning" in line and "PrintBlankNote" not in line] == []
    assert sum("PrintBlankNote" in line for line in lines) == 1


PRINT_SLIPS = [
    # (the word misread in [print.gear], gross: exit 2). Each is undone by the check's
    # known slips (the flip is the truth): DN read as UP (the coast flank's generating
    # spiral angle 37.68 deg, the drive flank misses its mean point), WITH as AWAY (the
    # root 11.09 mm behind the tip plane against the dedendum 7.53), the cradle angle's
    # sign (the hand left, as UP), MD read + (the tooth 12.2 mm along the work axis: the
    # flanks miss their mean point; X_D -> 2 a - X_D about the print's datum)
    ("blank_offset", "UP 0.225", True),
    ("sliding_base", "AWAY 0.070", False),
    ("cradle_angle", "-67D 11M", True),
    ("machine_centre_to_back", "MD 0.240", False),
]


@pytest.mark.parametrize("key, word, gross", PRINT_SLIPS, ids=[k for k, _, _ in PRINT_SLIPS])
def test_a_word_read_wrong_through_the_print_is_named(doc, key, word, gross):
    # the typed-settings check of a gear typed as a print names the print's key as typed
    # (print.gear.<key>, its value the word as typed) on both gear flanks, in the warning
    # lines and, for a gross slip, in the refusal; the pinion agrees
    got = check_pair_blank(_load(_with(doc, **{key: word})))
    gear, pinion = got.flanks[:2], got.flanks[2:]
    assert [(f.slip, f.slip_value) for f in gear] == [(f"print.gear.{key}", word)] * 2
    assert all(f.agrees for f in pinion) and not got.hand_slip
    assert got.gross == gross
    lines = got.warnings()
    assert len(lines) == 2 and all(f"likely print.gear.{key} " in line for line in lines)
    if gross:
        with pytest.raises(InputRangeError, match=rf"print\.gear\.{key} = '{word}'"):
            got.raise_if_gross()
    if key == "blank_offset":
        # test_blank_check.py on the hand-typed sheet: 37.68 deg (README), the drive
        # flank misses the mean point
        assert "does not reach" in gear[0].missing
        rows = {c.quantity: c for c in gear[1].comparisons}
        assert rows["spiral angle"].measured == pytest.approx(37.68, abs=0.01)


def test_a_blade_angle_typed_wrong_is_named_by_its_print_key(doc):
    # "IB 18D 0M" typed "IB 19D 0M": no sign or unit slip explains the drive flank's
    # generating pressure angle 19 deg against the printed 18D 0M (its blade's identity,
    # 1e-7 deg); the single-key search names the inside blade as typed in the print,
    # print.gear.blades[1], with the value it needs in the converted key (deg): the
    # truth, 18, inside it; the coast flank (OB) agrees
    got = check_pair_blank(_load(_with(doc, blades=["OB 24D 30M", "IB 19D 0M"])))
    drive, coast = got.flanks[:2]
    assert coast.agrees and not drive.agrees and not got.gross
    (key,) = drive.single_keys
    assert key.key == "print.gear.blades[1] (converted: blade.gear.drive.blade_angle_deg)"
    assert key.low <= 18.0 <= key.high
    assert "print.gear.blades[1] (converted: blade.gear.drive.blade_angle_deg) typed 19" \
        in got.warnings()[0]


def test_round_trip_keeps_the_print_as_typed(pair):
    # the writer keeps the user's print: [print.gear] with the values as typed (TOML
    # numbers as parsed), no [machine.gear.*]; read back it is the same pair, and the
    # text a fixed point
    text = pair_to_toml(pair)
    assert "[print.gear]" in text and "[machine.gear." not in text and "[blade.gear." not in text
    assert 'sliding_base = "WITH 0.070"' in text
    assert 'blades = ["OB 24D 30M", "IB 18D 0M"]' in text
    back = _load(tomllib.loads(text))
    assert back.machine == pair.machine and back.print_gear == pair.print_gear
    assert back.blank == pair.blank
    assert pair_to_toml(back) == text


def test_a_changed_gear_is_written_as_tables(pair):
    # a pair whose gear is no longer the print's (a correction moved a setting) is
    # written with the gear's tables, the print dropped: the file says what is cut
    gear = pair.machine[0]
    moved = dataclasses.replace(gear, settings=dataclasses.replace(
        gear.settings, radial_distance_mm=gear.settings.radial_distance_mm + 0.01))
    changed = dataclasses.replace(pair, machine=(moved, *pair.machine[1:]))
    text = pair_to_toml(changed)
    assert "[print.gear]" not in text and "[machine.gear.drive]" in text
    assert parse_pair(tomllib.loads(text)).machine == changed.machine
    # and it is checked as typed tables against the pair's blank, not against the page
    assert printed_stated_blank(pair) is not None and printed_stated_blank(changed) is None


CARELESS = [
    # (change to [print.gear], the key and words named)
    ({"sliding_base": "WTH 0.070"},
     r"print\.gear\.sliding_base = 'WTH 0\.070'.*a word of WITH, AWAY"),
    ({"blank_offset": "DOWN 0.225"}, r"print\.gear\.blank_offset = 'DOWN 0\.225'.*UP, DN"),
    ({"cradle_angle": "67D 71M"}, r"print\.gear\.cradle_angle = '67D 71M'.*\[0, 60\)"),
    ({"blades": ["0B 24D 30M", "IB 18D 0M"]}, r"print\.gear\.blades\[0\] = '0B 24D 30M'.*OB, IB"),
    ({"machine_centre_to_back": "-0.240 MD"}, r"print\.gear\.machine_centre_to_back = "
                                              r"'-0\.240 MD'.*'MD' and a signed number"),
    ({"sliding_base": True}, r"print\.gear\.sliding_base = True.*as printed"),
    ({"slidng_base": "WITH 0.070"}, r"print\.gear\.slidng_base = 'WITH 0\.070'.*known key"),
    ({"blank_offset": None}, r"print\.gear\.blank_offset = None.*required"),
    # the printed blank the check states for the gear
    ({"gear_spiral_angle_deg": None}, r"print\.gear\.gear_spiral_angle_deg = None.*required"),
    ({"face_width_in": None}, r"print\.gear\.face_width_in = None.*required"),
    ({"gear_pressure_angle_convex_deg": "18D 60M"},
     r"print\.gear\.gear_pressure_angle_convex_deg = '18D 60M'.*\[0, 60\)"),
    ({"face_width_in": 31.75}, r"print\.gear\.face_width_in = 31\.75.*\(0, 8\.548\) in"),
    ({"gear_hand": "RIHGT"}, r"print\.gear\.gear_hand = 'RIHGT'.*RIGHT, LEFT"),
    # the print's hand and the pair's contradict: both state it
    ({"gear_hand": "LEFT"}, r"print\.gear\.gear_hand = 'LEFT'.*right \(design\.pinion_hand "
                            r"= 'left'\)"),
    # inches and millimetres: the print's lengths are inches
    ({"radial_in": 104.3432}, r"print\.gear\.radial_in = 104\.3432.*machine\.gear\.drive\."
                              r"radial_distance_mm = 2650\.31.*typed in mm\?"),
    # (the blade point radius it gives, 2902 mm, is refused by the blade's range (0, 1000]
    # mm before the pair's [cutter] is compared: the radial distance's form, above)
    ({"cutter_diameter_in": 228.6}, r"print\.gear\.cutter_diameter_in = 228\.6.*blade\.gear\."
                                    r"drive\.point_radius_mm = 2902\.077.*typed in mm\?"),
    ({"point_width_finish_in": 2.286}, r"print\.gear\.point_width_finish_in = 2\.286.*"
                                       r"typed in mm\?"),
    ({"gear_crown_to_crossing_point_in": 32.8422},
     r"print\.gear\.gear_crown_to_crossing_point_in = 32\.8422.*whole depth.*typed in mm\?"),
    ({"cone_distance_in": 108.5596}, r"print\.gear\.cone_distance_in = 108\.5596.*typed in mm\?"),
    # the words' numbers in mm: the root off the tip plane by more than the whole depth,
    # the print's spiral angle off the blank's by more than 3 deg, put right by / 25.4
    ({"sliding_base": "WITH 1.778"}, r"print\.gear\.sliding_base = 'WITH 1\.778'.*root.*"
                                     r"typed in mm\?"),
    ({"machine_centre_to_back": "MD -6.096"}, r"print\.gear\.machine_centre_to_back = "
                                              r"'MD -6\.096'.*root.*typed in mm\?"),
    ({"blank_offset": "DN 5.715"}, r"print\.gear\.blank_offset = 'DN 5\.715'.*spiral angle.*"
                                   r"typed in mm\?"),
    # the ratio typed as cradle / work: the printed test roll disagrees
    ({"ratio_nc_75": round(41 / 75 / (0.545665 * 75 / 41), 6)},
     r"print\.gear\.work_test_roll = '29D 57M'"),
]


@pytest.mark.parametrize("change, named", CARELESS, ids=[next(iter(c)) + "-" + str(i)
                                                         for i, (c, _) in enumerate(CARELESS)])
def test_a_careless_print_is_refused_naming_the_key(doc, change, named):
    with pytest.raises(InputRangeError, match=named):
        _load(_with(doc, **change))


@pytest.mark.parametrize("key, word", [("sliding_base", "AWAY 0.070"),
                                       ("machine_centre_to_back", "MD 0.240"),
                                       ("blank_offset", "UP 0.225")])
def test_a_sign_word_read_wrong_is_not_taken_for_millimetres(doc, key, word):
    # a sign slip moves the root (3.6 / 11.4 mm) or the spiral angle (10.9 deg) too, but
    # no / 25.4 puts it right: it loads, and the typed-settings check takes it up
    # (test_a_word_read_wrong_through_the_print_is_caught_by_the_blank_check)
    got = _load(_with(doc, **{key: word}))
    assert dict(got.print_gear)[key] == word


def test_print_and_typed_gear_tables_are_not_both_given(doc, sheet):
    both = {**doc, "machine": {**doc["machine"], "gear": {"drive": sheet["machine"]["gear"]["drive"]}}}
    with pytest.raises(InputRangeError, match=r"\[print\.gear\] = 'given with \[machine\.gear"
                                              r"\.drive\]'.*not both"):
        _load(both)


def test_a_print_needs_the_pinion_tables(doc):
    bare = {k: v for k, v in doc.items() if k not in ("machine", "blade")}
    with pytest.raises(InputRangeError, match=r"\[machine\.pinion\.drive\].*required with "
                                              r"\[print\.gear\].*design --machine-settings"):
        _load(bare)


def test_a_pinion_print_is_refused_naming_it(doc):
    pinion = {**doc, "print": {**doc["print"], "pinion": dict(doc["print"]["gear"])}}
    with pytest.raises(InputRangeError, match=r"print\.pinion = .*\[print\.gear\] only"):
        _load(pinion)

