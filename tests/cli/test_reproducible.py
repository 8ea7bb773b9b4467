"""Identical runs write byte-identical result files; timings live only in run.json.

Truth: two runs of the same command into two directories give files with equal bytes
(figures included), and the run manifests list the same files with the same SHA-256 —
so every difference between the manifests is a timing, a time stamp or the path.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import gearcontact
from gearcontact.cli import main
from gearcontact.cli.outdir import MANIFEST


@pytest.mark.parametrize("argv", [
    ["tca", "--pair", "s0003-centred", "--phases", "5", "--quiet"],
    ["ltca", "--pair", "s0003-centred", "--phases", "5", "--cells", "24", "--export-problem"],
])
def test_identical_runs_identical_files(tmp_path, argv):
    outs = [tmp_path / "a", tmp_path / "b"]
    for out in outs:
        assert main(argv + ["--out", str(out)]) == 0
    _assert_identical_files(outs)


def test_identical_multi_tooth_runs_identical_files(multi_tooth_runs):
    """The multi-tooth LTCA of the calibrated s0003 (tests/cli/conftest.py
    MULTI_TOOTH_ARGV, figures included), run twice by the fixture that
    test_ltca.py::test_multi_tooth asserts on."""
    _assert_identical_files(multi_tooth_runs)


def _assert_identical_files(outs):
    """The two run directories ``outs`` hold the same files with the same bytes, their
    manifests the same SHA-256; timings only in the manifest."""
    manifests = [json.loads((d / MANIFEST).read_text()) for d in outs]
    files = [{f["path"]: f["sha256"] for f in m["files"]} for m in manifests]
    assert files[0] == files[1] and files[0]
    for name in files[0]:
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes(), name
    # the timings are in the manifest, and nowhere in the result files
    assert manifests[0]["timings_s"]
    for name in files[0]:
        if name.endswith((".json", ".csv", ".md")):
            text = (outs[0] / name).read_text()
            assert "timings_s" not in text and "solve_ms" not in text, name


@pytest.mark.slow
def test_a_pair_without_easeoff_writes_identical_files(tmp_path, bare_pair_file):
    """A pair file without an [easeoff.drive] table: analyze synthesizes the ease-off in
    each run and summary.md carries its block, with the same bytes in both runs (the
    note counts TCA runs, not seconds); the synthesis time is in run.json only. Slow:
    two syntheses (~15 s CPU each); the default suite checks the note itself
    (tests/cli/test_pair_preparation.py::test_the_note_holds_no_timing)."""
    argv = ["analyze", "--pair", str(bare_pair_file), "--side", "drive", "--phases", "5",
            "--lte-phases", "0", "--torques", "64.5", "--no-figures", "--quiet"]
    outs = [tmp_path / "a", tmp_path / "b"]
    for out in outs:
        assert main(argv + ["--out", str(out)]) == 0
    manifests = [json.loads((d / MANIFEST).read_text()) for d in outs]
    files = [{f["path"]: f["sha256"] for f in m["files"]} for m in manifests]
    assert files[0] == files[1] and "summary.md" in files[0]
    summary = (outs[0] / "summary.md").read_text()
    assert "**Ease-off synthesized.**" in summary and "[easeoff.drive]" in summary
    assert all(m["timings_s"]["easeoff_synthesis_s"] > 0 for m in manifests)


def _run_cli(argv, out, *, hash_seed, env=None):
    """``gearcontact argv --out out`` in a fresh interpreter (its own hash seed and
    object addresses, as two separate runs have), with ``env`` added to the
    environment."""
    src = str(Path(gearcontact.__file__).parents[1])
    env = {**os.environ, **(env or {}), "PYTHONHASHSEED": str(hash_seed),
           "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
    proc = subprocess.run([sys.executable, "-m", "gearcontact", *argv, "--out", str(out)],
                          env=env, capture_output=True, text=True, timeout=600, check=False)
    assert proc.returncode == 0, proc.stderr[-2000:]


@pytest.mark.parametrize("argv", [
    ["vectors", "--count", "20"],
    ["rtl", "verilog", "--core", "chain"],   # fit + hertz sources (all: 7 cores, ~30 s CPU)
    ["rtl", "soc"],
], ids=["vectors", "rtl-verilog", "rtl-soc"])
def test_generated_files_identical_across_runs_and_places(tmp_path, argv):
    """Two runs in separate processes (other hash seeds), into directories of other
    names and depths, write the same files with the same bytes; no file names the
    output directory or the installation path (Amaranth ``src`` attributes, LiteX
    dates and Yosys script paths are rewritten by :mod:`gearcontact.hw.reproducible`)."""
    if argv[:2] == ["rtl", "soc"]:
        pytest.importorskip("litex")
    outs = [tmp_path / "a", tmp_path / "deeper" / "other_name"]
    for seed, out in enumerate(outs):
        _run_cli(argv, out, hash_seed=seed)
    trees = [sorted(p.relative_to(o).as_posix() for p in o.rglob("*")
                    if p.is_file() and not p.name.startswith((".", MANIFEST)))
             for o in outs]
    assert trees[0] == trees[1] and trees[0]
    install = str(Path(gearcontact.__file__).parents[1])
    for name in trees[0]:
        data = (outs[0] / name).read_bytes()
        assert data == (outs[1] / name).read_bytes(), name
        assert str(tmp_path).encode() not in data, name
        assert install.encode() not in data, name
        assert b'src = "/' not in data, name    # Amaranth source paths import-relative


#: Commands whose results go through dense or sparse linear algebra (the shell, the FE,
#: the bending LCPs): small sizes, run in fresh processes.
THREADED = {
    "lte": ["lte", "--phases", "11", "--cells", "24", "--quiet", "--no-figures"],
    "ltca-multi-tooth": ["ltca", "--phases", "11", "--cells", "40", "--multi-tooth",
                         "--multi-tooth-cells", "24", "--quiet", "--no-figures"],
    "bending-fe": ["bending", "--points", "3", "3", "--fe", "--fe-mesh", "6", "4", "2", "2",
                   "--no-figures"],
    "twin-bending": ["twin", "--phases", "11", "--duration-ms", "3", "--bending", "--quiet",
                     "--no-figures"],
}

#: The environment of a run with every thread pool at one thread (as Dask's workers
#: set it, distributed.nanny.pre-spawn-environ).
ONE_THREAD = {k: "1" for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS",
                               "NUMBA_NUM_THREADS")}


@pytest.mark.slow
@pytest.mark.parametrize("argv", THREADED.values(), ids=THREADED.keys())
def test_a_run_in_process_equals_fresh_runs_with_any_thread_count(tmp_path, argv):
    """One run in this process, after the others of this module, and two in fresh
    processes, one with the thread pools as found and one with every pool at one thread:
    the same result files, byte for byte (before the shell and the FE ran their BLAS on
    one thread, the loaded TE with bending moved by 1.6e-9 arcsec and the FE compliance
    by 1e-15 relative between 1 and 2 threads). Slow: four commands, 1-2 min CPU each
    (the in-process half of it for the light commands is
    test_identical_runs_identical_files)."""
    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: every pool runs one thread either way")
    here, fresh, one = tmp_path / "here", tmp_path / "fresh", tmp_path / "one"
    assert main(argv + ["--out", str(here)]) == 0
    _run_cli(argv, fresh, hash_seed=1)
    _run_cli(argv, one, hash_seed=2, env=ONE_THREAD)
    for other in (fresh, one):
        _assert_identical_files([here, other])
