"""Sweeps on Dask distributed (:mod:`gearcontact.sweep.run`, :mod:`.store`, :mod:`.cell`).

Truths: a 2 x 2 sweep on a LocalCluster of 2 worker processes equals the per-point
results computed serially in this process, bit for bit (same code, same inputs, the
flanks shipped by pickling); the zero-misalignment point reproduces the nominal TCA
(and LTCA) exactly; a sweep interrupted after some points and rerun computes exactly
the remaining cells and ends equal to an uninterrupted run; a point whose TCA does not
converge is recorded with its error while the others finish.
"""

import dataclasses

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")

from gearcontact.sweep import store as store_mod  # noqa: E402
from gearcontact.sweep.cell import CELL_VARIABLES, TCA_VARIABLES, compute_point  # noqa: E402
from gearcontact.sweep.grid import SweepGrid, parse_vary  # noqa: E402
from gearcontact.sweep.run import run_sweep  # noqa: E402

PHASES = 21      # enough for a cycle of the centred set-up; keeps a point at ~0.1 s
GRID = SweepGrid((parse_vary("E=-0.05:0.05:2"), parse_vary("P=-0.05:0.05:2")), (64.5,))


def _open(report):
    return xr.open_zarr(report.store, consolidated=False).load()


def test_cluster_sweep_equals_serial_points(s0003_centred, client, tmp_path):
    pair, flanks = s0003_centred
    rep = run_sweep(pair, GRID, out=tmp_path, side="drive", phases=PHASES, client=client,
                    progress=False)
    assert (rep.computed, rep.skipped, rep.failed) == (4, 0, 0)
    ds = _open(rep)
    assert ds["te0_pp_arcsec"].attrs["units"] == "arcsec"
    assert ds["E_mm"].attrs["units"] == "mm" and ds["torque_nm"].attrs["units"] == "N m"
    for idx, a, _ in GRID.points():
        want = compute_point(pair, flanks, a, GRID.torques_nm, side="drive",
                             compute=("tca",), phases=PHASES)
        cell = ds.isel(E_mm=idx[0], P_mm=idx[1])
        assert float(cell["E_mm"]) == a["E_mm"] and float(cell["P_mm"]) == a["P_mm"]
        for name in TCA_VARIABLES:      # bit for bit
            np.testing.assert_array_equal(cell[name].values, want[name], err_msg=name)
    assert (ds["status"].values == store_mod.DONE).all()


@pytest.mark.filterwarnings("error::gearcontact.halfspace.ellipse.CoarseGridWarning")
def test_zero_misalignment_reproduces_the_nominal_tca_and_ltca(s0003_centred, tmp_path):
    from gearcontact.halfspace.ellipse import CoarseGridWarning
    from gearcontact.ltca.lte import loaded_te
    from gearcontact.ltca.pair_ltca import single_pair_ltca
    from gearcontact.sweep.cell import LTE_CELLS, LTE_PHASES, lte_stride
    from gearcontact.tca.analysis import analyze_pair

    pair, flanks = s0003_centred
    grid = SweepGrid((parse_vary("E=0:0:1"),), (64.5, 129.0))
    rep = run_sweep(pair, grid, out=tmp_path, side="drive", compute=("tca", "ltca"),
                    phases=PHASES, cells=24, workers=0, progress=False)
    ds = _open(rep).isel(E_mm=0)
    tca, _ = analyze_pair(pair, side="drive", phases=PHASES, flanks=flanks)
    assert (ds["te0_pp_arcsec"].values == tca.cycle.te0_pp_arcsec).all()
    assert (ds["paint_major_mm"].values == 2 * tca.mean_ellipse.semi_major_mm).all()
    for k, t in enumerate(grid.torques_nm):
        with pytest.warns(CoarseGridWarning):     # the direct call warns; the sweep records
            case = single_pair_ltca(tca, flanks, pair, t, side="drive", cells=24)
        assert ds["preview_p_max_mpa"].values[k] == case.preview.p_max_mpa
        assert ds["lcp_p90_mpa"].values[k] == case.patch.p90_mpa
        assert ds["lcp_peak_mpa"].values[k] == case.patch.p_peak_mpa
        # the loaded TE at the documented phase count (21 TCA phases, stride 2: 11)
        lte = loaded_te(tca, flanks, pair, t, side="drive", cells=LTE_CELLS,
                        stride=lte_stride(PHASES))
        assert len(lte.phi1_rad) == LTE_PHASES
        assert ds["lte_lcp_pp_arcsec"].values[k] == lte.te_lcp_pp_arcsec
        assert ds["lte_preview_pp_arcsec"].values[k] == lte.te_pre_pp_arcsec
    # 24 cells per side resolve the minor semi-axis with ~6 cells: recorded, not warned
    assert ds["lcp_coarse_grid"].values.all()
    # twice the torque: the Hertzian p_max grows by 2^(1/3) (Hertz: p_max ~ W^(1/3))
    p = ds["preview_p_max_mpa"].values
    assert p[1] / p[0] == pytest.approx(2 ** (1 / 3), rel=1e-9)


def test_interrupted_sweep_resumes_without_recomputing(s0003_centred, client, tmp_path,
                                                       monkeypatch):
    pair = s0003_centred[0]
    whole = _open(run_sweep(pair, GRID, out=tmp_path / "whole", side="drive",
                            phases=PHASES, client=client, progress=False))
    real_write, written = store_mod.write_point, []

    def write_then_interrupt(*a, **k):
        real_write(*a, **k)
        written.append(a[2])
        if len(written) == 2:
            raise KeyboardInterrupt       # Ctrl-C after two of four points

    monkeypatch.setattr("gearcontact.sweep.run.write_point", write_then_interrupt)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(pair, GRID, out=tmp_path / "cut", side="drive", phases=PHASES,
                  client=client, progress=False)
    monkeypatch.setattr("gearcontact.sweep.run.write_point", real_write)
    rep = run_sweep(pair, GRID, out=tmp_path / "cut", side="drive", phases=PHASES,
                    client=client, progress=False)
    assert (rep.computed, rep.skipped) == (2, 2)          # nothing computed twice
    again = run_sweep(pair, GRID, out=tmp_path / "cut", side="drive", phases=PHASES,
                      client=client, progress=False)
    assert (again.computed, again.skipped) == (0, 4)
    xr.testing.assert_identical(_open(rep), whole)


def test_failed_point_is_recorded_not_fatal(s0003_centred, tmp_path):
    # A lengthwise crowning of 40 um/mm^2 relieves the toe/tip corner by ~1.7 mm, far
    # beyond the ease-off limit (5 % of the pinion mean normal tooth thickness, ~0.1 mm):
    # that variant's flanks cannot be built, a named error recorded on its point. (A
    # misalignment no longer serves here: since edge-to-surface contact is modelled,
    # every error within the sweep limits gives a result.)
    pair = s0003_centred[0]
    grid = SweepGrid((parse_vary("easeoff.drive.lengthwise_crowning_um_per_mm2=0.1:40:2"),),
                     (64.5,))
    rep = run_sweep(pair, grid, out=tmp_path, side="drive", phases=PHASES, workers=0,
                    progress=False)
    assert (rep.computed, rep.failed) == (2, 1)
    ds = _open(rep)
    assert ds["status"].values.ravel().tolist() == [store_mod.DONE, store_mod.FAILED]
    assert ds["error"].values[0, 0] == ""
    assert ds["error"].values[1, 0].startswith("InputRangeError: easeoff (drive) relief")
    assert "101.8 um" in ds["error"].values[1, 0]
    assert np.isfinite(ds["te0_pp_arcsec"].values[0, 0])
    assert np.isnan(ds["te0_pp_arcsec"].values[1, 0])
    assert set(CELL_VARIABLES) >= set(TCA_VARIABLES) and "lcp_p90_mpa" not in ds


def test_other_grid_in_the_same_store_is_refused(s0003_centred, tmp_path):
    from gearcontact.validation import InputRangeError

    pair = s0003_centred[0]
    grid = SweepGrid((parse_vary("E=0:0:1"),), (64.5,))
    run_sweep(pair, grid, out=tmp_path, side="drive", phases=PHASES, workers=0,
              progress=False)
    other = dataclasses.replace(grid, torques_nm=(32.25,))
    with pytest.raises(InputRangeError, match="--out"):
        run_sweep(pair, other, out=tmp_path, side="drive", phases=PHASES, workers=0,
                  progress=False)
