"""``gearcontact bending``: tooth bending compliance of one member (shell, optionally FE).

Writes into ``--out`` (created if missing): ``compliance.json`` (``points_mm``: a lattice
of points of the loaded flank (``--side``, default the pair's design side) in the
member's body frame; ``shell_mm_per_n``: the shell
Rayleigh-Ritz point-compliance matrix between them; the deflections under segment loads
around the points and line loads over the face; with ``--fe`` also ``fe_mm_per_n``,
the FE segment / line deflections, ``fe_nodes`` (nodes of the P2 mesh), ``fe_root``
(the root meshed: "cutter", the real one, or "ellipse") and the shell-to-FE ratios)
and ``deflection.png`` (deflection over the flank); the FE build time goes to
``run.json`` only (result files are byte-identical across runs). A cylindrical pair's
tooth is loaded on the flank its ``--side`` mesh loads (drive: the clockwise facing
flanks, the tooth's "coast" side; docs/bending.md sec. 9), its real root the
trochoid its generating rack cuts.
"""

from __future__ import annotations

import numpy as np

from ..geometry.pair import BEVEL, CYLINDRICAL
from ..structure.compliance import SEGMENT_NODES, FeMesh, flank_compliance, write_compliance
from ..structure.cylindrical_compliance import cylindrical_flank_compliance
from ..structure.cylindrical_tooth import loaded_side
from ..tca.cylindrical_cycle import FACING_OF_SIDE
from ..structure.fe import fe_node_count
from ..structure.shell import ORDER, ORDER_FACE
from ..validation import InputRangeError
from .options import (add_pair_arguments, check_count, check_pair_arguments, load_pair_for,
                      run_timings)
from .outdir import final_path


#: Accepted cells of ``--fe-mesh`` per direction: face (at least the segment-load
#: stencil, SEGMENT_NODES + 1), height (2: the FE model), thickness, rim layers (above 8
#: the quadratically graded rim layers of s0003 invert cells: 12 give 2 inverted).
FE_MESH_RANGES = {"NXI": (SEGMENT_NODES + 1, 32), "NETA": (2, 16), "NZETA": (1, 8),
                  "NRIM": (1, 8)}
#: Most P2 nodes of the FE model (:func:`~gearcontact.structure.fe.fe_node_count`; the
#: real root adds the slot bottoms and the fillet zone, 3 layers and 2 cells across each
#: slot): the default 12 6 3 4 has 6,525 on the real root (3,675 on the ellipse root);
#: 24 8 4 6 has 12,789 on the ellipse root (FE build 156 s, 1.4 GB peak, 2 busy cores)
#: and 20,531 on the real root (s0003-centred pinion: 2.0 GB peak, 95 s CPU for the
#: whole command; docs/bending.md sec. 10), which the cap keeps; the sparse
#: factorization grows about quadratically.
MAX_FE_NODES = 21_000


def fe_nodes(n_xi: int, n_eta: int, n_zeta: int, n_rim: int, root: str = "cutter") -> int:
    """P2 nodes of the FE mesh of ``--fe-mesh n_xi n_eta n_zeta n_rim`` on ``--fe-root``
    (an upper bound where the real root falls back to the ellipse)."""
    return fe_node_count(n_xi, n_eta, n_zeta, n_rim, root=root == "cutter")


def register(sub) -> None:
    p = sub.add_parser("bending", help="tooth bending compliance (shell Rayleigh-Ritz, "
                                       "optionally checked by 3D finite elements)",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_pair_arguments(p, phases=False)
    p.add_argument("--member", choices=("pinion", "gear"), default="pinion")
    p.add_argument("--side", choices=("drive", "coast"), default=None,
                   help="loaded flank (default: the pair's design side, the one its "
                        "contact uses; a cylindrical pair: the flank its drive / coast "
                        "mesh loads, default drive)")
    p.add_argument("--order", type=int, default=ORDER,
                   help="Legendre order of the Ritz basis over the height of rim and "
                        f"tooth, 1..16 (default {ORDER})")
    p.add_argument("--order-face", type=int, default=ORDER_FACE,
                   help=f"Legendre order along the face, 1..24 (default {ORDER_FACE})")
    p.add_argument("--points", type=int, nargs=2, default=(3, 3), metavar=("NXI", "NETA"),
                   help="flank lattice: points along the face and the height (default 3 3)")
    p.add_argument("--fe", action="store_true",
                   help="also solve the 3D P2 finite-element model (needs the 'fe' extra)")
    p.add_argument("--fe-mesh", type=int, nargs=4, default=(12, 6, 3, 4),
                   metavar=("NXI", "NETA", "NZETA", "NRIM"),
                   help="FE cells along face ({}-{}), height ({}-{}), thickness ({}-{}) and "
                        "rim ({}-{}), at most {:,} P2 nodes in all (default 12 6 3 4: "
                        "6,525 on the real root, 3,675 on the ellipse root)".format(
                            *(n for r in FE_MESH_RANGES.values() for n in r), MAX_FE_NODES))
    p.add_argument("--fe-root", choices=("cutter", "ellipse"), default="cutter",
                   help="root of the FE tooth: the real root its cutter leaves (default; a "
                        "cylindrical tooth's: the trochoid of its generating rack; where it "
                        "cannot be built, the ellipse root with a warning) or the "
                        "quarter-ellipse root (docs/bending.md sec. 3, 9, 10)")
    # as every computing command (analyze, reproduce, tca, lte, sweep, twin): a script
    # passes --quiet to any of them
    p.add_argument("--quiet", action="store_true",
                   help="no progress bars (this command shows none; its result line, "
                        "notes and warnings are printed as without it)")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """Options, the pair and the optional FE dependency before any work."""
    check_pair_arguments(args, kinds=(BEVEL, CYLINDRICAL))
    for name, n in zip(("--points NXI", "--points NETA"), args.points):
        check_count(name, n, 1, 50)
    check_count("--order", args.order, 1, 16)
    check_count("--order-face", args.order_face, 1, 24)
    for (name, (lo, hi)), n in zip(FE_MESH_RANGES.items(), args.fe_mesh):
        check_count(f"--fe-mesh {name}", n, lo, hi)
    n = fe_nodes(*args.fe_mesh, args.fe_root)
    if args.fe and n > MAX_FE_NODES:
        raise InputRangeError("--fe-mesh", " ".join(map(str, args.fe_mesh)),
                              f"at most {MAX_FE_NODES:,} P2 nodes on the {args.fe_root} "
                              f"root; this mesh has {n:,}")
    if args.fe:
        try:
            import skfem  # noqa: F401
        except ImportError:
            raise InputRangeError("--fe", True, "available only with the 'fe' extra "
                                  "(pip install 'gearcontact[fe]')") from None


def run(args) -> int:
    # lattice over the inner part of the flank (xi in +-0.5, eta in +-1/3)
    lattice = [s * (np.linspace(-1, 1, n) if n > 1 else np.zeros(1))
               for s, n in zip((0.5, 1 / 3), args.points)]
    opts = dict(xi=lattice[0], eta=lattice[1], order=args.order, order_face=args.order_face,
                fe=args.fe, fe_mesh=FeMesh(*args.fe_mesh), fe_root=args.fe_root)
    if args.gear_pair.kind == CYLINDRICAL:
        pair, flanks = args.gear_pair, None
        side = loaded_side(FACING_OF_SIDE[args.side])
        res = cylindrical_flank_compliance(pair, args.member, side=side, **opts)
    else:
        # a pair file without an ease-off table: synthesized; no TCA of the pair here
        pair = load_pair_for(args, mesh_follows=False)
        flanks = args.prepared_pair.flank_set()     # built once (the synthesis' if it ran)
        side = args.prepared_pair.side
        res = flank_compliance(pair, args.member, side=side, flanks=flanks, **opts)
    write_compliance(res, args.out, pair=pair, flanks=flanks, figures=not args.no_figures,
                     order=args.order, order_face=args.order_face)
    seg = res.segment_shell_mm_per_n
    where = (f"points on the flank the {args.side} mesh loads (the tooth's {side} side)"
             if pair.kind == CYLINDRICAL else f"{side}-flank points")
    line = (f"{pair.name} {args.member}: {len(res.xi)} {where}, shell segment-load "
            f"deflection {seg.min():.3g}..{seg.max():.3g} mm/N")
    if res.fe_mm_per_n is not None:
        r = res.ratios()
        run_timings(args, fe_build_s=res.fe_build_s)
        line += (f"; FE ({res.fe_root} root, {res.fe_nodes} nodes, {res.fe_build_s:.1f} s) "
                 f"shell/FE "
                 f"{r.min():.2f}..{r.max():.2f}")
    print(line + f" -> {final_path(args, args.out)}")
    return 0
