"""``gearcontact export c --hertz-form exact``: the twin's exact Hertz law in the C library
(``gc_hertz_exact_table_fp64``, gc_hertz_exact_table.h/.c).

Truth: exact elliptic Hertz with scipy's Carlson integrals and a Brent solve of the
eccentricity equation (:func:`gearcontact.analytic.hertz.exact_elliptic_hertz`, 4 eps),
independent of the table, at random points off the table's grid; and the twin's
compiled law (:func:`gearcontact.twin.exact_hertz.exact_hertz_terms`), which the C
repeats operation by operation on the same doubles. The library is exported and built
once per module the way a user does (``python -m gearcontact export c --hertz-form
exact``, ``make``).
"""

from __future__ import annotations

import ctypes
import difflib
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gearcontact.analytic.hertz import exact_elliptic_hertz
from gearcontact.export.c_library import C_FILES, EXACT_FILES, render_c_library
from gearcontact.twin.exact_hertz import (RATIO_MAX, REL_BOUND, STEP, exact_hertz_table,
                                          exact_hertz_terms)

ROOT = Path(__file__).resolve().parents[2]
E_PRIME = 226373.6      # steel on steel, MPa (E 206 GPa, nu 0.3)
#: C against the twin's compiled law: the same operations on the same doubles and the
#: same libm give the same bits (measured: identical). The bound leaves room for a libm
#: whose log/exp round differently by an ulp: log(alpha) <= 18.5 off by an ulp
#: (3.6e-15) moves ln c_a, ln sqrt(p), ln K by at most that times their slope in
#: ln alpha (< 1), i.e. < 4e-15 relative in a, b, p_max, the approach, plus an ulp of
#: each exp (1.1e-16) and 5 ulp of the cube root: below 1e-14.
TWIN_REL = 1e-14

pytestmark = pytest.mark.skipif(
    shutil.which("gcc") is None or shutil.which("make") is None,
    reason="gcc and make are needed to build the exported C library (Debian: gcc make)")


def _gearcontact(*argv, cwd=None):
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    return subprocess.run([sys.executable, "-m", "gearcontact", *argv], env=env, cwd=cwd,
                          capture_output=True, text=True, timeout=600)


class _Fp64(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("a_mm", "b_mm", "k", "p_max_mpa", "alpha",
                                               "R_x_mm", "R_y_mm", "approach_mm")] \
        + [("flags", ctypes.c_uint32)]


@pytest.fixture(scope="module")
def exact_lib(tmp_path_factory):
    """``(export directory, gc_hertz_exact_table_fp64, the header's text)``."""
    lib = tmp_path_factory.mktemp("cexact") / "clib"
    run = _gearcontact("export", "c", "--hertz-form", "exact", "--out", str(lib))
    assert run.returncode == 0, run.stderr
    make = subprocess.run(["make", "-C", str(lib), "CC=gcc", "build/libgearcontact.so"],
                          capture_output=True, text=True, timeout=600)
    assert make.returncode == 0, make.stderr
    so = ctypes.CDLL(str(lib / "build" / "libgearcontact.so"))
    fn = so.gc_hertz_exact_table_fp64
    fn.argtypes = [ctypes.c_double] * 4
    fn.restype = _Fp64
    return lib, fn, (lib / "gearcontact.h").read_text()


def _points(n: int, seed: int, ratio_hi: float):
    """``(A-, B-, W)``: A- log-uniform in 1e-4 .. 0.1 1/mm, the ratio B-/A- log-uniform in
    1 .. ratio_hi, W log-uniform in 1 .. 1e5 N; plus ratios on the table's first interval
    (its one-sided stencil) and at grid midpoints, all off the grid nodes."""
    rng = np.random.default_rng(seed)
    u = np.concatenate([rng.uniform(0.0, math.log(ratio_hi), n),
                        rng.uniform(0.0, 2.0 * STEP, 8), (np.arange(8) * 97 + 0.5) * STEP])
    lo = 10.0 ** rng.uniform(-4.0, -1.0, u.size)
    return lo, lo * np.exp(u), 10.0 ** rng.uniform(0.0, 5.0, u.size)


def test_c_exact_law_against_scipy_exact_hertz(exact_lib):
    """a, b, p_max and the approach within REL_BOUND = 1e-8 relative of exact Hertz
    (scipy), over curvature ratios 1 .. 1.4e5 (axis ratios to ~1000) and loads
    1 .. 1e5 N, A and B passed in either order. The bound is the twin's declared one
    (gearcontact.twin.exact_hertz, before its test ran): the 4-point cubic at h = 0.02
    errs by at most h^4 |f''''| 3/128 in each log (a few 1e-10 for these smooth
    functions of ln alpha), the fp64 roundings (cube root 5 ulp, exp, products) ~1e-15;
    1e-8 leaves a factor ~30 over the interpolation. Measured: docs/hertz.md sec. 7."""
    _, fn, _ = exact_lib
    err = []
    for k, (lo, hi, w) in enumerate(zip(*_points(500, 3, 1.4e5))):
        ex = exact_elliptic_hertz(lo, hi, w, e_prime_mpa=E_PRIME)
        r = fn(hi, lo, w, E_PRIME) if k % 2 else fn(lo, hi, w, E_PRIME)
        assert r.flags == 0
        err.append([r.a_mm / ex.a_mm, r.b_mm / ex.b_mm, r.p_max_mpa / ex.p_max_mpa,
                    r.approach_mm / ex.approach_mm])
    err = np.abs(np.array(err) - 1.0)
    assert err.max() < REL_BOUND, err.max(axis=0)


def test_c_exact_law_is_the_twin_law(exact_lib):
    """The C law equals the twin's compiled exact_hertz_terms within TWIN_REL (its
    derivation above) over the whole table, curvature ratios 1 .. RATIO_MAX (1e8)."""
    _, fn, _ = exact_lib
    tab = exact_hertz_table()
    worst = 0.0
    for lo, hi, w in zip(*_points(2000, 5, RATIO_MAX)):
        r = fn(lo, hi, w, E_PRIME)
        want = exact_hertz_terms(lo, hi, w, E_PRIME, tab, 0)
        got = (r.a_mm, r.b_mm, r.p_max_mpa, r.approach_mm)
        worst = max(worst, max(abs(g / t - 1.0) for g, t in zip(got, want)))
    assert worst <= TWIN_REL, worst


def test_c_exact_law_has_no_answer_beyond_the_table(exact_lib):
    """Beyond the table's curvature ratio the C law flags GC_HERTZ_FLAG_BEYOND_EXACT_TABLE
    with every output 0 (the twin: no contact law there, never extrapolated or
    clipped); a saddle or a flat direction flags not elliptic; at the table's end it
    answers."""
    _, fn, header = exact_lib
    assert "#define GC_HERTZ_FLAG_BEYOND_EXACT_TABLE 128u" in header
    lo = 1e-6
    beyond = fn(lo, lo * RATIO_MAX * 1.000001, 100.0, E_PRIME)
    assert beyond.flags == 128
    assert (beyond.a_mm, beyond.b_mm, beyond.p_max_mpa, beyond.approach_mm) == (0, 0, 0, 0)
    at_end = fn(lo, lo * RATIO_MAX, 100.0, E_PRIME)
    assert at_end.flags == 0 and at_end.approach_mm > 0.0
    for a, b in ((0.0, 0.1), (-0.01, 0.1)):
        assert fn(a, b, 100.0, E_PRIME).flags == 1      # GC_HERTZ_FLAG_NOT_ELLIPTIC


def test_default_export_is_unchanged_by_the_exact_form():
    """The default export is the Hamrock-Brewe one, file for file; the exact form adds
    its two files and changes only gearcontact.h (inserted lines) and the Makefile
    (every other file byte-identical; each line of the default it replaces is replaced
    by one naming gc_hertz_exact_table, none removed)."""
    default = render_c_library()
    assert tuple(default) == C_FILES
    assert render_c_library(hertz_form="hamrock-brewe") == default
    assert not any("exact_table" in text for text in default.values())
    exact = render_c_library(hertz_form="exact")
    assert set(exact) == set(C_FILES) | set(EXACT_FILES)
    for name, text in default.items():
        if name in ("gearcontact.h", "Makefile"):
            old, new = text.splitlines(), exact[name].splitlines()
            ops = difflib.SequenceMatcher(None, old, new, autojunk=False).get_opcodes()
            changed = [op for op in ops if op[0] != "equal"]
            assert changed and all(
                tag in ("insert", "replace") and j2 - j1 >= i2 - i1
                and (tag == "insert" or all("gc_hertz_exact_table" in line
                                            for line in new[j1:j2]))
                for tag, i1, i2, j1, j2 in changed), (name, changed)
        else:
            assert exact[name] == text, name


def test_export_c_refuses_a_bad_form_and_reruns_identically(tmp_path):
    """A misspelt form exits 2 naming the option before any file is written; a second
    export into the same directory writes the same files."""
    bad = _gearcontact("export", "c", "--hertz-form", "Exact", "--out",
                       str(tmp_path / "bad"))
    assert bad.returncode == 2 and "--hertz-form" in bad.stderr and "exact" in bad.stderr
    assert not (tmp_path / "bad").exists()
    out = tmp_path / "clib"
    texts = []
    for _ in range(2):
        assert _gearcontact("export", "c", "--hertz-form", "exact", "--out",
                            str(out)).returncode == 0
        texts.append({p.name: p.read_bytes() for p in sorted(out.iterdir())
                      if p.name != "run.json"})
    assert texts[0] == texts[1] and set(EXACT_FILES) <= set(texts[0])
