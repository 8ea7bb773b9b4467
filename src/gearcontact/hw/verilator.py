"""Build and run an RTL core under Verilator through the generic C++ harness.

:func:`build_model` takes a core's Verilog (from its ``convert_verilog``) and a
:class:`~.harness.HarnessSpec`, generates the harness (:func:`.harness.generate_harness`)
and compiles both with ``verilator --cc --exe --build -O3`` (Amaranth's Verilog needs
``-Wno-WIDTH``; see HARDWARE.md). Builds are cached by a SHA-256 of the Verilog, the
harness, the flags and the Verilator version under :func:`cache_root`
(``$GEARCONTACT_CACHE_DIR/verilator`` or ``~/.cache/gearcontact/verilator``), so a
second build of the same core is a lookup; concurrent builders serialize on a lock
file, and a build lands in its final directory only when complete.

:meth:`VerilatorModel.run` packs the vectors into a stimulus file in a temporary
directory, runs the binary and returns the outputs, the per-vector cycle counts and the
simulator speed. Nothing is written into the source tree.

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

from .harness import HarnessSpec, generate_harness, pack_stimulus, unpack_results

__all__ = ["VerilatorNotFound", "VerilatorBuildError", "VerilatorModel", "SimRun",
           "verilator_available", "verilator_version", "require_verilator", "cache_root",
           "build_model", "VERILATOR_FLAGS", "INSTALL_HINT"]

#: Flags of every build (``-Wno-WIDTH``/``-Wno-fatal``: Amaranth Verilog, HARDWARE.md).
VERILATOR_FLAGS = ("--cc", "--exe", "--build", "-O3", "-Wno-WIDTH", "-Wno-fatal",
                   "--x-assign", "fast", "--x-initial", "fast")
#: How to get the toolchain on Debian/Ubuntu (what CI's ``.ci/run`` does).
INSTALL_HINT = ("install it with: apt-get install -y --no-install-recommends "
                "verilator g++ make")
_TOOLS = ("verilator", "g++", "make")


class VerilatorNotFound(RuntimeError):
    """Verilator (or the C++ toolchain it drives) is not installed."""


class VerilatorBuildError(RuntimeError):
    """``verilator --build`` failed; the message carries the log tail and the directory."""


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
        Wall time of the simulation loop inside the binary (no file I/O, no build).
    wall_seconds : float
        Wall time of the whole call (packing, process start, I/O, decoding).
    """

    outputs: dict
    cycles: np.ndarray
    sim_cycles: int
    seconds: float
    wall_seconds: float

    @property
    def cycles_per_second(self) -> float:
        """Simulator speed: clock cycles per second of simulation."""
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
            timeout: float | None = None) -> SimRun:
        """Run vectors through the model.

        Parameters are those of :func:`.harness.pack_stimulus` (codes per port);
        ``timeout`` bounds the subprocess (seconds).

        Raises
        ------
        RuntimeError
            The harness failed (e.g. no ``done`` within ``spec.max_cycles``).
        """
        t0 = time.perf_counter()
        stream, n = pack_stimulus(self.spec, inputs, beats, n_beats)
        with tempfile.TemporaryDirectory(prefix="gearcontact-vl-") as tmp:
            stim, res = Path(tmp) / "stimulus.bin", Path(tmp) / "results.bin"
            stream.astype("<u4").tofile(stim)
            proc = subprocess.run([str(self.binary), str(stim), str(res), str(n),
                                   str(self.spec.max_cycles)],
                                  capture_output=True, text=True, timeout=timeout)
            if proc.returncode != 0:
                raise RuntimeError(f"Verilator harness for {self.spec.top} failed "
                                   f"(exit {proc.returncode}): {proc.stderr.strip()}")
            words = np.fromfile(res, dtype="<u4")
        stats = json.loads(proc.stdout.strip().splitlines()[-1])
        outputs, cycles = unpack_results(self.spec, words, n)
        return SimRun(outputs=outputs, cycles=cycles, sim_cycles=int(stats["sim_cycles"]),
                      seconds=float(stats["seconds"]),
                      wall_seconds=time.perf_counter() - t0)


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


def _compile(work: Path, spec: HarnessSpec, verilog: str, harness: str, flags: tuple,
             jobs: int) -> None:
    (work / f"{spec.top}.v").write_text(verilog)
    (work / "harness.cpp").write_text(harness)
    cmd = (["verilator"] + list(flags) + ["-j", str(jobs), "--top-module", spec.top,
           "-Mdir", "obj", "-o", "harness", f"{spec.top}.v", "harness.cpp"])
    proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    (work / "build.log").write_text(proc.stdout + proc.stderr)
    if proc.returncode != 0 or not (work / "obj" / "harness").is_file():
        tail = "\n".join((proc.stdout + proc.stderr).strip().splitlines()[-25:])
        raise VerilatorBuildError(f"verilator build of {spec.top} failed "
                                  f"(exit {proc.returncode}):\n{tail}")
