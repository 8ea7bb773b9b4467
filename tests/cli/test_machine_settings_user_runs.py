"""`design --machine-settings` on an ordinary hypoid's blank, then `tca` on the file it
writes, through the console script as a user runs them (docs/machine_settings.md sec. 5,
"Ordinary hypoids, as a user runs them").

The published 10 x 41 hypoid print's blank (tests/geometry/summary_sheets/README.md) was
refused by `tca` on the written file (a node of the grid's margin beyond a fold of the
envelope, exit 2). Truths: the written pair runs and its reference contact P0 is the
blank's mean point on both members (the standard pinion keeps the conjugate pinion's
mean node; `tca.json` mating point = the pinion's mean point posed, 1e-6 mm), with no
mate warning; the print's shipped file (the print's gear with the blank's pinion) is
named as no pair of mates, side by side.
"""

import json
from pathlib import Path

import pytest
from console_script import run_console

from gearcontact.geometry.pair import load_pair

PRINT = Path(__file__).resolve().parents[1] / "geometry" / "summary_sheets" / \
    "hypoid_10x41_no16_pair.toml"


@pytest.mark.slow
def test_standard_settings_of_the_print_blank_run(tmp_path):
    text = PRINT.read_text()
    blank = tmp_path / "no16_blank.toml"        # the blank alone, as a user types it
    blank.write_text(text[:text.index('# "NO. 16 GEAR MACHINE')])
    rc, out, err = run_console("design", "--pair", blank, "--machine-settings",
                               "--out", tmp_path / "ms")
    assert rc == 0, err
    written = tmp_path / "ms" / "machine_settings.toml"
    mean_x = float(load_pair(blank).blank.pitch_point_mm[0])
    for side in ("drive", "coast"):
        rc, out, err = run_console("tca", "--pair", written, "--side", side, "--out",
                                   tmp_path / side, "--no-figures", "--quiet")
        assert rc == 0, err
        assert "MateWarning" not in err
        got = json.loads((tmp_path / side / "tca.json").read_text())
        assert got["mean_point_contact"] == "surface"
        # P0 at the blank's mean point: the pinion's mean node posed at its phase is the
        # mating point (its x, along the pinion axis, the blank's mean point's: measured
        # to 1e-10 mm in the slow library test; 1e-6 mm asserted)
        assert got["mating_point_mm"][0] == pytest.approx(mean_x, abs=1e-6)


@pytest.mark.slow
def test_the_prints_gear_with_the_blanks_pinion_is_named(tmp_path):
    rc, out, err = run_console("tca", "--pair", PRINT, "--out", tmp_path / "t",
                               "--no-figures", "--quiet")
    assert rc == 0, err                      # a result, reported: not a refusal
    for side in ("drive", "coast"):
        said = [line for line in err.splitlines() if "MateWarning" in line
                and f"[machine.pinion.{side}]" in line]
        assert len(said) == 1 and "are not mates" in said[0]
