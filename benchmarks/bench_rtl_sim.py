"""Benchmark of RTL simulation speed: clock cycles per second per core and simulator.

For every core (gap L = 16, fit, hertz, chain, comb) runs seeded random vectors through
Verilator (the generic C++ harness, :mod:`gearcontact.hw.verilator`) and through the
Amaranth simulator, checks them against the golden model and prints cycles/s,
evaluations/s, the cycle count per evaluation, the Verilator build wall time (0 when
cached) and the mismatches (must be 0). Cycles/s count every simulated clock,
including the write bursts that load a stencil or the gap samples.

Run: ``python benchmarks/bench_rtl_sim.py [--verilator-vectors 5000]
[--amaranth-vectors 5] [--cores gap fit ...] [--json]``.
"""

from __future__ import annotations

import argparse
import json

from gearcontact.hw.harness_cores import CORE_NAMES, CoreUnavailable, run_equivalence
from gearcontact.hw.verilator import verilator_available


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--verilator-vectors", type=int, default=5000,
                    help="random vectors per core under Verilator (default 5000)")
    ap.add_argument("--amaranth-vectors", type=int, default=5,
                    help="random vectors per core under Amaranth (default 5; 0 skips)")
    ap.add_argument("--cores", nargs="+", choices=CORE_NAMES, default=list(CORE_NAMES))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", action="store_true", help="print JSON rows instead")
    args = ap.parse_args(argv)

    plan = []
    if verilator_available():
        plan.append(("verilator", args.verilator_vectors))
    if args.amaranth_vectors > 0:
        plan.append(("amaranth", args.amaranth_vectors))
    rows = []
    for core in args.cores:
        for sim, n in plan:
            try:
                rep = run_equivalence(core, n, args.seed, simulator=sim, corners=False)
            except CoreUnavailable as exc:
                print(f"{core}: skipped ({exc})")
                break
            evals = rep.vectors / rep.sim_seconds if rep.sim_seconds else float("inf")
            rows.append({"core": core, "simulator": sim, "vectors": rep.vectors,
                         "cycles_per_eval": rep.cycles, "mismatches": rep.mismatches,
                         "cycles_per_second": round(rep.cycles_per_second),
                         "evals_per_second": round(evals, 1),
                         "sim_seconds": round(rep.sim_seconds, 3),
                         "build_seconds": round(rep.build_seconds, 1)})
    if args.json:
        print(json.dumps(rows, indent=2))
    else:
        print(f"{'core':6} {'simulator':10} {'vectors':>8} {'cyc/eval':>8} {'cycles/s':>11} "
              f"{'evals/s':>9} {'sim s':>8} {'build s':>8} {'mismatch':>8}")
        for r in rows:
            print(f"{r['core']:6} {r['simulator']:10} {r['vectors']:8d} "
                  f"{r['cycles_per_eval']!s:>8} {r['cycles_per_second']:11,d} "
                  f"{r['evals_per_second']:9.1f} {r['sim_seconds']:8.2f} "
                  f"{r['build_seconds']:8.1f} {r['mismatches']:8d}")
    return 1 if any(r["mismatches"] for r in rows) else 0


if __name__ == "__main__":
    raise SystemExit(main())
