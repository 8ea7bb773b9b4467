"""Per-core benches: the cores' descriptors with the harness spec derived from them.

Each stage folder describes its cores once (:mod:`gearcontact.preview.core`: the
Amaranth component, the stimulus-to-port mapping, the vectorized golden model, the
Amaranth runner, the cycle count, the protocol port names). A :class:`CoreBench` is
such a descriptor plus what the hardware side derives from it:

* the :class:`~.harness.HarnessSpec` (:func:`derive_spec`): every operand, output and
  burst-field width, signedness and element count read from the component's
  ``signature.members`` (nothing hand-typed), which also gives the vector layouts of
  :mod:`.vectors` and the port README of ``gearcontact rtl verilog``;
* its Verilog (the core's ``convert_verilog``, cached by source digest).

:func:`run_equivalence` runs a stimulus through a simulator and the golden model and
returns an :class:`EquivalenceReport` (mismatches, cycle counts, speed) -- the engine of
``gearcontact rtl sim``, of the bulk tests and of the benchmark. Core modules are
imported lazily, so a bench whose RTL is not present raises
:class:`CoreUnavailable` only when used.
"""

from __future__ import annotations

import hashlib
import importlib
import os
import time
from dataclasses import dataclass, fields
from functools import cache
from pathlib import Path

import numpy as np

from ..errors import ToolUnavailable
from ..preview.core import CoreDescriptor, core_descriptors
from ..preview.stimulus import Stimulus
from ..validation import InputRangeError
from .harness import HarnessSpec, Port, Stream, WritePort

__all__ = ["CoreBench", "CoreUnavailable", "EquivalenceReport", "BENCHES", "CORE_NAMES",
           "get_bench", "verilator_model", "run_equivalence", "SIMULATORS", "derive_spec",
           "member_port"]

SIMULATORS = ("verilator", "amaranth")


class CoreUnavailable(ToolUnavailable, RuntimeError):
    """The RTL module of a core is not importable (not built yet in this checkout)."""


def _module(name: str):
    try:
        return importlib.import_module(f"gearcontact.preview.{name}")
    except ImportError as exc:
        raise CoreUnavailable(f"RTL module gearcontact.preview.{name} is not available: "
                              f"{exc}") from exc


def member_port(name: str, shape) -> Port:
    """:class:`~.harness.Port` of a signature member's shape: width and signedness of
    the element, ``count`` for an ``ArrayLayout`` (element 0 in the low bits)."""
    from amaranth.hdl import Shape
    from amaranth.lib.data import ArrayLayout
    if isinstance(shape, ArrayLayout):
        elem, count = Shape.cast(shape.elem_shape), shape.length
    else:
        elem, count = Shape.cast(shape), 1
    return Port(name, elem.width, count, elem.signed)


def derive_spec(desc: CoreDescriptor) -> HarnessSpec:
    """The :class:`~.harness.HarnessSpec` of a core, every width from its component's
    ``signature.members``: operand inputs are the ``In`` members that are not the start
    strobe, a write-port name, a stream handshake or a ``control`` port; checked outputs
    the ``Out`` members that are not ``done``, a handshake or ``control``; both in
    signature order.

    Raises
    ------
    CoreUnavailable
        The core's RTL module is not importable.
    """
    from amaranth.lib.wiring import Flow
    try:
        comp = desc.make_component()
    except ImportError as exc:
        raise CoreUnavailable(f"RTL of core {desc.name} is not available: {exc}") from exc
    comp._MustUse__silence = True             # described, never elaborated: no warning
    members = comp.signature.members
    stream = Stream() if desc.stream else None
    skip = {desc.go, desc.done, *desc.control}
    if stream is not None:
        skip |= {stream.in_valid, stream.in_ready, stream.out_valid, stream.out_ready}
    wn = desc.write
    if wn is not None:
        skip |= {wn.strobe, *wn.fields} | {n for n in (wn.addr, wn.clear) if n}
    unknown = skip - set(members)
    if unknown:
        raise ValueError(f"core {desc.name}: {sorted(unknown)} are not ports of "
                         f"{type(comp).__name__}")

    def ports(flow):
        return tuple(member_port(n, m.shape) for n, m in members.items()
                     if m.is_port and m.flow == flow and n not in skip)

    write = None
    if wn is not None:
        write = WritePort(strobe=wn.strobe, max_beats=wn.max_beats, addr=wn.addr,
                          clear=wn.clear,
                          fields=tuple(member_port(n, members[n].shape) for n in wn.fields))
    return HarnessSpec(top=desc.top, inputs=ports(Flow.In), outputs=ports(Flow.Out),
                       go=desc.go, done=desc.done, max_cycles=desc.max_cycles, write=write,
                       stream=stream)


@dataclass(frozen=True)
class CoreBench(CoreDescriptor):
    """A core's :class:`~gearcontact.preview.core.CoreDescriptor` with its derived
    harness spec (see the module docstring)."""

    @property
    def spec(self) -> HarnessSpec:
        """Port description for the generic harness (:func:`derive_spec`, once per
        bench)."""
        memo = self.__dict__.get("_spec")
        if memo is None:
            memo = derive_spec(self)
            object.__setattr__(self, "_spec", memo)
        return memo

    def verilog(self) -> str:
        """The core's Verilog, top module ``spec.top``."""
        return _verilog(self.name)


BENCHES: dict[str, CoreBench] = {
    name: CoreBench(**{f.name: getattr(d, f.name) for f in fields(CoreDescriptor)})
    for name, d in core_descriptors().items()}
CORE_NAMES = tuple(BENCHES)


def get_bench(name: str) -> CoreBench:
    """The bench of core ``name`` (one of :data:`CORE_NAMES`)."""
    try:
        return BENCHES[name]
    except KeyError:
        raise InputRangeError("core", name, f"one of {list(CORE_NAMES)}") from None


@cache
def _source_digest() -> str:
    """SHA-256 of every ``.py`` file of the installed package and the Amaranth version:
    the key of the Verilog cache (any source edit regenerates the Verilog)."""
    import amaranth
    pkg = Path(__file__).resolve().parents[1]
    h = hashlib.sha256(amaranth.__version__.encode())
    for f in sorted(pkg.rglob("*.py")):
        h.update(str(f.relative_to(pkg)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()


@cache
def _verilog(name: str) -> str:
    """Verilog of core ``name``; exported once per package source state (~4 s each) and
    kept beside the Verilator builds (``cache_root().parent / "verilog"``)."""
    from .verilator import cache_root
    bench = get_bench(name)
    _module(bench.module)                                  # CoreUnavailable if absent
    key = hashlib.sha256(f"{_source_digest()}\0{bench.spec.top}\0"
                         f"{sorted(bench.verilog_kwargs.items())}".encode()).hexdigest()
    path = cache_root().parent / "verilog" / f"{bench.spec.top}-{key[:24]}.v"
    if path.is_file():
        return path.read_text()
    text = _module(bench.module).convert_verilog(name=bench.spec.top, **bench.verilog_kwargs)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(f".{os.getpid()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)
    return text


@cache
def verilator_model(name: str):
    """The compiled (cached) Verilator model of core ``name``."""
    from .verilator import build_model
    bench = get_bench(name)
    return build_model(bench.spec, bench.verilog())


@dataclass(frozen=True)
class EquivalenceReport:
    """Outcome of :func:`run_equivalence`.

    Attributes
    ----------
    core, simulator : str
    vectors : int
        Vectors run (corner cases + random).
    corner_vectors : int
    mismatches : int
        Vectors whose outputs differ from the golden model in any checked port.
    mismatch_examples : list of dict
        Up to 5 mismatching vectors: index, label, port, rtl and golden values.
    cycles : int or None
        The cycle count of every vector if they are all equal, else None.
    cycles_expected : int
        The golden timing model's count.
    cycle_counts : dict
        Distinct cycle count -> number of vectors.
    sim_cycles : int
        Clock cycles simulated (bursts included).
    sim_seconds : float
        Simulation time (Verilator: inside the binary; Amaranth: the runner call).
    build_seconds : float
        Verilog export + Verilator build in this call (about 0 when both are cached).
    golden_seconds : float
    streaming : bool
        The core takes a valid/ready stream (``cycles`` is then the latency).
    measured_ii : float or None
        Streaming cores: edges between the first and last accepted input per input
        (1.0 when one input is accepted per clock).
    """

    core: str
    simulator: str
    vectors: int
    corner_vectors: int
    mismatches: int
    mismatch_examples: list
    cycles: int | None
    cycles_expected: int
    cycle_counts: dict
    sim_cycles: int
    sim_seconds: float
    build_seconds: float
    golden_seconds: float
    streaming: bool = False
    measured_ii: float | None = None

    @property
    def initiation_interval(self):
        """Edges between two accepted evaluations: measured for a streaming core; for a
        go/done core a start is accepted only once the previous run is done, so it is
        the run's cycle count (write bursts before ``go`` not included)."""
        return self.measured_ii if self.streaming else self.cycles

    @property
    def cycles_per_second(self) -> float:
        """Simulator speed, clock cycles per second."""
        return self.sim_cycles / self.sim_seconds if self.sim_seconds > 0 else float("inf")

    @property
    def ok(self) -> bool:
        """No mismatch, every vector took exactly the expected cycle count (latency) and,
        for a streaming core, one input was accepted per clock."""
        return (self.mismatches == 0 and self.cycles == self.cycles_expected
                and (not self.streaming or self.measured_ii in (None, 1.0)))

    def as_dict(self) -> dict:
        """JSON-ready summary."""
        return {"core": self.core, "simulator": self.simulator, "vectors": self.vectors,
                "corner_vectors": self.corner_vectors, "mismatches": self.mismatches,
                "mismatch_examples": self.mismatch_examples, "cycles": self.cycles,
                "cycles_expected": self.cycles_expected,
                "cycle_counts": {str(k): v for k, v in self.cycle_counts.items()},
                "sim_cycles": self.sim_cycles, "sim_seconds": round(self.sim_seconds, 6),
                "cycles_per_second": round(self.cycles_per_second, 1),
                "build_seconds": round(self.build_seconds, 3),
                "golden_seconds": round(self.golden_seconds, 3),
                "initiation_interval": self.initiation_interval,
                "latency_cycles": self.cycles, "ok": self.ok}


def _burst_cycles(bench: CoreBench, st: Stimulus) -> int:
    """Cycles the Amaranth runners spend on writes (for their speed figure)."""
    wp = bench.spec.write
    if wp is None:
        return 0
    _, beats, _ = bench.ports(st)
    per = next(iter(beats.values())).shape[1] + (1 if wp.clear else 0)
    return per * len(st)


def simulate(bench: CoreBench, st: Stimulus, simulator: str = "verilator", *,
             jobs: int = 1):
    """Run ``st`` on the RTL: ``(outputs, cycles, sim_cycles, sim_seconds, build_s,
    initiation_interval)`` (the last is None except for streaming cores).

    ``jobs`` parallel simulator processes (Verilator only); ``sim_seconds`` is summed
    over them, so ``sim_cycles / sim_seconds`` is the speed of one process.
    """
    if simulator == "verilator":
        t0 = time.perf_counter()
        model = verilator_model(bench.name)
        build = time.perf_counter() - t0
        run = model.run(*bench.ports(st), jobs=jobs)
        return (run.outputs, run.cycles, run.sim_cycles, run.seconds, build,
                run.initiation_interval)
    if simulator == "amaranth":
        t0 = time.perf_counter()
        outs, cycles, *ii = bench.amaranth(st)
        secs = time.perf_counter() - t0
        sim_cycles = (int(cycles.sum()) if bench.spec.stream is None
                      else int(cycles.max(initial=0)) + len(st))
        return (outs, cycles, sim_cycles + _burst_cycles(bench, st), secs, 0.0,
                ii[0] if ii else None)
    raise InputRangeError("simulator", simulator, f"one of {list(SIMULATORS)}")


def run_equivalence(core: str, n: int, seed: int = 0, *, simulator: str = "verilator",
                    corners: bool = True, stim: Stimulus | None = None, jobs: int = 1,
                    **stimulus_kwargs) -> EquivalenceReport:
    """Run corner cases + ``n`` random vectors through the RTL and the golden model.

    Parameters
    ----------
    core : str
        One of :data:`CORE_NAMES`.
    n, seed : int
        Random vectors and their seed (:mod:`gearcontact.preview.stimulus`).
    simulator : {"verilator", "amaranth"}, keyword-only
    corners : bool, keyword-only
        Include the corner cases.
    stim : Stimulus, keyword-only, optional
        Use these vectors instead of generating them.
    jobs : int, keyword-only
        Parallel Verilator processes over chunks of the vectors.

    Returns
    -------
    EquivalenceReport

    Raises
    ------
    CoreUnavailable
        The core's RTL module is missing.
    gearcontact.hw.verilator.VerilatorNotFound
        ``simulator="verilator"`` without Verilator installed.
    """
    bench = get_bench(core)
    st = stim if stim is not None else bench.stimulus(n, seed, corners=corners,
                                                      **stimulus_kwargs)
    outs, cycles, sim_cycles, sim_s, build_s, ii = simulate(bench, st, simulator, jobs=jobs)
    t0 = time.perf_counter()
    gold = bench.golden(st)
    golden_s = time.perf_counter() - t0
    bad = np.zeros(len(st), bool)
    examples = []
    for port, want in gold.items():
        diff = np.asarray(outs[port]) != want
        bad |= diff
        for i in np.flatnonzero(diff)[:5 - len(examples)]:
            examples.append({"vector": int(i), "label": st.labels[i], "port": port,
                             "rtl": int(outs[port][i]), "golden": int(want[i])})
    values, counts = np.unique(cycles, return_counts=True)
    return EquivalenceReport(
        core=core, simulator=simulator, vectors=len(st), corner_vectors=st.n_corner,
        mismatches=int(bad.sum()), mismatch_examples=examples,
        cycles=int(values[0]) if len(values) == 1 else None,
        cycles_expected=int(bench.cycles(st)),
        cycle_counts={int(v): int(c) for v, c in zip(values, counts)},
        sim_cycles=int(sim_cycles), sim_seconds=float(sim_s), build_seconds=float(build_s),
        golden_seconds=golden_s, streaming=bench.spec.stream is not None,
        measured_ii=ii)

