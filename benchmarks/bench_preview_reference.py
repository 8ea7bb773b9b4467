"""Benchmark of the fp64 stage-D preview (Hamrock–Brewe) from Python.

Prints one table: scalar ``hertz_preview`` latency per call (median, p99 and the
p99/p50 jitter ratio over individually timed calls, timer overhead subtracted) and
batch throughput of ``hertz_preview_array``, beside the paper's CPU reference
(docs/spec.md sec. 7: preview 277 us per call with 7 % jitter). Target: median <= ~1 us.
Inputs are seeded points of the accuracy domain (steel). The process CPU time is
printed too: on a shared machine wall-clock percentiles include other load.

Run: ``python benchmarks/bench_preview_reference.py [--quick]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from gearcontact.materials import STEEL, effective_modulus_mpa
from gearcontact.preview.hertz.reference import hertz_preview_array
from gearcontact.report.latency import PAPER_JITTER, PAPER_US, preview_inputs, scalar_latency


def _empty(A_minus, B_minus, load_n, *, e_prime_mpa):
    """Same signature, no work: the interpreter's own call cost on this machine."""
    return None


def call_floor(n: int, ep: float) -> float:
    """Median cost (us) of calling an empty function with the same signature (timer
    overhead subtracted, as in :func:`~gearcontact.report.latency.scalar_latency`)."""
    clock = time.perf_counter_ns
    dt = np.empty(n)
    empty = np.empty(n)
    for i in range(n):
        t0 = clock()
        empty[i] = clock() - t0
    for i in range(n):
        t0 = clock()
        _empty(0.1, 0.2, 100.0, e_prime_mpa=ep)
        dt[i] = clock() - t0
    return float(np.median(dt) - np.median(empty)) * 1e-3


def batch_rate(n: int, ep: float, repeats: int = 5) -> float:
    a, b, w = preview_inputs(n, seed=2)
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        hertz_preview_array(a, b, w, e_prime_mpa=ep)
        best = min(best, time.perf_counter() - t0)
    return n / best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer samples")
    args = ap.parse_args()
    n = 50_000 if args.quick else 300_000
    ep = effective_modulus_mpa(STEEL)
    s = scalar_latency(n, e_prime_mpa=ep, warmup=20_000)
    floor = call_floor(n, ep)
    rate = batch_rate(200_000 if args.quick else 1_000_000, ep)
    print(f"stage D fp64 preview (Hamrock-Brewe), {n} timed scalar calls, steel")
    print(f"{'measure':<34}{'this work':>14}{'paper CPU':>14}{'ratio':>10}")
    print(f"{'scalar call median (us)':<34}{s.p50_us:>14.3f}{PAPER_US:>14.1f}"
          f"{PAPER_US / s.p50_us:>9.0f}x")
    print(f"{'scalar call p99 (us)':<34}{s.p99_us:>14.3f}{'':>14}{'':>10}")
    print(f"{'jitter p99/p50 - 1':<34}{100 * s.jitter:>13.1f}%"
          f"{100 * PAPER_JITTER:>13.1f}%{'':>10}")
    print(f"{'scalar CPU time per call (us)':<34}{s.cpu_us:>14.3f}{'':>14}{'':>10}")
    print(f"{'batch previews/s (numpy)':<34}{rate:>14.3e}{1e6 / PAPER_US:>14.3e}"
          f"{rate * PAPER_US / 1e6:>9.0f}x")
    print(f"{'empty call, same signature (us)':<34}{floor:>14.3f}{'':>14}{'':>10}")
    print("(timer overhead subtracted; target median <= ~1 us)")


if __name__ == "__main__":
    main()
