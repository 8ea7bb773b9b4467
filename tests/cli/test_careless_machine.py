"""The machine-settings workflow (`design --machine-settings`, its options, and the
commands on the files it writes) run as a careless user runs it, through the console
script: a misread print word, a length in the wrong unit, a typed gear that does not cut
its blank. Each test was a defect found by trying the command (session 26, helper
careless): the message it gave before is in the test's docstring.

Truth: the developers' guide (bad input: one error line naming the field, the value and
the allowed range, before any expensive work, exit 2; never an internal error) and
docs/machine_settings.md sec. 2 (a sign word read wrong is named by the typed-settings
check, "The check when a pair is loaded"; the published page's own readings).
"""

from pathlib import Path

import pytest
from console_script import run_console

ROOT = Path(__file__).resolve().parents[2]
PRINT_GEAR = ROOT / "examples" / "machine_settings" / "hypoid_10x41_print_gear.toml"


def _error_line(err: str) -> str:
    """The last stderr line, asserted to be an input error (not an internal one)."""
    assert "Traceback" not in err and "internal error" not in err, err
    return err.strip().splitlines()[-1]


def _misread(tmp_path, old: str, new: str) -> Path:
    """The published print's gear page with one printed line typed ``new``."""
    text = PRINT_GEAR.read_text()
    assert text.count(old) == 1, old
    path = tmp_path / "misread.toml"
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize("old, new, key", [
    # before: exit 1, "internal error, please report (ValueError: f(a) and f(b) must have
    # different signs)" from the standard pinion's blade (the gear never checked)
    ('blank_offset = "DN 0.225"', 'blank_offset = "UP 0.225"', "print.gear.blank_offset"),
    # before: exit 2 naming "blade.profile_reference_mm = -2.6165..." (a derived pinion
    # blade's key the user never typed)
    ('sliding_base = "WITH 0.070"', 'sliding_base = "AWAY 0.070"', "print.gear.sliding_base"),
    # before: exit 2 naming "gear coast flank at (u, v) = ... 'residual 6.005e-01'"
    ('machine_centre_to_back = "MD -0.240"', 'machine_centre_to_back = "MD +0.240"',
     "print.gear.machine_centre_to_back"),
])
def test_a_misread_word_of_a_typed_gear_is_named(tmp_path, old, new, key):
    """The gear page typed alone, one sign word read wrong (sec. 2's table: UP moves the
    printed spiral angle 10.7 deg, AWAY the root 3.6 mm, MD + 11.4 mm): the typed gear is
    checked against its print before its standard pinion is derived, and the word is named
    (its value as typed), exit 2."""
    code, _, err = run_console("design", "--pair", _misread(tmp_path, old, new),
                               "--machine-settings")
    line = _error_line(err)
    assert code == 2, err
    assert line.startswith("gearcontact design: error: ")
    assert f"{key} = '{new.split(' = ')[1][1:-1]}'" in line, line
    assert "docs/machine_settings.md" in line


F2_MACHINE = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def _typed(tmp_path, old: str, new: str) -> Path:
    """The F.2 pair typed as a summary sheet prints it, its first ``old`` typed ``new``."""
    text = F2_MACHINE.read_text()
    assert old in text, old
    path = tmp_path / "typed.toml"
    path.write_text(text.replace(old, new, 1))
    return path


def test_a_point_radius_typed_in_metres_is_named_with_the_edge_radius(tmp_path):
    """The gear's inside blade point radius typed in m: before, the error named
    ``edge_radius_mm = 0.4`` with the range ``[0, 0.05665]`` and not why (the range's
    end is half the point radius); now the edge radius's range names the point radius
    it comes from, as typed."""
    code, _, err = run_console("design", "--pair", _typed(
        tmp_path, "point_radius_mm = 113.3", "point_radius_mm = 0.1133"))
    line = _error_line(err)
    assert code == 2
    assert "blade.gear.drive.edge_radius_mm = 0.4 " in line
    assert "[0, 0.05665]" in line
    assert "blade.gear.drive.point_radius_mm = 0.1133" in line


def test_a_huge_point_radius_is_refused_by_its_range(tmp_path):
    """A point radius of 1e300 mm (a wrong exponent): before, three numpy
    RuntimeWarnings (overflow in square, dot; invalid value in divide) on stderr ahead
    of the cutter-circle refusal; now the key's range, read from the file, nothing
    computed: (0, 1000] mm, the radial distance's bound."""
    code, _, err = run_console("design", "--pair", _typed(
        tmp_path, "point_radius_mm = 113.3", "point_radius_mm = 1e300"))
    line = _error_line(err)
    assert code == 2
    assert "RuntimeWarning" not in err, err
    assert "blade.gear.drive.point_radius_mm = 1e+300" in line
    assert "(0, 1000]" in line


def test_a_grid_in_nanometres_names_the_csv_column(tmp_path):
    """A measured ease-off grid (`--target-flank`) whose `easeoff_um` column holds nm
    (20000 where 20 um is meant) over s0003's active coast flank (u 0.423..2.897, v
    27.705..43.913 mm, the range the grid check names): before, the error named the
    library's fitted polynomial, "easeoff (coast) relief at the toe/root corner ...
    reduce the crowning or move the relief centre" (advice for typed [easeoff] tables, no
    word of the file); now the file and its column, the limit kept (5 % of the pinion
    mean normal tooth thickness, 125.7 um on s0003)."""
    rows = ["side,v_mm,u_mm,easeoff_um"]
    for i, u in enumerate((0.423, 1.248, 2.072, 2.897)):
        rows += [f"coast,{v},{u},{20000.0 * (i > 0)}" for v in (27.705, 33.108, 38.51, 43.913)]
    grid = tmp_path / "grid_nm.csv"
    grid.write_text("\n".join(rows) + "\n")
    code, _, err = run_console("design", "--pair", "s0003", "--machine-settings",
                               "--target-flank", grid)
    line = _error_line(err)
    assert code == 2
    assert f"{grid}: coast easeoff_um" in line, line
    assert "<= 125.7 um" in line and "um, not nm or mm" in line
    assert "reduce the crowning" not in line


def test_a_file_saved_with_a_byte_order_mark_reads_as_without(tmp_path):
    """A pair file saved by an editor that writes the UTF-8 byte order mark (Windows
    Notepad, Excel's "CSV UTF-8"): before, "(TOML syntax) = 'Invalid statement (at line
    1, column 1)'" for the pair and "header = '\\ufeffside,v_mm,u_mm,easeoff_um'" for a
    grid CSV, though the text is the same; now the mark is read as the encoding's, not
    the text's: the same design printed byte for byte as from the file without it."""
    plain = tmp_path / "plain.toml"
    plain.write_text(F2_MACHINE.read_text(), encoding="utf-8")
    marked = tmp_path / "marked.toml"
    marked.write_text(F2_MACHINE.read_text(), encoding="utf-8-sig")
    assert marked.read_bytes().startswith(b"\xef\xbb\xbf")
    code, out, err = run_console("design", "--pair", marked)
    assert code == 0, err
    assert out == run_console("design", "--pair", plain)[1].replace("plain", "marked")


def test_a_bad_byte_after_a_byte_order_mark_is_named_at_its_offset(tmp_path):
    """The mark dropped, a bad byte is still named at its offset in the file (5 here:
    the 3 bytes of the mark, then "ab"), as an editor shows it."""
    grid = tmp_path / "bad.csv"
    grid.write_bytes(b"\xef\xbb\xbfab\xffcd")
    code, _, err = run_console("design", "--pair", "s0003", "--machine-settings",
                               "--target-flank", grid)
    line = _error_line(err)
    assert code == 2
    assert f"{grid} (byte 5) = b'\\xffcd'" in line and "UTF-8 text" in line


@pytest.mark.parametrize("command", ["design", "tca"])
def test_a_mean_point_off_the_face_is_refused_by_the_check(tmp_path, command):
    """The gear drive flank's machine root angle in radians (1.2262 for 70.2532 deg): its
    generating gear's mean cone distance is 227.07 mm against the blank's 81.273, 146 mm
    off on a 25.4 mm face (docs/machine_settings.md sec. 2, "A mean point off the face":
    beyond half the face width is an input error). Before (session 26): a warning
    naming the slip, then the ease-off shape's flanks failed on "blade.gear.drive.
    point_radius_mm = 113.3" (renamed to the slip by cli.settings_slip, the failure of
    a key typed right kept in the message). Now refused by the check itself, before any
    flank work: the slip as typed, the measured and the blank's values, the face's
    range (81.273 -+ 12.7 mm), exit 2, nothing of the work in the message."""
    argv = ["--out", tmp_path / "out", "--no-figures"] if command == "tca" else []
    code, _, err = run_console(command, "--pair", _typed(
        tmp_path, "machine_root_angle_deg = 70.2532", "machine_root_angle_deg = 1.2262"), *argv)
    line = _error_line(err)
    assert code == 2
    assert line.startswith(f"gearcontact {command}: error: "
                           "machine.gear.drive.machine_root_angle_deg = 1.2262 "), line
    assert "mean cone distance 227.0" in line and "the blank's 81.2730" in line, line
    assert "off the gear's face, 68.5730 to 93.9730 mm" in line, line
    assert "point_radius_mm" not in line and "failed on it" not in line, line
    assert not (tmp_path / "out").exists()


SLIPS_THE_WORK_MEETS = [
    # the pinion drive flank's ratio of roll typed as cradle / work (1 / 2.785714; sec. 2:
    # work / cradle): the check warns naming it, the run goes on, and the flank build
    # fails. Before: "pinion drive flank at (u, v) = (2.5426, 76.4937) mm = 'residual
    # 4.713e+01' ... a node the generated envelope reaches".
    ("ratio_of_roll = 2.785714", "ratio_of_roll = 0.358974",
     "machine.pinion.drive.ratio_of_roll = 0.358974 ", "residual"),
]


@pytest.mark.parametrize("command", ["design", "tca"])
@pytest.mark.parametrize("old, new, named, failure", SLIPS_THE_WORK_MEETS,
                         ids=["roll-cradle-per-work"])
def test_a_slip_the_check_warned_about_is_named_where_the_work_fails(
        tmp_path, command, old, new, named, failure):
    """A typed setting off its blank that the check warns about (not gross) and the
    flank work after it fails on: the error names the check's likely slip, its value
    as typed, the failure kept in the message (cli.settings_slip)."""
    argv = ["--out", tmp_path / "out", "--no-figures"] if command == "tca" else []
    code, _, err = run_console(command, "--pair", _typed(tmp_path, old, new), *argv)
    line = _error_line(err)
    assert code == 2
    assert line.startswith(f"gearcontact {command}: error: {named}"), line
    assert failure in line
    assert "warning: the " in err


@pytest.mark.parametrize("old, new, named", [
    ("pinion = 14", "pinion = 0", "teeth.pinion = 0 is outside the allowed range: an integer >= 5"),
    ("gear = 39", "gear = 10", "teeth.gear = 10 is outside the allowed range: an integer >= "
                               "teeth.pinion = 14"),
    ("offset_mm = 0.0", "offset_mm = -5.0", "axes.offset_mm = -5.0 "),
    ("pinion_spiral_angle_deg = 35.0", "pinion_spiral_angle_deg = 0.0",
     "design.pinion_spiral_angle_deg = 0.0 "),
    ("clearance_factor = 0.125", "clearance_factor = 12.5", "design.clearance_factor = 12.5 "),
])
def test_a_blank_key_is_named_as_the_file_spells_it(tmp_path, old, new, named):
    """The blank tables of a settings pair typed out of range: before, the key named as
    the blank design's argument ("pinion_teeth = 0", "offset_mm = -5.0",
    "clearance_factor = 12.5"), not as the file's table and key; now dotted, as every
    other key of the file is named (the range unchanged)."""
    code, _, err = run_console("design", "--pair", _typed(tmp_path, old, new))
    line = _error_line(err)
    assert code == 2
    assert f"typed.toml: {named}" in line, line


def test_an_easeoff_synthesis_of_a_pair_cut_from_settings_is_refused(tmp_path):
    """`design --synthesize-easeoff` on a pair cut from machine settings (the F.2 sheet):
    before, exit 1, "internal error, please report (AttributeError: 'RadialSheet' object
    has no attribute 'exact')" in the path-angle reach check (a generated pinion is no
    conjugate pinion with an ease-off); the tables it would print cannot be given beside
    the settings either (``[easeoff.*]`` is refused with ``[machine.*]``). Now refused
    before any flank, naming the option and the mode that synthesizes settings."""
    code, _, err = run_console("design", "--pair", F2_MACHINE, "--synthesize-easeoff")
    line = _error_line(err)
    assert code == 2
    assert "--synthesize-easeoff = True" in line
    assert "--machine-settings --local-synthesis" in line


@pytest.mark.parametrize("header, words", [
    # before: "Print = 'table' ... one of the tables ['assembly', ..., 'teeth']", the
    # print's table not among them
    ("[Print.Gear]", ["Print = 'table'", "'print.gear'"]),
    # before: the whole page's dict as the value (some 900 characters)
    ("[print.gera]", ["print.gera = 'table'", "[print.gear] only"]),
])
def test_a_misspelt_print_table_is_named_shortly_with_the_right_spelling(
        tmp_path, header, words):
    text = PRINT_GEAR.read_text()
    assert text.count("\n[print.gear]\n") == 1
    path = tmp_path / "page.toml"
    path.write_text(text.replace("\n[print.gear]\n", f"\n{header}\n"))
    code, _, err = run_console("design", "--pair", path, "--machine-settings")
    line = _error_line(err)
    assert code == 2
    for w in words:
        assert w in line, line
    assert len(line) < 600, line


@pytest.mark.parametrize("old, new, named", [
    # before: "print.gear.cutter_diameter_in = 9.0 ... a value whose conversion
    # (blade.gear.drive.point_radius_mm = -6.35) lies in (0, 1000]": the diameter, typed
    # right, named for the point width
    ("point_width_finish_in = 0.0900", "point_width_finish_in = 9.5",
     "print.gear.point_width_finish_in = 9.5 is outside the allowed range: [0, 9)"),
    # before: "print.gear.work_test_roll = '29D 57M' ... -29.9450 deg within half a
    # minute": the test roll, typed right, named for the ratio's sign
    ("ratio_nc_75 = 0.545665", "ratio_nc_75 = -0.545665",
     "print.gear.ratio_nc_75 = -0.545665 is outside the allowed range: [0, inf)"),
])
def test_a_print_number_out_of_range_is_named_not_the_one_beside_it(tmp_path, old, new,
                                                                       named):
    code, _, err = run_console("design", "--pair", _misread(tmp_path, old, new),
                               "--machine-settings")
    line = _error_line(err)
    assert code == 2
    assert named in line, line


def test_a_rerun_keeps_the_settings_file_the_user_edited(tmp_path):
    """docs/machine_settings.md sec. 5: `design --machine-settings --out DIR` writes
    the settings "as a TOML the user can keep and edit". Edited in place (a blade angle
    changed) and the same command run again: before, exit 0, the edit silently replaced
    by the standard settings (the directory held "a previous run of the same command");
    now refused before any work, naming the file and why (its SHA-256 is no longer the
    one run.json lists), the edit kept byte for byte; --force replaces it. An unedited
    re-run still replaces its files (byte-identical: identical runs)."""
    out = tmp_path / "ms"
    argv = ["design", "--pair", ROOT / "examples" / "iso23509_f2_spiral_bevel.toml",
            "--machine-settings", "--out", out]
    assert run_console(*argv)[0] == 0
    written = out / "machine_settings.toml"
    first = written.read_bytes()
    assert run_console(*argv)[0] == 0
    assert written.read_bytes() == first
    edited = first.replace(b"blade_angle_deg = 20.0", b"blade_angle_deg = 21.0", 1)
    assert edited != first
    written.write_bytes(edited)
    code, _, err = run_console(*argv)
    line = _error_line(err)
    assert code == 2
    assert "'machine_settings.toml'" in line and "run.json" in line and "--force" in line
    assert written.read_bytes() == edited
    assert run_console(*argv, "--force")[0] == 0
    assert written.read_bytes() == first


def test_a_target_flank_of_neither_format_names_both_headers(tmp_path):
    """`--target-flank` given the pair TOML (the wrong file): before, its first line
    refused against the ease-off grid's header alone, "side,v_mm,u_mm,easeoff_um", though
    the option reads measured deviations in machine coordinates too; now both headers
    are named."""
    code, _, err = run_console("design", "--pair", "s0003", "--machine-settings",
                               "--target-flank", F2_MACHINE)
    line = _error_line(err)
    assert code == 2
    assert f"{F2_MACHINE}: header = " in line
    assert "side,v_mm,u_mm,easeoff_um" in line
    assert "member,flank,L_mm,R_mm,deviation_um" in line


@pytest.mark.parametrize("torques", [["64.5", "64.5"], ["64.5", "64.500001"]])
def test_a_torque_given_twice_is_refused(tmp_path, torques):
    """`analyze --torques 64.5 64.5` (on the F.2 settings pair): before, exit 0, the LTCA
    solved twice, ltca_torques.csv with the row twice and one pressure_64.5Nm.csv (the
    second run's; a torque equal to 6 significant digits, 64.500001, wrote the same
    file name over the first's). Now refused before any work, naming the option and the
    repeated torque."""
    code, _, err = run_console("analyze", "--pair", F2_MACHINE, "--torques", *torques,
                               "--out", tmp_path / "a")
    line = _error_line(err)
    assert code == 2
    assert line.startswith("gearcontact analyze: error: --torques = ")
    assert "each torque once" in line and "pressure_64.5Nm.csv" in line
    assert not (tmp_path / "a").exists()


def test_an_empty_out_is_refused_not_the_working_directory(tmp_path):
    """`design --machine-settings --out ""` (an unset shell variable): before, exit 0 and
    machine_settings.toml written into the working directory, outside the
    output-directory policy (no run.json, beside foreign files); now the policy's
    refusal of an empty path, nothing written."""
    code, _, err = run_console("design", "--pair", ROOT / "examples" /
                               "iso23509_f2_spiral_bevel.toml", "--machine-settings",
                               "--out", "", cwd=tmp_path)
    line = _error_line(err)
    assert code == 2
    assert "--out = ''" in line and "empty path given" in line
    assert list(tmp_path.iterdir()) == []
