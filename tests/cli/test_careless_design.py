"""`gearcontact design`'s writers run as a careless user runs them (session 27, helper
writer), through the console script; each test was a defect found by trying the
command, the message it gave before in its docstring.

Truth: the developers' guide (bad input: one error line naming the option the user
typed, its value and the allowed range, before any flank work, exit 2; never a key the
user did not type) and the blade model (docs/machine_settings.md sec. 5, "The blade
curvature written").
"""

from pathlib import Path

import pytest
from console_script import run_console

ROOT = Path(__file__).resolve().parents[2]
F2 = ROOT / "examples" / "iso23509_f2_spiral_bevel.toml"


@pytest.mark.parametrize("option", ["--blade-profile-crowning-um", "--lengthwise-crowning-um"])
def test_a_crowning_below_the_flanks_accuracy_is_named_by_its_option(option):
    """Before: `--blade-profile-crowning-um 1e-310` (a subnormal: its blade radius
    (h_mw/2)^2 / 2c overflows) was refused naming `blade.profile_radius_mm = inf`, a key
    the user never typed, after the standard settings were built; the lengthwise one
    was taken as 0 without a word. A crowning in (0, 1e-6) um is below the flanks' own
    accuracy (their interpolation, ~1e-9 mm = 1e-6 um); type 0 for none."""
    code, out, err = run_console("design", "--pair", F2, "--machine-settings", option,
                                 "1e-310")
    assert code == 2, err
    line = err.strip().splitlines()[-1]
    assert line.startswith(f"gearcontact design: error: {option} (um) = 1e-310"), line
    assert "0 (no crowning)" in line and "blade.profile_radius_mm" not in line
    assert out == ""


def test_a_crowning_that_points_the_pinion_is_named_by_its_options():
    """Before: `--lengthwise-crowning-um 200 --blade-profile-crowning-um 200` (the
    range's end) on F.2 was refused naming `[machine.pinion.drive] /
    [machine.pinion.coast] (blade point radii 141.2 / 83.94 mm)`, derived tables the user
    never typed (the pinion check's verdict: a pointed tooth at the heel). Now the
    options typed are named with their values (which one pointed the tooth is not known:
    200 lengthwise alone does not), the check's verdict kept in the message, exit 2."""
    code, out, err = run_console("design", "--pair", F2, "--machine-settings",
                                 "--lengthwise-crowning-um", "200",
                                 "--blade-profile-crowning-um", "200")
    assert code == 2, err
    line = err.strip().splitlines()[-1]
    assert line.startswith("gearcontact design: error: --lengthwise-crowning-um / "
                           "--blade-profile-crowning-um (um) = (200.0, 200.0)"), line
    assert "pointed pinion tooth" in line and "[machine.pinion.drive]" in line
    assert out == ""
