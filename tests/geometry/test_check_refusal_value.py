"""A refusal of the typed-settings check names a key, the value typed and the allowed
range, never ``None`` (geometry.blank_check; docs/machine_settings.md sec. 5, "Ordinary
pairs, measured": a flank explained by more than one key, or by none, was refused as
``[machine.pinion.drive] = None``)."""

from __future__ import annotations

import re

import pytest

from gearcontact.cli import main

from .f2_variants import retyped


def test_two_keys_refusal_names_the_first_key_typed_and_its_range(tmp_path, capsys):
    """F.2's pinion drive machine root angle typed -10 (for 0): the pressure angle (33.4
    deg) and root depth are far off, and the machine root angle or the tilt alone would
    make the flank agree. Exit 2 naming ``machine_root_angle_deg = -10.0`` and the
    interval of values at which the flank agrees. Truth: the shipped example, typed 0,
    agrees with its blank (test_basic_settings.py), so 0 lies in the interval and -10
    outside it (no tolerance: an inclusion; the interval's ends are the bracketing roots
    of the excess, 1e-3 of the narrowest band). ~6 s."""
    path = retyped(tmp_path, "machine.pinion.drive", {"machine_root_angle_deg": "-10.0"})
    assert main(["design", "--pair", str(path)]) == 2
    err = capsys.readouterr().err
    assert "= None" not in err
    got = re.search(r"machine\.pinion\.drive\.machine_root_angle_deg = -10\.0 is outside the "
                    r"allowed range: \[(-?[0-9.]+), (-?[0-9.]+)\] \(this key alone moved\)", err)
    assert got, err
    low, high = float(got.group(1)), float(got.group(2))
    assert low <= 0.0 <= high and not low <= -10.0 <= high
    assert "machine.pinion.drive.tilt_deg typed 19.7468" in err


@pytest.mark.slow
def test_no_key_refusal_names_the_typed_table(tmp_path, capsys):
    """F.2's pinion drive blade with a cubic profile term 1 /mm^2 (its limit, for 0):
    pressure angle 6.86 deg against 20, root depth 1.03 mm against 2.39; no known slip
    and no key alone explains it (the pressure angle is not monotonic in the cubic term:
    19.37 deg at 0.1, 21.82 at 0.3, 1.84 at 0.5). Exit 2 naming the table and its typed
    values, the cubic term among them as typed. ~17 s (the two-slip search runs)."""
    path = retyped(tmp_path, "blade.pinion.drive", {"profile_cubic_per_mm2": "1.0"})
    assert main(["design", "--pair", str(path)]) == 2
    err = capsys.readouterr().err
    assert "= None" not in err
    assert "[machine.pinion.drive] = {" in err
    assert "'blade.pinion.drive.profile_cubic_per_mm2': 1.0" in err
    assert "'machine.pinion.drive.tilt_deg': 19.7468" in err
    assert "pressure angle 6.8640 deg, the blank's 20.0000 (tolerance" in err
