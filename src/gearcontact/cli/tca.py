"""``gearcontact tca``: unloaded tooth contact analysis of a pair.

Writes into ``--out`` (created if missing): ``tca.json`` (summary), ``te0.csv``,
``contact_path.csv``, ``gap_stencil.csv`` (49-sample hardware stencil),
``gap_field.csv`` (80 x 80 host field), ``phase_table.json``, ``phase_table.bin`` and
the figures ``te0.png``, ``contact_pattern.png`` and ``flanks_in_mesh.png``. Per phase
``tca.json`` says whether the contact is flank on flank or an edge touching the other
flank (``phase_contact``, :mod:`gearcontact.tca.edge_contact`).

A cylindrical pair (``kind = "cylindrical"``) gets the mesh-cycle TCA of every tooth
pair in the zone of action (:mod:`gearcontact.tca.cylindrical_cycle`; ``--side drive``:
the pinion's cw flanks, ``coast``: its ccw flanks): ``tca.json``, ``te0.csv``,
``contact_lines.csv``, ``te0.png`` and ``contact_pattern.png``
(:mod:`gearcontact.tca.cylindrical_export`; docs/cylindrical.md sec. 6).
"""

from __future__ import annotations

import time
from pathlib import Path

from ..geometry.pair import BEVEL, CYLINDRICAL
from ..tca.analysis import analyze_pair
from ..tca.cylindrical_cycle import cylindrical_mesh_cycle
from ..tca.cylindrical_export import write_cylindrical_tca_outputs
from ..tca.export import write_line_contact_outputs, write_tca_outputs
from ..tca.line_contact import LineContact
from .options import (
    MAX_PAIRS,
    add_pair_arguments,
    check_count,
    check_pair_arguments,
    load_pair_for,
    run_timings,
)
from ..validation import InputRangeError
from .outdir import final_path


def register(sub) -> None:
    p = sub.add_parser("tca", help="unloaded TCA: contact path, TE0, gap stencil, phase table",
                       description=__doc__.split("\n\n")[1])
    add_pair_arguments(p, misalignment=True)
    p.add_argument("--pairs", type=int, default=None,
                   help=f"neighbouring tooth pairs on each side, 0 to {MAX_PAIRS} (default 3; "
                        "bevel pairs: a cylindrical pair takes every pair in its zone of "
                        "action)")
    p.add_argument("--table-records", type=int, default=None,
                   help=f"maximum records of the binary phase table, 1 to "
                        f"{MAX_TABLE_RECORDS} (default 16; bevel pairs)")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run, check=check)


#: Upper limit of ``--table-records`` (the record index of the binary table is 16 bit).
MAX_TABLE_RECORDS = 65535


def check(args) -> None:
    """Every option and the pair file, before any work."""
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))
    if args.gear_pair.kind == CYLINDRICAL:
        for option, value, why in (
                ("--pairs", args.pairs, "every tooth pair in the zone of action is analysed"),
                ("--table-records", args.table_records,
                 "no phase table is written for line contact")):
            if value is not None:
                raise InputRangeError(option, value, f"not given for a cylindrical pair ({why})")
        return
    args.pairs = 3 if args.pairs is None else args.pairs
    args.table_records = 16 if args.table_records is None else args.table_records
    check_count("--pairs", args.pairs, 0, MAX_PAIRS)
    check_count("--table-records", args.table_records, 1, MAX_TABLE_RECORDS)


#: ``--side`` of a cylindrical pair -> the flank facing in mesh
#: (:data:`gearcontact.geometry.cylindrical.flank.FACINGS`).
CYLINDRICAL_FACING = {"drive": "cw", "coast": "ccw"}


def run_cylindrical(args) -> int:
    pair = args.gear_pair
    out = Path(args.out)
    t0 = time.perf_counter()
    cycle = cylindrical_mesh_cycle(pair, facing=CYLINDRICAL_FACING[args.side],
                                   phases=args.phases)
    run_timings(args, mesh_cycle=time.perf_counter() - t0)
    write_cylindrical_tca_outputs(cycle, pair, out, side=args.side,
                                  figures=not args.no_figures)
    print(f"{pair.name} {args.side} ({cycle.facing} flanks): TE0 p-p "
          f"{cycle.te0_pp_arcsec:.3f} arcsec, pairs in the zone "
          f"{cycle.pairs_in_zone.min()}-{cycle.pairs_in_zone.max()} (mean "
          f"{cycle.mean_pairs_in_zone:.3f}, eps_gamma {pair.geometry.total_contact_ratio:.3f}),"
          f" contact lines {cycle.mean_line_length_mm:.2f} mm mean -> {final_path(args, out)}")
    return 0


def run(args) -> int:
    if args.gear_pair.kind == CYLINDRICAL:
        return run_cylindrical(args)
    pair = load_pair_for(args)
    out = Path(args.out)
    try:
        res, flanks = analyze_pair(pair, side=args.side, phases=args.phases,
                                   pairs=args.pairs, flanks=args.prepared_pair.flank_set(),
                                   progress=not args.quiet)
    except LineContact as line:
        write_line_contact_outputs(line.result, out, pair_name=pair.name, side=args.side)
        print(f"{pair.name} {args.side}: {line} -> {final_path(args, out)}")
        return 0
    run_timings(args, **res.timings_s)
    write_tca_outputs(res, flanks, pair, out, side=args.side,
                      table_records=args.table_records, figures=not args.no_figures)
    cyc, rc, ell = res.cycle, res.mean_curvature, res.mean_ellipse
    print(f"{pair.name} {args.side}: TE0 p-p {cyc.te0_pp_arcsec:.3f} arcsec, "
          f"A- {rc.A_minus_per_mm:.5g} B- {rc.B_minus_per_mm:.5g} 1/mm, paint ellipse "
          f"{2 * ell.semi_major_mm:.2f} x {2 * ell.semi_minor_mm:.3f} mm at "
          f"{ell.angle_deg:.1f} deg -> {final_path(args, out)}")
    if res.edge_counts:
        print("edge contact (phases of " + str(len(res.edges)) + "): "
              + ", ".join(f"{k} {v}" for k, v in res.edge_counts.items()))
    if res.edge_contact_counts:
        print("  of which an edge touches the other flank: "
              + ", ".join(f"{k} {v}" for k, v in res.edge_contact_counts.items())
              + (f"; P0 is on the {res.mean_point.edge_contact}"
                 if res.mean_point.edge_contact else ""))
    return 0
