"""``gearcontact twin`` on a cylindrical pair (table backend): at 3000 rpm, far below
the mesh resonance (25,600 rpm, tests/twin/test_cylindrical.py), the twin is
quasi-static, so its dynamic TE is the loaded TE of ltca.cylindrical_lte at the same
torque and phases (the table's own LCP) and its mean mesh torque the load torque; the
preview backends and the options a cylindrical pair has no meaning for are refused
before any work; the README line runs as written."""

import json
from pathlib import Path

import pytest
from readme_lines import readme_argv

from gearcontact.cli import main
from gearcontact.geometry.pair import load_pair
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te

ROOT = Path(__file__).resolve().parents[2]
EV = str(ROOT / "examples" / "ev_reducer_helical_23x67.toml")


def test_quasi_static_twin_is_the_loaded_te(tmp_path, capsys):
    """DTE p-p within 5 % of the loaded TE p-p (the mesh excitation at 1150 Hz
    amplifies by 1/(1 - (1150/9830)^2) = 1.014 on the mesh mode, the RK4 step and the
    table's linear interpolation between the 11 rows add less); mean mesh torque within
    0.1 % of 64.5 N·m."""
    out = tmp_path / "tw"
    assert main(["twin", "--pair", EV, "--backend", "table", "--phases", "11",
                 "--duration-ms", "30", "--out", str(out), "--no-figures", "--quiet"]) == 0
    doc = json.loads((out / "twin.json").read_text())
    lte = cylindrical_loaded_te(load_pair(EV, kinds=("cylindrical",)), 64.5, phases=11,
                                cells_along=40, bending=False)   # the twin's rigid default
    assert doc["backend"] == "table" and doc["contact_loss"] == 0.0
    assert doc["dte_pp_arcsec"] == pytest.approx(lte.lte_pp_arcsec, rel=5e-2)
    assert doc["mean_mesh_torque_nm"] == pytest.approx(64.5, rel=1e-3)
    assert doc["mesh_frequency_hz"] == pytest.approx(23 * 3000 / 60, rel=1e-12)
    assert "ev_reducer_helical_23x67 twin table" in capsys.readouterr().out


@pytest.mark.parametrize("extra, field", [([], "--backend"),
                                          (["--backend", "golden"], "--backend"),
                                          (["--backend", "table", "--table-source",
                                            "preview"], "--table-source"),
                                          (["--backend", "table", "--speed-sweep",
                                            "1000:3000:1000"], "--speed-sweep")])
def test_refused_before_work(extra, field, tmp_path, capsys):
    assert main(["twin", "--pair", EV, "--out", str(tmp_path / "o"), *extra]) == 2
    err = capsys.readouterr().err
    assert field in err and "cylindrical" in err
    assert not (tmp_path / "o").exists()


def test_readme_twin_cylindrical(tmp_path):
    argv = readme_argv("gearcontact twin --pair examples/ev_reducer_helical", tmp_path / "run")
    assert main(argv) == 0
    doc = json.loads((tmp_path / "run" / "twin.json").read_text())
    assert doc["backend"] == "table" and 1.0 < doc["dynamic_factor"] < 1.05
