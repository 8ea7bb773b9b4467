"""``gearcontact analyze``: the main job — design, TCA, loaded contact at the operating
torques and the physics-direct preview, written to one directory with ``summary.md``.
"""

from __future__ import annotations

from ..report.analyze import DEFAULT_TORQUES_NM, run_analysis
from .options import add_pair_arguments, check_pair_arguments


def register(sub) -> None:
    p = sub.add_parser("analyze", help="main job: design, TCA, LTCA and preview of a pair "
                                       "into one directory",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p)
    p.add_argument("--torques", type=float, nargs="+", default=list(DEFAULT_TORQUES_NM),
                   metavar="T", help="gear torques in N·m (default 32.25 64.5 129 258)")
    p.add_argument("--lte-torque", type=float, default=64.5, metavar="T",
                   help="gear torque of the loaded-TE run, N·m (default 64.5)")
    p.add_argument("--lte-phases", type=int, default=61,
                   help="phases of the loaded-TE run over one pitch (default 61, every TCA "
                        "phase; 0 skips it)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    check_pair_arguments(args)
    if args.lte_phases != 0 and args.lte_phases < 3:
        raise ValueError(f"--lte-phases = {args.lte_phases} must be 0 (skip) or >= 3")
    res = run_analysis(args.pair, out_dir=args.out, torques_nm=args.torques,
                       phases=args.phases, side=args.side, figures=not args.no_figures,
                       progress=not args.quiet,
                       lte_torque_nm=args.lte_torque if args.lte_phases else None,
                       lte_phases=max(args.lte_phases, 3))
    if res.easeoff_note:
        print(res.easeoff_note.partition("\n")[0].rstrip(":") + " (the TOML block is in summary.md)")
    design = min(res.cases, key=lambda c: abs(c.torque_nm - args.lte_torque))
    print(f"{res.pair.name}: TE0 p-p {res.tca.cycle.te0_pp_arcsec:.2f} arcsec; at "
          f"{design.torque_nm:g} N·m W = {design.load_n:.0f} N, preview p_max "
          f"{design.preview.p_max_mpa:.0f} MPa, LCP p90 {design.patch.p90_mpa:.0f} MPa"
          + (f"; LTE p-p {res.lte.te_lcp_pp_arcsec:.2f} (LCP) / "
             f"{res.lte.te_pre_pp_arcsec:.2f} (preview) arcsec" if res.lte is not None else "")
          + f" -> {res.out_dir / 'summary.md'}")
    return 0
