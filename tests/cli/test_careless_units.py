"""A machine setting typed in another unit, run as a careless user runs it, through the
console script (session 28, helper careless2; docs/machine_settings.md sec. 2, "A mean
point not reached"): a radial distance in inches or metres, a cradle angle in radians.
Before, each was a warning (the flank does not reach its mean point, so no gross bound
applied) and the work after it failed on another key; now the check refuses it before
any flank work, naming the key as typed, its value and the conversion under which the
flank agrees. And the generation check's undercut named as the pair file spells it.

Truths: each slip is made from the right value of a shipped file (the F.2 example's
settings, the No. 16 print page), so the key and the conversion are known in advance
(tests/geometry/test_blank_check_reach.py computes the generating gear by hand); the
developers' guide: one error line, exit 2, nothing written.
"""

from dataclasses import replace
from pathlib import Path

import pytest
from console_script import run_console

from gearcontact.geometry.pair import load_pair, pair_to_toml

ROOT = Path(__file__).resolve().parents[2]
F2_MACHINE = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"
PRINT_GEAR = ROOT / "examples" / "machine_settings" / "hypoid_10x41_print_gear.toml"


def _error_line(err: str) -> str:
    """The last stderr line, asserted to be an input error (not an internal one)."""
    assert "Traceback" not in err and "internal error" not in err, err
    return err.strip().splitlines()[-1]


def _typed(tmp_path, source: Path, edits: dict) -> Path:
    """``source`` with every ``old`` line typed ``new`` (a sheet typed in the wrong unit
    throughout: both flanks' tables)."""
    text = source.read_text()
    for old, new in edits.items():
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "typed.toml"
    path.write_text(text)
    return path


#: (command, the F.2 lines typed, the key named with its value, the conversion's words)
F2_SLIPS = [
    # 94.9385 mm typed in inches (3.7377): before, a warning, then `design`'s flank work
    # failed naming the slip through cli.settings_slip after the ease-off shape's flanks
    ("design", {"radial_distance_mm = 94.9385": "radial_distance_mm = 3.7377"},
     "machine.gear.drive.radial_distance_mm = 3.7377 ", "typed in inches: x 25.4 mm"),
    # -80.4732 deg typed in radians (-1.405)
    ("analyze", {"cradle_angle_deg = -80.4732": "cradle_angle_deg = -1.405"},
     "machine.gear.drive.cradle_angle_deg = -1.405 ", "typed in radians: to degrees"),
]


@pytest.mark.parametrize("command, edits, named, words", F2_SLIPS,
                         ids=["design-radial-inches", "analyze-cradle-radians"])
def test_a_gear_setting_in_another_unit_is_refused_before_any_work(
        tmp_path, command, edits, named, words):
    """The gear's generating gear puts the mean point off the face (114.9 / -19.4 mm
    against 81.273 -+ 12.7 mm): refused by the check, exit 2, nothing written."""
    argv = (["--out", tmp_path / "out", "--no-figures", "--phases", "3", "--torques", "64.5",
             "--lte-phases", "0"] if command == "analyze" else [])
    code, _, err = run_console(command, "--pair", _typed(tmp_path, F2_MACHINE, edits), *argv)
    line = _error_line(err)
    assert code == 2, err
    assert line.startswith(f"gearcontact {command}: error: {named}is outside the allowed "
                           "range: the unit that cuts the blank's tooth"), line
    assert words in line and "off the gear's face, 68.5730 to 93.9730 mm" in line, line
    assert "failed on it" not in line
    assert not (tmp_path / "out").exists()


@pytest.mark.slow          # ~40 s at load 16: the pinion's slip search re-solves its flanks
def test_a_pinion_radial_distance_in_metres_is_refused(tmp_path):
    """97.6652 / 91.8362 mm typed in metres (0.0977 / 0.0918): the pinion flanks miss
    their mean point; x 1000 makes each agree. Before: "no known sign or unit slip
    explains it" (metres were not tried), a warning."""
    path = _typed(tmp_path, F2_MACHINE, {"radial_distance_mm = 97.6652": "radial_distance_mm = 0.0977",
                                         "radial_distance_mm = 91.8362": "radial_distance_mm = 0.0918"})
    code, _, err = run_console("design", "--pair", path)
    line = _error_line(err)
    assert code == 2
    assert line.startswith("gearcontact design: error: machine.pinion.drive.radial_distance_mm "
                           "= 0.0977 is outside the allowed range: the unit that cuts"), line
    assert "typed in metres: x 1000 mm" in line


@pytest.mark.slow          # ~15 s at load 16
def test_a_print_radial_converted_twice_is_refused_by_the_print_key(tmp_path):
    """The No. 16 page's radial 4.108 in divided by 25.4 again (0.1617): the gear flanks
    miss the printed blank's mean point, their generating gear 116.1 mm against 92.685
    -+ 15.9 mm. Before: a warning, then the standard pinion's derivation failed (renamed
    to the slip). Now refused by the check, naming the print's key as typed."""
    path = _typed(tmp_path, PRINT_GEAR, {"\nradial_in = 4.108": "\nradial_in = 0.1617"})
    code, _, err = run_console("design", "--pair", path, "--machine-settings")
    line = _error_line(err)
    assert code == 2
    assert line.startswith("gearcontact design: error: print.gear.radial_in = 0.1617 is "
                           "outside the allowed range: the unit that cuts the printed "
                           "blank's tooth"), line
    assert "x 25.4 mm" in line and "derivation" not in line


def test_an_undercut_names_the_gear_addendum_factor_as_the_file_spells_it(tmp_path):
    """geometry.generation's undercut refusal: a 5 / 70 pair from s0003-centred with a
    gear addendum factor of 0.5 and an 8 deg drive blade (tests/geometry/
    test_conjugate.py's limit-line pair). Before: "gear_addendum_factor = 0.5", the library's name; now
    the file's key, the verified fix kept (<= 0.071)."""
    s0003 = load_pair("s0003-centred")
    pair = replace(s0003, pinion_teeth=5, gear_teeth=70, gear_addendum_factor=0.5,
                   cutter=replace(s0003.cutter, pressure_angle_drive_deg=8.0))
    path = tmp_path / "undercut.toml"
    path.write_text(pair_to_toml(pair))
    code, _, err = run_console("design", "--pair", path)
    line = _error_line(err)
    assert code == 2
    assert "design.gear_addendum_factor = 0.5 is outside the allowed range: <= 0.071 " \
           "(or no undercut)" in line, line


def test_a_gear_sliding_base_in_inches_is_named_with_its_unit(tmp_path):
    """-5.6402 mm typed in inches (-0.2221): the gear flanks reach their mean point, 0.22
    mm behind the tip plane against the blank's 5.64, inside the blade's 0.4 mm edge
    round. Session 27: the library named the edge round's refusal
    "blade.gear.drive.edge_radius_mm = 0.4 ... (25.4 times too large? ...)", a key typed
    right; session 28 named the slip as typed and the conversion, the edge round's
    finding kept. Since session 29 the comparison refuses it first: its root lies above
    the mating tip (docs sec. 2, "A root above the mating tip"), whatever the edge
    radius; exit 2."""
    code, _, err = run_console("design", "--pair", _typed(
        tmp_path, F2_MACHINE, {"sliding_base_mm = -5.6402": "sliding_base_mm = -0.2221"}))
    line = _error_line(err)
    assert code == 2
    assert line.startswith("gearcontact design: error: machine.gear.drive.sliding_base_mm = "
                           "-0.2221 is outside the allowed range: "), line
    assert "with the unit corrected (typed in inches: x 25.4 mm) the flank agrees" in line
    assert "the root above the mating tip, which runs 4.8369 mm deep" in line
