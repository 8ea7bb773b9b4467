"""``design --machine-settings`` on a pair whose blades carry a Toprem (tests/data/toprem):
the relief kept as given on the blades it writes (docs/machine_settings.md sec. 6
"Relieved blades").

Truths: the standard settings of a relieved pair are those of the same pair without
the relief (the relief lies below the blade point that cuts the mean point, where the
settings are solved), the relief carried over unchanged; a relief reaching that point,
or measured points off the relieved flank, exit 2 naming the key or the points.
"""

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from easeoff_grid import write_points_csv

from gearcontact.cli import main
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.relief_setup import blade_relief, with_relief

ROOT = Path(__file__).resolve().parents[2]
TOPREM = ROOT / "tests" / "data" / "toprem" / "iso23509_f2_toprem.toml"
SMOOTH = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def _setups(path):
    return {(s.member, s.side): s for s in load_pair(path).machine}


def test_machine_settings_keep_the_relief(capsys, tmp_path):
    # both pairs' standard settings (~3 s each); the relieved pair's written file loads
    # with the pinion's Toprem (2 deg from 2 mm) and, the relief taken off, equals the
    # smooth pair's to the last digit (the same computation; the TOML writes repr floats)
    for path, out in ((TOPREM, "relieved"), (SMOOTH, "smooth")):
        assert main(["design", "--pair", str(path), "--machine-settings", "--out",
                     str(tmp_path / out)]) == 0
    capsys.readouterr()
    got = _setups(tmp_path / "relieved" / "machine_settings.toml")
    smooth = _setups(tmp_path / "smooth" / "machine_settings.toml")
    given = _setups(TOPREM)
    for key, s in got.items():
        assert blade_relief(s.blade) == blade_relief(given[key].blade), key
        assert with_relief(s, dict.fromkeys(blade_relief(s.blade), 0.0)) == smooth[key], key
    assert got["pinion", "drive"].blade.toprem_angle_deg == 2.0


@pytest.mark.parametrize("edit, key, allowed", [
    # a Toprem from 10 mm: deeper than the whole pinion tooth, the mean point on it
    ("toprem_depth_mm = 2.0", "blade.pinion.drive.toprem_depth_mm = 10.0", "< 2.4"),
    # deeper than the blade itself (50 mm): refused when the pair is read
    ("toprem_depth_mm = 2.0", "blade.pinion.drive.toprem_depth_mm = 60.0", "50"),
])
def test_machine_settings_refuse_a_relief_reaching_the_mean_point(capsys, tmp_path, edit,
                                                                   key, allowed):
    depth = key.split(" = ")[1]
    text = TOPREM.read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace(edit, f"toprem_depth_mm = {depth}", 1))
    assert main(["design", "--pair", str(bad), "--machine-settings"]) == 2
    err = capsys.readouterr().err
    assert key in err and allowed in err, err


def _own_pinion_csv(path, *, inside: bool):
    """The relieved pair's own drive pinion measured at 7 x 9 points against itself (the
    pinion its settings cut: the flank --target-flank rows of a pair cut from machine
    settings are read against; deviation 0) inside its box, or at the positions of the
    blank's conjugate pinion's box (whose root line, 1.215 mm, lies below the relieved
    flank's, 1.296 mm)."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.kinked import machine_flank

    pair = load_pair(TOPREM)
    own = next(s for s in pair.machine if (s.member, s.side) == ("pinion", "drive"))
    truth = machine_flank(own, pair.blank, face_width_mm=pair.pinion_face_width_mm)
    nominal = truth if inside else build_flanks(dataclasses.replace(pair, machine=())).pinion.drive
    b = nominal.boundary
    pad = (0.1, 0.5) if inside else (0.0, 0.0)
    U, V = np.meshgrid(np.linspace(b.u_root + pad[0], b.u_tip - pad[0], 7),
                       np.linspace(b.v_toe + pad[1], b.v_heel - pad[1], 9), indexing="ij")
    write_points_csv(path, nominal, truth, "drive", U.ravel(), V.ravel())
    return path


def test_target_flank_points_off_the_relieved_flank_are_refused(capsys, tmp_path):
    # on the conjugate pinion's box the lowest row lies below the relieved flank the
    # pair's settings cut (its root line is traced by the Toprem segment's edge round,
    # u 1.296 mm, against 1.215 mm): exit 2 before any fit, naming the first such row
    # (line 2: L at the toe, R below the flank) and the cut flank's range (~8 s)
    csv = _own_pinion_csv(tmp_path / "m.csv", inside=False)
    assert main(["design", "--pair", str(TOPREM), "--machine-settings", "--target-flank",
                 str(csv)]) == 2
    err = capsys.readouterr().err
    assert "m.csv: pinion drive: line 2 (L = 64.54054215814256 mm" in err, err
    assert "= 'off the flank' is outside the allowed range: a point on the pinion " \
           "flank's active box" in err, err


def test_target_flank_of_a_relieved_pair_is_fitted_with_its_relief(capsys, tmp_path):
    # ~6 s: the pair's own relieved drive pinion measured at 63 points inside its flank,
    # deviation 0: read against the pinion the pair's settings cut, fitted from those
    # settings with the Toprem kept, the typed settings written back within 1e-4 deg /
    # mm (on the 9 x 11 grid the first-order bounds of the sheet's own error, 3.1e-4 um
    # at the points, are <= 5.7e-5, the blade angle's; docs/machine_settings.md sec. 6),
    # the coast pinion and the gear the pair's own
    import math

    csv = _own_pinion_csv(tmp_path / "m.csv", inside=True)
    assert main(["design", "--pair", str(TOPREM), "--machine-settings", "--target-flank",
                 str(csv), "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "| drive | 63 | 0.00 |" in out, out
    assert "drive: the relieved blade's toprem kink at u " in out, out
    got, typed = _setups(tmp_path / "o" / "machine_settings.toml"), _setups(TOPREM)
    assert got["pinion", "drive"].blade.toprem_depth_mm == 2.0
    assert blade_relief(got["pinion", "drive"].blade) == \
        blade_relief(typed["pinion", "drive"].blade)
    for key in (("pinion", "coast"), ("gear", "drive"), ("gear", "coast")):
        assert got[key] == typed[key], key
    a, b = got["pinion", "drive"], typed["pinion", "drive"]
    for f in ("radial_distance_mm", "cradle_angle_deg", "ratio_of_roll"):
        assert math.isclose(getattr(a.settings, f), getattr(b.settings, f), abs_tol=1e-4), f
    assert math.isclose(a.blade.blade_angle_deg, b.blade.blade_angle_deg, abs_tol=1e-4)
    assert (tmp_path / "o" / "machine_settings_points.csv").exists()
