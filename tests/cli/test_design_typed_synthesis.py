"""``gearcontact design --machine-settings --local-synthesis`` on a pair file that types
its gear (issue 27; docs/machine_settings.md sec. 5): the pinion is synthesized against
the typed gear (tca.setting_synthesis with the typed gear's uncrowned pinion as base)
and the file written keeps the gear as typed.

Truths, declared before measuring: the typed gear is kept in the written file exactly
(==, the tables as read); for the blank's own gear typed (F.2's formate gear, a file
typing the gear alone) the synthesized pinion tables equal the untyped pair's within
1e-6 relative (the two bases agree to rounding, 1e-14, and M is the mean node in both:
the search follows the same path; 1e-6 leaves room for the least squares' steps only).
"""

import dataclasses
import tomllib
import warnings
from argparse import Namespace
from pathlib import Path

import pytest

from gearcontact.cli import main
from gearcontact.cli.design_options import kept_gear
from gearcontact.geometry.basic_settings import member_setups
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.pair import load_pair, pair_to_toml

from . import test_design_typed_pinion as typed_pinion

PRINT = typed_pinion.PRINT
#: the print's gear page alone (the fixture of tests/cli/test_design_typed_pinion.py)
page_alone = typed_pinion.page_alone

F2 = Path(__file__).resolve().parents[2] / "examples" / "iso23509_f2_spiral_bevel.toml"


def _gear_alone_file(tmp_path) -> Path:
    """F.2 with its blank's formate gear typed alone ([machine.gear.*], no pinion)."""
    pair = load_pair(F2)
    gear, _ = member_setups(pair, "formate")
    path = tmp_path / "f2_gear_alone.toml"
    path.write_text(pair_to_toml(dataclasses.replace(
        pair, typed_gear=tuple(gear[s] for s in SIDES))))
    return path


def test_a_kept_gear_with_local_synthesis_is_taken(tmp_path):
    # the refusal is lifted: kept_gear returns the typed gear (the synthesis' gear)
    path = _gear_alone_file(tmp_path)
    pair = load_pair(path, gear_alone=True)
    args = Namespace(pair=str(path), machine_settings=True, keep_gear=False,
                     local_synthesis=True, target_flank=None)
    assert kept_gear(args, pair) == {s.side: s for s in pair.typed_gear}


@pytest.mark.slow
def test_the_blank_gear_typed_alone_synthesizes_the_untyped_pinion(tmp_path):
    # ~3 min: two syntheses of F.2 (typed gear file, the built-in pair file)
    path = _gear_alone_file(tmp_path)
    typed, plain = tmp_path / "typed", tmp_path / "plain"
    assert main(["design", "--pair", str(path), "--machine-settings", "--local-synthesis",
                 "--out", str(typed)]) == 0
    assert main(["design", "--pair", str(F2), "--machine-settings", "--local-synthesis",
                 "--out", str(plain)]) == 0
    written = (typed / "machine_settings.toml").read_text()
    assert "gear: typed ([machine.gear.*] / [blade.gear.*], kept as typed), formate" in written
    a, b = (tomllib.loads((d / "machine_settings.toml").read_text()) for d in (typed, plain))
    source = tomllib.loads(path.read_text())
    assert a["machine"]["gear"] == source["machine"]["gear"]
    assert a["blade"]["gear"] == source["blade"]["gear"]
    for table in ("machine", "blade"):
        for side in SIDES:
            got, want = a[table]["pinion"][side], b[table]["pinion"][side]
            assert set(got) == set(want)
            for key, value in want.items():
                if isinstance(value, float):
                    assert got[key] == pytest.approx(value, rel=1e-6, abs=1e-9), (side, key)
                else:
                    assert got[key] == value, (side, key)


@pytest.mark.slow
def test_the_print_page_keeps_its_gear_and_writes_a_pinion(page_alone, tmp_path):
    # ~40 s. The file written keeps [print.gear] verbatim and types the pinion alone; a
    # side the synthesis cannot pivot (no point of its path inside the flank, exit 4;
    # the drive side, whose path misses the mean section, now pivots off it:
    # tests/tca/test_setting_synthesis_typed.py) gets the standard pinion, the tables of
    # `design --machine-settings` on the same page (==, the same code)
    out, std = tmp_path / "out", tmp_path / "std"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's blank note
        code = main(["design", "--pair", str(page_alone), "--machine-settings",
                     "--local-synthesis", "--out", str(out)])
        assert main(["design", "--pair", str(page_alone), "--machine-settings",
                     "--out", str(std)]) == 0
    assert code in (0, 4)
    text = (out / "machine_settings.toml").read_text()
    doc, plain = tomllib.loads(text), tomllib.loads((std / "machine_settings.toml").read_text())
    assert doc["print"]["gear"] == tomllib.loads(PRINT.read_text())["print"]["gear"]
    assert set(doc["machine"]) == set(doc["blade"]) == {"pinion"}
    assert "gear: typed ([print.gear], kept as typed), generated" in text
    for side in SIDES:
        if f"{side}: not synthesized" in text:
            assert code == 4
            assert doc["machine"]["pinion"][side] == plain["machine"]["pinion"][side]
            assert doc["blade"]["pinion"][side] == plain["blade"]["pinion"][side]
