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
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gearcontact.export.c_library import C_FILES, GOLDEN_SOURCES, render_c_library
from gearcontact.hw.vectors import read_hex
from gearcontact.preview.hertz.luts import (CBRT_SPEC, EE_EXACT_SPEC, POW_EXACT_SPEC,
                                            POW_SPEC, rom_words)
from gearcontact.preview.hertz.reference import hertz_preview
from gearcontact.validation import InputRangeError

ROOT = Path(__file__).resolve().parents[2]
COUNT = 10_000                      # random vectors per core (the corner cases on top)
CORES = ("hertz", "hertz_exact")
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
def built(tmp_path_factory):
    """An export built with its Makefile, and the vectors of the Hertz cores."""
    base = tmp_path_factory.mktemp("cexport")
    lib, vec = base / "lib", base / "vectors"
    _gearcontact("export", "c", "--out", str(lib))
    make = subprocess.run(["make", "-C", str(lib), "CC=gcc"], capture_output=True,
                          text=True, timeout=300)
    assert make.returncode == 0, make.stdout[-3000:] + make.stderr[-3000:]
    _gearcontact("vectors", "--out", str(vec), "--count", str(COUNT), "--cores",
                 ",".join(CORES))
    return lib, vec


def _check(lib: Path, vec: Path):
    return subprocess.run([str(lib / "gearcontact_check"), str(vec)], capture_output=True,
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


def test_checker_names_the_core_of_a_corrupted_output_word(built, tmp_path):
    lib, vec = built
    bad = tmp_path / "vectors"
    shutil.copytree(vec, bad)
    path = bad / "hertz_exact_out.hex"
    lines = path.read_text().splitlines()
    k = 500
    word = lines[k][16:24]                      # output field 2, p_max (8 digits)
    lines[k] = lines[k][:16] + f"{int(word, 16) ^ 1:08x}" + lines[k][24:]
    path.write_text("\n".join(lines) + "\n")
    run = _check(lib, bad)
    assert run.returncode == 1
    n = len(lines)
    assert f"hertz_exact: {n} vectors, 1 mismatches" in run.stdout.splitlines()
    assert f"hertz: {n} vectors, 0 mismatches" in run.stdout.splitlines()
    assert f"hertz_exact: vector {k} field p_max" in run.stderr


def test_checker_refuses_a_truncated_file_and_an_empty_directory(built, tmp_path):
    lib, vec = built
    bad = tmp_path / "vectors"
    bad.mkdir()
    assert _check(lib, bad).returncode == 2
    shutil.copy(vec / "hertz_in.hex", bad)
    (bad / "hertz_out.hex").write_text("".join((vec / "hertz_out.hex").open().readlines()[:-1]))
    run = _check(lib, bad)
    assert run.returncode == 2 and "hertz: line" in run.stderr


class _Fp64(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("a_mm", "b_mm", "k", "p_max_mpa", "alpha",
                                               "R_x_mm", "R_y_mm", "approach_mm")] \
        + [("flags", ctypes.c_uint32)]


def test_fp64_c_within_1e12_of_the_python_reference(built):
    lib, vec = built
    so = ctypes.CDLL(str(lib / "libgearcontact.so"))
    so.gc_hertz_fp64.restype = _Fp64
    so.gc_hertz_fp64.argtypes = [ctypes.c_double] * 4
    ins = read_hex(vec / "hertz_in.hex", "hertz", "in")
    A, B = np.ldexp(ins["A"], -20), np.ldexp(ins["B"], -20)
    W, E = np.ldexp(ins["W"], -8), ins["e_prime"].astype(float)
    worst, valid, flagged = 0.0, 0, 0
    for a, b, w, e in zip(A, B, W, E):
        c = so.gc_hertz_fp64(a, b, w, e)
        try:
            ref = hertz_preview(a, b, w, e_prime_mpa=e)
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


def test_golden_sources_hold_no_floating_point(built):
    lib, _ = built
    for name in GOLDEN_SOURCES + ("gc_tables.h",):
        code = re.sub(r"/\*.*?\*/", "", (lib / name).read_text(), flags=re.S)
        # no floating type, no libm, no decimal floating literal (1.5, 2e3)
        assert not re.search(r"\b(float|double)\b|math\.h|\b\d+\.\d*|\b\d+[eE][+-]?\d+\b",
                             code), name
    # the test would see them (the fp64 source has all three)
    assert re.search(r"\bdouble\b", (lib / "gc_hertz_fp64.c").read_text())


def test_roms_are_the_package_tables(built):
    lib, _ = built
    text = (lib / "gc_tables.c").read_text()
    for name, spec in (("pow", POW_SPEC), ("pow_exact", POW_EXACT_SPEC),
                       ("ee_exact", EE_EXACT_SPEC), ("cbrt", CBRT_SPEC)):
        body = re.search(rf"gc_rom_{name}\[256\] = \{{(.*?)\}};", text, re.S).group(1)
        words = tuple(int(w, 16) for w in re.findall(r"0x([0-9a-f]{8})u", body))
        assert words == rom_words(spec), name


def test_identical_runs_write_identical_files(built):
    lib, _ = built
    again = render_c_library()          # a second run, in this process
    assert list(again) == list(C_FILES)
    for name, text in again.items():
        assert text.encode() == (lib / name).read_bytes(), name
