"""``gearcontact export fmu`` on a cylindrical pair (the EV reducer's helical stage): the
mesh FMU against the twin's line law, the drivetrain FMU against ``gearcontact twin``.

Truth: the twin's own compiled line law (:func:`gearcontact.twin.line_law._line_law`,
the numba code ``gearcontact twin`` runs on a cylindrical pair) evaluated by
:func:`gearcontact.export.line_mesh_law.line_mesh_outputs` at the very inputs FMPy fed
the FMU, on the table the export baked in; for the drivetrain FMU the twin's own run
(:func:`gearcontact.twin.simulate.simulate` on :func:`gearcontact.twin.cylindrical.
cylindrical_model`, the model ``gearcontact twin`` builds); FMPy's FMI 3.0 schema
validation. Exported the way a user does (a subprocess of ``python -m gearcontact``),
7 phases per pitch to keep the tables small (~10 s per export). The domain counts (issue
27): the twin's own counters (``tcount[3..5]``, counted by
:func:`gearcontact.twin.line_law._line_fp64`) over the same previews, exact integers;
the C library's lift against :func:`gearcontact.preview.hertz.reference.line_lift` bit
for bit.
"""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
from fmpy.validation import validate_fmu  # noqa: E402

from gearcontact.export.line_mesh_law import LineMeshTable, line_mesh_outputs  # noqa: E402
from gearcontact.export.mesh_law import BACKENDS  # noqa: E402

from .conftest import export_fmu_cli as _cli  # noqa: E402
from .test_fmu import (COUNTS as MESH_COUNTS, INPUTS, OUTPUTS,  # noqa: E402
                       _assert_law as assert_mesh_law, _signal as signal, _sweep as sweep)
# FMU output -> twin column (the twin's te_arcsec is the DTE)
from .test_fmu_drivetrain import (COUNTS, PAIRS as TWIN_COLUMNS, _assert_counts,  # noqa: E402
                                  _assert_reproduces, assert_twin_csv)

ROOT = Path(__file__).resolve().parents[2]
EV = ROOT / "examples" / "ev_reducer_helical_23x67.toml"
NAME = "ev_reducer_helical_23x67"
TORQUE_NM = 200.0


def _export(out: Path, kind: str, *options, pair: Path = EV, name: str = NAME) -> Path:
    """``gearcontact export fmu --pair PAIR --kind KIND --phases 7 OPTIONS --out out`` in a
    subprocess (the user's way; ``--torque`` the tests' unless given): the FMU's path."""
    if "--torque" not in options:
        options = ("--torque", str(TORQUE_NM), *options)
    run = _cli("--pair", str(pair), "--kind", kind, "--phases", "7", *options, "--out",
               str(out), cwd=out.parent)
    assert run.returncode == 0, run.stderr
    return out / f"gearcontact_{kind}_{name}.fmu"


def _assert_law(res, tab, backend: str) -> list:
    """The mesh FMU run ``res`` against :func:`line_mesh_outputs` (test_fmu's check:
    golden identical, fp64 within 1e-9 relative, reasons at
    :func:`test_mesh_fmu_equals_the_twin_line_law`; the domain counts, where ``res`` has
    them, identical: integers, the twin's counts of the same previews)."""
    return assert_mesh_law(res, tab, backend, law=line_mesh_outputs)


@pytest.fixture(scope="module")
def mesh_fmu(tmp_path_factory):
    fmu = _export(tmp_path_factory.mktemp("cyl_fmu") / "mesh", "mesh")
    return fmu, LineMeshTable.from_npz(fmu.parent / f"gearcontact_mesh_{NAME}_table.npz")


#: The mesh FMU's sweep: the gear's lag grows by 3e-4 rad (~4x the export torque's
#: rotation) from open flanks (test_fmu._signal)
LAG_RAD = 3e-4


def _signal(tab):
    return signal(tab, lag_rad=LAG_RAD)


def test_mesh_fmu_validates_against_the_fmi3_schema(mesh_fmu):
    fmu, _ = mesh_fmu
    assert validate_fmu(str(fmu)) == []
    names = set(zipfile.ZipFile(fmu).namelist())
    assert {"sources/gc_line_law.c", "sources/gc_line_law.h", "sources/gc_mesh_fmu.c",
            f"binaries/x86_64-linux/gearcontact_mesh_{NAME}.so"} <= names
    md = fmpy.read_model_description(str(fmu))
    assert md.fmiVersion == "3.0" and md.coSimulation and md.modelExchange
    assert "line law" in md.description
    # the domain counts of the bevel pair's mesh FMU: instantaneous Int32 outputs
    var = {v.name: v for v in md.modelVariables}
    assert {n: (var[n].type, var[n].causality, var[n].variability) for n in MESH_COUNTS} == \
        dict.fromkeys(MESH_COUNTS, ("Int32", "output", "discrete"))


@pytest.mark.parametrize("fmi_type", ["CoSimulation", "ModelExchange"])
@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_mesh_fmu_equals_the_twin_line_law(mesh_fmu, backend, fmi_type):
    """Every output at every recorded instant equals the Python law at the inputs the
    FMU held then: fp64 within 1e-9 relative (the same operations in the same order;
    the bound leaves room for another libm's log/pow/sqrt by a few ulp, amplified by the
    slice law's Newton and by the cancellation in theta = psi_p/u + eps - psi_g, ~1e5
    at these angles: <= 1e-10), golden identical (integer line chain, then the same fp64
    operations); the domain counts identical (integers). Measured: identical in both
    backends and both interfaces; no preview outside the domain or without a law in
    this sweep (test_mesh_fmu_counts_previews_as_the_twin reaches them)."""
    fmu, tab = mesh_fmu
    res = sweep(fmu, tab, backend, fmi_type, lag_rad=LAG_RAD)
    loaded = sum(ref.torque_gear_nm > 0.0 for ref in _assert_law(res, tab, backend))
    # the sweep covers open flanks, several pairs and beyond the export torque
    assert res["torque_gear_nm"][0] == 0.0 and res["active_pairs"][0] == 0
    assert 0 < loaded < len(res) and res["active_pairs"].max() >= 3
    assert res["torque_gear_nm"].max() > TORQUE_NM


#: The gear held this far behind the pinion (rad) over two pitches: pairs barely closed,
#: their contact lines short (test_mesh_fmu_counts_previews_as_the_twin)
HELD_LAG_RAD = 1.75e-4


@pytest.mark.parametrize("backend, fmi_type", [("fp64", "ModelExchange"),
                                               ("golden", "CoSimulation")])
def test_mesh_fmu_counts_previews_as_the_twin(mesh_fmu, backend, fmi_type):
    """The domain counts where they are not zero: the gear held HELD_LAG_RAD behind the
    pinion over two pitches (401 instants), where a pair barely closes and its loaded
    line is shorter than the line core's 1 mm: the host's lift runs the core on (2^s
    W, 2^s L), whose ellipse it keeps (line mode answered, the preview outside the
    datapath's domain; golden: the chain flags it, the fp64 line chain answers). At
    every instant both counts equal the twin's counters (``line_law._line_fp64``'s
    tcount[3], tcount[5]) over the same previews of the twin's compiled law
    (:func:`line_mesh_outputs`), exact integers; every other output as in
    :func:`test_mesh_fmu_equals_the_twin_line_law` (same tolerances). Measured: one pair
    outside at 26 instants, none without a law, in both backends and interfaces."""
    from gearcontact.export.line_mesh_law import _LineLaw
    from gearcontact.export.mesh_law import law_of

    fmu, tab = mesh_fmu
    sig = _signal(tab)
    sig["phi_gear_rad"] = sig["phi_pinion_rad"] / tab.ratio - HELD_LAG_RAD
    sig["omega_gear_rad_s"] = sig["omega_pinion_rad_s"] / tab.ratio
    res = fmpy.simulate_fmu(str(fmu), fmi_type=fmi_type, start_time=0.0, stop_time=0.02,
                            output_interval=5e-5, input=sig,
                            output=list(INPUTS + OUTPUTS + MESH_COUNTS),
                            start_values={"backend": BACKENDS[backend]})
    law = law_of(tab, _LineLaw)
    before = int(law.tcount[3])
    _assert_law(res, tab, backend)
    assert law.tcount[3] - before == res["pairs_outside_datapath"].sum() >= 10  # (26)
    assert res["pairs_without_contact_law"].max() == 0


def test_mesh_law_runs_the_line_and_the_edge_slices(mesh_fmu):
    """The sweep's law is the line law (line mode, a loaded length below the line's on
    the crowned and relieved flanks) and the table carries the edge slices beyond the
    helical lines' ends with a positive effective width: the port is exercised where
    the cylindrical law differs from the bevel one."""
    from gearcontact.export.line_mesh_law import _LineLaw
    from gearcontact.export.mesh_law import law_of

    _, tab = mesh_fmu
    assert tab.slices == 16 and tab.beyond > 0 and tab.beyond_width_mm > 0.0
    line_mesh_outputs(tab, 0.3 * tab.pitch_rad, 0.3 * tab.pitch_rad / tab.ratio - 1e-4,
                      0.0, 0.0, backend="fp64")
    law = law_of(tab, _LineLaw)
    i = int(0.3 * tab.pitch_rad / tab.step_rad)
    j = int(np.flatnonzero(tab.valid[:, i] & tab.valid[:, i + 1])[0])
    lam, pv = law.law(j, i, 0.0, 5e-3, 0)
    assert lam > 0.0 and pv[3] == 1.0           # line mode
    assert 0.0 < 2.0 * pv[0] < tab.line_rows[j, i, 52]     # L_c = 2 a below the line's L


@pytest.fixture(scope="module")
def mesh_binary(mesh_fmu, tmp_path_factory):
    """The module's mesh FMU's shared library loaded in process by ctypes (no compile:
    its sources hold the C library's ``gc_line_lift_fp64`` and the line law
    ``gc_line_law``, exported symbols), with their signatures."""
    import ctypes

    fmu, _ = mesh_fmu
    with zipfile.ZipFile(fmu) as z:
        name = next(n for n in z.namelist() if n.startswith("binaries/x86_64-linux/"))
        so = ctypes.CDLL(z.extract(name, tmp_path_factory.mktemp("cyl_so")))
    dbl, ptr = ctypes.c_double, ctypes.POINTER(ctypes.c_double)
    so.gc_line_lift_fp64.argtypes, so.gc_line_lift_fp64.restype = [dbl, dbl], dbl
    so.gc_line_lifted_keeps_ellipse.argtypes = [dbl] * 5
    so.gc_line_lifted_keeps_ellipse.restype = ctypes.c_int
    so.gc_line_law.argtypes = [ctypes.c_int, ptr, ptr, dbl, ctypes.c_int, dbl, dbl, dbl,
                               ptr, ptr]
    so.gc_line_law.restype = dbl
    return so


def test_c_lift_equals_the_host_lift(mesh_binary):
    """The C library's line-core domain on the host (``gc_line_lift_fp64``,
    ``gc_line_lifted_keeps_ellipse``) against the Python the twin's line law counts with
    (:func:`gearcontact.preview.hertz.reference.line_lift`, ``lifted_keeps_ellipse``,
    compiled by numba): bit for bit, no tolerance. The lift is fixed point (the LOAD
    and LINE_LENGTH codes, floor(x 2^frac + 1/2) of an exact product, then integer
    shifts): the same IEEE operations give the same powers of two. The SELECT's cube
    root is libm's pow in both (numba's ``lift ** (1/3)`` calls the process's libm), so
    its margins are decided alike. Operands: loads over the envelope and its edges
    (2^-8 .. 2^17 N, the lifted load's limit 2^17 / 2^s), lengths log-uniform 2^-10 ..
    2^11 mm and on the code boundaries (half codes around 1 mm, 2^-8 mm and each 2^-s
    mm), zero, negative; ellipses at the SELECT's two margins +-1 ulp for every lift
    2^0 .. 2^8."""
    import math

    from gearcontact.preview.hertz.reference import lifted_keeps_ellipse, line_lift

    so = mesh_binary
    rng = np.random.default_rng(27)
    edges = np.array([1 << 12, 1 << 13, 1 << 16, 1 << 19, 1 << 20]) - 1.0
    codes = (np.concatenate([edges, edges + 1.0, edges + 2.0])[:, None]
             + np.array([-0.5, -0.25, 0.0, 0.25, 0.5])[None]).ravel()
    lengths = np.concatenate([np.exp2(rng.uniform(-10.0, 11.0, 600)), codes / 2.0 ** 20,
                              [0.0, -1.0, -1e-3, 1024.0, 1024.5, 1e6]])
    loads = np.concatenate([np.exp2(rng.uniform(-9.0, 18.0, 60)),
                            [2.0 ** -8, 2.0 ** -9, 1.5 / 256, 0.0, -1.0, 1.0, 131072.0,
                             131072.0 + 1 / 512, 131073.0]
                            + [2.0 ** (17 - s) + e for s in range(1, 9)
                               for e in (0.0, 1 / 512, 1 / 256)]])
    seen = {}
    for w in loads:
        for length in lengths:
            want = line_lift(float(w), float(length))
            got = so.gc_line_lift_fp64(float(w), float(length))
            assert got.hex() == want.hex(), (float(w), float(length), got, want)
            seen[want] = seen.get(want, 0) + 1
    # every outcome reached: no lift (0), none needed (1), each shift 1..8
    assert set(seen) == {0.0, 1.0} | {2.0 ** s for s in range(1, 9)}, seen
    both = set()
    for s in range(9):
        lift = 2.0 ** s
        c = lift ** (1.0 / 3.0)
        for _ in range(40):
            length = math.exp(rng.uniform(-6.0, 0.0))
            p_l = math.exp(rng.uniform(4.0, 8.0))
            a0 = 0.5 * (lift * length) / c       # c a at the length margin
            p0 = p_l / c                         # c p at the pressure margin
            for a, p in ((a0, 0.5 * p0), (2.0 * a0, p0), (a0, p0)):
                for da in (-1, 0, 1):
                    for dp in (-1, 0, 1):
                        args = (math.nextafter(a, math.inf * da) if da else a,
                                math.nextafter(p, math.inf * dp) if dp else p, p_l, length,
                                lift)
                        want = bool(lifted_keeps_ellipse(*args))
                        assert bool(so.gc_line_lifted_keeps_ellipse(*args)) == want, args
                        both.add(want)
    assert both == {True, False}


def edited_stencils(gaps, valid, opening, *, curvature_hi: float):
    """A copy of the gap stencils ``gaps`` (pairs x rows x 49, mm) with two edits at the
    valid entries of least opening (the pairs that carry the load; ties to the row
    nearest the table's middle): at the first a saddle (``c (s^2 + t^2)`` subtracted,
    ``c`` half the stencil's larger curvature B_max: its smaller one, ~0 on a line, goes
    to about -B_max / 2, beyond the fit's resolution: no law over part of each
    adjacent row interval), at the next one at least 3 rows away the samples scaled to
    a B_max of twice ``curvature_hi`` (outside the line core's envelope, a law still).
    A test's table with previews that the twin counts in both counters."""
    from gearcontact.contract.stencil import stencil_coordinates
    from gearcontact.preview.fit.reference import fitted_coefficients
    from gearcontact.twin.contact_law import _principal

    g, valid = np.array(gaps, float), np.asarray(valid, bool)
    mid = valid.shape[1] // 2
    entries = sorted(zip(*np.nonzero(valid)),
                     key=lambda e: (float(opening[e]), abs(int(e[1]) - mid), int(e[0])))
    (j0, k0) = entries[0]
    (j1, k1) = next(e for e in entries if abs(int(e[1]) - int(k0)) >= 3)
    s, t = stencil_coordinates()

    def b_max(x):
        return max(_principal(*fitted_coefficients(x))[:2])

    g[j0, k0] -= 0.5 * b_max(g[j0, k0]) * (s * s + t * t)
    g[j1, k1] *= 2.0 * curvature_hi / b_max(g[j1, k1])
    return g


def _edited_rows(tab):
    """The mesh FMU table's line rows with :func:`edited_stencils` (the samples, then
    stage C's fp64 c3, c4, c5 of them: twin.model._curvature_rows' columns)."""
    from gearcontact.preview.fit.reference import fitted_coefficients
    from gearcontact.preview.hertz.reference import ENVELOPE

    rows = np.array(tab.line_rows)
    rows[..., :49] = edited_stencils(rows[..., :49], tab.valid, tab.opening_mm,
                                     curvature_hi=ENVELOPE["curvature_per_mm"][1])
    rows[..., 49:52] = fitted_coefficients(rows[..., :49])
    return rows


def test_c_line_law_counts_each_preview_as_the_twin(mesh_fmu, mesh_binary):
    """The C line law's domain test (``gc_line_law``'s pv[GC_LP_OUTSIDE], and its
    GC_LINE_LAW_NONE) preview by preview against the twin's compiled law
    (``line_law._line_law``) on the same rows: its tcount[3] and tcount[5] increments,
    exact; the law itself (its return and pv) unchanged, bit for bit (the same
    operations: the mesh FMU's tests hold it so). Both backends, every pair valid over
    a row interval, 12 fractions x approaches 1e-6 .. 1e-2 mm each, on the export's table
    and on it with :func:`edited_stencils`' saddle and curvature beyond the envelope.
    Each count is reached: previews outside (the lifted short lines of the table, the
    curvature beyond the envelope, golden: flagged) and previews without a law (the
    saddle)."""
    import ctypes
    import dataclasses

    from gearcontact.export.line_mesh_law import _LineLaw

    so = mesh_binary
    _, tab = mesh_fmu
    rng = np.random.default_rng(25)
    ptr = ctypes.POINTER(ctypes.c_double)
    pv_c = (ctypes.c_double * 9)()
    totals = {}
    for name, rows in (("export", tab.line_rows), ("edited", _edited_rows(tab))):
        law = _LineLaw(dataclasses.replace(tab, line_rows=rows))
        rows = np.ascontiguousarray(rows)
        for backend in (0, 1):
            outside = no_law = 0
            for i in range(rows.shape[1] - 1):
                for j in np.flatnonzero(tab.valid[:, i] & tab.valid[:, i + 1]):
                    r0, r1 = (rows[j, k].ctypes.data_as(ptr) for k in (i, i + 1))
                    for f in np.concatenate([[0.0, 1.0], rng.uniform(0.0, 1.0, 10)]):
                        d = float(np.exp(rng.uniform(np.log(1e-6), np.log(1e-2))))
                        before = int(law.tcount[3]), int(law.tcount[5])
                        lam, pv = law.law(int(j), i, float(f), d, backend)
                        lam_c = so.gc_line_law(backend, r0, r1, float(f), i, d, -0.0, 1.0,
                                               None, pv_c)
                        at = (name, backend, i, int(j), float(f), d)
                        assert lam_c.hex() == float(lam).hex(), at
                        n = slice(0, 8) if lam > 0.0 else slice(3, 8)
                        assert [v.hex() for v in pv_c[n]] == \
                            [float(v).hex() for v in pv[n]], at
                        assert (int(law.tcount[3]) - before[0],
                                int(law.tcount[5]) - before[1]) == \
                            (int(pv_c[8]), int(lam_c == -1.0)), at
                        outside += int(pv_c[8])
                        no_law += int(lam_c == -1.0)
            totals[name, backend] = outside, no_law
    assert all(o > 0 for o, _ in totals.values()), totals
    assert totals["export", 0][1] == totals["export", 1][1] == 0, totals
    assert totals["edited", 0][1] > 0 and totals["edited", 1][1] > 0, totals
    assert totals["edited", 0][0] > totals["export", 0][0], totals


def test_cylindrical_fmu_refuses_another_curvature_source(tmp_path):
    """--curvatures exact on a cylindrical pair (its law is the line chain on the
    stencil): refused before any work, naming the option (exit 2)."""
    run = _cli("--pair", str(EV), "--kind", "drivetrain", "--curvatures", "exact", "--out",
               str(tmp_path / "o"), cwd=tmp_path)
    assert run.returncode == 2
    assert "--curvatures" in run.stderr and "cylindrical" in run.stderr
    assert not (tmp_path / "o").exists()


@pytest.fixture(scope="module")
def bending_fmus(tmp_path_factory):
    """The EV pair's mesh and drivetrain FMUs with --bending (7 phases, 200 N·m)."""
    base = tmp_path_factory.mktemp("cyl_fmu_bending")
    return {kind: _export(base / kind, kind, "--bending") for kind in ("mesh", "drivetrain")}


@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_mesh_fmu_with_bending_equals_the_twin_line_law(bending_fmus, backend):
    """--bending: the twin's coupled slice law (Newton with the exact Jacobian on the
    loaded slices at the approach, from the series state with the uniform load's
    compliance; its secant compliance in series), every output at every instant of the
    sweep equal to the Python law (fp64 within 1e-9 relative, golden identical: reasons
    as without bending; the coupled law's Newton and dense solve are the same operations
    in the same order). Measured: identical in both backends; the teeth's bending softens the
    mesh (the largest force of the sweep below the rigid teeth's)."""
    fmu = bending_fmus["mesh"]
    assert [validate_fmu(str(f)) for f in bending_fmus.values()] == [[], []]
    tab = LineMeshTable.from_npz(fmu.parent / f"gearcontact_mesh_{NAME}_table.npz")
    assert tab.bending_mm_per_n is not None
    res = fmpy.simulate_fmu(str(fmu), start_time=0.0, stop_time=0.02, output_interval=5e-5,
                            input=_signal(tab), output=list(INPUTS + OUTPUTS),
                            start_values={"backend": BACKENDS[backend]})
    forces = [ref.mesh_force_n for ref in _assert_law(res, tab, backend)]
    assert res["active_pairs"].max() >= 3
    rigid = LineMeshTable(**{**tab.__dict__, "bending_mm_per_n": None,
                             "line_rows": tab.line_rows[..., :-(tab.slices + 2 * tab.beyond)
                                                        ** 2]})
    k = int(np.argmax(forces))
    row = res[k]
    stiff = line_mesh_outputs(rigid, *(float(row[n]) for n in INPUTS), backend=backend)
    assert 0.0 < forces[k] < stiff.mesh_force_n


@pytest.mark.parametrize("backend, twin_backend", [("fp64", "reference"),
                                                   ("golden", "golden")])
def test_drivetrain_fmu_with_bending_reproduces_gearcontact_twin(bending_fmus, backend,
                                                                 twin_backend):
    """``gearcontact twin --bending`` on the EV pair (7 phases, 200 N·m, 12000 rpm, 10 us,
    600 steps: the coupled law warm-started from each pair's last effective ease-off, the
    twin's blocks restarting it twice; the golden chain flags a few previews, answered by
    the fp64 line chain) against the FMU:
    every recorded step identical in golden, fp64 within 1e-9 relative (as without
    bending); the domain counts the twin's (exact). Measured: identical in both
    backends, every column; counts 12 previews outside in 12 steps, 0 without a law, in
    both backends."""
    from gearcontact.geometry.pair import load_pair
    from gearcontact.twin.cylindrical import cylindrical_model

    model = cylindrical_model(load_pair(EV, kinds=("cylindrical",)), torque_nm=TORQUE_NM,
                              backend=twin_backend, phases=7, bending=True)
    twin, _ = _assert_twin_reproduced(bending_fmus["drivetrain"], model, backend,
                                      speed_rpm=SPEED_RPM, duration_s=6e-3,
                                      step_us=STEP_US, steps=600)
    assert twin.summary["bending"]
    # counted as the twin (_assert_twin_reproduced): previews outside the domain in both
    # backends (golden: the fp64 fallback ran; measured 12 in 12 steps, both backends)
    assert twin.summary["previews_outside_datapath"] > 0

def test_mesh_fmu_reports_the_coupled_law_not_converging(tmp_path, monkeypatch):
    """The FMU's failure path of the coupled slice law (cs_solve returning -1: the mesh
    FMU's getters answer fmi3Error naming it, as the twin raises in
    line_law._coupled_state), reached through the iteration cap rendered into the C
    (``line.max_steps`` of fmu_cylindrical.line_law_context, coupled_slice_law.MAX_STEPS
    for every user; 0 here, in process, so that no solve may take a step). Truth: the
    error and its message at the first instant with a loaded pair, where the same FMU
    rendered with the default cap runs the same sweep (test_mesh_fmu_with_bending_equals_
    the_twin_line_law)."""
    from gearcontact.export import fmu_cylindrical
    from gearcontact.geometry.pair import load_pair

    law_context = fmu_cylindrical.line_law_context

    def capped(mesh, **kw):
        ctx = law_context(mesh, **kw)
        ctx["line"]["max_steps"] = 0
        return ctx

    monkeypatch.setattr(fmu_cylindrical, "line_law_context", capped)
    fmu = fmu_cylindrical.export_cylindrical_mesh_fmu(
        load_pair(EV, kinds=("cylindrical",)), tmp_path, pair_name=NAME, side="drive",
        phases=7, torque_nm=TORQUE_NM, bending=True)
    tab = LineMeshTable.from_npz(tmp_path / f"gearcontact_mesh_{NAME}_table.npz")
    messages = []

    def logger(*args):
        messages.append(" ".join(a.decode() if isinstance(a, bytes) else str(a)
                                 for a in args))

    with pytest.raises(Exception) as err:
        fmpy.simulate_fmu(str(fmu.fmu_path), start_time=0.0, stop_time=0.02,
                          output_interval=5e-5, input=_signal(tab),
                          output=list(INPUTS + OUTPUTS), logger=logger,
                          start_values={"backend": BACKENDS["fp64"]})
    assert "fmi3Error" in str(err.value) or "fmi3GetFloat64" in str(err.value)
    assert any("coupled slice law: no convergence" in msg for msg in messages), messages


SPEED_RPM = 12000.0
STEP_US = 10.0
DURATION_S = 3e-3       # 300 steps of 10 us: past the twin's 256-step block (its cache)


def _assert_twin_reproduced(fmu, model, backend: str, *, speed_rpm: float,
                            duration_s: float, step_us: float, steps: int):
    """Simulate ``model`` (the twin) and the drivetrain ``fmu`` under FMPy at the same
    speed, step and duration; assert ``steps`` recorded steps and that every FMU output
    at the first ``steps`` communication points equals the twin's record (golden
    identical, fp64 within 1e-9 relative: reasons at the tests), and the FMU's domain
    counts after them the twin's run's (test_fmu_drivetrain._assert_counts: exact, the
    same previews counted). Returns (twin, res)."""
    from gearcontact.twin.simulate import simulate

    twin = simulate(model, speed_rpm=speed_rpm, duration_s=duration_s,
                    step_s=1e-6 * step_us)
    res = fmpy.simulate_fmu(str(fmu), start_time=0.0, stop_time=duration_s,
                            output_interval=1e-6 * step_us,
                            output=list(TWIN_COLUMNS) + list(COUNTS),
                            start_values={"backend": BACKENDS[backend],
                                          "speed_rpm": speed_rpm, "step_us": step_us})
    n = twin.summary["steps"]
    assert n == steps and len(res) == n + 1
    _assert_reproduces(res, twin, n, backend)
    _assert_counts(res, twin, n)
    return twin, res


@pytest.fixture(scope="module")
def drivetrain_fmu(tmp_path_factory):
    return _export(tmp_path_factory.mktemp("cyl_fmu") / "drivetrain", "drivetrain")


def test_drivetrain_fmu_validates_against_the_fmi3_schema(drivetrain_fmu):
    assert validate_fmu(str(drivetrain_fmu)) == []
    assert "sources/gc_line_law.c" in zipfile.ZipFile(drivetrain_fmu).namelist()
    md = fmpy.read_model_description(str(drivetrain_fmu))
    assert md.fmiVersion == "3.0" and md.coSimulation and not md.modelExchange
    assert "line law" in md.description
    # the domain counts of the bevel pair's drivetrain FMU: cumulative Int64 outputs
    var = {v.name: v for v in md.modelVariables}
    assert {n: (var[n].type, var[n].causality, var[n].variability) for n in COUNTS} == \
        dict.fromkeys(COUNTS, ("Int64", "output", "discrete"))


@pytest.mark.parametrize("backend, twin_backend", [("fp64", "reference"),
                                                   ("golden", "golden")])
def test_drivetrain_fmu_reproduces_gearcontact_twin(drivetrain_fmu, backend, twin_backend):
    """``gearcontact twin --pair EV --phases 7 --torque 200 --speed-rpm 12000 --step-us 10
    --duration-ms 3`` (the library calls the CLI makes: :func:`~gearcontact.twin.
    cylindrical.cylindrical_model`, :func:`~gearcontact.twin.simulate.simulate`) against
    the FMU under FMPy at the same parameters: every recorded step equals the FMU's
    output at that communication point. Tolerance: fp64 1e-9 relative (the bound the
    issue sets; the C repeats the twin's operations in the same order, another libm's
    log/pow may differ by an ulp), golden identical; the domain counts after the 300
    steps the twin's (exact). Measured: identical in both backends, every column;
    counts 0, 0, 0 as the twin's (test_drivetrain_fmu_counts_previews_as_the_twin
    reaches them)."""
    from gearcontact.geometry.pair import load_pair
    from gearcontact.twin.cylindrical import cylindrical_model

    model = cylindrical_model(load_pair(EV, kinds=("cylindrical",)), torque_nm=TORQUE_NM,
                              backend=twin_backend, phases=7)
    _, res = _assert_twin_reproduced(drivetrain_fmu, model, backend, speed_rpm=SPEED_RPM,
                                     duration_s=DURATION_S, step_us=STEP_US, steps=300)
    # loaded and dynamic: the mesh carries the torque on average, the DTE moves, several
    # pairs share the load (a helical stage, eps_gamma ~ 3.5)
    assert 0.9 * TORQUE_NM < np.mean(res["mesh_torque_nm"]) < 1.1 * TORQUE_NM
    assert np.ptp(res["dte_arcsec"]) > 0.1 and np.min(res["pairs_loaded"]) >= 2


@pytest.fixture(scope="module")
def edited_drivetrain(tmp_path_factory):
    """``(FMU, model of a backend)``: the EV pair's model (7 phases, 200 N·m) with
    :func:`edited_stencils` in its mesh table (a saddle on one pair's row, a curvature
    beyond the line core's envelope on another's), built by the twin's
    :func:`~gearcontact.twin.model.build_model` with the line chain, written by the
    export's own :func:`~gearcontact.export.fmu_drivetrain.write_drivetrain_fmu` (one
    compile for both backends)."""
    import dataclasses

    from gearcontact.export.fmu import fmi3_header_dir
    from gearcontact.export.fmu_drivetrain import write_drivetrain_fmu
    from gearcontact.geometry.pair import load_pair
    from gearcontact.preview.hertz.reference import ENVELOPE
    from gearcontact.twin.cylindrical import cylindrical_model
    from gearcontact.twin.layout import LINE_SOURCE
    from gearcontact.twin.model import build_model

    base = cylindrical_model(load_pair(EV, kinds=("cylindrical",)), torque_nm=TORQUE_NM,
                             phases=7)
    m = base.mesh
    mesh = dataclasses.replace(m, stencil_gaps_mm=edited_stencils(
        m.stencil_gaps_mm, m.valid, m.opening_mm,
        curvature_hi=ENVELOPE["curvature_per_mm"][1]))

    def model(be):
        return build_model(mesh, base.drivetrain, TORQUE_NM, backend=be,
                           curvatures=LINE_SOURCE, reverse_note=base.reverse_note)

    fmu = write_drivetrain_fmu(model("reference"), tmp_path_factory.mktemp("cyl_edited"),
                               pair_name=f"{NAME}_edited", side=m.side, bending=False,
                               header_dir=fmi3_header_dir()).fmu_path
    return fmu, model


@pytest.mark.parametrize("backend, twin_backend", [("fp64", "reference"),
                                                   ("golden", "golden")])
def test_drivetrain_fmu_counts_previews_as_the_twin(edited_drivetrain, backend,
                                                    twin_backend):
    """The domain counts where the twin's are not zero: the :func:`edited_drivetrain`
    FMU after 300 steps at 12000 rpm: its three counts equal the twin's run of the same
    model (exact: integers counting the same previews), every output reproduces it
    (:func:`_assert_twin_reproduced`'s tolerances). Each count is reached. Measured:
    fp64 16 previews outside in 16 steps, 102 without a law; golden 118 in 118 (the
    saddle's previews flagged by the chain too), 102."""
    fmu, model = edited_drivetrain
    twin, _ = _assert_twin_reproduced(fmu, model(twin_backend), backend,
                                      speed_rpm=SPEED_RPM, duration_s=DURATION_S,
                                      step_us=STEP_US, steps=300)
    assert all(twin.summary[name] > 0 for name in COUNTS), twin.summary


def test_drivetrain_fmu_static_start_is_the_balance(drivetrain_fmu):
    """Independent of the twin: at rest (speed 0: no mesh damping torque) the mesh
    carries the load torque at t = 0 (the static point, bisection to 1e-15: 1e-9
    relative)."""
    rest = fmpy.simulate_fmu(str(drivetrain_fmu), stop_time=1e-4, output_interval=1e-5,
                             start_values={"speed_rpm": 0.0})
    assert rest["mesh_torque_nm"][0] == pytest.approx(TORQUE_NM, rel=1e-9)


SPUR = ROOT / "examples" / "spur_20x40_m3.toml"
#: no designed backlash: the mirrored reverse law closes as soon as the loaded flank opens
NO_BACKLASH = "[drivetrain]\nbacklash_mm = 0.0\n"


@pytest.fixture(scope="module")
def spur_drivetrain_fmu(tmp_path_factory):
    base = tmp_path_factory.mktemp("cyl_fmu")
    (base / "dt.toml").write_text(NO_BACKLASH)
    return _export(base / "spur", "drivetrain", "--torque", "10", "--drivetrain",
                   str(base / "dt.toml"), pair=SPUR, name="spur_20x40_m3"), base / "dt.toml"


@pytest.mark.parametrize("backend, twin_backend", [("fp64", "reference"),
                                                   ("golden", "golden")])
def test_spur_drivetrain_fmu_reproduces_the_twin_through_rattle(
        spur_drivetrain_fmu, backend, twin_backend):
    """A spur pair (no edge slices: the line law's other branch) lightly loaded (10 N·m)
    at 15000 rpm without backlash, 600 steps of 10 us: the mesh loses contact, the teeth
    fly free and strike the reverse flank (the loaded law mirrored, as the twin's), and
    the run passes the twin's 256-step blocks twice; every recorded step of
    ``gearcontact twin --drivetrain dt.toml`` equals the FMU's output, golden identical,
    fp64 within 1e-9 relative (as above), the domain counts the twin's (exact).
    Measured: identical in both backends, every column; counts 0, 0, 0."""
    from gearcontact.geometry.pair import load_pair
    from gearcontact.twin.cylindrical import cylindrical_model
    from gearcontact.twin.params import load_drivetrain

    fmu, dt_file = spur_drivetrain_fmu
    pair = load_pair(SPUR, kinds=("cylindrical",))
    model = cylindrical_model(pair, torque_nm=10.0, backend=twin_backend, phases=7,
                              drivetrain=load_drivetrain(dt_file, pair))
    twin, res = _assert_twin_reproduced(fmu, model, backend, speed_rpm=15000.0,
                                        duration_s=6e-3, step_us=10.0, steps=600)
    # the run loses contact (measured 5 % of the steps), strikes the reverse flank
    # (measured 57 steps of negative mesh torque) and comes back loaded
    assert 0.02 < twin.summary["contact_loss"] < 0.5
    assert np.sum(np.asarray(res["mesh_torque_nm"]) < 0.0) >= 10
    assert np.max(res["mesh_torque_nm"]) > 10.0


def isolated_counts(fmu: Path, backend: str, *, steps: int) -> dict:
    """The drivetrain ``fmu``'s domain counts after ``steps`` steps of 10 us at its start
    values (FMPy in a process without gearcontact: the record after the last step)."""
    from .conftest import simulate_isolated

    res = simulate_isolated(fmu, start_time=0.0, stop_time=steps / 1e5,
                            output_interval=1e-5, output=list(COUNTS),
                            start_values={"backend": BACKENDS[backend]})
    assert len(res["time"]) == steps + 1
    return {n: int(res[n][-1]) for n in COUNTS}


@pytest.mark.slow
def test_done_when_the_default_export_reproduces_the_twin_cli(tmp_path):
    """Issue 25's "Done when" on the cylindrical pair, as a twin developer runs it:
    ``gearcontact export fmu --pair examples/ev_reducer_helical_23x67.toml --kind
    drivetrain`` with default options (61 phases, 64.5 N·m), simulated by FMPy in a
    process where gearcontact cannot be imported at its start values (3000 rpm, 10 us),
    against ``gearcontact twin --pair examples/ev_reducer_helical_23x67.toml --duration
    0.00501 --backend reference|golden`` (501 steps; both commands this checkout's,
    ``python -m gearcontact``). Truth: the twin's twin.csv at its 12 significant digits:
    golden identical (the FMU's value printed the same way is the file's text), fp64
    within 1e-9 relative (the issue's bound; the CSV's rounding, <= 5e-13 relative, is
    inside it); the domain counts after the 501 steps twin.json's (exact: integers
    counting the same previews). Measured: every value of both backends equal at the
    CSV's 12 digits; counts 0, 0, 0 in both."""
    import csv
    import json
    import os
    import subprocess
    import sys

    from .conftest import simulate_isolated

    run = _cli("--pair", str(EV), "--kind", "drivetrain", "--out", str(tmp_path / "fmu"),
               cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    fmu = tmp_path / "fmu" / f"gearcontact_drivetrain_{NAME}.fmu"
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    for backend, name in (("fp64", "reference"), ("golden", "golden")):
        twin = subprocess.run([sys.executable, "-m", "gearcontact", "twin", "--pair", str(EV),
                               "--out", str(tmp_path / f"tw_{name}"), "--duration", "0.00501",
                               "--backend", name, "--no-figures", "--quiet"],
                              capture_output=True, text=True, env=env, cwd=tmp_path,
                              timeout=900)
        assert twin.returncode == 0, twin.stderr[-2000:]
        with open(tmp_path / f"tw_{name}" / "twin.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        assert len(rows) == 501
        res = simulate_isolated(fmu, start_time=0.0, stop_time=5e-3, output_interval=1e-5,
                                output=list(TWIN_COLUMNS),
                                start_values={"backend": BACKENDS[backend]})
        assert len(res["time"]) == 501
        assert_twin_csv(res, rows, TWIN_COLUMNS, backend)
        # issue 27: the counts after the twin's 501 steps are its twin.json's
        summary = json.loads((tmp_path / f"tw_{name}" / "twin.json").read_text())
        assert isolated_counts(fmu, backend, steps=501) == {n: summary[n] for n in COUNTS}
