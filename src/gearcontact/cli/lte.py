"""``gearcontact lte``: loaded transmission error over one pinion pitch (rigid teeth).

Writes into ``--out`` (created if missing): ``lte.json`` (peak-to-peaks of TE0, TE_LCP
and TE_pre, contact and mesh compliances, active pairs, load shares at P0, timings; see
:meth:`~gearcontact.contact.lte.LoadedTE.summary`), ``lte.csv`` (one row per phase: TE0,
TE_LCP, TE_pre, rotations, active pairs, load per pair) and ``lte.png``.
"""

from __future__ import annotations

import sys
from ..contact.lte import loaded_te
from ..report.lte_plot import write_lte_outputs
from ..tca.analysis import analyze_pair
from .options import add_pair_arguments, check_pair_arguments, load_pair_for


def register(sub) -> None:
    p = sub.add_parser("lte", help="loaded transmission error along the mesh phase: "
                                   "TE_LCP, TE_pre, active pairs, compliances",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, torque=True, cells=40)
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run)


def run(args) -> int:
    check_pair_arguments(args)
    pair = load_pair_for(args)
    from ..report.analyze import published_values

    tca, flanks = analyze_pair(pair, side=args.side, phases=args.phases,
                               progress=not args.quiet)
    res = loaded_te(tca, flanks, pair, args.torque, side=args.side, cells=args.cells,
                    progress=not args.quiet)
    write_lte_outputs(res, args.out, figures=not args.no_figures,
                      title=f"{pair.name} {args.side}", published=published_values(pair.name))
    print(f"{pair.name} {args.side} {args.torque:g} N·m, {len(res.phi1_rad)} phases: TE p-p "
          f"TE0 {res.te0_pp_arcsec:.2f} / LCP {res.te_lcp_pp_arcsec:.2f} / preview "
          f"{res.te_pre_pp_arcsec:.2f} arcsec; compliance LCP "
          f"{res.compliance_lcp_mm_per_n:.3g} / preview {res.compliance_pre_mm_per_n:.3g} "
          f"mm/N; active pairs {res.active_lcp.min()}-{res.active_lcp.max()} -> {args.out}")
    if not res.converged:
        bad = [k for k, s in enumerate(res.status) if s != "converged"]
        print(f"gearcontact lte: warning: LCP not converged at phases {bad}", file=sys.stderr)
        return 1
    return 0
