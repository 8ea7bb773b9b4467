"""``gearcontact tca``: unloaded tooth contact analysis of a pair.

Writes into ``--out`` (created if missing): ``tca.json`` (summary), ``te0.csv``,
``contact_path.csv``, ``gap_stencil.csv`` (49-sample hardware stencil),
``gap_field.csv`` (80 x 80 host field), ``phase_table.json``, ``phase_table.bin`` and
the figures ``te0.png``, ``contact_pattern.png`` and ``flanks_in_mesh.png``.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..tca.analysis import analyze_pair
from ..tca.export import write_tca_outputs
from ..tca.line_contact import LineContact
from .options import add_pair_arguments, check_pair_arguments, load_pair_for


def register(sub) -> None:
    p = sub.add_parser("tca", help="unloaded TCA: contact path, TE0, gap stencil, phase table",
                       description=__doc__.split("\n\n")[1])
    add_pair_arguments(p)
    p.add_argument("--pairs", type=int, default=2,
                   help="neighbouring tooth pairs on each side (default 2)")
    p.add_argument("--table-records", type=int, default=16,
                   help="maximum records of the binary phase table (default 16)")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.set_defaults(func=run)


def run(args) -> int:
    check_pair_arguments(args)
    pair = load_pair_for(args)
    out = Path(args.out)
    try:
        res, flanks = analyze_pair(pair, side=args.side, phases=args.phases,
                                   pairs=args.pairs, progress=not args.quiet)
    except LineContact as line:
        out.mkdir(parents=True, exist_ok=True)
        (out / "tca.json").write_text(json.dumps(
            {"pair": pair.name, "side": args.side, **line.result.as_dict()}, indent=2))
        print(f"{pair.name} {args.side}: {line} -> {out}")
        return 0
    write_tca_outputs(res, flanks, pair, out, side=args.side,
                      table_records=args.table_records, figures=not args.no_figures)
    cyc, rc, ell = res.cycle, res.mean_curvature, res.mean_ellipse
    print(f"{pair.name} {args.side}: TE0 p-p {cyc.te0_pp_arcsec:.3f} arcsec, "
          f"A- {rc.A_minus_per_mm:.5g} B- {rc.B_minus_per_mm:.5g} 1/mm, paint ellipse "
          f"{2 * ell.semi_major_mm:.2f} x {2 * ell.semi_minor_mm:.3f} mm at "
          f"{ell.angle_deg:.1f} deg -> {out}")
    if res.edge_counts:
        print("edge contact (phases of " + str(len(res.edges)) + "): "
              + ", ".join(f"{k} {v}" for k, v in res.edge_counts.items()))
    return 0
