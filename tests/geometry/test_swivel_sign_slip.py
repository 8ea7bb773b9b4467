"""A swivel typed with the wrong sign is named as a known slip (geometry.known_slips;
docs/machine_settings.md sec. 5, "Ordinary pairs, measured": before, ``design`` refused
``[machine.pinion.drive] = None``, "no single typed key alone makes it agree", after the
two-key search, 106 s on a loaded machine)."""

from __future__ import annotations

import re
from pathlib import Path

from gearcontact.cli import main

EXAMPLE = Path(__file__).parents[2] / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def test_pinion_swivel_sign_is_named(tmp_path, capsys):
    """F.2's pinion drive swivel -82.0712 typed +82.0712 (the cradle angle's sign kept, so
    not the other hand): exit 2 naming the key, the typed value and the other sign. The
    truth is the shipped example, which agrees with its blank with -82.0712 (loaded
    without a warning in test_basic_settings.py); the flip back is exact."""
    text = EXAMPLE.read_text()
    head, rest = text.split("[machine.pinion.drive]\n", 1)
    body, tail = rest.split("\n[", 1)
    assert "swivel_deg = -82.0712" in body
    body = body.replace("swivel_deg = -82.0712", "swivel_deg = 82.0712")
    path = tmp_path / "pair.toml"
    path.write_text(f"{head}[machine.pinion.drive]\n{body}\n[{tail}")
    assert main(["design", "--pair", str(path)]) == 2
    err = capsys.readouterr().err
    assert "machine.pinion.drive.swivel_deg = 82.0712" in err
    assert re.search(r"with the other swivel sign the flank agrees", err)
