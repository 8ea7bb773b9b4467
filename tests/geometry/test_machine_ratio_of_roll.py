"""A typed ratio of roll of the wrong sign, or a pinion typed formate, is refused on load
naming the key, the value and the allowed range (geometry.machine.setup_from_tables;
docs/machine_settings.md sec. 5, "Ordinary pairs, measured": before, ``design`` warned
"no known sign or unit slip explains it" and, 20-90 s later, refused a node of the
envelope naming only the tables, never the ratio of roll)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from gearcontact.cli import main

EXAMPLE = Path(__file__).parents[2] / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def _with(table: str, line: str) -> str:
    text = EXAMPLE.read_text()
    head, rest = text.split(f"[{table}]\n", 1)
    body, tail = rest.split("\n[", 1)
    body = re.sub(r"^ratio_of_roll = .*$", line, body, flags=re.M)
    return f"{head}[{table}]\n{body}\n[{tail}"


@pytest.mark.parametrize("table, value, allowed", [
    ("machine.pinion.drive", "-2.785714", "> 0: the pinion is generated"),
    ("machine.pinion.coast", "0.0", "> 0: the pinion is generated"),
    ("machine.gear.drive", "-0.5", ">= 0: work / cradle rotation")])
def test_ratio_of_roll_sign_is_refused_on_load(tmp_path, capsys, table, value, allowed):
    """Exit 2 with the dotted key, the value and the range in one line on stderr; the
    refusal comes from loading, so no flank is cut (a few s for the CLI's imports)."""
    path = tmp_path / "pair.toml"
    path.write_text(_with(table, f"ratio_of_roll = {value}"))
    assert main(["design", "--pair", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{table}.ratio_of_roll = {float(value)}" in err
    assert allowed in err
    assert "warning" not in err            # refused before the typed-settings check


def test_the_example_as_typed_still_loads(tmp_path):
    """The shipped F.2 settings (gear formate 0, pinion 2.785714) pass unchanged."""
    path = tmp_path / "pair.toml"
    path.write_text(_with("machine.pinion.drive", "ratio_of_roll = 2.785714"))
    assert main(["design", "--pair", str(path)]) == 0
