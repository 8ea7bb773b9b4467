"""``gearcontact lte``: loaded transmission error over one pinion pitch (with the shell
bending of both teeth; ``--rigid``: rigid teeth, the Love half-space alone).

Writes into ``--out`` (created if missing): ``lte.json`` (peak-to-peaks of TE0, TE_LCP
and TE_pre, contact and mesh compliances, active pairs, load shares at P0, mesh
stiffness statistics rigid and, unless ``--rigid``, with bending; ``bending`` records
which tooth model ran; see
:meth:`~gearcontact.ltca.lte.LoadedTE.summary`), ``lte.csv`` (one row per phase: TE0,
TE_LCP, TE_pre, rotations, active pairs, load per pair, mesh stiffness in N·m/rad and
N/mm rigid and with bending) and ``lte.png``; timings go to ``run.json`` only.
"""

from __future__ import annotations

import dataclasses
import time

from ..halfspace.result import SolveStatus
from ..ltca.lte import loaded_te
from ..errors import CheckFailed
from ..report.lte_plot import write_lte_outputs
from ..tca.analysis import analyze_pair
from ..validation import InputRangeError
from .options import (
    add_pair_arguments,
    check_pair_arguments,
    load_pair_for,
    lte_warnings,
    rename_load_error,
    run_timings,
    warn,
)
from .outdir import final_path


def register(sub) -> None:
    p = sub.add_parser("lte", help="loaded transmission error along the mesh phase: "
                                   "TE_LCP, TE_pre, active pairs, compliances",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, torque=True, cells=40, misalignment=True)
    teeth = p.add_mutually_exclusive_group()
    teeth.add_argument("--rigid", action="store_true",
                       help="rigid teeth: the Love half-space compliance alone (default: "
                            "with the shell bending of the pinion and gear teeth)")
    teeth.add_argument("--bending", action="store_true",
                       help="tooth bending in the coupled LCP (the default; kept for "
                            "scripts)")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run, check=check_pair_arguments)


def run(args) -> int:
    pair = load_pair_for(args)
    from ..report.analyze import published_values

    tca, flanks = analyze_pair(pair, side=args.side, phases=args.phases,
                               progress=not args.quiet)
    bending = None
    if not args.rigid:
        from ..ltca.tooth_bending import tooth_bending

        bending = tooth_bending(flanks, pair, side=args.side)
    try:
        # JIT warm-up on three phases (first, P0, last) of the same problem, so that the
        # solve times of the run exclude the compilation of the mesh-LCP kernels
        t0 = time.perf_counter()
        loaded_te(tca, flanks, pair, args.torque, side=args.side, cells=args.cells,
                  stride=len(tca.cycle.phi1_rad), bending=bending, progress=False)
        jit_s = time.perf_counter() - t0
        res = loaded_te(tca, flanks, pair, args.torque, side=args.side, cells=args.cells,
                        bending=bending, stiffness=True, progress=not args.quiet)
    except InputRangeError as exc:
        raise rename_load_error(exc, args.torque, pair, tca) from None
    run_timings(args, tca=tca.timings_s, lte=res.timings_s, jit_warm_up_s=jit_s,
                solve_ms_per_phase=float(res.solve_ms.mean()),
                field_ms_per_phase=float(res.field_ms.mean()))
    write_lte_outputs(res, args.out, figures=not args.no_figures,
                      title=f"{pair.name} {args.side}", published=published_values(pair.name),
                      extra={"assembly": dataclasses.asdict(pair.assembly)})
    print(f"{pair.name} {args.side} {args.torque:g} N·m, {len(res.phi1_rad)} phases"
          f"{', rigid teeth' if args.rigid else ', bending'}: TE p-p "
          f"TE0 {res.te0_pp_arcsec:.2f} / LCP {res.te_lcp_pp_arcsec:.2f} / preview "
          f"{res.te_pre_pp_arcsec:.2f} arcsec; compliance LCP "
          f"{res.compliance_lcp_mm_per_n:.3g} / preview {res.compliance_pre_mm_per_n:.3g} "
          f"mm/N; active pairs {res.active_lcp.min()}-{res.active_lcp.max()} -> "
          f"{final_path(args, args.out)}")
    for line in lte_warnings(res):
        warn("lte", line)
    if not res.converged:
        bad = [k for k, s in enumerate(res.status) if s is not SolveStatus.CONVERGED]
        raise CheckFailed(f"LCP not converged at phases {bad}")   # the files stay
    return 0
