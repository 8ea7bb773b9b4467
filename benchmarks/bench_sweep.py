"""Sweep throughput (issue 15): cells per second of the (E, P) 9 x 9 TCA sweep of
s0003-centred in this process (plain loop, ``workers=0``) and on a Dask LocalCluster of
1 and 2 worker processes, the scaling ratio 2 / 1 worker and the per-cell overhead of
the Dask path over the plain loop. The flanks and the cluster start-up are timed apart
(``flanks_s``; ``first_s``: from the flanks to the first point written, with the
cluster start, the scatter and the workers' first call; ``steady/s``: points per second
from the first to the last point). The Dask overhead per cell is also measured
directly: 81 no-op tasks taking the scattered nominal variant (flanks) as the real
tasks do, submitted and gathered through ``as_completed`` on a 1-worker cluster
(``noop_ms``: wall time per task). Prints a table and the load average (the machine
is shared).

Usage: python3 benchmarks/bench_sweep.py [--steps 9] [--phases 61]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time


def main() -> None:
    from gearcontact.geometry.pair import load_pair
    from gearcontact.sweep import SweepGrid, parse_vary, run_sweep

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=9)
    ap.add_argument("--phases", type=int, default=61)
    a = ap.parse_args()
    load0 = os.getloadavg()
    pair = load_pair("s0003-centred")
    grid = SweepGrid((parse_vary(f"E=-0.1:0.1:{a.steps}"),
                      parse_vary(f"P=-0.1:0.1:{a.steps}")), (64.5,))
    # untimed warm-up: compiled kernels into numba's cache for every process
    with tempfile.TemporaryDirectory() as d:
        run_sweep(pair, SweepGrid((parse_vary("E=0:0:1"),), (64.5,)), out=d, side="drive",
                  phases=a.phases, workers=0, progress=False)
    rows = []
    for workers in (0, 1, 2):
        with tempfile.TemporaryDirectory() as d:
            t0 = time.perf_counter()
            rep = run_sweep(pair, grid, out=d, side="drive", phases=a.phases,
                            workers=workers, progress=False)
            rows.append((workers, rep.computed, time.perf_counter() - t0, rep.failed,
                         rep.flanks_s, rep.first_s,
                         (rep.computed - 1) / (rep.last_s - rep.first_s)))
    print(f"(E, P) {a.steps} x {a.steps} TCA sweep, s0003-centred drive, {a.phases} phases")
    print(f"{'workers':>8} {'cells':>6} {'wall_s':>8} {'cells/s':>8} {'failed':>7} "
          f"{'flanks_s':>9} {'first_s':>8} {'steady/s':>9}")
    for w, n, s, f, fl, first, steady in rows:
        print(f"{('loop' if w == 0 else w):>8} {n:>6} {s:8.2f} {n / s:8.2f} {f:>7} "
              f"{fl:9.2f} {first:8.2f} {steady:9.2f}")
    noop_ms = _noop_overhead_ms(pair, a.steps ** 2)
    loop, one, two = rows
    print(f"scaling 2 / 1 workers (steady state): {two[6] / one[6]:.2f}x; Dask (1 worker) "
          f"overhead per cell vs loop (steady state): {1e3 * (1 / one[6] - 1 / loop[6]):.1f}"
          f" ms; start-up (first point after the flanks): {one[5]:.2f} s vs loop "
          f"{loop[5]:.2f} s")
    print(f"Dask overhead per task, measured on no-op tasks with the scattered flanks "
          f"(1 worker): {noop_ms:.1f} ms")
    print(f"load average: at start {load0}, at end {os.getloadavg()} (2 cores, shared)")


def _noop(variant, assembly, torques, kwargs) -> dict:
    return {"error": [""] * len(torques)}


def _noop_overhead_ms(pair, n: int) -> float:
    """Wall time per no-op task (submit, schedule, run, result), ms."""
    from distributed import Client, LocalCluster, as_completed

    from gearcontact.geometry.flank import build_flanks
    from gearcontact.sweep.design import Variant

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        shared = client.scatter(Variant(pair, build_flanks(pair), 0.0), broadcast=True)
        client.submit(_noop, shared, {}, [64.5], {}, pure=False).result()   # warm
        t0 = time.perf_counter()
        futures = [client.submit(_noop, shared, {"E_mm": 0.001 * i}, [64.5], {},
                                 pure=False) for i in range(n)]
        for fut in as_completed(futures):
            fut.result()
        return 1e3 * (time.perf_counter() - t0) / n


if __name__ == "__main__":
    main()
