"""``gearcontact export fmu --kind drivetrain``: the drivetrain FMU against ``gearcontact
twin``.

Truth: the twin itself -- :func:`gearcontact.twin.model.model_for_pair` and
:func:`gearcontact.twin.simulate.simulate`, the two library calls ``gearcontact twin``
makes, with the pair prepared as the CLI prepares it -- at the same pair, side, phases,
drivetrain file, curvature source, torque, speed, step and duration; FMPy's FMI 3.0
schema validation. The FMU is exported once
per module the way a user does (a real subprocess of ``python -m gearcontact``, s0003
with 9 phases, a drivetrain file that switches the PI speed controller on and removes
the backlash, a light torque, the twin's default curvature source ``stencil``: the
C -> D preview per pair and step; ~15 s) and simulated by FMPy at parameters other than its
start values (speed, step): at 20000 rpm the mesh frequency (4.3 kHz) excites the
2.8 kHz mode enough for contact loss and impacts on the reverse flank (the loaded law
mirrored: s0003's drive side is in line contact). A second export (s0003-centred,
``--curvatures exact``) runs the reverse flank's own law through rattle.
"""

from __future__ import annotations

import csv
import json
import math
import re
import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
from fmpy.validation import validate_fmu  # noqa: E402

from gearcontact.export.mesh_law import BACKENDS  # noqa: E402

from .conftest import (_shell, docs_snippet, export_fmu_cli as _cli,  # noqa: E402
                       run_isolated, simulate_isolated)

ROOT = Path(__file__).resolve().parents[2]
TORQUE_NM = 5.0
SPEED_RPM = 20000.0
STEP_US = 5.0
DURATION_S = 4e-3           # 800 steps of 5 us
#: the PI speed controller on; no designed backlash: the mirrored reverse law closes as
#: soon as the loaded flank opens
DRIVETRAIN = "[drivetrain]\nspeed_control_bandwidth_hz = 40.0\nbacklash_mm = 0.0\n"
#: FMU output -> twin column (the twin's te_arcsec is the DTE)
PAIRS = {"pinion_speed_rad_s": "pinion_speed_rad_s", "gear_speed_rad_s": "gear_speed_rad_s",
         "dte_arcsec": "te_arcsec", "mesh_force_n": "mesh_load_n",
         "mesh_torque_nm": "mesh_torque_nm", "mesh_rotation_rad": "theta_rad",
         "p_max_mpa": "p_max_mpa", "a_mm": "a_mm", "b_mm": "b_mm",
         "pairs_loaded": "pairs_loaded"}
#: the domain counts since initialization, named as the twin's summary keys
COUNTS = ("previews_outside_datapath", "steps_outside_datapath",
          "previews_without_contact_law")


def export_s0003(base: Path, *options: str) -> tuple[Path, Path]:
    """``(FMU, drivetrain file)``: the module's export (s0003, 9 phases, TORQUE_NM,
    DRIVETRAIN) into ``base`` with ``options`` added (tests/export/test_fmu_exact_hertz.py:
    ``--hertz-form exact``)."""
    (base / "dt.toml").write_text(DRIVETRAIN)
    out = base / "s0003"
    run = _cli("--pair", "s0003", "--kind", "drivetrain", "--phases", "9", "--torque",
               str(TORQUE_NM), "--drivetrain", str(base / "dt.toml"), *options, "--out",
               str(out), cwd=base)
    assert run.returncode == 0, run.stderr
    return out / "gearcontact_drivetrain_s0003.fmu", base / "dt.toml"


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    return export_s0003(tmp_path_factory.mktemp("fmu_drivetrain"))


def _assert_reproduces(res, twin, n: int, backend: str) -> None:
    """Every output of the FMU run ``res`` at the first ``n`` communication points
    equals the twin's record: golden identical, fp64 within 1e-9 relative (the bound
    the issue sets; another libm's pow/log/cbrt may differ by an ulp)."""
    for name, col in PAIRS.items():
        got, want = np.asarray(res[name][:n], float), twin.columns[col]
        if backend == "golden":
            np.testing.assert_array_equal(got, want, err_msg=name)
        else:
            np.testing.assert_allclose(got, want, rtol=1e-9, atol=0.0, err_msg=name)


def _assert_counts(res, twin, n: int) -> None:
    """The FMU's domain counts after ``n`` steps equal the twin's run of ``n`` steps
    (its summary: kernel.run_steps' tcount[3..5]), exactly (integers counting the same
    previews); 0 at initialization, never decreasing."""
    for name in COUNTS:
        got = np.asarray(res[name])
        assert got.dtype == np.int64 and got[0] == 0, name
        assert np.all(np.diff(got) >= 0), name
        assert int(got[n]) == twin.summary[name], (name, int(got[n]), twin.summary[name])


def _fmu_run(fmu, backend, **kw):
    return fmpy.simulate_fmu(str(fmu), start_time=0.0, stop_time=DURATION_S,
                             output_interval=1e-6 * STEP_US, output=list(PAIRS) + [
                                 "pinion_speed_rpm", *COUNTS],
                             start_values={"backend": BACKENDS[backend],
                                           "speed_rpm": SPEED_RPM, "step_us": STEP_US}, **kw)


@pytest.fixture(scope="module")
def twin_models(exported):
    """The models of ``gearcontact twin --pair s0003 --phases 9 --torque 5 --drivetrain
    dt.toml`` per FMU backend, by the library call of
    :mod:`gearcontact.cli.twin` (the pair prepared as the CLI prepares it)."""
    from gearcontact.tca.synthesis import prepare_pair
    from gearcontact.twin.params import load_drivetrain
    from gearcontact.twin.simulate import model_for_pair

    _, dt_file = exported
    prepared = prepare_pair("s0003")
    pair = prepared.pair
    drivetrain = load_drivetrain(dt_file, pair)
    return {backend: model_for_pair(pair, torque_nm=TORQUE_NM, backend=twin_backend,
                                    drivetrain=drivetrain, side=prepared.side, phases=9,
                                    curvatures="stencil")
            for backend, twin_backend in (("fp64", "reference"), ("golden", "golden"))}


@pytest.fixture(scope="module")
def twin_runs(twin_models):
    """... ``--speed-rpm 20000 --step-us 5 --duration-ms 4``: :func:`~gearcontact.twin.
    simulate.simulate` as the CLI calls it."""
    from gearcontact.twin.simulate import simulate

    return {backend: simulate(model, speed_rpm=SPEED_RPM, duration_s=DURATION_S,
                              step_s=1e-6 * STEP_US)
            for backend, model in twin_models.items()}


def test_fmu_validates_against_the_fmi3_schema(exported):
    fmu, _ = exported
    assert validate_fmu(str(fmu)) == []
    names = set(zipfile.ZipFile(fmu).namelist())
    assert {"modelDescription.xml", "sources/buildDescription.xml",
            "sources/gc_drivetrain_fmu.c", "sources/gc_contact_law.c",
            "binaries/x86_64-linux/gearcontact_drivetrain_s0003.so"} <= names
    md = fmpy.read_model_description(str(fmu))
    assert md.fmiVersion == "3.0" and md.coSimulation and not md.modelExchange
    var = {v.name: v for v in md.modelVariables}
    for name in ("pinion_speed_rpm", "dte_arcsec", "mesh_force_n", "p_max_mpa"):
        assert var[name].causality == "output"
    assert {n: (var[n].causality, var[n].unit, var[n].start) for n in
            ("speed_rpm", "torque_nm", "step_us")} == {
        "speed_rpm": ("parameter", "rpm", "3000"), "torque_nm": ("parameter", "N.m", "5.0"),
        "step_us": ("parameter", "us", "10")}
    assert var["backend"].causality == "parameter"
    assert md.defaultExperiment.stepSize == "1e-05"
    assert {n: (var[n].type, var[n].causality, var[n].variability) for n in COUNTS} == \
        dict.fromkeys(COUNTS, ("Int64", "output", "discrete"))


@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_fmu_reproduces_gearcontact_twin(exported, twin_runs, backend):
    """Every recorded step of the twin (the state at the start of each step) equals the
    FMU's output at that communication point. Tolerance: fp64 1e-9 relative (the bound
    the issue sets; the C repeats the twin's operations in the same order, and another
    libm's pow/log/cbrt may differ by an ulp), golden identical. Measured: identical
    in both backends, every column."""
    fmu, _ = exported
    res = _fmu_run(fmu, backend)
    twin = twin_runs[backend]
    n = twin.summary["steps"]
    assert n == 800 and len(res) == n + 1
    assert res["time"][n] == pytest.approx(DURATION_S, rel=1e-12)
    _assert_reproduces(res, twin, n, backend)
    # s0003's previews lie in the datapath's domain, each with a law: the twin counts 0
    _assert_counts(res, twin, n)
    assert twin.summary["previews_outside_datapath"] == 0
    np.testing.assert_array_equal(res["pinion_speed_rpm"],
                                  res["pinion_speed_rad_s"] * 30.0 / math.pi)
    # the run is loaded and dynamic: the mesh carries the torque on average and the DTE
    # moves. With the cut-patch law (ltca.edge_law: s0003's tip-edge bearing 17-27 %
    # softer, its edge tail 3-4.5 times) it stays on the loaded flank nearly all the time
    # (measured: 7 of 800 steps in free flight with the scales at the rows' operating
    # loads; session 14's scales fitted over T/4 .. T none, its least mesh torque 0.066
    # N·m; the untruncated law 43 steps in free flight and 11 on the reverse flank): free
    # flight and the reverse flank are reproduced in
    # test_fmu_reproduces_the_twin_through_rattle
    assert 0.5 * TORQUE_NM < np.mean(res["mesh_torque_nm"]) < 1.5 * TORQUE_NM
    assert np.ptp(res["dte_arcsec"]) > 0.1
    assert np.mean(np.asarray(res["mesh_torque_nm"]) > 0.0) >= 0.98


@pytest.mark.parametrize("backend, twin_backend", [("fp64", "reference"),
                                                   ("golden", "golden")])
def test_fmu_counts_previews_as_the_twin(twin_models, tmp_path, backend, twin_backend):
    """The domain counts where they are not zero: the module's twin model (s0003, 9
    phases, TORQUE_NM, DRIVETRAIN) with the TCA's curvatures (``curvatures="exact"``)
    edited by :func:`tests.export.test_fmu.edited_curvatures` (a saddle on one pair's
    row, a ratio 4 alpha_max on another's), built by the twin's
    :func:`~gearcontact.twin.model.build_model` and written by the export's own
    :func:`~gearcontact.export.fmu_drivetrain.write_drivetrain_fmu`: after the module's
    800 steps at 20000 rpm the FMU's three counts equal the twin's run of the same
    model (:func:`_assert_counts`: exact), and every output reproduces it
    (:func:`_assert_reproduces`' tolerances). Each count is reached."""
    import dataclasses

    from gearcontact.export.fmu import fmi3_header_dir
    from gearcontact.export.fmu_drivetrain import write_drivetrain_fmu
    from gearcontact.preview.hertz.reference import ENVELOPE
    from gearcontact.twin.model import build_model
    from gearcontact.twin.simulate import simulate

    from .test_fmu import edited_curvatures

    base = twin_models["fp64"]
    a, b = edited_curvatures(base.mesh.A_minus_per_mm, base.mesh.B_minus_per_mm,
                             base.mesh.valid, base.mesh.opening_mm,
                             alpha_max=ENVELOPE["alpha"][1])
    mesh = dataclasses.replace(base.mesh, A_minus_per_mm=a, B_minus_per_mm=b)

    def model(be):
        return build_model(mesh, base.drivetrain, TORQUE_NM, backend=be,
                           reverse=base.reverse, reverse_note=base.reverse_note,
                           curvatures="exact")

    fmu = write_drivetrain_fmu(model("reference"), tmp_path, pair_name="s0003_edited",
                               side=base.mesh.side, bending=False,
                               header_dir=fmi3_header_dir()).fmu_path
    twin = simulate(model(twin_backend), speed_rpm=SPEED_RPM, duration_s=DURATION_S,
                    step_s=1e-6 * STEP_US)
    res = _fmu_run(fmu, backend)
    n = twin.summary["steps"]
    assert n == 800 and len(res) == n + 1
    _assert_reproduces(res, twin, n, backend)
    _assert_counts(res, twin, n)
    assert all(twin.summary[name] > 0 for name in COUNTS), twin.summary


def test_fmu_static_start_is_the_balance(exported):
    """Independent of the twin: at t = 0 the members turn at the nominal speeds (pinion
    speed_rpm, gear speed_rpm / u: the pinion's 1e-12 relative) and, at rest (speed 0:
    no mesh damping torque), the mesh carries the load torque (the static point,
    bisection to 1e-15: 1e-9 relative)."""
    fmu, _ = exported
    res = _fmu_run(fmu, "fp64")
    assert res["pinion_speed_rpm"][0] == pytest.approx(SPEED_RPM, rel=1e-12)
    rest = fmpy.simulate_fmu(str(fmu), stop_time=1e-4, output_interval=1e-5,
                             start_values={"speed_rpm": 0.0})
    assert rest["mesh_torque_nm"][0] == pytest.approx(TORQUE_NM, rel=1e-9)
    assert rest["pinion_speed_rpm"][0] == 0.0


def _refusal(fmu, start):
    """The log messages of an FMPy run whose fmi3ExitInitializationMode fails."""
    messages = []
    with pytest.raises(fmpy.fmi1.FMICallException, match="ExitInitializationMode"):
        fmpy.simulate_fmu(str(fmu), stop_time=1e-3, output_interval=5e-5,
                          start_values=start,
                          logger=lambda env, status, cat, msg: messages.append(msg.decode()))
    return messages


@pytest.mark.parametrize("start, words", [
    ({"step_us": 0.5}, ("step_us = 0.5", "[1, 50]")),
    ({"speed_rpm": 2e5}, ("speed_rpm = 200000", "[0, 100000]")),
    ({"torque_nm": -1.0}, ("torque_nm = -1", "(0, 5]")),
    # above the export torque the table's edge-pair fields (sized at it) no longer cover
    # the contact: refused, not run on a table out of its range
    ({"torque_nm": 5.5}, ("torque_nm = 5.5", "(0, 5]", "--torque 5.5")),
    ({"torque_nm": 100.0, "step_us": 50.0}, ("torque_nm = 100", "(0, 5]")),
])
def test_fmu_refuses_bad_parameters(exported, start, words):
    """fmi3ExitInitializationMode fails with one log message naming the parameter, its
    value and the allowed range (the twin's checks: simulate, check_step; the torque
    at most the export torque, the table's size)."""
    fmu, _ = exported
    messages = _refusal(fmu, start)
    assert len(messages) == 1 and all(w in messages[0] for w in words), messages


def test_fmu_torque_range_is_the_variables_max(exported):
    """The modelDescription says the range too: torque_nm's max is the export torque,
    the start value; the FMU runs at it (the edge of the range is inside)."""
    fmu, _ = exported
    md = fmpy.read_model_description(str(fmu))
    var = next(v for v in md.modelVariables if v.name == "torque_nm")
    assert float(var.max) == TORQUE_NM == float(var.start)
    res = fmpy.simulate_fmu(str(fmu), stop_time=2e-4, output_interval=1e-5,
                            output=["mesh_force_n"], start_values={"torque_nm": TORQUE_NM})
    assert res["mesh_force_n"][-1] > 0.0


@pytest.mark.slow
def test_fmu_refuses_a_step_beyond_the_rk4_bound(tmp_path):
    """In the torque range, beyond the RK4 bound h omega_max <= 2: the mesh stiffens
    with the load (omega ~ W^(1/6)); s0003 (9 phases) at 50 N.m has h omega_max = 1.93
    at 50 us (gearcontact.twin.statics.check_step), at 100 N.m 1.93 * 2^(1/6) = 2.17:
    an export at 100 N.m refuses 50 us (the default export of 5 N.m cannot reach it)."""
    run = _cli("--pair", "s0003", "--kind", "drivetrain", "--phases", "9", "--torque",
               "100", "--out", str(tmp_path), cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    messages = _refusal(tmp_path / "gearcontact_drivetrain_s0003.fmu", {"step_us": 50.0})
    assert len(messages) == 1 and "step_us = 50" in messages[0] \
        and "RK4 stability" in messages[0], messages


def test_two_exports_write_the_same_fmu(tmp_path):
    """Identical runs write identical files: two ``export fmu --kind drivetrain`` in
    separate processes (other addresses) give the same .fmu, byte for byte -- its
    instantiation token is a digest of the baked data, and an absent array (no bending)
    once digested as the address of None. 5 phases: the cheapest table (~10 s)."""
    runs = []
    for name in ("a", "b"):
        run = _cli("--pair", "s0003", "--kind", "drivetrain", "--phases", "5",
                   "--out", str(tmp_path / name), cwd=tmp_path)
        assert run.returncode == 0, run.stderr
        runs.append((tmp_path / name / "gearcontact_drivetrain_s0003.fmu").read_bytes())
    assert runs[0] == runs[1]


def test_fmu_refuses_a_communication_step_off_the_grid(exported):
    fmu, _ = exported
    messages = []
    with pytest.raises(fmpy.fmi1.FMICallException, match="DoStep"):
        fmpy.simulate_fmu(str(fmu), stop_time=1e-3, output_interval=2.5e-5,
                          start_values={"step_us": 10.0},
                          logger=lambda env, status, cat, msg: messages.append(msg.decode()))
    assert "whole number of internal steps" in messages[0]


def test_fmu_runs_without_gearcontact(exported):
    """The FMU simulates in a Python process where gearcontact cannot be imported, with
    the very numbers of this process's FMPy run (same binary: identical)."""
    fmu, _ = exported
    here = _fmu_run(fmu, "golden")
    there = simulate_isolated(fmu, start_time=0.0, stop_time=DURATION_S,
                              output_interval=1e-6 * STEP_US, output=list(PAIRS),
                              start_values={"backend": 1, "speed_rpm": SPEED_RPM,
                                            "step_us": STEP_US})
    for name in PAIRS:
        np.testing.assert_array_equal(there[name], np.asarray(here[name], float),
                                      err_msg=name)


def test_docs_snippet_reproduces_the_twin(exported, twin_models, capsys):
    """The FMPy snippet of docs/export.md ("The drivetrain twin as an FMI 3.0 FMU") on
    this module's FMU: its DTE peak-to-peak, largest mesh force and peak pressure over
    the 501 points 0 .. 5 ms equal the twin's over 501 steps of 10 us at 3000 rpm
    (fp64: 1e-9 relative, the equivalence bound above; measured identical)."""
    from gearcontact.twin.simulate import simulate

    fmu, _ = exported
    text = (ROOT / "docs" / "export.md").read_text()
    part = text.split("# The drivetrain twin as an FMI 3.0 FMU", 1)[1]
    snippet = part.split("## Use from FMPy", 1)[1].split("```python\n", 1)[1].split("```")[0]
    assert "twin_fmu/gearcontact_drivetrain_s0003.fmu" in snippet
    exec(compile(snippet.replace("twin_fmu/gearcontact_drivetrain_s0003.fmu", str(fmu)),
                 "export.md", "exec"), {})
    dte_pp, force_max, p_max = (float(v) for v in capsys.readouterr().out.split())
    twin = simulate(twin_models["fp64"], speed_rpm=3000.0, duration_s=5.01e-3, step_s=1e-5)
    assert twin.summary["steps"] == 501
    c = twin.columns
    assert dte_pp == pytest.approx(np.ptp(c["te_arcsec"]), rel=1e-9, abs=0.0)
    assert force_max == pytest.approx(c["mesh_load_n"].max(), rel=1e-9, abs=0.0)
    assert p_max == pytest.approx(c["p_max_mpa"].max(), rel=1e-9, abs=0.0)


def assert_twin_csv(res, rows, columns, backend: str) -> None:
    """The FMU's outputs ``res`` against a twin.csv's ``rows`` (FMU output -> CSV column
    in ``columns``): golden and the pair count printed as the file prints them (12
    significant digits, ``tca.export.write_csv``) and equal to its text, fp64 within
    1e-9 relative (the issue's bound)."""
    for out, col in columns.items():
        text = [row[col] for row in rows]
        if backend == "golden" or out == "pairs_loaded":
            fmt = [str(int(v)) if out == "pairs_loaded" else f"{v:.12g}" for v in res[out]]
            assert fmt == text, out
        else:
            np.testing.assert_allclose(res[out], np.array(text, float), rtol=1e-9,
                                       atol=0.0, err_msg=out)


@pytest.mark.slow
def test_done_when_the_readme_fmu_reproduces_the_twin_cli(readme_export, tmp_path):
    """Issue 25's "Done when" as a twin developer runs it: the README's FMU
    (``gearcontact export fmu --pair s0003 --kind drivetrain --out twin_fmu/``, default
    options: 61 phases, 64.5 N.m), FMPy in a process where gearcontact cannot be
    imported -- the docs' snippet as written, in the README's directory, and every
    output in both backends at the FMU's start values (3000 rpm, 10 us) -- against the
    console script ``gearcontact twin --pair s0003 --duration 0.00501 --backend
    reference|golden`` (the same pair, side, phases, torque, speed, step: 501 steps).
    Truth: the twin's record as its twin.csv prints it, 12 significant digits
    (``tca.export.write_csv``): golden identical (the FMU's value printed the same way
    is the file's text), fp64 within 1e-9 relative (the issue's bound; the CSV's
    rounding, <= 5e-13 relative, is inside it); the snippet's three figures within
    1e-9 of the same from the CSV (a peak-to-peak of ~9 arcsec from values ~60: the
    CSV's rounding ~1e-11 of it) and the figures the docs state (their 3 or 4
    digits); the domain counts after the 501 steps equal twin.json's (exact).
    Measured: every value of both backends equal at the CSV's 12 digits.
    ~1-2 min: two twin runs, each with its 61-phase TCA of both sides."""
    base, lines, runs = readme_export
    line = next(x for x in lines["export_fmu"] if "--kind drivetrain" in x)
    assert runs[line].returncode == 0, runs[line].stderr
    fmu = base / "twin_fmu" / "gearcontact_drivetrain_s0003.fmu"
    twin = {}
    for backend in ("fp64", "golden"):
        name = "reference" if backend == "fp64" else backend
        run = _shell(f"gearcontact twin --pair s0003 --out tw_{name} --duration 0.00501 "
                     f"--backend {name} --no-figures --quiet", tmp_path)
        assert run.returncode == 0, run.stderr[-2000:]
        with open(tmp_path / f"tw_{name}" / "twin.csv", newline="") as f:
            twin[backend] = list(csv.DictReader(f))
        assert len(twin[backend]) == 501
        res = simulate_isolated(fmu, start_time=0.0, stop_time=5e-3, output_interval=1e-5,
                                output=list(PAIRS),
                                start_values={"backend": BACKENDS[backend]})
        assert len(res["time"]) == 501
        assert_twin_csv(res, twin[backend], PAIRS, backend)
        # issue 27: the FMU's domain counts after the twin's 501 steps are its twin.json's
        # (exact: integers counting the same previews; measured 5, 5, 0 in both)
        counts = simulate_isolated(fmu, start_time=0.0, stop_time=5.01e-3,
                                   output_interval=1e-5, output=list(COUNTS),
                                   start_values={"backend": BACKENDS[backend]})
        summary = json.loads((tmp_path / f"tw_{name}" / "twin.json").read_text())
        assert len(counts["time"]) == 502
        assert {n: int(counts[n][-1]) for n in COUNTS} == {n: summary[n] for n in COUNTS}
    dte_pp, force_max, p_max = (float(v) for v in run_isolated(
        docs_snippet("The drivetrain twin as an FMI 3.0 FMU"), base).splitlines()[-1].split())
    c = {k: np.array([float(r[k]) for r in twin["fp64"]])
         for k in ("te_arcsec", "mesh_load_n", "p_max_mpa")}
    assert dte_pp == pytest.approx(np.ptp(c["te_arcsec"]), rel=1e-9, abs=0.0)
    assert force_max == pytest.approx(c["mesh_load_n"].max(), rel=1e-9, abs=0.0)
    assert p_max == pytest.approx(c["p_max_mpa"].max(), rel=1e-9, abs=0.0)
    text = (ROOT / "docs" / "export.md").read_text()
    stated = re.search(r"with\s+the default export \(61 phases, 64.5 N·m\) ([\d.]+) "
                       r"arcsec, (\d+) N and (\d+) MPa", text)
    assert stated, "the docs' stated figures"
    assert (f"{dte_pp:.2f}", f"{force_max:.0f}", f"{p_max:.0f}") == stated.groups()


@pytest.fixture(scope="module")
def rattle_fmu(tmp_path_factory):
    base = tmp_path_factory.mktemp("rattle")
    (base / "dt.toml").write_text("[drivetrain]\nbacklash_mm = 0.0095\n")
    run = _cli("--pair", "s0003-centred", "--side", "drive", "--kind", "drivetrain",
               "--curvatures", "exact", "--phases", "9", "--torque", "0.5", "--drivetrain", str(base / "dt.toml"),
               "--out", str(base / "o"), cwd=base)
    assert run.returncode == 0, run.stderr
    return base / "o" / "gearcontact_drivetrain_s0003_centred.fmu", base / "dt.toml"


@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_fmu_reproduces_the_twin_through_rattle(rattle_fmu, backend):
    """The reverse flank's own law (s0003-centred, drive side loaded: its coast side has
    a contact ellipse, so the twin runs that side's own TCA, its phase and closure), with
    the TCA's curvatures (``--curvatures exact``), through contact loss and back-flank
    impacts: 0.5 N.m, the backlash 0.0095 mm just clearing the flanks' 9.48 um
    interference, 14000 rpm, 2000 steps of 5 us. Measured
    in the twin: 161 steps on the reverse flank (mesh torque < 0), 440 in free flight.
    Same tolerances as above; measured identical. ~30 s (both sides' TCA at export and
    in the twin)."""
    from gearcontact.tca.synthesis import prepare_pair
    from gearcontact.twin.params import load_drivetrain
    from gearcontact.twin.simulate import model_for_pair, simulate

    fmu, dt_file = rattle_fmu
    res = fmpy.simulate_fmu(str(fmu), stop_time=1e-2, output_interval=5e-6,
                            output=[*PAIRS, *COUNTS], start_values={
                                "backend": BACKENDS[backend], "speed_rpm": 14000.0,
                                "step_us": 5.0})
    prepared = prepare_pair("s0003-centred", side="drive")
    model = model_for_pair(prepared.pair, torque_nm=0.5, side="drive", phases=9,
                           backend="reference" if backend == "fp64" else "golden",
                           drivetrain=load_drivetrain(dt_file, prepared.pair),
                           curvatures="exact")
    assert model.reverse is not None            # the own law, not the mirror
    twin = simulate(model, speed_rpm=14000.0, duration_s=1e-2, step_s=5e-6)
    n = twin.summary["steps"]
    assert n == 2000 and len(res) == n + 1
    _assert_reproduces(res, twin, n, backend)
    _assert_counts(res, twin, n)
    torque = np.asarray(res["mesh_torque_nm"])
    assert (torque < 0.0).sum() > 50 and (torque == 0.0).sum() > 100


@pytest.mark.slow
@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_fmu_reproduces_the_twin_with_tooth_bending(tmp_path_factory, backend):
    """``gearcontact export fmu --kind drivetrain --bending`` against ``gearcontact twin
    --bending`` (the same model call with ``bending=True``): the pairs' bending
    compliance in series with the Hertzian law, Newton on W^(1/3) from each pair's last
    root. s0003, 9 phases, 64.5 N.m, 3000 rpm, 600 steps of 10 us: past the twin's
    blocks of 256 steps, where its Newton starts afresh (the FMU restarts with it).
    Tolerances as above (fp64 1e-9 relative, golden identical); measured identical in
    both. The bending is in the run: the twin's rigid model (the same tables, zero
    compliance) turns the mesh less by over 10 %. ~1 min (the shell model of both
    teeth at export and in the twin)."""
    import dataclasses

    from gearcontact.tca.synthesis import prepare_pair
    from gearcontact.twin.model import build_model, model_for_pair
    from gearcontact.twin.simulate import simulate

    base = tmp_path_factory.mktemp("bending")
    run = _cli("--pair", "s0003", "--kind", "drivetrain", "--bending", "--phases", "9",
               "--out", str(base), cwd=base)
    assert run.returncode == 0, run.stderr
    res = fmpy.simulate_fmu(str(base / "gearcontact_drivetrain_s0003.fmu"), stop_time=6e-3,
                            output_interval=1e-5, output=[*PAIRS, *COUNTS],
                            start_values={"backend": BACKENDS[backend]})
    prepared = prepare_pair("s0003")
    model = model_for_pair(prepared.pair, torque_nm=64.5, side=prepared.side, phases=9,
                           backend="reference" if backend == "fp64" else "golden",
                           bending=True)
    twin = simulate(model, speed_rpm=3000.0, duration_s=6e-3, step_s=1e-5)
    n = twin.summary["steps"]
    assert n == 600 and len(res) == n + 1 and twin.summary["bending"]
    _assert_reproduces(res, twin, n, backend)
    _assert_counts(res, twin, n)
    def rigid(mesh):
        return None if mesh is None else dataclasses.replace(
            mesh, bending_mm_per_n=np.zeros_like(mesh.bending_mm_per_n))

    rigid_model = build_model(rigid(model.mesh), model.drivetrain, 64.5,
                              backend=model.backend, reverse=rigid(model.reverse),
                              reverse_note=model.reverse_note, curvatures=model.curvatures)
    theta_rigid = simulate(rigid_model, speed_rpm=3000.0, duration_s=6e-3,
                           step_s=1e-5).columns["theta_rad"]
    assert np.mean(res["mesh_rotation_rad"][:n]) > 1.1 * np.mean(theta_rigid)


def _run_harness(fmu, tmp_path, harness: str, name: str, flags=()) -> str:
    """The stdout of ``harness`` (C including ``gc_contact_law.c``) built as the FMU's
    binary is (:data:`gearcontact.export.fmu.FMU_CFLAGS`, plus ``flags``) from the
    sources inside ``fmu`` and the preview library."""
    import shutil
    import subprocess

    from gearcontact.export.fmu import FMU_CFLAGS

    if shutil.which("gcc") is None:
        pytest.skip("gcc is needed")
    src = tmp_path / "src"
    if not src.exists():
        src.mkdir()
        with zipfile.ZipFile(fmu) as z:
            for entry in z.namelist():
                if entry.startswith("sources/") and entry.endswith((".c", ".h")):
                    (src / Path(entry).name).write_bytes(z.read(entry))
    (src / f"{name}.c").write_text(harness)
    library = [str(p) for p in sorted(src.glob("gc_*.c"))
               if p.name not in ("gc_contact_law.c", "gc_drivetrain_fmu.c")]
    exe = tmp_path / name
    run = subprocess.run(["gcc", *FMU_CFLAGS, *flags, f"-I{src}", "-o", str(exe),
                          str(src / f"{name}.c"), *library, "-lm"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, (name, run.stderr)
    return subprocess.run([str(exe)], capture_output=True, text=True, timeout=120,
                          check=True).stdout


#: Harness of :func:`test_stencil_gap_codes_are_the_twin_quantization`: gc_contact_law.c's
#: static gap_codes on xorshift rows (magnitudes 2^-25 .. 2^12 mm, a sample beyond
#: STENCIL_GAP's +-1024 mm, an infinity or a NaN now and then, fractions in [0, 1] with both ends),
#: each vector printed as f, the rows and the result in hexadecimal floats and integers;
#: every fourth vector within +-256 mm (+-256 itself now and then, fractions a few ulp
#: beyond [0, 1] too) also through the unchecked lanes (checked 0, the drivetrain FMU's
#: CV_IN_RANGE), printed after "U". The rows as gc_law_kappa_stencil's (the samples, then
#: c3..c5, here xorshift values with an infinity or a NaN now and then: the unchecked
#: lanes read the first of them beside the last sample and discard it).
_GAP_HARNESS = r"""
#include <stdio.h>
#include "gc_contact_law.c"

static uint64_t x = 88172645463325252u;
static uint64_t next(void) { x ^= x << 13; x ^= x >> 7; x ^= x << 17; return x; }
static double unit(void) { return (double)(next() >> 11) / 9007199254740992.0; }

static double sample(void)
{
    if (next() % 1000u == 0u)
        return next() % 2u ? INFINITY : NAN;
    return (unit() - 0.5) * ldexp(1.0, (int)(next() % 38u) - 25);
}

/* within +-256 mm, the bound of the unchecked lanes */
static double sample_in_range(void)
{
    if (next() % 50u == 0u)
        return next() % 2u ? 256.0 : -256.0;
    return (unit() - 0.5) * ldexp(1.0, (int)(next() % 35u) - 25);
}

int main(void)
{
    double r0[GC_FIT_TAPS + 3], r1[GC_FIT_TAPS + 3], f;
    int32_t codes[GC_FIT_TAPS + 1];
    int v, q, ok, in_range;
    for (v = 0; v < 3000; ++v) {
        in_range = v % 4 == 2;
        for (q = GC_FIT_TAPS; q < GC_FIT_TAPS + 3; ++q) {   /* the row's c3..c5 */
            r0[q] = sample();
            r1[q] = sample();
        }
        for (q = 0; q < GC_FIT_TAPS; ++q) {
            r0[q] = in_range ? sample_in_range() : sample();
            r1[q] = v % 3 == 0 ? r0[q] + ldexp(unit() - 0.5, -12)
                    : in_range ? sample_in_range() : sample();
            if (in_range && fabs(r1[q]) > 256.0)
                r1[q] = r0[q];
        }
        f = v % 5 == 0 ? (double)(v % 2) : unit();
        if (in_range && v % 3 != 0)
            f = v % 3 == 1 ? -0x1p-50 : 1.0 + 0x1p-50;
        ok = gap_codes(r0, r1, f, 1, codes);
        printf("%a %d", f, ok);
        for (q = 0; q < GC_FIT_TAPS; ++q)
            printf(" %a %a %ld", r0[q], r1[q], ok ? (long)codes[q] : 0L);
        if (in_range) {
            ok = gap_codes(r0, r1, f, 0, codes);
            printf(" U %d", ok);
            for (q = 0; q < GC_FIT_TAPS; ++q)
                printf(" %ld", (long)codes[q]);
        }
        printf("\n");
    }
    return 0;
}
"""


def test_stencil_gap_codes_are_the_twin_quantization(exported, tmp_path):
    """The golden stencil's STENCIL_GAP codes (gc_contact_law.c's gap_codes: two samples
    per SSE2 instruction, or one by one with -DGC_SCALAR_LANES, the code other targets
    get) equal the twin's quantization computed here in Python's doubles, the operations
    of :func:`gearcontact.twin.contact_law._kappa`: ``floor((r0 + f (r1 - r0)) 2^21 +
    1/2)`` (STENCIL_GAP Q(32,21)), flagged where a sample lies outside [-2^31, 2^31)
    codes (or is not a number), on 3,000 vectors of 49 samples; the unchecked lanes
    (the drivetrain FMU's CV_IN_RANGE: no range test) give the same codes on the 750
    vectors within +-256 mm, fractions a few ulp beyond [0, 1] included. Exact: the
    same IEEE operations."""
    fmu, _ = exported
    outputs = {flavour: _run_harness(fmu, tmp_path, _GAP_HARNESS, flavour, flags)
               for flavour, flags in (("sse2", []), ("scalar", ["-DGC_SCALAR_LANES"]))}
    assert outputs["sse2"] == outputs["scalar"]
    flagged = unchecked = 0
    for line in outputs["sse2"].splitlines():
        words = line.split()
        if "U" in words:            # the unchecked lanes: never flagged, the same codes
            u = words.index("U")
            assert words[u + 1] == "1" and words[1] == "1", line[:80]
            assert words[u + 2:] == words[4:u:3], line[:80]
            unchecked += 1
        f, ok = float.fromhex(words[0]), int(words[1])
        want, bad = [], False
        for q in range(49):
            r0, r1 = float.fromhex(words[2 + 3 * q]), float.fromhex(words[3 + 3 * q])
            t = (r0 + f * (r1 - r0)) * 2.0 ** 21 + 0.5
            bad |= not (-2.0 ** 31 <= t < 2.0 ** 31)
            want.append(math.floor(t) if not bad else 0)
        assert ok == (not bad), line[:80]
        flagged += bad
        if ok:
            assert [int(words[4 + 3 * q]) for q in range(49)] == want
    assert 100 < flagged < 2900           # both outcomes exercised
    assert unchecked == 750


#: Harness of :func:`test_golden_kappa_is_the_twin_bit_for_bit`: gc_contact_law.c's
#: static kappa_golden (stage D's codes, the preview's load and kappa from the library's
#: cube root) on xorshift operands: curvature codes log-uniform over the datapath's
#: range and a little beyond (flagged), loads over [1, 2^17] N (the twin's evaluation
#: envelope) and E' codes over theirs; printed as integers and hexadecimal floats.
_KAPPA_HARNESS = r"""
#include <stdio.h>
#include "gc_contact_law.c"

static uint64_t x = 88172645463325252u;
static uint64_t next(void) { x ^= x << 13; x ^= x >> 7; x ^= x << 17; return x; }
static double unit(void) { return (double)(next() >> 11) / 9007199254740992.0; }

int main(void)
{
    double out[4], kap, we;
    int32_t a, b, t, e;
    int v;
    for (v = 0; v < 125000; ++v) {
        a = (int32_t)ldexp(1.0, 8 + (int)(16.2 * unit())) + (int32_t)(next() % 256u);
        b = (int32_t)ldexp(1.0, 8 + (int)(16.2 * unit())) + (int32_t)(next() % 256u);
        if (a > b) { t = a; a = b; b = t; }
        if (v % 8 != 0 && b > 8 * a)        /* mostly below alpha_max: few flagged */
            b = a + (int32_t)(next() % (uint32_t)(7 * a));
        we = v % 97 == 0 ? (v % 2 ? 1.0 : 131072.0) : exp(unit() * 11.783);
        e = 4096 + (int32_t)(next() % 2093057u);
        out[0] = out[1] = out[2] = out[3] = 0.0;
        kap = kappa_golden(a, b, we, e, out);
        printf("%d %d %a %d %a %a %a %a %a\n", a, b, we, e, kap, out[0], out[1], out[2],
               out[3]);
    }
    return 0;
}
"""


def test_golden_kappa_is_the_twin_bit_for_bit(exported, tmp_path):
    """The golden law's kappa in the FMU's C (gc_contact_law.c's kappa_golden: stage D,
    then ``3 F W^(1/3) / (pi a E')`` with the library's cube root ``gc_cbrt_positive``)
    equals the twin's compiled :func:`gearcontact.twin.contact_law._kappa_golden` bit
    for bit, kappa and (a, b, p_max, load), on 125,000 operands of which >= 100,000 in
    the datapath's domain (the others flagged, -1 on both sides). Exact: stage D is
    integer arithmetic, the rest the same IEEE operations in the same order (no FMA)."""
    from gearcontact.preview.fit.golden import element_constants
    from gearcontact.preview.fit.pinv import N_COEFFS, N_TAPS
    from gearcontact.preview.hertz.golden_vec import golden_constants
    from gearcontact.twin import kernel as K
    from gearcontact.twin.contact_law import _kappa_golden

    fmu, _ = exported
    lines = _run_harness(fmu, tmp_path, _KAPPA_HARNESS, "kappa").splitlines()
    pow_lut, cbrt_lut, cst = golden_constants()
    fit = (*element_constants(), np.zeros((1, N_TAPS), np.int64),
           np.zeros((1, N_COEFFS), np.int64), np.zeros((0, N_TAPS), np.int64))
    trace, tcount, prm = np.zeros((0, 9), np.int64), np.zeros(K.N_COUNT, np.int64), \
        np.zeros(K.N_PRM)
    out, load, valid = np.zeros(K.N_PREVIEW), K.PV_LOAD, 0
    for line in lines:
        w = line.split()
        prm[K.P_ECODE] = int(w[3])
        want = _kappa_golden(int(w[0]), int(w[1]), 0, float.fromhex(w[2]), prm, pow_lut,
                             cbrt_lut, cst, trace, tcount, fit, out)
        assert float.fromhex(w[4]) == want, line
        if want > 0.0:
            assert [float.fromhex(s) for s in w[5:]] == [out[0], out[1], out[2], out[load]], line
            valid += 1
    assert len(lines) == 125_000 and valid >= 100_000, valid


@pytest.mark.slow
def test_fmu_of_a_machine_settings_pair_reproduces_the_twin(tmp_path):
    """``gearcontact export fmu --kind drivetrain`` on the pair whose flanks are cut
    from machine settings (examples/machine_settings/iso23509_f2_machine.toml; issue 27
    item 1) against ``gearcontact twin`` on it (the library call, the pair prepared as
    the CLI prepares it), 9 phases, the default torque, speed, step and curvature source
    (stencil), 300 steps: every output at every communication point, fp64 within 1e-9
    relative and golden identical (the bounds above). Every preview of F.2 lies outside
    the fixed-point domain (its lengthwise curvature below the least code,
    tests/twin/test_machine_pair.py): the FMU's golden backend runs them on the fp64
    law as the twin does, so both backends reproduce the twin's fp64 trajectory.
    ~15 s (the TCA of both sides, the C compiled at export)."""
    from gearcontact.tca.synthesis import prepare_pair
    from gearcontact.twin.model import model_for_pair
    from gearcontact.twin.simulate import simulate

    src = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"
    run = _cli("--pair", str(src), "--kind", "drivetrain", "--phases", "9", "--out",
               str(tmp_path), cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    fmu = tmp_path / "gearcontact_drivetrain_iso23509_f2_machine.fmu"
    prepared = prepare_pair(str(src))
    assert not prepared.synthesized and len(prepared.pair.machine) == 4
    twins = {}
    for backend, twin_backend in (("fp64", "reference"), ("golden", "golden")):
        model = model_for_pair(prepared.pair, torque_nm=64.5, backend=twin_backend,
                               side=prepared.side, phases=9, curvatures="stencil")
        twin = simulate(model, speed_rpm=3000.0, duration_s=3e-3, step_s=1e-5)
        n = twin.summary["steps"]
        res = fmpy.simulate_fmu(str(fmu), stop_time=3e-3, output_interval=1e-5,
                                output=[*PAIRS, *COUNTS],
                                start_values={"backend": BACKENDS[backend]})
        assert n == 300 and len(res) == n + 1
        _assert_reproduces(res, twin, n, backend)
        assert twin.summary["steps_outside_datapath"] == n
        # issue 27: the FMU says so too, counting as the twin (every step; its previews)
        _assert_counts(res, twin, n)
        assert twin.summary["previews_outside_datapath"] >= n
        twins[backend] = twin
    for name in ("theta_rad", "mesh_load_n"):
        np.testing.assert_array_equal(twins["golden"].columns[name],
                                      twins["fp64"].columns[name])
    # a loaded run: the mesh carries the torque on average
    assert 0.5 * 64.5 < np.mean(twins["fp64"].columns["mesh_torque_nm"]) < 1.5 * 64.5
