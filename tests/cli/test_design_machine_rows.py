"""``gearcontact design --machine-settings --target-flank CSV`` on a pair cut from
machine settings: its pinion rows read against the pinion its settings cut, a relieved
gear blade's rows fitted with the relief kept, careless CSVs (docs/machine_settings.md
sec. 6 "Gear flanks", "Pinion rows of a machine pair").

Truths: the pinion the ISO 23509 F.2 machine pair's settings cut, measured on its own
CMM grid with deviation 0, writes the typed settings back (the library's recovery and
its first-order bounds: tests/geometry/test_machine_pinion_rows.py); a relieved gear
cut with known perturbations is written back with its relief
(tests/geometry/test_gear_correction_relieved.py). Careless input exits 2 naming the
column or the file line, the value and the allowed range.
"""

import math
from pathlib import Path

import pytest
from easeoff_grid import (GEAR_FORMATE_PERTURBATION, member_pivot_length_mm,
                         write_gear_measured_csv)

from gearcontact.cli import main
from gearcontact.geometry.gear_correction import gear_seeds, machine_seeds
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.measuring_grid import measuring_grid
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.relief_setup import blade_relief
from gearcontact.geometry.setting_fit import apply_corrections

ROOT = Path(__file__).resolve().parents[2]
F2_MACHINE = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"
_SETTINGS = ("radial_distance_mm", "cradle_angle_deg", "machine_root_angle_deg",
             "machine_centre_to_back_mm", "sliding_base_mm", "blank_offset_mm",
             "ratio_of_roll")


def _setups(path):
    return {(s.member, s.side): s for s in load_pair(path).machine}


def test_zero_pinion_rows_of_a_machine_pair_write_its_typed_settings(capsys, tmp_path):
    # ~8 s: the drive pinion the pair's settings cut, its 9 x 11 CMM grid with
    # deviation 0 (a perfect part): the pinion drive written within 1e-4 (deg, mm) of
    # the typed settings (the library's first-order bounds of the sheet's own error
    # are <= 2.1e-5, the blade angle's; tests/geometry/test_machine_pinion_rows.py),
    # the pinion coast and the gear exactly the pair's own (not measured)
    pair = load_pair(F2_MACHINE)
    own = machine_seeds(pair, "pinion")["drive"]
    nominal = machine_flank(own, pair.blank, face_width_mm=pair.pinion_face_width_mm)
    g = measuring_grid(nominal, member="pinion", flank="drive", rows=9, cols=11)
    csv = tmp_path / "zero.csv"
    csv.write_text("member,flank,row,col,L_mm,R_mm,deviation_um\n" + "".join(
        f"pinion,drive,{i},{j},{float(L)!r},{float(R)!r},0.0\n"
        for i, j, L, R in zip(g.row, g.col, g.L_mm, g.R_mm)))
    out = tmp_path / "o"
    assert main(["design", "--pair", str(F2_MACHINE), "--machine-settings", "--target-flank",
                 str(csv), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "| pinion side | points |" in text and "| drive | 99 | 0.00 |" in text, text
    assert "gear: the pair's own" in text
    got, typed = _setups(out / "machine_settings.toml"), _setups(F2_MACHINE)
    for key in (("pinion", "coast"), ("gear", "drive"), ("gear", "coast")):
        assert got[key] == typed[key], key
    a, b = got["pinion", "drive"], typed["pinion", "drive"]
    for f in _SETTINGS:
        assert math.isclose(getattr(a.settings, f), getattr(b.settings, f), abs_tol=1e-4), f
    assert math.isclose(a.blade.blade_angle_deg, b.blade.blade_angle_deg, abs_tol=1e-4)
    rows = (out / "machine_settings_points.csv").read_text().splitlines()
    assert rows[0].startswith("member,flank,line,L_mm,R_mm,deviation_um") and len(rows) == 100
    # the residual at each point < 1e-3 um (the sheet's interpolation error; measured
    # 3.3e-5 um)
    assert max(abs(float(r.split(",")[-1])) for r in rows[1:]) < 1e-3


def test_relieved_gear_rows_keep_the_relief(capsys, tmp_path):
    # ~4 s: the F.2 machine pair with a 2 deg Toprem from 3 mm on its gear drive blade,
    # the gear cut with known perturbations (formate subset), measured on its nominal
    # grid: the written gear drive is the cut one within 1e-9 (mm, deg; the library's
    # first-order bounds are below 6e-12, the fit's stopping in another process
    # margin), its Toprem as typed; the residual over the flank not reported ("-": a
    # spline through a kinked flank's deviations would smooth it)
    toml = tmp_path / "relieved.toml"
    text = F2_MACHINE.read_text()
    head = "[blade.gear.drive]\n"
    assert text.count(head) == 1
    toml.write_text(text.replace(head, head + "toprem_angle_deg = 2.0\ntoprem_depth_mm = 3.0\n"))
    pair = load_pair(toml)
    seed = gear_seeds(pair, "formate")["drive"]
    assert seed.blade.toprem_angle_deg == 2.0
    smooth = next(s for s in load_pair(F2_MACHINE).machine
                  if (s.member, s.side) == ("gear", "drive"))
    true = apply_corrections(seed, GEAR_FORMATE_PERTURBATION,
                             pivot_length_mm=member_pivot_length_mm(smooth, pair.blank))
    csv = tmp_path / "gear.csv"
    write_gear_measured_csv(csv, pair, seed, true, "drive")
    out = tmp_path / "o"
    assert main(["design", "--pair", str(toml), "--machine-settings", "--target-flank",
                 str(csv), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "| drive | 99 |" in printed and "| - |" in printed, printed
    got = _setups(out / "machine_settings.toml")["gear", "drive"]
    assert blade_relief(got.blade) == blade_relief(seed.blade)
    for f in _SETTINGS:
        assert math.isclose(getattr(got.settings, f), getattr(true.settings, f),
                            abs_tol=1e-9), f
    for f in ("blade_angle_deg", "point_radius_mm"):
        assert math.isclose(getattr(got.blade, f), getattr(true.blade, f), abs_tol=1e-9), f


_HEAD = "member,flank,L_mm,R_mm,deviation_um\n"


@pytest.mark.parametrize("text, words", [
    # a column missing (R_mm): named, not read as the other (u, v) ease-off format
    ("member,flank,L_mm,deviation_um\npinion,drive,76.0,1.0\n",
     "bad.csv: header (line 1) columns = 'R_mm' is outside the allowed range: each of "
     "member,flank,L_mm,R_mm,deviation_um once"),
    # NaN and an empty cell: the column named with the file line
    (_HEAD + "pinion,drive,76.0,nan,1.0\n",
     "bad.csv: line 2 R_mm = 'nan' is outside the allowed range: a finite number"),
    (_HEAD + "gear,coast,30.0,70.0,\n",
     "bad.csv: line 2 deviation_um = '' is outside the allowed range: a finite number"),
    # a deviation of more than half the tooth (pi m_mn / 4 = 2524 um on F.2; here a
    # length in nm, or the wrong nominal)
    (_HEAD + "gear,drive,30.0,70.0,1e5\n",
     "bad.csv: line 2 (gear drive) deviation_um = 100000.0 is outside the allowed range: "
     "|deviation| < 2524 um, pi m_mn / 4"),
    # a row with a cell too few
    (_HEAD + "pinion,drive,76.0,25.9\n",
     "bad.csv: line 2 = 'pinion,drive,76.0,25.9' is outside the allowed range: 5 values"),
])
def test_careless_csv_exits_2_naming_the_column_or_line(capsys, tmp_path, text, words):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    assert main(["design", "--pair", str(F2_MACHINE), "--machine-settings",
                 "--target-flank", str(path)]) == 2
    err = capsys.readouterr().err
    assert words in err, err


def test_pinion_rows_off_the_machine_cut_flank_exit_2(capsys, tmp_path, monkeypatch):
    # ~4 s (the machine-cut flanks are built to read the rows against): valid gear rows
    # (the gear's own, deviation 0) and a pinion row on the pinion blank (clearance line
    # u 0.854 mm over the root cone) but below the root line of the flank the pair's
    # drive settings cut (u 1.075 mm; R 25.81 mm at L = 76 mm): exit 2 naming the file
    # line, L, R and the flank's range, before any fit of either member (the fit
    # raising proves it; eight more pinion rows: eight settings need eight points)
    import gearcontact.geometry.gear_correction as correction

    monkeypatch.setattr(correction, "solve_fit", lambda *a, **k: pytest.fail("fitted"))
    pair = load_pair(F2_MACHINE)
    gear = gear_seeds(pair, "formate")["drive"]
    write_gear_measured_csv(tmp_path / "gear.csv", pair, gear, gear, "drive")
    cells = [r.split(",") for r in (tmp_path / "gear.csv").read_text().splitlines()[2:]]
    gear_rows = "".join(",".join(c[:2] + c[4:]) + "\n" for c in cells)     # no row, col
    rows = "".join(f"pinion,drive,{70.0 + k!r},27.0,0.0\n" for k in range(8))
    path = tmp_path / "off.csv"
    path.write_text(_HEAD + gear_rows + "pinion,drive,76.0,25.65,0.0\n" + rows)
    assert main(["design", "--pair", str(F2_MACHINE), "--machine-settings",
                 "--target-flank", str(path)]) == 2
    err = capsys.readouterr().err
    assert ("off.csv: pinion drive: line 101 (L = 76.0 mm, R = 25.65 mm) = 'off the flank' "
            "is outside the allowed range: a point on the pinion flank's active box") in err, err
