"""``gearcontact twin`` end to end through :func:`gearcontact.cli.main`.

Truths: the files and JSON keys; the summary statistics are those of the CSV columns
(to its 12 digits); the time axis has the requested step; the mesh carries the load
torque on average; bad input -> exit 2 with the field named, before the TCA runs.
"""

import json
from pathlib import Path

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.cli.outdir import MANIFEST

KEYS = ("backend", "steps", "step_us", "mesh_frequency_hz", "dte_pp_arcsec", "dynamic_factor",
        "contact_loss", "mean_mesh_torque_nm", "static_mesh_load_n", "natural_frequencies_hz",
        "drivetrain")


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    d = tmp_path_factory.mktemp("twin") / "new"
    assert main(["twin", "--pair", "s0003", "--torque", "64.5", "--speed-rpm", "3000",
                 "--duration-ms", "6", "--step-us", "10", "--phases", "31",
                 "--backend", "golden", "--out", str(d), "--quiet"]) == 0
    return d


def test_files_keys_and_consistency(out):
    for name in ("twin.json", "twin.csv", "twin.png", "twin_spectrum.png"):
        assert (out / name).stat().st_size > 0, name
    data = json.loads((out / "twin.json").read_text())
    for key in KEYS:
        assert key in data, key
    assert data["backend"] == "golden" and data["steps"] == 600
    assert data["mesh_frequency_hz"] == pytest.approx(350.0)      # 7 x 3000 / 60
    header = (out / "twin.csv").read_text().splitlines()[0].split(",")
    rows = np.genfromtxt(out / "twin.csv", delimiter=",", skip_header=1, dtype=float)
    col = {name: rows[:, i] for i, name in enumerate(header)}
    assert rows.shape[0] == 600
    np.testing.assert_allclose(np.diff(col["t_s"]), 10e-6, rtol=1e-9)
    late = col["t_s"] >= 0.5 * data["duration_s"]
    assert data["dte_pp_arcsec"] == pytest.approx(np.ptp(col["te_arcsec"][late]), rel=1e-9)
    assert data["dynamic_factor"] == pytest.approx(
        col["mesh_torque_nm"][late].max() / 64.5, rel=1e-9)
    # 3 ms after the static start: the mean mesh torque is the load torque within the
    # dynamic swing (dynamic factor ~1.02)
    assert data["mean_mesh_torque_nm"] == pytest.approx(64.5, rel=0.02)


def test_identical_runs_identical_files(out, tmp_path):
    """A second identical run writes byte-identical files (figures included); the
    real-time factor and step timings are only in run.json."""
    again = tmp_path / "again"
    assert main(["twin", "--pair", "s0003", "--torque", "64.5", "--speed-rpm", "3000",
                 "--duration-ms", "6", "--step-us", "10", "--phases", "31",
                 "--backend", "golden", "--out", str(again), "--quiet"]) == 0
    manifests = [json.loads((Path(d) / MANIFEST).read_text()) for d in (out, again)]
    files = [{f["path"]: f["sha256"] for f in m["files"]} for m in manifests]
    assert files[0] == files[1] and set(files[0]) >= {"twin.json", "twin.csv", "twin.png",
                                                      "twin_spectrum.png"}
    for name in files[0]:
        assert (out / name).read_bytes() == (again / name).read_bytes(), name
    timings = manifests[1]["timings_s"]
    for key in ("real_time_factor", "step_time_p50_us", "step_time_p99_us", "wall_s"):
        assert timings[key] > 0, key
        assert key not in (out / "twin.json").read_text(), key


@pytest.mark.parametrize("argv, field", [
    (["--backend", "fpga"], "--backend"),
    (["--step-us", "80"], "--step-us"),
    (["--duration-ms", "-1"], "--duration-ms"),
    (["--duration", "0"], "--duration"),
    (["--torque", "-3"], "--torque"),
])
def test_bad_input_exit_2(tmp_path, capsys, argv, field):
    code = main(["twin", "--out", str(tmp_path / "x"), "--quiet", *argv])
    assert code == 2
    assert field in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_bad_drivetrain_file_exit_2(tmp_path, capsys):
    f = tmp_path / "d.toml"
    f.write_text("[drivetrain]\nload_inertia_kgm2 = -0.1\n")
    code = main(["twin", "--drivetrain", str(f), "--out", str(tmp_path / "x"), "--quiet"])
    assert code == 2 and "drivetrain.load_inertia_kgm2" in capsys.readouterr().err


@pytest.mark.parametrize("content, named", [
    (None, "--drivetrain"),                         # no such file
    (b"[drivetrain]\nload_inertia_kgm2 = \xff\n", "(byte 33)"),   # not UTF-8
    (b"[drivetrain\n", "TOML syntax")])
def test_unreadable_drivetrain_file_exit_2_before_work(tmp_path, capsys, content, named):
    """Each was 'internal error, please report' (careless-user probe of issue 12)."""
    f = tmp_path / "d.toml"
    if content is not None:
        f.write_bytes(content)
    code = main(["twin", "--drivetrain", str(f), "--out", str(tmp_path / "x"), "--quiet"])
    assert code == 2 and named in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_duration_has_an_upper_limit(tmp_path, capsys):
    """--duration 1e9 ran for hours; the limit is named in the message."""
    code = main(["twin", "--duration", "1e9", "--out", str(tmp_path / "x"), "--quiet"])
    assert code == 2 and "at most 60 s" in capsys.readouterr().err


def test_speed_sweep_files(tmp_path):
    d = tmp_path / "sweep"
    assert main(["twin", "--speed-sweep", "1000:3000:1000", "--phases", "31", "--workers", "1",
                 "--out", str(d), "--quiet"]) == 0
    data = json.loads((d / "sweep.json").read_text())
    assert data["speeds_rpm"] == [1000.0, 3000.0, 3]
    assert set(data) >= {"reference", "table", "resonance_speeds_rpm"}
    rows = np.genfromtxt(d / "sweep.csv", delimiter=",", skip_header=1, dtype=float)
    assert rows.shape == (3, 7)
    assert data["reference"]["max_dynamic_factor"] == pytest.approx(rows[:, 1].max())
    assert (d / "sweep.png").stat().st_size > 0


@pytest.fixture
def no_twin_work(monkeypatch):
    """The first expensive stage of both twin paths fails the test if reached."""
    import gearcontact.cli.twin as cli_twin

    def fail(*a, **k):
        raise AssertionError("the twin's work started before the options were checked")

    monkeypatch.setattr(cli_twin, "model_for_pair", fail)


@pytest.mark.parametrize("argv, needles", [
    # was a BrokenProcessPool (exit 1) once the workers met the --speed-rpm limit
    (["--speed-sweep", "90000:110000:5000"], ("--speed-sweep", "(0, 100000] rpm")),
    # was 64 forks for 4 tasks
    (["--speed-sweep", "1000:2000:1000", "--workers", "64"],
     ("--workers = 64", "(the CPU count)")),
    (["--workers", "2"], ("--workers", "only with --speed-sweep")),
    # was a 60M x 16 record in memory, MemoryError after 71 s
    (["--duration", "60", "--step-us", "1"],
     ("--record-every = 1", ">= 10: 60,000,000 rows", "6,000,000")),
])
def test_sizes_and_speeds_checked_before_work(tmp_path, capsys, no_twin_work, argv, needles):
    """Issue 28 probe: each exits 2 before any work, naming the option and the limit."""
    code = main(["twin", "--out", str(tmp_path / "x"), "--quiet", *argv])
    err = capsys.readouterr().err
    assert code == 2, err
    for needle in needles:
        assert needle in err, (needle, err)
    assert not (tmp_path / "x").exists()


def test_record_limit_is_the_longest_run_at_the_default_step(tmp_path, capsys, no_twin_work):
    """60 s at 10 us (the documented longest run) is 6,000,000 rows: accepted; the
    check is the record's size, so --record-every 10 admits 60 s at 1 us."""
    from gearcontact.cli.twin import MAX_DURATION_S, MAX_RECORD_ROWS

    assert MAX_RECORD_ROWS == round(MAX_DURATION_S / 10e-6)
    for argv in (["--duration", "60"], ["--duration", "60", "--step-us", "1",
                                        "--record-every", "10"]):
        # past every check: the stand-in for the work is reached (main reports it as a bug)
        assert main(["twin", "--out", str(tmp_path / "x"), "--quiet", *argv]) == 1
        assert "the twin's work started" in capsys.readouterr().err
