"""``gearcontact design --pair FILE`` on a pair cut from machine settings: each flank at
the blank's mean point, the generating gear's spiral angle, pressure angle and mean cone
distance (what a summary sheet prints) beside the pitch cone's, in the table and in
``--json`` (report.design_mean_point; docs/machine_settings.md sec. 2). The installed
console script, default options.

Truth: the ISO 23509 F.2 blank the example's settings come from
(examples/machine_settings/iso23509_f2_machine.toml: `design --machine-settings` of
examples/iso23509_f2_spiral_bevel.toml, typed to 4 decimals): beta_m2 = 35 deg, the
blade angles alpha = 20 deg, R_m2 = 81.273 mm (published). Tolerances: the typing's
rounding propagated, worst case over the signs (radial S_r 94.9385 mm and cradle angle
q -80.4732 deg to +-5e-5, machine root angle to +-5e-5 deg; the cutter radius 114.3 mm,
blank offset, MCTB and blade angles are exact as typed):
cos(beta) = |S_r sin q| / r_c gives 5.51e-5 deg (d/dS_r -0.86, d/dq 0.24 deg per mm /
deg), the cone distance of the crossing (S_r cos q + r_c sin beta) / cos(delta -
gamma_m) 1.63e-4 mm; the pressure angles are the blade angles at any roll (tilt 0).
The table prints 4 decimals (+-5e-5 more).
"""

import json
import math
from pathlib import Path

import pytest
from console_script import run_console

from gearcontact.geometry.flank_angles import PINION_UNDEFINED, measure_mean_point
from gearcontact.geometry.pair import load_pair

ROOT = Path(__file__).resolve().parents[2]
F2_MACHINE = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"
BETA_TOL_DEG, CONE_TOL_MM = 5.6e-5, 1.7e-4      # the typing's rounding (module docstring)
SHOWN = 5e-5                                     # the table's 4 decimals


def _rows(text: str) -> dict:
    """``{(member, side): [six numbers or None]}`` of the printed table."""
    out = {}
    for line in text.splitlines():
        words = line.split()
        if len(words) == 9 and words[0] in ("gear", "pinion") and words[2].startswith("("):
            out[words[0], words[1]] = [None if w == "-" else float(w) for w in words[3:]]
    return out


def test_design_prints_the_generating_gear_beside_the_pitch_cone():
    code, out, err = run_console("design", "--pair", F2_MACHINE)
    assert code == 0, err
    assert "'generating' = the generating" in out and "'pitch cone' = the cut" in out
    rows = _rows(out)
    assert set(rows) == {("gear", "drive"), ("gear", "coast"), ("pinion", "drive"),
                         ("pinion", "coast")}
    pair = load_pair(F2_MACHINE)
    b = pair.blank
    for side in ("drive", "coast"):
        beta_gen, beta_cone, alpha_gen, alpha_cone, r_gen, r_cone = rows["gear", side]
        assert beta_gen == pytest.approx(35.0, abs=BETA_TOL_DEG + SHOWN)
        assert alpha_gen == pytest.approx(20.0, abs=SHOWN)
        assert r_gen == pytest.approx(81.273, abs=CONE_TOL_MM + SHOWN)
        # the pitch-cone columns: the cut flank on the blank's pitch cone at R_m2
        # (geometry.flank_angles, tested there), printed as measured
        cone = measure_mean_point(pair.machine[0 if side == "drive" else 1],
                                  pitch_angle_deg=b.pitch_angle_gear_deg,
                                  cone_distance_mm=b.mean_cone_distance_gear_mm)
        assert (beta_cone, alpha_cone, r_cone) == pytest.approx(
            (cone.spiral_angle_deg, cone.pressure_angle_deg, 81.273), abs=SHOWN)
        # the pitch cone is not the cradle plane: a formate gear's flank on it is not
        # the print's (docs/machine_settings.md sec. 2)
        assert abs(beta_cone - 35.0) > 1.0 and abs(alpha_cone - 20.0) > 0.5
        # the pinion: its pitch cone's, no generating gear (no print definition found)
        pinion = rows["pinion", side]
        assert pinion[0::2] == [None, None, None]
        assert pinion[5] == pytest.approx(b.mean_cone_distance_pinion_mm, abs=SHOWN)
    assert f"pinion: {PINION_UNDEFINED}" in out


def test_design_json_gives_the_generating_gear_beside_the_pitch_cone():
    code, out, err = run_console("design", "--pair", F2_MACHINE, "--json")
    assert code == 0, err
    got = json.loads(out)["mean_point_angles"]
    for side, flank in (("drive", "convex"), ("coast", "concave")):
        gear = got["gear"][side]
        assert gear["flank"] == flank and gear["missing"] == ""
        gen = gear["generating_gear"]
        assert gen["spiral_angle_deg"] == pytest.approx(35.0, abs=BETA_TOL_DEG)
        assert gen["pressure_angle_deg"] == pytest.approx(20.0, abs=1e-9)
        assert gen["cone_distance_mm"] == pytest.approx(81.273, abs=CONE_TOL_MM)
        assert gear["pitch_cone"]["cone_distance_mm"] == 81.273
        assert gear["pitch_cone"]["hand"] == "left"     # the gear of a right-hand pinion
        pinion = got["pinion"][side]
        assert pinion["generating_gear"] is None and pinion["missing"] == PINION_UNDEFINED
        assert pinion["pitch_cone"]["hand"] == "right"


@pytest.mark.slow
def test_design_round_trip_of_a_generated_hypoid_gear(tmp_path):
    # `design --machine-settings` of a hypoid whose default gear is generated (13/26,
    # E 21.3 mm, tests/design_space.py), its file given back to `design --json`: the
    # generating gear of the written settings (full precision) is the blank's, beta_m2,
    # the effective pressure angles and R_m2 (tolerance: double-precision round-off,
    # 1e-9 deg / mm, as tests/geometry/test_flank_angles.py); ~15 s under load
    from design_space import generated_hypoid

    from gearcontact.geometry.pair import pair_to_toml

    blank_file = tmp_path / "generated.toml"
    blank_file.write_text(pair_to_toml(generated_hypoid()))
    code, _, err = run_console("design", "--pair", blank_file, "--machine-settings",
                               "--out", tmp_path / "cut")
    assert code == 0, err
    code, out, err = run_console("design", "--pair", tmp_path / "cut" / "machine_settings.toml",
                                 "--json")
    assert code == 0, err
    got = json.loads(out)
    assert got["gear_generation"] == "machine"
    b = load_pair(blank_file).blank
    for side in ("drive", "coast"):
        gen = got["mean_point_angles"]["gear"][side]["generating_gear"]
        assert gen["spiral_angle_deg"] == pytest.approx(b.spiral_angle_gear_deg, abs=1e-9)
        assert gen["pressure_angle_deg"] == pytest.approx(
            getattr(b, f"pressure_angle_{side}_deg"), abs=1e-9)
        assert gen["cone_distance_mm"] == pytest.approx(b.mean_cone_distance_gear_mm, abs=1e-9)
    assert not math.isclose(b.pressure_angle_drive_deg, b.pressure_angle_coast_deg)
