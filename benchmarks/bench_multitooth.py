"""Multi-tooth LTCA at one phase (issue target <= 30 ms): the coupled LCP of all engaged
pairs of s0003 at P0, rigid and with the bending blocks of both teeth.

Times, after the TCA (61 phases), the shell build and a warm-up of the compiled kernels
(all untimed): the whole ``multi_tooth_ltca`` call (gap fields, bending factors, both
solves, CP_max) and the two LCP solves alone (``solve_rigid_ms``, ``solve_ms``), best of
``--repeat`` runs, wall and process CPU. Each call builds its fields afresh, as a new
phase would. Prints a table and the load average (the machine is shared: compare on a
quiet machine).

Usage: python3 benchmarks/bench_multitooth.py [--pair s0003] [--repeat 5] [--cells 40]
"""

from __future__ import annotations

import argparse
import os
import time

from gearcontact.ltca.mesh_lcp import warm_up_mesh_lcp
from gearcontact.ltca.multitooth import multi_tooth_ltca
from gearcontact.ltca.tooth_bending import tooth_bending
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair

TARGET_MS = 30.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pair", default="s0003", help="preset or TOML (default s0003)")
    ap.add_argument("--repeat", type=int, default=5, help="repetitions, best kept (default 5)")
    ap.add_argument("--cells", type=int, default=40, help="cells per side (default 40)")
    ap.add_argument("--torque", type=float, default=64.5, help="gear torque, N·m")
    args = ap.parse_args()
    pair = load_pair(args.pair)
    tca, flanks = analyze_pair(pair, phases=61)
    bending = tooth_bending(flanks, pair, side=pair.design_side)
    warm_up_mesh_lcp()
    multi_tooth_ltca(tca, flanks, pair, args.torque, bending=bending, cells=args.cells)
    best = None
    for _ in range(max(1, args.repeat)):
        w0, c0 = time.perf_counter(), time.process_time()
        case = multi_tooth_ltca(tca, flanks, pair, args.torque, bending=bending,
                                cells=args.cells)
        row = (1e3 * (time.perf_counter() - w0), 1e3 * (time.process_time() - c0),
               case.solve_rigid_ms, case.solve_ms)
        best = row if best is None else tuple(min(a, b) for a, b in zip(best, row))
    wall, cpu, rigid, bent = best
    print(f"{pair.name} {pair.design_side} {args.torque:g} N·m, {len(case.pairs)} pairs, "
          f"{args.cells} cells, best of {args.repeat}")
    print(f"{'quantity':40s} {'ms':>9s} {'target':>8s}")
    print(f"{'multi_tooth_ltca wall (fields + 2 solves)':40s} {wall:9.1f}")
    print(f"{'multi_tooth_ltca process CPU':40s} {cpu:9.1f}")
    print(f"{'LCP solve rigid':40s} {rigid:9.1f} {TARGET_MS:8.0f}")
    print(f"{'LCP solve with bending':40s} {bent:9.1f} {TARGET_MS:8.0f}")
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")


if __name__ == "__main__":
    main()
