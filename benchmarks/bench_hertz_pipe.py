"""Throughput of the stage-D cores: serialized (756 cycles) beside pipelined (II = 1).

Runs seeded random vectors through Verilator for ``hertz`` (one shared divider, go/done)
and ``hertz_pipe`` (valid/ready stream) -- and, with ``--chains``, ``chain`` and
``chain_pipe`` -- checks them against the golden model and prints, per core: the
latency (cycles from acceptance to result), the measured initiation interval (clock
edges between accepted inputs), clock cycles per preview over the whole run
(write bursts and reset included), previews per second at the board clock (50 MHz,
``--mhz``) and the mismatches (must be 0). Cycle counts do not depend on the machine;
the load average is printed for the simulation times.

Run: ``python benchmarks/bench_hertz_pipe.py [--vectors 20000] [--mhz 50] [--chains]``.
"""

from __future__ import annotations

import argparse
import os

from gearcontact.hw.harness_cores import run_equivalence
from gearcontact.hw.verilator import verilator_available


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--vectors", type=int, default=20_000, help="random vectors per core")
    ap.add_argument("--mhz", type=float, default=50.0, help="clock for previews/s (MHz)")
    ap.add_argument("--chains", action="store_true", help="also chain and chain_pipe")
    ap.add_argument("--seed", type=int, default=3)
    args = ap.parse_args(argv)
    if not verilator_available():
        print("Verilator is not installed: apt-get install verilator g++ make")
        return 2
    cores = ["hertz", "hertz_pipe"] + (["chain", "chain_pipe"] if args.chains else [])
    print(f"{'core':11} {'vectors':>8} {'latency':>8} {'II':>6} {'cyc/preview':>11} "
          f"{'previews/s @ ' + format(args.mhz, 'g') + ' MHz':>22} {'sim s':>7} "
          f"{'mismatch':>8}")
    bad = 0
    for core in cores:
        rep = run_equivalence(core, args.vectors, args.seed, corners=False)
        per = rep.sim_cycles / rep.vectors
        rate = args.mhz * 1e6 / per
        print(f"{core:11} {rep.vectors:8d} {rep.cycles!s:>8} {rep.initiation_interval!s:>6} "
              f"{per:11.2f} {rate:22,.0f} {rep.sim_seconds:7.2f} {rep.mismatches:8d}")
        bad += rep.mismatches
    print(f"load average {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} CPUs")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
