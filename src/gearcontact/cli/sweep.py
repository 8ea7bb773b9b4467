"""``gearcontact sweep``: the contact analysis over a grid of assembly errors, design
variants and torques, on Dask distributed (docs/sweeps.md).

Writes into ``--out`` (created if missing): ``sweep.zarr``, one xarray Dataset with the
dimensions of the ``--vary`` keys (``E_mm``, ``P_mm``, ``G_mm``, ``alpha_deg``, design
keys with ``_`` for ``.``) and ``torque_nm``, filled as grid points finish (a pair cut
from machine settings varies the keys of its ``[machine.*]`` / ``[blade.*]`` tables,
:mod:`gearcontact.sweep.settings_keys`). A rerun of the same command computes only
the cells still pending (resumable after a crash or Ctrl-C); a rerun with another grid
or other settings into the same directory is refused.

A cylindrical pair (``kind = "cylindrical"``) sweeps the keys of its
``[modifications.pinion]``, ``[modifications.gear]`` and ``[assembly]`` tables by their
dotted names; a cell holds TE0 and (``--compute tca,ltca``) the loaded TE peak-to-peak,
peak pressure and mean mesh stiffness at its torque (:mod:`gearcontact.sweep.cylindrical`).
"""

from __future__ import annotations

import re
from pathlib import Path

from ..geometry.pair import BEVEL, CYLINDRICAL
from ..sweep.design import check_variants
from ..sweep.grid import SweepGrid, parse_vary
from ..sweep.run import sweep_settings
from ..sweep.settings_keys import SETTING_KEYS
from ..sweep.store import CREATING_NAME, STORE_NAME, check_store
from ..validation import InputRangeError
from .options import (
    MAX_CELLS,
    add_pair_arguments,
    check_count,
    check_cylindrical_torque,
    check_pair_arguments,
    check_torque,
    load_pair_for,
    run_timings,
    warn,
)
from .outdir import final_path

#: Upper limit of ``--workers`` (local worker processes).
MAX_WORKERS = 256
#: What ``--compute`` accepts.
COMPUTE = ("tca", "tca,ltca")
#: LCP solver of the LTCA cells.
SOLVER = "pk_cg"
#: Default ``--cells``: per side of the LTCA's gap field (bevel), along the face of the
#: loaded TE (cylindrical, as ``gearcontact lte``).
DEFAULT_CELLS = {BEVEL: 80, CYLINDRICAL: 40}
_ADDRESS = re.compile(r"^(tcp|tls)://[^\s:/]+:\d{1,5}$")


def register(sub) -> None:
    p = sub.add_parser("sweep", help="TCA / LTCA over a grid of assembly errors and "
                                     "torques on Dask distributed (zarr, resumable)",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, misalignment=True)
    p.add_argument("--cells", type=int, default=None,
                   help=f"LTCA cells per side of the gap field of a bevel pair (default "
                        f"{DEFAULT_CELLS[BEVEL]}); of a cylindrical pair, cells along the "
                        f"face of its loaded TE (default {DEFAULT_CELLS[CYLINDRICAL]}); 16 "
                        f"to {MAX_CELLS}")
    p.add_argument("--vary", action="append", default=[], metavar="KEY=START:STOP:STEPS",
                   help="KEY over numpy.linspace(START, STOP, STEPS), ends included; KEY "
                        "an assembly error E, P, G (mm), alpha (deg) with the signs of "
                        "--misalignment, or a design key of the pair's TOML: "
                        "easeoff.drive.<coefficient>, easeoff.coast.<coefficient> "
                        "('ease-off.' also accepted), cutter.<key> (e.g. "
                        "easeoff.drive.lengthwise_crowning_um_per_mm2=0.08:0.16:5, "
                        "cutter.radius_mm=44:46:5; flanks rebuilt once per variant); "
                        "a pair cut from machine settings: "
                        "machine.<member>.<flank>.<key>, blade.<member>.<flank>.<key> "
                        "as its tables spell them (e.g. "
                        "machine.pinion.drive.tilt_deg=19:21:5; each variant read and "
                        "cut as the pair file with the values edited in) instead of the "
                        "[easeoff.*] / [cutter] keys; "
                        "a cylindrical pair: modifications.pinion.<key>, "
                        "modifications.gear.<key>, assembly.<key> (e.g. "
                        "modifications.pinion.tip_relief_um=0:20:5, "
                        "assembly.axis_inclination_um=-20:20:5); "
                        "repeat for more dimensions")
    p.add_argument("--torques", type=float, nargs="+", default=[64.5], metavar="T",
                   help="gear torques in N·m (default 64.5; used by ltca)")
    p.add_argument("--compute", default="tca", choices=COMPUTE, metavar="tca|tca,ltca",
                   help="per cell: unloaded TCA, or TCA and per torque the LTCA at P0 "
                        "and the loaded TE p-p (default tca)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", default=None, metavar="tcp://HOST:PORT",
                       help="address of a running Dask scheduler (default: a local "
                            "cluster)")
    where.add_argument("--workers", type=int, default=None,
                       help=f"worker processes of the local cluster, 1 to {MAX_WORKERS} "
                            "(default: the CPU count); 0 computes in this process "
                            "without Dask")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run, check=check, staged_output=False,
                   resume_entries=(STORE_NAME, CREATING_NAME))


def check(args) -> None:
    """Every option and the pair file, before any work; the optional tools."""
    import importlib.util

    missing = [m for m in ("distributed", "xarray", "zarr") if importlib.util.find_spec(m) is None]
    if missing:     # a missing optional tool is bad input (exit 2), said as such
        raise InputRangeError("gearcontact sweep", f"without {', '.join(missing)}",
                              "installed with the 'sweep' extra: pip install "
                              "'gearcontact[sweep]'")
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))
    kind = args.gear_pair.kind
    if args.cells is None:
        args.cells = DEFAULT_CELLS[kind]
    args.grid = SweepGrid(tuple(parse_vary(v, kind=kind, pair=args.gear_pair)
                                for v in args.vary),
                          tuple(args.torques))
    check_variants(args.gear_pair, args.grid)
    for t in args.torques:
        if kind == BEVEL:
            check_torque("--torques (N·m)", t, args.gear_pair)
        else:
            check_cylindrical_torque("--torques (N·m)", t, args.gear_pair)
    if args.workers is not None:
        check_count("--workers", args.workers, 0, MAX_WORKERS)
    if args.scheduler is not None and not _ADDRESS.match(args.scheduler):
        raise InputRangeError("--scheduler", args.scheduler,
                              "a scheduler address tcp://HOST:PORT (or tls://HOST:PORT)")
    # a store of another sweep in --out: refused before the run touches the directory
    compute = tuple(args.compute.split(","))
    check_store(Path(args.out) / STORE_NAME, args.grid, compute, sweep_settings(
        args.gear_pair, side=args.side, compute=compute, phases=args.phases,
        cells=args.cells, solver=SOLVER))
    # last, as it may wait for Dask's connect timeout: an unreachable scheduler is
    # refused before the output directory is touched (no run.json, no lock left)
    args.client = _connect(args.scheduler) if args.scheduler is not None else None


def _connect(address: str):
    """A client of the scheduler at ``address``, connected before the store is touched;
    an unreachable scheduler is bad input naming ``--scheduler`` (exit 2)."""
    from distributed import Client

    try:
        return Client(address)
    except OSError as exc:     # refused, unknown host, or Dask's connect timeout
        raise InputRangeError("--scheduler", address, f"the address of a running Dask "
                              f"scheduler (connecting failed: {exc})") from None


def run(args) -> int:
    from ..sweep.run import run_sweep

    if getattr(args, "grid", None) is None:
        check(args)
    # a pair file without an ease-off table of the side: the synthesized one (said on
    # stdout, as every pair command does), the base of every grid point and variant
    # (a cylindrical pair as loaded: it has no ease-off)
    cylindrical = args.gear_pair.kind == CYLINDRICAL
    pair = args.gear_pair if cylindrical else load_pair_for(args)
    grid = args.grid
    # setting keys: every variant is read and cut on its own, the nominal flanks unused
    nominal = not cylindrical and not any(v.key in SETTING_KEYS for v in grid.vary)
    client = args.client
    try:
        report = run_sweep(pair, grid, out=args.out, side=args.side,
                           compute=tuple(args.compute.split(",")), phases=args.phases,
                           cells=args.cells, solver=SOLVER, workers=args.workers,
                           client=client,
                           flanks=args.prepared_pair.flank_set() if nominal else None,
                           settings_check=None if cylindrical
                           else args.prepared_pair.settings_check,
                           progress=not args.quiet)
    finally:
        if client is not None:
            client.close()
    run_timings(args, sweep_s=report.wall_s, cells_computed=report.computed)
    if not args.no_figures:      # redrawn on every run
        from ..sweep.plots import plot_design, plot_maps

        title = f"{pair.name} {args.side}"
        if len(grid.vary) >= 2 and pair.kind == BEVEL:     # the V/H chart of E, P
            plot_maps(report.store, args.out / "sweep_maps.png", title=title)
        if any(v.design for v in grid.vary):
            plot_design(report.store, args.out / "sweep_design.png", title=title)
    print(f"{pair.name} {args.side}: {grid.cells} cells ({' x '.join(map(str, grid.shape))}"
          f" over {', '.join(grid.dims)}): {report.computed} computed, {report.skipped} "
          f"already finished, {report.failed} failed -> {final_path(args, report.store)}")
    for e in report.errors[:5]:
        warn("sweep", f"failed cells: {e}")
    return 0
