"""``gearcontact ltca`` end to end through :func:`gearcontact.cli.main`.

Truths: the files and JSON keys the issue lists; load balance of the written pressure
map (sum of pressure x cell area = W, to the CSV's 12 significant digits); the mesh
rotation is the approach over the lever (rigid teeth); the preview p_max is Hertzian in
W (Hamrock-Brewe from the written curvature-free quantities: p_max = 3 W / (2 pi a b)).
"""

import json

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.ltca.pair_ltca import ARCSEC_PER_RAD

KEYS = ("load_n", "p_mean_mpa", "p90_mpa", "p_peak_mpa", "delta_mm", "mesh_rotation_arcsec",
        "n_contact_cells", "preview_p_max_mpa", "solver")


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    d = tmp_path_factory.mktemp("ltca") / "new"             # created by the command
    assert main(["ltca", "--pair", "s0003-centred", "--torque", "64.5", "--out", str(d),
                 "--phases", "11", "--cells", "40"]) == 0
    return d


def test_files_and_keys(out):
    for name in ("ltca.json", "pressure_map.csv", "pressure_map.png"):
        assert (out / name).stat().st_size > 0, name
    data = json.loads((out / "ltca.json").read_text())
    for key in KEYS:
        assert key in data, key
    # timings only in the run manifest: identical runs give identical result files
    assert "solve_ms" not in data
    assert json.loads((out / "run.json").read_text())["timings_s"]["solve_ms"] > 0
    assert data["solver"] == "pk_cg" and data["status"] == "converged"
    assert data["torque_nm"] == 64.5
    # W = T / lever, rotation = delta / lever
    assert data["load_n"] == pytest.approx(64.5e3 / data["lever_mm"], rel=1e-12)
    assert data["mesh_rotation_arcsec"] == pytest.approx(
        data["delta_mm"] / data["lever_mm"] * ARCSEC_PER_RAD, rel=1e-12)
    assert data["preview_p_max_mpa"] == pytest.approx(
        1.5 * data["load_n"] / (np.pi * data["preview_a_mm"] * data["preview_b_mm"]),
        rel=1e-9)


def test_pressure_map_carries_the_load(out):
    data = json.loads((out / "ltca.json").read_text())
    s, t, p = np.loadtxt(out / "pressure_map.csv", delimiter=",", skiprows=1).T
    assert s.size == 40 * 40
    ds = np.diff(np.unique(s)).mean()
    dt = np.diff(np.unique(t)).mean()
    assert (p >= 0).all()
    assert p.sum() * ds * dt == pytest.approx(data["load_n"], rel=1e-9)
    assert (p > 0).sum() == data["n_contact_cells"]
    assert p.max() == pytest.approx(data["p_peak_mpa"], rel=1e-11)


@pytest.mark.parametrize("argv, word", [
    (["--torque", "-1"], "--torque"), (["--phases", "2"], "phases"),
    # a dense solver at 320 cells per side would need tens of GB: refused at once
    (["--solver", "nnls", "--cells", "320"], "[16, 80] per side with the dense --solver"),
    (["--solver", "active_set", "--cells", "81"], "--cells = 81"),
    # below the envelope's 1 N at any lever (was "blocks = []" from the mesh LCP in lte)
    (["--torque", "1e-9"], "--torque (N·m) = 1e-09")])
def test_bad_input(tmp_path, capsys, argv, word):
    assert main(["ltca", "--out", str(tmp_path)] + argv) == 2
    assert word in capsys.readouterr().err


@pytest.fixture(scope="module")
def overload(tmp_path_factory):
    """4000 N·m: the bearing runs off the tooth (s0003-centred, rigid teeth)."""
    d = tmp_path_factory.mktemp("ltca4000")
    import contextlib
    import io

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        code = main(["ltca", "--pair", "s0003-centred", "--torque", "4000", "--out", str(d),
                     "--phases", "5",
                     "--cells", "24", "--export-problem", "--no-figures"])
    return code, err.getvalue(), d


def test_edge_spike_warned_on_stderr(overload):
    code, err, d = overload
    data = json.loads((d / "ltca.json").read_text())
    assert code == 0 and data["edge_contact"]
    # the truncated patch's peak is far above the Hertzian p_max: one stderr line says so
    assert data["p_peak_mpa"] > 1.5 * data["preview_p_max_mpa"]
    lines = [ln for ln in err.splitlines() if "flank edge" in ln]
    assert len(lines) == 1 and "edge spike" in lines[0]
    assert f"{data['p_peak_mpa']:.0f} MPa" in lines[0]


def test_exported_problem_resolves_with_another_solver(overload):
    """The exported LCP is complete: the active-set solver (Cholesky, bordered load
    constraint) on the file's arrays alone reproduces pk_cg's pressure within the two
    solvers' tolerances (1e-6 of the peak) and closes the load exactly."""
    from gearcontact.halfspace.grid import TangentGrid
    from gearcontact.halfspace.lcp import solve_lcp

    _, _, d = overload
    z = np.load(d / "ltca_problem.npz")
    readme = (d / "ltca_problem.README.md").read_text()
    for key in z.files:
        assert f"`{key}`" in readme, key
    x, y = z["x_mm"], z["y_mm"]
    grid = TangentGrid.uniform(x.size, y.size, dx_mm=float(z["dx_mm"]),
                               dy_mm=float(z["dy_mm"]), x0_mm=float(x[0]), y0_mm=float(y[0]))
    res = solve_lcp(z["gap_mm"], grid, float(z["load_n"]), e_star_mpa=float(z["e_star_mpa"]),
                    solver="active_set", warn_coarse=False)
    p = z["pressure_mpa"]
    assert res.pressure_mpa.sum() * z["dx_mm"] * z["dy_mm"] == pytest.approx(
        float(z["load_n"]), rel=1e-9)
    np.testing.assert_allclose(res.pressure_mpa, p, atol=1e-6 * p.max())
    assert res.delta_mm == pytest.approx(float(z["delta_mm"]), rel=1e-6)
    assert not (p[~z["on_flank"]] > 0).any()


MULTI_KEYS = ("load_share_pct", "n_engaged", "mesh_rotation_rigid_arcsec",
              "mesh_rotation_arcsec", "cp_max_mpa", "p_peak_cell_mpa", "preview_p_max_mpa")


def test_multi_tooth(multi_tooth_runs):
    """``--multi-tooth`` on the calibrated (tip-edge) s0003: the keys the issue lists,
    timings only in run.json, shares = pair loads / total, bending rotates more, the
    CSV rows belong to the engaged pairs, and the cell peak is the trimmed edge spike
    (above CP_max). The run: tests/cli/conftest.py MULTI_TOOTH_ARGV (``ltca --pair
    s0003 --torque 64.5 --phases 11 --cells 24 --multi-tooth --multi-tooth-cells 24``),
    shared with test_reproducible.py."""
    d = multi_tooth_runs[0]
    for name in ("multitooth.json", "multitooth.csv", "multitooth.png", "ltca.json"):
        assert (d / name).stat().st_size > 0, name
    data = json.loads((d / "multitooth.json").read_text())
    for key in MULTI_KEYS:
        assert key in data, key
    assert "solve_ms" not in data
    timings = json.loads((d / "run.json").read_text())["timings_s"]
    assert timings["multi_tooth_solve_ms"] > 0 and timings["multi_tooth_solve_rigid_ms"] > 0
    loads = np.array(data["pair_loads_n"])
    assert data["load_share_pct"] == pytest.approx(list(100 * loads / loads.sum()), rel=1e-12)
    assert data["n_engaged"] == len(data["load_share_pct"]) == len(data["pair_offsets"])
    assert data["pair_offsets"][0] == 0
    assert data["mesh_rotation_arcsec"] > data["mesh_rotation_rigid_arcsec"]
    assert data["converged"] and data["edge_contact"]
    assert data["trimmed_cells"] > 0 and data["p_peak_cell_mpa"] > data["cp_max_mpa"]
    # the edge loaded the boundary row: re-solved without it (converged; load balance
    # and the spike of the re-solve: tests/halfspace/test_line_peak.py); the spike re-forms
    # on the new boundary row (a sharp-edge singularity), so the re-solved cell peak
    # stays far above CP_max
    assert data["edge_resolved"] and data["status_resolved"] == "converged"
    assert sum(data["load_share_resolved_pct"]) == pytest.approx(100.0, rel=1e-9)
    assert data["p_peak_trimmed_resolved_mpa"] > 2 * data["cp_max_resolved_mpa"]
    lt = json.loads((d / "ltca.json").read_text())
    assert lt["edge_resolved"] and lt["trimmed_cells"] > 0
    assert lt["p_peak_cell_mpa"] > lt["cp_max_mpa"] > 0
    assert lt["p_peak_trimmed_resolved_mpa"] > lt["cp_max_resolved_mpa"] > 0
    rows = np.loadtxt(d / "multitooth.csv", delimiter=",", skiprows=1)
    assert set(rows[:, 0].astype(int)) == set(data["pair_offsets"])


def test_multi_tooth_cells_checked(tmp_path, capsys):
    assert main(["ltca", "--multi-tooth", "--multi-tooth-cells", "8",
                 "--out", str(tmp_path / "x")]) == 2
    # issue 28 probe: without --multi-tooth the option was silently ignored
    assert main(["ltca", "--multi-tooth-cells", "40", "--out", str(tmp_path / "x")]) == 2
    assert "only with --multi-tooth" in capsys.readouterr().err
    assert not (tmp_path / "x").exists()
