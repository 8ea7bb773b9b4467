"""`gearcontact design --machine-settings` asked for uncrowned settings (both crowning
options 0), through the console script (docs/machine_settings.md sec. 4, "Uncrowned
settings").

Truth: a pinion cut by the generating surface complementary to the gear's, exact ratio
of roll, no crowning, is conjugate to the gear (Litvin & Fuentes 2004, sec. 9.3), so the
TCA finds line contact (B- at its reference point below LINE_CURVATURE_PER_MM, the
bound the loaded commands refuse on; tests/tca/test_line_contact.py measured 5.2e-13
1/mm on this pair) and the loaded commands refuse the written file. `design` writes the
settings as asked (exit 0: a conjugate pair is a valid request and line contact is a
result) and says so on stderr, in the file's head comment and in run.json, with the
refusal's own advice (`tca.line_contact.CROWNING_ADVICE`). The crowned default pays no
check and says nothing.
"""

import json
from pathlib import Path

import pytest
from console_script import run_console

from gearcontact.tca.line_contact import CROWNING_ADVICE, LINE_CURVATURE_PER_MM

ROOT = Path(__file__).resolve().parents[2]
F2 = ROOT / "examples" / "iso23509_f2_spiral_bevel.toml"


@pytest.mark.slow
def test_uncrowned_settings_are_written_with_their_line_contact_named(tmp_path):
    # ~1 min at load 16: design, one flank build and a 61-phase TCA per side
    out = tmp_path / "uncrowned"
    code, stdout, err = run_console("design", "--pair", F2, "--machine-settings",
                                    "--lengthwise-crowning-um", "0",
                                    "--blade-profile-crowning-um", "0", "--out", out)
    assert code == 0, err
    assert "Traceback" not in err
    text = (out / "machine_settings.toml").read_text()
    manifest = json.loads((out / "run.json").read_text())
    for side in ("drive", "coast"):
        # stderr: the loaded commands' refusal itself, side and advice named
        assert f"line contact on the {side} side" in err, err
        # the head comment: uncrowned, its side, the advice (no noise-level number:
        # identical runs on other CPUs write identical files)
        assert f"{side}: uncrowned" in text
        found = manifest["line_contact"][side]
        assert abs(found["b_minus_per_mm"]) <= LINE_CURVATURE_PER_MM
        assert CROWNING_ADVICE in found["message"]
    assert CROWNING_ADVICE in err and CROWNING_ADVICE in text.replace("\n# ", " ")
    assert "warning" in err


def test_crowned_settings_say_nothing_of_line_contact(tmp_path):
    out = tmp_path / "crowned"
    code, _, err = run_console("design", "--pair", F2, "--machine-settings", "--out", out)
    assert code == 0, err
    assert "line contact" not in err
    assert "uncrowned" not in (out / "machine_settings.toml").read_text()
    assert "line_contact" not in json.loads((out / "run.json").read_text())


@pytest.mark.slow
def test_a_side_fitted_to_a_zero_grid_is_named_uncrowned(tmp_path):
    """`--target-flank` with a measured grid of zero deviations on the drive side (the
    pair has no ease-off: the coast is fitted to zero too): the fit is the conjugate
    pinion's settings on both sides (ease-off max 0), so both are checked and named.
    Before: an internal error (EdgeContact) in the check's TCA on the coast side, the
    start of the cycle at the pinion's toe edge; `tca.line_contact` now also tries the
    line at the start's phase through the gear face's sections. ~6 min at load 18."""
    import numpy as np

    rows = ["side,v_mm,u_mm,easeoff_um"]
    # covers F.2's active drive flank (u 1.215..7.682, v 64.541..88.447 mm)
    rows += [f"drive,{float(v)!r},{float(u)!r},0.0" for u in np.linspace(1.0, 8.0, 6)
             for v in np.linspace(64.0, 89.0, 9)]
    grid = tmp_path / "zero.csv"
    grid.write_text("\n".join(rows) + "\n")
    out = tmp_path / "zero"
    code, _, err = run_console("design", "--pair", F2, "--machine-settings", "--target-flank",
                               grid, "--out", out, timeout=1800.0)
    assert code == 0, err
    text = (out / "machine_settings.toml").read_text()
    manifest = json.loads((out / "run.json").read_text())
    for side in ("drive", "coast"):
        assert f"line contact on the {side} side" in err, err
        assert f"{side}: uncrowned" in text
        assert abs(manifest["line_contact"][side]["b_minus_per_mm"]) <= LINE_CURVATURE_PER_MM
