"""``gearcontact ltca``: loaded contact of the reference tooth pair at P0 under a torque.

Writes into ``--out`` (created if missing): ``ltca.json`` (load, LCP mean / p90 / peak
pressure, approach, mesh rotation, contact cells, preview p_max, solver and
the rest of :meth:`~gearcontact.ltca.pair_ltca.PairLoadCase.summary`),
``pressure_map.csv`` (``s_mm,t_mm,pressure_mpa`` over the principal-frame field),
``pressure_map.png`` (pressure map with the Hertzian preview ellipse overlaid) and, with
``--export-problem``, the solved LCP as ``ltca_problem.npz`` with
``ltca_problem.README.md`` (:mod:`gearcontact.ltca.problem_export`). With
``--multi-tooth`` also the coupled LCP of all engaged pairs at P0, rigid and with the
shell bending of both teeth (:mod:`gearcontact.ltca.multitooth`): ``multitooth.json``
(load shares, rotations, CP_max, cell peak, preview p_max), ``multitooth.csv`` and the
full-wheel figure ``multitooth.png`` (:mod:`gearcontact.report.multitooth`). The
solve times (``solve_ms``, ``multi_tooth_solve_ms``, ``multi_tooth_solve_rigid_ms``) go
to ``run.json`` only, so identical runs write identical result files. Edge contact is
reported on stderr; ``ltca.json`` names the flank edges the loaded patch reaches
(``edge_contact_edges``, its cells and ``edge_pressure_ratio_p90``: the largest pressure
there over p90, :func:`~gearcontact.tca.edges.loaded_patch_edges`) and whether the
unloaded contact at P0 is itself an edge contact (``tca_edge_contact``, the edge's name).

A cylindrical pair (``kind = "cylindrical"``) gets the loaded contact at the pitch-point
phase of its loaded TE (the same solve as ``gearcontact lte``, with the shell bending of
both teeth; ``--rigid``: rigid teeth), every pair in contact, ``--cells`` cells along the
face (default 40, as ``lte``): ``ltca.json``, ``line_load.csv``, ``pressure_map.csv``,
``pressure_map.png`` (:mod:`gearcontact.report.cylindrical_ltca`; docs/cylindrical.md
sec. 12). ``--multi-tooth`` (all pairs are in already), ``--multi-tooth-cells``,
``--solver``, ``--export-problem`` and ``--misalignment`` are refused for it.
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from pathlib import Path

from ..geometry.pair import BEVEL, CYLINDRICAL
from ..halfspace.lcp import SOLVERS, LcpConvergenceError, warm_up
from ..halfspace.patch import ContactAtEdgeWarning
from ..ltca.pair_ltca import single_pair_ltca
from ..report.ltca import write_ltca_outputs
from ..tca.analysis import analyze_pair
from ..tca.edges import loaded_patch_edges
from ..errors import CheckFailed
from ..validation import InputRangeError
from .options import (
    MAX_CELLS,
    add_pair_arguments,
    check_count,
    case_warnings,
    check_pair_arguments,
    load_pair_for,
    rename_load_error,
    run_timings,
    warn,
)
from .outdir import final_path


def register(sub) -> None:
    p = sub.add_parser("ltca", help="loaded contact of one tooth pair at P0: pressure map, "
                                    "statistics, approach, preview beside it",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, torque=True, misalignment=True)
    p.add_argument("--cells", type=int, default=None,
                   help=f"cells per side of the tangent-plane gap field, 16 to {MAX_CELLS} "
                        f"(default {CELLS}; a cylindrical pair: cells along the face, default "
                        f"{CYLINDRICAL_CELLS} as gearcontact lte)")
    p.add_argument("--rigid", action="store_true",
                   help="a cylindrical pair: rigid teeth, the Love half-space alone (default: "
                        "with the shell bending of both teeth, as gearcontact lte)")
    p.add_argument("--solver", default=None, choices=SOLVERS,
                   help="LCP solver (default pk_cg; not for a cylindrical pair)")
    p.add_argument("--export-problem", action="store_true",
                   help="also write the solved LCP (gap, on-flank mask, grid, load, E*, "
                        "solution) as ltca_problem.npz with ltca_problem.README.md")
    p.add_argument("--multi-tooth", action="store_true",
                   help="also solve all engaged pairs together at P0, rigid and with tooth "
                        "bending: multitooth.json/.csv/.png")
    p.add_argument("--multi-tooth-cells", type=int, default=None,
                   help=f"with --multi-tooth: cells per side of each pair's field in the "
                        f"multi-tooth solve, 16 to {MAX_CELLS} (default "
                        f"{MULTI_TOOTH_CELLS}, as gearcontact lte)")
    # as every computing command (analyze, reproduce, tca, lte, sweep, twin): a script
    # passes --quiet to any of them
    p.add_argument("--quiet", action="store_true",
                   help="no progress bars (this command shows none; its result line, "
                        "notes and warnings are printed as without it)")
    p.set_defaults(func=run, check=_check)


#: Upper limit of ``--cells`` for the dense solvers (nnls, active_set): their influence
#: matrix grows as cells^4. Measured on s0003 at 80 cells: 0.46 GB peak memory,
#: active_set 21 s and nnls 53 s of solve (load average ~10); 160 cells would need ~16x.
MAX_DENSE_CELLS = 80


#: Default ``--multi-tooth-cells``.
MULTI_TOOTH_CELLS = 40
#: Default ``--cells`` of a bevel pair (per side of the gap field) and of a cylindrical
#: pair (along the face, as ``gearcontact lte``).
CELLS, CYLINDRICAL_CELLS = 80, 40

#: Options a cylindrical pair refuses -> why (``args`` attribute, option, reason).
NOT_CYLINDRICAL = (
    ("multi_tooth", "--multi-tooth", "every pair in contact is in the cylindrical loaded "
                                     "contact already"),
    ("multi_tooth_cells", "--multi-tooth-cells", "no multi-tooth solve of a cylindrical pair;"
                                                 " --cells sets its cells along the face"),
    ("solver", "--solver", "the cylindrical loaded contact is the mesh LCP of the loaded TE, "
                           "its one solver"),
    ("export_problem", "--export-problem", "the export is of the single-pair LCP of a "
                                           "bevel pair"),
)


def _check(args) -> None:
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))
    if args.gear_pair.kind == CYLINDRICAL:
        for attr, option, why in NOT_CYLINDRICAL:
            given = getattr(args, attr)
            if given not in (None, False):
                raise InputRangeError(option, given, f"not given for a cylindrical pair ({why})")
        if args.cells is None:
            args.cells = CYLINDRICAL_CELLS
        return
    if args.rigid:
        raise InputRangeError("--rigid", True, "given only for a cylindrical pair (a bevel "
                                               "pair's single-pair contact is of rigid teeth; "
                                               "--multi-tooth adds tooth bending)")
    if args.cells is None:
        args.cells = CELLS
    if args.solver is None:
        args.solver = "pk_cg"
    if args.multi_tooth_cells is not None and not args.multi_tooth:
        raise InputRangeError("--multi-tooth-cells", args.multi_tooth_cells,
                              "given only with --multi-tooth (without it the option has "
                              "no effect)")
    if args.multi_tooth_cells is None:
        args.multi_tooth_cells = MULTI_TOOTH_CELLS
    check_count("--multi-tooth-cells", args.multi_tooth_cells, 16, MAX_CELLS, note=" per side")
    if args.solver != "pk_cg":
        check_count("--cells", args.cells, 16, MAX_DENSE_CELLS,
                    note=f" per side with the dense --solver {args.solver}")


def run_cylindrical(args) -> int:
    """The loaded contact of a cylindrical pair at the pitch-point phase."""
    from ..ltca.cylindrical_lte import STRIP_TOO_NARROW
    from ..ltca.cylindrical_ltca import cylindrical_ltca
    from ..report.cylindrical_ltca import write_cylindrical_ltca_outputs
    from ..tca.cylindrical_cycle import FACING_OF_SIDE

    pair = args.gear_pair
    t0 = time.process_time()
    c = cylindrical_ltca(pair, args.torque, facing=FACING_OF_SIDE[args.side],
                         phases=args.phases, cells_along=args.cells, bending=not args.rigid)
    run_timings(args, ltca_cpu_s=time.process_time() - t0, lcp_cpu_s=c.lte.solve_time_s)
    doc = write_cylindrical_ltca_outputs(c, pair, args.out, side=args.side,
                                         figures=not args.no_figures)
    shares = " / ".join(f"{p['load_share']:.3f}" for p in doc["pairs"])
    print(f"{pair.name} {args.side} {args.torque:g} N·m at the pitch point ({doc['teeth']}): "
          f"F_n = {doc['normal_load_n']:.0f} N on {doc['pairs_loaded']} pairs (shares "
          f"{shares}), p_max {doc['p_max_mpa']:.0f} MPa"
          f"{' on an edge' if doc['p_max_on_edge'] else ''}, rotation "
          f"{doc['rotation_arcsec']:.2f} arcsec, approach {1e3 * doc['approach_mm']:.2f} µm "
          f"-> {final_path(args, args.out)}")
    if doc["p_max_on_edge"]:
        warn("ltca", f"p_max {doc['p_max_mpa']:.0f} MPa lies on a sharp edge (a loaded line "
                     "end or a tip edge): the half-space's singular pressure there, which grows"
                     " with --cells (docs/cylindrical.md sec. 7)")
    if c.lte.edge_touch:
        warn("ltca", STRIP_TOO_NARROW)
    if not c.lte.converged:
        raise CheckFailed("LCP not converged")   # the files stay
    return 0


def run(args) -> int:
    if getattr(args, "gear_pair", None) is None:
        _check(args)
    if args.gear_pair.kind == CYLINDRICAL:
        return run_cylindrical(args)
    pair = load_pair_for(args)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    tca, flanks = analyze_pair(pair, side=args.side, phases=args.phases,
                               flanks=args.prepared_pair.flank_set())
    jit_s = warm_up(args.solver)   # solve_ms below then excludes the JIT compilation
    t1 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ContactAtEdgeWarning)  # case_warnings below
            case = single_pair_ltca(tca, flanks, pair, args.torque, side=args.side,
                                    cells=args.cells, solver=args.solver)
    except InputRangeError as exc:
        raise rename_load_error(exc, args.torque, pair, tca) from None
    run_timings(args, tca_s=t1 - t0 - jit_s, jit_warm_up_s=jit_s,
                ltca_s=time.perf_counter() - t1,
                solve_ms=case.patch.lcp.solve_time_ms)
    # what edge_contact means: the flank edges the loaded patch reaches, and how much
    # pressure it carries there (tca.edges.loaded_patch_edges)
    side = args.side or pair.design_side
    reach = loaded_patch_edges(flanks.flank("pinion", side), flanks.flank("gear", side),
                               pair.kinematics(), tca.mean_point, case)
    write_ltca_outputs(
        case, out, figures=not args.no_figures, title=f"{pair.name} {args.side}",
        extra={**reach.as_dict(), "tca_edge_contact": tca.mean_point.edge_contact,
               "assembly": dataclasses.asdict(pair.assembly)},
        problem_materials=((pair.pinion_material, pair.gear_material)
                           if args.export_problem else None),
        problem_title=f"{pair.name} {args.side}, {args.torque:g} N·m at P0")
    multi = _multi_tooth(args, tca, flanks, pair, out) if args.multi_tooth else None
    print(f"{pair.name} {args.side} {args.torque:g} N·m: W = {case.load_n:.0f} N, LCP mean "
          f"{case.patch.p_mean_mpa:.0f} / p90 {case.patch.p90_mpa:.0f} / peak "
          f"{case.patch.p_peak_mpa:.0f} MPa, preview p_max {case.preview.p_max_mpa:.0f} MPa, "
          f"mesh rotation {case.mesh_rotation_arcsec:.1f} arcsec "
          f"({case.patch.lcp.solver}, {case.patch.lcp.solve_time_ms:.0f} ms) -> "
          f"{final_path(args, out)}")
    for line in case_warnings(case):
        warn("ltca", line)
    if reach.edges:
        warn("ltca", f"the loaded patch reaches the {', '.join(reach.edges)} "
                     f"({reach.boundary_cells} cells; pressure there up to "
                     f"{reach.boundary_pressure_ratio:.2f} x p90)")
    if tca.mean_point.edge_contact:
        warn("ltca", f"unloaded contact at P0 is edge contact ({tca.mean_point.edge_contact} "
                     "touching the other flank)")
    # the files stay (run.json records exit 4) for inspection of the failed solve
    if not case.patch.converged:
        raise LcpConvergenceError(case.patch.lcp)
    if multi is not None and not multi.converged:
        raise CheckFailed(f"multi-tooth LCP not converged (rigid {multi.status_rigid}, "
                          f"bending {multi.status})")
    return 0


def _multi_tooth(args, tca, flanks, pair, out):
    """The multi-tooth solve at P0 and its files; returns the case."""
    from ..ltca.mesh_lcp import warm_up_mesh_lcp
    from ..ltca.multitooth import multi_tooth_ltca
    from ..ltca.tooth_bending import tooth_bending
    from ..report.analyze import published_values
    from ..report.multitooth import write_multitooth_outputs

    t0 = time.perf_counter()
    bending = tooth_bending(flanks, pair, side=args.side)
    t1 = time.perf_counter()
    jit_s = warm_up_mesh_lcp()
    t2 = time.perf_counter()
    try:
        mt = multi_tooth_ltca(tca, flanks, pair, args.torque, side=args.side,
                              bending=bending, cells=args.multi_tooth_cells)
    except InputRangeError as exc:
        raise rename_load_error(exc, args.torque, pair, tca) from None
    run_timings(args, bending_build_s=t1 - t0, multi_tooth_jit_warm_up_s=jit_s,
                multi_tooth_s=time.perf_counter() - t2, multi_tooth_solve_ms=mt.solve_ms,
                multi_tooth_solve_rigid_ms=mt.solve_rigid_ms)
    write_multitooth_outputs(mt, out, figures=not args.no_figures,
                             title=f"{pair.name} {args.side}",
                             published=published_values(pair.name))
    shares = " / ".join(f"{s:.1f}" for s in mt.load_share_pct)
    print(f"multi-tooth at P0: {len(mt.pairs)} pairs, shares {shares} % with bending; "
          f"rotation {mt.rotation_rigid_arcsec:.1f} rigid -> {mt.rotation_arcsec:.1f} arcsec; "
          f"CP_max {mt.cp_max_mpa:.0f} MPa (cell peak {mt.p_peak_cell_mpa:.0f}, preview "
          f"{mt.preview_p_max_mpa:.0f})")
    return mt
