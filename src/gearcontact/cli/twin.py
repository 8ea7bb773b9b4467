"""``gearcontact twin``: real-time torsional drivetrain twin driven by the contact preview.

Writes into ``--out`` (created if missing): ``twin.json`` (backend, steps, step_us,
mesh frequency, mean mesh torque and load vs the
static ones, dynamic factor, contact-loss fraction, DTE peak-to-peak, linearised natural
frequencies, the mesh rows per contact mode; :func:`gearcontact.twin.simulate.simulate`),
``twin.csv`` (time series), ``mesh.csv`` (the loaded side's mesh table per phase and pair:
surface or edge contact, docs/twin.md) and
``twin.png`` / ``twin_spectrum.png``; the real-time factor and the step-time p50/p99
are timings and go to ``run.json`` only (identical runs write byte-identical files). With ``--speed-sweep START:STOP:STEP`` it runs the
dynamic factor vs speed curve instead, for the preview twin (``--backend``) and the table
twin side by side, in parallel over the speeds: ``sweep.json``, ``sweep.csv``,
``sweep.png`` (:mod:`gearcontact.twin.sweep`). Drivetrain parameters: the ``[drivetrain]`` table
of ``--drivetrain FILE`` over the s0003 defaults of :mod:`gearcontact.twin.params`.

A cylindrical pair (``kind = "cylindrical"``) runs the preview's line chain as the
contact law (``--backend reference``, the default, ``golden``, ``rtl``: the ChainLineCore
replay, or ``soc``: the replay through the host driver on the line_core SoC) or its
loaded-TE table (``--backend table``: the loaded TE of its mesh cycle over
a torque ladder), rigid teeth or with ``--bending`` (the preview backends: the coupled
slice law, the line law on the ease-off the teeth's bending along the contact line
leaves, :mod:`gearcontact.ltca.coupled_slice_law`), and
``--speed-sweep`` beside the table twin (:mod:`gearcontact.twin.cylindrical`,
docs/cylindrical.md sec. 10); ``--curvatures exact``, ``--table-source preview`` and
``--hertz-form exact`` are refused for it.

``--hertz-form exact`` (reference backend, bevel and hypoid pairs) evaluates the
preview's fp64 law as exact elliptic Hertz instead of Hamrock-Brewe's closed forms
(:mod:`gearcontact.twin.exact_hertz`; docs/twin.md, docs/hertz.md sec. 7).
"""

from __future__ import annotations

import math
import os

from ..geometry.pair import BEVEL, CYLINDRICAL
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM, HERTZ_FORMS
from ..tca.line_contact import check_loadable
from ..twin.cylindrical import (CYLINDRICAL_BACKENDS, cylindrical_model,
                                cylindrical_sweep_models)
from ..twin.params import check_drivetrain_file, load_drivetrain
from ..twin.report import write_sweep_outputs, write_twin_outputs
from ..twin.simulate import (BACKENDS, CURVATURE_SOURCES, MAX_SPEED_RPM, STEP_RANGE_US,
                             build_model, model_for_pair, simulate)
from ..twin.sweep import parse_speed_range, speed_sweep
from ..validation import InputRangeError, check_positive, check_range
from .options import (add_pair_arguments, check_count, check_pair_arguments, load_pair_for,
                      run_timings)
from .outdir import final_path

#: Longest simulated time one run accepts (s): 6 million steps at 10 us, about 10 s of
#: wall time on the compiled fp64 backend; longer studies are several runs.
MAX_DURATION_S = 60.0
#: Most rows of the time series one run keeps (steps / --record-every): the longest run
#: at the default step (MAX_DURATION_S at 10 us). The record is held in memory, 16
#: float64 per row: 6 million rows are 0.77 GB. Without this check 60 s at 1 us (60
#: million rows, 7.7 GB) ended in a MemoryError after a minute of work.
MAX_RECORD_ROWS = 6_000_000


def register(sub) -> None:
    p = sub.add_parser("twin", help="torsional drivetrain twin with the preview as the "
                                    "contact law: dynamic TE, mesh load, dynamic factor",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, torque=True)
    p.add_argument("--speed-rpm", type=float, default=3000.0,
                   help="pinion (motor) speed in rpm (default 3000)")
    dur = p.add_mutually_exclusive_group()
    dur.add_argument("--duration-ms", type=float, default=None,
                     help="simulated time in ms (default 50)")
    dur.add_argument("--duration", type=float, default=None,
                     help="simulated time in s (alternative to --duration-ms)")
    p.add_argument("--step-us", type=float, default=10.0,
                   help=f"fixed RK4 step in us, {STEP_RANGE_US[0]:g}-{STEP_RANGE_US[1]:g} "
                        "(default 10)")
    p.add_argument("--backend", default="reference",
                   help=f"contact backend: one of {', '.join(BACKENDS)} (default reference)")
    p.add_argument("--drivetrain", default=None,
                   help="TOML file with a [drivetrain] table (default: s0003 estimates)")
    p.add_argument("--table-source", default="lcp", choices=("lcp", "preview"),
                   help="table backend: LTCA (lcp, default) or Hertz preview loaded TE")
    p.add_argument("--bending", action="store_true",
                   help="tooth bending of both members (shell model): in series with a "
                        "bevel pair's Hertzian law; coupled with a cylindrical pair's line "
                        "law along the line (docs/cylindrical.md sec. 10) (default rigid "
                        "teeth)")
    p.add_argument("--curvatures", default="stencil", choices=CURVATURE_SOURCES,
                   help="where the preview's curvatures come from: stencil (default: stage "
                        "C per step, the curvature fit of the 7 x 7 gap stencil, then "
                        "stage D: the whole C -> D preview) or exact (the TCA's "
                        "shape-operator curvatures, the law of the loaded TE's preview)")
    p.add_argument("--hertz-form", default=DEFAULT_HERTZ_FORM, choices=HERTZ_FORMS,
                   help="the preview's fp64 Hertz law: hamrock-brewe (default: the closed "
                        "forms, within 5 %% of exact Hertz up to curvature ratio 122) or "
                        "exact (exact elliptic Hertz, tabled over the curvature ratio; "
                        "--backend reference only)")
    p.add_argument("--board", default=None, metavar="HOST:PORT",
                   help="soc backend: replay the previews through the litex_server at "
                        "HOST:PORT (a board built with this pair's E', or `gearcontact rtl "
                        "serve`) instead of the SoC simulation in this process")
    p.add_argument("--record-every", type=int, default=1,
                   help=f"write every n-th step to twin.csv (default 1); steps / n must "
                        f"not exceed {MAX_RECORD_ROWS:,} rows (held in memory)")
    p.add_argument("--speed-sweep", default=None, metavar="START:STOP:STEP",
                   help="rpm range: dynamic factor vs speed, preview and table twins")
    p.add_argument("--workers", type=int, default=None,
                   help="worker processes of the speed sweep, 1 to the CPU count (default: "
                        "CPU count; never more than the sweep's runs are started)")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """Every option before any work (and before the output directory is touched)."""
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))
    if args.backend not in BACKENDS:
        raise InputRangeError("--backend", args.backend, f"one of {list(BACKENDS)}")
    if args.hertz_form != DEFAULT_HERTZ_FORM and args.backend != "reference":
        raise InputRangeError("--hertz-form", args.hertz_form,
                              f"{DEFAULT_HERTZ_FORM} with --backend {args.backend} (the "
                              "exact form is the fp64 law of --backend reference)")
    if args.gear_pair.kind == CYLINDRICAL:
        check_cylindrical(args)
    else:
        check_loadable(args.gear_pair, args.side)
    check_range("--step-us", args.step_us, *STEP_RANGE_US)
    if args.duration is not None:
        duration_s = check_positive("--duration", args.duration)
    else:
        duration_s = 1e-3 * check_positive("--duration-ms", 50.0 if args.duration_ms is None
                                           else args.duration_ms)
    if duration_s > MAX_DURATION_S:
        raise InputRangeError("--duration" if args.duration is not None else "--duration-ms",
                              args.duration if args.duration is not None
                              else args.duration_ms,
                              f"at most {MAX_DURATION_S:g} s of simulated time")
    if args.drivetrain is not None:
        check_drivetrain_file(args.drivetrain)
    check_range("--speed-rpm", args.speed_rpm, 0.0, MAX_SPEED_RPM)
    if args.record_every < 1:
        raise InputRangeError("--record-every", args.record_every, ">= 1")
    speeds = parse_speed_range(args.speed_sweep) if args.speed_sweep else None
    rows = math.ceil(round(duration_s / (1e-6 * args.step_us)) / args.record_every)
    if speeds is None and rows > MAX_RECORD_ROWS:     # before the record is allocated
        raise InputRangeError("--record-every", args.record_every, f">= "
                              f"{math.ceil(rows * args.record_every / MAX_RECORD_ROWS)}: "
                              f"{rows:,} rows of the time series (duration / step / "
                              f"--record-every) exceed the {MAX_RECORD_ROWS:,} one run holds")
    if speeds is not None and speeds[-1] > MAX_SPEED_RPM:
        raise InputRangeError("--speed-sweep", args.speed_sweep, f"speeds in (0, "
                              f"{MAX_SPEED_RPM:g}] rpm (the --speed-rpm limit)")
    if speeds is not None and args.backend not in ("reference", "golden"):
        raise InputRangeError("--backend", args.backend, "reference or golden with "
                              "--speed-sweep (the table twin runs beside it)")
    if args.workers is not None:
        if speeds is None:
            raise InputRangeError("--workers", args.workers, "only with --speed-sweep")
        check_count("--workers", args.workers, 1, os.cpu_count() or 1,
                    note=" (the CPU count)")
    args.board_address = None
    if args.board is not None:
        if args.backend != "soc":
            raise InputRangeError("--board", args.board, "only with --backend soc")
        from ..hw.serve import parse_address
        args.board_address = parse_address(args.board, field="--board")
    args.duration_s, args.speeds = duration_s, speeds


def check_cylindrical(args) -> None:
    """The options a cylindrical pair's twin takes (module docstring)."""
    if args.backend not in CYLINDRICAL_BACKENDS:
        raise InputRangeError("--backend", args.backend, f"one of {list(CYLINDRICAL_BACKENDS)}"
                                                         " for a cylindrical pair "
                                                         "(docs/cylindrical.md sec. 10)")
    if args.table_source != "lcp":
        raise InputRangeError("--table-source", args.table_source, "lcp for a cylindrical pair "
                                                                   "(its loaded TE is the LCP's)")
    if args.curvatures != "stencil":
        raise InputRangeError("--curvatures", args.curvatures, "stencil for a cylindrical pair "
                                                               "(the line chain: stage C on "
                                                               "the stencil per step)")
    if args.hertz_form != DEFAULT_HERTZ_FORM:
        raise InputRangeError("--hertz-form", args.hertz_form,
                              f"{DEFAULT_HERTZ_FORM} for a cylindrical pair (the line "
                              "chain's law)")


def run(args) -> int:
    if not hasattr(args, "duration_s"):
        check(args)
    speeds = args.speeds
    if args.gear_pair.kind == CYLINDRICAL:
        pair = args.gear_pair
        drivetrain = load_drivetrain(args.drivetrain, pair)
        if speeds is not None:
            return _sweep(args, pair, drivetrain, speeds, cylindrical_sweep_models(
                pair, torque_nm=args.torque, backend=args.backend, drivetrain=drivetrain,
                side=args.side, phases=args.phases, bending=args.bending))
        model = cylindrical_model(pair, torque_nm=args.torque, backend=args.backend,
                                  drivetrain=drivetrain, side=args.side, phases=args.phases,
                                  bending=args.bending)
        return _simulate(args, pair, model, drivetrain, {})
    pair = load_pair_for(args)      # a pair file without an ease-off table: synthesized
    drivetrain = load_drivetrain(args.drivetrain, pair)
    if speeds is not None:
        return _sweep(args, pair, drivetrain, speeds, _bevel_sweep_models(args, pair,
                                                                          drivetrain))
    model = model_for_pair(pair, torque_nm=args.torque, backend=args.backend,
                           drivetrain=drivetrain, side=args.side, phases=args.phases,
                           table_source=args.table_source, bending=args.bending,
                           curvatures=args.curvatures, flanks=args.prepared_pair.flank_set(),
                           progress=not args.quiet, hertz_form=args.hertz_form)
    return _simulate(args, pair, model, drivetrain,
                     {"easeoff_synthesized": args.prepared_pair.synthesized})


def _simulate(args, pair, model, drivetrain, extra: dict) -> int:
    duration_s = args.duration_s
    res = simulate(model, speed_rpm=args.speed_rpm, duration_s=duration_s,
                   step_s=1e-6 * args.step_us, record_every=args.record_every,
                   progress=not args.quiet, board=args.board_address)
    run_timings(args, **res.timings)
    extra = {"pair": pair.name, "side": args.side, **extra,
             "drivetrain": drivetrain.as_dict()}
    if args.backend == "table":
        extra["table_source"] = args.table_source
    s = write_twin_outputs(res, args.out, figures=not args.no_figures,
                           title=f"{pair.name} {args.side}", extra=extra, mesh=model.mesh)
    print(f"{pair.name} twin {s['backend']} ({s['curvatures']} curvatures): {s['steps']} "
          f"steps of {s['step_us']:g} us, "
          f"mesh {s['mesh_frequency_hz']:g} Hz; mean mesh torque {s['mean_mesh_torque_nm']:.3f}"
          f" / static {s['static_mesh_torque_nm']:g} N·m, dynamic factor "
          f"{s['dynamic_factor']:.3f}, contact loss {100 * s['contact_loss']:.1f} %, DTE p-p "
          f"{s['dte_pp_arcsec']:.2f} arcsec; real-time factor "
          f"{res.timings['real_time_factor']:.2f} "
          f"-> {final_path(args, args.out)}")
    if s.get("previews_outside_datapath"):      # a result of the pair, in twin.json too
        why = ("loaded lengths or curvatures outside the line core's ranges"
               if s["curvatures"] == "line" else "long bearings")
        print(f"  {s['previews_outside_datapath']} previews in {s['steps_outside_datapath']} "
              f"steps lie outside the fixed-point datapath's domain ({why}): "
              f"evaluated by {s['outside_datapath_evaluated_by']}")
    if s.get("hertz_form"):     # only a non-default form is stated (default output kept)
        print(f"  fp64 Hertz law: {s['hertz_form']} on {s['hertz_law_rows']} mesh rows "
              f"(curvature ratio up to {s['hertz_law_ratio_max']:.4g}; "
              f"{s['hertz_law_status']})")
    if s.get("hertz_law_rows_beyond_range"):    # likewise (docs/hertz.md sec. 7)
        print(f"  {s['hertz_law_rows_beyond_range']} of {s['hertz_law_rows']} mesh rows "
              f"(curvature ratio up to {s['hertz_law_ratio_max']:.4g}) lie beyond the range "
              "where the Hamrock-Brewe law is within 5 % of exact Hertz "
              f"({s['hertz_law_status']})")
    return 0


def _bevel_sweep_models(args, pair, drivetrain) -> dict:
    table_model = model_for_pair(pair, torque_nm=args.torque, backend="table",
                                 drivetrain=drivetrain, side=args.side, phases=args.phases,
                                 table_source=args.table_source, bending=args.bending,
                                 flanks=args.prepared_pair.flank_set(), progress=not args.quiet)
    preview = build_model(table_model.mesh, drivetrain, args.torque, backend=args.backend,
                          reverse=table_model.reverse, reverse_note=table_model.reverse_note,
                          curvatures=args.curvatures, hertz_form=args.hertz_form)
    return {args.backend: preview, "table": table_model}


def _sweep(args, pair, drivetrain, speeds, models: dict) -> int:
    sw = speed_sweep(models, speeds, step_s=1e-6 * args.step_us, workers=args.workers,
                     progress=not args.quiet)
    run_timings(args, **{f"{label}_mean_real_time_factor": float(rows["real_time_factor"].mean())
                         for label, rows in sw.rows.items()})
    s = write_sweep_outputs(sw, args.out, figures=not args.no_figures,
                            title=f"{pair.name} {args.side} {args.torque:g} N·m",
                            extra={"pair": pair.name, "step_us": args.step_us,
                                   "table_source": args.table_source,
                                   "drivetrain": drivetrain.as_dict()})
    print(f"{pair.name} twin speed sweep {speeds[0]:g}-{speeds[-1]:g} rpm ({speeds.size} "
          f"speeds): max dynamic factor {args.backend} {s[args.backend]['max_dynamic_factor']:.3f}"
          f" at {s[args.backend]['at_speed_rpm']:g} rpm, table "
          f"{s['table']['max_dynamic_factor']:.3f} at {s['table']['at_speed_rpm']:g} rpm "
          f"-> {final_path(args, args.out)}")
    return 0
