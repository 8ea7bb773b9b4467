"""``gearcontact design --machine-settings`` on a pair file that types its gear (issue 27:
the standard pinion of a typed gear, geometry.typed_pinion; docs/machine_settings.md
sec. 5): the published 10 x 41 print's page alone ([print.gear], no pinion tables), and
the shipped pair file typing both members (the rule: the blank's standard settings of
both members unless --keep-gear)."""

import json
import tomllib
import warnings
from pathlib import Path

import pytest

from gearcontact.cli import main
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.typed_pinion import typed_gear_machine_pair

PRINT = Path("tests/geometry/summary_sheets/hypoid_10x41_no16_pair.toml")


@pytest.fixture()
def page_alone(tmp_path):
    """The shipped pair file without its pinion tables: the print's gear page alone."""
    text = PRINT.read_text()
    path = tmp_path / "print_page.toml"
    path.write_text(text[:text.index("[machine.pinion.drive]")])
    return path


def _quiet_load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's blank note
        return load_pair(path)


def _tables(path) -> dict:
    with open(path, "rb") as f:
        return tomllib.load(f)


def test_the_page_alone_is_refused_by_tca_naming_the_pinion_tables(page_alone, tmp_path,
                                                                   capsys):
    assert main(["tca", "--pair", str(page_alone), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "[machine.pinion.drive]" in err and "design --machine-settings" in err


def test_design_derives_the_pinion_of_the_page_and_tca_runs(page_alone, tmp_path, capsys):
    # the written file: [print.gear] exactly as typed; its pinion the library's
    # (typed_gear_machine_pair on the shipped file's gear, floats at full precision: ==);
    # uncrowned (both crowning options 0), `gearcontact tca` on it (31 phases, 120 x 150
    # nodes) finds TE0 = 0 within 1e-4 arcsec on both sides (the conjugacy tolerance of
    # test_typed_pinion.py; measured 2.6e-10 / 2.9e-10 arcsec) and no MateWarning
    out = tmp_path / "out"
    assert main(["design", "--pair", str(page_alone), "--machine-settings",
                 "--lengthwise-crowning-um", "0", "--blade-profile-crowning-um", "0",
                 "--out", str(out)]) == 0
    written = out / "machine_settings.toml"
    doc = _tables(written)
    assert doc["print"]["gear"] == _tables(PRINT)["print"]["gear"]
    assert set(doc["machine"]) == {"pinion"}
    assert "gear: typed, generated" in written.read_text()
    shipped = _quiet_load(PRINT)
    want = typed_gear_machine_pair(shipped, {s.side: s for s in shipped.machine
                                             if s.member == "gear"},
                                   lengthwise_crowning_um=0.0, blade_profile_crowning_um=0.0)
    assert _quiet_load(written).machine == want.machine
    capsys.readouterr()
    for side in ("drive", "coast"):
        run = tmp_path / f"tca_{side}"
        assert main(["tca", "--pair", str(written), "--out", str(run), "--side", side,
                     "--phases", "31", "--no-figures"]) == 0
        assert "not mates" not in capsys.readouterr().err
        got = json.loads((run / "tca.json").read_text())
        assert got["te0_pp_arcsec"] < 1e-4
        assert not got["edge_contact_phases"]


def test_both_members_typed_the_rule(tmp_path, page_alone):
    # without --keep-gear the blank's standard settings replace both members (today's
    # rule, kept: the gear is the blank's formate gear, ratio of roll 0); with it the
    # typed gear is kept and the pinion tables are those the page alone gets (==)
    plain, kept, alone = (tmp_path / d for d in ("plain", "kept", "alone"))
    assert main(["design", "--pair", str(PRINT), "--machine-settings", "--out",
                 str(plain)]) == 0
    doc = _tables(plain / "machine_settings.toml")
    assert "print" not in doc and doc["machine"]["gear"]["drive"]["ratio_of_roll"] == 0.0
    assert main(["design", "--pair", str(PRINT), "--machine-settings", "--keep-gear",
                 "--out", str(kept)]) == 0
    assert main(["design", "--pair", str(page_alone), "--machine-settings", "--out",
                 str(alone)]) == 0
    a, b = (_tables(d / "machine_settings.toml") for d in (kept, alone))
    assert a["print"]["gear"] == b["print"]["gear"] == _tables(PRINT)["print"]["gear"]
    assert a["machine"] == b["machine"] and a["blade"] == b["blade"]


@pytest.mark.parametrize("argv, field", [
    (["--pair", str(PRINT), "--keep-gear"], "--keep-gear"),
    (["--pair", "s0003", "--machine-settings", "--keep-gear"], "--keep-gear")])
def test_contradictions_are_refused_naming_the_option(argv, field, capsys):
    assert main(["design", *argv]) == 2
    err = capsys.readouterr().err
    assert f"error: {field} = " in err


def test_a_kept_gear_with_a_target_flank_is_refused(page_alone):
    # the check itself (a target file is read by the option checks before it: a real
    # measured file is not needed to reach this refusal)
    from argparse import Namespace

    from gearcontact.cli.design_options import kept_gear
    from gearcontact.validation import InputRangeError

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's blank note
        pair = load_pair(page_alone, gear_alone=True)
    assert {s.side for s in pair.typed_gear} == {"drive", "coast"} and not pair.machine
    args = Namespace(pair=str(page_alone), machine_settings=True, keep_gear=False,
                     local_synthesis=False, target_flank="measured.csv")
    with pytest.raises(InputRangeError) as got:
        kept_gear(args, pair)
    assert got.value.field == "--target-flank"
    assert set(kept_gear(Namespace(**{**vars(args), "target_flank": None}), pair)) == {
        "drive", "coast"}
