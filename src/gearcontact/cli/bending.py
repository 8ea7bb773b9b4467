"""``gearcontact bending``: tooth bending compliance of one member (shell, optionally FE).

Writes into ``--out`` (created if missing): ``compliance.json`` (``points_mm``: drive-flank
points in the member's body frame; ``shell_mm_per_n``: shell Rayleigh-Ritz compliance
matrix between them; the through-thickness compliance of each point; with ``--fe`` also
``fe_mm_per_n``, ``fe_through_mm_per_n``, ``fe_nodes`` (nodes of the P2 mesh) and the
shell-to-FE ratios) and ``deflection.png`` (deflection over the flank).
"""

from __future__ import annotations

import numpy as np

from ..geometry.flank import build_flanks
from ..geometry.pair import load_pair
from ..structure.compliance import FeMesh, flank_compliance, write_compliance
from ..validation import InputRangeError
from .options import add_pair_arguments


def register(sub) -> None:
    p = sub.add_parser("bending", help="tooth bending compliance (shell Rayleigh-Ritz, "
                                       "optionally checked by 3D finite elements)",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, phases=False)
    p.add_argument("--member", choices=("pinion", "gear"), default="pinion")
    p.add_argument("--order", type=int, default=8,
                   help="Legendre order of the Ritz basis per direction, 1..16 (default 8)")
    p.add_argument("--points", type=int, nargs=2, default=(3, 3), metavar=("NXI", "NETA"),
                   help="flank lattice: points along the face and the height (default 3 3)")
    p.add_argument("--fe", action="store_true",
                   help="also solve the 3D P2 finite-element model (needs the 'fe' extra)")
    p.add_argument("--fe-mesh", type=int, nargs=4, default=(12, 6, 3, 4),
                   metavar=("NXI", "NETA", "NZETA", "NRIM"),
                   help="FE cells along face, height, thickness and rim (default 12 6 3 4)")
    p.set_defaults(func=run)


def run(args) -> int:
    for name, n in zip(("--points NXI", "--points NETA"), args.points):
        if not 1 <= n <= 50:
            raise InputRangeError(name, n, "[1, 50]")
    pair = load_pair(args.pair)
    flanks = build_flanks(pair)
    lattice = [0.75 * (np.linspace(-1, 1, n) if n > 1 else np.zeros(1)) for n in args.points]
    res = flank_compliance(pair, args.member, flanks=flanks, xi=lattice[0], eta=lattice[1],
                           order=args.order, fe=args.fe, fe_mesh=FeMesh(*args.fe_mesh))
    write_compliance(res, args.out, pair=pair, flanks=flanks, figures=not args.no_figures,
                     order=args.order)
    line = (f"{pair.name} {args.member}: {len(res.xi)} drive-flank points, shell "
            f"through-thickness compliance {res.shell_through_mm_per_n.min():.3g}.."
            f"{res.shell_through_mm_per_n.max():.3g} mm/N")
    if res.fe_mm_per_n is not None:
        r = res.shell_through_mm_per_n / res.fe_through_mm_per_n
        line += (f"; FE ({res.fe_nodes} nodes, {res.fe_build_s:.1f} s) shell/FE "
                 f"{r.min():.2f}..{r.max():.2f}")
    print(line + f" -> {args.out}")
    return 0
