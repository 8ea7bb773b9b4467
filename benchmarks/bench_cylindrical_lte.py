"""Benchmark: loaded TE of the helical EV-reducer example over one pinion pitch (61
phases) with the shell bending of both teeth (issue 26's budget: <= 1 s CPU) and with
rigid teeth.

Beside it, the time ``ross-rotordynamics`` takes for its mesh stiffness of the same
pair over the same number of phases (issue 26: the budget printed beside the independent
code's stiffness computation; ROSS's energy method is a spur tooth's, so on this helical,
shifted, modified pair its stiffness is printed as a time reference, not a comparison:
that is benchmarks/bench_mesh_stiffness_ross.py on the spur pair). Skipped with a note
where ROSS is not installed (a benchmark-only peer).

The unloaded mesh cycle (:func:`gearcontact.tca.cylindrical_cycle.cylindrical_mesh_cycle`)
runs once and is timed on its own; so is the one-off build of the tooth models (shells of
both teeth, their flank maps and row splines: :func:`gearcontact.ltca.cylindrical_bending.
cylindrical_bending`, cached per pair for every later run, as for bevel pairs); the
mesh-LCP kernels are compiled (or loaded from numba's cache) before timing. Then
:func:`gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te` is timed as a whole
(wall-clock and process CPU, best of ``--repeat``), with the CPU of its LCP loop
(``solve_time_s``: grids, gaps, bending factors, solves) beside it. The machine's load
average is printed.

Run: ``python benchmarks/bench_cylindrical_lte.py [--repeat N] [--phases N]
[--torque N·m]``.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np
from bench_mesh_stiffness_ross import ross_stiffness

from gearcontact.geometry.pair import CYLINDRICAL, load_pair
from gearcontact.ltca.cylindrical_bending import cylindrical_bending
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.ltca.mesh_lcp import warm_up_mesh_lcp
from gearcontact.ltca.tooth_bending import flank_rows
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle

TARGET_S = 1.0
PAIR = Path(__file__).resolve().parents[1] / "examples" / "ev_reducer_helical_23x67.toml"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--phases", type=int, default=61)
    ap.add_argument("--torque", type=float, default=64.5, help="gear torque, N·m")
    args = ap.parse_args()
    pair = load_pair(PAIR, kinds=(CYLINDRICAL,))
    warm_up_mesh_lcp()
    w0, c0 = time.perf_counter(), time.process_time()
    cycle = cylindrical_mesh_cycle(pair, phases=args.phases)
    print(f"unloaded cycle: {time.perf_counter() - w0:.3f} s wall, "
          f"{time.process_time() - c0:.3f} s CPU")
    w0, c0 = time.perf_counter(), time.process_time()
    teeth = cylindrical_bending(pair, facing=cycle.facing)
    for shell in (teeth.pinion, teeth.gear):
        flank_rows(shell, teeth.side).rows(np.zeros((1, 2)))
    print(f"tooth models (shells, flank maps, row splines; once per pair): "
          f"{time.perf_counter() - w0:.3f} s wall, {time.process_time() - c0:.3f} s CPU")
    for bending in (True, False):
        best = None
        for _ in range(max(args.repeat, 1)):
            w0, c0 = time.perf_counter(), time.process_time()
            res = cylindrical_loaded_te(pair, args.torque, cycle=cycle, bending=bending)
            t = (time.perf_counter() - w0, time.process_time() - c0, res.solve_time_s)
            best = t if best is None or t[1] < best[1] else best
        wall, cpu, loop = best
        label = "with bending" if bending else "rigid teeth"
        verdict = f" (target <= {TARGET_S} s CPU) -> {'ok' if cpu <= TARGET_S else 'over'}" \
            if bending else ""
        print(f"loaded TE, {args.phases} phases, {args.torque:g} N·m, {label}: {wall:.3f} s "
              f"wall, {cpu:.3f} s CPU (LCP loop {loop:.3f} s CPU){verdict}")
        print(f"  LTE p-p {res.lte_pp_arcsec:.3f} arcsec, mean stiffness "
              f"{res.mean_stiffness_n_per_mm_um:.2f} N/(mm·µm), LCP iterations max "
              f"{res.iterations.max()}; load average {os.getloadavg()[0]:.2f}")
    try:
        k, t_ross, _ = ross_stiffness(pair, args.phases - 1)
    except SystemExit as exc:                      # ROSS not installed: say so
        print(f"ROSS stiffness: not run ({exc})")
    else:
        print(f"ROSS stiffness (energy method, spur tooth of the same m_n, z, b), "
              f"{args.phases - 1} phases: {t_ross:.3f} s CPU; mean {k.mean():.2f} "
              f"N/(mm·µm) (a time reference: no helix, shift or micro-geometry)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
