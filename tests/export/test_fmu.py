"""``gearcontact export fmu --kind mesh``: the FMI 3.0 mesh FMU against the twin's law.

Truth: the twin's own compiled contact law (:func:`gearcontact.twin.contact_law._kappa`,
the numba code ``gearcontact twin`` runs) evaluated by :func:`gearcontact.export.
mesh_law.mesh_outputs` at the very inputs FMPy fed the FMU (read back from the FMU), on
the table the export baked in; FMPy's FMI 3.0 schema validation. The FMU is exported
once per module the way a user does (a real subprocess of ``python -m gearcontact``,
s0003 with 9 phases to keep the TCA short, ~15 s) and simulated by FMPy in both
interfaces with a prescribed constant-speed ramp of the pinion angle and a gear lagging
by a mesh rotation that sweeps from open flanks to a few times the rated load.
"""

from __future__ import annotations

import math
import re
import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
from fmpy.validation import validate_fmu  # noqa: E402

from gearcontact.export.mesh_law import BACKENDS, MeshLawTable, mesh_outputs  # noqa: E402

from .conftest import (docs_snippet, export_fmu_cli as _cli, run_isolated,  # noqa: E402
                       simulate_isolated)

ROOT = Path(__file__).resolve().parents[2]
OUTPUTS = ("torque_pinion_nm", "torque_gear_nm", "mesh_force_n", "te_arcsec", "p_max_mpa",
           "a_mm", "b_mm", "active_pairs")
INPUTS = ("phi_pinion_rad", "phi_gear_rad", "omega_pinion_rad_s", "omega_gear_rad_s")
#: the domain counts of the point-contact law's mesh FMU (not a cylindrical pair's)
COUNTS = ("pairs_outside_datapath", "pairs_without_contact_law")


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    out = tmp_path_factory.mktemp("fmu") / "s0003"
    run = _cli("--pair", "s0003", "--kind", "mesh", "--phases", "9", "--out", str(out),
               cwd=out.parent)
    assert run.returncode == 0, run.stderr
    fmu = out / "gearcontact_mesh_s0003.fmu"
    return fmu, MeshLawTable.from_npz(out / "gearcontact_mesh_s0003_table.npz")


def _signal(tab: MeshLawTable, *, lag_rad: float = 4.2e-4):
    """Constant pinion speed over two pinion pitches; the gear lags by theta(t) from
    -2e-5 rad (flanks open) by ``lag_rad`` more, its speed the derivative of its angle."""
    t = np.linspace(0.0, 0.02, 401)
    wp = 2.0 * tab.pitch_rad / 0.02
    theta = -2e-5 + lag_rad * t / 0.02
    phi_g = wp * t / tab.ratio - theta
    wg = np.full_like(t, wp / tab.ratio - lag_rad / 0.02)
    sig = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in INPUTS])
    sig["time"], sig["phi_pinion_rad"], sig["phi_gear_rad"] = t, wp * t, phi_g
    sig["omega_pinion_rad_s"], sig["omega_gear_rad_s"] = wp, wg
    return sig


def _sweep(fmu, tab, backend: str, fmi_type: str, *, lag_rad: float = 4.2e-4,
           counts: bool = True):
    """The mesh FMU under FMPy over :func:`_signal` (401 instants, every input and
    output recorded, the domain counts unless ``counts`` is false) in ``backend`` and
    ``fmi_type``."""
    res = fmpy.simulate_fmu(str(fmu), fmi_type=fmi_type, start_time=0.0, stop_time=0.02,
                            output_interval=5e-5, input=_signal(tab, lag_rad=lag_rad),
                            output=list(INPUTS + OUTPUTS + (COUNTS if counts else ())),
                            start_values={"backend": BACKENDS[backend]})
    assert len(res) == 401
    return res


def _assert_law(res, tab: MeshLawTable, backend: str, *, law=mesh_outputs) -> list:
    """Every output of the FMU run ``res`` at every recorded instant equals ``law``
    (:func:`mesh_outputs`; a cylindrical pair's ``line_mesh_outputs``) at the inputs the
    FMU held then: golden identical, fp64 within 1e-9 relative (reasons at
    :func:`test_fmu_equals_the_twin_contact_law`); the domain counts, where ``res``
    has them, identical (integers: the twin's counts of the same previews). Returns
    the Python law's outputs, row by row."""
    refs = []
    counts = tuple(n for n in COUNTS if n in res.dtype.names)
    for row in res:
        ref = law(tab, *(float(row[n]) for n in INPUTS), backend=backend)
        for name in counts:
            assert int(row[name]) == getattr(ref, name), (name, float(row["time"]))
        for name in OUTPUTS:
            got, want = float(row[name]), float(getattr(ref, name))
            if backend == "golden":
                assert got == want, (name, float(row["time"]))
            else:
                assert got == pytest.approx(want, rel=1e-9, abs=0.0), name
        refs.append(ref)
    return refs


def test_fmu_validates_against_the_fmi3_schema(exported):
    fmu, _ = exported
    assert validate_fmu(str(fmu)) == []
    names = set(zipfile.ZipFile(fmu).namelist())
    assert {"modelDescription.xml", "sources/buildDescription.xml", "sources/gc_mesh_fmu.c",
            "binaries/x86_64-linux/gearcontact_mesh_s0003.so"} <= names
    # the default form (Hamrock-Brewe) carries nothing of the exact one (--hertz-form
    # exact, tests/export/test_fmu_exact_hertz.py): its files and table as before it
    assert not any("exact" in n for n in names)
    with np.load(fmu.parent / "gearcontact_mesh_s0003_table.npz") as z:
        assert "hertz_form" not in z.files
    md = fmpy.read_model_description(str(fmu))
    assert md.fmiVersion == "3.0" and md.coSimulation and md.modelExchange
    causal = {v.name: (v.causality, v.unit) for v in md.modelVariables}
    assert {n: causal[n][0] for n in INPUTS} == dict.fromkeys(INPUTS, "input")
    assert {n: causal[n][0] for n in OUTPUTS + COUNTS} == dict.fromkeys(OUTPUTS + COUNTS,
                                                                       "output")
    assert {v.name: v.type for v in md.modelVariables if v.name in COUNTS} == \
        dict.fromkeys(COUNTS, "Int32")
    assert causal["backend"][0] == "parameter" and causal["torque_gear_nm"][1] == "N.m"


@pytest.mark.parametrize("fmi_type", ["CoSimulation", "ModelExchange"])
@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_fmu_equals_the_twin_contact_law(exported, backend, fmi_type):
    """Every output at every recorded instant equals the Python law at the inputs the
    FMU held then: fp64 within 1e-9 relative (the same operations in the same order;
    the bound leaves room for another libm's pow/cbrt/log by a few ulp, amplified by
    W = (d/kappa)^(3/2) and by the cancellation in theta = psi_p/u + eps - psi_g,
    ~1e5 at these angles: <= 1e-10), golden identical (integer stage D, then the same
    fp64 operations). Measured: identical in both backends and both interfaces."""
    fmu, tab = exported
    res = _sweep(fmu, tab, backend, fmi_type)
    loaded = sum(ref.torque_gear_nm > 0.0 for ref in _assert_law(res, tab, backend))
    # the sweep covers open flanks, one and several pairs, and the rated torque. The
    # domain counts (equal to the twin's above): s0003's table has no saddle (least
    # min(A-, B-) 1.0e-3 1/mm), but its cut-patch edge rows reach B- = 48 1/mm, beyond
    # the datapath's 16: measured one pair outside at the 2 last of 401 instants (the
    # largest lag, ~3.7 kN), in both backends
    assert res["pairs_without_contact_law"].max() == 0
    assert 0 < np.count_nonzero(res["pairs_outside_datapath"]) < len(res)
    assert res["torque_gear_nm"][0] == 0.0 and res["active_pairs"][0] == 0
    assert 0 < loaded < len(res) and res["active_pairs"].max() >= 2
    assert res["torque_gear_nm"].max() > 64.5


def edited_curvatures(a, b, valid, opening, *, alpha_max: float):
    """Copies of the curvature rows ``a``, ``b`` (pairs x rows) with two edits at the
    valid entries of least opening (the pairs that carry the load; ties to the row
    nearest the table's middle): at the first a saddle (its smaller curvature made
    minus half itself: no law over a third of each adjacent row interval), at the
    next one at least 3 rows away a curvature ratio 4 alpha_max (outside the
    fixed-point datapath's domain, a law still: Hamrock-Brewe holds at any ratio). A
    test's table with previews that the twin counts in both counters."""
    a, b, valid = np.array(a, float), np.array(b, float), np.asarray(valid, bool)
    mid = valid.shape[1] // 2
    entries = sorted(zip(*np.nonzero(valid)),
                     key=lambda e: (float(opening[e]), abs(int(e[1]) - mid), int(e[0])))
    (j0, k0) = entries[0]
    (j1, k1) = next(e for e in entries if abs(int(e[1]) - int(k0)) >= 3)
    lo = min(a[j0, k0], b[j0, k0])
    if a[j0, k0] <= b[j0, k0]:
        a[j0, k0] = -0.5 * lo
    else:
        b[j0, k0] = -0.5 * lo
    lo = min(a[j1, k1], b[j1, k1])
    a[j1, k1], b[j1, k1] = lo, 4.0 * alpha_max * lo
    return a, b


@pytest.fixture(scope="module")
def edited(exported, tmp_path_factory):
    """The module's table with :func:`edited_curvatures` baked into a mesh FMU by the
    export's own writer (:func:`gearcontact.export.fmu.write_mesh_fmu`)."""
    import dataclasses

    from gearcontact.export.fmu import fmi3_header_dir, write_mesh_fmu
    from gearcontact.preview.hertz.reference import ENVELOPE

    _, tab = exported
    a, b = edited_curvatures(tab.A_minus_per_mm, tab.B_minus_per_mm, tab.valid,
                             tab.opening_mm, alpha_max=ENVELOPE["alpha"][1])
    tab = dataclasses.replace(tab, A_minus_per_mm=a, B_minus_per_mm=b)
    out = tmp_path_factory.mktemp("fmu_edited")
    fmu = write_mesh_fmu(tab, out, pair_name="s0003_edited", side="coast",
                         header_dir=fmi3_header_dir()).fmu_path
    return fmu, tab


@pytest.mark.parametrize("backend, fmi_type", [("fp64", "ModelExchange"),
                                               ("golden", "CoSimulation")])
def test_fmu_counts_previews_as_the_twin(edited, backend, fmi_type):
    """The domain counts at each instant: the pairs whose preview lies outside the
    datapath's domain and the pairs without a contact law equal the twin's counters
    (``contact_law._fp64_law``'s tcount[3], tcount[5]) over the same previews of the
    twin's compiled law (:func:`mesh_outputs`) at the inputs the FMU held, on a table
    with a saddle and a ratio beyond alpha_max (:func:`edited_curvatures`); every other
    output as in :func:`test_fmu_equals_the_twin_contact_law` (same tolerances). Both
    counts are reached: the edited rows are swept through."""
    fmu, tab = edited
    res = _sweep(fmu, tab, backend, fmi_type)
    _assert_law(res, tab, backend)
    assert res["pairs_outside_datapath"].max() >= 1
    assert res["pairs_without_contact_law"].max() >= 1


def test_fmu_law_closes_the_static_balance(exported):
    """Independent of the FMU: at the twin's static point the law's pinion torque is the
    gear torque times d theta/d psi_p (virtual work of a conservative mesh, no damping
    at rest) and the normal load is the torque over the levers' load-weighted mean,
    which lies between the smallest and largest lever."""
    _, tab = exported
    psi = 0.37 * tab.pitch_rad
    i = int(psi / tab.step_rad)
    de = (tab.eps_rad[i + 1] - tab.eps_rad[i]) / tab.step_rad
    ref = mesh_outputs(tab, psi, psi / tab.ratio - 2e-4, 0.0, 0.0, backend="fp64")
    assert ref.torque_pinion_nm == pytest.approx(-ref.torque_gear_nm * (1 / tab.ratio + de),
                                                 rel=1e-15)
    lever = 1e3 * ref.torque_gear_nm / ref.mesh_force_n
    levers = tab.lever_mm[tab.valid]
    assert levers.min() <= lever <= levers.max()


@pytest.mark.parametrize("args, field", [
    (("--kind", "gearbox"), "--kind"),
    (("--torque", "0"), "--torque"),
    (("--drivetrain", "dt.toml"), "--drivetrain"),      # a drivetrain file with --kind mesh
    (("--curvatures", "stencil"), "--curvatures"),      # the mesh FMU runs exact
    (("--kind", "drivetrain", "--drivetrain", "missing.toml"), "--drivetrain"),
    (("--pair", "no_such_pair"), "pair"),
    (("--phases", "2"), "--phases"),
])
def test_bad_input_is_refused_before_work(tmp_path, args, field):
    run = _cli(*args, "--out", str(tmp_path / "o"), cwd=tmp_path)
    assert run.returncode == 2
    assert field in run.stderr
    assert not (tmp_path / "o").exists()
    if args[1] == "gearbox":
        assert "'mesh', 'drivetrain'" in run.stderr


def test_fmu_rejects_non_finite_inputs(exported):
    """A NaN input is an fmi3Error, never a NaN output."""
    from fmpy import extract
    from fmpy.fmi3 import FMU3Slave

    fmu, _ = exported
    md = fmpy.read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU3Slave(guid=md.instantiationToken, unzipDirectory=extract(str(fmu)),
                      modelIdentifier=md.coSimulation.modelIdentifier)
    slave.instantiate()
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    with pytest.raises(Exception, match=r"fmi3SetFloat64 failed with status 3 \(error\)"):
        slave.setFloat64([vr["phi_pinion_rad"]], [math.nan])
    # the input kept its last value: the outputs stay finite (flanks open at 0, 0)
    assert slave.getFloat64([vr["phi_pinion_rad"], vr["torque_gear_nm"]]) == [0.0, 0.0]
    slave.terminate()
    slave.freeInstance()


def _snippet_law(tab: MeshLawTable) -> tuple[float, int]:
    """What the docs' snippet prints, from the twin's law on ``tab`` (golden): the mean
    gear torque and the most pairs in contact over its 201 output points."""
    assert tab.ratio == 10.0        # the snippet's u
    t = np.linspace(0.0, 0.01, 201)
    w_p = 314.16
    # co-simulation samples the outputs at t + h with the inputs applied at t (FMPy's
    # loop), except the first row: the inputs at the recorded time minus one interval
    ref = [mesh_outputs(tab, w_p * s, w_p * s / 10.0 - 2e-4, w_p, w_p / 10.0,
                        backend="golden") for s in np.concatenate([[0.0], t[:-1]])]
    return (float(np.mean([r.torque_gear_nm for r in ref])),
            max(r.active_pairs for r in ref))


def test_docs_snippet_runs(exported, capsys):
    """The FMPy snippet of docs/export.md, on the exported FMU: it prints the mean gear
    torque and the most pairs in contact, which equal the twin's law at its inputs
    (1e-12 relative: the mean of 201 torques the FMU gives bit for bit, summed in
    another order)."""
    fmu, tab = exported
    snippet = docs_snippet("The gear mesh as an FMI 3.0 FMU")
    assert "clib_fmu/gearcontact_mesh_s0003.fmu" in snippet
    exec(compile(snippet.replace("clib_fmu/gearcontact_mesh_s0003.fmu", str(fmu)),
                 "export.md", "exec"), {})
    mean, pairs = capsys.readouterr().out.split()
    want_mean, want_pairs = _snippet_law(tab)
    assert float(mean) == pytest.approx(want_mean, rel=1e-12)
    assert int(pairs) == want_pairs


def test_docs_snippet_as_written_without_gearcontact(readme_export):
    """The snippet exactly as written (its relative path, no replacement) in a process
    where gearcontact cannot be imported, in the README's directory, on the README's
    FMU (``gearcontact export fmu --pair s0003 --kind mesh --out clib_fmu/``: default
    options, 61 phases): it prints what the docs say it prints (the mean gear torque to
    the docs' 0.1 N·m, the most pairs exactly), and that is the twin's law on the FMU's
    table (1e-12 relative, as above)."""
    base, lines, runs = readme_export
    line = next(x for x in lines["export_fmu"] if "--kind mesh" in x)
    assert runs[line].returncode == 0, runs[line].stderr
    mean, pairs = run_isolated(docs_snippet("The gear mesh as an FMI 3.0 FMU"),
                               base).splitlines()[-1].split()
    text = (ROOT / "docs" / "export.md").read_text()
    stated = re.search(r"this prints a mean gear torque of ([\d.]+) N·m with up to (\d+) "
                       r"pairs", text)
    assert stated and f"{float(mean):.1f}" == stated[1] and pairs == stated[2]
    want_mean, want_pairs = _snippet_law(MeshLawTable.from_npz(
        base / "clib_fmu" / "gearcontact_mesh_s0003_table.npz"))
    assert float(mean) == pytest.approx(want_mean, rel=1e-12)
    assert int(pairs) == want_pairs


def test_fmu_of_a_pair_without_ease_off_table(tmp_path):
    """s0003-centred without its drive-side ease-off table (synthesized at export, the
    note printed): the FMU validates and equals the law on its own table (golden,
    co-simulation: identical). ~25 s: the synthesis and a 9-phase TCA."""
    from importlib import resources

    text = resources.files("gearcontact").joinpath("data/pairs/s0003-centred.toml").read_text()
    head, rest = text.split("[easeoff.drive]", 1)
    bare = tmp_path / "bare.toml"
    bare.write_text(head + "[easeoff.coast]" + rest.split("[easeoff.coast]", 1)[1])
    run = _cli("--pair", str(bare), "--side", "drive", "--phases", "9", "--out",
               str(tmp_path / "o"), cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert "synthes" in run.stdout.lower()
    # the synthesized table in a file named on stdout, not printed (as analyze's
    # summary.md): the note's TOML block
    toml = tmp_path / "o" / "easeoff.toml"
    assert f"(the TOML block is in {toml})" in run.stdout
    assert "lengthwise_crowning_um_per_mm2" not in run.stdout
    assert toml.read_text().startswith("[easeoff.drive]\n")
    fmu = tmp_path / "o" / "gearcontact_mesh_s0003_centred.fmu"
    tab = MeshLawTable.from_npz(tmp_path / "o" / "gearcontact_mesh_s0003_centred_table.npz")
    assert validate_fmu(str(fmu)) == []
    res = fmpy.simulate_fmu(str(fmu), start_time=0.0, stop_time=0.02, output_interval=2e-4,
                            input=_signal(tab), output=list(INPUTS + OUTPUTS),
                            start_values={"backend": BACKENDS["golden"]})
    for row in res:
        ref = mesh_outputs(tab, *(float(row[n]) for n in INPUTS), backend="golden")
        assert [float(row[n]) for n in OUTPUTS] == [float(getattr(ref, n)) for n in OUTPUTS]
    assert res["torque_gear_nm"].max() > 0.0


@pytest.mark.slow
@pytest.mark.parametrize("backend, rel", [("reference", 1e-9), ("golden", 1e-4)])
def test_mesh_law_is_the_twin_law(backend, rel):
    """The FMU's law (mesh_law, which the FMU equals bit for bit) against ``gearcontact
    twin`` itself: at every recorded step of a twin run (s0003, exact curvatures, rigid
    teeth, 9 phases, 3000 rpm, 5 ms at 10 us) the law evaluated at the step's pinion
    and gear angles and speeds gives the twin's mesh torque, load, contact ellipse and
    pair count. The twin samples each preview at the pair's load of the previous step,
    the law at its current load (two samples). fp64, 1e-9 relative: kappa is load
    independent up to rounding (~1e-15), the gear angle is recovered from the recorded
    theta (~1e-13 of theta). golden, 1e-4: a pair that just closed is sampled by the
    twin at 1 N (its previous load 0), where the semi-axis a ~ 0.1 mm has only ~1e5
    codes of 2^-20 mm: kappa ~ 1/a carries ~1e-5 of rounding, W ~ kappa^(-3/2) 1.5x
    that (the law samples at the load itself); measured below, docs/export.md. The FMU
    equals the law itself bit for bit (test above)."""
    from gearcontact.cli.options import load_pair
    from gearcontact.export.mesh_law import mesh_law_table
    from gearcontact.twin.simulate import model_for_pair, simulate

    model = model_for_pair(load_pair("s0003"), torque_nm=64.5, backend=backend,
                           side="coast", phases=9, curvatures="exact")
    res = simulate(model, speed_rpm=3000.0, duration_s=5e-3, step_s=1e-5)
    tab = mesh_law_table(model.mesh)
    c = res.columns
    c_m = res.summary["mesh_damping_n_s_per_mm"]
    eps = np.interp(np.mod(c["psi_p_rad"], tab.pitch_rad), model.mesh.psi_rad, tab.eps_rad)
    worst = 0.0
    for k in range(len(c["t_s"])):
        psi_g = c["psi_p_rad"][k] / tab.ratio + eps[k] - c["theta_rad"][k]
        out = mesh_outputs(tab, c["psi_p_rad"][k], psi_g, c["pinion_speed_rad_s"][k],
                           c["gear_speed_rad_s"][k], backend="fp64" if backend == "reference"
                           else "golden", mesh_damping_n_s_per_mm=c_m)
        assert out.active_pairs == c["pairs_loaded"][k]
        for mine, twin in ((out.torque_gear_nm, c["mesh_torque_nm"][k]),
                           (out.mesh_force_n, c["mesh_load_n"][k]), (out.a_mm, c["a_mm"][k]),
                           (out.b_mm, c["b_mm"][k]), (out.p_max_mpa, c["p_max_mpa"][k])):
            assert mine == pytest.approx(twin, rel=rel, abs=1e-12)
            if twin:
                worst = max(worst, abs(mine - twin) / abs(twin))
    print(f"{backend}: worst relative difference to the twin {worst:.2e}")


def test_fmu_runs_without_gearcontact(exported):
    """The mesh FMU simulates in a Python process where gearcontact cannot be imported,
    with the very numbers of this process's FMPy run (same binary: identical)."""
    fmu, tab = exported
    kw = {"start_time": 0.0, "stop_time": 0.02, "output_interval": 5e-5,
          "output": list(OUTPUTS), "start_values": {"backend": BACKENDS["golden"]}}
    sig = _signal(tab)
    here = fmpy.simulate_fmu(str(fmu), input=sig, **kw)
    np.save(fmu.parent / "signal.npy", sig)
    script_input = {"input_npy": str(fmu.parent / "signal.npy")}
    there = simulate_isolated(fmu, **kw, **script_input)
    for name in OUTPUTS:
        np.testing.assert_array_equal(there[name], np.asarray(here[name], float),
                                      err_msg=name)


@pytest.mark.slow
@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_fmu_with_tooth_bending_equals_the_twin_contact_law(tmp_path, backend):
    """``--bending``: the table carries each pair's bending compliance (the twin's
    mesh table with ``bending``) and the FMU's law solves ``d = kappa W^(2/3) + c_b W``
    by the twin's Newton (:func:`gearcontact.twin.contact_law._pair_load`, started
    afresh: the element has no state). Every output at every recorded instant of the
    co-simulation sweep equals :func:`mesh_outputs` on the exported table: fp64 within
    1e-9 relative, golden identical (as above; measured identical). The bending is in
    the law: at the sweep's largest mesh rotation the gear torque is below the rigid
    law's on the same table. ~40 s (the shell model of both teeth at export)."""
    import dataclasses

    run = _cli("--pair", "s0003", "--kind", "mesh", "--phases", "9", "--bending",
               "--out", str(tmp_path), cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    tab = MeshLawTable.from_npz(tmp_path / "gearcontact_mesh_s0003_table.npz")
    assert tab.bending_mm_per_n is not None and tab.bending_mm_per_n.max() > 0.0
    res = fmpy.simulate_fmu(str(tmp_path / "gearcontact_mesh_s0003.fmu"), start_time=0.0,
                            stop_time=0.02, output_interval=5e-5, input=_signal(tab),
                            output=list(INPUTS + OUTPUTS),
                            start_values={"backend": BACKENDS[backend]})
    _assert_law(res, tab, backend)
    last = [float(res[n][-1]) for n in INPUTS]
    rigid = mesh_outputs(dataclasses.replace(tab, bending_mm_per_n=None), *last,
                         backend=backend)
    assert 0.0 < res["torque_gear_nm"][-1] < 0.95 * rigid.torque_gear_nm
