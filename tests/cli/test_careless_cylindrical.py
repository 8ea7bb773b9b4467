"""A careless user's tries on cylindrical pairs, through every command that reads one
(issue 26's acceptance: design, tca, lte, ltca, analyze, twin, bending, sweep, export
flanks, export fmu).

Truth (the house rule on bad input, docs/cylindrical.md sec. 1): each bad file or option
is exit code 2 with a message naming the field, the value and the allowed range, before
any work -- no output directory is created, nothing beside it is touched. The messages
are matched on the words a user needs (the dotted key, the value as written, the rule);
no number is measured here, so there is no tolerance. A rerun into the directory of its
own earlier run works and rewrites the same files (run.json, which holds timings, aside).
"""

import re
from pathlib import Path

import pytest

from gearcontact.cli import main

ROOT = Path(__file__).resolve().parents[2]
SPUR = ROOT / "examples" / "spur_20x40_m3.toml"
EV = ROOT / "examples" / "ev_reducer_helical_23x67.toml"

# every command that takes --pair and reads a cylindrical pair, with the least options
# it needs; design prints (no --out)
COMMANDS = {
    "design": ["design"],
    "tca": ["tca", "--no-figures"],
    "lte": ["lte", "--no-figures", "--phases", "3"],
    "analyze": ["analyze", "--no-figures", "--phases", "3"],
    "twin": ["twin", "--no-figures", "--phases", "3"],
    "bending": ["bending"],
    "sweep": ["sweep", "--vary", "modifications.pinion.lead_crowning_um=0:10:2"],
    "export flanks": ["export", "flanks"],
    "ltca": ["ltca", "--no-figures", "--phases", "3"],
    "export fmu": ["export", "fmu", "--kind", "mesh", "--phases", "3"],
}


def _edit(text: str, tmp_path: Path, name: str, old: str, new: str) -> Path:
    assert old in text, old
    path = tmp_path / f"{name}.toml"
    path.write_text(text.replace(old, new, 1))
    return path


def _bad_files(tmp_path: Path) -> dict[str, tuple[Path, list[str]]]:
    spur, ev = SPUR.read_text(), EV.read_text()
    helix0 = re.sub(r"helix_angle_deg = [0-9.]+", "helix_angle_deg = 0.0", ev)
    return {
        # a hand on a spur pair: the key, the value, the rule
        "spur with pinion_hand": (
            _edit(spur, tmp_path, "spur_hand", "[cylindrical]\n",
                  '[cylindrical]\npinion_hand = "right"\n'),
            ["cylindrical.pinion_hand", "'right'", "absent for a spur pair"]),
        # the helical example turned spur, its hand left in
        "helix 0 with hand": (
            _edit(helix0, tmp_path, "helix0_hand", "[teeth]", "[teeth]"),
            ["cylindrical.pinion_hand", "'left'", "absent for a spur pair"]),
        # a misspelt key: named, the known keys listed
        "bad key": (
            _edit(spur, tmp_path, "bad_key", "[cylindrical]\n",
                  "[cylindrical]\nhelix_angle_degs = 10.0\n"),
            ["cylindrical.helix_angle_degs", "10.0", "a known key of [cylindrical]",
             "'helix_angle_deg'"]),
        "bad modification key": (
            _edit(ev, tmp_path, "bad_mod_key", "lead_crowning_um = 5.0",
                  "lead_crowing_um = 5.0"),
            ["modifications.pinion.lead_crowing_um", "'lead_crowning_um'"]),
        # a material table without its Young's modulus (an absent table is steel)
        "material without E": (
            _edit(ev, tmp_path, "material_no_e", "[material.gear]\nyoungs_modulus_gpa = 210.0\n",
                  "[material.gear]\n"),
            ["material.gear.youngs_modulus_gpa", "required"]),
        # a tip relief without its start diameter
        "relief without start": (
            _edit(ev, tmp_path, "relief_no_start", "tip_relief_start_diameter_mm = 54.6\n", ""),
            ["modifications.pinion.tip_relief_start_diameter_mm", "required"]),
    }


@pytest.mark.parametrize("command", list(COMMANDS))
def test_bad_pair_files_exit_2_before_any_work(command, tmp_path, capsys):
    """Every bad file through every command: exit 2, the field, value and rule named on
    stderr, no traceback, no output directory."""
    for label, (path, words) in _bad_files(tmp_path).items():
        out = tmp_path / f"out_{label.replace(' ', '_')}"
        argv = [*COMMANDS[command], "--pair", str(path)]
        if command != "design":
            argv += ["--out", str(out)]
        assert main(argv) == 2, label
        err = capsys.readouterr().err
        assert "Traceback" not in err, label
        for word in words:
            assert word in err, (label, word, err)
        assert not out.exists(), label


@pytest.mark.parametrize("command", [c for c in COMMANDS if c != "design"])
def test_a_file_as_out_is_refused_and_left_alone(command, tmp_path, capsys):
    """--out naming an existing file (the pair itself, copied): exit 2 naming --out and
    the file, the file byte for byte as before."""
    target = tmp_path / "pair.toml"
    target.write_bytes(SPUR.read_bytes())
    argv = [*COMMANDS[command], "--pair", str(SPUR), "--out", str(target)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "pair.toml" in err and "existing file" in err
    assert target.read_bytes() == SPUR.read_bytes()


def test_design_refuses_out_for_a_cylindrical_pair(tmp_path, capsys):
    """design prints a cylindrical pair's geometry: --out is named as not taken."""
    assert main(["design", "--pair", str(SPUR), "--out", str(tmp_path / "d")]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "cylindrical" in err
    assert not (tmp_path / "d").exists()


def _files(root: Path) -> dict[str, bytes]:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*"))
            if p.is_file() and p.name != "run.json"}


def test_rerun_into_the_same_directory(tmp_path, capsys):
    """``gearcontact tca`` twice into one directory: the second run is accepted (the
    directory holds a run of the same command) and rewrites the same files; another
    command into it is refused naming --out and the command that wrote it."""
    out = tmp_path / "run"
    argv = ["tca", "--pair", str(SPUR), "--phases", "9", "--no-figures", "--out", str(out)]
    assert main(argv) == 0
    first = _files(out)
    assert first
    assert main(argv) == 0
    assert _files(out) == first
    capsys.readouterr()
    assert main(["lte", "--pair", str(SPUR), "--phases", "3", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "gearcontact tca" in err
    assert _files(out) == first


@pytest.mark.parametrize("spec, words", [
    ("modifications.pinion.lead_crowning_um=10:0:3", ["'10:0:3'", "STOP >= START"]),
    ("modifications.pinion.lead_crowning_um=0:10:0", ["STEPS = 0", "[1, 101]"]),
    ("modifications.pinion.lead_crowning_um=0:10", ["'0:10'", "three fields"]),
    # one value computed three times
    ("modifications.pinion.lead_crowning_um=5:5:3", ["'5:5:3'", "STEPS = 1 when STOP == START"]),
    ("modifications.pinion.lead_crowning_um=0:nan:3", ["STOP = nan", "finite"]),
    ("modifications.pinion.lead_crowning_um=0:300:3",
     ["modifications.pinion.lead_crowning_um = 300.0", "[0, 200]"]),
    ("modifications.pinion.helix_slope_um=-300:0:3",
     ["modifications.pinion.helix_slope_um = -300.0", "[-200, 200]"]),
    ("modifications.pinion.tip_relief_start_diameter_mm=50:70:3",
     ["tip_relief_start_diameter_mm = 50.0", "(56.6344, 66.0000) mm"]),
    ("cylindrical.helix_angle_deg=0:10:3", ["cylindrical.helix_angle_deg",
                                            "assembly.axis_deviation_um"]),
])
def test_sweep_over_a_modification_with_a_bad_range(spec, words, tmp_path, capsys):
    """``sweep --vary`` on a cylindrical pair's keys with a bad range: exit 2 naming the
    key, the value and the allowed range, before any cell runs (no output directory)."""
    pytest.importorskip("distributed")
    out = tmp_path / "sweep"
    assert main(["sweep", "--pair", str(SPUR), "--vary", spec, "--out", str(out),
                 "--quiet"]) == 2
    err = capsys.readouterr().err
    for word in words:
        assert word in err, (word, err)
    assert not out.exists()
