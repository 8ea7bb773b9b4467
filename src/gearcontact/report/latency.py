"""Determinism and latency in the report (docs/spec.md sec. 8, item 4).

Two kinds of latency are set side by side:

* the RTL cores' cycle counts, which are constants of the design (the golden timing
  model; the RTL tests assert every simulated run equals them, so their spread is
  exactly zero): gap pass (L = 16 lanes, N = 49 samples), fit C, Hertz D, the C -> D
  chain and the combinational C + D variant;
* the fp64 preview's CPU latency from Python, measured on this machine: the median and
  99th percentile of individually timed scalar calls (timer overhead subtracted) and
  the jitter ``p99 / p50 - 1``, beside the published CPU figure (277 us, 7 % jitter).

:func:`scalar_latency` is also what ``benchmarks/bench_preview_reference.py`` runs.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..materials import STEEL, effective_modulus_mpa
from ..preview.fit.golden import FIT_CYCLES
from ..preview.gap.golden import gap_latency
from ..preview.hertz.reference import hertz_preview
from ..preview.hertz.schedule import CHAIN_CYCLES, COMB_CYCLES, HERTZ_CYCLES

__all__ = ["PAPER_JITTER", "PAPER_US", "ScalarLatency", "core_cycles", "preview_inputs",
           "scalar_latency"]

#: Published CPU preview: 277 us per call with 7 % jitter (docs/spec.md sec. 7).
PAPER_US = 277.0
PAPER_JITTER = 0.07


@dataclass(frozen=True)
class ScalarLatency:
    """Wall-clock latency of single fp64 preview calls.

    Attributes
    ----------
    p50_us, p99_us : float
        Median and 99th percentile per call, us (timer overhead subtracted).
    jitter : float
        ``p99 / p50 - 1``, dimensionless.
    calls : int
        Timed calls.
    cpu_us : float
        Process CPU time per call over the timed loop, us.
    """

    p50_us: float
    p99_us: float
    jitter: float
    calls: int
    cpu_us: float


def core_cycles(*, lanes: int = 16, n_samples: int = 49) -> dict[str, int]:
    """Clock cycles from ``go`` to ``done`` per core (constants of the design); for the
    pipelined cores (initiation interval 1) the latency of each preview."""
    from ..preview.chain_pipe import CHAIN_PIPE_CYCLES
    from ..preview.hertz.rtl_pipe import pipe_latency

    return {f"gap pass (L = {lanes}, N = {n_samples})": gap_latency(n_samples, lanes),
            "fit C": FIT_CYCLES, "Hertz D": HERTZ_CYCLES, "chain C -> D": CHAIN_CYCLES,
            "combinational C + D": COMB_CYCLES,
            "pipelined Hertz D (II = 1)": pipe_latency(),
            "chain C -> D with pipelined D": CHAIN_PIPE_CYCLES}


def preview_inputs(n: int, seed: int = 1):
    """Seeded (A-, B-, W) points of the accuracy domain: curvatures 1e-3..1 1/mm with
    ratio <= 128, loads 10..20 000 N (log-uniform)."""
    rng = np.random.default_rng(seed)
    a = np.exp(rng.uniform(np.log(1e-3), 0.0, n))
    b = np.minimum(a * np.exp(rng.uniform(0.0, np.log(128.0), n)), 1.0)
    w = np.exp(rng.uniform(np.log(10.0), np.log(2e4), n))
    return a, b, w


def scalar_latency(n: int = 20_000, *, e_prime_mpa: float | None = None,
                   warmup: int = 2_000) -> ScalarLatency:
    """Time ``n`` individual :func:`~gearcontact.preview.hertz.reference.hertz_preview`
    calls (steel by default) on :func:`preview_inputs`."""
    ep = effective_modulus_mpa(STEEL) if e_prime_mpa is None else float(e_prime_mpa)
    a, b, w = (x.tolist() for x in preview_inputs(n))
    clock = time.perf_counter_ns
    for i in range(min(n, warmup)):
        hertz_preview(a[i], b[i], w[i], e_prime_mpa=ep)
    empty = np.empty(n)
    for i in range(n):                               # timer overhead
        t0 = clock()
        empty[i] = clock() - t0
    overhead = float(np.median(empty))
    dt = np.empty(n)
    c0 = time.process_time()
    for i in range(n):
        ai, bi, wi = a[i], b[i], w[i]
        t0 = clock()
        hertz_preview(ai, bi, wi, e_prime_mpa=ep)
        dt[i] = clock() - t0
    cpu = time.process_time() - c0
    dt = (dt - overhead) * 1e-3
    p50, p99 = np.percentile(dt, [50, 99])
    return ScalarLatency(p50_us=float(p50), p99_us=float(p99), jitter=float(p99 / p50 - 1.0),
                         calls=int(n), cpu_us=cpu / n * 1e6)
