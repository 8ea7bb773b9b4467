"""Bending operator build (s0003 by default; target <= 10 s): shell Rayleigh-Ritz of both members.

Measures, for the pinion and the gear tooth: the tooth geometry, the Ritz stiffness
assembly + Cholesky (``build_shell`` with the member's fillet and rim), and one compliance operator on 400 flank points
(a 20 x 20 LTCA-sized lattice), beside the flank generation the operator needs. Prints
a table and the load average (the machine is shared: compare on a quiet machine).

With ``--lte`` it also times the loaded TE over one pitch (the pair's design side) (61 TCA phases,
64.5 N·m, 40 cells per field) rigid and with the bending blocks of both teeth in the
coupled LCP (issue target with bending <= 1 s CPU; wall and process CPU, one run each
after an untimed warm-up of the compiled kernels).

Usage: python3 benchmarks/bench_bending.py [--pair s0003] [--order 10] [--order-face 16] [--repeat 3] [--lte]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair
from gearcontact.structure.rim import rim_segment
from gearcontact.structure.shell import ORDER, ORDER_FACE, RIM_STIFFENING, build_shell
from gearcontact.structure.tooth import tooth_geometry

TARGET_S = 10.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--order", type=int, default=ORDER,
                    help=f"Ritz order over the height of rim and tooth (default {ORDER})")
    ap.add_argument("--order-face", type=int, default=ORDER_FACE,
                    help=f"Ritz order along the face (default {ORDER_FACE})")
    ap.add_argument("--repeat", type=int, default=3, help="repetitions, best kept (default 3)")
    ap.add_argument("--lte", action="store_true",
                    help="also time the loaded TE over one pitch, rigid and with bending")
    ap.add_argument("--pair", default="s0003", help="preset or TOML (default s0003)")
    args = ap.parse_args()
    pair = load_pair(args.pair)
    t0 = time.perf_counter()
    flanks = build_flanks(pair)
    t_flanks = time.perf_counter() - t0
    rows = []
    total = 0.0
    for member in ("pinion", "gear"):
        best = None
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            material = pair.pinion_material if member == "pinion" else pair.gear_material
            tooth = tooth_geometry(flanks, member, material=material)
            t1 = time.perf_counter()
            shell = build_shell(tooth, order=args.order, order_face=args.order_face,
                                rim=rim_segment(tooth, stiffening=RIM_STIFFENING[member]))
            t2 = time.perf_counter()
            XI, ETA = np.meshgrid(np.linspace(-1, 1, 20), np.linspace(-1, 1, 20))
            op = shell.compliance(tooth.points_at("drive", XI.ravel(), ETA.ravel()))
            t3 = time.perf_counter()
            w = np.ones(op.shape[0])
            t4 = time.perf_counter()
            for _ in range(100):
                op.apply(w)
            t5 = time.perf_counter()
            times = (t1 - t0, t2 - t1, t3 - t2, (t5 - t4) / 100)
            best = times if best is None or sum(times) < sum(best) else best
        total += sum(best[:3])
        rows.append((member, shell.n_functions, *best))
    print(f"{pair.name} bending operator, orders {args.order} / {args.order_face} "
          f"(best of {args.repeat})")
    print(f"{'member':8s} {'Ritz fns':>8s} {'tooth s':>9s} {'K+chol s':>9s} "
          f"{'400-pt op s':>11s} {'G w (us)':>9s}")
    for m, n, a, b, c, d in rows:
        print(f"{m:8s} {n:8d} {a:9.4f} {b:9.4f} {c:11.4f} {d * 1e6:9.1f}")
    print(f"both members: {total:.3f} s (target <= {TARGET_S:g} s; flank generation "
          f"before it: {t_flanks:.2f} s, cached per pair by the caller)")
    if args.lte:
        _bench_lte(pair, flanks)
    print(f"load average: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


def _bench_lte(pair, flanks) -> None:
    """Loaded TE over one pitch, rigid vs bending (default shell orders in the LCP)."""
    from gearcontact.ltca.lte import loaded_te
    from gearcontact.ltca.tooth_bending import tooth_bending
    from gearcontact.tca.analysis import analyze_pair

    side = pair.design_side
    tca = analyze_pair(pair, side=side, phases=61, flanks=flanks)[0]
    loaded_te(tca, flanks, pair, 64.5, cells=40, stride=30)   # warm-up (compiled kernels)
    print(f"\nloaded TE, {pair.name} {side}, 64.5 N·m, {len(tca.cycle.phi1_rad)} phases, "
          "40 cells")
    print(f"{'model':8s} {'wall s':>7s} {'CPU s':>7s} {'solves s':>9s} {'fields s':>9s} "
          f"{'rotation P0':>12s} {'shares P0 (%)':>24s}")
    for label, bend in (("rigid", None),
                        ("bending", tooth_bending(flanks, pair, side=side))):
        w, c = time.perf_counter(), time.process_time()
        res = loaded_te(tca, flanks, pair, 64.5, cells=40, bending=bend)
        w, c = time.perf_counter() - w, time.process_time() - c
        k = res.reference_index
        loads = res.pair_loads_lcp_n[:, k]
        shares = " ".join(f"{x:.1f}" for x in 100 * loads / loads.sum() if x > 0)
        print(f"{label:8s} {w:7.2f} {c:7.2f} {res.timings_s['solves_s']:9.2f} "
              f"{res.timings_s['fields_s']:9.2f} {res.rotation_lcp_arcsec[k]:9.2f} as "
              f"{shares:>24s}")


if __name__ == "__main__":
    main()
