"""``gearcontact export``: the preview datapath for use outside Python.

``gearcontact export c --out DIR`` writes a self-contained C99 library of the preview
datapath (golden fixed point and fp64) with a Makefile and the checker
``gearcontact_check VECTOR_DIR``, which compares it with the files of
``gearcontact vectors`` (:mod:`gearcontact.export.c_library`; docs/export.md).
``gearcontact export fmu --pair PAIR --kind mesh --out DIR`` writes an FMI 3.0 FMU
(co-simulation and model exchange, plain C, a Linux x86-64 binary built at export) of
one gear mesh with the pair's mesh table baked in (:mod:`gearcontact.export.fmu`);
``--kind drivetrain`` the co-simulation FMU of the whole drivetrain twin, the model of
``gearcontact twin`` (rigid teeth, or with ``--bending`` the teeth's bending in series
with the Hertzian law, as ``gearcontact twin --bending``, in either kind;
:mod:`gearcontact.export.fmu_drivetrain`). A cylindrical pair (``kind =
"cylindrical"``) gets both kinds with its twin's line law (rigid teeth or ``--bending``;
:mod:`gearcontact.export.fmu_cylindrical`). ``--hertz-form exact`` (bevel and hypoid
pairs) gives either kind the twin's exact Hertz form as its fp64 law
(:mod:`gearcontact.twin.exact_hertz`, its table and cubic in C; the FMU's backend fp64
only), as ``gearcontact twin --hertz-form exact``; ``export c --hertz-form exact`` adds
that law to the C library.
``gearcontact export flanks --pair PAIR --out DIR`` writes the flanks of both members
(and the root fillets of members whose cutter is known) as STEP (B-spline surfaces) and
as CMM point grids with normals (:mod:`gearcontact.export.flanks`).
"""

from __future__ import annotations

from ..preview.hertz.formats import DEFAULT_HERTZ_FORM, HERTZ_FORMS
from ..validation import InputRangeError, check_positive
from .options import MAX_PHASES, check_machine_settings, check_pair_arguments, load_pair_for
from .outdir import add_out_argument, final_path


def register(sub) -> None:
    p = sub.add_parser("export", help="export the preview datapath (C99 library), a gear "
                                      "mesh (FMI 3.0 FMU) or the flanks (STEP, CMM grids)",
                       description=__doc__.split("\n\n")[1])
    cmds = p.add_subparsers(dest="export_command", metavar="ACTION", required=True)
    c = cmds.add_parser("c", help="C99 library of the datapath (golden fixed point and "
                                  "fp64) with a Makefile and the vector checker")
    add_out_argument(c)
    c.add_argument("--hertz-form", default=DEFAULT_HERTZ_FORM, choices=HERTZ_FORMS,
                   help="hamrock-brewe (default: the library as ever) or exact: the "
                        "library adds the twin's exact Hertz law (gearcontact twin "
                        "--hertz-form exact), gc_hertz_exact_table_fp64")
    # make's build/ beside the export is the user's, kept from run to run (never
    # foreign, never removed): a new export into a built directory replaces the sources
    c.set_defaults(func=run_c, resume_entries=("build",))
    f = cmds.add_parser("fmu", help="FMI 3.0 FMU in C of one gear mesh (co-simulation and "
                                    "model exchange) or of the drivetrain twin "
                                    "(co-simulation)")
    f.add_argument("--pair", default="s0003", help="preset name or TOML file, bevel/hypoid or "
                                                   "cylindrical (default s0003)")
    f.add_argument("--kind", default="mesh",
                   help="what the FMU models: mesh (default) or drivetrain (the twin)")
    add_out_argument(f)
    f.add_argument("--side", default=None, choices=("drive", "coast"),
                   help="loaded flank (default: the pair's design_side)")
    f.add_argument("--phases", type=int, default=61,
                   help=f"TCA phases per pinion pitch baked into the table, 3 to "
                        f"{MAX_PHASES} (default 61)")
    f.add_argument("--torque", type=float, default=64.5,
                   help="gear torque in N·m sizing the mesh table (default 64.5); "
                        "drivetrain: also the start value of its torque_nm")
    f.add_argument("--curvatures", default=None, choices=("stencil", "exact"),
                   help="drivetrain: the preview's curvature source, as gearcontact twin "
                        "(default stencil); the mesh FMU runs exact (the TCA's curvatures); "
                        "a cylindrical pair: stencil only (its line chain)")
    f.add_argument("--bending", action="store_true",
                   help="tooth bending of both members in series with the contact law "
                        "(Hertzian, or a cylindrical pair's line law), as gearcontact twin "
                        "--bending (default rigid teeth)")
    f.add_argument("--drivetrain", default=None,
                   help="drivetrain: TOML file with a [drivetrain] table, as gearcontact "
                        "twin (default: the pair's estimates)")
    f.add_argument("--hertz-form", default=DEFAULT_HERTZ_FORM, choices=HERTZ_FORMS,
                   help="the contact law's fp64 Hertz form, as gearcontact twin: "
                        "hamrock-brewe (default) or exact (the twin's exact Hertz table; "
                        "the FMU's backend fp64 only; bevel and hypoid pairs)")
    f.set_defaults(func=run_fmu, check=check_fmu)
    g = cmds.add_parser("flanks", help="the flanks (and fillets) of both members as STEP "
                                       "B-spline surfaces and CMM point grids with normals")
    g.add_argument("--pair", default="s0003", help="preset name or TOML file, bevel/hypoid "
                                                   "or cylindrical (default s0003)")
    add_out_argument(g)
    g.add_argument("--grid", default="5x9", metavar="ROWSxCOLS",
                   help="CSV grid per flank: ROWS lines along the face width (root to tip) x "
                        "COLS points on each (toe to heel), each 2 to 201 (default 5x9, the "
                        "Gleason grid)")
    g.set_defaults(func=run_flanks, check=check_flanks)


def run_c(args) -> int:
    from ..export.c_library import export_c_library
    for path in export_c_library(args.out, hertz_form=args.hertz_form):
        print(final_path(args, path))
    return 0


def check_fmu(args) -> None:
    """Cheap checks before the TCA: the kind, the phase count, the torque, the
    drivetrain file, the pair (bevel/hypoid or cylindrical)."""
    from ..export.fmu import check_fmu_kind
    from ..export.fmu_cylindrical import check_cylindrical_fmu
    from ..geometry.pair import BEVEL, CYLINDRICAL
    from ..tca.line_contact import check_loadable
    from ..twin.params import check_drivetrain_file
    check_fmu_kind(args.kind)
    check_positive("--torque", args.torque)
    if args.kind == "mesh" and args.curvatures not in (None, "exact"):
        raise InputRangeError("--curvatures", args.curvatures, "exact with --kind mesh "
                              "(stencil: --kind drivetrain)")
    if args.drivetrain is not None:
        if args.kind != "drivetrain":
            raise InputRangeError("--drivetrain", args.drivetrain, "only with --kind "
                                  "drivetrain")
        check_drivetrain_file(args.drivetrain)
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))
    if args.gear_pair.kind == CYLINDRICAL:
        check_cylindrical_fmu(curvatures=args.curvatures, hertz_form=args.hertz_form)
        return
    check_loadable(args.gear_pair, args.side)


def run_fmu(args) -> int:
    from ..geometry.pair import CYLINDRICAL
    if args.gear_pair.kind == CYLINDRICAL:
        return _run_cylindrical_fmu(args)
    pair = load_pair_for(args)
    if args.kind == "drivetrain":
        from ..export.fmu_drivetrain import export_drivetrain_fmu
        from ..twin.params import load_drivetrain
        fmu = export_drivetrain_fmu(pair, args.out, pair_name=args.gear_pair.name,
                                    side=args.side, phases=args.phases,
                                    torque_nm=args.torque,
                                    drivetrain=load_drivetrain(args.drivetrain, pair),
                                    curvatures=args.curvatures or "stencil",
                                    bending=args.bending,
                                    flanks=args.prepared_pair.flank_set(),
                                    hertz_form=args.hertz_form)
        print(final_path(args, fmu.fmu_path))
        return 0
    from ..export.fmu import export_mesh_fmu
    fmu = export_mesh_fmu(pair, args.out, pair_name=args.gear_pair.name, side=args.side,
                          phases=args.phases, torque_nm=args.torque, bending=args.bending,
                          flanks=args.prepared_pair.flank_set(), hertz_form=args.hertz_form)
    for path in (fmu.fmu_path, fmu.table_path):
        print(final_path(args, path))
    return 0


def _run_cylindrical_fmu(args) -> int:
    from ..twin.params import load_drivetrain
    pair = args.gear_pair
    if args.kind == "drivetrain":
        from ..export.fmu_drivetrain import export_drivetrain_fmu
        fmu = export_drivetrain_fmu(pair, args.out, pair_name=pair.name, side=args.side,
                                    phases=args.phases, torque_nm=args.torque,
                                    drivetrain=load_drivetrain(args.drivetrain, pair),
                                    bending=args.bending)
        print(final_path(args, fmu.fmu_path))
        return 0
    from ..export.fmu_cylindrical import export_cylindrical_mesh_fmu
    fmu = export_cylindrical_mesh_fmu(pair, args.out, pair_name=pair.name, side=args.side,
                                      phases=args.phases, torque_nm=args.torque,
                                      bending=args.bending)
    for path in (fmu.fmu_path, fmu.table_path):
        print(final_path(args, path))
    return 0


def check_flanks(args) -> None:
    """Cheap checks before the flanks are built: the grid, the pair (either kind)."""
    from ..export.flanks import parse_grid
    from ..geometry.pair import BEVEL, CYLINDRICAL, load_pair
    args.grid_size = parse_grid(args.grid)
    try:
        args.gear_pair = load_pair(args.pair, kinds=(BEVEL, CYLINDRICAL))
    except InputRangeError as exc:
        if exc.field != "pair":     # a field inside the file: named as it is
            raise
        raise InputRangeError("--pair", exc.value, exc.allowed) from None
    check_machine_settings(args)      # typed machine settings against the blank tables


def run_flanks(args) -> int:
    from ..export.flanks import export_flanks
    from ..geometry.pair import CYLINDRICAL
    cylindrical = args.gear_pair.kind == CYLINDRICAL
    pair = args.gear_pair if cylindrical else load_pair_for(args, mesh_follows=False)
    done = export_flanks(pair, args.out, pair_name=args.gear_pair.name, grid=args.grid_size,
                         flanks=None if cylindrical else args.prepared_pair.flank_set())
    for path in (*done.step_paths, *done.csv_paths, done.summary_path):
        print(final_path(args, path))
    print(f"STEP faces within {done.fit_error_mm * 1e3:.3g} um of the flanks (check grid)")
    return 0
