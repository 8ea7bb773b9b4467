"""A summary sheet's gear page typed verbatim into a pair file (``[print.gear]``,
geometry.print_table; docs/machine_settings.md sec. 2 "Typing a print", sec. 3).

Truths: the published page (summary_sheets/README.md): the pair file
summary_sheets/hypoid_10x41_no16_pair.toml holds its words and numbers as printed
(checked here against the sheet's own [printed] table), and loading it gives exactly the
gear tables the sheet's test data typed by hand (hypoid_10x41_no16_gear.toml); the
console script's ``design`` prints the generating gear's spiral and pressure angles the
print prints, within the print's rounding as test_flank_angles.py derives it (its
constants, not copies). The MD datum's comparison against the pair's blank: the print's
chain by hand arithmetic (test_print_words.py) against the blank's apex. Every refusal
names the key as typed (the value typed wrong is the truth).
"""

from __future__ import annotations

import dataclasses
import json
import math
import tomllib
import warnings
from pathlib import Path

import pytest
from console_script import run_console

from gearcontact.geometry.blank_check import check_pair_blank
from gearcontact.geometry.machine import setup_from_tables
from gearcontact.geometry.pair import pair_to_toml, parse_pair
from gearcontact.geometry.print_table import PrintDatumWarning
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
        warnings.simplefilter("ignore", PrintDatumWarning)
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
        if key == "gear_pitch_angle_deg":
            assert degrees_minutes(key, value) == pytest.approx(p[key], abs=5e-7)
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


def test_the_md_datum_is_compared_with_the_pairs_blank(doc, sheet):
    # the MD's datum comes from the print's chain (the pitch apex 0.2354 in between,
    # test_print_words.py by hand); the pair's ISO 23509 blank puts its apex elsewhere
    # (its pitch angle is not the print program's: 74.898 against 74D 49M, measured):
    # the difference is reported, beyond the print's rounding propagated (0.044 mm:
    # 0.0005 in on each length of the chain, 0.5' on the pitch angle), and the gear
    # is still cut about the print's apex (the test above)
    p = sheet["printed"]
    d = math.radians(p["gear_pitch_angle_deg"])
    tol = IN * (0.0005 * (1 + math.cos(d) + math.sin(d))
                + (p["cone_distance_in"] * math.sin(d) + p["gear_addendum_in"] * math.cos(d))
                * math.radians(0.5 / 60))
    with pytest.warns(PrintDatumWarning, match=r"print\.gear\.gear_crown_to_crossing_point_in"
                      r".*0\.2354 in.*0\.2481 in by the pair's blank: -0\.322 mm.*"
                      rf"rounding \({tol:.3f} mm\).*74\.8982 deg, printed 74D 49M"):
        got = parse_pair(doc, name="sheet")
    assert IN * _pitch_apex_in(p) - got.blank.gear_apex_z_mm == pytest.approx(-0.322,
                                                                              abs=5e-4)


def test_design_prints_the_printed_generating_angles():
    # the console script as a user runs it, on the pair file: the generating gear's
    # spiral angle and pressure angles against the printed 26D 57M, 18D 0M (convex,
    # drive) and 24D 30M (concave, coast), the mean cone distance against the printed
    # 4.274 - 1.250 / 2 in; tolerances the print's rounding propagated
    # (test_flank_angles.py). design measures at the pair's blank's mean point (pitch
    # angle 74.898 deg, the print's 74.817): the spiral angle moves by 2e-5 deg and the
    # cone distance by 0.013 mm against test_flank_angles' measurement at the printed
    # mean point (measured), inside the tolerances with margin. The typed-settings
    # check ran on the converted tables as on typed ones (its findings: the pair's
    # blank's gear spiral angle 26.799 deg is the ISO design's, not the print's)
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
    check = got["blank_check"]["flanks"]["gear"]["drive"]["comparisons"]
    rows = {c["quantity"]: c for c in check}
    assert rows["spiral angle"]["stated"] == pytest.approx(got["spiral_angle_gear_deg"],
                                                           abs=1e-12)
    assert "PrintDatumWarning" in err


@pytest.fixture(scope="module")
def up_slip(doc):
    """The typed-settings check of the pair with DN read as UP in the print."""
    return check_pair_blank(_load(_with(doc, blank_offset="UP 0.225")))


def test_a_word_read_wrong_through_the_print_is_caught_by_the_blank_check(up_slip):
    # the same typed-settings check as hand-typed tables: DN read as UP in the print is
    # a gross slip (exit 2): the coast flank's generating spiral angle 37.678 deg
    # (test_blank_check.py on the hand-typed sheet: 37.68), the drive flank misses the
    # mean point
    assert up_slip.gross
    assert "does not reach" in up_slip.flanks[0].missing
    rows = {c.quantity: c for c in up_slip.flanks[1].comparisons}
    assert rows["spiral angle"].measured == pytest.approx(37.68, abs=0.01)


@pytest.mark.xfail(strict=True, reason=(
    "differs: the slip is caught (gross, exit 2) but not named on this pair. The check "
    "compares with the pair's ISO 23509 blank, whose gear spiral angle (26.799 deg) is "
    "not the print's (26.95; the print's program designs its blank otherwise), and its "
    "tolerance is the converted values' 4th decimal (0.0006 deg), not the print's "
    "rounding (0.048 deg): with DN restored the flank still disagrees (26.943 deg), so no "
    "slip explains it. The sheet's own check (test_blank_check.py, against the printed "
    "blank with the print's rounding) names it"))
def test_a_word_read_wrong_through_the_print_is_named(up_slip):
    assert [f.slip for f in up_slip.flanks[:2]] == [f"machine.gear.{s}.blank_offset_mm"
                                                   for s in SIDES]


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
    # inches and millimetres: the print's lengths are inches
    ({"radial_in": 104.3432}, r"print\.gear\.radial_in = 104\.3432.*machine\.gear\.drive\."
                              r"radial_distance_mm = 2650\.31.*typed in mm\?"),
    ({"cutter_diameter_in": 228.6}, r"print\.gear\.cutter_diameter_in = 228\.6.*cutter\."
                                    r"radius_mm = 114\.3.*typed in mm\?"),
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

