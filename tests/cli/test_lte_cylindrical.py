"""``gearcontact lte`` on a cylindrical pair, run as a user runs it: the README's line
(default options: 61 phases, tooth bending with the rigid-tooth run beside it, the
Harris map) through `gearcontact.cli.main`, and the options it refuses together.

Truths: the normal load of the torque, F_n = T2 / (r_b2 cos beta_b) (ISO 6336-1), which
the line loads of every phase must integrate to about the gear axis with their levers
(the LCP's torque balance, 1e-9: r_b2 cos beta_b for a line, a tip edge's own); the
Harris map's torques, those of the ISO tangential line loads F_t / b = 50 ... 400 N/mm at
the gear's reference circle d2 = z2 m_n / cos beta; the map's row at the example's own
tip relief (8 um) and torque equal to a loaded TE run at that torque.
"""

import json
import math
import shlex
from pathlib import Path

import numpy as np
import pytest
from readme_lines import readme_commands

from gearcontact.cli import main
from gearcontact.geometry.pair import CYLINDRICAL, load_pair

ROOT = Path(__file__).resolve().parents[2]
EV = str(ROOT / "examples" / "ev_reducer_helical_23x67.toml")
PHASES = "61"  # the default


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    d = tmp_path_factory.mktemp("lte_cyl") / "run"
    line = [c for c in readme_commands() if c.startswith("gearcontact lte --pair examples/ev_")]
    assert len(line) == 1, "README has one lte line for the helical example"
    argv = shlex.split(line[0])[1:]
    argv[argv.index("--out") + 1] = str(d)
    assert main(argv) == 0
    return d


def test_files_and_numbers(out):
    for name in ("lte.json", "lte.csv", "line_load.csv", "harris_map.csv", "lte.png",
                 "harris_map.png"):
        assert (out / name).stat().st_size > 0, name
    pair = load_pair(EV, kinds=(CYLINDRICAL,))
    g = pair.geometry
    doc = json.loads((out / "lte.json").read_text())
    assert doc["teeth"] == "bending" and doc["converged"] and not doc["edge_touch"]
    assert doc["rigid"]["converged"] and doc["harris_map"]["teeth"] == "bending"
    torque = doc["torque_gear_nm"]
    assert torque == 64.5                                    # the command's default
    fn = torque * 1e3 / (0.5 * g.base_diameter_gear_mm * math.cos(math.radians(
        g.base_helix_angle_deg)))
    assert doc["normal_load_n"] == pytest.approx(fn, rel=1e-12)
    iso = doc["iso6336_method_b"]
    assert iso["mean_stiffness_over_c_gamma_alpha"] == pytest.approx(
        doc["mesh_stiffness_mean_n_per_mm_um"] / iso["c_gamma_alpha_n_per_mm_um"], rel=1e-12)
    # 64.5 N·m is 29 N/mm: below Method B's 100 N/mm (no ratio asserted here)
    assert iso["line_load_ft_per_b_n_per_mm"] == pytest.approx(
        64.5e3 / (0.5 * 67 * 2.0 / math.cos(math.radians(25.0))) / 30.0, rel=1e-12)
    assert iso["within_validity"] is False
    lte = np.genfromtxt(out / "lte.csv", delimiter=",", names=True)
    assert len(lte) == int(PHASES)
    assert doc["lte_pp_arcsec"] == pytest.approx(np.ptp(lte["lte_arcsec"]), abs=1e-9)
    # loaded: the gear lags beyond TE0 at every phase (cw facing, TE0 < 0), further with
    # bending than with rigid teeth, whose mesh is stiffer at every phase
    assert (lte["lte_arcsec"] < lte["te0_arcsec"]).all()
    assert (lte["lte_arcsec"] < lte["lte_rigid_arcsec"]).all()
    assert (lte["mesh_stiffness_n_per_mm_um"] < lte["mesh_stiffness_rigid_n_per_mm_um"]).all()
    assert doc["rigid"]["lte_pp_arcsec"] == pytest.approx(np.ptp(lte["lte_rigid_arcsec"]),
                                                          abs=1e-9)
    shares = np.column_stack([lte[n] for n in lte.dtype.names if n.startswith("load_share")])
    # the normal loads sum to F_n where lines alone carry; a tip edge's lever is at most
    # a line's (r_b2 cos beta_b: the touched normal is an involute's), so more elsewhere
    assert np.all(shares.sum(axis=1) >= 1.0 - 1e-9)
    if doc["tip_contact_phases"] == 0:
        np.testing.assert_allclose(shares.sum(axis=1), 1.0, rtol=1e-9)
    lines = np.genfromtxt(out / "line_load.csv", delimiter=",", names=True)
    z = np.unique(lines["pinion_z_mm"])
    dz = z[1] - z[0]
    lever = 0.5 * g.base_diameter_gear_mm * math.cos(math.radians(g.base_helix_angle_deg))
    for phi in np.unique(lines["phi1_deg"]):
        at = lines["phi1_deg"] == phi
        moment = (lines["load_n_per_mm"][at] * lines["lever_mm"][at]).sum() * dz
        assert moment == pytest.approx(fn * lever, rel=1e-9)


def test_harris_map(out):
    pair = load_pair(EV, kinds=(CYLINDRICAL,))
    g = pair.geometry
    d2 = 67 * 2.0 / math.cos(math.radians(25.0))
    harris = np.genfromtxt(out / "harris_map.csv", delimiter=",", names=True)
    assert list(harris["tip_relief_um"]) == [0.0, 4.0, 8.0, 12.0, 16.0]
    doc = json.loads((out / "lte.json").read_text())["harris_map"]
    np.testing.assert_allclose(doc["torques_gear_nm"],
                               np.array([50, 100, 200, 300, 400]) * g.face_width_mm * d2 / 2e3,
                               rtol=1e-12)
    pp = np.array(doc["lte_pp_arcsec"])
    assert pp.shape == (5, 5) and (pp > 0).all() and doc["converged"]
    # every row has one TE0 (the example's relief only shifts where it lies)
    assert np.array(doc["te0_pp_arcsec"]) == pytest.approx(harris["te0_pp_arcsec"], abs=1e-9)


def test_rigid_and_bending_refused_together(tmp_path, capsys):
    d = tmp_path / "out"
    with pytest.raises(SystemExit) as exc:              # argparse's own refusal
        main(["lte", "--pair", EV, "--out", str(d), "--bending", "--rigid"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--rigid" in err and "Traceback" not in err
    assert not d.exists()
