"""``gearcontact lte`` end to end through :func:`gearcontact.cli.main`.

Truths: the files and JSON keys; the peak-to-peaks in lte.json are those of the CSV
columns (to its 12 digits); torque balance of every written row (sum_j W_j l_j = T needs
the levers, so checked as: the per-pair loads are non-negative and the preview/LCP load
totals agree within the Hertz-vs-LCP lever mix, 5 %); TE_LCP = TE0 + rotation (s0003
drive, envelope = min).
"""

import json

import numpy as np
import pytest

from gearcontact.cli import main

KEYS = ("te_lcp_pp_arcsec", "te_pre_pp_arcsec", "te0_pp_arcsec", "compliance_lcp_mm_per_n",
        "compliance_pre_mm_per_n", "mesh_compliance_lcp_mm_per_n", "active_pairs_lcp_max",
        "converged")


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    d = tmp_path_factory.mktemp("lte") / "new"
    assert main(["lte", "--pair", "s0003-centred", "--torque", "64.5", "--out", str(d),
                 "--phases", "11", "--cells", "24", "--quiet", "--rigid"]) == 0
    return d


def header_of(path):
    return path.read_text().splitlines()[0].split(",")


def test_files_keys_and_consistency(out):
    for name in ("lte.json", "lte.csv", "lte.png"):
        assert (out / name).stat().st_size > 0, name
    data = json.loads((out / "lte.json").read_text())
    for key in KEYS:
        assert key in data, key
    assert data["converged"] and data["phases"] == 11
    # timings only in the run manifest (identical runs, identical result files)
    assert "timings_s" not in data and "solve_ms" not in header_of(out / "lte.csv")
    assert json.loads((out / "run.json").read_text())["timings_s"]["solve_ms_per_phase"] > 0
    header = (out / "lte.csv").read_text().splitlines()[0].split(",")
    rows = np.genfromtxt(out / "lte.csv", delimiter=",", skip_header=1, dtype=float)
    col = {name: rows[:, i] for i, name in enumerate(header)}
    assert rows.shape[0] == 11
    for key in ("te0", "te_lcp", "te_pre"):
        assert np.ptp(col[f"{key}_arcsec"]) == pytest.approx(data[f"{key}_pp_arcsec"],
                                                             rel=1e-10)
    np.testing.assert_allclose(col["te_lcp_arcsec"] - col["te0_arcsec"],
                               col["rotation_lcp_arcsec"], rtol=1e-10)
    loads = np.column_stack([col[h] for h in header if h.startswith("load_lcp_pair")])
    pre = np.column_stack([col[h] for h in header if h.startswith("load_pre_pair")])
    assert (loads >= 0).all() and (pre >= 0).all()
    np.testing.assert_allclose(loads.sum(axis=1), pre.sum(axis=1), rtol=0.05)
    assert ((loads > 0).sum(axis=1) >= col["active_lcp"]).all()


@pytest.mark.parametrize("argv, word", [(["--torque", "0"], "--torque"),
                                        (["--cells", "8"], "cells"),
                                        (["--phases", "1"], "phases")])
def test_bad_input(tmp_path, capsys, argv, word):
    assert main(["lte", "--out", str(tmp_path), "--phases", "11", "--quiet"] + argv) == 2
    assert word in capsys.readouterr().err


def test_lte_with_bending(out, tmp_path):
    # the shell bending of both teeth in the coupled LCP (tests/ltca/
    # test_tooth_bending.py checks it against its limits): the same command without
    # --rigid (bending is the default) is flagged, converges, balances the shares and
    # is more compliant
    d = tmp_path / "bend"
    assert main(["lte", "--pair", "s0003-centred", "--torque", "64.5", "--out", str(d),
                 "--phases", "11", "--cells", "24", "--quiet", "--no-figures"]) == 0
    bent = json.loads((d / "lte.json").read_text())
    rigid = json.loads((out / "lte.json").read_text())
    assert bent["bending"] and not rigid["bending"] and bent["converged"]
    assert sum(bent["reference_load_share"].values()) == pytest.approx(1.0, rel=1e-12)
    assert bent["mesh_compliance_lcp_mm_per_n"] > rigid["mesh_compliance_lcp_mm_per_n"]
    assert bent["reference_rotation_lcp_arcsec"] > rigid["reference_rotation_lcp_arcsec"]
    # one run gives the mesh stiffness rigid and with bending: its rigid stiffness is the
    # rigid run's (the same fields and LCPs, started from the bending instead of the
    # rigid solution: equal to the solver tolerance 1e-8 over the 10 % torque step of
    # the difference quotient, 1e-6), the bending one is softer, and at P0 it is the
    # inverse of the mesh compliance (same step, 1e-6)
    for key in ("mesh_stiffness_rigid_n_per_mm_mean", "mesh_stiffness_rigid_nm_per_rad_mean"):
        assert bent[key] == pytest.approx(rigid[key], rel=1e-6)
    assert "mesh_stiffness_bending_n_per_mm_mean" not in rigid
    assert bent["mesh_stiffness_bending_n_per_mm_max"] < bent["mesh_stiffness_rigid_n_per_mm_min"]
    assert bent["reference_mesh_stiffness_bending_n_per_mm"] == pytest.approx(
        1.0 / bent["mesh_compliance_lcp_mm_per_n"], rel=1e-6)
    with open(d / "lte.csv") as f:
        header = f.readline().strip().split(",")
    rows = np.loadtxt(d / "lte.csv", delimiter=",", skiprows=1,
                      usecols=[header.index(c) for c in (
                          "mesh_stiffness_rigid_nm_per_rad", "mesh_stiffness_rigid_n_per_mm",
                          "mesh_stiffness_bending_nm_per_rad",
                          "mesh_stiffness_bending_n_per_mm")])
    lever = bent["reference_lever_mm"]
    np.testing.assert_allclose(rows[:, 1], 1e3 * rows[:, 0] / lever ** 2, rtol=1e-11)
    np.testing.assert_allclose(rows[:, 3], 1e3 * rows[:, 2] / lever ** 2, rtol=1e-11)
    assert rows[:, 2].mean() == pytest.approx(bent["mesh_stiffness_bending_nm_per_rad_mean"],
                                              rel=1e-11)
