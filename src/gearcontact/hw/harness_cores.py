"""Per-core benches: port description, golden model and simulator runners of each core.

A :class:`CoreBench` ties one RTL core to everything needed to check it in bulk:

* its Verilog (the core's ``convert_verilog``) and :class:`~.harness.HarnessSpec`;
* the inputs of :mod:`gearcontact.preview.stimulus` mapped onto its ports;
* the vectorized golden model, returning the expected value of every checked output
  port (named as the port);
* the Amaranth-simulator runner (the core's ``simulate_*_core``), as the fallback;
* the expected, data-independent cycle count.

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
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cache, partial
from pathlib import Path

import numpy as np

from ..preview.stimulus import Stimulus, stimulus
from ..validation import InputRangeError
from .harness import HarnessSpec, Port, WritePort

__all__ = ["CoreBench", "CoreUnavailable", "EquivalenceReport", "BENCHES", "CORE_NAMES",
           "get_bench", "verilator_model", "run_equivalence", "SIMULATORS"]

SIMULATORS = ("verilator", "amaranth")
_S32 = dict(bits=32, signed=True)


class CoreUnavailable(RuntimeError):
    """The RTL module of a core is not importable (not built yet in this checkout)."""


def _module(name: str):
    try:
        return importlib.import_module(f"gearcontact.preview.{name}")
    except ImportError as exc:
        raise CoreUnavailable(f"RTL module gearcontact.preview.{name} is not available: "
                              f"{exc}") from exc


@dataclass(frozen=True)
class CoreBench:
    """How to drive, export and check one core (see the module docstring).

    Attributes
    ----------
    name : str
        Core name (``gap``, ``fit``, ``hertz``, ``chain``, ``comb``).
    module : str
        RTL module under :mod:`gearcontact.preview` (with ``convert_verilog``).
    spec : HarnessSpec
        Port description for the generic harness.
    ports : callable
        ``Stimulus -> (inputs, beats, n_beats)`` for :func:`.harness.pack_stimulus`.
    golden : callable
        ``Stimulus -> {output port: int64 array}``.
    amaranth : callable
        ``Stimulus -> ({output port: int64 array}, cycles)`` via the Amaranth simulator.
    cycles : callable
        ``Stimulus -> expected cycles per vector`` (one int for the whole batch).
    verilog_kwargs : dict
        Extra keyword arguments of ``convert_verilog``.
    stimulus_kwargs : dict
        Extra keyword arguments of the stimulus generator.
    summary : str
        One line for ``--help`` and the port README.
    """

    name: str
    module: str
    spec: HarnessSpec
    ports: Callable
    golden: Callable
    amaranth: Callable
    cycles: Callable
    verilog_kwargs: dict = field(default_factory=dict)
    stimulus_kwargs: dict = field(default_factory=dict)
    summary: str = ""

    def verilog(self) -> str:
        """The core's Verilog, top module ``spec.top``."""
        return _verilog(self.name)

    def stimulus(self, n: int, seed: int = 0, **kwargs) -> Stimulus:
        """Corner cases + ``n`` random vectors (:mod:`gearcontact.preview.stimulus`)."""
        return stimulus("comb" if self.name == "comb" else self.name, n, seed,
                        **{**self.stimulus_kwargs, **kwargs})


# ---------------------------------------------------------------------------------
# gap (stage A/B), L = 16
# ---------------------------------------------------------------------------------
GAP_LANES = 16
_GAP_MAX = 16 * GAP_LANES


def _gap_ports(st: Stimulus):
    f = st.fields
    n, N = f["g"].shape[:2]
    inputs = {"r": f["r"].reshape(n, 9), "t": f["t"], "p": f["p"], "tau2": f["tau2"],
              "n_samples": np.full(n, N, np.int64)}
    return inputs, {"w_g": f["g"], "w_n": f["nrm"]}, None


def _gap_golden(st: Stimulus, variant: str = "published") -> dict:
    from ..preview.gap.fast import gap_golden_batch
    f = st.fields
    n = len(st)
    cols = {k: np.empty(n, np.int64) for k in ("gap", "idx", "valid", "overflow")}
    # one batch call per run of consecutive vectors sharing samples and gate
    same = np.zeros(n, bool)
    if n > 1:
        same[1:] = ((f["g"][1:] == f["g"][:-1]).all(axis=(1, 2))
                    & (f["nrm"][1:] == f["nrm"][:-1]).all(axis=(1, 2))
                    & (f["tau2"][1:] == f["tau2"][:-1]))
    starts = np.flatnonzero(~same).tolist() + [n]
    for a, b in zip(starts[:-1], starts[1:]):
        o = gap_golden_batch(f["r"][a:b], f["t"][a:b], f["p"][a:b], f["g"][a], f["nrm"][a],
                             int(f["tau2"][a]), lanes=GAP_LANES, variant=variant)
        cols["gap"][a:b], cols["idx"][a:b] = o.min_gap_code, o.min_idx
        cols["valid"][a:b], cols["overflow"][a:b] = o.valid, o.overflow
    return cols


def _gap_amaranth(st: Stimulus, variant: str = "published"):
    from ..preview.gap.golden import GapVector
    from ..preview.gap.rtl import simulate_gap_core
    f = st.fields
    vecs = [GapVector(r_code=f["r"][i], t_code=f["t"][i], p_code=f["p"][i],
                      g_code=f["g"][i], n_code=f["nrm"][i], tau2_code=int(f["tau2"][i]))
            for i in range(len(st))]
    outs, cycles = simulate_gap_core(vecs, lanes=GAP_LANES, variant=variant)
    return ({"gap": np.array([o.min_gap_code for o in outs], np.int64),
             "idx": np.array([o.min_idx for o in outs], np.int64),
             "valid": np.array([o.valid for o in outs], np.int64),
             "overflow": np.array([o.overflow for o in outs], np.int64)},
            np.asarray(cycles, np.int64))


def _gap_cycles(st: Stimulus) -> int:
    from ..preview.gap.golden import gap_latency
    return gap_latency(st.fields["g"].shape[1], GAP_LANES)


_GAP_SPEC = HarnessSpec(
    top="gap_core", go="start", done="done", max_cycles=4 * _GAP_MAX,
    inputs=(Port("r", 21, 9, True), Port("t", 24, 3, True), Port("p", 24, 3, True),
            Port("tau2", 64), Port("n_samples", 16)),
    outputs=(Port("gap", **_S32), Port("idx", 16), Port("valid", 1), Port("overflow", 1)),
    write=WritePort(strobe="w_valid", addr="w_addr", max_beats=_GAP_MAX,
                    fields=(Port("w_g", 24, 3, True), Port("w_n", 21, 3, True))))


# ---------------------------------------------------------------------------------
# fit (stage C)
# ---------------------------------------------------------------------------------
_FIT_OUT = tuple(f"c{j}" for j in range(6)) + ("a_minus", "b_minus")


def _fit_cols(c, a, b, flags) -> dict:
    out = {f"c{j}": np.asarray(c)[:, j].astype(np.int64) for j in range(6)}
    out.update(a_minus=np.asarray(a, np.int64), b_minus=np.asarray(b, np.int64),
               flags=np.asarray(flags, np.int64))
    return out


def _fit_golden(st: Stimulus) -> dict:
    from ..preview.fit.golden import golden_fit_batch
    g = golden_fit_batch(st.fields["gaps"])
    return _fit_cols(g.c_codes, g.a_minus_codes, g.b_minus_codes, g.flags)


def _fit_amaranth(st: Stimulus):
    from ..preview.fit.rtl import simulate_fit_core
    outs, cycles = simulate_fit_core(st.fields["gaps"])
    return (_fit_cols([o.c_codes for o in outs], [o.a_minus_code for o in outs],
                      [o.b_minus_code for o in outs], [o.flags for o in outs]),
            np.asarray(cycles, np.int64))


def _fit_cycles(st: Stimulus) -> int:
    from ..preview.fit.golden import FIT_CYCLES
    return FIT_CYCLES


def _stencil_write(clear: str = "wr_rst") -> WritePort:
    return WritePort(strobe="wr_en", clear=clear, max_beats=49,
                     fields=(Port("wr_data", **_S32),))


_FIT_SPEC = HarnessSpec(
    top="fit_core", go="go", done="done", max_cycles=400, inputs=(),
    outputs=tuple(Port(n, **_S32) for n in _FIT_OUT) + (Port("flags", 4),),
    write=_stencil_write())


# ---------------------------------------------------------------------------------
# hertz (stage D), chain (C -> D) and comb (combinational C + D)
# ---------------------------------------------------------------------------------
_HERTZ_OUT = tuple(Port(n, **_S32) for n in ("a", "b", "p_max", "k", "A_min", "B_max",
                                              "R_x", "R_y")) + (Port("alpha", 32),)


def _hertz_cols(codes) -> dict:
    """Output columns (by port) from a HertzCodesArray or a list of HertzCodes."""
    from ..preview.hertz.rtl import OUTPUT_PORTS  # port -> HertzCodes field
    if isinstance(codes, list):
        return {p: np.array([getattr(c, f) for c in codes], np.int64)
                for p, f in OUTPUT_PORTS.items()}
    return {p: np.asarray(getattr(codes, f), np.int64) for p, f in OUTPUT_PORTS.items()}


def _hertz_ports(st: Stimulus):
    return {k: st.fields[k] for k in ("A", "B", "W", "e_prime")}, None, None


def _hertz_golden(hertz_form: str):
    def run(st: Stimulus) -> dict:
        from ..preview.hertz.golden_vec import hertz_golden_array
        f = st.fields
        return _hertz_cols(hertz_golden_array(f["A"], f["B"], f["W"],
                                              e_prime_code=f["e_prime"],
                                              hertz_form=hertz_form))
    return run


def _hertz_amaranth(hertz_form: str):
    def run(st: Stimulus):
        from ..preview.hertz.rtl import simulate_hertz_core
        f = st.fields
        rows = np.stack([f["A"], f["B"], f["W"], f["e_prime"]], axis=1)
        outs, cycles = simulate_hertz_core(rows, hertz_form=hertz_form)
        return _hertz_cols(outs), np.asarray(cycles, np.int64)
    return run


def _hertz_cycles(st: Stimulus) -> int:
    from ..preview.hertz.schedule import HERTZ_CYCLES
    return HERTZ_CYCLES


_HERTZ_SPEC = HarnessSpec(
    top="hertz_core", go="go", done="done", max_cycles=2000,
    inputs=(Port("A", **_S32), Port("B", **_S32), Port("W", **_S32),
            Port("e_prime", **_S32)),
    outputs=_HERTZ_OUT + (Port("flags", 7),))


_CHAIN_PORTS = ("a", "b", "p_max", "k", "R_x", "R_y", "alpha")


def _chain_cols(hertz, fit_c, fit_a, fit_b, flags) -> dict:
    """Chain/comb output columns: stage-D outputs, the fit registers, the chain flags."""
    h = _hertz_cols(hertz)
    cols = {p: h[p] for p in _CHAIN_PORTS}
    cols.update(_fit_cols(fit_c, fit_a, fit_b, flags))
    return cols


def _chain_ports(st: Stimulus):
    f = st.fields
    return {"W": f["W"], "e_prime": f["e_prime"]}, {"wr_data": f["gaps"]}, None


def _chain_golden(hertz_form: str = "hamrock-brewe"):
    def run(st: Stimulus) -> dict:
        from ..preview.chain import chain_golden_batch
        f = st.fields
        res = chain_golden_batch(f["gaps"], f["W"], e_prime_code=f["e_prime"],
                                 hertz_form=hertz_form)
        return _chain_cols(res.hertz, res.fit.c_codes, res.fit.a_minus_codes,
                           res.fit.b_minus_codes, res.flags)
    return run


def _chain_amaranth(module: str, runner: str, **kwargs):
    def run(st: Stimulus):
        fn = getattr(_module(module), runner)
        f = st.fields
        outs, cycles = [None] * len(st), np.zeros(len(st), np.int64)
        for e in np.unique(f["e_prime"]):          # the runners take one E' per call
            idx = np.flatnonzero(f["e_prime"] == e)
            o, c = fn(f["gaps"][idx], f["W"][idx], e_prime_code=int(e), **kwargs)
            for i, oi, ci in zip(idx, o, c):
                outs[i], cycles[i] = oi, ci
        return _chain_cols([o.hertz for o in outs], [o.fit.c_codes for o in outs],
                           [o.fit.a_minus_code for o in outs],
                           [o.fit.b_minus_code for o in outs], [o.flags for o in outs]), cycles
    return run


def _chain_cycles(st: Stimulus) -> int:
    from ..preview.hertz.schedule import CHAIN_CYCLES
    return CHAIN_CYCLES


def _comb_cycles(st: Stimulus) -> int:
    from ..preview.hertz.schedule import COMB_CYCLES
    return COMB_CYCLES


def _chain_spec(top: str) -> HarnessSpec:
    return HarnessSpec(
        top=top, go="go", done="done", max_cycles=2000,
        inputs=(Port("W", **_S32), Port("e_prime", **_S32)),
        outputs=tuple(Port(n, **_S32) for n in _CHAIN_PORTS[:6]) + (Port("alpha", 32),)
        + tuple(Port(n, **_S32) for n in _FIT_OUT) + (Port("flags", 12),),
        write=_stencil_write())


BENCHES: dict[str, CoreBench] = {b.name: b for b in (
    CoreBench("gap", "gap.rtl", _GAP_SPEC, _gap_ports, _gap_golden, _gap_amaranth,
              _gap_cycles, verilog_kwargs={"lanes": GAP_LANES},
              summary=f"stage A/B gap kernel, L = {GAP_LANES} lanes, N = 16 samples"),
    CoreBench("gap_lean", "gap.rtl", replace(_GAP_SPEC, top="gap_lean_core"), _gap_ports,
              partial(_gap_golden, variant="lean"), partial(_gap_amaranth, variant="lean"),
              _gap_cycles, verilog_kwargs={"lanes": GAP_LANES, "variant": "lean"},
              summary=f"gap kernel variant 'lean' (15 DSP48E1 per lane), L = {GAP_LANES}"),
    CoreBench("fit", "fit.rtl", _FIT_SPEC, lambda st: ({}, {"wr_data": st.fields["gaps"]},
                                                        None),
              _fit_golden, _fit_amaranth, _fit_cycles,
              summary="stage C curvature fit (49-tap baked pseudo-inverse MAC + isqrt)"),
    CoreBench("hertz", "hertz.rtl", _HERTZ_SPEC, _hertz_ports, _hertz_golden("hamrock-brewe"),
              _hertz_amaranth("hamrock-brewe"), _hertz_cycles,
              summary="stage D serialized elliptic Hertz (one shared 80-bit divider)"),
    CoreBench("hertz_exact", "hertz.rtl", replace(_HERTZ_SPEC, top="hertz_exact_core"),
              _hertz_ports, _hertz_golden("exact"), _hertz_amaranth("exact"), _hertz_cycles,
              verilog_kwargs={"hertz_form": "exact"},
              summary="stage D with hertz_form='exact' (exact k and E tables, 756 cycles)"),
    CoreBench("chain", "chain_rtl", _chain_spec("chain_core"), _chain_ports, _chain_golden(),
              _chain_amaranth("chain_rtl", "simulate_chain_core"), _chain_cycles,
              summary="C -> D chain: fit core feeding the serialized stage D"),
    CoreBench("chain_exact", "chain_rtl", _chain_spec("chain_exact_core"), _chain_ports,
              _chain_golden("exact"),
              _chain_amaranth("chain_rtl", "simulate_chain_core", hertz_form="exact"),
              _chain_cycles, verilog_kwargs={"hertz_form": "exact"},
              summary="C -> D chain with stage D in hertz_form='exact'"),
    CoreBench("comb", "comb_rtl", _chain_spec("comb_core"), _chain_ports, _chain_golden(),
              _chain_amaranth("comb_rtl", "simulate_comb_core"), _comb_cycles,
              summary="combinational C + D variant (array dividers, pipelined)"),
    CoreBench("comb_exact", "comb_rtl", _chain_spec("comb_exact_core"), _chain_ports,
              _chain_golden("exact"),
              _chain_amaranth("comb_rtl", "simulate_comb_core", hertz_form="exact"),
              _comb_cycles, verilog_kwargs={"hertz_form": "exact"},
              summary="combinational C + D with hertz_form='exact' (58 cycles)"),
)}
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

    @property
    def cycles_per_second(self) -> float:
        """Simulator speed, clock cycles per second."""
        return self.sim_cycles / self.sim_seconds if self.sim_seconds > 0 else float("inf")

    @property
    def ok(self) -> bool:
        """No mismatch and every vector took exactly the expected cycle count."""
        return self.mismatches == 0 and self.cycles == self.cycles_expected

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
                "golden_seconds": round(self.golden_seconds, 3), "ok": self.ok}


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
    """Run ``st`` on the RTL: ``(outputs, cycles, sim_cycles, sim_seconds, build_s)``.

    ``jobs`` parallel simulator processes (Verilator only); ``sim_seconds`` is summed
    over them, so ``sim_cycles / sim_seconds`` is the speed of one process.
    """
    if simulator == "verilator":
        t0 = time.perf_counter()
        model = verilator_model(bench.name)
        build = time.perf_counter() - t0
        run = model.run(*bench.ports(st), jobs=jobs)
        return run.outputs, run.cycles, run.sim_cycles, run.seconds, build
    if simulator == "amaranth":
        t0 = time.perf_counter()
        outs, cycles = bench.amaranth(st)
        secs = time.perf_counter() - t0
        return outs, cycles, int(cycles.sum()) + _burst_cycles(bench, st), secs, 0.0
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
    outs, cycles, sim_cycles, sim_s, build_s = simulate(bench, st, simulator, jobs=jobs)
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
        golden_seconds=golden_s)

