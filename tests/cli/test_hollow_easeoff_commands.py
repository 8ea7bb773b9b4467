"""The hollow ease-off warning on the command line (docs/machine_settings.md sec. 2, "The
hollow ease-off warning"): `tca` warns on stderr and records the shapes in run.json,
`design` prints its line and its JSON entry.

Truth: s0003 cut by `design --machine-settings` (geometry.easeoff_settings) with its
coast pinion's fitted 2C typed with the wrong sign (made here: the flip is the truth),
the coast pinion hollow lengthwise (its values tested in
tests/geometry/test_easeoff_shape.py); the file as written warns nothing.
"""

from __future__ import annotations

import dataclasses
import json

import pytest

from gearcontact.cli import main
from gearcontact.geometry.pair import load_pair, pair_to_toml

TCA = ("--phases", "3", "--no-figures", "--quiet")


@pytest.fixture(scope="module")
def s0003_files(tmp_path_factory):
    """``(as written, coast 2C flipped)``: the TOML files of s0003 cut by design's
    ease-off fit (~5 s)."""
    from gearcontact.geometry.easeoff_settings import easeoff_machine_pair

    pair = easeoff_machine_pair(load_pair("s0003")).pair
    flipped = dataclasses.replace(pair, machine=tuple(
        dataclasses.replace(s, settings=dataclasses.replace(
            s.settings, modified_roll=(-s.settings.modified_roll[0],
                                       *s.settings.modified_roll[1:])))
        if (s.member, s.side) == ("pinion", "coast") else s for s in pair.machine))
    out = tmp_path_factory.mktemp("s0003")
    paths = out / "s0003_machine.toml", out / "s0003_flipped.toml"
    for path, p in zip(paths, (pair, flipped)):
        path.write_text(pair_to_toml(p))
    return paths


def test_tca_warns_a_hollow_pinion_and_records_it(tmp_path, s0003_files, capsys):
    code = main(["tca", "--pair", str(s0003_files[1]), "--out", str(tmp_path / "t"),
                 "--side", "coast", *TCA])
    err = capsys.readouterr().err
    assert code == 0, err
    hollow = [line for line in err.splitlines() if "is hollow against the conjugate" in line]
    assert len(hollow) == 1 and "[machine.pinion.coast]" in hollow[0]
    got = json.loads((tmp_path / "t" / "run.json").read_text())
    assert got["blank_check"]["agrees"] is True          # a different check
    shape = got["easeoff_shape"]
    assert shape["flanks"]["coast"]["flagged"] is True
    assert shape["flanks"]["drive"]["flagged"] is False
    assert shape["warnings"] == hollow and shape["missing"] == {}
    assert got["timings_s"]["easeoff_shape_s"] > 0.0


def test_design_prints_the_shapes(s0003_files, capsys):
    for path, flagged in zip(s0003_files, (False, True)):
        assert main(["design", "--pair", str(path)]) == 0
        out, err = capsys.readouterr()
        line = [x for x in out.splitlines() if x.startswith("pinion ease-off against")]
        assert len(line) == 1
        assert ("HOLLOW" in line[0]) == flagged and ("none hollow" in line[0]) != flagged
        assert ("is hollow against the conjugate" in err) == flagged
        assert main(["design", "--pair", str(path), "--json"]) == 0
        shape = json.loads(capsys.readouterr().out)["easeoff_shape"]
        assert shape["flanks"]["coast"]["flagged"] is flagged
