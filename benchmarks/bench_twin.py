"""Benchmark of the drivetrain twin: steps per second and real-time factor per backend.

Runs ``gearcontact.twin`` on s0003 (64.5 N·m, 3000 rpm, 10 us RK4 step, default
drivetrain) for each contact backend and prints the wall and CPU time of the model's
build (the edge-contact TCA and mesh table of both sides), steps/s, the real-time factor
(simulated / wall time), the step time p50 / p99 (over blocks of 256 steps, one
compiled call each) and their jitter, the process CPU time per step and the load
average (the machine is shared: wall-clock figures include other load). Targets
(issue 14): compiled fp64 backend >= 10x real time on one core, golden >= 1x; the
``rtl`` and ``soc`` backends (golden loop + lockstep replay on ChainCore / HertzCore /
ChainLineCore or through the SoC register driver: tri_core / bhseq_core / line_core,
:mod:`gearcontact.twin.cosim`) run shorter times and
state their rates (the CPU column counts this process only, not the simulator).
``--curvatures``: the preview's curvature source (``stencil``: stage C per step, the
default; ``exact``; ``both``: every backend with each).

``--pair`` a cylindrical pair's TOML (e.g. ``examples/ev_reducer_helical_23x67.toml``):
its twin (:func:`gearcontact.twin.cylindrical.cylindrical_model`, ``--phases`` rows,
the preview backends on the line chain, the table backend on the loaded-TE table). The
column ``kernel us/step`` is the compiled loop's thread CPU time per step
(``time.thread_time`` around each block): on a shared machine the wall-clock
percentiles count the other processes' time slices too, the thread's own time much
less so (it still feels their cache and hyperthread contention).

Run: ``python benchmarks/bench_twin.py [--duration-ms 200] [--step-us 10]
[--curvatures stencil|exact|both] [--bending] [--pair PAIR] [--phases 61]`` (the 7/60
pair of tests/design_space.py, CHATTER_PAIR, is the one whose build the edge-contact TCA
dominates).
"""

from __future__ import annotations

import argparse
import os
import time

from gearcontact.geometry.cylindrical.pair import CylindricalPair
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair
from gearcontact.twin import kernel
from gearcontact.twin.cylindrical import CYLINDRICAL_BACKENDS, cylindrical_model
from gearcontact.twin.ltca_table import torque_table
from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import BACKENDS, build_model, model_for_pair, simulate


class _KernelClock:
    """Thread CPU time of the compiled step loop (``kernel.run_steps`` wrapped for the
    blocks of more than one step: not the one-step compile call)."""

    def __init__(self):
        self.seconds, self.steps = 0.0, 0
        self._run = kernel.run_steps
        kernel.run_steps = self

    def __call__(self, y, t0, n_steps, *args):
        c = time.thread_time()
        rows = self._run(y, t0, n_steps, *args)
        if n_steps > 1:
            self.seconds += time.thread_time() - c
            self.steps += n_steps
        return rows

    def take(self) -> float:
        """us per step since the last call."""
        us = self.seconds / max(self.steps, 1) * 1e6
        self.seconds, self.steps = 0.0, 0
        return us


def _cylindrical_models(pair, args):
    """The twin models of a cylindrical pair by backend (module docstring)."""
    backends = [b for b in args.backends.split(",") if b in CYLINDRICAL_BACKENDS]
    models = {b: cylindrical_model(pair, torque_nm=args.torque, phases=args.phases,
                                   backend=b, bending=args.bending) for b in backends}
    return models


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration-ms", type=float, default=200.0, help="simulated time (ms)")
    ap.add_argument("--step-us", type=float, default=10.0, help="RK4 step (us)")
    ap.add_argument("--speed-rpm", type=float, default=3000.0)
    ap.add_argument("--torque", type=float, default=64.5, help="gear torque (N·m)")
    ap.add_argument("--record-every", type=int, default=1, help="record every n-th step")
    ap.add_argument("--rtl-duration-ms", type=float, default=10.0,
                    help="simulated time of the rtl backend (lockstep RTL replay), ms")
    ap.add_argument("--soc-duration-ms", type=float, default=0.1,
                    help="simulated time of the soc backend (register driver replay), ms")
    ap.add_argument("--backends", default=",".join(BACKENDS))
    ap.add_argument("--pair", default="s0003")
    ap.add_argument("--bending", action="store_true", help="tooth bending in the law")
    ap.add_argument("--curvatures", default="stencil", choices=("stencil", "exact", "both"),
                    help="the preview's curvature source (default stencil: stage C per step)")
    ap.add_argument("--phases", type=int, default=61, help="cycle rows (cylindrical pair)")
    args = ap.parse_args()
    clock = _KernelClock()
    pair = load_pair(args.pair, kinds=("bevel", "cylindrical"))
    if isinstance(pair, CylindricalPair):
        models = _cylindrical_models(pair, args)
        print(f"{pair.name} (cylindrical) twin, {args.torque:g} N·m, {args.speed_rpm:g} rpm, "
              f"step {args.step_us:g} us, {args.duration_ms:g} ms simulated, "
              f"{args.phases} phases, bending {args.bending}")
        _table(args, [(be, be, m) for be, m in models.items()], clock)
        return
    side = pair.design_side
    w0, c0 = time.perf_counter(), time.process_time()
    base = model_for_pair(pair, torque_nm=args.torque, side=side, phases=61,
                          bending=args.bending)
    build = (time.perf_counter() - w0, time.process_time() - c0)
    mesh = base.mesh
    tca, flanks = analyze_pair(pair, side=side, phases=61, edge_contact=False)
    dt = default_drivetrain(pair)
    print(f"{pair.name} ({side}) twin, {args.torque:g} N·m, {args.speed_rpm:g} rpm, step "
          f"{args.step_us:g} us, {args.duration_ms:g} ms simulated, record every "
          f"{args.record_every}, bending {args.bending}; reverse flank: {base.reverse_note}")
    # the model's build: the edge-contact TCA of both sides (61 phases) and their mesh
    # tables, what `gearcontact twin` runs before its first step
    print(f"model build (edge-contact TCA and mesh table of both sides): wall {build[0]:.1f} "
          f"s, CPU {build[1]:.1f} s")
    runs = []
    sources = ("stencil", "exact") if args.curvatures == "both" else (args.curvatures,)
    for be, src in [(be, src) for be in args.backends.split(",") for src in sources
                    if be != "table" or src == sources[0]]:
        table = None
        if be == "table":
            table = torque_table(tca, flanks, pair, mesh, args.torque, side=side)
        model = build_model(mesh, dt, args.torque, backend=be, table=table,
                            reverse=base.reverse, reverse_note=base.reverse_note,
                            curvatures=src)
        runs.append((be, be if be == "table" else f"{be} ({src})", model))
    _table(args, runs, clock)


def _table(args, runs, clock) -> None:
    """Run each ``(backend, label, model)`` and print its row (module docstring)."""
    print(f"{'backend':<20}{'steps/s':>12}{'RT factor':>11}{'p50 (us)':>10}{'p99 (us)':>10}"
          f"{'p99/p50':>9}{'CPU us/step':>13}{'kernel us/step':>16}{'DF':>7}")
    lines = []
    for be, label, model in runs:
        simulate(model, speed_rpm=args.speed_rpm, duration_s=1e-3, step_s=1e-6 * args.step_us)
        ms = {"rtl": args.rtl_duration_ms, "soc": args.soc_duration_ms}.get(be,
                                                                          args.duration_ms)
        clock.take()
        c0 = time.process_time()
        res = simulate(model, speed_rpm=args.speed_rpm, duration_s=1e-3 * ms,
                       step_s=1e-6 * args.step_us, record_every=args.record_every)
        cpu = (time.process_time() - c0) / res.summary["steps"] * 1e6
        s, tm = res.summary, res.timings
        print(f"{label:<20}{s['steps'] / tm['wall_s']:>12.4g}{tm['real_time_factor']:>11.2f}"
              f"{tm['step_time_p50_us']:>10.3f}{tm['step_time_p99_us']:>10.3f}"
              f"{tm['step_time_p99_us'] / tm['step_time_p50_us']:>9.2f}{cpu:>13.3f}"
              f"{clock.take():>16.3f}{s['dynamic_factor']:>7.3f}")
        if be in ("rtl", "soc"):
            where = (f"{s['rtl_core']} core, {s['rtl_simulator']}" if be == "rtl"
                     else f"the {s['soc_kind']} SoC (register driver)")
            lines.append(f"{label}: {s[be + '_previews']} previews replayed on {where} at "
                         f"{tm[be + '_previews_per_s']:.4g} previews/s, "
                         f"{s[be + '_mismatches']} mismatches ({ms:g} ms simulated)")
    for line in lines:
        print(line)
    print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())} "
          f"on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
