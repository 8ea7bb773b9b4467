"""The README's machine-settings lines, verbatim, in a real process (issue 27).

``gearcontact design --pair s0003 --machine-settings --out mach_s0003/`` fits the pinion
settings that cut s0003's ease-off (~20 s). Truths: its residual table is the library's measured one
(tests/geometry/test_setting_fit.py: coast 0.566 / 0.120 um max / RMS) and the written
pair loads back with settings for all four flanks, the coast blade with its cubic term.

``gearcontact design --pair examples/iso23509_f2_spiral_bevel.toml --machine-settings
--out mach/`` writes the standard settings of the F.2 pair; ``gearcontact analyze --pair
mach/machine_settings.toml --out results/f2_machine`` runs the main job on the flanks cut
from them. Both lines run as printed from a scratch directory holding a link to
``examples/``, so their relative paths resolve as in a checkout.

Truths: the written file loads back as the F.2 pair with settings for all four flanks
(that the settings reproduce the blank's spiral and pressure angles is
tests/geometry/test_basic_settings.py's); ``analyze`` synthesizes no ease-off for it,
conserves load in the multi-tooth step (shares add to 100 %, 1e-9 %) and its loaded
TE's LCPs converged.
"""

import json
import os
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
from readme_lines import readme_commands

import gearcontact
from gearcontact.geometry.pair import load_pair

ROOT = Path(__file__).resolve().parents[2]


def _readme_lines() -> list[str]:
    design = [c for c in readme_commands()
              if "--machine-settings" in c and "iso23509_f2_spiral_bevel" in c]
    analyze = [c for c in readme_commands()
               if c.startswith("gearcontact analyze") and "machine_settings.toml" in c]
    assert len(design) == 1 and len(analyze) == 1, (design, analyze)
    return [design[0], analyze[0]]


def _run(line: str, cwd: Path) -> subprocess.CompletedProcess:
    src = str(Path(gearcontact.__file__).parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
    return subprocess.run([sys.executable, "-m", "gearcontact", *shlex.split(line)[1:]],
                          cwd=cwd, env=env, capture_output=True, text=True, timeout=3000,
                          check=False)


def _run_example_line(prefix: str, tmp_path: Path) -> tuple[subprocess.CompletedProcess, Path]:
    """The one README line starting with ``prefix``, run as written from ``tmp_path``
    (holding a link to ``examples/``); it exits 0. Its process and ``--out`` directory."""
    lines = [c for c in readme_commands() if c.startswith(prefix)]
    assert len(lines) == 1, lines
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    proc = _run(lines[0], tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    words = shlex.split(lines[0])
    return proc, tmp_path / words[words.index("--out") + 1]


def test_readme_machine_settings_lines(tmp_path):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    design, analyze = _readme_lines()
    proc = _run(design, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    written = tmp_path / "mach" / "machine_settings.toml"
    pair = load_pair(written)
    assert len(pair.machine) == 4
    base = load_pair(ROOT / "examples" / "iso23509_f2_spiral_bevel.toml")
    assert (pair.pinion_teeth, pair.gear_teeth) == (base.pinion_teeth, base.gear_teeth)
    proc = _run(analyze, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    out = tmp_path / "results" / "f2_machine"
    assert "ease-off synthesized" not in proc.stdout
    tca = json.loads((out / "tca.json").read_text())
    assert tca["te0_pp_arcsec"] > 0.0
    mt = json.loads((out / "multitooth.json").read_text())
    assert sum(mt["load_share_pct"]) == pytest.approx(100.0, abs=1e-9)
    lte = json.loads((out / "lte.json").read_text())
    for rec in (lte if isinstance(lte, list) else [lte]):
        assert rec["converged"], rec.get("unconverged_phases")


def _s0003_line() -> str:
    lines = [c for c in readme_commands() if c.startswith("gearcontact design --pair s0003 ")
             and "--machine-settings" in c]
    assert len(lines) == 1, lines
    return lines[0]


def test_readme_s0003_machine_settings_line_parses():
    # the line as written, through the CLI's parser: the built-in pair, the fit, the
    # output directory (running it is the slow test below)
    from gearcontact.cli import build_parser

    args = build_parser().parse_args(shlex.split(_s0003_line())[1:])
    assert (args.command, args.pair, args.machine_settings) == ("design", "s0003", True)
    assert args.out is not None and Path(args.out) == Path("mach_s0003")


def test_readme_s0003_machine_settings_line(tmp_path):
    proc = _run(_s0003_line(), tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    # drive: the conjugate seed (0.000 um); coast: the measured residual of the fit
    assert "| drive | 0.00 | 0.000 | 0.000 |" in proc.stdout
    assert "| coast | 22.90 | 0.566 | 0.120 |" in proc.stdout
    pair = load_pair(tmp_path / "mach_s0003" / "machine_settings.toml")
    assert len(pair.machine) == 4
    coast = next(s for s in pair.machine if (s.member, s.side) == ("pinion", "coast"))
    assert coast.blade.profile_cubic_per_mm2 != 0.0
    # drive: its ease-off table is all zero, so the fit leaves terms of rounding (a
    # radius of 1e10 mm, a cubic of 1e-10 1/mm^2; session 28's audit): written straight,
    # as geometry.written_blade's 1 nm rule says, and named in the head comment
    drive = next(s for s in pair.machine if (s.member, s.side) == ("pinion", "drive"))
    assert (drive.blade.profile_radius_mm, drive.blade.profile_cubic_per_mm2,
            drive.blade.profile_quartic_per_mm3) == (0.0, 0.0, 0.0)
    head = (tmp_path / "mach_s0003" / "machine_settings.toml").read_text()
    assert "# blade.pinion.drive.profile_radius_mm / profile_cubic_per_mm2: the derived " \
        "profile" in head and "written straight (0)" in head
    assert "refuse this side" in head
    # and its roll: the fit leaves ratio 10.00000000027, 2C -1.2e-11, 6D -8.7e-11 there
    # (session 29), a flank displacement of at most 5e-10 mm against the seed's roll
    # (geometry.written_roll's bound, brute force 2.2e-10 mm:
    # tests/geometry/test_written_roll.py), below its 1 nm rule: written as the seed's,
    # the conjugate pinion's of a formate gear, whose ratio of roll is z2 / z1 = 70 / 7
    # exactly (the gear is its own generating gear), no modified roll
    assert drive.settings.ratio_of_roll == 70 / 7 == 10.0
    assert (drive.settings.modified_roll, drive.settings.helical_motion) == ((), ())
    assert "# machine.pinion.drive: the fitted motion (ratio of roll 10.0000000003, 2C " \
        "-1.22e-11, 6D -8.75e-11) departs" in head and "written as the seed's (ratio " \
        "of roll 10)" in head
    # every other value written as fitted: the coast keeps its roll (a departure of
    # 0.0635 in the ratio is no rounding)
    assert coast.settings.ratio_of_roll != 10.0 and len(coast.settings.modified_roll) == 2
    assert (tmp_path / "mach_s0003" / "machine_settings_residual.svg").is_file()


def test_readme_typed_machine_settings_example(tmp_path):
    """The shipped typed-settings example (examples/machine_settings/, kept out of the
    `examples/*.toml` glob of test_examples.py) in its README line, as written (issue
    28: every shipped example appears in the README as a command that works). Truths as
    for the `mach/` line above: the flanks are cut from the file's settings (no ease-off
    synthesized), the multi-tooth shares conserve the load (1e-9 %), the loaded TE's
    LCPs converged. About 30 s CPU (issue 28 audit: exit 0, 27 s CPU)."""
    proc, out = _run_example_line("gearcontact analyze --pair examples/machine_settings/", tmp_path)
    assert "ease-off synthesized" not in proc.stdout
    pair = load_pair(ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml")
    assert len(pair.machine) == 4
    # summary.md says so under the blank (the file: gear ratio of roll 0, formate; the
    # typed sheet agrees with its blank, tests/geometry/test_blank_check.py)
    assert ("Flanks cut from machine settings (the pair's [machine.*] / [blade.*] tables): "
            "gear drive and coast formate, pinion drive and coast generated. The "
            "typed-settings check: every flank agrees with the blank within its tolerance"
            ) in (out / "summary.md").read_text()
    mt = json.loads((out / "multitooth.json").read_text())
    assert sum(mt["load_share_pct"]) == pytest.approx(100.0, abs=1e-9)
    lte = json.loads((out / "lte.json").read_text())
    for rec in (lte if isinstance(lte, list) else [lte]):
        assert rec["converged"], rec.get("unconverged_phases")


def test_readme_print_gear_example(tmp_path):
    """The shipped print's gear page alone (examples/machine_settings/
    hypoid_10x41_print_gear.toml) in its README line, as written: ``design
    --machine-settings`` keeps the gear as printed and writes its standard pinion.
    Truths: the written ``[print.gear]`` is the example's, verbatim (the gear is kept as
    typed); its pinion is the library's ``typed_gear_machine_pair`` of the example's gear
    with the default crowning, floats at full precision (==: the CLI adds nothing); and
    the written pair's members are mates: loading it and building its flanks raises no
    ``MateWarning`` (normals at the pinion's mean point within 1 deg, the warning's bound;
    the blank's own standard pinion with this gear is 2.6 / 3.0 deg apart,
    docs/machine_settings.md sec. 5). About 10 s CPU."""
    import tomllib
    import warnings

    from gearcontact.geometry.flank import MateWarning, build_flanks
    from gearcontact.geometry.typed_pinion import typed_gear_machine_pair

    proc, out = _run_example_line("gearcontact design --pair examples/machine_settings/", tmp_path)
    example = ROOT / "examples" / "machine_settings" / "hypoid_10x41_print_gear.toml"
    written = out / "machine_settings.toml"
    with open(example, "rb") as f, open(written, "rb") as g:
        assert tomllib.load(g)["print"]["gear"] == tomllib.load(f)["print"]["gear"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # the typed-settings check's notes
        typed = load_pair(example, gear_alone=True)
    want = typed_gear_machine_pair(typed)
    with warnings.catch_warnings():
        warnings.simplefilter("error", MateWarning)
        pair = load_pair(written)
        build_flanks(pair)
    assert pair.machine == want.machine
