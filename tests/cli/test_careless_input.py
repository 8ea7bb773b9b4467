"""The options of session 12's commands as a careless user gives them, through the
installed console script: every refusal exits 2 with one line naming the option (or
the file's field) and the value given, before any flank work; none is an internal error
(exit 1) or a traceback, and no option is silently ignored. Each test is one process
(~5 s on two busy cores, nearly all of it the start-up).

Truth: the developers' guide (bad input: field, value, allowed range, before any
expensive work; nothing silently dropped). Each refusal below was a defect found by
trying the command: an ignored option (exit 0), a contradiction reported only after the
pair's generation check (or as the pair's own defect), a field named as the library
spells it instead of the option.
"""

from pathlib import Path

import pytest

from console_script import run_console
from design_space import design_space_candidate
from gearcontact.geometry.pair import pair_to_toml

ROOT = Path(__file__).resolve().parents[2]
SPUR = ROOT / "examples" / "spur_20x40_m3.toml"
F3 = ROOT / "examples" / "iso23509_f3.toml"


def _refused(argv, *words):
    """Run ``gearcontact *argv``: exit 2, one error line holding every word, no
    traceback; returns stderr."""
    code, _, err = run_console(*argv)
    assert code == 2, err
    assert "Traceback" not in err and "internal error" not in err, err
    line = err.strip().splitlines()[-1]
    for w in words:
        assert w in line, (w, line)
    return line


@pytest.fixture(scope="module")
def short_path_pair(tmp_path_factory):
    """10/15, E 0.3 r2, beta1 25 deg, face 0.15 R_m (tests/design_space.py), crowned:
    ``design`` refuses the pair itself (contact path eps_p 0.778 < 0.85, naming the
    spiral angle; tests/geometry/test_contact_ratio.py) -- so an option refused on it
    is refused before the pair's generation check."""
    path = tmp_path_factory.mktemp("pair") / "short_path.toml"
    path.write_text(pair_to_toml(design_space_candidate(10, 1.5, 0.3, 25.0, 0.15, "drive")))
    return path


@pytest.mark.parametrize("argv, words", [
    # given without what they need: exit 0 before, the option ignored
    (["--force"], ["--force", "True", "--out"]),
    (["--machine-settings", "--json"], ["--json", "True", "--machine-settings"]),
    # contradictions: named before the pair's own refusal (before: pinion_spiral_angle_deg)
    (["--fit", "minimax"], ["--fit", "'minimax'", "--machine-settings"]),
    (["--machine-settings", "--local-synthesis"], ["--local-synthesis", "ease-off"]),
])
def test_design_options_refused_before_the_pair(short_path_pair, argv, words):
    line = _refused(["design", "--pair", short_path_pair, *argv], *words)
    assert "pinion_spiral_angle_deg" not in line


def test_a_contact_path_too_short_for_any_fix_names_the_teeth_as_the_file_spells_them(
        tmp_path):
    """The contact-ratio refusal (geometry.contact_ratio) names the file's keys: 8/8,
    beta1 20 deg, face 0.15 R_m (tests/geometry/test_contact_ratio.py: eps_p 0.752,
    neither a face nor a spiral angle fixes it). Before: "pinion_teeth / gear_teeth =
    (8, 8)", the library's names (the blank keys were named as typed since session 26,
    geometry.pair; this refusal comes after the reader, from the generation check). The
    spiral angle's: tests/cli/test_pair_refusal.py (design, twin, export fmu)."""
    path = tmp_path / "eight.toml"
    path.write_text(pair_to_toml(design_space_candidate(8, 1.0, 0.0, 20.0, 0.15, "drive")))
    line = _refused(["design", "--pair", path])
    assert line.startswith("gearcontact design: error: teeth.pinion / teeth.gear = (8, 8) is "
                           "outside the allowed range: more teeth (the contact path of "), line
    assert "no face width or spiral angle tried fixes it" in line


def test_design_target_flank_directory_names_the_option(tmp_path):
    # before: "target flank = ..." (the reader's field, not the option)
    _refused(["design", "--pair", F3, "--machine-settings", "--target-flank", tmp_path],
             "--target-flank", str(tmp_path), "file")


def test_design_local_synthesis_on_a_cylindrical_pair():
    # before: exit 0, the cylindrical geometry printed and the option ignored
    _refused(["design", "--pair", SPUR, "--local-synthesis"], "--local-synthesis",
             "cylindrical")


def test_twin_refuses_a_drivetrain_file_as_the_pair(tmp_path):
    # before: "drivetrain = 'table' ... one of the tables [...]" (an unknown table)
    _refused(["twin", "--pair", ROOT / "examples" / "drivetrain_s0003.toml", "--out",
              tmp_path / "d"], "drivetrain_s0003.toml", "[drivetrain]", "--drivetrain")
    assert not (tmp_path / "d").exists()


@pytest.mark.parametrize("command", [["export", "fmu", "--bending"],
                                     ["export", "fmu", "--kind", "drivetrain"], ["twin"]])
def test_a_conjugate_loaded_side_is_refused_before_the_tca(tmp_path, command):
    # s0003 (no assembly errors) with an [easeoff.coast] table of zeros: the loaded
    # coast flanks (its design side) are conjugate, line contact. Before: the flanks built and the TCA run
    # (31 s for a generated hypoid) to exit 2 with the line contact; now refused naming
    # the table before any flank, the output directory not created
    from dataclasses import replace

    from gearcontact.geometry.pair import EaseOffCoefficients, load_pair

    pair = tmp_path / "conjugate.toml"
    pair.write_text(pair_to_toml(replace(load_pair("s0003"),
                                         easeoff_coast=EaseOffCoefficients())))
    _refused([*command, "--pair", pair, "--out", tmp_path / "o"], "[easeoff.coast]",
             "all coefficients 0", "synthesized")
    assert not (tmp_path / "o").exists()
