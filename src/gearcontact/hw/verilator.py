"""Build and run an RTL core under Verilator through the generic C++ harness.

:func:`build_model` takes a core's Verilog (from its ``convert_verilog``) and a
:class:`~.harness.HarnessSpec`, generates the harness (:func:`.harness.generate_harness`)
and compiles both with ``verilator --cc --exe -O3`` and ``make`` -- the two halves of
``verilator --build``, split so that the Verilator run-time objects, identical for every
core, are compiled once and reused (Amaranth's Verilog needs ``-Wno-WIDTH``; see
docs/hardware.md sec. 2). Builds are cached by a SHA-256 of the Verilog, the
harness, the flags and the Verilator version under :func:`cache_root`
(``$GEARCONTACT_CACHE_DIR/verilator`` or ``~/.cache/gearcontact/verilator``), so a
second build of the same core is a lookup; concurrent builders serialize on a lock
file, and a build lands in its final directory only when complete.

:meth:`VerilatorModel.run` packs the vectors into stimulus files in a temporary
directory, runs the binary (optionally as parallel processes over chunks) and returns
the outputs, the per-vector cycle counts and the simulator speed. Nothing is written
into the source tree.

Errors are explicit: without Verilator (or g++/make) :class:`VerilatorNotFound` names the
Debian packages to install; a failing build raises :class:`VerilatorBuildError` with
the tail of the compiler log.
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import os
import resource
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import ToolUnavailable

from .harness import HarnessSpec, generate_harness, pack_stimulus, unpack_results

__all__ = ["VerilatorNotFound", "VerilatorBuildError", "VerilatorModel", "SimRun",
           "verilator_available", "verilator_version", "require_verilator", "cache_root",
           "build_model", "VERILATOR_FLAGS", "INSTALL_HINT"]

#: Verilator flags of every build (``-Wno-WIDTH``/``-Wno-fatal``: Amaranth Verilog, see
#: docs/hardware.md sec. 2); the C++ is then compiled by ``make`` as ``verilator --build`` would.
VERILATOR_FLAGS = ("--cc", "--exe", "-O3", "-Wno-WIDTH", "-Wno-fatal",
                   "--x-assign", "fast", "--x-initial", "fast")
#: How to get the toolchain on Debian/Ubuntu (what CI's ``.ci/run`` does).
INSTALL_HINT = ("install it with: apt-get install -y --no-install-recommends "
                "verilator g++ make")
_TOOLS = ("verilator", "g++", "make")


class VerilatorNotFound(ToolUnavailable, RuntimeError):
    """Verilator (or the C++ toolchain it drives) is not installed."""


class VerilatorBuildError(ToolUnavailable, RuntimeError):
    """``verilator --build`` failed (the toolchain here cannot build the harness: exit 2);
    the message carries the log tail and the directory."""


def _missing_tools() -> list[str]:
    return [t for t in _TOOLS if shutil.which(t) is None]


def verilator_available() -> bool:
    """True when ``verilator``, ``g++`` and ``make`` are on PATH."""
    return not _missing_tools()


def require_verilator() -> None:
    """Raise :class:`VerilatorNotFound` (naming the apt packages) unless available."""
    missing = _missing_tools()
    if missing:
        raise VerilatorNotFound(
            f"{', '.join(missing)} not found on PATH: the Verilator simulator needs the "
            f"Debian packages 'verilator', 'g++' and 'make'; {INSTALL_HINT}")


@lru_cache(maxsize=1)
def verilator_version() -> str:
    """``verilator --version`` output (e.g. ``Verilator 5.006 2023-01-22 ...``)."""
    require_verilator()
    return subprocess.run(["verilator", "--version"], capture_output=True, text=True,
                          check=True).stdout.strip()


def cache_root() -> Path:
    """Directory holding cached builds (created on demand, outside the source tree)."""
    base = os.environ.get("GEARCONTACT_CACHE_DIR")
    if base:
        root = Path(base)
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        root = (Path(xdg) if xdg else Path.home() / ".cache") / "gearcontact"
    return root / "verilator"


@dataclass(frozen=True)
class SimRun:
    """Result of :meth:`VerilatorModel.run`.

    Attributes
    ----------
    outputs : dict
        Output port name -> int64 codes, shape ``(n,)`` (``(n, count)`` for array ports).
    cycles : numpy.ndarray
        Per-vector cycles from the ``go`` edge to ``done`` (int64, shape ``(n,)``).
    sim_cycles : int
        All clock cycles simulated (bursts, runs and the reset), for the speed.
    seconds : float
        Wall time of the simulation loops inside the binaries (no file I/O, no build),
        summed over the processes.
    wall_seconds : float
        Wall time of the whole call (packing, process start, I/O, decoding).
    processes : int
        Simulator processes run in parallel.
    initiation_interval : float or None
        Streaming cores only: edges between the first and the last accepted input
        divided by the accepted inputs minus one, the largest over the processes
        (1.0 = one input per clock); None for go/done cores or single vectors.
    """

    outputs: dict
    cycles: np.ndarray
    sim_cycles: int
    seconds: float
    wall_seconds: float
    processes: int = 1
    initiation_interval: float | None = None

    @property
    def cycles_per_second(self) -> float:
        """Simulator speed: clock cycles per second of one simulator process."""
        return self.sim_cycles / self.seconds if self.seconds > 0 else float("inf")


@dataclass(frozen=True)
class VerilatorModel:
    """A compiled harness + core.

    Attributes
    ----------
    spec : HarnessSpec
    binary : pathlib.Path
        The executable (in the cache directory).
    build_seconds : float
        Wall time spent building in this process (0.0 when the cache had it).
    cached : bool
        True when the build came from the cache.
    build_cpu_seconds : float
        CPU time (user + system) of the compiler processes of this build (0.0 when
        cached): the build cost on an idle machine, whatever the load.
    """

    spec: HarnessSpec
    binary: Path
    build_seconds: float
    cached: bool
    build_cpu_seconds: float = 0.0

    def run(self, inputs: dict, beats: dict | None = None, n_beats=None, *,
            jobs: int = 1, timeout: float | None = None, bubble_per_mille: int = 0,
            stall_per_mille: int = 0, seed: int = 0) -> SimRun:
        """Run vectors through the model.

        Parameters
        ----------
        inputs, beats, n_beats
            As for :func:`.harness.pack_stimulus` (codes per port).
        jobs : int, keyword-only
            Split the vectors into this many contiguous chunks simulated by parallel
            processes (each from reset; results are concatenated in order).
        timeout : float, keyword-only, optional
            Bound on each subprocess, seconds.
        bubble_per_mille, stall_per_mille, seed : int, keyword-only
            Streaming cores only: random input bubbles and output stalls per 1000
            clocks (0..999) and the seed of their pattern (see :mod:`.harness`).

        Raises
        ------
        RuntimeError
            The harness failed (e.g. no ``done`` within ``spec.max_cycles``).
        """
        t0 = time.perf_counter()
        n = _n_vectors(self.spec, inputs, beats)
        jobs = max(1, min(int(jobs), n))
        bounds = np.linspace(0, n, jobs + 1).astype(int)
        with tempfile.TemporaryDirectory(prefix="gearcontact-vl-") as tmp:
            procs = []
            for j, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
                stream, m = pack_stimulus(
                    self.spec, _rows(inputs, a, b), _rows(beats, a, b),
                    None if n_beats is None else np.asarray(n_beats)[a:b])
                stim, res = Path(tmp) / f"stimulus{j}.bin", Path(tmp) / f"results{j}.bin"
                stream.astype("<u4").tofile(stim)
                cmd = [str(self.binary), str(stim), str(res), str(m),
                       str(self.spec.max_cycles)]
                if self.spec.stream is not None:
                    cmd += [str(int(bubble_per_mille)), str(int(stall_per_mille)),
                            str(int(seed) + j)]
                procs.append((subprocess.Popen(cmd, stdout=subprocess.PIPE,
                                               stderr=subprocess.PIPE, text=True), res, m))
            chunks = []
            try:
                for proc, res, m in procs:
                    out, err = proc.communicate(timeout=timeout)
                    if proc.returncode != 0:
                        raise RuntimeError(f"Verilator harness for {self.spec.top} failed "
                                           f"(exit {proc.returncode}): {err.strip()}")
                    stats = json.loads(out.strip().splitlines()[-1])
                    chunks.append(unpack_results(self.spec, np.fromfile(res, dtype="<u4"),
                                                 m) + (stats,))
            finally:
                for proc, _, _ in procs:
                    if proc.poll() is None:
                        proc.kill()
                        proc.wait()
        outputs = {p.name: np.concatenate([c[0][p.name] for c in chunks])
                   for p in self.spec.outputs}
        spans = [(c[2]["last_accept"] - c[2]["first_accept"]) / (c[2]["vectors"] - 1)
                 for c in chunks if "first_accept" in c[2] and c[2]["vectors"] > 1]
        return SimRun(outputs=outputs, cycles=np.concatenate([c[1] for c in chunks]),
                      sim_cycles=sum(int(c[2]["sim_cycles"]) for c in chunks),
                      seconds=sum(float(c[2]["seconds"]) for c in chunks),
                      wall_seconds=time.perf_counter() - t0, processes=jobs,
                      initiation_interval=max(spans) if spans else None)


def _n_vectors(spec: HarnessSpec, inputs: dict, beats: dict | None) -> int:
    if spec.inputs:
        return len(np.asarray(inputs[spec.inputs[0].name]))
    if beats is None:
        raise ValueError(f"{spec.top}: no operand inputs and no write-port beats given")
    return len(np.asarray(beats[spec.write.fields[0].name]))


def _rows(d: dict | None, a: int, b: int) -> dict | None:
    return None if d is None else {k: np.asarray(v)[a:b] for k, v in d.items()}


def _build_key(verilog: str, harness: str, flags: tuple) -> str:
    h = hashlib.sha256()
    for part in (verilator_version(), " ".join(flags), harness, verilog):
        h.update(part.encode())
        h.update(b"\0")
    return h.hexdigest()[:24]


def build_model(spec: HarnessSpec, verilog: str, *, jobs: int | None = None,
                extra_flags: tuple = ()) -> VerilatorModel:
    """Compile ``verilog`` (top module ``spec.top``) with the generated harness.

    Parameters
    ----------
    spec : HarnessSpec
        Port description of the core.
    verilog : str
        The core's Verilog (its ``convert_verilog(name=spec.top)``).
    jobs : int, optional
        Parallel compile jobs (default: CPU count, at most 4).
    extra_flags : tuple of str
        Additional Verilator flags (part of the cache key).

    Returns
    -------
    VerilatorModel

    Raises
    ------
    VerilatorNotFound
        Verilator, g++ or make is missing (message names the packages).
    VerilatorBuildError
        Verilator or the C++ compiler failed.
    """
    require_verilator()
    harness = generate_harness(spec)
    flags = VERILATOR_FLAGS + tuple(extra_flags)
    key = _build_key(verilog, harness, flags)
    root = cache_root()
    root.mkdir(parents=True, exist_ok=True)
    final = root / f"{spec.top}-{key}"
    binary = final / "obj" / "harness"
    if binary.is_file():
        return VerilatorModel(spec, binary, 0.0, True)
    t0 = time.perf_counter()
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(root / f".{spec.top}-{key}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            if binary.is_file():            # another process built it meanwhile
                return VerilatorModel(spec, binary, time.perf_counter() - t0, True)
            work = Path(tempfile.mkdtemp(prefix=f".build-{spec.top}-", dir=root))
            try:
                _compile(work, spec, verilog, harness, flags,
                         jobs or min(4, os.cpu_count() or 1))
                os.replace(work, final)
            finally:
                shutil.rmtree(work, ignore_errors=True)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime)
    return VerilatorModel(spec, binary, time.perf_counter() - t0, False, cpu)


#: Verilator run-time objects every model links (same sources and flags for every
#: core): compiled once per Verilator version and flag set, then copied into each build
#: directory so that ``make`` finds them up to date (saves ~6 s of CPU per build).
_RUNTIME_FILES = ("verilated.o", "verilated.d", "verilated_threads.o", "verilated_threads.d")


def _runtime_dir(flags: tuple) -> Path:
    h = hashlib.sha256(f"{verilator_version()}\0{' '.join(flags)}".encode()).hexdigest()
    return cache_root() / f"runtime-{h[:16]}"


def _compile(work: Path, spec: HarnessSpec, verilog: str, harness: str, flags: tuple,
             jobs: int) -> None:
    (work / f"{spec.top}.v").write_text(verilog)
    (work / "harness.cpp").write_text(harness)
    obj, runtime = work / "obj", _runtime_dir(flags)
    log = []

    def step(cmd: list) -> None:
        proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True, check=False)
        log.append(proc.stdout + proc.stderr)
        (work / "build.log").write_text("".join(log))
        if proc.returncode != 0:
            tail = "\n".join((proc.stdout + proc.stderr).strip().splitlines()[-25:])
            raise VerilatorBuildError(f"verilator build of {spec.top} failed "
                                      f"(exit {proc.returncode}):\n{tail}")

    # 1. Verilog -> C++ (what ``verilator --build`` does first)
    step(["verilator"] + list(flags) + ["--top-module", spec.top, "-Mdir", "obj",
                                        "-o", "harness", f"{spec.top}.v", "harness.cpp"])
    # 2. the shared run-time objects, newer than the freshly generated makefile
    if all((runtime / f).is_file() for f in _RUNTIME_FILES):
        for f in _RUNTIME_FILES:
            shutil.copyfile(runtime / f, obj / f)
    # 3. C++ -> executable (the ``--build`` step)
    step(["make", "-C", "obj", "-f", f"V{spec.top}.mk", "-j", str(jobs)])
    if not (obj / "harness").is_file():
        raise VerilatorBuildError(f"verilator build of {spec.top}: no executable "
                                  f"(log: {work / 'build.log'})")
    if not runtime.is_dir() and all((obj / f).is_file() for f in _RUNTIME_FILES):
        tmp = Path(tempfile.mkdtemp(prefix=".runtime-", dir=runtime.parent))
        for f in _RUNTIME_FILES:
            shutil.copy2(obj / f, tmp / f)
        try:
            os.replace(tmp, runtime)
        except OSError:                     # another build published it first
            shutil.rmtree(tmp, ignore_errors=True)
