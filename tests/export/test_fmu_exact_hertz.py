"""``gearcontact export fmu --hertz-form exact``: the FMUs with the twin's exact Hertz law.

Truth: ``gearcontact twin --hertz-form exact`` itself (:func:`gearcontact.twin.model.
model_for_pair` with ``hertz_form="exact"`` and :func:`gearcontact.twin.simulate.
simulate`, the CLI's two library calls) for the drivetrain FMU; the twin's compiled
law at the inputs FMPy fed the mesh FMU (:func:`gearcontact.export.mesh_law.
mesh_outputs` on the table it baked) and, independent of both, exact elliptic Hertz
with scipy's Carlson integrals (:func:`gearcontact.analytic.hertz.exact_elliptic_hertz`)
at the pair's interpolated curvatures and load; FMPy's FMI 3.0 schema validation. Both
FMUs are exported once per module the way a user does (a real subprocess of ``python
-m gearcontact``, s0003 with 9 phases; the drivetrain with the settings of
tests/export/test_fmu_drivetrain.py), ~15 s each.
"""

from __future__ import annotations

import ctypes
import shutil
import subprocess
import zipfile

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
from fmpy.validation import validate_fmu  # noqa: E402

from gearcontact.analytic.hertz import exact_elliptic_hertz  # noqa: E402
from gearcontact.export.c_library import EXACT_FILES  # noqa: E402
from gearcontact.export.mesh_law import (BACKENDS, MeshLawTable, _kinematics,  # noqa: E402
                                         closed_pairs, mesh_outputs)
from gearcontact.twin.exact_hertz import REL_BOUND  # noqa: E402
from gearcontact.validation import InputRangeError  # noqa: E402

from .conftest import export_fmu_cli as _cli  # noqa: E402
from .test_c_exact_hertz import E_PRIME  # noqa: E402
from .test_fmu import INPUTS, _assert_law, _sweep  # noqa: E402
from .test_fmu_cylindrical import EV  # noqa: E402
from .test_fmu_drivetrain import (DURATION_S, SPEED_RPM, STEP_US, TORQUE_NM,  # noqa: E402
                                  _assert_counts, _assert_reproduces, _fmu_run,
                                  export_s0003)


@pytest.fixture(scope="module")
def mesh_exact(tmp_path_factory):
    out = tmp_path_factory.mktemp("fmu_exact") / "s0003"
    run = _cli("--pair", "s0003", "--kind", "mesh", "--phases", "9", "--hertz-form",
               "exact", "--out", str(out), cwd=out.parent)
    assert run.returncode == 0, run.stderr
    return out, MeshLawTable.from_npz(out / "gearcontact_mesh_s0003_table.npz")


@pytest.fixture(scope="module")
def drivetrain_exact(tmp_path_factory):
    return export_s0003(tmp_path_factory.mktemp("fmu_dt_exact"), "--hertz-form", "exact")


def test_exact_fmus_validate_and_carry_the_exact_law(mesh_exact, drivetrain_exact):
    mesh_dir, tab = mesh_exact
    assert tab.hertz_form == "exact"
    for fmu in (mesh_dir / "gearcontact_mesh_s0003.fmu", drivetrain_exact[0]):
        assert validate_fmu(str(fmu)) == []
        names = set(zipfile.ZipFile(fmu).namelist())
        assert {f"sources/{name}" for name in EXACT_FILES} <= names
        assert "exact Hertz" in fmpy.read_model_description(str(fmu)).description


@pytest.mark.parametrize("fmi_type", ["CoSimulation", "ModelExchange"])
def test_mesh_fmu_equals_the_twin_exact_law(mesh_exact, fmi_type):
    """Every output at every recorded instant equals the twin's compiled exact law at
    the inputs the FMU held then, within 1e-9 relative: the tolerance of the
    Hamrock-Brewe mesh FMU against the same law (tests/export/test_fmu.py), for the same
    reason (the C repeats the law's operations in the same order on the same table
    doubles; room for another libm's log/exp/cbrt by a few ulp, amplified by W =
    (d/kappa)^(3/2) and the cancellation in theta, <= 1e-10)."""
    mesh_dir, tab = mesh_exact
    res = _sweep(mesh_dir / "gearcontact_mesh_s0003.fmu", tab, "fp64", fmi_type)
    _assert_law(res, tab, "fp64")
    assert res["active_pairs"].max() >= 2 and res["torque_gear_nm"].max() > 64.5


def test_mesh_fmu_semi_axes_and_pressure_are_exact_hertz(mesh_exact):
    """Independent of the twin: at every instant with one loaded pair, the FMU's a, b,
    p_max are exact elliptic Hertz (scipy) at the pair's interpolated curvatures and
    its load (mesh_force_n), within REL_BOUND = 1e-8 (the table's declared bound, see
    tests/export/test_c_exact_hertz.py; the similarity scaling W^(1/3) from the unit
    load adds a few ulp)."""
    mesh_dir, tab = mesh_exact
    res = _sweep(mesh_dir / "gearcontact_mesh_s0003.fmu", tab, "fp64", "CoSimulation")
    worst, single = 0.0, 0
    for row in res:
        if row["active_pairs"] != 1:
            continue
        i, f, _, theta, _, _ = _kinematics(tab, *(float(row[n]) for n in INPUTS))
        (j, _, _), = list(closed_pairs(tab, i, f, theta))
        A = tab.A_minus_per_mm[j, i] + f * (tab.A_minus_per_mm[j, i + 1]
                                            - tab.A_minus_per_mm[j, i])
        B = tab.B_minus_per_mm[j, i] + f * (tab.B_minus_per_mm[j, i + 1]
                                            - tab.B_minus_per_mm[j, i])
        ex = exact_elliptic_hertz(min(A, B), max(A, B), float(row["mesh_force_n"]),
                                  e_prime_mpa=tab.e_prime_mpa)
        worst = max(worst, abs(row["a_mm"] / ex.a_mm - 1.0), abs(row["b_mm"] / ex.b_mm - 1.0),
                    abs(row["p_max_mpa"] / ex.p_max_mpa - 1.0))
        single += 1
    assert single > 20 and worst < REL_BOUND, (single, worst)


def test_exact_fmus_refuse_the_golden_backend(mesh_exact, drivetrain_exact):
    """The golden stage D is Hamrock-Brewe's: an exact FMU refuses backend 1 with one
    log message naming it and the way out (the twin refuses --backend golden with
    --hertz-form exact); the Python law likewise."""
    for fmu in (drivetrain_exact[0], mesh_exact[0] / "gearcontact_mesh_s0003.fmu"):
        messages = []
        with pytest.raises(fmpy.fmi1.FMICallException, match="fmi3SetInt64"):
            fmpy.simulate_fmu(str(fmu), stop_time=1e-3, output_interval=5e-5,
                              start_values={"backend": BACKENDS["golden"]},
                              logger=lambda env, status, cat, msg: messages.append(
                                  msg.decode()))
        assert len(messages) == 1 and "backend = 1 (golden)" in messages[0] \
            and "--hertz-form hamrock-brewe" in messages[0], messages
    with pytest.raises(InputRangeError, match="backend.*fp64"):
        mesh_outputs(mesh_exact[1], 0.0, 0.0, 0.0, 0.0, backend="golden")


@pytest.fixture(scope="module")
def twin_exact(drivetrain_exact):
    """``gearcontact twin --pair s0003 --phases 9 --torque 5 --drivetrain dt.toml
    --hertz-form exact --speed-rpm 20000 --step-us 5 --duration-ms 4`` by its library
    calls, and the same run with Hamrock-Brewe (the forms must differ for the test to
    say anything)."""
    from gearcontact.tca.synthesis import prepare_pair
    from gearcontact.twin.params import load_drivetrain
    from gearcontact.twin.simulate import model_for_pair, simulate

    prepared = prepare_pair("s0003")
    drivetrain = load_drivetrain(drivetrain_exact[1], prepared.pair)
    return {form: simulate(model_for_pair(prepared.pair, torque_nm=TORQUE_NM,
                                          backend="reference", drivetrain=drivetrain,
                                          side=prepared.side, phases=9,
                                          curvatures="stencil", hertz_form=form,
                                          flanks=prepared.flank_set()),
                           speed_rpm=SPEED_RPM, duration_s=DURATION_S, step_s=1e-6 * STEP_US)
            for form in ("exact", "hamrock-brewe")}


def test_drivetrain_fmu_reproduces_the_exact_twin(drivetrain_exact, twin_exact):
    """Every recorded step of ``gearcontact twin --hertz-form exact`` equals the FMU's
    output at that communication point within 1e-9 relative: the tolerance of the
    Hamrock-Brewe drivetrain FMU against the twin (tests/export/test_fmu_drivetrain.py:
    the bound the issue sets; the C repeats the twin's operations in the same order,
    another libm's log/exp/cbrt may differ by an ulp). The exact and Hamrock-Brewe
    twins differ by far more (the mesh force by > 1e-3 relative somewhere)."""
    twin = twin_exact["exact"]
    n = twin.summary["steps"]
    res = _fmu_run(drivetrain_exact[0], "fp64")
    assert n == 800 and len(res) == n + 1
    _assert_reproduces(res, twin, n, "fp64")
    _assert_counts(res, twin, n)      # 0 in both (s0003's previews in the domain)
    hb = twin_exact["hamrock-brewe"].columns["mesh_load_n"]
    ex = twin.columns["mesh_load_n"]
    assert np.max(np.abs(ex - hb) / np.maximum(np.abs(hb), 1.0)) > 1e-3


def test_cylindrical_pair_refuses_the_exact_form(tmp_path):
    """The line chain has no exact form (gearcontact twin refuses it too): exit 2 before
    any work, naming the option and what is allowed; a misspelt form likewise."""
    for args in (("--pair", str(EV), "--hertz-form", "exact"),
                 ("--pair", "s0003", "--hertz-form", "Exact")):
        run = _cli(*args, "--kind", "drivetrain", "--out", str(tmp_path / "o"),
                   cwd=tmp_path)
        assert run.returncode == 2 and "--hertz-form" in run.stderr, run.stderr
        assert "hamrock-brewe" in run.stderr
        assert not (tmp_path / "o").exists()


def test_exact_mesh_export_rerun_writes_the_same_files(mesh_exact, tmp_path):
    """The export run again into its own directory writes byte-identical
    files (the FMU's binary included: the same compiler and flags)."""
    mesh_dir, _ = mesh_exact
    again = tmp_path / "s0003"
    shutil.copytree(mesh_dir, again)
    run = _cli("--pair", "s0003", "--kind", "mesh", "--phases", "9", "--hertz-form",
               "exact", "--out", str(again), cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    for name in ("gearcontact_mesh_s0003.fmu", "gearcontact_mesh_s0003_table.npz"):
        assert (again / name).read_bytes() == (mesh_dir / name).read_bytes(), name


def test_fmu_law_is_the_twin_law_and_has_none_beyond_the_table(mesh_exact, tmp_path):
    """The exact FMU's own contact law (``gc_law_fp64`` of its ``sources/``, compiled
    with the FMU's flags) against the twin's ``contact_law._fp64_law`` with the exact
    form: kappa and (a, b, p_max) at 1 N within TWIN_REL = 1e-14 (the C law's bound
    against the twin's, tests/export/test_c_exact_hertz.py) at random curvatures over
    ratios 1 .. 1e8; beyond the table (and for a saddle) both answer -1, no contact law
    (the twin counts it in previews_without_contact_law), never a clipped value."""
    from gearcontact.export.fmu import FMU_CFLAGS
    from gearcontact.twin import kernel as K
    from gearcontact.twin.contact_law import _fp64_law
    from gearcontact.twin.exact_hertz import RATIO_MAX, exact_hertz_table

    from .test_c_exact_hertz import TWIN_REL

    src = tmp_path / "sources"
    with zipfile.ZipFile(mesh_exact[0] / "gearcontact_mesh_s0003.fmu") as z:
        for name in z.namelist():
            if name.startswith("sources/"):
                z.extract(name, tmp_path)
    (tmp_path / "law.c").write_text(
        '#include "gc_contact_law.h"\n'
        "double law(double lo, double hi, double e, double out[4])\n"
        "{\n    return gc_law_fp64(lo, hi, e, out);\n}\n")
    so = tmp_path / "law.so"
    build = subprocess.run(["gcc", *FMU_CFLAGS, "-fPIC", "-shared", "-I", str(src), "-o",
                            str(so), str(tmp_path / "law.c"),
                            str(src / "gc_hertz_exact_table.c"), "-lm"],
                           capture_output=True, text=True)
    assert build.returncode == 0, build.stderr
    law = ctypes.CDLL(str(so)).law
    law.argtypes = [ctypes.c_double] * 3 + [ctypes.POINTER(ctypes.c_double)]
    law.restype = ctypes.c_double
    prm = np.concatenate([np.zeros(K.N_PRM), exact_hertz_table()])
    prm[K.P_HFORM] = K.HERTZ_FORM_CODES["exact"]
    prm[K.P_EP] = E_PRIME
    tcount = np.zeros(K.N_COUNT, np.int64)
    out3 = np.zeros(K.N_PREVIEW)
    out = (ctypes.c_double * 4)()
    rng = np.random.default_rng(17)
    worst = 0.0
    for _ in range(500):
        lo = 10.0 ** rng.uniform(-4.0, -1.0)
        hi = lo * np.exp(rng.uniform(0.0, np.log(RATIO_MAX)))
        kap = law(lo, hi, E_PRIME, out)
        want = _fp64_law(lo, hi, prm, tcount, out3, False)
        assert out[3] == out3[K.PV_LOAD] == 1.0
        worst = max(worst, abs(kap / want - 1.0),
                    *(abs(out[q] / out3[q] - 1.0) for q in range(3)))
    assert worst <= TWIN_REL, worst
    assert tcount[5] == 0
    for lo, hi in ((1e-6, 1e-6 * RATIO_MAX * 1.01), (0.0, 0.1), (-1e-3, 0.1)):
        assert law(lo, hi, E_PRIME, out) == -1.0
        assert _fp64_law(lo, hi, prm, tcount, out3, False) == -1.0
    assert tcount[5] == 3
