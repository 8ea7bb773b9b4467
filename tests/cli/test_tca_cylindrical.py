"""``gearcontact tca`` on a cylindrical pair, run as a user runs it (default options,
through :func:`gearcontact.cli.main`), and the options it refuses.

Truths: the ISO 21771 contact ratio and mean length of the lines of contact
(b ε_α / cos β_b) of the pair's geometry; the half normal backlash of the example's
centre distance (a_w 100.1 mm against the zero-backlash 100.0854 mm) as TE0: material
is only removed by the modifications, so the gear lags at least j_bn / (2 r_b2 cos β_b),
and exactly that where a contact line crosses the pinion's unmodified point.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.geometry.pair import CYLINDRICAL, load_pair
from gearcontact.tca.types import ARCSEC_PER_RAD

ROOT = Path(__file__).resolve().parents[2]
EV = str(ROOT / "examples" / "ev_reducer_helical_23x67.toml")


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    d = tmp_path_factory.mktemp("tca_cyl") / "run"
    assert main(["tca", "--pair", EV, "--out", str(d)]) == 0
    return d


def test_files_and_numbers(out):
    for name in ("tca.json", "te0.csv", "contact_lines.csv", "te0.png", "contact_pattern.png"):
        assert (out / name).stat().st_size > 0, name
    g = load_pair(EV, kinds=(CYLINDRICAL,)).geometry
    doc = json.loads((out / "tca.json").read_text())
    assert doc["side"] == "drive" and doc["facing"] == "cw" and doc["phases_per_pitch"] == 61
    te = np.genfromtxt(out / "te0.csv", delimiter=",", names=True)
    assert len(te) == 61
    # the pairs in the zone average eps_gamma: 2 / 60 (two count steps per pitch, each
    # placed within one phase step)
    assert np.mean(te["pairs_in_zone"][:-1]) == pytest.approx(g.total_contact_ratio, abs=2 / 60)
    # the lines average b eps_alpha / cos beta_b; the gear-tip ends of the lines sit where
    # the gear's own flank (relieved 8 um, 10 um of backlash) crosses its tip, up to
    # ~20 um / sin beta_b = 0.05 mm along a line: 0.1 mm
    beta_b = math.radians(g.base_helix_angle_deg)
    iso = g.face_width_mm * g.transverse_contact_ratio / math.cos(beta_b)
    assert np.mean(te["line_length_mm"][:-1]) == pytest.approx(iso, abs=0.1)
    assert doc["line_length_iso_mean_mm"] == pytest.approx(iso, rel=1e-12)
    # TE0: at most minus the half backlash (rad -> arcsec), and within 0.01 arcsec of it
    # (a line passes within one phase step of the pinion's unmodified point, where the
    # crowning is of second order in that distance)
    half = -g.normal_backlash_mm / (g.base_diameter_gear_mm * math.cos(beta_b)) * ARCSEC_PER_RAD
    assert te["te0_arcsec"].max() <= half + 1e-6
    assert te["te0_arcsec"].max() == pytest.approx(half, abs=0.01)
    assert doc["te0_pp_arcsec"] == pytest.approx(np.ptp(te["te0_arcsec"]), abs=1e-9)
    lines = np.genfromtxt(out / "contact_lines.csv", delimiter=",", names=True)
    assert len(lines) == int(te["pairs_in_zone"].sum())


def test_identical_runs_identical_files(out, tmp_path):
    again = tmp_path / "again"
    assert main(["tca", "--pair", EV, "--out", str(again), "--no-figures"]) == 0
    for name in ("tca.json", "te0.csv", "contact_lines.csv"):
        assert (again / name).read_bytes() == (out / name).read_bytes(), name


@pytest.mark.parametrize("option", [["--pairs", "2"], ["--table-records", "8"],
                                    ["--misalignment", "E=0.01"]])
def test_refused_options(option, tmp_path, capsys):
    assert main(["tca", "--pair", EV, "--out", str(tmp_path / "o"), *option]) == 2
    err = capsys.readouterr().err
    assert option[0] in err and "cylindrical" in err and "Traceback" not in err
    assert not (tmp_path / "o").exists()


def test_coast_side(tmp_path):
    """--side coast analyses the ccw flanks: the pinion turns the other way, TE0 changes
    sign (TE0 = phi2 - phi1 / u), so it is at least plus the half backlash (0.01 arcsec
    as above), with the same pairs in the zone."""
    d = tmp_path / "coast"
    assert main(["tca", "--pair", EV, "--out", str(d), "--side", "coast", "--no-figures"]) == 0
    g = load_pair(EV, kinds=(CYLINDRICAL,)).geometry
    doc = json.loads((d / "tca.json").read_text())
    assert doc["side"] == "coast" and doc["facing"] == "ccw"
    beta_b = math.radians(g.base_helix_angle_deg)
    half = g.normal_backlash_mm / (g.base_diameter_gear_mm * math.cos(beta_b)) * ARCSEC_PER_RAD
    assert doc["te0_min_arcsec"] >= half - 1e-6
    assert doc["te0_min_arcsec"] == pytest.approx(half, abs=0.01)
    assert doc["mean_pairs_in_zone"] == pytest.approx(g.total_contact_ratio, abs=2 / 60)
