"""``gearcontact sweep`` (:mod:`gearcontact.cli.sweep`) under the CLI contract.

Truths: bad grids (also unknown TOML keys and impossible design values) are exit 2
before any output; zero misalignment reproduces ``gearcontact tca`` exactly; a
cutter-radius sweep builds each variant and draws the design figure; the cluster path for real - a
``dask scheduler`` and a ``dask worker`` started as subprocesses on the loopback
address, the sweep run through ``--scheduler`` - gives the Dataset of the in-process
run (``--workers 0``) exactly; the rerun of the same command computes nothing; run.json
lists the store's files.
"""

import json
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")

import gearcontact  # noqa: E402
from gearcontact.cli import main  # noqa: E402

ARGS = ["sweep", "--pair", "s0003-centred", "--vary", "E=-0.05:0.05:2", "--vary",
        "P=-0.05:0.05:2", "--phases", "21", "--quiet"]


@pytest.mark.parametrize("bad,named", [
    (["--vary", "E=0.1:-0.1:3"], "reversed range"), (["--vary", "E=0:0.1:0"], "STEPS"),
    (["--vary", "H=0:0.1:2"], "one of the assembly errors"), (["--vary", "E=0:1:2", "--vary", "E=0:1:2"],
                                              "each key at most once"),
    (["--scheduler", "localhost:8786"], "tcp://HOST:PORT"), (["--workers", "-1"], "--workers"),
    (["--torques", "1e9"], "--torques"),
    # an unknown TOML key: named, with the allowed keys listed
    (["--vary", "easeoff.drive.crowning=0:1:2"], "easeoff.drive.crowning"),
    (["--vary", "cutter.diameter_mm=80:90:2"], "cutter.radius_mm, cutter.point_width_mm"),
    # a design value the pair refuses, before any flank is built
    (["--vary", "cutter.radius_mm=-5:45:2"], "cutter.radius_mm")])
def test_bad_input_exits_2_before_any_output(tmp_path, capsys, bad, named):
    out = tmp_path / "o"
    assert main(["sweep", *bad, "--out", str(out)]) == 2
    assert named in capsys.readouterr().err
    assert not out.exists()


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def scheduler():
    """A real scheduler and one worker process on the loopback address, for the one test
    that uses them (module-scoped they idled on to the module's end: ~3 s CPU a minute,
    40 s of CPU measured under load)."""
    from distributed import Client

    addr = f"tcp://127.0.0.1:{_free_port()}"
    env = dict(os.environ, PYTHONPATH=str(Path(gearcontact.__file__).parents[1]))
    procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler",
                               "--host", "127.0.0.1", "--port", addr.rsplit(":", 1)[1],
                               "--no-dashboard"], env=env, stderr=subprocess.DEVNULL)]
    procs.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", addr,
                                   "--nworkers", "1", "--nthreads", "1", "--no-dashboard"],
                                  env=env, stderr=subprocess.DEVNULL))
    try:
        with Client(addr, timeout=60) as c:
            c.wait_for_workers(1, timeout=60)
        yield addr
    finally:
        for p in reversed(procs):
            p.terminate()
            p.wait(timeout=30)


def test_scheduler_address_runs_the_same_sweep(tmp_path, scheduler, capsys):
    remote, local = tmp_path / "remote", tmp_path / "local"
    assert main([*ARGS, "--scheduler", scheduler, "--out", str(remote)]) == 0
    assert main([*ARGS, "--workers", "0", "--no-figures", "--out", str(local)]) == 0
    a = xr.open_zarr(remote / "sweep.zarr", consolidated=False).load()
    b = xr.open_zarr(local / "sweep.zarr", consolidated=False).load()
    assert (a["status"].values == 1).all()
    xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())
    capsys.readouterr()
    assert main([*ARGS, "--scheduler", scheduler, "--out", str(remote)]) == 0
    assert "0 computed, 4 already finished" in capsys.readouterr().out
    files = [f["path"] for f in json.loads((remote / "run.json").read_text())["files"]]
    assert "sweep_maps.png" in files and any(f.startswith("sweep.zarr/") for f in files)
    # a killed run leaves no run.json: the store is still the sweep's own, not foreign
    (local / "run.json").unlink()
    assert main([*ARGS, "--workers", "0", "--no-figures", "--out", str(local)]) == 0
    assert "0 computed, 4 already finished" in capsys.readouterr().out


def test_killed_sweep_resumes_to_the_uninterrupted_result(tmp_path, capsys):
    """SIGKILL of the command after some points, rerun: the Dataset equals an
    uninterrupted run's and every cell is computed once (computed + finished = total)."""
    import re
    import signal

    args = ["sweep", "--pair", "s0003-centred", "--vary", "E=-0.04:0.04:9", "--phases", "61",
            "--workers", "0", "--no-figures"]
    cut = tmp_path / "cut"
    env = dict(os.environ, PYTHONPATH=str(Path(gearcontact.__file__).parents[1]))
    proc = subprocess.Popen([sys.executable, "-m", "gearcontact", *args, "--out", str(cut)],
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    seen = b""
    while not re.search(rb"\b([2-7])/9 ", seen):      # tqdm: 2 to 7 of 9 cells done
        chunk = proc.stderr.read1(256)
        assert chunk, f"the sweep ended before it could be killed: {seen[-300:]!r}"
        seen += chunk
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    capsys.readouterr()
    assert main([*args, "--quiet", "--out", str(cut)]) == 0
    m = re.search(r"(\d+) computed, (\d+) already finished", capsys.readouterr().out)
    computed, finished = map(int, m.groups())
    assert finished >= 2 and computed + finished == 9
    assert main([*args, "--quiet", "--out", str(tmp_path / "whole")]) == 0
    xr.testing.assert_identical(
        xr.open_zarr(cut / "sweep.zarr", consolidated=False).load(),
        xr.open_zarr(tmp_path / "whole" / "sweep.zarr", consolidated=False).load())


def test_pair_without_easeoff_is_swept_with_the_synthesized_one(tmp_path, capsys):
    """A pair file without an [easeoff.drive] table: the sweep uses the synthesized
    ease-off, says so, and reproduces `gearcontact tca` of the same file exactly (both go
    through tca.synthesis.prepare_pair, deterministic)."""
    from importlib import resources

    text = resources.files("gearcontact").joinpath("data/pairs/s0003-centred.toml").read_text()
    head, rest = text.split("[easeoff.drive]", 1)
    pair_file = tmp_path / "bare.toml"
    pair_file.write_text(head + "[easeoff.coast]" + rest.split("[easeoff.coast]", 1)[1])
    tca, sweep = tmp_path / "tca", tmp_path / "sweep"
    assert main(["tca", "--pair", str(pair_file), "--side", "drive", "--phases", "21",
                 "--no-figures", "--out", str(tca)]) == 0
    assert main(["sweep", "--pair", str(pair_file), "--side", "drive", "--vary", "E=0:0:1",
                 "--phases", "21", "--workers", "0", "--quiet", "--out", str(sweep)]) == 0
    assert capsys.readouterr().out.count("has no [easeoff.drive] table: ease-off synthesized") == 2
    want = json.loads((tca / "tca.json").read_text())
    got = xr.open_zarr(sweep / "sweep.zarr", consolidated=False).load().isel(
        E_mm=0, torque_nm=0)
    assert float(got["te0_pp_arcsec"]) == want["te0_pp_arcsec"]          # exactly


def test_zero_misalignment_reproduces_gearcontact_tca(tmp_path):
    tca, sweep = tmp_path / "tca", tmp_path / "sweep"
    assert main(["tca", "--pair", "s0003-centred", "--phases", "21", "--no-figures",
                 "--out", str(tca)]) == 0
    assert main(["sweep", "--pair", "s0003-centred", "--vary", "E=0:0:1", "--phases", "21",
                 "--workers", "0", "--quiet", "--out", str(sweep)]) == 0
    want = json.loads((tca / "tca.json").read_text())
    got = xr.open_zarr(sweep / "sweep.zarr", consolidated=False).load().isel(
        E_mm=0, torque_nm=0)
    assert float(got["te0_pp_arcsec"]) == want["te0_pp_arcsec"]          # exactly
    assert float(got["paint_major_mm"]) == 2 * want["paint_ellipse"]["semi_major_mm"]
    assert bool(got["pattern_on_flank"]) == want["pattern_on_flank"]


def test_cutter_radius_sweep_builds_each_variant_and_draws_it(tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["sweep", "--pair", "s0003-centred", "--vary", "cutter.radius_mm=44.6:45.6:2",
                 "--vary", "E=-0.01:0.01:2", "--phases", "21", "--workers", "0", "--quiet",
                 "--out", str(out)]) == 0
    assert "4 computed" in capsys.readouterr().out
    ds = xr.open_zarr(out / "sweep.zarr", consolidated=False).load()
    assert ds["cutter_radius_mm"].attrs == {"units": "mm", "key": "cutter.radius_mm"}
    assert (ds["status"].values == 1).all()
    te = ds["te0_pp_arcsec"].isel(torque_nm=0).values
    assert te[0, 0] != te[1, 0]            # another cutter, other flanks
    files = [f["path"] for f in json.loads((out / "run.json").read_text())["files"]]
    assert {"sweep_maps.png", "sweep_design.png"} <= set(files)
    # the rerun resumes: nothing computed (no variant rebuilt), the same Dataset
    assert main(["sweep", "--pair", "s0003-centred", "--vary", "cutter.radius_mm=44.6:45.6:2",
                 "--vary", "E=-0.01:0.01:2", "--phases", "21", "--workers", "0", "--quiet",
                 "--no-figures", "--out", str(out)]) == 0
    assert "0 computed, 4 already finished" in capsys.readouterr().out
    xr.testing.assert_identical(xr.open_zarr(out / "sweep.zarr", consolidated=False).load(), ds)


def test_unreachable_scheduler_is_bad_input_before_the_store(tmp_path, capsys):
    """Nothing listens on the port: exit 2 naming --scheduler (was an internal error
    after 30 s, with an empty store left behind; then a run.json and the lock in a
    directory the run created: the probe of issue 28). The directory is not created."""
    import dask

    out = tmp_path / "o"
    with dask.config.set({"distributed.comm.timeouts.connect": "2s"}):
        code = main(ARGS + ["--scheduler", f"tcp://127.0.0.1:{_free_port()}",
                            "--out", str(out)])
    assert code == 2
    assert "--scheduler" in capsys.readouterr().err
    assert not out.exists()


def test_design_keys_on_a_relieved_pair_exit_2_naming_the_blade(tmp_path, capsys):
    # a pair cut from machine settings takes no [easeoff.*] / [cutter] key (its flanks
    # are the settings'); with a Toprem the ease-off variant would be laid on the kinked
    # pinion and smooth the kink: refused before any flank, the blade key named
    # (tests/data/toprem: both pinion blades 2 deg from 2 mm)
    out = tmp_path / "o"
    toprem = Path(__file__).resolve().parents[1] / "data" / "toprem" / "iso23509_f2_toprem.toml"
    assert main(["sweep", "--pair", str(toprem), "--vary",
                 "easeoff.drive.lengthwise_crowning_um_per_mm2=0:0.1:2", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--vary easeoff.drive.lengthwise_crowning_um_per_mm2" in err, err
    assert "[blade.pinion.drive] toprem_angle_deg = 2" in err and "kink" in err, err
    assert not out.exists()
