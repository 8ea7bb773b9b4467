"""Calibration of the bevel shell's rim factor (``structure.shell.RIM_STIFFENING``) against
the 3D FE on the teeth's real roots (docs/bending.md sec. 10).

The procedure of sec. 10, as a script: for every tooth the P2 FE on its real root
(``flank_compliance(..., fe=True, fe_root="cutter")``, default mesh 12 x 6 x 3 + 4, 3
fillet layers, 2 slot cells; the pair's design side; the 12 distributed loads of the
lattice xi in {-0.5, 0, 0.5}, eta in {-1/3, 0, 1/3}: 9 segment loads and 3 line loads),
computed once; the shell (orders 10 / 16, the member's rim segment with each factor)
at every factor of the grid; shell / FE per tooth and the largest |log(shell / FE)|
over all teeth. The calibrated factor is the grid factor with the smallest worst misfit
(one factor for both members).

Teeth: the s0003-centred pinion and gear, the s0003 gear, the F.2 machine-settings
pinion and gear, the F.2 formate / conjugate pair's pinion (the F.2 gear of that pair
is the same formate tooth as the machine pair's: identical FE values, not repeated),
and with ``--with-s0003-pinion`` the s0003 pinion, whose slot closes in a V at the toe
(session 18: the eighth tooth).

With ``--fe-root ellipse`` the FE meshes the shell's own quarter-ellipse root instead:
the plate's misfit with the same root geometry in both models. ``--mesh`` and ``--eta``
give the finer mesh of the slow test (20 8 4 6, -0.5 0 0.5). With ``--membrane naghdi``
the shell couples membrane and bending through the mid-surface's curvature (a shallow
shell, ``build_shell(..., membrane=True)``; docs/bending.md sec. 12), with ``--membrane
dmv`` in the membrane strain only (``membrane_shear=False``); the FE unchanged. With
``--rim-block`` the block below the fillet is the Ritz solid of ``structure.rim_block`` (``build_shell(...,
rim_block=True)``)
(docs/bending.md sec. 13; ``--block-orders`` its enrichment's degrees, ``none`` for the
plate's fields alone in the solid; ``--solid-tooth`` a tooth without a block as the Ritz
solid of ``structure.tooth_solid``, session 25). With ``--rim-depth fillet`` both models clamp the
rim's bottom at the shell's own fillet height instead of the tooth height: the shell's
block has depth 0 and the rule of sec. 13 ("Teeth without a block") takes the plate at
the block model's factor; the teeth without a block of sec. 13's session-24 paragraph.

Usage: python3 benchmarks/bench_rim_calibration.py [--factors 1.3 1.4 ...]
       [--with-s0003-pinion] [--only LABEL ...] [--fe-root cutter|ellipse]
       [--mesh N_XI N_ETA N_ZETA N_RIM] [--eta ...] [--membrane dmv|naghdi]
       [--rim-block [--block-orders P_XI P_S P_ZETA | none]] [--rim-depth height|fillet]
       [--json FILE]
"""

from __future__ import annotations

import argparse
import json
import os
import time
import warnings

import numpy as np

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair
from gearcontact.structure.compliance import (EllipseRootWarning, FeMesh, flank_compliance,
                                              shell_compliance)
from gearcontact.structure.rim import rim_segment
from gearcontact.structure.rim_block import BLOCK_ORDERS
from gearcontact.structure.shell import ORDER, ORDER_FACE, RIM_STIFFENING, build_shell
from gearcontact.structure.tooth import tooth_geometry

F2_MACHINE = "examples/machine_settings/iso23509_f2_machine.toml"
F2_CONJUGATE = "examples/iso23509_f2_spiral_bevel.toml"

#: (label, pair, member) of the seven teeth of sec. 10 (the F.2 gear once).
TEETH = [("s0003-centred pinion", "s0003-centred", "pinion"),
         ("F.2 machine pinion", F2_MACHINE, "pinion"),
         ("F.2 conjugate pinion", F2_CONJUGATE, "pinion"),
         ("s0003-centred gear", "s0003-centred", "gear"),
         ("s0003 gear", "s0003", "gear"),
         ("F.2 gear", F2_MACHINE, "gear")]
EIGHTH = ("s0003 pinion", "s0003", "pinion")
FACTORS = (1.3, 1.4, 1.45, 1.5, 1.55, 1.6, 1.7)


#: Flank sets built so far, per pair (both members of a pair share one).
_FLANKS: dict = {}


def measure(pair_name: str, member: str, factors, *, fe_root: str = "cutter",
            eta=(-1 / 3, 0.0, 1 / 3), fe_mesh: FeMesh = FeMesh(),
            membrane: str | None = None, rim_block: bool = False,
            block_orders=BLOCK_ORDERS, rim_depth: str = "height",
            solid_tooth: bool = False) -> dict:
    """The FE deflections of one tooth under the distributed loads (computed once) and
    shell / FE at every factor of ``factors`` (segment loads, then line loads)."""
    pair = load_pair(pair_name)
    if pair_name not in _FLANKS:
        _FLANKS[pair_name] = build_flanks(pair)
    flanks = _FLANKS[pair_name]
    material = pair.pinion_material if member == "pinion" else pair.gear_material
    tooth = tooth_geometry(flanks, member, material=material)
    kw = dict(side=pair.design_side, flanks=flanks, fe_mesh=fe_mesh, eta=tuple(eta))
    # the rim's clamped bottom: the tooth height (default) or the shell's fillet height
    depth = None if rim_depth == "height" else rim_segment(tooth).fillet_mm
    with warnings.catch_warnings():
        warnings.simplefilter("error", EllipseRootWarning)   # the real root or nothing
        t0 = time.process_time()
        ref = flank_compliance(pair, member, fe=True, fe_root=fe_root,
                               rim=rim_segment(tooth, depth_mm=depth), **kw)
        fe_s = time.process_time() - t0
    fe = np.concatenate([ref.segment_fe_mm_per_n, ref.line_fe_mm_per_n])
    ratios = {}
    for k in factors:
        rim = rim_segment(tooth, depth_mm=depth, stiffening=float(k))
        if membrane:        # the shallow shell of the same tooth and rim (sec. 12)
            shell = build_shell(tooth, order=ORDER, order_face=ORDER_FACE, rim=rim,
                                membrane=True, membrane_shear=membrane == "naghdi")
            res = shell_compliance(shell, side=kw["side"], eta=kw["eta"], fe_mesh=fe_mesh)
        elif rim_block:     # the Ritz solid below the fillet (sec. 13)
            shell = build_shell(tooth, order=ORDER, order_face=ORDER_FACE, rim=rim,
                                rim_block=True, block_orders=block_orders,
                                solid_tooth=solid_tooth)
            res = shell_compliance(shell, side=kw["side"], eta=kw["eta"], fe_mesh=fe_mesh)
        else:
            res = flank_compliance(pair, member, rim=rim, **kw)
        ratios[float(k)] = np.concatenate([res.segment_shell_mm_per_n,
                                           res.line_shell_mm_per_n]) / fe
    return {"side": pair.design_side, "fe_nodes": ref.fe_nodes, "fe_cpu_s": fe_s,
            "rim_depth_mm": rim.depth_mm, "fillet_mm": rim.fillet_mm,
            "fe_mm_per_n": fe.tolist(), "line_fe_um_per_kn": (1e6 * ref.line_fe_mm_per_n).tolist(),
            "ratios": {k: v.tolist() for k, v in ratios.items()}}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--factors", type=float, nargs="+", default=FACTORS)
    ap.add_argument("--with-s0003-pinion", action="store_true",
                    help="add the s0003 pinion (V-slot root) as the eighth tooth")
    ap.add_argument("--only", nargs="+", default=None,
                    help="labels of the teeth to run (default all)")
    ap.add_argument("--fe-root", choices=("cutter", "ellipse"), default="cutter",
                    help="the FE's root: the real one (default, the calibration) or the "
                         "shell's own quarter ellipse (the plate's misfit on one geometry)")
    ap.add_argument("--mesh", type=int, nargs="+", default=None,
                    help="FE cells N_XI N_ETA N_ZETA N_RIM [N_FILLET N_SLOT] (default "
                         "12 6 3 4 3 2, the calibration's)")
    ap.add_argument("--eta", type=float, nargs="+", default=(-1 / 3, 0.0, 1 / 3),
                    help="lattice heights (default -1/3 0 1/3)")
    ap.add_argument("--membrane", choices=("dmv", "naghdi"), default=None,
                    help="the shell with the membrane-curvature coupling (sec. 12)")
    ap.add_argument("--rim-block", action="store_true",
                    help="the rim block below the fillet as a Ritz solid (sec. 13)")
    ap.add_argument("--block-orders", nargs="+", default=None,
                    help="the block enrichment's degrees P_XI P_S P_ZETA, or none "
                         f"(default {' '.join(map(str, BLOCK_ORDERS))})")
    ap.add_argument("--rim-depth", choices=("height", "fillet"), default="height",
                    help="the clamped bottom of both models: the tooth height (default) "
                         "or the shell's fillet height (no block below the fillet)")
    ap.add_argument("--solid-tooth", action="store_true",
                    help="with --rim-block: a tooth without a block as the Ritz solid of "
                         "structure.tooth_solid (sec. 13, session 25)")
    ap.add_argument("--json", default=None, help="write the measurements to this file")
    args = ap.parse_args()
    teeth = TEETH + ([EIGHTH] if args.with_s0003_pinion else [])
    if args.only:
        teeth = [t for t in teeth if t[0] in args.only]
    factors = sorted(set(args.factors))
    if args.block_orders is None:
        block_orders = BLOCK_ORDERS
    elif args.block_orders == ["none"]:
        block_orders = None
    else:
        block_orders = tuple(int(p) for p in args.block_orders)
    out = {}
    for label, name, member in teeth:
        out[label] = measure(name, member, factors, fe_root=args.fe_root, eta=args.eta,
                             fe_mesh=FeMesh() if args.mesh is None else FeMesh(*args.mesh),
                             membrane=args.membrane, rim_block=args.rim_block,
                             block_orders=block_orders, rim_depth=args.rim_depth,
                             solid_tooth=args.solid_tooth)
        print(f"{label}: rim depth {out[label]['rim_depth_mm']:.3f} mm, fillet "
              f"{out[label]['fillet_mm']:.3f} mm; FE {out[label]['fe_nodes']} nodes, {out[label]['fe_cpu_s']:.1f} s "
              f"CPU; line FE (um/kN) "
              + ", ".join(f"{x:.3f}" for x in out[label]["line_fe_um_per_kn"]), flush=True)
    print(f"\nshell / FE (min .. max over the 12 loads), current RIM_STIFFENING "
          f"{RIM_STIFFENING}")
    print(f"{'factor':>6s} " + " ".join(f"{t[0]:>22s}" for t in teeth)
          + "  max|log|  log span")
    worst, span = {}, {}
    for k in factors:
        cells, w = [], 0.0
        every = np.concatenate([out[label]["ratios"][k] for label, _, _ in teeth])
        for label, _, _ in teeth:
            r = np.asarray(out[label]["ratios"][k])
            cells.append(f"{r.min():.3f} .. {r.max():.3f}")
            w = max(w, float(np.max(np.abs(np.log(r)))))
        worst[k] = w
        # the spread of shell / FE over all teeth and loads (docs/bending.md sec. 12)
        span[k] = float(np.log(every.max() / every.min()))
        print(f"{k:6.3f} " + " ".join(f"{c:>22s}" for c in cells)
              + f"  {w:.3f}     {span[k]:.3f}")
    best = min(worst, key=worst.get)
    print(f"\nsmallest worst misfit: factor {best:g}, max |log(shell / FE)| {worst[best]:.3f}")
    print(f"load average: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({"factors": factors, "worst_abs_log": worst, "log_span": span,
                       "teeth": out}, fh,
                      indent=1)


if __name__ == "__main__":
    main()
