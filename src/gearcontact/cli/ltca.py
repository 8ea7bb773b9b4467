"""``gearcontact ltca``: loaded contact of the reference tooth pair at P0 under a torque.

Writes into ``--out`` (created if missing): ``ltca.json`` (load, LCP mean / p90 / peak
pressure, approach, mesh rotation, contact cells, preview p_max, solver, solve time and
the rest of :meth:`~gearcontact.contact.pair_ltca.PairLoadCase.summary`),
``pressure_map.csv`` (``s_mm,t_mm,pressure_mpa`` over the principal-frame field) and
``pressure_map.png`` (pressure map with the Hertzian preview ellipse overlaid).
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import numpy as np

from ..contact.lcp import SOLVERS
from ..contact.pair_ltca import preview_ellipse, single_pair_ltca
from ..contact.patch import ContactAtEdgeWarning, plot_patch
from ..tca.analysis import analyze_pair
from ..tca.export import write_csv
from .options import add_pair_arguments, check_pair_arguments, load_pair_for


def register(sub) -> None:
    p = sub.add_parser("ltca", help="loaded contact of one tooth pair at P0: pressure map, "
                                    "statistics, approach, preview beside it",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, torque=True, cells=80)
    p.add_argument("--solver", default="pk_cg", choices=SOLVERS, help="LCP solver (default pk_cg)")
    p.set_defaults(func=run)


def run(args) -> int:
    check_pair_arguments(args)
    pair = load_pair_for(args)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    tca, flanks = analyze_pair(pair, side=args.side, phases=args.phases)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ContactAtEdgeWarning)  # reported in the JSON
        case = single_pair_ltca(tca, flanks, pair, args.torque, side=args.side,
                                cells=args.cells, solver=args.solver)
    summary = case.summary()
    (out / "ltca.json").write_text(json.dumps(summary, indent=2))
    g = case.patch.grid
    s, t = np.meshgrid(g.x_mm, g.y_mm)
    write_csv(out / "pressure_map.csv", ["s_mm", "t_mm", "pressure_mpa"],
              zip(map(float, s.ravel()), map(float, t.ravel()),
                  map(float, case.patch.pressure_mpa.ravel())))
    if not args.no_figures:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(9, 3.2))
        plot_patch(case.patch, ax, ellipse=preview_ellipse(case.preview, g))
        ax.set_title(f"{pair.name} {args.side} {args.torque:g} N·m, W = {case.load_n:.0f} N:"
                     f" LCP p90 {case.patch.p90_mpa:.0f}, peak {case.patch.p_peak_mpa:.0f};"
                     f" preview p_max {case.preview.p_max_mpa:.0f} MPa (cyan)", fontsize=9)
        ax.set_xlabel("s along the long axis (mm)")
        ax.set_ylabel("t (mm)")
        fig.tight_layout()
        fig.savefig(out / "pressure_map.png", dpi=120)
        plt.close(fig)
    print(f"{pair.name} {args.side} {args.torque:g} N·m: W = {case.load_n:.0f} N, LCP mean "
          f"{case.patch.p_mean_mpa:.0f} / p90 {case.patch.p90_mpa:.0f} / peak "
          f"{case.patch.p_peak_mpa:.0f} MPa, preview p_max {case.preview.p_max_mpa:.0f} MPa, "
          f"mesh rotation {case.mesh_rotation_arcsec:.1f} arcsec "
          f"({case.patch.lcp.solver}, {case.patch.lcp.solve_time_ms:.0f} ms) -> {out}")
    if not case.patch.converged:
        print(f"gearcontact ltca: warning: LCP {case.patch.lcp.status}: "
              f"{case.patch.lcp.message}", file=sys.stderr)
        return 1
    return 0
