"""``gearcontact lte``: loaded transmission error over one pinion pitch (with the shell
bending of both teeth; ``--rigid``: rigid teeth, the Love half-space alone).

Writes into ``--out`` (created if missing): ``lte.json`` (peak-to-peaks of TE0, TE_LCP
and TE_pre, contact and mesh compliances, active pairs, load shares at P0, mesh
stiffness statistics rigid and, unless ``--rigid``, with bending; ``bending`` records
which tooth model ran; see
:meth:`~gearcontact.ltca.lte.LoadedTE.summary`), ``lte.csv`` (one row per phase: TE0,
TE_LCP, TE_pre, rotations, active pairs, load per pair, mesh stiffness in N·m/rad and
N/mm rigid and with bending) and ``lte.png``; timings go to ``run.json`` only.

A cylindrical pair (``kind = "cylindrical"``) gets the loaded TE over its mesh cycle
with the shell bending of both teeth (and the rigid-tooth one beside it; ``--rigid``:
rigid teeth only), ``--cells`` cells along the face, and the Harris map (loaded TE p-p
at the ISO line loads 50-400 N/mm for 0 to 2 times the pinion's tip relief, same tooth
model):
``lte.json``, ``lte.csv``, ``line_load.csv``, ``harris_map.csv``, ``lte.png``,
``harris_map.png`` (:mod:`gearcontact.report.cylindrical_lte`; docs/cylindrical.md
sec. 7).
"""

from __future__ import annotations

import dataclasses
import time

from ..geometry.pair import BEVEL, CYLINDRICAL
from ..halfspace.result import SolveStatus
from ..ltca.cylindrical_lte import (STRIP_TOO_NARROW, cylindrical_loaded_te_models, harris_map,
                                    harris_tip_reliefs_um, harris_torques_nm)
from ..ltca.lte import loaded_te
from ..errors import CheckFailed
from ..report.analyze_cylindrical import end_loaded_note
from ..report.cylindrical_lte import write_cylindrical_lte_outputs
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
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """Every option and the pair file, before any work."""
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))


#: ``--side`` of a cylindrical pair -> the flank facing in mesh (as ``gearcontact tca``).
CYLINDRICAL_FACING = {"drive": "cw", "coast": "ccw"}


def run_cylindrical(args) -> int:
    pair = args.gear_pair
    facing = CYLINDRICAL_FACING[args.side]
    bending = not args.rigid
    t0 = time.process_time()
    res, rigid = cylindrical_loaded_te_models(pair, args.torque, bending=bending,
                                              facing=facing, phases=args.phases,
                                              cells_along=args.cells)
    t1 = time.process_time()
    harris = harris_map(pair, harris_torques_nm(pair), harris_tip_reliefs_um(pair),
                        facing=facing, phases=args.phases, cells_along=args.cells,
                        bending=bending)
    run_timings(args, lte_cpu_s=t1 - t0, lcp_cpu_s=res.solve_time_s,
                harris_map_cpu_s=time.process_time() - t1)
    write_cylindrical_lte_outputs(res, harris, pair, args.out, side=args.side,
                                  figures=not args.no_figures, rigid=rigid)
    print(f"{pair.name} {args.side} ({facing} flanks) {args.torque:g} N·m, "
          f"{len(res.phi1_rad)} phases, {'bending' if bending else 'rigid teeth'}: TE p-p TE0 "
          f"{res.te0_arcsec.max() - res.te0_arcsec.min():.2f} / loaded "
          f"{res.lte_pp_arcsec:.2f} arcsec, p_max {res.max_pressure_mpa.max():.0f} MPa, "
          f"mesh stiffness {res.mean_stiffness_n_per_mm_um:.1f} N/(mm·µm) mean; Harris map "
          f"{len(harris.tip_reliefs_um)} x {len(harris.torques_nm)} -> "
          f"{final_path(args, args.out)}")
    if res.peak_at_edge[int(res.max_pressure_mpa.argmax())]:
        warn("lte", end_loaded_note({"lcp_max_pressure_mpa": float(res.max_pressure_mpa.max()),
                                     "lcp_peak_at_edge": True, "end_loaded_lines": None}))
    if res.edge_touch or harris.edge_touch:
        warn("lte", STRIP_TOO_NARROW)
    if not (res.converged and harris.converged and (rigid is None or rigid.converged)):
        raise CheckFailed("LCP not converged")   # the files stay
    return 0


def run(args) -> int:
    if args.gear_pair.kind == CYLINDRICAL:
        return run_cylindrical(args)
    pair = load_pair_for(args)
    from ..report.analyze import published_values

    tca, flanks = analyze_pair(pair, side=args.side, phases=args.phases,
                               flanks=args.prepared_pair.flank_set(), progress=not args.quiet)
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
