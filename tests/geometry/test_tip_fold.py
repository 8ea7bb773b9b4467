"""``design --machine-settings`` and ``tca`` agree on a blank whose standard settings cut a
pinion flank that folds above its tip (geometry.generated_box.check_tip_margin;
docs/machine_settings.md sec. 5, "A fold at the tip").

The truth is the workflow's own contract, not a number of this code: every command
reads what ``design`` writes. Before, on the 16/16 spiral bevel at face 4 mm and beta 35
deg, ``design --machine-settings`` warned (contact ratio) and wrote settings on which
``tca`` exited 2 at a node of the pinion's coast flank (the node grid's corner above
the tip at the heel, where the envelope folds). Now ``design`` refuses before writing,
with the message ``tca`` gives on those settings, word for word; with less lengthwise
crowning (the pinion coast cutter radius 16.8 -> 43.8 mm) both run.
"""

from __future__ import annotations

import warnings

import pytest

from gearcontact.cli import main
from gearcontact.geometry import basic_settings, generated_box
from gearcontact.geometry.conjugate import UndercutError
from gearcontact.geometry.gear_generation import generation_of
from gearcontact.geometry.generated import generated_pinion_box, generated_pinion_flank
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.pair import load_pair, pair_to_toml

# 16/16 spiral bevel, E 0, R_m 55 mm, beta 35 deg, cutter 57.15 mm (helper crcheck's family,
# docs/machine_settings.md sec. 5), here at face 4 mm (0.07 R_e)
from .test_machine_contact_ratio import _blank

FACE_MM = 4.0

def _error_line(err: str, command: str) -> str:
    """The error of ``gearcontact <command>`` on stderr, without its prefix."""
    prefix = f"gearcontact {command}: error: "
    lines = [line for line in err.splitlines() if line.startswith(prefix)]
    assert len(lines) == 1, err
    return lines[0][len(prefix):]


def _old_settings(blank_file):
    """The standard settings design wrote before for ``blank_file`` (the pinion box
    and top-land checks skipped: ``check_settings_top_land`` makes the boxes; they change
    no setting)."""
    blank = load_pair(blank_file)
    with pytest.MonkeyPatch.context() as patch, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        patch.setattr(basic_settings, "check_settings_top_land", lambda *a, **k: None)
        generation = generation_of(check_generation(blank, contact_ratio=False))
        return basic_settings.standard_machine_pair(blank, gear_generation=generation)


def test_design_refuses_what_tca_refuses(tmp_path, capsys):
    blank_file = _blank(tmp_path, FACE_MM)
    out = tmp_path / "mach"
    assert main(["design", "--pair", str(blank_file), "--machine-settings",
                 "--out", str(out)]) == 2
    design_error = _error_line(capsys.readouterr().err, "design")
    assert not (out / "machine_settings.toml").exists()
    # the cause, named: the flank's settings, where it folds, the design fields that fix it
    for word in ("[machine.pinion.coast] / [blade.pinion.coast]", "(heel: the box is",
                 "design.gear_face_width_mm", "design.pinion_spiral_angle_deg",
                 "--lengthwise-crowning-um", '"A fold at the tip"'):
        assert word in design_error
    written = tmp_path / "machine_settings.toml"
    written.write_text(pair_to_toml(_old_settings(blank_file)))
    assert main(["tca", "--pair", str(written), "--out", str(tmp_path / "tca")]) == 2
    assert _error_line(capsys.readouterr().err, "tca") == design_error


def test_the_tip_check_refuses_what_the_node_grid_cannot_solve(tmp_path, monkeypatch):
    """The truth of the early refusal is the node grid itself (the exact node solves
    behind the flank): the coast flank the check refuses has a grid node without a
    solution once the check is skipped; the drive flank it passes builds. A 12 x 15 grid
    holds the corners of the full one (linspace ends), where the fold is."""
    cut = _old_settings(_blank(tmp_path, FACE_MM))
    setups = {s.side: s for s in cut.machine if s.member == "pinion"}
    face = cut.pinion_face_width_mm
    with pytest.raises(UndercutError, match="fold of the generated pinion coast flank"):
        generated_pinion_box(setups["coast"], cut.blank, pinion_face_width_mm=face)
    monkeypatch.setattr(generated_box, "check_tip_margin", lambda *a, **k: None)
    box = generated_pinion_box(setups["coast"], cut.blank, pinion_face_width_mm=face)[1]
    with pytest.raises(UndercutError, match="a node the generated envelope reaches"):
        generated_pinion_flank(setups["coast"], cut.blank, pinion_face_width_mm=face,
                               n_u=12, n_v=15, box=box)
    monkeypatch.undo()
    generated_pinion_flank(setups["drive"], cut.blank, pinion_face_width_mm=face,
                           n_u=12, n_v=15)


@pytest.mark.slow
def test_less_crowning_runs_in_both(tmp_path, capsys):
    """The fix the refusal names, measured: 10 um of lengthwise crowning (pinion coast
    cutter radius 43.8 mm instead of 16.8 mm): design exit 0, and tca on its file exit 0."""
    blank_file = _blank(tmp_path, FACE_MM)
    out = tmp_path / "mach"
    assert main(["design", "--pair", str(blank_file), "--machine-settings",
                 "--lengthwise-crowning-um", "10", "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["tca", "--pair", str(out / "machine_settings.toml"),
                 "--out", str(tmp_path / "tca")]) == 0


def test_keep_gear_refuses_the_folding_pinion_before_writing(tmp_path, capsys):
    """``design --machine-settings --keep-gear`` on those settings keeps the (blank's own)
    gear and derives its standard pinion (geometry.typed_pinion; the same pinion as the
    standard settings' to round-off): the same fold, refused before any file is written,
    naming the pinion flank's settings and the fold."""
    blank_file = _blank(tmp_path, FACE_MM)
    written = tmp_path / "machine_settings.toml"
    written.write_text(pair_to_toml(_old_settings(blank_file)))
    out = tmp_path / "kept"
    assert main(["design", "--pair", str(written), "--machine-settings", "--keep-gear",
                 "--out", str(out)]) == 2
    error = _error_line(capsys.readouterr().err, "design")
    assert not (out / "machine_settings.toml").exists()
    for word in ("[machine.pinion.coast] / [blade.pinion.coast]", "(heel: the box is",
                 '"A fold at the tip"'):
        assert word in error
