"""Sweeps of a cylindrical pair (gearcontact.sweep.cylindrical) against independent
truths: every cell equals the direct mesh cycle and loaded TE of the pair file with the
swept values written into its TOML (bit for bit: the same computation on the same
pair), and along swept helix-slope and misalignment axes the closed forms of TE0 that
tests/tca/test_cylindrical_cycle.py checks on the cycle itself."""

import math
from pathlib import Path

import numpy as np
import pytest

xr = pytest.importorskip("xarray")

from gearcontact.geometry.cylindrical.pair import CylindricalPair  # noqa: E402
from gearcontact.geometry.pair import load_pair  # noqa: E402
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te  # noqa: E402
from gearcontact.sweep import SweepGrid, parse_vary, run_sweep  # noqa: E402
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle  # noqa: E402
from gearcontact.tca.types import ARCSEC_PER_RAD  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
EV = ROOT / "examples" / "ev_reducer_helical_23x67.toml"
KINDS = ("cylindrical",)


def _sweep(pair, vary, tmp_path, *, torques=(200.0,), compute=("tca",), **kw):
    grid = SweepGrid(tuple(parse_vary(v, kind="cylindrical") for v in vary), tuple(torques))
    report = run_sweep(pair, grid, out=tmp_path, side=kw.pop("side", "drive"),
                       compute=compute, workers=0, progress=False, **kw)
    assert report.failed == 0, report.errors
    return xr.open_zarr(report.store, consolidated=False).load()


def test_cells_equal_direct_runs_of_the_modified_pair_file(tmp_path):
    """A 2 x 2 grid over the pinion tip relief and the axis inclination of the EV stage
    at one torque: each cell's TE0 p-p, loaded TE p-p, peak pressure and mean stiffness
    are those of cylindrical_mesh_cycle + cylindrical_loaded_te on the example file
    with the two values written into its TOML text (==, no tolerance: the sweep must
    compute the same pair with the same options)."""
    pair = load_pair(EV, kinds=KINDS)
    ds = _sweep(pair, ["modifications.pinion.tip_relief_um=4:12:2",
                       "assembly.axis_inclination_um=-15:15:2"], tmp_path / "s",
                compute=("tca", "ltca"), phases=11, cells=16)
    text = EV.read_text()
    assert text.count("[modifications.pinion]\ntip_relief_um = 8.0\n") == 1
    for c_a in (4.0, 12.0):
        for f_delta in (-15.0, 15.0):
            file = tmp_path / f"ev_{c_a:g}_{f_delta:g}.toml"
            file.write_text(text.replace("[modifications.pinion]\ntip_relief_um = 8.0\n",
                                         f"[modifications.pinion]\ntip_relief_um = {c_a}\n")
                            + f"\n[assembly]\naxis_inclination_um = {f_delta}\n")
            direct = load_pair(file, kinds=KINDS)
            cycle = cylindrical_mesh_cycle(direct, facing="cw", phases=11)
            lte = cylindrical_loaded_te(direct, 200.0, cycle=cycle, cells_along=16)
            cell = ds.sel(modifications_pinion_tip_relief_um=c_a,
                          assembly_axis_inclination_um=f_delta, torque_nm=200.0)
            assert float(cell["te0_pp_arcsec"]) == cycle.te0_pp_arcsec
            assert float(cell["te0_mean_arcsec"]) == float(np.mean(cycle.envelope_arcsec[:-1]))
            assert float(cell["lte_pp_arcsec"]) == lte.lte_pp_arcsec
            assert float(cell["p_max_mpa"]) == float(lte.max_pressure_mpa.max())
            assert float(cell["stiffness_mean_n_per_mm_um"]) == lte.mean_stiffness_n_per_mm_um
    # the swept keys matter: the four loaded TEs differ
    assert np.unique(ds["lte_pp_arcsec"].values).size == 4


def _ev_class(beta, hand, b, **kw):
    """The 23/67 pair of tests/tca/test_cylindrical_cycle.py (m_n 2 mm, x 0.3 / 0.1)."""
    return CylindricalPair(name="t", pinion_teeth=23, gear_teeth=67, normal_module_mm=2.0,
                           pinion_face_width_mm=b, gear_face_width_mm=b, helix_angle_deg=beta,
                           pinion_hand=hand, profile_shift_pinion=0.3, profile_shift_gear=0.1,
                           **kw)


@pytest.mark.parametrize("side, sign", [("drive", 1), ("coast", -1)])
def test_helix_slope_axis_closed_form(side, sign, tmp_path):
    """Along a swept pinion helix slope f_Hbeta = 0..12 um of the helical 23/67, TE0 is
    the constant ±f / (2 r_b2) (drive: cw facing, +), exact in the plane of action:
    1e-6 arcsec, the cycle test's tolerance (solves to 1e-11 mm)."""
    pair = _ev_class(25.0, "left", 30.0)
    ds = _sweep(pair, ["modifications.pinion.helix_slope_um=0:12:4"], tmp_path, side=side,
                phases=31)
    f_um = ds["modifications_pinion_helix_slope_um"].values
    rb2 = 0.5 * pair.geometry.base_diameter_gear_mm
    truth = sign * 0.5 * f_um * 1e-3 / rb2 * ARCSEC_PER_RAD
    np.testing.assert_allclose(ds["te0_mean_arcsec"].isel(torque_nm=0).values, truth, atol=1e-6)
    assert ds["te0_pp_arcsec"].values.max() < 1e-6


def test_misalignment_axes_closed_form(tmp_path):
    """Over a 3 x 3 grid of axis deviation f_Sigma_beta and inclination f_Sigma_delta
    (-10..10 um) of the spur 23/67, b = 20 mm: TE0 is the constant
    |f_Sigma_beta cos(alpha_wt) + f_Sigma_delta sin(alpha_wt)| / (2 r_b2), first order in
    the tilt: 1 % of TE0 (neglected terms ~ tilt^2 r_b2; tests/tca), and 1e-6 arcsec at
    the aligned centre."""
    pair = _ev_class(0.0, None, 20.0)
    ds = _sweep(pair, ["assembly.axis_deviation_um=-10:10:3",
                       "assembly.axis_inclination_um=-10:10:3"], tmp_path, phases=21)
    a_wt = math.radians(pair.geometry.working_pressure_angle_deg)
    rb2 = 0.5 * pair.geometry.base_diameter_gear_mm
    f_beta = ds["assembly_axis_deviation_um"].values[:, None]
    f_delta = ds["assembly_axis_inclination_um"].values[None, :]
    truth = 0.5 * np.abs(f_beta * math.cos(a_wt) + f_delta * math.sin(a_wt)) * 1e-3 / rb2 \
        * ARCSEC_PER_RAD
    got = ds["te0_mean_arcsec"].isel(torque_nm=0).values
    np.testing.assert_allclose(got, truth, rtol=0.01, atol=1e-6)
    assert truth.max() > 10.0     # the grid reaches a TE0 well above the tolerances


def test_dask_cluster_equals_in_process(client, tmp_path):
    """The same unloaded sweep of the spur 23/67 on the package's two-worker cluster and
    in this process (workers=0): every variable equal (the pair travels to the workers
    by pickle; nothing of the cell depends on where it runs)."""
    pair = _ev_class(0.0, None, 20.0)
    vary = ["modifications.pinion.lead_crowning_um=0:8:2",
            "assembly.axis_deviation_um=-5:5:2"]
    grid = SweepGrid(tuple(parse_vary(v, kind="cylindrical") for v in vary), (100.0,))
    report = run_sweep(pair, grid, out=tmp_path / "dask", side="drive", phases=11,
                       client=client, progress=False)
    assert report.failed == 0, report.errors
    on_cluster = xr.open_zarr(report.store, consolidated=False).load()
    here = _sweep(pair, vary, tmp_path / "here", torques=(100.0,), phases=11)
    xr.testing.assert_identical(on_cluster, here)
