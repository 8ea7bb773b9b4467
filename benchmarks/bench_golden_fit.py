"""Benchmark of the stage-C curvature fit: golden-model evaluations per second.

Prints one table: scalar golden (bit-by-bit isqrt and math.isqrt fast path),
vectorized golden (numpy int64), the fp64 reference (peer: the float model the
golden replaces) and the cycle-accurate Amaranth simulation of the RTL core, with
ratios against the scalar fp64 reference.

Run: ``python benchmarks/bench_golden_fit.py [--n-scalar 2000] [--n-batch 200000]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from gearcontact.preview.fit.golden import (FIT_CYCLES, encode_gaps, golden_fit,
                                            golden_fit_batch)
from gearcontact.preview.fit.reference import fit_curvatures
from gearcontact.preview.fit.rtl import simulate_fit_core
from gearcontact.contract.stencil import stencil_coordinates


def random_fields(n: int, seed: int) -> np.ndarray:
    """n seeded elliptic quadratic gap fields (mm), A-, B- log-uniform in [1e-3, 1]."""
    rng = np.random.default_rng(seed)
    s, t = stencil_coordinates()
    a, b = np.sort(np.exp(rng.uniform(np.log(1e-3), 0.0, (2, n))), axis=0)[::-1]
    th = rng.uniform(-np.pi / 2, np.pi / 2, n)
    co, si = np.cos(th), np.sin(th)
    c3 = a * co**2 + b * si**2
    c4 = 2 * (a - b) * si * co
    c5 = a * si**2 + b * co**2
    c0, c1, c2 = rng.uniform(-0.05, 0.05, (3, n))
    return (c0[:, None] + c1[:, None] * s + c2[:, None] * t + c3[:, None] * s * s
            + c4[:, None] * s * t + c5[:, None] * t * t)


def _rate(fn, count: int) -> tuple[float, float]:
    t0 = time.perf_counter()
    fn()
    dt = time.perf_counter() - t0
    return count / dt, dt


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n-scalar", type=int, default=2000, help="stencils for scalar paths")
    ap.add_argument("--n-batch", type=int, default=200000, help="stencils for the batch path")
    ap.add_argument("--n-rtl", type=int, default=50, help="stencils through the RTL sim")
    args = ap.parse_args(argv)

    fields = random_fields(max(args.n_scalar, args.n_batch, args.n_rtl), seed=0)
    codes = encode_gaps(fields)
    rows_py = [[int(x) for x in row] for row in codes[:args.n_scalar]]
    golden_fit_batch(codes[:10])            # warm caches (ROM bake)
    fit_curvatures(fields[0])

    res = {}
    res["fp64 reference (scalar)"] = _rate(
        lambda: [fit_curvatures(f) for f in fields[:args.n_scalar]], args.n_scalar)
    res["golden scalar, bit-by-bit isqrt"] = _rate(
        lambda: [golden_fit(r, bitwise=True) for r in rows_py], args.n_scalar)
    res["golden scalar, math.isqrt"] = _rate(
        lambda: [golden_fit(r, bitwise=False) for r in rows_py], args.n_scalar)
    res["golden vectorized (int64)"] = _rate(
        lambda: golden_fit_batch(codes[:args.n_batch]), args.n_batch)
    res["RTL simulation (Amaranth)"] = _rate(
        lambda: simulate_fit_core(codes[:args.n_rtl]), args.n_rtl)

    peer = res["fp64 reference (scalar)"][0]
    print(f"{'path':34s} {'fits/s':>12s} {'time s':>8s} {'x fp64 ref':>10s}")
    for name, (rate, dt) in res.items():
        print(f"{name:34s} {rate:12.4g} {dt:8.3f} {rate / peer:10.3g}")
    rtl_rate = res["RTL simulation (Amaranth)"][0]
    # per stencil the runner clocks 1 wr_rst + 49 writes + FIT_CYCLES run cycles
    print(f"RTL sim clock rate: {rtl_rate * (1 + 49 + FIT_CYCLES):.4g} cycles/s; "
          f"hardware latency {FIT_CYCLES} cycles (1.04 us at 50 MHz)")


if __name__ == "__main__":
    main()
