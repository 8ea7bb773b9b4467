"""``gearcontact tca``: unloaded tooth contact analysis of a pair.

Writes into ``--out`` (created if missing): ``tca.json`` (summary), ``te0.csv``,
``contact_path.csv``, ``gap_stencil.csv`` (49-sample hardware stencil),
``gap_field.csv`` (80 x 80 host field), ``phase_table.json``, ``phase_table.bin`` and
the figures ``te0.png``, ``contact_pattern.png`` and ``flanks_in_mesh.png``. Per phase
``tca.json`` says whether the contact is flank on flank or an edge touching the other
flank (``phase_contact``, :mod:`gearcontact.tca.edge_contact`).
"""

from __future__ import annotations

from pathlib import Path

from ..tca.analysis import analyze_pair
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
from .outdir import final_path


def register(sub) -> None:
    p = sub.add_parser("tca", help="unloaded TCA: contact path, TE0, gap stencil, phase table",
                       description=__doc__.split("\n\n")[1])
    add_pair_arguments(p, misalignment=True)
    p.add_argument("--pairs", type=int, default=3,
                   help=f"neighbouring tooth pairs on each side, 0 to {MAX_PAIRS} (default 3)")
    p.add_argument("--table-records", type=int, default=16,
                   help=f"maximum records of the binary phase table, 1 to "
                        f"{MAX_TABLE_RECORDS} (default 16)")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run, check=check)


#: Upper limit of ``--table-records`` (the record index of the binary table is 16 bit).
MAX_TABLE_RECORDS = 65535


def check(args) -> None:
    """Every option and the pair file, before any work."""
    check_pair_arguments(args)
    check_count("--pairs", args.pairs, 0, MAX_PAIRS)
    check_count("--table-records", args.table_records, 1, MAX_TABLE_RECORDS)


def run(args) -> int:
    pair = load_pair_for(args)
    out = Path(args.out)
    try:
        res, flanks = analyze_pair(pair, side=args.side, phases=args.phases,
                                   pairs=args.pairs, flanks=args.prepared_pair.flanks,
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
