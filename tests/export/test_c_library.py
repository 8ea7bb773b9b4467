"""``gearcontact export c``: the generated C99 library against the golden model.

Truth: the golden Python model's expected outputs as ``gearcontact vectors`` writes them
(the RTL test vectors: corner cases, 10,000 seeded random and raw whole-range words
per core), bit for bit; the fp64 Python reference
(:func:`gearcontact.preview.hertz.reference.hertz_preview`) within 1e-12 relative (the C
code repeats its operations in the same order on the same libm: the bound leaves room
for a libm that rounds exp/log/cbrt differently by an ulp or two, ~1e-15 each, amplified
at most ~10x through the formulas); the ROM words of the package's tables. Everything
runs the way a user does: real subprocesses of ``python -m gearcontact``, ``make``, the
checker.
"""

from __future__ import annotations

import ctypes
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gearcontact.export.c_constants import (FIT_LANES, expand_fit_mac_plan, fit_mac_ops,
                                            fit_mac_plan, orbit_members)
from gearcontact.export.c_library import C_FILES, GOLDEN_SOURCES, render_c_library
from gearcontact.hw.vectors import LINE_CORES, read_hex
from gearcontact.preview.hertz.luts import (CBRT_SPEC, EE_EXACT_SPEC, POW_EXACT_SPEC,
                                            POW_SPEC, rom_words)
from gearcontact.contract.qformat import STENCIL_GAP
from gearcontact.preview.chain import chain_reference
from gearcontact.preview.fit.pinv import baked_pinv
from gearcontact.preview.fit.reference import fit_curvatures
from gearcontact.preview.gap.reference import gap_reference
from gearcontact.preview.hertz.line import FLAG_LENGTH_RANGE, LENGTH_MIN_CODE, LIFT_MAX_SHIFT
from gearcontact.preview.hertz.reference import hertz_preview, truncated_preview
from gearcontact.preview.stimulus import line_stimulus
from gearcontact.preview.stimulus_lift import short_line_stimulus
from gearcontact.validation import InputRangeError

ROOT = Path(__file__).resolve().parents[2]
COUNT = 10_000                      # random vectors per core (the corner cases on top)
#: every core ``gearcontact vectors`` writes, in the checker's order
CORES = ("gap", "fit", "hertz", "chain", "gap_lean", "hertz_exact", "chain_exact") + LINE_CORES
FP64_STENCILS = 3000                # stencils of the fp64 fit/chain comparison
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror"]

pytestmark = pytest.mark.skipif(
    shutil.which("gcc") is None or shutil.which("make") is None,
    reason="gcc and make are needed to build the exported C library (Debian: gcc make)")


def _gearcontact(*argv, timeout=600):
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    run = subprocess.run([sys.executable, "-m", "gearcontact", *argv], env=env,
                         capture_output=True, text=True, timeout=timeout)
    assert run.returncode == 0, run.stderr[-3000:]
    return run


@pytest.fixture(scope="module")
def built(request, tmp_path_factory):
    """An export built with its Makefile, and the vectors of the Hertz cores. The
    library is the README's ``gearcontact export c --out clib/ && make -C clib/``
    (default options, run once per session: tests/export/conftest.py), or without the
    console script the same export through ``python -m gearcontact``."""
    base = tmp_path_factory.mktemp("cexport")
    vec = base / "vectors"
    try:
        readme_dir, lines, runs = request.getfixturevalue("readme_export")
    except pytest.skip.Exception:
        readme_dir = None
    if readme_dir is not None:
        run = runs.get(lines["export_c"][0])
        assert run is not None and run.returncode == 0, "the README's export c line failed"
        lib = readme_dir / "clib"
    else:
        lib = base / "lib"
        _gearcontact("export", "c", "--out", str(lib))
        make = subprocess.run(["make", "-C", str(lib), "CC=gcc"], capture_output=True,
                              text=True, timeout=300)
        assert make.returncode == 0, make.stdout[-3000:] + make.stderr[-3000:]
    _gearcontact("vectors", "--out", str(vec), "--count", str(COUNT), "--cores",
                 ",".join(CORES))
    return lib, vec


def _check(lib: Path, vec: Path):
    return subprocess.run([str(lib / "build" / "gearcontact_check"), str(vec)], capture_output=True,
                          text=True, timeout=300)


def test_every_source_compiles_strict_c99(built):
    lib, _ = built
    for name in (n for n in C_FILES if n.endswith(".c")):
        run = subprocess.run(["gcc", *STRICT, "-c", "-o", os.devnull, str(lib / name)],
                             capture_output=True, text=True, timeout=120)
        assert run.returncode == 0, (name, run.stderr)
    assert all(flag in (lib / "Makefile").read_text() for flag in STRICT)


def test_golden_c_equals_the_golden_model_on_the_rtl_vectors(built):
    lib, vec = built
    run = _check(lib, vec)
    assert run.returncode == 0, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    n = {c: sum(1 for _ in (vec / f"{c}_in.hex").open()) for c in CORES}
    assert all(v >= COUNT for v in n.values())
    assert lines == [f"{c}: {n[c]} vectors, 0 mismatches" for c in CORES]


def test_golden_sources_alone_build_into_the_users_own_program(built, tmp_path):
    """Issue 25's "compile the golden C library into their own code": the checker
    (standing in for the user's program) and the four golden sources alone, compiled by
    one gcc line of the user's own (no Makefile, none of its flags: -O3 -ffast-math
    -pedantic, no -lm), link and give 0 mismatches on the same vectors: the golden code
    needs neither libm nor a floating-point model (integer only)."""
    lib, vec = built
    exe = tmp_path / "own_check"
    build = subprocess.run(["gcc", *STRICT, "-pedantic", "-O3", "-ffast-math", "-o", str(exe),
                            str(lib / "gearcontact_check.c"),
                            *(str(lib / n) for n in GOLDEN_SOURCES)],
                           capture_output=True, text=True, timeout=300)
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([str(exe), str(vec)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.count(", 0 mismatches") == len(CORES)


class _FitCodes(ctypes.Structure):
    _fields_ = [("a_minus", ctypes.c_int32), ("b_minus", ctypes.c_int32),
                ("flags", ctypes.c_uint32)] + [(f"c{j}", ctypes.c_int32) for j in range(6)]


def test_golden_fit_of_the_curvatures_alone_equals_the_full_fit(built):
    """gc_fit_golden_curvatures (the drivetrain FMU's golden fit, no c0..c2) against
    gc_fit_golden and the golden model's expected outputs on the fit vectors: where
    every |gap code| <= GC_FIT_LINEAR_SAFE_CODE (its contract), A-, B-, c3..c5 and the
    flags equal, bit for bit, and c0..c2 are 0; beyond it, equal wherever the full fit
    does not flag a coefficient overflow (only c0..c2's can then differ). The bound
    itself: |c_j| <= (G sum_i |W_ji| + 2^20) >> 21 <= COEFF_MAX for j = 0..2, checked on
    the ROM here, and that it is the largest code that keeps it."""
    from gearcontact.export.c_constants import (fit_constants, fit_flags,
                                                fit_linear_safe_code, fit_weight_codes)
    from gearcontact.preview.fit.golden import golden_fit
    lib, vec = built
    so = ctypes.CDLL(str(lib / "build" / "libgearcontact.so"))
    for name in ("gc_fit_golden", "gc_fit_golden_curvatures"):
        getattr(so, name).restype = _FitCodes
        getattr(so, name).argtypes = [ctypes.POINTER(ctypes.c_int32)]
    safe, top = fit_linear_safe_code(), 2 ** 31 - 1
    shift = fit_constants()["COEFF_SHIFT"]
    l1 = [sum(abs(w) for w in row) for row in fit_weight_codes()[:3]]
    assert all((safe * n + (1 << (shift - 1))) >> shift <= top for n in l1)
    assert any(((safe + 1) * n + (1 << (shift - 1))) >> shift > top for n in l1)
    ins = read_hex(vec / "fit_in.hex", "fit", "in")["wr_data"]
    want = read_hex(vec / "fit_out.hex", "fit", "out")
    # beyond the bound without an overflow (the vectors' whole-range words mostly
    # overflow c0..c2): 200 stencils at offsets from the bound to 2^31 - 1 codes (c0 up
    # to 1024 mm, within COEFF), curved along s, their expected outputs the golden model's
    col = np.arange(49) % 7 - 3
    offsets = np.linspace(safe + 1, 2 ** 31 - 1 - 9 * 4096, 200).astype(np.int64)
    extra = offsets[:, None] + 4096 * col[None, :] ** 2
    ins = np.concatenate([ins, extra])
    overflow = 1 << [n for n, _ in fit_flags()].index("coefficient_overflow")
    inside = beyond = 0
    for k, g in enumerate(ins):
        arr = (ctypes.c_int32 * 49)(*(int(x) for x in g))
        full, alone = so.gc_fit_golden(arr), so.gc_fit_golden_curvatures(arr)
        if k < len(want["flags"]):
            assert full.flags == want["flags"][k] and full.a_minus == want["a_minus"][k]
        else:
            model = golden_fit(g)
            assert (full.flags, full.a_minus, full.b_minus) \
                == (model.flags, model.a_minus_code, model.b_minus_code)
        same = [(getattr(full, n), getattr(alone, n)) for n in
                ("a_minus", "b_minus", "flags", "c3", "c4", "c5")]
        if int(np.abs(g).max()) <= safe:
            inside += 1
            assert all(x == y for x, y in same), k
            assert (alone.c0, alone.c1, alone.c2) == (0, 0, 0)
        elif not full.flags & overflow:
            beyond += 1
            assert all(x == y for x, y in same), k
    assert inside >= 5000 and beyond >= 200, (inside, beyond)


def test_golden_c_portable_build_equals_the_golden_model(built, tmp_path):
    """The code other compilers get (-DGC_PORTABLE_SCHEDULE: no asm barrier in the fit's
    MAC; -DGC_PORTABLE_BIT_LENGTH: the six-step bit length) computes the same integers:
    0 mismatches on the same vectors, built by the export's Makefile into its own
    directory."""
    lib, vec = built
    out = tmp_path / "portable"
    make = subprocess.run(["make", "-C", str(lib), "CC=gcc", f"BUILD={out}",
                           "CFLAGS=-O2 -DGC_PORTABLE_SCHEDULE -DGC_PORTABLE_BIT_LENGTH",
                           str(out / "gearcontact_check")],
                          capture_output=True, text=True, timeout=300)
    assert make.returncode == 0, make.stdout[-3000:] + make.stderr[-3000:]
    run = subprocess.run([str(out / "gearcontact_check"), str(vec)], capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.count(", 0 mismatches") == len(CORES)


def test_checker_names_the_core_of_a_corrupted_output_word(built, tmp_path):
    lib, vec = built
    bad = tmp_path / "vectors"
    shutil.copytree(vec, bad)
    path = bad / "hertz_exact_out.hex"
    lines = path.read_text().splitlines()
    k = next(i for i in range(500, len(lines)) if lines[i].endswith("00"))   # flags 0
    word = lines[k][16:24]                      # output field 2, p_max (8 digits)
    lines[k] = lines[k][:16] + f"{int(word, 16) ^ 1:08x}" + lines[k][24:]
    path.write_text("\n".join(lines) + "\n")
    run = _check(lib, bad)
    assert run.returncode == 1
    n = len(lines)
    assert f"hertz_exact: {n} vectors, 1 mismatches" in run.stdout.splitlines()
    assert f"hertz: {n} vectors, 0 mismatches" in run.stdout.splitlines()
    assert f"hertz_exact: vector {k} field p_max" in run.stderr


def test_checker_names_the_line_core_of_a_corrupted_lift_and_semi_axis(built, tmp_path):
    """A lifted line-mode vector's ``lift`` (the last hex digit of hertz_line_out.hex)
    and a chain_line vector's ``a`` (the first 8 digits) off by one: exit 1, each core
    counts 1 mismatch and names its vector and field, hertz_line_exact stays clean."""
    lib, vec = built
    bad = tmp_path / "vectors"
    shutil.copytree(vec, bad)
    y = read_hex(vec / "hertz_line_out.hex", "hertz_line", "out")
    k = int(np.flatnonzero((y["lift"] > 1) & (y["flags"] == 0))[0])
    path = bad / "hertz_line_out.hex"
    lines = path.read_text().splitlines()
    lines[k] = lines[k][:-1] + f"{int(lines[k][-1], 16) ^ 1:x}"
    path.write_text("\n".join(lines) + "\n")
    cpath = bad / "chain_line_out.hex"
    clines = cpath.read_text().splitlines()
    j = len(clines) - 1
    clines[j] = f"{int(clines[j][:8], 16) ^ 1:08x}" + clines[j][8:]
    cpath.write_text("\n".join(clines) + "\n")
    run = _check(lib, bad)
    assert run.returncode == 1
    out = run.stdout.splitlines()
    assert f"hertz_line: {len(lines)} vectors, 1 mismatches" in out
    assert f"chain_line: {len(clines)} vectors, 1 mismatches" in out
    assert f"hertz_line_exact: {len(lines)} vectors, 0 mismatches" in out
    assert f"hertz_line: vector {k} field lift: C {y['lift'][k]}, expected " \
           f"{y['lift'][k] ^ 1}" in run.stderr
    assert f"chain_line: vector {j} field a" in run.stderr


def test_checker_refuses_a_truncated_file_and_an_empty_directory(built, tmp_path):
    lib, vec = built
    bad = tmp_path / "vectors"
    bad.mkdir()
    assert _check(lib, bad).returncode == 2
    shutil.copy(vec / "hertz_in.hex", bad)
    (bad / "hertz_out.hex").write_text("".join((vec / "hertz_out.hex").open().readlines()[:-1]))
    run = _check(lib, bad)
    assert run.returncode == 2 and "hertz: line" in run.stderr


def _line_vectors(stimulus: str, count: int) -> dict:
    """Line-core operands: :func:`line_stimulus` (``"full"``) or the short lines below
    1 mm of :func:`short_line_stimulus` (``"short"``: every lift 1..8 and the lift's
    corners)."""
    gen = short_line_stimulus if stimulus == "short" else line_stimulus
    return {k: v.tolist() for k, v in gen(count, 0 if stimulus == "full" else 1).fields.items()}


@pytest.mark.parametrize("core", LINE_CORES)
def test_line_vectors_reach_every_mode_and_lift(built, core):
    """The line cores' vectors the checker passes (``gc_line_golden`` with its lift
    ``gc_line_length_lift``, ``gc_chain_line_golden``: 0 mismatches above) exercise what
    the C code branches on: both modes, every similarity exponent (stage D line core),
    every lift 1..8 answered in line mode, lifted runs that keep the ellipse (flagged
    ``length_range``) and unliftable lines (flagged, lift 0), flagged inputs."""
    _, vec = built
    y = read_hex(vec / f"{core}_out.hex", core, "out")
    f = y["flags"] & 0xFF
    lift = y["lift"]
    assert len(lift) >= COUNT
    line = (f == 0) & (y["mode"] == 1)
    assert set(lift[line & (lift > 0)]) == set(range(1, LIFT_MAX_SHIFT + 1))
    assert ((f == FLAG_LENGTH_RANGE) & (lift > 0)).any()       # lifted ellipse
    x = read_hex(vec / f"{core}_in.hex", core, "in")
    short = (x["L"] > 0) & (x["L"] < LENGTH_MIN_CODE)
    assert (short & (lift == 0) & (f & FLAG_LENGTH_RANGE > 0)).any()   # no lift
    assert ((f == 0) & (y["mode"] == 0)).any() and (f & ~FLAG_LENGTH_RANGE).any()
    if core != "chain_line":
        assert set(y["scale"][f == 0]) == {0, 1, 2, 3}


class _Fp64(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("a_mm", "b_mm", "k", "p_max_mpa", "alpha",
                                               "R_x_mm", "R_y_mm", "approach_mm")] \
        + [("flags", ctypes.c_uint32)]


class _Fit(ctypes.Structure):
    _fields_ = [("c", ctypes.c_double * 6), ("A_minus_per_mm", ctypes.c_double),
                ("B_minus_per_mm", ctypes.c_double), ("elliptic", ctypes.c_int)]


class _Chain(ctypes.Structure):
    _fields_ = [("fit", _Fit), ("hertz", _Fp64)]


FORMS = {"hamrock-brewe": (0, "gc_hertz_fp64"), "exact": (1, "gc_hertz_exact_fp64")}


def _library(lib: Path):
    so = ctypes.CDLL(str(lib / "build" / "libgearcontact.so"))
    for _, name in FORMS.values():
        getattr(so, name).restype = _Fp64
        getattr(so, name).argtypes = [ctypes.c_double] * 4
    so.gc_fit_fp64.restype = _Fit
    so.gc_fit_fp64.argtypes = [ctypes.POINTER(ctypes.c_double)]
    so.gc_chain_fp64.restype = _Chain
    so.gc_chain_fp64.argtypes = [ctypes.POINTER(ctypes.c_double), ctypes.c_double,
                                 ctypes.c_double, ctypes.c_int]
    return so


@pytest.mark.parametrize("form", list(FORMS))
def test_fp64_hertz_within_1e12_of_the_python_reference(built, form):
    """The stage-D vectors' inputs, decoded. Hamrock-Brewe: the same quantities on two
    independent paths, the cube root within 5 ulp instead of libm's (measured 1.8e-15). Exact: Carlson's R_F, R_D and a bisection to
    adjacent doubles against scipy's and Brent's to 4 eps (measured 1.8e-15; 2.5e-15 on the
    AMD EPYC machine of session 19)."""
    lib, vec = built
    so = _library(lib)
    code, function = FORMS[form]
    core = "hertz" if form == "hamrock-brewe" else "hertz_exact"
    ins = read_hex(vec / f"{core}_in.hex", core, "in")
    A, B = np.ldexp(ins["A"], -20), np.ldexp(ins["B"], -20)
    W, E = np.ldexp(ins["W"], -8), ins["e_prime"].astype(float)
    worst, valid, flagged = 0.0, 0, 0
    for a, b, w, e in zip(A, B, W, E):
        c = getattr(so, function)(a, b, w, e)
        try:
            ref = hertz_preview(a, b, w, e_prime_mpa=e, hertz_form=form)
        except InputRangeError:
            assert c.flags != 0 and c.a_mm == 0.0   # same domain: refused in both
            flagged += 1
            continue
        assert c.flags == 0
        for name, _ in _Fp64._fields_[:-1]:
            want = getattr(ref, name)
            worst = max(worst, abs(getattr(c, name) - want) / abs(want))
        valid += 1
    assert valid >= 8000 and flagged >= 500
    assert worst <= 1e-12, worst


@pytest.mark.parametrize("form", list(FORMS))
def test_fp64_fit_and_chain_within_1e12_of_the_python_reference(built, form):
    """The chain vectors' stencils (plausible elliptic ones and whole-range words).
    c0, c1, c2: within 1e-12 of the dot product's own scale sum_i |M_ji g_i| (the
    reference sums through BLAS in another order; its rounding is ~1e-16 of that
    scale, measured 3.6e-16). c3, c4, c5, A-, B- and ``elliptic``: equal bit for bit
    (both sum c3..c5 over the second differences about the centre with the same IEEE
    operations in the same order, fitted_coefficients; then the same closed form).
    Chain Hertz outputs where the reference accepts the stencil: 1e-12 relative, the
    issue's bound: with A-, B- equal, what differs is stage D alone, the cube root and
    libm's exp/log (as in the stage-D test above, measured 1.8e-15) and the chain's
    Hamrock-Brewe terms formed from A- and det = A- B- instead of A-, B- (a few ulps;
    measured 1.3e-15, exact Hertz 1.8e-15, on the AMD EPYC of session 19; 1.0e-12 before c3..c5 were summed
    over second differences: the BLAS sum's rounding, ~1e-16 of the stencil's offset
    and slopes, is up to 1e-12 of a near-cylindrical stencil's B-). The first 3,000
    stencils (corner cases first): the Python reference takes ~1 ms per stencil (exact
    Hertz: the first 1,000)."""
    lib, vec = built
    so = _library(lib)
    ins = read_hex(vec / "chain_in.hex", "chain", "in")
    gaps = np.ldexp(ins["wr_data"].astype(float), -STENCIL_GAP.frac)
    loads, moduli = np.ldexp(ins["W"].astype(float), -8), ins["e_prime"].astype(float)
    m = baked_pinv().weights
    worst_c = worst_hz = 0.0
    valid = refused = 0
    code = FORMS[form][0]
    count = FP64_STENCILS if form == "hamrock-brewe" else FP64_STENCILS // 3
    for g, w, e in zip(gaps[:count], loads, moduli):
        arr = (ctypes.c_double * 49)(*g)
        fit, ref = so.gc_fit_fp64(arr), fit_curvatures(g)
        scale = np.abs(m[:3] * g).sum(axis=1)
        dc = np.abs(np.array(fit.c[:3]) - np.array(ref.coefficients[:3]))
        assert (dc[scale == 0] == 0).all()
        worst_c = max(worst_c, float(np.max(dc / np.where(scale > 0, scale, 1.0))))
        assert list(fit.c[3:]) == list(ref.coefficients[3:])
        assert (fit.A_minus_per_mm, fit.B_minus_per_mm, bool(fit.elliptic)) \
            == (ref.A_minus_per_mm, ref.B_minus_per_mm, ref.elliptic)
        chain = so.gc_chain_fp64(arr, w, e, code)
        try:
            hz = chain_reference(g, w, e_prime_mpa=e, hertz_form=form).hertz
        except InputRangeError:
            assert chain.hertz.flags != 0
            refused += 1
            continue
        assert chain.hertz.flags == 0
        for name, _ in _Fp64._fields_[:-1]:
            want = getattr(hz, name)
            worst_hz = max(worst_hz, abs(getattr(chain.hertz, name) - want) / abs(want))
        valid += 1
    assert valid >= count // 2 and refused >= count // 10
    assert worst_c <= 1e-12 and worst_hz <= 1e-12, (worst_c, worst_hz)


def test_fp64_chain_does_the_same_work_for_every_stencil(built):
    """gc_chain_fp64 runs stage D on every stencil (gc_hertz_preview.h: operands outside
    the envelope replaced, the outputs masked by the flags), its terms from A-, det = A-
    B- and A-^2 / det instead of A-, B-. On every chain vector and on stencils no
    envelope admits (flat, NaN, 2^40 mm gaps, W and E' 0 or NaN): the flags are the
    envelope's of the fit's A-, B- (gc_hertz_fp64 on them; NOT_ELLIPTIC where B- <= 0),
    every output is +0.0 where a flag is set, errno stays 0 (libm's error path is never
    taken), and where the stencil is accepted the outputs are within 1e-13 relative of
    gc_hertz_fp64's on A-, B-: the two differ by the roundings of det against A- B- and
    of A-^2 / det against A- / B- (a few ulp), which the terms' exponents (at most 1 in
    magnitude) do not amplify (measured 1.1e-15, k; 6,688 accepted of 10,020)."""
    lib, vec = built
    so = _library(lib)
    errno_so = ctypes.CDLL(str(lib / "build" / "libgearcontact.so"), use_errno=True)
    errno_so.gc_chain_fp64.restype, errno_so.gc_chain_fp64.argtypes = \
        so.gc_chain_fp64.restype, so.gc_chain_fp64.argtypes
    ins = read_hex(vec / "chain_in.hex", "chain", "in")
    gaps = np.ldexp(ins["wr_data"].astype(float), -STENCIL_GAP.frac)
    loads, moduli = np.ldexp(ins["W"].astype(float), -8), ins["e_prime"].astype(float)
    nan = float("nan")
    cases = list(zip(gaps, loads, moduli)) + [
        (np.zeros(49), 100.0, 2.3e5), (np.full(49, nan), 100.0, 2.3e5),
        (np.full(49, 2.0 ** 40), 100.0, 2.3e5), (gaps[0], 0.0, 2.3e5),
        (gaps[0], nan, 2.3e5), (gaps[0], 100.0, 0.0), (-gaps[0], 100.0, nan)]
    names = [n for n, _ in _Fp64._fields_[:-1]]
    worst, kinds = 0.0, {True: 0, False: 0}
    ctypes.set_errno(0)
    for g, w, e in cases:
        c = errno_so.gc_chain_fp64((ctypes.c_double * 49)(*g), w, e, 0)
        fit = c.fit
        alone = so.gc_hertz_fp64(fit.A_minus_per_mm, fit.B_minus_per_mm, w, e)
        want = alone.flags if fit.elliptic else 1       # GC_HERTZ_FLAG_NOT_ELLIPTIC
        assert c.hertz.flags == want, (c.hertz.flags, want)
        outs = [getattr(c.hertz, n) for n in names]
        kinds[want == 0] += 1
        if want:
            assert all(x == 0.0 and math.copysign(1.0, x) == 1.0 for x in outs), outs
            continue
        for n, x in zip(names, outs):
            ref = getattr(alone, n)
            worst = max(worst, abs(x - ref) / abs(ref))
    assert ctypes.get_errno() == 0
    assert kinds[True] >= 5000 and kinds[False] >= 2000, kinds
    assert worst <= 1e-13, worst


class _Gap(ctypes.Structure):
    _fields_ = [("gap_mm", ctypes.c_double), ("idx", ctypes.c_int), ("valid", ctypes.c_int)]


def _doubles(a) -> ctypes.Array:
    a = np.ascontiguousarray(a, float).ravel()
    return (ctypes.c_double * a.size)(*a)


def test_fp64_gap_within_1e12_of_the_python_reference(built):
    """Seeded passes the reference accepts (orthonormal R, unit normals; the quantized
    vector operands are not, to its tolerances): 16 samples scattered within 1 mm of
    the posed point, gates of 0.2 to 2 mm. The winning sample and validity must be
    equal; gamma (a difference of coordinates of up to ~60 mm) within 1e-12 of the
    coordinates' magnitude (it is not a relative quantity: it may be ~0)."""
    lib, _ = built
    so = ctypes.CDLL(str(lib / "build" / "libgearcontact.so"))
    so.gc_gap_fp64.restype = _Gap
    ptr = ctypes.POINTER(ctypes.c_double)
    so.gc_gap_fp64.argtypes = [ptr] * 5 + [ctypes.c_double, ctypes.c_int]
    rng = np.random.default_rng(25)
    worst, valid = 0.0, 0
    for _ in range(2000):
        q, r = np.linalg.qr(rng.normal(size=(3, 3)))
        rot = q * np.sign(np.diag(r))
        rot = rot if np.linalg.det(rot) > 0 else -rot
        t, p = rng.uniform(-30, 30, 3), rng.uniform(-30, 30, 3)
        g = rot @ p + t + rng.uniform(-1, 1, (16, 3))
        nrm = rng.normal(size=(16, 3))
        nrm /= np.linalg.norm(nrm, axis=1)[:, None]
        tau = rng.uniform(0.2, 2.0)
        ref = gap_reference(rot, t, p, g, nrm, tau_mm=tau, lanes=16)
        c = so.gc_gap_fp64(_doubles(g), _doubles(nrm), _doubles(rot), _doubles(t),
                           _doubles(p), tau, 16)
        assert bool(c.valid) == ref.valid
        if ref.valid:
            assert c.idx == ref.min_idx
            worst = max(worst, abs(c.gap_mm - ref.min_gap_mm) / np.abs(g).max())
            valid += 1
    assert valid >= 1000
    assert worst <= 1e-12, worst


class _LineFp64(ctypes.Structure):
    _fields_ = [("mode", ctypes.c_uint32)] \
        + [(n, ctypes.c_double) for n in ("a_mm", "b_mm", "k", "p_max_mpa", "p_ellipse_mpa",
                                          "p_line_mpa")] + [("flags", ctypes.c_uint32)]


@pytest.mark.parametrize("stimulus", ["full", "short"])
@pytest.mark.parametrize("form", list(FORMS))
def test_fp64_line_core_within_1e12_of_the_python_reference(built, form, stimulus):
    """The line stimulus (3,000 random + corners, decoded) and 3,000 short lines
    (:func:`short_line_stimulus`: the host's lift below 1 mm) through
    :func:`truncated_preview` (envelope=True) and ``gc_line_fp64``: the same mode, every
    output within 1e-12 relative (measured: 1.1e-15 with Hamrock-Brewe, 1.6e-15
    exact), and an input the reference refuses is flagged (short lines: the lifted
    run's ellipse, or no lift)."""
    lib, _ = built
    so = ctypes.CDLL(str(lib / "build" / "libgearcontact.so"))
    so.gc_line_fp64.restype = _LineFp64
    so.gc_line_fp64.argtypes = [ctypes.c_double] * 5 + [ctypes.c_int]
    f = {k: np.asarray(v) for k, v in _line_vectors(stimulus, 3000).items()}
    cols = (np.ldexp(f["A"].astype(float), -20), np.ldexp(f["B"].astype(float), -20),
            np.ldexp(f["W"].astype(float), -8), np.ldexp(f["L"].astype(float), -20),
            f["e_prime"].astype(float))
    worst, modes = 0.0, set()
    for a, b, w, length, e in zip(*cols):
        c = so.gc_line_fp64(a, b, w, length, e, FORMS[form][0])
        try:
            ref = truncated_preview(a, b, w, length, e_prime_mpa=e, hertz_form=form)
        except InputRangeError:
            assert c.flags != 0
            continue
        assert c.flags == 0 and c.mode == {"elliptic": 0, "line": 1}[ref.mode]
        modes.add(ref.mode)
        for name, _ in _LineFp64._fields_[1:-1]:
            want = getattr(ref, name)
            worst = max(worst, abs(getattr(c, name) - want) / abs(want) if want
                        else abs(getattr(c, name)))
    assert modes == ({"elliptic", "line"} if stimulus == "full" else {"line"})
    assert worst <= 1e-12, worst


def test_golden_sources_hold_no_floating_point(built):
    lib, _ = built
    for name in GOLDEN_SOURCES + ("gc_tables.h",):
        code = re.sub(r"/\*.*?\*/", "", (lib / name).read_text(), flags=re.S)
        # no floating type, no libm, no decimal floating literal (1.5, 2e3)
        assert not re.search(r"\b(float|double)\b|math\.h|\b\d+\.\d*|\b\d+[eE][+-]?\d+\b",
                             code), name
    # the test would see them (the fp64 sources have them)
    assert re.search(r"\bdouble\b", (lib / "gc_hertz_fp64.c").read_text())
    assert re.search(r"\b\d+\.\d*", (lib / "gc_fit_fp64.c").read_text())


def test_roms_are_the_package_tables(built):
    lib, _ = built
    text = (lib / "gc_tables.c").read_text()
    for name, spec in (("pow", POW_SPEC), ("pow_exact", POW_EXACT_SPEC),
                       ("ee_exact", EE_EXACT_SPEC), ("cbrt", CBRT_SPEC)):
        body = re.search(rf"gc_rom_{name}\[256\] = \{{(.*?)\}};", text, re.S).group(1)
        words = tuple(int(w, 16) for w in re.findall(r"0x([0-9a-f]{8})u", body))
        assert words == rom_words(spec), name
    rows = re.search(r"gc_rom_fit\[6\]\[49\] = \{(.*?)\n\};", text, re.S).group(1)
    codes = [int(x) for x in re.findall(r"-?\d+", rows)]
    assert codes == [w for row in baked_pinv().weight_codes for w in row]


def test_identical_runs_write_identical_files(built):
    lib, _ = built
    again = render_c_library()          # a second run, in this process
    assert list(again) == list(C_FILES)
    for name, text in again.items():
        assert text.encode() == (lib / name).read_bytes(), name


def test_a_new_export_into_a_built_directory(tmp_path):
    """``make`` builds into build/, which the export keeps as the user's: a second export
    into the built directory succeeds (exit 0; the second make with the user's own
``CFLAGS=-O3``, which adds to the strict flags rather than replacing them), leaves build/ and a foreign-free
    directory (the export's files, run.json, build/), and make rebuilds from the new
    sources into a checker that runs; a file the export did not write is still
    refused (exit 2, named)."""
    lib = tmp_path / "lib"
    _gearcontact("export", "c", "--out", str(lib))
    for flags in ([], ["CFLAGS=-O3"]):
        # a CFLAGS of the user's own (second round) adds to the contract's flags
        make = subprocess.run(["make", "-C", str(lib), "CC=gcc", *flags], capture_output=True,
                              text=True, timeout=300)
        assert make.returncode == 0, make.stderr[-3000:]
        compiles = [ln for ln in make.stdout.splitlines() if " -c -o " in ln]
        assert compiles and all("-std=c99" in ln and "-Werror" in ln and "-fPIC" in ln
                                and "-ffp-contract=off" in ln for ln in compiles)
        assert all("-O3" in ln for ln in compiles) == bool(flags)
        assert (lib / "build" / "gearcontact_check").is_file()
        assert not list(lib.glob("*.o")) and not list(lib.glob("*.a"))
        _gearcontact("export", "c", "--out", str(lib))      # the rerun: accepted
        assert (lib / "build" / "libgearcontact.a").is_file()
    empty = tmp_path / "empty"
    empty.mkdir()
    run = subprocess.run([str(lib / "build" / "gearcontact_check"), str(empty)],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 2          # the checker runs (and refuses an empty directory)
    (lib / "notes.txt").write_text("mine")
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    run = subprocess.run([sys.executable, "-m", "gearcontact", "export", "c", "--out",
                          str(lib)], env=env, capture_output=True, text=True, timeout=600)
    assert run.returncode == 2 and "notes.txt" in run.stderr and "--force" in run.stderr


@pytest.mark.skipif(shutil.which("gcc") is None or shutil.which("objdump") is None
                    or os.uname().machine != "x86_64", reason="gcc, objdump on x86-64")
def test_a_cflags_of_the_users_cannot_turn_on_fma_contraction(tmp_path):
    """The contract's flags come after the user's CFLAGS (the compiler takes the last of
    two contradicting flags), so ``CFLAGS='-O2 -mfma -ffp-contract=fast -ffast-math'``
    compiles no fused multiply-add into the fp64 flavour (``gearcontact_check`` checks
    the golden flavour only, so nothing else would see it). Truth: the machine code --
    no ``vfmadd`` in build/gc_hertz_fp64.o; the control, the same file compiled with
    those flags last, has them (measured 15: the test can see a contraction)."""
    lib = tmp_path / "lib"
    _gearcontact("export", "c", "--out", str(lib))
    user = "-O2 -mfma -ffp-contract=fast -ffast-math"
    make = subprocess.run(["make", "-C", str(lib), "CC=gcc", f"CFLAGS={user}",
                           "build/gc_hertz_fp64.o"], capture_output=True, text=True,
                          timeout=120)
    assert make.returncode == 0, make.stderr[-3000:]

    def fmas(obj):
        dump = subprocess.run(["objdump", "-d", str(obj)], capture_output=True, text=True,
                              check=True, timeout=60).stdout
        return len(re.findall(r"\bvfn?m(add|sub)", dump))

    assert fmas(lib / "build" / "gc_hertz_fp64.o") == 0
    control = tmp_path / "control.o"
    subprocess.run(["gcc", "-std=c99", *user.split(), "-c", "-o", str(control),
                    str(lib / "gc_hertz_fp64.c")], check=True, timeout=120)
    assert fmas(control) > 0


#: Harness of :func:`test_fit_square_root_equals_the_rtl_recurrence`: the fit's static
#: isqrt_floor (table seed + two Newton steps) against the RTL's 32-step non-restoring
#: recurrence (gearcontact.preview.fit.golden.isqrt_nonrestoring, the previous C code).
_ISQRT_HARNESS = r"""
#include <stdio.h>
#include "gc_fit_golden.c"

static uint64_t rtl(uint64_t d)
{
    int64_t q = 0, rem = 0;
    int i;
    for (i = 31; i >= 0; --i) {
        int64_t pair = (int64_t)((d >> (2 * i)) & 3u);
        rem = rem >= 0 ? rem * 4 + pair - (q * 4 + 1) : rem * 4 + pair + (q * 4 + 3);
        q = q * 2 + (int64_t)(rem >= 0);
    }
    return (uint64_t)q;
}

/* Python's int.bit_length, one bit at a time (gc_bit_length's truth) */
static int bits(uint64_t d)
{
    int k = 0;
    for (; d; d >>= 1)
        ++k;
    return k;
}

static long bad, n;
static void check(uint64_t d)
{
    bad += gc_bit_length(d) != bits(d);
    if (d <= (uint64_t)GC_C_D_MAX_CODE) {
        bad += (uint64_t)isqrt_floor(d) != rtl(d);
        ++n;
    }
}

int main(void)
{
    uint64_t d, k, x = 88172645463325252u;
    int i;
    for (d = 0; d < ((uint64_t)1 << 20); ++d)          /* every small radicand */
        check(d);
    for (k = 1; k <= (uint64_t)GC_C_E_MAX_CODE + 1u; k += 1u + k / 4096u) {
        check(k * k - 1u);                             /* both sides of every square */
        check(k * k);
        check(k * k + 1u);
    }
    for (i = 0; i < 63; ++i) {                         /* powers of two and neighbours */
        check(((uint64_t)1 << i) - 1u);
        check((uint64_t)1 << i);
        check(((uint64_t)1 << i) + 1u);
    }
    for (i = 0; i < 1000000; ++i) {                    /* xorshift64 radicands */
        x ^= x << 13; x ^= x >> 7; x ^= x << 17;
        check(x >> 1);
        check(x >> (1 + i % 62));
    }
    printf("%ld %ld\n", n, bad);
    return 0;
}
"""


def test_fit_square_root_equals_the_rtl_recurrence(built, tmp_path):
    """The C fit computes r = floor(sqrt(d)) from a seed table and two Newton steps
    (proof in gc_fit_golden.c), not by the RTL's recurrence: the two agree on every
    radicand below 2^20, on k^2 - 1, k^2, k^2 + 1 for ~58,000 k up to
    isqrt(D_MAX) + 1, on 2^i and its neighbours and on 2 million random radicands. On
    the same words (every one, also beyond D_MAX) gc_bit_length, a count-leading-zeros
    instruction with GNU C, equals the bit-by-bit count."""
    lib, _ = built
    (tmp_path / "harness.c").write_text(_ISQRT_HARNESS)
    exe = tmp_path / "harness"
    run = subprocess.run(["gcc", *STRICT, "-O2", f"-I{lib}", "-o", str(exe),
                          str(tmp_path / "harness.c"), str(lib / "gc_hertz_golden.c"),
                          str(lib / "gc_tables.c")], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    n, bad = map(int, subprocess.run([str(exe)], capture_output=True, text=True,
                                     timeout=120, check=True).stdout.split())
    assert n > 3_000_000 and bad == 0, (n, bad)


def test_fit_mac_plan_multiplies_out_to_the_rom():
    """The regrouped golden MAC of gc_fit_golden.c (the stencil's orbit sums shared by
    every row, one multiply per distinct |word|, c3 and c5 as P = acc3 + acc5 and
    Q = acc3 - acc5) is the ROM's linear form exactly: expanded term by term, combined
    and halved it gives back every word, for the baked ROM (56 multiplies, 72 row by
    row: c0 10, c1 12, c2 12, c4 6 on their orbit sums, P 10 and Q 6 instead of 16 and
    16) and for a random integer matrix without symmetry (tap by tap, one multiply per
    distinct magnitude). Every form's sum_i |W_i| stays below 2^32: partial sums below
    2^31 2^32 = 2^63 (int64); the C code's P +- Q are 2 acc_j, below 2^32 L1(M_j)."""
    rom = tuple(tuple(int(w) for w in row) for row in baked_pinv().weight_codes)
    plan = fit_mac_plan()
    assert expand_fit_mac_plan(plan) == rom
    assert [f["parity"] for f in plan["forms"]] == [(0, 0), (1, 0), (0, 1), (0, 0), (0, 0),
                                                    (1, 1)]
    assert [len(f["terms"]) for f in plan["forms"]] == [10, 12, 12, 10, 6, 6]
    assert [c["halve"] for c in plan["coeffs"]] == [0, 0, 0, 1, 0, 1]
    assert fit_mac_ops(plan) == {"muls": 56, "adds": 157}
    for f in plan["forms"]:                   # the width bound, recomputed on the taps
        w = [0] * 49
        for t in f["terms"]:
            for sign, keys in ((1, t["plus"]), (-1, t["minus"])):
                for a, b in keys:
                    for tap, s in orbit_members(a, b, f["parity"]):
                        w[tap] += sign * s * t["word"]
        assert sum(map(abs, w)) < 2 ** 32
    assert max(sum(map(abs, r)) for r in rom) < 2 ** 31
    rnd = tuple(tuple(int(w) for w in row)
                for row in np.random.default_rng(0).integers(-9, 10, (6, 49)))
    other = fit_mac_plan(rnd)
    assert expand_fit_mac_plan(other) == rnd
    assert {f["parity"] for f in other["forms"]} == {None}
    assert fit_mac_ops(other)["muls"] == sum(len({abs(w) for w in r if w}) for r in rnd)


def test_orbit_sums_partition_the_stencil():
    """The 49 orbit sums u_p(a, b) are a change of basis of the 49 samples with +-1
    entries: every tap once per parity class it belongs to (4 orbits of 4 points, 12 of
    2 and the centre), and the sums of the four classes over one orbit recover 4 g(a, b)
    at its point (a, b >= 0) (the C butterfly's signs, written out here)."""
    keys = [(a, b, p) for p in ((0, 0), (1, 0), (0, 1), (1, 1)) for a in range(4)
            for b in range(4) if (a or not p[0]) and (b or not p[1])]
    assert len(keys) == 49
    for p in ((0, 0), (1, 0), (0, 1), (1, 1)):
        taps = [t for a, b, q in keys if q == p for t, _ in orbit_members(a, b, q)]
        assert len(taps) == len(set(taps))
    assert sorted(t for a, b, q in keys if q == (0, 0)
                  for t, _ in orbit_members(a, b, q)) == list(range(49))
    # u00 + u10 + u01 + u11 at (a, b) = 4 g(a, b): s = a is column 3 + a, t = b row 3 + b
    for a in range(1, 4):
        for b in range(1, 4):
            total = {}
            for q in ((0, 0), (1, 0), (0, 1), (1, 1)):
                for tap, s in orbit_members(a, b, q):
                    total[tap] = total.get(tap, 0) + s
            assert {t: v for t, v in total.items() if v} == {7 * (3 + b) + 3 + a: 4}


def _c_lanes(text: str, table: str) -> list[list[float]]:
    """The GC_LANES(...) groups of the C table ``table``, as doubles."""
    body = text[text.index(f"static const gc_lanes {table}"):]
    body = body[:body.index("};")]
    return [[float.fromhex(w) for w in m.group(1).split(", ")]
            for m in re.finditer(r"GC_LANES\((.*?)\)", body)]


def test_fp64_fit_applies_every_weight_bit_for_bit(built):
    """gc_fit_fp64.c's tables hold the fp64 pseudo-inverse's own words. c0, c1, c2: its
    hexadecimal literals, read back in lane order (FIT_LANES consecutive taps per
    vector, then the remaining taps), give every weight exactly, each tap once. c3, c4,
    c5 (over the second differences about the centre, gc_fit_fp64.c): expanded back
    onto the taps in exact rational arithmetic (tap i < 24: pair_i; its reflection
    48 - i: pair_i + skew_i; the centre: total - sum (2 pair_i + skew_i)), every weight
    exactly, but for the roundings of skew and total: within half an ulp of each
    (2^-53 relative), ~1e-30 of a weight."""
    from fractions import Fraction
    lib, _ = built
    text = (lib / "gc_fit_fp64.c").read_text()
    groups = _c_lanes(text, "FIT_M")
    rows = [[float(w) for w in row] for row in baked_pinv().weights]
    per_row = 49 // FIT_LANES
    assert len(groups) == 3 * per_row and all(len(g) == FIT_LANES for g in groups)
    for j, row in enumerate(rows[:3]):
        got = [w for g in groups[j * per_row:(j + 1) * per_row] for w in g]
        tail = re.search(rf"c\[{j}\] = .*?;", text).group(0)
        got += [float.fromhex(w) for w in re.findall(r"(-?0x[0-9a-f.]+p[-+]\d+) \* gaps_mm", tail)]
        assert got == row
    pair, skew = _c_lanes(text, "FIT_PAIR"), _c_lanes(text, "FIT_SKEW")
    total = [float.fromhex(w) for w in re.search(r"FIT_TOTAL\[3\] = \{(.*?)\}", text)
             .group(1).split(", ")]
    per_row = 24 // FIT_LANES
    assert len(pair) == len(skew) == 3 * per_row
    ulp = Fraction(1, 2 ** 53)
    for j, row in enumerate(rows[3:]):
        p = [Fraction(w) for g in pair[j * per_row:(j + 1) * per_row] for w in g]
        k = [Fraction(w) for g in skew[j * per_row:(j + 1) * per_row] for w in g]
        want = [Fraction(w) for w in row]
        assert p == want[:24]
        assert all(abs(a + b - want[48 - i]) <= ulp * abs(b) for i, (a, b) in enumerate(zip(p, k)))
        centre = Fraction(total[j]) - sum(2 * a + b for a, b in zip(p, k))
        assert abs(centre - want[24]) <= ulp * (abs(Fraction(total[j])) + sum(map(abs, k)))


#: Harness of :func:`test_fp64_fit_same_bits_with_and_without_simd`: gc_fit_fp64 on
#: xorshift stencils (gaps of either sign over six decades) and gc_chain_fp64 on them
#: scaled down, every output as hexadecimal.
_LANES_HARNESS = r"""
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include "gearcontact.h"

int main(void)
{
    uint64_t x = 88172645463325252u;
    double g[GC_FIT_TAPS];
    int n, i;
    for (n = 0; n < 2000; ++n) {
        gc_fit_fp64_result r;
        for (i = 0; i < GC_FIT_TAPS; ++i) {
            x ^= x << 13; x ^= x >> 7; x ^= x << 17;
            g[i] = ((double)(x >> 11) / 9007199254740992.0 - 0.3) * (double)(1 << (n % 20));
        }
        gc_chain_fp64_result c;
        r = gc_fit_fp64(g);
        for (i = 0; i < 6; ++i)
            printf("%a ", r.c[i]);
        printf("%a %a %d ", r.A_minus_per_mm, r.B_minus_per_mm, r.elliptic);
        /* the chain on a 2^-24 share of the stencil: some accepted, most refused */
        for (i = 0; i < GC_FIT_TAPS; ++i)
            g[i] = ldexp(g[i], -24);
        c = gc_chain_fp64(g, 50.0 + n, 2.3e5, 0);
        printf("%a %a %a %a %a %u\n", c.hertz.a_mm, c.hertz.b_mm, c.hertz.p_max_mpa,
               c.hertz.approach_mm, c.hertz.alpha, c.hertz.flags);
    }
    return 0;
}
"""


def test_fp64_fit_same_bits_with_and_without_simd(built, tmp_path):
    """The fit's lanes give the same bits as a GNU C vector (SSE2 on x86-64), as four
    doubles one by one (-DGC_SCALAR_LANES, the code other compilers get) and as one AVX
    register (-mavx2, where the CPU has it): the same operations in the same order. So
    does the chain's stage D with its selections by SSE2 masks and by conditional
    expressions (-DGC_PORTABLE_SELECT, other targets)."""
    lib, _ = built
    (tmp_path / "harness.c").write_text(_LANES_HARNESS)
    flavours = {"vector": [], "scalar": ["-DGC_SCALAR_LANES"],
                "portable": ["-DGC_SCALAR_LANES", "-DGC_PORTABLE_SELECT"]}
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.exists() and " avx2" in cpuinfo.read_text():
        flavours["avx2"] = ["-mavx2"]
    outputs = {}
    for name, flags in flavours.items():
        exe = tmp_path / name
        run = subprocess.run(["gcc", *STRICT, "-O2", "-ffp-contract=off", *flags, f"-I{lib}",
                              "-o", str(exe), str(tmp_path / "harness.c"),
                              # gc_hertz_golden.c: the fp64 line takes the golden lift's
                          # domain (gc_line_length_lift), as Python's fp64 reference does
                          *(str(lib / n) for n in ("gc_fit_fp64.c", "gc_hertz_fp64.c",
                                                   "gc_hertz_golden.c", "gc_tables.c")),
                          "-lm"],
                             capture_output=True, text=True, timeout=120)
        assert run.returncode == 0, (name, run.stderr)
        outputs[name] = subprocess.run([str(exe)], capture_output=True, text=True,
                                       timeout=60, check=True).stdout
    assert outputs["vector"].count("\n") == 2000
    assert all(out == outputs["vector"] for out in outputs.values()), list(outputs)


#: Harness of :func:`test_fp64_cube_root_within_5_ulp_of_the_exact_root`: gc_cbrt.h's
#: gc_cbrt_positive (the fp64 Hertz forms' and the FMUs' golden kappa's) on edge and xorshift inputs (random bit patterns of positive
#: doubles), each printed with its result as hexadecimal floats.
_CBRT_HARNESS = r"""
#include <stdio.h>
#include "gc_cbrt.h"

static void show(double x)
{
    printf("%a %a\n", x, gc_cbrt_positive(x));
}

int main(void)
{
    static const double edges[] = {1.0, 2.0, 4.0, 8.0, 27.0, 0.125, 1.5, 0.75, 3.0,
                                   DBL_MIN, DBL_MAX, 0.0, 1e-310, 5e-324};
    uint64_t x = 88172645463325252u, bits;
    double v;
    int i;
    for (i = 0; i < (int)(sizeof edges / sizeof edges[0]); ++i) {
        show(edges[i]);
        show(nextafter(edges[i], 0.0));
        show(nextafter(edges[i], 1e308));
    }
    for (i = -1074; i < 1024; ++i)
        show(ldexp(1.0, i));
    for (i = 0; i < 100000; ++i) {
        x ^= x << 13; x ^= x >> 7; x ^= x << 17;
        bits = x >> 1;                        /* positive: every exponent, subnormals too */
        memcpy(&v, &bits, sizeof v);
        if (v <= DBL_MAX)
            show(v);
    }
    return 0;
}
"""


def test_fp64_cube_root_within_5_ulp_of_the_exact_root(built, tmp_path):
    """The Hamrock-Brewe forms' and the golden kappa's cube root (gc_cbrt.h, a seed
    polynomial and one Halley step instead of libm's cbrt; proof of the 5 ulp bound in
    its comment), against the exact root in rational arithmetic (no libm): (y - 5 ulp)^3 <= x <=
    (y + 5 ulp)^3 for every positive normal input (powers of two over the whole range,
    neighbours of edges, 100,000 random bit patterns; measured 3.25 ulp). Zero,
    subnormals go to libm's cbrt: equal to math.cbrt (the same libm). Every result
    equals the twin's compiled cube root bit for bit (gearcontact.analytic.cube_root
    under numba, the drivetrain FMU's law repeats the twin's)."""
    from fractions import Fraction

    from gearcontact.twin.contact_law import _cbrt_positive
    lib, _ = built
    (tmp_path / "harness.c").write_text(_CBRT_HARNESS)
    exe = tmp_path / "harness"
    run = subprocess.run(["gcc", *STRICT, "-D_DEFAULT_SOURCE", "-O2", "-ffp-contract=off",
                          f"-I{lib}", "-o", str(exe), str(tmp_path / "harness.c"), "-lm"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    lines = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120,
                           check=True).stdout.split("\n")
    normal = worst = 0
    for line in filter(None, lines):
        x, y = (float.fromhex(w) for w in line.split())
        assert y == _cbrt_positive(x), (x, y)
        if not 2.2250738585072014e-308 <= x <= 1.7976931348623157e308:
            assert y == math.cbrt(x) or (x != x and y != y), (x, y)
            continue
        ulp = Fraction(math.ulp(y))
        fx, fy = Fraction(x), Fraction(y)
        k = next(k for k in range(6) if (fy - k * ulp) ** 3 <= fx <= (fy + k * ulp) ** 3)
        worst = max(worst, k)
        normal += 1
    assert normal > 100_000 and worst <= 5, worst
