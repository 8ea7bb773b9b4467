"""A setting typed at the top of its range passes the typed-settings check
(geometry.blank_check; docs/machine_settings.md sec. 5, "Ordinary pairs, measured": a
120F of 100.0, inside its documented range [-100, 100], was refused as
``modified_roll_120f_per_rad4 = 100.05``, a value nobody typed: the check's rounding
propagation moved the key up by its half unit, out of the range)."""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcontact.cli import main

EXAMPLE = Path(__file__).parents[2] / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


@pytest.mark.parametrize("value", ["100.0", "-100.0"])
def test_a_value_at_its_range_limit_is_checked_not_refused(tmp_path, capsys, value):
    """F.2's pinion drive with 120F typed at either limit of [-100, 100] (its effect at
    the mean roll is small: the flank agrees): ``design`` exits 0 and names no range
    error; the bottom limit passed before as well (the half unit moved it inwards)."""
    text = EXAMPLE.read_text()
    head, rest = text.split("[machine.pinion.drive]\n", 1)
    rest = rest.replace("tilt_deg = 19.7468",
                        f"tilt_deg = 19.7468\nmodified_roll_120f_per_rad4 = {value}", 1)
    path = tmp_path / "pair.toml"
    path.write_text(f"{head}[machine.pinion.drive]\n{rest}")
    assert main(["design", "--pair", str(path)]) == 0
    assert "outside the allowed range" not in capsys.readouterr().err
