"""The machine-settings workflow (`design --machine-settings`, its options, and the
commands on the files it writes) run as a careless user runs it, through the console
script: a misread print word, a length in the wrong unit, a typed gear that does not cut
its blank. Each test was a defect found by trying the command (session 26, helper
careless): the message it gave before is in the test's docstring.

Truth: the developers' guide (bad input: one error line naming the field, the value and
the allowed range, before any expensive work, exit 2; never an internal error) and
docs/machine_settings.md sec. 2 (a sign word read wrong is named by the typed-settings
check, "The check when a pair is loaded"; the published page's own readings).
"""

from pathlib import Path

import pytest
from console_script import run_console

ROOT = Path(__file__).resolve().parents[2]
PRINT_GEAR = ROOT / "examples" / "machine_settings" / "hypoid_10x41_print_gear.toml"


def _error_line(err: str) -> str:
    """The last stderr line, asserted to be an input error (not an internal one)."""
    assert "Traceback" not in err and "internal error" not in err, err
    return err.strip().splitlines()[-1]


def _misread(tmp_path, old: str, new: str) -> Path:
    """The published print's gear page with one printed line typed ``new``."""
    text = PRINT_GEAR.read_text()
    assert text.count(old) == 1, old
    path = tmp_path / "misread.toml"
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize("old, new, key", [
    # before: exit 1, "internal error, please report (ValueError: f(a) and f(b) must have
    # different signs)" from the standard pinion's blade (the gear never checked)
    ('blank_offset = "DN 0.225"', 'blank_offset = "UP 0.225"', "print.gear.blank_offset"),
    # before: exit 2 naming "blade.profile_reference_mm = -2.6165..." (a derived pinion
    # blade's key the user never typed)
    ('sliding_base = "WITH 0.070"', 'sliding_base = "AWAY 0.070"', "print.gear.sliding_base"),
    # before: exit 2 naming "gear coast flank at (u, v) = ... 'residual 6.005e-01'"
    ('machine_centre_to_back = "MD -0.240"', 'machine_centre_to_back = "MD +0.240"',
     "print.gear.machine_centre_to_back"),
])
def test_a_misread_word_of_a_typed_gear_is_named(tmp_path, old, new, key):
    """The gear page typed alone, one sign word read wrong (sec. 2's table: UP moves the
    printed spiral angle 10.7 deg, AWAY the root 3.6 mm, MD + 11.4 mm): the typed gear is
    checked against its print before its standard pinion is derived, and the word is named
    (its value as typed), exit 2."""
    code, _, err = run_console("design", "--pair", _misread(tmp_path, old, new),
                               "--machine-settings")
    line = _error_line(err)
    assert code == 2, err
    assert line.startswith("gearcontact design: error: ")
    assert f"{key} = '{new.split(' = ')[1][1:-1]}'" in line, line
    assert "docs/machine_settings.md" in line

