"""``gearcontact rtl``: run the RTL cores against the golden model, export their Verilog.

``rtl sim`` runs the corner cases plus N seeded random vectors of a core through the
RTL (Verilator, or the Amaranth simulator) and the bit-exact golden model, and reports
cycles per evaluation, vectors, mismatches and the simulator speed; the exit code is 4
on any mismatch or cycle-count deviation. ``rtl verilog`` writes a core's Verilog and a
README of its ports; ``rtl soc`` and ``rtl synth`` (board flow, synthesis reports).

``soc`` and ``synth`` are defined in :mod:`.rtl_hw` and hooked in here.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from ..errors import RtlMismatch
from ..hw.harness_cores import CORE_NAMES, SIMULATORS, get_bench
from ..hw.verilator import require_verilator, verilator_available, verilator_version
from ..hw.verilog_export import write_core_verilog

from ..validation import InputRangeError
from .options import check_count
from .outdir import add_out_argument, final_path

#: Most random vectors of one ``rtl sim`` run (the slow suite runs 100,000).
MAX_SIM_VECTORS = 10_000_000
#: Most parallel Verilator processes.
MAX_JOBS = 64


def register(sub) -> None:
    p = sub.add_parser("rtl", help="RTL cores: bulk simulation against the golden model, "
                                   "Verilog export",
                       description=__doc__.split("\n\n")[1])
    cmds = p.add_subparsers(dest="rtl_command", metavar="ACTION", required=True)

    s = cmds.add_parser("sim", help="run corner cases + N random vectors through the RTL "
                                    "and the golden model")
    s.add_argument("--core", choices=CORE_NAMES, required=True,
                   help="; ".join(f"{n}: {get_bench(n).summary}" for n in CORE_NAMES))
    s.add_argument("--vectors", type=int, default=1000, metavar="N",
                   help=f"random vectors in addition to the corner cases, 0 to "
                        f"{MAX_SIM_VECTORS} (default 1000)")
    s.add_argument("--seed", type=int, default=0, metavar="S", help="random seed (default 0)")
    s.add_argument("--simulator", choices=SIMULATORS, default=None,
                   help="default: verilator when installed, else amaranth (slow)")
    s.add_argument("--samples", type=int, default=None, metavar="N",
                   help="gap cores only: samples per pass (default 16)")
    s.add_argument("--no-corners", action="store_true", help="random vectors only")
    s.add_argument("--jobs", type=int, default=1, metavar="J",
                   help="parallel Verilator processes (default 1)")
    s.add_argument("--json", action="store_true", help="print one JSON object")
    s.set_defaults(func=run_sim, check=check_sim)

    v = cmds.add_parser("verilog", help="write a core's Verilog and a README of its ports")
    v.add_argument("--core", choices=CORE_NAMES + ("all",), required=True)
    add_out_argument(v)
    v.set_defaults(func=run_verilog)

    from .rtl_hw import register_rtl_subcommands  # rtl soc, rtl synth
    register_rtl_subcommands(cmds)


def check_sim(args) -> None:
    """Every ``rtl sim`` option, before any build or simulation."""
    check_count("--vectors", args.vectors, 1 if args.no_corners else 0, MAX_SIM_VECTORS,
                note=" (at least 1 with --no-corners)" if args.no_corners else "")
    check_count("--jobs", args.jobs, 1, MAX_JOBS)
    check_count("--seed", args.seed, 0, 2 ** 63 - 1)
    if args.samples is not None and args.core not in ("gap", "gap_lean"):
        raise InputRangeError("--samples", args.samples, "only with --core gap or gap_lean")


def run_sim(args) -> int:
    from ..hw.harness_cores import run_equivalence
    check_sim(args)
    kwargs = {}
    if args.samples is not None:
        kwargs["n_samples"] = args.samples
    simulator = args.simulator
    if simulator is None:
        simulator = "verilator" if verilator_available() else "amaranth"
        if simulator == "amaranth":
            print("gearcontact rtl: Verilator not installed, using the Amaranth simulator "
                  "(slow); apt-get install verilator for bulk runs", file=sys.stderr)
    if simulator == "verilator":        # missing or broken: ToolUnavailable (exit 2)
        require_verilator()
    rep = run_equivalence(args.core, args.vectors, args.seed, simulator=simulator,
                          corners=not args.no_corners, jobs=args.jobs, **kwargs)
    version = verilator_version() if simulator == "verilator" else None
    if args.json:
        print(json.dumps({**rep.as_dict(), "seed": args.seed, "simulator_version": version},
                         indent=2))
    else:
        bench = get_bench(args.core)
        print(f"core         {rep.core}: {bench.summary}")
        print(f"simulator    {rep.simulator}" + (f" ({version.split(' rev')[0]})"
                                                  if version else ""))
        print(f"vectors      {rep.vectors} ({rep.corner_vectors} corner cases + "
              f"{rep.vectors - rep.corner_vectors} random, seed {args.seed})")
        counts = ", ".join(f"{c} x {k}" for k, c in rep.cycle_counts.items())
        print(f"cycles       {rep.cycles if rep.cycles is not None else counts} per "
              f"evaluation (expected {rep.cycles_expected}"
              f"{', data independent' if rep.cycles is not None else ''})")
        if rep.streaming:
            print(f"interval     {rep.initiation_interval} cycles between accepted inputs "
                  f"(initiation interval; cycles above = latency)")
        print(f"mismatches   {rep.mismatches}")
        for ex in rep.mismatch_examples:
            print(f"  vector {ex['vector']} ({ex['label']}): {ex['port']} rtl {ex['rtl']} "
                  f"golden {ex['golden']}")
        print(f"speed        {rep.cycles_per_second:,.0f} cycles/s ({rep.sim_cycles:,} cycles "
              f"in {rep.sim_seconds:.3g} s; build {rep.build_seconds:.3g} s, golden "
              f"{rep.golden_seconds:.3g} s)")
    if not rep.ok:
        raise RtlMismatch(f"RTL != golden on core {rep.core}: {rep.mismatches} of "
                          f"{rep.vectors} vectors mismatch; cycles {rep.cycles} (expected "
                          f"{rep.cycles_expected}), initiation interval "
                          f"{rep.measured_ii if rep.streaming else 'n/a'}")
    return 0


def run_verilog(args) -> int:
    out = Path(args.out)
    for core in (CORE_NAMES if args.core == "all" else (args.core,)):
        exported = write_core_verilog(core, out)
        print(f"{final_path(args, exported.path)} ({exported.lines} lines, "
              f"{exported.ports} ports)")
    return 0
