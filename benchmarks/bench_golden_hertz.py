"""Benchmark of the stage-D golden models (bit-exact fixed point).

Prints one table of stage-D evaluations per second: the scalar Python-int model
(floor-division fast path and the 80-iteration bit-serial divider), and the vectorized
numba model (bit-identical) with 1 and all threads, beside the datapath's own rate
(one evaluation per 756 cycles at the paper's 50 MHz board clock = 66 k/s; the C->D
chain 806 cycles = 62 k/s). Target of the vectorized model: >= 1e6 evaluations/s on
2 cores. Wall-clock and per-CPU-second rates are both printed (the latter is robust
against other load on a shared machine). Inputs: seeded codes of the accuracy domain.

Run: ``python benchmarks/bench_golden_hertz.py [--quick]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from gearcontact.materials import STEEL, effective_modulus_mpa
from gearcontact.preview.hertz.golden import encode_hertz_inputs, hertz_golden
from gearcontact.preview.hertz.golden_vec import HAVE_NUMBA, hertz_golden_array
from gearcontact.preview.hertz.schedule import CHAIN_CYCLES, HERTZ_CYCLES

BOARD_HZ = 50e6


def _codes(n: int, seed: int = 3):
    rng = np.random.default_rng(seed)
    a = np.exp(rng.uniform(np.log(1e-3), 0.0, n))
    b = np.minimum(a * np.exp(rng.uniform(0.0, np.log(128.0), n)), 1.0)
    w = np.exp(rng.uniform(np.log(10.0), np.log(2e4), n))
    return encode_hertz_inputs(a, b, w, e_prime_mpa=effective_modulus_mpa(STEEL))


def _rate(fn, n: int, repeats: int = 3) -> tuple[float, float]:
    best_wall, best_cpu = np.inf, np.inf
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        best_wall = min(best_wall, time.perf_counter() - t0)
        best_cpu = min(best_cpu, time.process_time() - c0)
    return n / best_wall, n / best_cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller batches")
    args = ap.parse_args()
    n_scalar = 2_000 if args.quick else 20_000
    n_serial = 50 if args.quick else 300
    n_vec = 500_000 if args.quick else 4_000_000
    ac, bc, wc, ec = _codes(n_vec)
    sa, sb, sw = ac[:n_scalar].tolist(), bc[:n_scalar].tolist(), wc[:n_scalar].tolist()

    def scalar():
        for i in range(n_scalar):
            hertz_golden(sa[i], sb[i], sw[i], e_prime_code=ec)

    def serial():
        for i in range(n_serial):
            hertz_golden(sa[i], sb[i], sw[i], e_prime_code=ec, bit_serial=True)

    hertz_golden_array(ac[:10], bc[:10], wc[:10], e_prime_code=ec)     # JIT / cache load
    rows = [("scalar golden, floor-division path", *_rate(scalar, n_scalar)),
            ("scalar golden, bit-serial divider", *_rate(serial, n_serial, 1))]
    if HAVE_NUMBA:
        import numba
        threads = numba.get_num_threads()
        for nt in sorted({1, threads}):
            numba.set_num_threads(nt)
            label = f"vectorized golden (numba, {nt} thread{'s' if nt > 1 else ''})"
            rows.append((label, *_rate(
                lambda: hertz_golden_array(ac, bc, wc, e_prime_code=ec), n_vec)))
        numba.set_num_threads(threads)
    else:
        n_py = 2_000
        rows.append(("vectorized golden (no numba: plain Python)", *_rate(
            lambda: hertz_golden_array(ac[:n_py], bc[:n_py], wc[:n_py], e_prime_code=ec),
            n_py, 1)))
    print(f"stage D golden model, evaluations per second ({n_vec} vectorized)")
    print(f"{'model':<44}{'wall /s':>12}{'CPU /s':>12}{'vs board':>10}")
    board = BOARD_HZ / HERTZ_CYCLES
    for name, wall, cpu in rows:
        print(f"{name:<44}{wall:>12.3e}{cpu:>12.3e}{wall / board:>9.1f}x")
    print(f"{'datapath @ 50 MHz, 756 cycles (paper board)':<44}{board:>12.3e}"
          f"{'':>12}{1.0:>9.1f}x")
    print(f"{'C->D chain @ 50 MHz, 806 cycles':<44}{BOARD_HZ / CHAIN_CYCLES:>12.3e}")
    print("target: vectorized golden >= 1.0e+06 evaluations/s on 2 cores")


if __name__ == "__main__":
    main()
