"""Benchmark of the cylindrical drivetrain FMU's step: ns and instructions per 10 us twin
step of ``gearcontact export fmu --pair examples/ev_reducer_helical_23x67.toml --kind
drivetrain`` (the twin's line law, rigid teeth), beside its peers in the same run.

Peers, each timed by :func:`bench_c.bench_twin_step` (the FMU's C sources built with
the FMU's flags into a driver that times ``fmi3DoStep`` one by one: median, p99, max,
mean; callgrind's instructions per step with ``--instructions``; then the numba twin,
``gearcontact twin``, on the same model):

* the EV reducer's helical stage (23/67, 61 phases per pitch, 3000 rpm, 64.5 N.m): the
  target, <= 500 ns median per step in fp64 and golden (docs/performance.md);
* s0003's drivetrain FMU (the bevel law, curvatures stencil): the figure the target is
  taken from (docs/export.md, "The drivetrain FMU").

The machine is shared: the load average is printed before and after, the process is
pinned to one core; instruction counts (valgrind's callgrind, 6,000 steps, inclusive of
libm) do not depend on the load.

Run: ``python benchmarks/bench_fmu_cylindrical.py [--steps 200000] [--phases 61]
[--instructions] [--pair PAIR]``.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from bench_c import _pin, bench_twin_step

EV = Path(__file__).resolve().parents[1] / "examples" / "ev_reducer_helical_23x67.toml"


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=200000, help="twin steps timed")
    ap.add_argument("--phases", type=int, default=61, help="TCA phases of the tables")
    ap.add_argument("--cpu", type=int, default=None, help="core to pin (default: the last)")
    ap.add_argument("--pair", default=str(EV), help="the cylindrical pair's TOML")
    ap.add_argument("--instructions", action="store_true",
                    help="also count instructions per step under valgrind's callgrind")
    args = ap.parse_args(argv)
    print(_pin(args.cpu) + "; load average %.2f %.2f %.2f" % os.getloadavg())
    bench_twin_step(args.steps, args.phases, "line", args.instructions, args.pair)
    bench_twin_step(args.steps, args.phases, "stencil", args.instructions, None)
    print("load average after: %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    main()
