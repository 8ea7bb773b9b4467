"""Every command that analyses a pair checks its typed machine settings against its own
blank tables when it loads the pair, as ``design`` does (cli.options.check_machine_settings,
geometry.blank_check; docs/machine_settings.md sec. 2, "The check when a pair is
loaded"): the warning on stderr naming the key, and in the run's files (run.json
``blank_check``, analyze's summary.md). The installed console script, small options.

Truths: the ISO 23509 F.2 example (examples/machine_settings/iso23509_f2_machine.toml,
the standard settings of its blank typed to 4 decimals) agrees with its blank (no
warning, ``agrees`` true); the same file with one sheet word misread in both pinion
tables (written here) is caught and the misread key named: the flip is the truth
(tests/geometry/test_blank_check.py measures the same slips: the sliding base WITH /
AWAY puts the pinion's root 6.73 / 9.67 mm behind the tip plane against the blank's
2.39 mm; the ratio of roll typed as its reciprocal, 39/14 -> 14/39, cuts pinion flanks
that do not reach the mean point, and the pinion's generation then refuses them, as in
``design``). Tolerances: geometry.blank_check's, tested there.
"""

import importlib
import json
import math

import pytest
from console_script import run_console

import gearcontact.geometry.settings_check as settings_check
from gearcontact.cli import main

from .test_design_blank_check import F2_MACHINE, _flipped
from .test_pair_preparation import COMMANDS as PREPARED
from .test_pair_preparation import _capture

#: Small runs: the check runs before any work, whatever the phases.
TCA = ("--phases", "3", "--no-figures", "--quiet")


@pytest.fixture(scope="module")
def sliding_base_slip(tmp_path_factory):
    return _flipped(tmp_path_factory.mktemp("slip"), "machine.pinion", "sliding_base_mm",
                    lambda x: -x)


def _named(err: str, key: str) -> None:
    for side in ("drive", "coast"):
        assert f"likely machine.pinion.{side}.{key}" in err, err


def test_tca_records_a_settings_warning_in_run_json(tmp_path):
    # the pinion's machine root 0.5 deg off (no known slip; the flanks stay regular): a
    # warning, not an error: the run goes on (exit 0) and its run.json says it (1 deg
    # puts the pinion root above the mating tip: refused since session 29, docs
    # sec. 2, "A root above the mating tip")
    path = _flipped(tmp_path, "machine.pinion", "machine_root_angle_deg", lambda x: x + 0.5)
    code, out, err = run_console("tca", "--pair", path, "--out", tmp_path / "t", *TCA)
    assert code == 0, err
    got = json.loads((tmp_path / "t" / "run.json").read_text())["blank_check"]
    assert got["agrees"] is False and len(got["warnings"]) == 2
    for side in ("drive", "coast"):
        assert got["flanks"]["gear"][side]["agrees"] is True
        assert got["flanks"]["pinion"][side]["agrees"] is False
        assert f"[machine.pinion.{side}]" in err


def test_tca_warns_a_sliding_base_slip_then_refuses_the_pointed_tooth(tmp_path,
                                                                     sliding_base_slip):
    # the slip's warnings name the key; the settings then cut a pointed pinion (its
    # sliding base AWAY for WITH cuts 6.7 / 9.7 mm deep against the blank's 2.39:
    # geometry.settings_top_land), refused before any work: exit 2, nothing written
    code, out, err = run_console("tca", "--pair", sliding_base_slip, "--out",
                                 tmp_path / "t", *TCA)
    assert code == 2, err
    _named(err, "sliding_base_mm")
    assert "a pointed pinion tooth" in err and "likely slip" in err
    assert not (tmp_path / "t").exists()


def test_analyze_warns_a_sliding_base_slip_then_refuses_the_pointed_tooth(tmp_path,
                                                                         sliding_base_slip):
    code, out, err = run_console("analyze", "--pair", sliding_base_slip, "--out",
                                 tmp_path / "a", *TCA, "--torques", "64.5",
                                 "--lte-phases", "0")
    assert code == 2, err
    _named(err, "sliding_base_mm")
    assert "a pointed pinion tooth" in err
    assert not (tmp_path / "a").exists()


@pytest.mark.parametrize("command", ["tca", pytest.param("analyze", marks=pytest.mark.slow)])
def test_a_ratio_of_roll_reciprocal_is_named_before_the_generation_refuses(tmp_path,
                                                                           command):
    # the pinion's ratio of roll typed as cradle / work: the check names it on stderr
    # (a warning), then the pinion's generation refuses the flanks it cuts (exit 2, as
    # design does; a refused run leaves no directory)
    path = _flipped(tmp_path, "machine.pinion", "ratio_of_roll", lambda x: 1.0 / x)
    code, out, err = run_console(command, "--pair", path, "--out", tmp_path / "o", *TCA)
    assert code == 2, err
    _named(err, "ratio_of_roll")
    assert err.index("likely machine.pinion.drive.ratio_of_roll") \
        < err.index("gearcontact " + command + ":")
    assert not (tmp_path / "o").exists()


COMMANDS = [("lte",), ("ltca",), ("twin",), ("sweep",), ("bending",), ("export", "fmu"),
            ("export", "flanks")]


@pytest.mark.parametrize("command", COMMANDS, ids=[" ".join(c) for c in COMMANDS])
def test_every_command_checks_the_settings(tmp_path, capsys, command):
    # the check runs in every command's argument check, so a gross slip is refused
    # there, exit 2 before any work (a refused run leaves no directory): the blank's
    # hand word misread (every flank cuts the other hand; design exits 2 on it too,
    # tests/cli/test_design_blank_check.py; the cheapest gross slip: no slip search per
    # flank). In process (the console script's start-up is what the tests above pay)
    path = _flipped(tmp_path, "design", "pinion_hand", lambda line: 'pinion_hand = "left"')
    code = main([*command, "--pair", str(path), "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "design.pinion_hand = 'left' is outside the allowed range" in err
    assert not (tmp_path / "o").exists()


def test_a_clean_sheet_gets_no_warning(tmp_path):
    code, out, err = run_console("tca", "--pair", F2_MACHINE, "--out", tmp_path / "t", *TCA)
    assert code == 0, err
    assert "warning" not in err
    got = json.loads((tmp_path / "t" / "run.json").read_text())
    assert got["blank_check"]["agrees"] is True and got["blank_check"]["warnings"] == []
    assert got["timings_s"]["blank_check_s"] > 0.0


def test_a_pair_without_settings_has_no_entry(tmp_path):
    # pairs without [machine.*] tables: run.json keeps its fields
    code, out, err = run_console("tca", "--pair", "s0003-centred", "--out", tmp_path / "t",
                                 *TCA)
    assert code == 0, err
    got = json.loads((tmp_path / "t" / "run.json").read_text())
    assert "blank_check" not in got and "blank_check_s" not in got["timings_s"]


def test_a_pinion_blade_angle_in_radians_is_refused_naming_its_key(tmp_path):
    # 20 deg typed as 0.349 in both pinion blade tables: the pinion's pressure angle at
    # its mean point ~0.5 deg against the blank's 20 (geometry.blank_check,
    # GROSS_PRESSURE_DEG): exit 2 in the argument check, the blade key named, before the
    # envelope refused a node (the audit's run) and before any directory is written
    path = _flipped(tmp_path, "blade.pinion", "blade_angle_deg",
                    lambda x: round(math.radians(x), 3))
    code, out, err = run_console("tca", "--pair", path, "--out", tmp_path / "t", *TCA)
    assert code == 2, err
    assert "blade.pinion.drive.blade_angle_deg = 0.349 is outside the allowed range" in err
    assert "typed in radians" in err and "envelope" not in err
    assert not (tmp_path / "t").exists()


#: Where each command's analysis starts (tests/cli/test_pair_preparation.py's table) and
#: the export commands' library calls.
ANALYSED = {**{(c,): entry for c, entry in PREPARED.items()},
            ("export", "flanks"): ([], "gearcontact.export.flanks", "export_flanks"),
            ("export", "fmu"): ([], "gearcontact.export.fmu", "export_mesh_fmu")}


@pytest.mark.parametrize("command", sorted(ANALYSED), ids=" ".join)
def test_every_command_runs_the_check_once(tmp_path, monkeypatch, command):
    # the argument check runs it and hands its result to the library
    # (tca.synthesis.prepare_pair, report.analyze.run_analysis), which runs it when
    # given none: one comparison with the blank per run (the count is the truth). The
    # command is stopped where its analysis starts (after the preparation); that call
    # is handed the prepared flanks (a library call given none checks the pair again)
    calls, seen = [], []

    def counted(*args, _real=settings_check.check_pair_blank, **kwargs):
        calls.append(args)
        return _real(*args, **kwargs)

    monkeypatch.setattr(settings_check, "check_pair_blank", counted)
    extra, module, name = ANALYSED[command]
    importlib.import_module(module)     # modules that commands import when they run
    _capture(monkeypatch, module, name, seen)
    main([*command, "--pair", str(F2_MACHINE), *extra, "--out", str(tmp_path / "o")])
    assert len(seen) == 1, command      # the analysis was reached
    assert len(calls) == 1
    assert seen[0][1] is not None


def test_rtl_serve_refuses_a_hand_slip_before_serving(tmp_path, capsys, monkeypatch):
    # rtl serve --pair bakes the pair's E' into a simulated SoC: the pair is checked as
    # every pair command checks it, in the argument check, before anything is built
    # (the hand slip: exit 2 naming the key; the server never started)
    import gearcontact.hw.serve as hw_serve

    def serve(*args, **kwargs):
        raise AssertionError("served")

    monkeypatch.setattr(hw_serve, "serve", serve)
    path = _flipped(tmp_path, "design", "pinion_hand", lambda line: 'pinion_hand = "left"')
    code = main(["rtl", "serve", "--pair", str(path)])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "design.pinion_hand = 'left' is outside the allowed range" in err


def test_rtl_serve_warns_a_sliding_base_slip_and_serves(sliding_base_slip, capsys,
                                                       monkeypatch):
    # a warning-level slip: the warning lines on stderr naming the key, then the SoC
    # is served (here a stand-in that returns at once)
    import gearcontact.hw.serve as hw_serve

    served = []
    monkeypatch.setattr(hw_serve, "serve", lambda kind, **kwargs: served.append(kind))
    code = main(["rtl", "serve", "--pair", str(sliding_base_slip)])
    err = capsys.readouterr().err
    assert code == 0, err
    _named(err, "sliding_base_mm")
    assert served == ["tri_core"]


#: The commands that run no TCA of the pair (cli.options.load_pair_for(mesh_follows=False)).
WITHOUT_TCA = {("bending",), ("export", "flanks")}
#: Run by default (one of each kind); the others are slow.
QUICK = {("tca",), ("bending",)}


@pytest.fixture(scope="module")
def short_prediction(tmp_path_factory):
    """The standard settings of the 16 mm miter blank of
    tests/geometry/test_machine_contact_ratio.py (predicted eps_p 0.703 < 0.85, eps_vg
    1.426 < 1.55; their TCA has no gap, the console ``tca`` exits 0 on them there) typed
    into a pair file."""
    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.gear_generation import generation_of
    from gearcontact.geometry.generation import check_generation
    from gearcontact.geometry.pair import load_pair, pair_to_toml

    from geometry.test_machine_contact_ratio import _blank

    directory = tmp_path_factory.mktemp("short")
    blank = load_pair(_blank(directory, 16.0))
    cut = standard_machine_pair(blank, gear_generation=generation_of(
        check_generation(blank, contact_ratio=False)))
    path = directory / "miter_16_settings.toml"
    path.write_text(pair_to_toml(cut))
    return path


@pytest.mark.parametrize("command", [c if c in QUICK else pytest.param(
    c, marks=pytest.mark.slow) for c in sorted(ANALYSED)], ids=" ".join)
def test_the_prediction_is_warned_only_where_no_tca_follows(short_prediction, tmp_path,
                                                            monkeypatch, capsys, command):
    # docs/machine_settings.md sec. 5, "The readers' verdict on a short prediction": a
    # command whose TCA follows says nothing of the prediction (its TCA refuses a gap:
    # tests/geometry/test_machine_contact_ratio.py, the 12/12's settings through `tca`);
    # bending and export flanks warn once, naming the TCA that decides. Stopped where
    # the analysis starts: the warning is printed when the pair is read, before it
    extra, module, name = ANALYSED[command]
    importlib.import_module(module)
    seen = []
    _capture(monkeypatch, module, name, seen)
    main([*command, "--pair", str(short_prediction), *extra, "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert len(seen) == 1, err          # the analysis was reached
    warned = err.count("(ContactRatioWarning)")
    if command in WITHOUT_TCA:
        assert warned == 1, err
        assert "eps_p = 0.703" in err and "runs no TCA of the pair" in err
        assert "`gearcontact tca --pair FILE` measures the mesh" in err
    else:
        assert warned == 0, err


def test_a_generated_gears_hollow_pinion_is_warned_on_load(tmp_path, capsys):
    # F.3's standard settings with a generated gear and a drive pinion 2C of 0.05 typed
    # (tests/geometry/test_easeoff_shape.py: hollow lengthwise, -10.5 um): `tca` reads it
    # with the hollow line on stderr, measured after the generation check on its gear
    # boxes, and run.json's easeoff_shape holds the completed check: design's own
    # measurement of the same pair (check_settings(easeoff_generated=True), in this
    # process), float for float (JSON keeps a float's repr: exact)
    from geometry.test_easeoff_shape import ROOT, _with_drive_2c

    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.pair import load_pair, pair_to_toml
    from gearcontact.geometry.settings_check import check_settings

    pair = _with_drive_2c(standard_machine_pair(
        load_pair(ROOT / "examples" / "iso23509_f3.toml"), gear_generation="generated"), 0.05)
    path = tmp_path / "f3_generated_2c.toml"
    path.write_text(pair_to_toml(pair))
    design = check_settings(load_pair(path), easeoff_generated=True).easeoff
    assert [s.side for s in design.flanks if s.flagged] == ["drive"]
    assert main(["tca", "--pair", str(path), "--out", str(tmp_path / "t"), *TCA]) == 0
    err = capsys.readouterr().err
    assert err.count("(HollowEaseOffWarning)") == 1
    assert "the pinion drive flank cut from [machine.pinion.drive] is hollow" in err
    got = json.loads((tmp_path / "t" / "run.json").read_text())["easeoff_shape"]
    assert got["missing"] == {} and len(got["warnings"]) == 1
    for s in design.flanks:
        for key in ("C_p_um", "C_l_um", "bias_um", "fit_rms_um"):
            assert got["flanks"][s.side][key] == getattr(s, key), (s.side, key)
        assert got["flanks"][s.side]["flagged"] is s.flagged
