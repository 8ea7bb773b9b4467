"""Benchmark: ``gearcontact reproduce --quick`` end to end (issue 13 target: under
2 minutes on 2 cores), optionally the full run beside it.

Runs :func:`gearcontact.report.reproduce.run_reproduce` into a temporary directory and
prints the wall time of the main job and of every report item (the same split run.json
holds), the total against the target, the process CPU time and the load average (the
machine is shared: CPU time is the fairer figure). A run includes numba's compilation
when its on-disk cache is cold (to measure that case, clear the caches first: see
docs/architecture.md, "Compiled kernels").

Measured on the project machine (2 cores shared, load 1-4): quick 9-16 s warm, 40 s
with cold numba caches; full 25 s warm (accuracy studies 8 s, multi-tooth with bending
6 s).

Run: ``python benchmarks/bench_reproduce.py [--full]`` (needs ``pip install
'gearcontact[report]'``).
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time

from gearcontact.report.reproduce import run_reproduce

TARGET_QUICK_S = 120.0


def _run(quick: bool) -> tuple[dict, float, float]:
    with tempfile.TemporaryDirectory() as tmp:
        c0, t0 = time.process_time(), time.perf_counter()
        rep = run_reproduce(tmp, quick=quick, progress=False)
        return rep.timings_s, time.perf_counter() - t0, time.process_time() - c0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--full", action="store_true", help="also time the full run")
    args = ap.parse_args()
    runs = [("quick", True)] + ([("full", False)] if args.full else [])
    results = {name: _run(quick) for name, quick in runs}
    keys = [k for k, v in next(iter(results.values()))[0].items() if isinstance(v, float)]
    print(f"{'stage (wall s)':<18}" + "".join(f"{name:>10}" for name in results))
    for k in keys:
        print(f"{k:<18}" + "".join(f"{r[0].get(k, float('nan')):>10.2f}"
                                   for r in results.values()))
    print(f"{'process CPU s':<18}" + "".join(f"{r[2]:>10.2f}" for r in results.values()))
    quick_s = results["quick"][1]
    print(f"quick run {quick_s:.1f} s wall, target < {TARGET_QUICK_S:g} s: "
          f"{'met' if quick_s < TARGET_QUICK_S else 'NOT met'}")
    print("load average (1, 5, 15 min): " + ", ".join(f"{x:.2f}" for x in os.getloadavg()))


if __name__ == "__main__":
    main()
