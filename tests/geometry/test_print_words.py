"""A summary sheet's words and numbers mapped to the typed tables (geometry.print_words).

Truths: the published print typed in (summary_sheets/README.md): its typed tables are
exactly what the mapping gives from its `[printed]` table, so the docs table
(docs/machine_settings.md sec. 2), the code and the test data agree by construction;
the words' signs are decided by the print's own geometry (the root line in the cutter
tip plane, test_flank_angles.py; the generating spiral angle, test_blank_check.py),
re-checked here through the mapping; the parsers against hand arithmetic of the printed
forms; every refusal names the field, the value and the words allowed.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from gearcontact.geometry.print_words import (BLANK_OFFSET_WORDS, SLIDING_BASE_WORDS,
                                              degrees_minutes, gear_tables_from_print,
                                              md_value, pitch_apex_from_crossing_point_in,
                                              ratio_of_roll_from_nc75, word_value)
from gearcontact.validation import InputRangeError

from gearcontact.geometry.flank_angles import measure_mean_point
from gearcontact.geometry.machine import setup_from_tables

from .test_flank_angles import IN, _normal_thickness_in, _root_apex_z_mm

SHEET = Path(__file__).with_name("summary_sheets") / "hypoid_10x41_no16_gear.toml"


@pytest.fixture(scope="module")
def sheet():
    return tomllib.loads(SHEET.read_text(encoding="utf-8"))


def test_typed_sheet_is_the_print_through_the_words(sheet):
    # the test data's typed tables are exactly (bit for bit) the mapping of its
    # [printed] table: a sheet typed by hand and one typed through the mapping agree
    got = gear_tables_from_print(sheet["printed"])
    assert got == {"machine": sheet["machine"], "blade": sheet["blade"]}
    # the rounding as typed (4 decimals mm / deg, 6 for the ratio) is below the print's
    # own resolution (0.0005 in = 0.0127 mm, 0.5' = 0.0083 deg, 5e-7 x 75 / 41)
    raw = gear_tables_from_print(sheet["printed"], rounded=False)
    for side in ("drive", "coast"):
        for k, v in raw["machine"]["gear"][side].items():
            assert abs(v - got["machine"]["gear"][side][k]) <= (5e-7 if k == "ratio_of_roll"
                                                                else 5e-5)


def test_words_as_the_print_decided_them(sheet):
    # the signs the mapping gives are the ones the print's geometry decided (README):
    # WITH = + puts the root line in the cutter tip plane (measured -0.065 mm, within
    # 0.15 mm: the printed root apex's 0.005 in, test_flank_angles.py); the opposite
    # word AWAY puts it 3.62 mm behind it, MD read + 11.3 mm off (each > 20 x 0.15)
    p = sheet["printed"]
    gear = gear_tables_from_print(p)["machine"]["gear"]["drive"]
    assert _root_apex_z_mm(p, gear) == pytest.approx(-0.065, abs=1e-3)
    assert abs(_root_apex_z_mm(p, gear)) < 0.15
    away = gear_tables_from_print({**p, "sliding_base": "AWAY 0.070"})["machine"]["gear"]["drive"]
    assert away["sliding_base_mm"] == -gear["sliding_base_mm"] == pytest.approx(-1.778)
    assert abs(_root_apex_z_mm(p, away)) > 3.0
    md_plus = gear_tables_from_print({**p, "machine_centre_to_back": "MD +0.240"})
    assert abs(_root_apex_z_mm(p, md_plus["machine"]["gear"]["drive"])) > 3.0
    # DN = - (the opposite UP gives the generating spiral angle 37.68 deg against the
    # printed 26.95: test_blank_check.py); the blade words: OB cuts the gear's concave
    # (coast) flank with the printed "Gear PA Concave 24D 30M", IB the convex (drive)
    up = gear_tables_from_print({**p, "blank_offset": "UP 0.225"})["machine"]["gear"]["coast"]
    assert up["blank_offset_mm"] == pytest.approx(5.715) and gear["blank_offset_mm"] == -5.715
    blade = gear_tables_from_print(p)["blade"]["gear"]
    assert blade["coast"]["kind"] == "outside"
    assert blade["coast"]["blade_angle_deg"] == p["gear_pressure_angle_concave_deg"]
    assert blade["drive"]["kind"] == "inside"
    assert blade["drive"]["blade_angle_deg"] == p["gear_pressure_angle_convex_deg"]


def test_rough_point_width_cuts_the_printed_rough_thickness(sheet):
    # the point width's mapping (point radii (D -+ W) / 2) against the print's other
    # column: the page prints the gear tooth's normal chordal thickness at mid face for
    # the rough cut (point width 0.0600 in) as 0.1889 in beside the finish 0.1589 in
    # (0.0900 in). The same settings with the rough width typed through the mapping cut
    # a tooth of 0.18867 in (measured), the finish 0.15857 in. Tolerance as the finish
    # thickness's in test_flank_angles.py (the print's rounding propagated, 0.0023 in,
    # + the printed 0.00005): 0.00235 in; the thickness moves one to one with W
    # (0.0301 in for 0.0300 in), so a misread width is caught many times over.
    p = sheet["printed"]
    tables = gear_tables_from_print({**p, "point_width_finish_in": p["point_width_rough_in"]})
    measured = {side: measure_mean_point(
        setup_from_tables("gear", side, tables["machine"]["gear"][side],
                          tables["blade"]["gear"][side]),
        pitch_angle_deg=p["gear_pitch_angle_deg"],
        cone_distance_mm=IN * (p["cone_distance_in"] - 0.5 * p["face_width_in"]))
        for side in ("drive", "coast")}
    rough_in = _normal_thickness_in(p, measured)
    assert rough_in == pytest.approx(p["mean_normal_chordal_thickness_rough_in"], abs=0.00235)
    assert rough_in == pytest.approx(0.18867, abs=5e-6)       # measured


def test_printed_forms_against_hand_arithmetic():
    # exact forms of the print: degrees and minutes, words with unsigned numbers, MD
    # with a signed one (1e-12: float arithmetic of the same decimal)
    f = "printed.x"
    assert degrees_minutes(f, "26D 57M") == pytest.approx(26 + 57 / 60, abs=1e-12)
    assert degrees_minutes(f, "18D 0M") == 18.0
    assert degrees_minutes(f, "-5d 3m") == pytest.approx(-(5 + 3 / 60), abs=1e-12)
    assert degrees_minutes(f, "30 Deg") == 30.0
    assert degrees_minutes(f, "0") == 0.0
    assert degrees_minutes(f, 74.816667) == 74.816667
    assert word_value(f, "WITH 0.070", SLIDING_BASE_WORDS) == 0.070
    assert word_value(f, "away  0.070", SLIDING_BASE_WORDS) == -0.070
    assert word_value(f, "DN 0.225", BLANK_OFFSET_WORDS) == -0.225
    assert word_value(f, "UP 0.225", BLANK_OFFSET_WORDS) == 0.225
    assert md_value(f, "MD -0.240") == -0.240
    assert md_value(f, "MD 0.240") == md_value(f, "+0.240") == 0.240
    # the ratio of roll: 75 x Nc/75 / z, the printed test roll (30 deg -> 29D 57M) to
    # its minute
    assert ratio_of_roll_from_nc75(0.545665, 41) == pytest.approx(0.545665 * 75 / 41, abs=1e-15)
    assert 30.0 * ratio_of_roll_from_nc75(0.545665, 41) == pytest.approx(29 + 57 / 60,
                                                                         abs=0.5 / 60)


def test_md_datum_is_the_pitch_apex_of_the_printed_blank(sheet):
    # the pitch apex from the crossing point: crown to crossing point (1.293) less the
    # crown's axial distance from the apex; the printed root apex (-0.16, "between")
    # follows from it and the printed root angle (test_flank_angles.py, 0.005 in), and
    # the pinion's column of the same page gives the other side of the chain: the
    # gear's apex lies 0.2354 in between (towards the gear)
    p = sheet["printed"]
    got = pitch_apex_from_crossing_point_in(
        crown_to_crossing_point_in=1.293, outer_cone_distance_in=4.274,
        pitch_angle_deg=74 + 49 / 60, addendum_in=0.064)
    d = math.radians(74 + 49 / 60)
    assert got == pytest.approx(1.293 - 4.274 * math.cos(d) + 0.064 * math.sin(d), abs=1e-15)
    assert got == pytest.approx(0.2354, abs=5e-5)
    assert p["machine_centre_to_back"] == "MD -0.240"


@pytest.mark.parametrize("key, value, named", [
    ("sliding_base", "TOWARDS 0.070", r"printed\.sliding_base = 'TOWARDS 0\.070'.*WITH, AWAY"),
    ("sliding_base", "WITH -0.070", r"printed\.sliding_base = 'WITH -0\.070'.*unsigned"),
    ("sliding_base", 0.070, r"printed\.sliding_base = 0\.07.*text as printed"),
    ("blank_offset", "BELOW 0.225", r"printed\.blank_offset = 'BELOW 0\.225'.*UP, DN"),
    ("machine_centre_to_back", "MC -0.240", r"printed\.machine_centre_to_back = 'MC -0\.240'"),
    ("cradle_angle", "ABOVE 67D 11M", r"printed\.cradle_angle = 'ABOVE 67D 11M'.*minutes"),
    ("cradle_angle", "67D 61M", r"printed\.cradle_angle = '67D 61M'.*\[0, 60\)"),
    ("tilt_angle", "20D 0M", r"printed\.tilt_angle = '20D 0M'.*on no print read"),
    ("blades", ["OB 24D 30M", "XB 18D 0M"], r"printed\.blades\[1\] = 'XB 18D 0M'.*OB, IB"),
    ("blades", ["OB 24D 30M", "OB 18D 0M"], r"printed\.blades = .*one OB and one IB"),
    ("gear_teeth", 41.0, r"printed\.gear_teeth = 41\.0.*positive integer"),
    # the ratio typed as cradle / work (its reciprocal as Nc/75): the test roll disagrees
    ("ratio_nc_75", round(41 / 75 / (0.545665 * 75 / 41), 6),
     r"printed\.work_test_roll = '29D 57M'"),
])
def test_unknown_words_are_refused_naming_field_value_and_words(sheet, key, value, named):
    with pytest.raises(InputRangeError, match=named):
        gear_tables_from_print({**sheet["printed"], key: value})


def test_a_missing_key_is_named(sheet):
    p = dict(sheet["printed"])
    del p["sliding_base"]
    with pytest.raises(InputRangeError, match=r"printed\.sliding_base = None.*required"):
        gear_tables_from_print(p)
