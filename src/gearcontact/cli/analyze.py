"""``gearcontact analyze``: the main job — design, TCA, loaded contact at the operating
torques and the physics-direct preview, written to one directory with ``summary.md``.

A cylindrical pair (``kind = "cylindrical"``) gets TE0, the loaded TE at
``--lte-torque`` over ``--lte-phases`` phases (tooth bending; ``--rigid``: rigid
teeth), the Harris map, mesh stiffness, pressure and the preview's line chain per
phase and loaded pair (:mod:`gearcontact.report.analyze_cylindrical`; docs/cylindrical.md sec. 9).
"""

from __future__ import annotations

from ..errors import CheckFailed
from ..geometry.pair import BEVEL, CYLINDRICAL
from ..report.analyze import DEFAULT_TORQUES_NM, run_analysis
from ..ltca.cylindrical_lte import STRIP_TOO_NARROW
from ..report.analyze_cylindrical import end_loaded_note, run_cylindrical_analysis
from ..validation import InputRangeError
from .options import (
    MAX_PHASES,
    add_pair_arguments,
    case_warnings,
    check_count,
    check_cylindrical_torque,
    check_distinct_torques,
    check_pair_arguments,
    check_torque,
    lte_warnings,
    record_completed_settings,
    run_timings,
    warn,
)
from .outdir import final_path

#: Upper limit of the number of ``--torques``.
MAX_TORQUES = 32


def register(sub) -> None:
    p = sub.add_parser("analyze", help="main job: design, TCA, LTCA and preview of a pair "
                                       "into one directory",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, misalignment=True)
    p.add_argument("--torques", type=float, nargs="+", default=list(DEFAULT_TORQUES_NM),
                   metavar="T", help="gear torques in N·m (default 32.25 64.5 129 258)")
    p.add_argument("--lte-torque", type=float, default=64.5, metavar="T",
                   help="gear torque of the loaded-TE run, N·m (default 64.5)")
    p.add_argument("--lte-phases", type=int, default=None,
                   help="phases of the loaded-TE run over one pitch, 3 to --phases "
                        "(default: every TCA phase; 0 skips it)")
    p.add_argument("--rigid", action="store_true",
                   help="loaded TE with rigid teeth (default: with the shell bending of "
                        "both teeth)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """Every option and the pair file, before any work."""
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))
    if args.gear_pair.kind == CYLINDRICAL:
        check_cylindrical(args)
        return
    if not 1 <= len(args.torques) <= MAX_TORQUES:
        raise InputRangeError("--torques", args.torques, f"1 to {MAX_TORQUES} torques")
    for t in args.torques:
        check_torque("--torques (N·m)", t, args.gear_pair)
    check_distinct_torques("--torques", args.torques)
    check_torque("--lte-torque (N·m)", args.lte_torque, args.gear_pair)
    if args.lte_phases is None:
        args.lte_phases = args.phases
    if args.lte_phases != 0:
        # the loaded TE runs on TCA phases: more than --phases would silently be --phases
        check_count("--lte-phases", args.lte_phases, 3, min(args.phases, MAX_PHASES),
                    note=f", or 0 to skip (at most --phases = {args.phases}: the loaded TE "
                         "runs on TCA phases)")


def check_cylindrical(args) -> None:
    """The options of a cylindrical pair: one torque (``--lte-torque``); tooth bending
    unless ``--rigid``."""
    if list(args.torques) != list(DEFAULT_TORQUES_NM):
        raise InputRangeError("--torques", args.torques, "not given for a cylindrical pair (the "
                                                         "loaded TE and the preview run at "
                                                         "--lte-torque, the Harris map at the ISO "
                                                         "line loads 50-400 N/mm)")
    # held to the preview envelope as every other command's torque (an unchecked 1e6
    # N·m ran for minutes)
    check_cylindrical_torque("--lte-torque (N·m)", args.lte_torque, args.gear_pair)
    if args.lte_phases is None:
        args.lte_phases = args.phases
    check_count("--lte-phases", args.lte_phases, 3, MAX_PHASES,
                note=" (a cylindrical pair's loaded TE is the job)")


def run_cylindrical(args) -> int:
    res = run_cylindrical_analysis(args.gear_pair, out_dir=args.out, torque_nm=args.lte_torque,
                                   phases=args.lte_phases, side=args.side,
                                   figures=not args.no_figures, bending=not args.rigid)
    run_timings(args, **res.timings_s)
    h = res.summary
    teeth = "tooth bending" if h["teeth"] == "bending" else "rigid teeth"
    print(f"{res.pair.name} {args.side}, {h['torque_nm']:g} N·m, {teeth}: TE0 p-p "
          f"{h['te0_pp_arcsec']:.2f} / loaded TE p-p {h['lte_pp_arcsec']:.2f} arcsec, mesh "
          f"stiffness {h['mesh_stiffness_n_per_mm_um']['mean']:.1f} N/(mm·µm), p_max LCP "
          f"{h['lcp_max_pressure_mpa']:.0f} / preview {h['preview_max_pressure_mpa']['golden']:.0f}"
          f" MPa -> {final_path(args, res.out_dir / 'summary.md')}")
    if h["end_loaded_lines"] is not None or h["lcp_peak_at_edge"]:
        warn("analyze", end_loaded_note(h))
    if h["edge_touch"]:
        warn("analyze", STRIP_TOO_NARROW)
    if not h["converged"]:
        raise CheckFailed("LCP not converged")   # the files stay
    return 0


def run(args) -> int:
    if getattr(args, "gear_pair", None) is None:
        check(args)
    if args.gear_pair.kind == CYLINDRICAL:
        return run_cylindrical(args)
    res = run_analysis(args.gear_pair, out_dir=args.out, torques_nm=args.torques,
                       phases=args.phases, side=args.side, figures=not args.no_figures,
                       progress=not args.quiet,
                       lte_torque_nm=args.lte_torque if args.lte_phases else None,
                       lte_phases=max(args.lte_phases, 3), lte_bending=not args.rigid,
                       settings_check=args.settings_check)
    record_completed_settings(args, res.settings_check)     # a generated gear's pinions
    run_timings(args, **res.timings_s)
    if res.easeoff_note:
        print(res.easeoff_note.partition("\n")[0].rstrip(":") + " (the TOML block is in summary.md)")
    design = min(res.cases, key=lambda c: abs(c.torque_nm - args.lte_torque))
    print(f"{res.pair.name}: TE0 p-p {res.tca.cycle.te0_pp_arcsec:.2f} arcsec; at "
          f"{design.torque_nm:g} N·m W = {design.load_n:.0f} N, preview p_max "
          f"{design.preview.p_max_mpa:.0f} MPa, LCP p90 {design.patch.p90_mpa:.0f} MPa"
          + (f"; LTE p-p {res.lte.te_lcp_pp_arcsec:.2f} (LCP) / "
             f"{res.lte.te_pre_pp_arcsec:.2f} (preview) arcsec" if res.lte is not None else "")
          + f" -> {final_path(args, res.out_dir / 'summary.md')}")
    lines = [line for case in res.cases for line in case_warnings(case)]
    for line in lines + (lte_warnings(res.lte) if res.lte is not None else []):
        warn("analyze", line)
    return 0
