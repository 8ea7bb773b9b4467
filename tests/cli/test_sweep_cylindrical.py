"""``gearcontact sweep`` on a cylindrical pair (:mod:`gearcontact.cli.sweep`).

Truths: a bad key or value is exit 2 naming the key, the value and the allowed range,
before any output; two identical runs write identical files (run.json aside, which holds
the timings); the README's EV sweep runs as written, and its cell at the example's own
values (C_a = 8 um, aligned) is the direct cycle and loaded TE of the example file.
"""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")

from readme_lines import readme_argv  # noqa: E402

from gearcontact.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
EV = str(ROOT / "examples" / "ev_reducer_helical_23x67.toml")
SPUR = str(ROOT / "examples" / "spur_20x40_m3.toml")


@pytest.mark.parametrize("pair, extra, named", [
    # a value outside the key's range: the key, the value, the range
    (EV, ["--vary", "modifications.pinion.tip_relief_um=-5:10:4"],
     ["modifications.pinion.tip_relief_um", "-5", "[0, 500]"]),
    (EV, ["--vary", "assembly.axis_inclination_um=0:2000:3"],
     ["assembly.axis_inclination_um", "1000", "[-500, 500]"]),
    (EV, ["--vary", "modifications.gear.profile_crowning_um=0:250:2"],
     ["modifications.gear.profile_crowning_um", "250", "[0, 200]"]),
    # a tip relief on a member without a start diameter: the diameter and its range
    (SPUR, ["--vary", "modifications.gear.tip_relief_um=0:10:3"],
     ["modifications.gear.tip_relief_um=5", "tip_relief_start_diameter_mm", "(116.0100, "
      "126.0000) mm"]),
    # unknown keys, a bevel key: named, with the pair's keys listed
    (SPUR, ["--vary", "modifications.pinion.tip_relieff_um=0:1:2"],
     ["modifications.pinion.tip_relieff_um", "assembly.axis_deviation_um"]),
    (SPUR, ["--vary", "E=0:0.1:3"], ["'E'", "modifications.pinion.helix_slope_um"]),
    (SPUR, ["--misalignment", "E=0.1"], ["--misalignment", "[assembly] table"]),
    (SPUR, ["--torques", "-1"], ["--torques", "-1"]),
])
def test_bad_input_exit_2(pair, extra, named, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["sweep", "--pair", pair, *extra, "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    for text in named:
        assert text in err
    assert "Traceback" not in err and not out.exists()


def _files(root: Path) -> dict:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*"))
            if p.is_file() and p.name != "run.json"}


def test_identical_runs_identical_files(tmp_path, capsys):
    """Twice the same loaded sweep of the spur pair (lead crowning x torque, in
    process): the store and the figure are the same bytes; a third run into the first
    directory computes nothing (resumed, all cells finished)."""
    argv = ["sweep", "--pair", SPUR, "--vary", "modifications.pinion.lead_crowning_um=0:10:2",
            "--torques", "100", "200", "--compute", "tca,ltca", "--phases", "11", "--cells",
            "16", "--workers", "0", "--quiet"]
    for name in ("a", "b"):
        assert main([*argv, "--out", str(tmp_path / name)]) == 0
    a, b = _files(tmp_path / "a"), _files(tmp_path / "b")
    assert "sweep_design.png" in a and any(k.startswith("sweep.zarr/") for k in a)
    assert a.keys() == b.keys()
    assert [k for k in a if a[k] != b[k]] == []
    ds = xr.open_zarr(tmp_path / "a" / "sweep.zarr", consolidated=False)
    assert (ds["status"].values == 1).all()
    # the rerun into the same directory finds every cell finished (the settings match)
    capsys.readouterr()
    assert main([*argv, "--out", str(tmp_path / "a")]) == 0
    assert "0 computed, 4 already finished" in capsys.readouterr().out
    assert set(ds.dims) == {"modifications_pinion_lead_crowning_um", "torque_nm"}


def test_readme_ev_sweep(tmp_path, capsys):
    """The README line as written (22 s warm with rigid teeth; with bending, the default
    since, 98 s on a machine at load 16-18):
    exit 0, the 5 x 3 x 2 grid done; the cell at the file's own values equals the direct
    cycle and loaded TE of the example (==: the same pair and options)."""
    from gearcontact.geometry.pair import load_pair
    from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
    from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle

    argv = readme_argv("gearcontact sweep --pair examples/ev_reducer_helical",
                       tmp_path / "run")
    cwd = Path.cwd()
    try:
        import os

        os.chdir(ROOT)          # the README's relative pair path
        assert main(argv) == 0
    finally:
        os.chdir(cwd)
    ds = xr.open_zarr(tmp_path / "run" / "sweep.zarr", consolidated=False).load()
    assert ds["status"].shape == (5, 3, 2) and (ds["status"].values == 1).all()
    assert (tmp_path / "run" / "sweep_design.png").is_file()
    pair = load_pair(EV, kinds=("cylindrical",))
    cycle = cylindrical_mesh_cycle(pair, phases=21)
    cell = ds.sel(modifications_pinion_tip_relief_um=8.0, assembly_axis_inclination_um=0.0)
    assert float(cell["te0_pp_arcsec"].isel(torque_nm=0)) == cycle.te0_pp_arcsec
    for k, torque in enumerate(ds["torque_nm"].values):
        lte = cylindrical_loaded_te(pair, float(torque), cycle=cycle, cells_along=24)
        assert float(cell["lte_pp_arcsec"].isel(torque_nm=k)) == lte.lte_pp_arcsec
    assert np.isfinite(ds["stiffness_mean_n_per_mm_um"].values).all()
