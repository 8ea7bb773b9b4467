"""Benchmark of the stage A/B gap kernel: golden models, fp64 reference and RTL sim.

Prints one table of candidate gaps per second (one candidate = one (point, sample)
pair evaluated by Algorithm 1) beside the paper's FPGA figures (docs/spec.md sec. 7):

* board: 16 lanes x 12.5 MHz = 2.0e8 candidates/s (lane-parallel peak);
* projected: 63 lanes x 50 MHz = 3.15e9 candidates/s (DSP-saturated XC7K480T).

Target of the vectorized golden model: >= 1e9 candidates/s on 2 cores. Both wall-clock
and per-CPU-second rates are printed (the second is robust against other load on a
shared machine). Run: ``python benchmarks/bench_gap_kernel.py [--quick] [--zmm]``;
``--zmm`` sets ``NUMBA_CPU_FEATURES`` to the host features plus ``-prefer-256-bit`` so
that LLVM uses full 512-bit AVX-512 vectors (it must precede the numba import).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

ONE = 1 << 19
BOARD = 16 * 12.5e6
PROJECTED = 63 * 50e6


def codes(rng, m, n):
    """Seeded in-contract operands: m points (shared pose) x n samples."""
    g = rng.integers(-(4 << 16), 4 << 16, (n, 3))
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    q *= np.sign(np.linalg.det(q))
    return (np.floor(q * ONE + 0.5).astype(np.int64), rng.integers(-(1 << 16), 1 << 16, 3),
            rng.integers(-(4 << 16), 4 << 16, (m, 3)), g,
            np.floor(nrm * ONE + 0.5).astype(np.int64))


def timed(fn, reps):
    """Best (wall, cpu) seconds over ``reps`` calls."""
    best_w = best_c = float("inf")
    for _ in range(reps):
        c0, w0 = time.process_time(), time.perf_counter()
        fn()
        best_w = min(best_w, time.perf_counter() - w0)
        best_c = min(best_c, time.process_time() - c0)
    return best_w, best_c


def bench_batch(rng, m, n, lanes, reps):
    r, t, p, g, nc = codes(rng, m, n)
    gap_golden_batch(r, t, p[:2], g, nc, 1 << 34, lanes=lanes)      # compile / load cache
    w, c = timed(lambda: gap_golden_batch(r, t, p, g, nc, 1 << 34, lanes=lanes), reps)
    return m * n / w, m * n / c


def bench_scalar(rng, m, n):
    r, t, p, g, nc = codes(rng, m, n)
    vecs = [GapVector(r, t, p[k], g, nc, 1 << 34) for k in range(m)]
    w, c = timed(lambda: [gap_golden_codes(v, lanes=16) for v in vecs], 1)
    return m * n / w, m * n / c


def bench_reference(rng, m, n):
    gx = rng.uniform(-4, 4, (n, 3))
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    pts = rng.uniform(-4, 4, (m, 3))
    w, c = timed(lambda: [gap_sample_terms(np.eye(3), np.zeros(3), q, gx, nrm)
                          for q in pts], 1)
    return m * n / w, m * n / c


def bench_rtl(rng, lanes, passes):
    """Simulated cycles per second, elaboration excluded (difference of two runs)."""
    from gearcontact.preview.gap.rtl import simulate_gap_core
    vecs = []
    for _ in range(passes):
        r, t, p, g, nc = codes(rng, 1, 16)
        vecs.append(GapVector(r, t, p[0], g, nc, 1 << 34))
    runs = []
    for k in (1, passes):
        w0 = time.perf_counter()
        _, cycles = simulate_gap_core(vecs[:k], lanes=lanes)
        runs.append((time.perf_counter() - w0, sum(cycles) + 16 * k))  # + sample writes
    (w1, c1), (w2, c2) = runs
    return (c2 - c1) / (w2 - w1), cycles[0]


def main():
    global HAVE_NUMBA, gap_golden_batch, GapVector, gap_golden_codes, gap_latency
    global gap_sample_terms
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller problem sizes")
    ap.add_argument("--zmm", action="store_true", help="let numba use 512-bit vectors")
    args = ap.parse_args()
    if args.zmm:
        import llvmlite.binding as ll
        os.environ["NUMBA_CPU_FEATURES"] = ll.get_host_cpu_features().flatten() \
            + ",-prefer-256-bit"
    from gearcontact.preview.gap.fast import HAVE_NUMBA, gap_golden_batch
    from gearcontact.preview.gap.golden import GapVector, gap_golden_codes, gap_latency
    from gearcontact.preview.gap.reference import gap_sample_terms
    rng = np.random.default_rng(2024)
    scale = 8 if args.quick else 1
    reps = 2 if args.quick else 3
    threads = os.environ.get("NUMBA_NUM_THREADS", str(os.cpu_count()))
    print(f"gap kernel benchmark  (numba={'yes' if HAVE_NUMBA else 'no'}, "
          f"threads={threads}, cpus={os.cpu_count()}, 512-bit vectors={args.zmm})")
    print(f"{'model':<34}{'N':>6}{'L':>4}{'cand/s wall':>14}{'cand/s/CPU-s':>14}"
          f"{'vs board':>10}{'vs proj.':>10}")
    rows = []
    for m, n, lanes in ((1 << 20, 16, 16), (1 << 17, 256, 16), (1 << 14, 4096, 16),
                        (1 << 14, 4096, 64)):
        wall, cpu = bench_batch(rng, m // scale, n, lanes, reps)
        rows.append((f"golden batch (numba), M={m // scale}", n, lanes, wall, cpu))
    wall, cpu = bench_scalar(rng, 64 // (4 if args.quick else 1), 256)
    rows.append(("golden scalar (Python ints)", 256, 16, wall, cpu))
    wall, cpu = bench_reference(rng, 2000 // scale, 256)
    rows.append(("fp64 reference (numpy, per point)", 256, "-", wall, cpu))
    for name, n, lanes, wall, cpu in rows:
        print(f"{name:<34}{n:>6}{lanes:>4}{wall:>14.3g}{cpu:>14.3g}"
              f"{wall / BOARD:>10.3g}{wall / PROJECTED:>10.3g}")
    print()
    print("RTL (Amaranth simulator, 16-sample passes incl. sample writes)")
    print(f"{'lanes':>6}{'cycles/pass':>13}{'sim cycles/s':>14}")
    for lanes in (8, 16):
        cps, lat = bench_rtl(rng, lanes, 4 if args.quick else 12)
        print(f"{lanes:>6}{lat:>13}{cps:>14.3g}")
    print()
    print("hardware reference points (candidates/s)")
    print(f"  paper board, 16 lanes x 12.5 MHz, lane-parallel peak : {BOARD:.3g}")
    print(f"  paper projection, 63 lanes x 50 MHz                   : {PROJECTED:.3g}")
    for lanes, f_hz in ((16, 12.5e6), (16, 50e6), (64, 50e6)):
        lat = gap_latency(16, lanes)
        print(f"  this core, L={lanes}, {f_hz / 1e6:g} MHz: one 16-sample pass "
              f"{lat} cy -> {16 * f_hz / lat:.3g}/s; streaming N >> L -> "
              f"{lanes * f_hz:.3g}/s")


if __name__ == "__main__":
    main()
