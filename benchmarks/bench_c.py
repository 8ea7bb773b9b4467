"""Benchmark of the exported C library (``gearcontact export c``): ns per preview.

Exports the library into a temporary directory, builds it with its Makefile (gcc -O2)
and a small timing driver, and times every call individually (``clock_gettime``,
timer overhead subtracted) on the chain vectors' operands (seeded, corner cases
first): stage D alone and the C -> D chain, golden and fp64, Hamrock–Brewe. Prints
median, p99, max and p99/p50 per function beside the Python fp64 preview (0.92 us
median, docs/performance.md) and the published FPGA chain (806 cycles = 16 us at
50 MHz). Targets of issue 25: golden chain <= 200 ns median, fp64 <= 100 ns,
p99/p50 <= 1.5. Pin one core on a quiet machine for the targets
(``taskset -c 1 python benchmarks/bench_c.py``); on a shared machine the tail
includes other load.

Run: ``python benchmarks/bench_c.py [--vectors N]``.
"""

from __future__ import annotations

import argparse
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from gearcontact.export.c_library import export_c_library
from gearcontact.hw.vectors import vector_stimulus

DRIVER = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "gearcontact.h"

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

static void report(const char *name, int64_t *dt, long n, int64_t floor_ns)
{
    long i;
    for (i = 0; i < n; ++i)
        dt[i] -= floor_ns;
    qsort(dt, (size_t)n, sizeof dt[0], cmp);
    printf("%s %lld %lld %lld\n", name, (long long)dt[n / 2],
           (long long)dt[(long)(0.99 * (double)(n - 1))], (long long)dt[n - 1]);
}

int main(int argc, char **argv)
{
    long n, i, k;
    int32_t *gaps, *w, *e;
    double *gaps_mm, *w_n, *e_mpa;
    int64_t *dt, t0, floor_ns;
    uint32_t sink = 0u;
    FILE *fp = fopen(argv[1], "rb");
    (void)argc;
    if (!fp || fread(&n, sizeof n, 1, fp) != 1)
        return 2;
    gaps = malloc(sizeof *gaps * 49 * (size_t)n);
    w = malloc(sizeof *w * (size_t)n);
    e = malloc(sizeof *e * (size_t)n);
    gaps_mm = malloc(sizeof *gaps_mm * 49 * (size_t)n);
    w_n = malloc(sizeof *w_n * (size_t)n);
    e_mpa = malloc(sizeof *e_mpa * (size_t)n);
    dt = malloc(sizeof *dt * (size_t)n);
    if (fread(gaps, sizeof *gaps, 49 * (size_t)n, fp) != 49 * (size_t)n
        || fread(w, sizeof *w, (size_t)n, fp) != (size_t)n
        || fread(e, sizeof *e, (size_t)n, fp) != (size_t)n)
        return 2;
    for (i = 0; i < n; ++i) {
        for (k = 0; k < 49; ++k)
            gaps_mm[49 * i + k] = gaps[49 * i + k] / 65536.0;
        w_n[i] = w[i] / 256.0;
        e_mpa[i] = (double)e[i];
    }
    for (i = 0; i < n; ++i) {           /* the timer's own cost */
        t0 = now_ns();
        dt[i] = now_ns() - t0;
    }
    qsort(dt, (size_t)n, sizeof dt[0], cmp);
    floor_ns = dt[n / 2];
    printf("timer %lld\n", (long long)floor_ns);
#define TIME(NAME, CALL)                          \
    for (i = 0; i < n; ++i) {                     \
        t0 = now_ns();                            \
        CALL;                                     \
        dt[i] = now_ns() - t0;                    \
    }                                             \
    report(NAME, dt, n, floor_ns);
    for (k = 0; k < 2; ++k) {                     /* the first round warms the caches */
        TIME("golden_chain", sink ^= gc_chain_golden(gaps + 49 * i, w[i], e[i], 0).flags)
        TIME("fp64_chain", sink ^= gc_chain_fp64(gaps_mm + 49 * i, w_n[i], e_mpa[i], 0).hertz.flags)
        TIME("golden_fit", sink ^= gc_fit_golden(gaps + 49 * i).flags)
        TIME("golden_hertz", sink ^= gc_hertz_golden(40000 + (int32_t)(i % 1000) * 97, 900000, w[i], e[i], 0).flags)
        TIME("fp64_hertz", sink ^= gc_hertz_fp64(0.04 + (double)(i % 1000) * 1e-4, 0.9, w_n[i], e_mpa[i]).flags)
    }
    printf("sink %u\n", sink);
    return 0;
}
"""


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vectors", type=int, default=20000, help="random chain vectors")
    args = ap.parse_args(argv)
    stim = vector_stimulus("chain", args.vectors, 7)
    gaps = np.asarray(stim.fields["gaps"], np.int32)
    w = np.asarray(stim.fields["W"], np.int32)
    e = np.asarray(stim.fields["e_prime"], np.int32)
    with tempfile.TemporaryDirectory() as tmp:
        lib = Path(tmp) / "lib"
        export_c_library(lib)
        subprocess.run(["make", "-s", "-C", str(lib), "CC=gcc"], check=True)
        (lib / "bench.c").write_text(DRIVER)
        subprocess.run(["gcc", "-O2", "-std=c99", "-o", str(lib / "bench"),
                        str(lib / "bench.c"), str(lib / "libgearcontact.a"), "-lm",
                        f"-I{lib}"], check=True)
        data = Path(tmp) / "ops.bin"
        data.write_bytes(np.int64(len(w)).tobytes() + gaps.tobytes() + w.tobytes()
                         + e.tobytes())
        out = subprocess.run([str(lib / "bench"), str(data)], check=True,
                             capture_output=True, text=True).stdout.splitlines()
    rows = [ln.split() for ln in out if ln.split()[0] not in ("timer", "sink")]
    rows = rows[len(rows) // 2:]                  # the second (warm) round
    print(f"{len(w)} chain vectors (seed 7, corner cases first); timer overhead "
          f"{out[0].split()[1]} ns subtracted")
    print(f"{'function':<14} {'median ns':>10} {'p99 ns':>8} {'max ns':>9} {'p99/p50':>8}")
    for name, p50, p99, mx in rows:
        print(f"{name:<14} {int(p50):>10} {int(p99):>8} {int(mx):>9} "
              f"{int(p99) / max(int(p50), 1):>8.2f}")
    print("reference: Python fp64 preview 920 ns median (docs/performance.md); FPGA "
          "chain 806 cycles = 16,120 ns at 50 MHz; targets golden chain <= 200 ns, "
          "fp64 <= 100 ns, p99/p50 <= 1.5")


if __name__ == "__main__":
    main()
