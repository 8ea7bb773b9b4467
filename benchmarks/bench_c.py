"""Benchmark of the exported C: ns per preview (``gearcontact export c``) and ns per twin
step of the drivetrain FMU (``gearcontact export fmu --kind drivetrain``).

Exports the library into a temporary directory, builds it with its Makefile (gcc -O2,
the Makefile's default; ``--cflags`` replaces it, e.g. ``--cflags "-O2 -mavx2"`` for
the fp64 fit's lanes in one AVX register instead of two SSE2 ones: the same bits)
and a small timing driver, and times the calls on the chain vectors' operands (seeded,
corner cases first): stage D alone and the C -> D chain, golden and fp64,
Hamrock–Brewe. Prints median, p99, max and p99/p50 per function and method beside the
Python fp64 preview (0.92 us median, docs/performance.md) and the published FPGA chain
(806 cycles = 16 us at 50 MHz). The methods (a call takes ~40-90 ns, the timers' steps
are ~10 ns, so each says something else about the tail):

- ``call``: every call timed alone by ``clock_gettime`` (its median cost, ~20 ns,
  subtracted): the figures of the earlier rounds. Its read costs 20 or 30 ns (10 ns
  steps), which is in every figure: p99/p50 of a ~75 ns call moves by ~0.15 with it;
- ``tsc``: every call timed alone between ``lfence; rdtsc; lfence`` and ``rdtscp;
  lfence`` (x86-64 gcc/clang), the empty region's ticks (the same in every read)
  subtracted: the latency of one call from its start to its result, no overlap with
  its neighbours (hence a few ns above ``call``), still in the counter's steps (on the
  AMD EPYC KVM guest the TSC advances by 26 ticks = 10 ns: its median and p99 are
  multiples of 10 ns);
- ``batch``: 8 consecutive different vectors per TSC region, the region / 8: the
  timer's cost and step divided by 8, the calls may overlap as in a loop of previews;
  a p99 of means of 8 (an interruption diluted by 8, a slow vector too);
- ``vector``: each vector's mean over 16 sweeps timed as ``tsc``, those above twice its
  median left out (an interruption hits one sweep): the code's own spread over its
  inputs, the mean resolving below the counter's step (a call's start falls anywhere
  between two steps). With fixed operation counts this is the figure the code owns;
  ``call`` and ``tsc`` add what the machine adds (interruptions, a shared core).

Targets of issue 25: golden chain <= 200 ns median, fp64 <= 100 ns, p99/p50 <= 1.5.
Pin one core on a quiet machine for the targets (``taskset -c 1 python
benchmarks/bench_c.py``); on a shared machine the tail includes other load.

The twin step: the drivetrain FMU of s0003 is exported, its ``sources/`` built with a
timing driver into one program (gcc with the flags of the FMU's binary,
``gearcontact.export.fmu.FMU_CFLAGS``: -O2 -ffp-contract=off), and ``fmi3DoStep`` of
one 10 us step timed call by call (one
RK4 step with its 4 mesh evaluations of both flanks, the record and the finiteness
check; median, p99, max) and over a sustained run (mean; real-time factor = 10 us /
mean, which on a shared core includes the other jobs' time slices: hence also the
count of timed steps over 10 us, a missed real-time step, and the mean and factor of
the others), per backend, beside the compiled Python twin's step (numba,
``gearcontact twin``'s ``step_time_p50_us``). Target of issue 25: <= 0.5 us per step
(>= 20x real time at 10 us). The steps are also given by the pairs loaded after the
call (read outside the timed region): a call forms one preview per pair loaded at the
next step's start, so these are its slow and fast steps. The figures measured, round
by round and machine by machine: docs/export.md. The machine's state moves the
absolute figures more than the code does: compare alternated runs and instructions.

Instruction counts (``--instructions``, needs valgrind): the same calls once each
under ``valgrind --tool=callgrind``, instructions per call of each function (inclusive
of libm), and per ``fmi3DoStep`` of the step driver: independent of the machine's load,
unlike the nanoseconds.

The process pins itself to one core (``os.sched_setaffinity``, inherited by the
drivers; ``--cpu``) and prints the load average: figures taken under load say so.

Run: ``python benchmarks/bench_c.py [--vectors N] [--steps N] [--cpu K] [--curvatures
stencil|exact] [--pair CYLINDRICAL.toml] [--bending] [--twin-only | --previews-only]
[--instructions] [--cflags FLAGS]`` (``--pair``: the twin step of a cylindrical pair's
drivetrain FMU, its line law, instead of s0003's; ``--bending``: with the teeth's
bending).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import zipfile
import tempfile
from pathlib import Path

import numpy as np

from gearcontact.contract.qformat import STENCIL_GAP
from gearcontact.export.c_library import export_c_library
from gearcontact.hw.vectors import vector_stimulus

#: The operands of both drivers: ``n``, then the chain vectors' gap codes (49 per
#: vector, STENCIL_GAP Q(32,21)), W and E' codes as int32, read from the file ``path``,
#: and the same in physical units (mm, N, MPa) for the fp64 functions (the gaps scaled by
#: 2^-STENCIL_GAP.frac; a stale 2^-16 made the fp64 stencils' curvatures 32 times those
#: of the golden ones, and stage D refuse 68 % of them instead of 33 %).
OPERANDS = r"""
static long n;
static int32_t *gaps, *w, *e;
static double *gmm, *wn, *em;

static int read_operands(const char *path)
{
    long i, k;
    FILE *fp = fopen(path, "rb");
    if (!fp || fread(&n, sizeof n, 1, fp) != 1)
        return 0;
    gaps = malloc(sizeof *gaps * 49 * (size_t)n);
    w = malloc(sizeof *w * (size_t)n);
    e = malloc(sizeof *e * (size_t)n);
    gmm = malloc(sizeof *gmm * 49 * (size_t)n);
    wn = malloc(sizeof *wn * (size_t)n);
    em = malloc(sizeof *em * (size_t)n);
    if (fread(gaps, sizeof *gaps, 49 * (size_t)n, fp) != 49 * (size_t)n
        || fread(w, sizeof *w, (size_t)n, fp) != (size_t)n
        || fread(e, sizeof *e, (size_t)n, fp) != (size_t)n)
        return 0;
    fclose(fp);
    for (i = 0; i < n; ++i) {
        for (k = 0; k < 49; ++k)
            gmm[49 * i + k] = gaps[49 * i + k] / GAP_SCALE;
        wn[i] = w[i] / 256.0;
        em[i] = (double)e[i];
    }
    return 1;
}
"""
OPERANDS = (f"\n#define GAP_SCALE {float(1 << STENCIL_GAP.frac)!r}\n"  # STENCIL_GAP's 2^frac
            + OPERANDS)

#: the drivers' clock: headers, a monotonic ns clock, the sort order and the
#: timer's own median cost (timer_floor), shared by DRIVER and STEP_DRIVER.
TIMING = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

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

/* the median cost of the timer itself, over n reads, using dt as scratch */
static int64_t timer_floor(int64_t *dt, long n)
{
    long i;
    int64_t t0;
    for (i = 0; i < n; ++i) {
        t0 = now_ns();
        dt[i] = now_ns() - t0;
    }
    qsort(dt, (size_t)n, sizeof dt[0], cmp);
    return dt[n / 2];
}
"""

#: the time-stamp counter (x86-64 gcc/clang): ``tsc_begin`` (lfence; rdtsc; lfence: the
#: read waits for everything before it and nothing after it starts before it) and
#: ``tsc_end`` (rdtscp, which waits for every earlier instruction to have executed, then
#: lfence), ~50 cycles between the two with nothing timed and the same every time on
#: this machine, where clock_gettime's ~20 ns read moves in 10 ns steps; the counter's
#: rate (invariant TSC) calibrated against CLOCK_MONOTONIC over 50 ms.
TSC = r"""
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <x86intrin.h>
#define HAVE_TSC 1
static inline uint64_t tsc_begin(void)
{
    uint64_t t;
    _mm_lfence();
    t = __rdtsc();
    _mm_lfence();
    return t;
}

static inline uint64_t tsc_end(void)
{
    unsigned aux;
    uint64_t t = __rdtscp(&aux);
    _mm_lfence();
    return t;
}

/* TSC ticks per ns, against CLOCK_MONOTONIC over 50 ms */
static double tsc_per_ns(void)
{
    int64_t t0 = now_ns(), t1;
    uint64_t c0 = tsc_begin();
    while ((t1 = now_ns()) - t0 < 50000000)
        ;
    return (double)(tsc_begin() - c0) / (double)(t1 - t0);
}

/* the median ticks of an empty timed region, over n reads, using dt as scratch */
static int64_t tsc_floor(int64_t *dt, long n)
{
    long i;
    uint64_t t0;
    for (i = 0; i < n; ++i) {
        t0 = tsc_begin();
        dt[i] = (int64_t)(tsc_end() - t0);
    }
    qsort(dt, (size_t)n, sizeof dt[0], cmp);
    return dt[n / 2];
}
#endif
"""

DRIVER = TIMING + TSC + r"""
#include "gearcontact.h"
""" + OPERANDS + r"""
#define SWEEPS 16               /* sweeps of the per-vector method */
#define BATCH 8                 /* different vectors per timed region of the batch method */

/* p50, p99 and max of the n values x (sorted in place), in ns: x / scale */
static void report(const char *method, const char *name, int64_t *x, long n, double scale)
{
    qsort(x, (size_t)n, sizeof x[0], cmp);
    printf("%s %s %.1f %.1f %.1f\n", method, name, (double)x[n / 2] / scale,
           (double)x[(long)(0.99 * (double)(n - 1))] / scale, (double)x[n - 1] / scale);
}

/* SWEEPS times the mean of a vector's SWEEPS timings x (sorted in place) without those
 * above twice their median (an interruption in that sweep): the TSC advances in steps
 * (26 ticks = 10 ns on the AMD EPYC KVM guest), and a call's start falls anywhere
 * between two steps, so the mean of its timings resolves below a step where their
 * median cannot */
static int64_t vector_mean(int64_t *x)
{
    int64_t sum = 0, m;
    long s, c = 0;
    qsort(x, SWEEPS, sizeof x[0], cmp);
    m = x[SWEEPS / 2];
    for (s = 0; s < SWEEPS; ++s)
        if (x[s] <= 2 * m) {
            sum += x[s];
            ++c;
        }
    return sum * SWEEPS / c;
}

int main(int argc, char **argv)
{
    long i, j, k, s;
    int64_t *dt, *sw, t0, floor_ns;
    uint32_t sink = 0u;
#ifdef HAVE_TSC
    uint64_t c0;
    int64_t floor_tsc;
    double tpn;
#endif
    if (argc < 2 || !read_operands(argv[1]))
        return 2;
    dt = malloc(sizeof *dt * (size_t)n);
    sw = malloc(sizeof *sw * (size_t)n * SWEEPS);
    floor_ns = timer_floor(dt, n);
    printf("timer %lld\n", (long long)floor_ns);
#ifdef HAVE_TSC
    tpn = tsc_per_ns();
    floor_tsc = tsc_floor(dt, n);
    printf("tsc %.4f %lld\n", tpn, (long long)floor_tsc);
#endif
/* the four methods (the benchmark's docstring says what each measures): "call", every
 * call alone by clock_gettime, its median cost subtracted; "tsc", every call alone by
 * the serialised TSC, its empty region subtracted; "batch", BATCH consecutive different
 * vectors per region, per call; "vector", each vector's mean over SWEEPS sweeps
 * timed as "tsc", interruptions left out (vector_mean) */
#define CLOCKED(NAME, CALL)                                  \
    for (i = 0; i < n; ++i) {                                \
        t0 = now_ns();                                       \
        CALL;                                                \
        dt[i] = now_ns() - t0 - floor_ns;                    \
    }                                                        \
    report("call", NAME, dt, n, 1.0);
#ifdef HAVE_TSC
#define TSC_TIMED(NAME, CALL)                                \
    for (i = 0; i < n; ++i) {                                \
        c0 = tsc_begin();                                    \
        CALL;                                                \
        dt[i] = (int64_t)(tsc_end() - c0) - floor_tsc;       \
    }                                                        \
    report("tsc", NAME, dt, n, tpn);                         \
    for (j = 0; j + BATCH <= n; j += BATCH) {                \
        c0 = tsc_begin();                                    \
        for (i = j; i < j + BATCH; ++i)                      \
            CALL;                                            \
        dt[j / BATCH] = (int64_t)(tsc_end() - c0) - floor_tsc; \
    }                                                        \
    report("batch", NAME, dt, n / BATCH, tpn * BATCH);       \
    for (s = 0; s < SWEEPS; ++s)                             \
        for (i = 0; i < n; ++i) {                            \
            c0 = tsc_begin();                                \
            CALL;                                            \
            sw[SWEEPS * i + s] = (int64_t)(tsc_end() - c0) - floor_tsc; \
        }                                                    \
    for (i = 0; i < n; ++i)                                  \
        dt[i] = vector_mean(sw + SWEEPS * i);                \
    report("vector", NAME, dt, n, tpn * SWEEPS);
#else
#define TSC_TIMED(NAME, CALL)
#endif
#define TIME(NAME, CALL) CLOCKED(NAME, CALL) TSC_TIMED(NAME, CALL)
    for (k = 0; k < 2; ++k) {                     /* the first round warms the caches */
        printf("round %ld\n", k);
        TIME("golden_chain", sink ^= gc_chain_golden(gaps + 49 * i, w[i], e[i], 0).flags)
        TIME("fp64_chain", sink ^= gc_chain_fp64(gmm + 49 * i, wn[i], em[i], 0).hertz.flags)
        TIME("golden_fit", sink ^= gc_fit_golden(gaps + 49 * i).flags)
        TIME("golden_hertz", sink ^= gc_hertz_golden(40000 + (int32_t)(i % 1000) * 97, 900000, w[i], e[i], 0).flags)
        TIME("fp64_hertz", sink ^= gc_hertz_fp64(0.04 + (double)(i % 1000) * 1e-4, 0.9, wn[i], em[i]).flags)
    }
    printf("sink %u\n", sink);
    return 0;
}
"""


#: Instruction-count driver: each function once per operand, in its own loop (callgrind
#: reports each loop's instructions inclusive of what it calls).
COUNT_DRIVER = r"""
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include "gearcontact.h"
""" + OPERANDS + r"""
static uint32_t sink;
#define LOOP(NAME, CALL) \
    __attribute__((noinline)) static void loop_##NAME(void) \
    { long i; for (i = 0; i < n; ++i) CALL; }
LOOP(golden_chain, sink ^= gc_chain_golden(gaps + 49 * i, w[i], e[i], 0).flags)
LOOP(fp64_chain, sink ^= gc_chain_fp64(gmm + 49 * i, wn[i], em[i], 0).hertz.flags)
LOOP(golden_fit, sink ^= gc_fit_golden(gaps + 49 * i).flags)
LOOP(golden_hertz, sink ^= gc_hertz_golden(40000 + (int32_t)(i % 1000) * 97, 900000, w[i], e[i], 0).flags)
LOOP(fp64_fit, sink ^= (uint32_t)gc_fit_fp64(gmm + 49 * i).elliptic)
LOOP(fp64_hertz, sink ^= gc_hertz_fp64(0.04 + (double)(i % 1000) * 1e-4, 0.9, wn[i], em[i]).flags)

int main(int argc, char **argv)
{
    if (argc < 2 || !read_operands(argv[1]))
        return 2;
    loop_golden_chain(); loop_fp64_chain(); loop_golden_fit(); loop_golden_hertz();
    loop_fp64_fit(); loop_fp64_hertz();
    printf("sink %u\n", sink);
    return 0;
}
"""


STEP_DRIVER = TIMING + r"""
#include "fmi3Functions.h"

static void say(fmi3InstanceEnvironment env, fmi3Status s, fmi3String c, fmi3String msg)
{
    (void)env; (void)s; (void)c;
    fprintf(stderr, "%s\n", msg);
}

int main(int argc, char **argv)
{
    long n = atol(argv[1]), i;
    fmi3Int64 backend = atol(argv[2]);
    fmi3Float64 step_us = 10.0, h = 1e-5, t = 0.0;
    fmi3ValueReference vr_backend = VR_BACKEND, vr_step = VR_STEP_US, vr_np = VR_PAIRS_LOADED;
    fmi3Boolean ev, term, early;
    fmi3Float64 last;
    fmi3Int32 pairs;
    int64_t *dt = malloc(sizeof *dt * (size_t)n), *grp = malloc(sizeof *grp * (size_t)n), t0,
        floor_ns, total, within;
    long late;
    int *np_ = malloc(sizeof *np_ * (size_t)n), c;
    fmi3Instance m = fmi3InstantiateCoSimulation("bench", NULL, NULL, fmi3False, fmi3False,
        fmi3False, fmi3False, NULL, 0, NULL, say, NULL);
    (void)argc;
    if (!m || fmi3SetInt64(m, &vr_backend, 1, &backend, 1) != fmi3OK
        || fmi3SetFloat64(m, &vr_step, 1, &step_us, 1) != fmi3OK
        || fmi3EnterInitializationMode(m, fmi3False, 0.0, 0.0, fmi3False, 0.0) != fmi3OK
        || fmi3ExitInitializationMode(m) != fmi3OK)
        return 2;
    floor_ns = timer_floor(dt, n);
    for (i = 0; i < n; ++i, t += h)     /* warm-up */
        fmi3DoStep(m, t, h, fmi3True, &ev, &term, &early, &last);
    for (i = 0; i < n; ++i, t += h) {
        t0 = now_ns();
        if (fmi3DoStep(m, t, h, fmi3True, &ev, &term, &early, &last) != fmi3OK)
            return 3;
        dt[i] = now_ns() - t0 - floor_ns;
        /* the pairs loaded at the next step's start: the previews this call formed */
        fmi3GetInt32(m, &vr_np, 1, &pairs, 1);
        np_[i] = (int)pairs;
    }
    t0 = now_ns();
    for (i = 0; i < n; ++i, t += h)
        if (fmi3DoStep(m, t, h, fmi3True, &ev, &term, &early, &last) != fmi3OK)
            return 3;
    total = now_ns() - t0;
    for (c = 0; c <= 16; ++c) {         /* the steps by pairs loaded */
        long g = 0;
        for (i = 0; i < n; ++i)
            if (np_[i] == c)
                grp[g++] = dt[i];
        if (g == 0)
            continue;
        qsort(grp, (size_t)g, sizeof grp[0], cmp);
        printf("pairs %d %ld %lld %lld\n", c, g, (long long)grp[g / 2],
               (long long)grp[(long)(0.99 * (double)(g - 1))]);
    }
    for (i = 0, late = 0, within = 0; i < n; ++i) {   /* over the 10 us of a step */
        if (dt[i] > 10000)
            ++late;
        else
            within += dt[i];
    }
    qsort(dt, (size_t)n, sizeof dt[0], cmp);
    printf("%lld %lld %lld %.1f %lld %ld %.1f\n", (long long)dt[n / 2],
           (long long)dt[(long)(0.99 * (double)(n - 1))], (long long)dt[n - 1],
           (double)total / (double)n, (long long)floor_ns, late,
           (double)within / (double)(n - late));
    fmi3FreeInstance(m);
    return 0;
}
"""


def _pin(cpu: int | None) -> str:
    """Pin this process (and the drivers it starts) to one core; a note saying which."""
    if not hasattr(os, "sched_setaffinity"):
        return "not pinned (no sched_setaffinity)"
    cpus = sorted(os.sched_getaffinity(0))
    cpu = cpus[-1] if cpu is None else cpu
    os.sched_setaffinity(0, {cpu})
    return f"pinned to CPU {cpu} of {cpus}"


def _step_instructions(exe: Path, code: int, steps: int = 2000) -> float:
    """Instructions per ``fmi3DoStep`` of the step driver ``exe`` (backend ``code``)
    under callgrind, inclusive of libm: the driver runs 3 x ``steps`` steps."""
    out = exe.parent / f"callgrind.step.{code}"
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", str(exe),
                    str(steps), str(code)], check=True, capture_output=True)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", str(out)], check=True,
                          capture_output=True, text=True).stdout
    m = re.search(r"^\s*([\d,]+) .*?:fmi3DoStep ", text, re.M)
    return int(m.group(1).replace(",", "")) / (3 * steps) if m else float("nan")


def bench_twin_step(steps: int, phases: int, curvatures: str,
                    instructions: bool = False, pair_file: str | None = None,
                    bending: bool = False) -> None:
    """ns per twin step of the drivetrain FMU's C (module docstring); with
    ``instructions`` also the instructions per step under callgrind. ``pair_file``: a
    cylindrical pair's TOML instead of s0003 (its twin's line law, rigid teeth; the
    curvature source is the line chain's). ``bending``: the teeth's bending in series
    (``--bending`` of the export and the twin)."""
    from fmpy import __file__ as fmpy_file

    from gearcontact.export.fmu import FMU_CFLAGS
    from gearcontact.export.fmu_drivetrain import (DRIVETRAIN_VARIABLES,
                                                   drivetrain_fmu_model,
                                                   export_drivetrain_fmu)
    from gearcontact.geometry.pair import CYLINDRICAL, load_pair
    from gearcontact.tca.synthesis import prepare_pair
    from gearcontact.twin.cylindrical import cylindrical_model
    from gearcontact.twin.simulate import simulate

    if pair_file is None:
        prepared = prepare_pair("s0003")
        pair, side, label = prepared.pair, prepared.side, "s0003"
    else:
        pair = load_pair(pair_file, kinds=(CYLINDRICAL,))
        side, label, curvatures = "drive", pair.name, "line"
    vr = {v[0]: v[1] for v in DRIVETRAIN_VARIABLES}
    with tempfile.TemporaryDirectory() as tmp:
        fmu = export_drivetrain_fmu(pair, tmp, pair_name=label, side=side, phases=phases,
                                    curvatures=None if pair_file else curvatures,
                                    bending=bending)
        src = Path(tmp) / "src"
        with zipfile.ZipFile(fmu.fmu_path) as z:
            for name in z.namelist():
                if name.startswith("sources/") and name.endswith((".c", ".h")):
                    (src / Path(name).name).parent.mkdir(exist_ok=True)
                    (src / Path(name).name).write_bytes(z.read(name))
        (src / "bench_step.c").write_text(STEP_DRIVER)
        exe = Path(tmp) / "bench_step"
        subprocess.run(["gcc", *FMU_CFLAGS,
                        f"-DVR_BACKEND={vr['backend']}", f"-DVR_STEP_US={vr['step_us']}",
                        f"-DVR_PAIRS_LOADED={vr['pairs_loaded']}",
                        "-I", str(src), "-I", str(Path(fmpy_file).parent / "c-code"),
                        "-o", str(exe), *sorted(str(p) for p in src.glob("*.c")), "-lm"],
                       check=True)
        print(f"\ntwin step of the drivetrain FMU ({label}, curvatures {curvatures}"
              f"{', bending' if bending else ''}, "
              f"{phases} phases, 3000 rpm, "
              f"64.5 N.m, 10 us; {steps} steps timed one by one, {steps} sustained)")
        print(f"{'backend':<8} {'median ns':>10} {'p99 ns':>8} {'max ns':>9} "
              f"{'p99/p50':>8} {'mean ns':>8} {'RTF @10us':>10}")
        groups = {}
        for name, code in (("fp64", 0), ("golden", 1)):
            lines = subprocess.run([str(exe), str(steps), str(code)], check=True,
                                   capture_output=True, text=True).stdout.splitlines()
            groups[name] = [x.split()[1:] for x in lines if x.startswith("pairs ")]
            out = lines[-1].split()
            p50, p99, mx, mean = int(out[0]), int(out[1]), int(out[2]), float(out[3])
            late, within = int(out[5]), float(out[6])
            print(f"{name:<8} {p50:>10} {p99:>8} {mx:>9} {p99 / max(p50, 1):>8.2f} "
                  f"{mean:>8.1f} {1e4 / mean:>9.1f}x   (timer {out[4]} ns subtracted; "
                  f"{late} timed steps over 10 us ({100 * late / steps:.3f} %), the mean "
                  f"of the others {within:.1f} ns, {1e4 / within:.1f}x)")
        # which steps are slow: a call forms one preview per pair loaded at the next
        # step's start (and one per pair a later stage closes)
        print("by pairs loaded (the previews a step forms): " + "; ".join(
            f"{name} " + ", ".join(f"{c} pairs {100 * int(g) / steps:.1f} % of steps "
                                   f"p50 {p50} p99 {p99} ns" for c, g, p50, p99 in rows)
            for name, rows in groups.items()))
        if instructions and shutil.which("valgrind") and shutil.which("callgrind_annotate"):
            print("instructions per step (callgrind, 6,000 steps, inclusive of libm; load "
                  "independent): " + ", ".join(f"{name} {_step_instructions(exe, code):,.0f}"
                                               for name, code in (("fp64", 0), ("golden", 1))))
    if pair_file is None:
        model = drivetrain_fmu_model(pair, side=side, phases=phases, torque_nm=64.5,
                                     curvatures=curvatures, bending=bending)
    else:
        model = cylindrical_model(pair, torque_nm=64.5, phases=phases, bending=bending)
    res = simulate(model, speed_rpm=3000.0, duration_s=1e-5 * steps, step_s=1e-5)
    print(f"numba twin (gearcontact twin, reference, curvatures {curvatures}): step "
          f"{1e3 * res.timings['step_time_p50_us']:.0f} ns p50 of 256-step blocks, "
          f"{1e3 * res.timings['step_time_p99_us']:.0f} ns p99, RTF "
          f"{res.timings['real_time_factor']:.1f}x; target <= 500 ns per step (>= 20x)")


def _instructions(lib: Path, data: Path, n: int, cflags: str) -> None:
    """Instructions per call of each timed function, under callgrind (module docstring)."""
    if shutil.which("valgrind") is None or shutil.which("callgrind_annotate") is None:
        print("instructions: valgrind not installed, skipped")
        return
    (lib / "count.c").write_text(COUNT_DRIVER)
    exe, out = lib / "count", lib / "callgrind.out"
    subprocess.run(["gcc", "-O2", "-std=gnu99", "-o", str(exe), str(lib / "count.c"),
                    str(lib / "build" / "libgearcontact.a"), "-lm", f"-I{lib}"], check=True)
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", str(exe),
                    str(data)], check=True, capture_output=True)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", str(out)], check=True,
                          capture_output=True, text=True).stdout
    counts = {m.group(2): int(m.group(1).replace(",", "")) / n
              for m in re.finditer(r"^\s*([\d,]+) .*?:loop_(\w+) ", text, re.M)}
    print(f"instructions per call (callgrind, {n} operands, library gcc {cflags}; load "
          "independent):")
    for name in ("golden_chain", "fp64_chain", "golden_fit", "golden_hertz", "fp64_fit",
                 "fp64_hertz"):
        print(f"  {name:<14} {counts.get(name, float('nan')):>8.0f}")


#: the driver's timing methods and what each measures (module docstring)
METHODS = {
    "call": "per call, clock_gettime (every call timed alone; the timer's ~20 ns read, "
            "moving in ~10 ns steps, is in each figure's noise):",
    "tsc": "per call, serialised TSC (every call timed alone, lfence/rdtsc .. rdtscp/"
           "lfence: the latency of one call, the empty region's ticks subtracted):",
    "batch": "per call in batches of 8 different consecutive vectors (one TSC region "
             "per batch / 8: timer cost and granularity / 8, calls may overlap; the "
             "tail of a mean of 8, interruptions diluted by 8):",
    "vector": "per vector, the mean of its 16 serialised-TSC timings, those above twice "
              "its median left out (the code's own spread over its inputs, below the "
              "TSC's step; interruptions, which hit a vector in one sweep, removed):",
}


def bench_previews(vectors: int, instructions: bool = False, cflags: str = "-O2") -> None:
    """ns per preview of the C library built with ``CFLAGS=cflags`` (module docstring)."""
    stim = vector_stimulus("chain", vectors, 7)
    gaps = np.asarray(stim.fields["gaps"], np.int32)
    w = np.asarray(stim.fields["W"], np.int32)
    e = np.asarray(stim.fields["e_prime"], np.int32)
    with tempfile.TemporaryDirectory() as tmp:
        lib = Path(tmp) / "lib"
        export_c_library(lib)
        subprocess.run(["make", "-s", "-C", str(lib), "CC=gcc", f"CFLAGS={cflags}"],
                       check=True)
        (lib / "bench.c").write_text(DRIVER)
        subprocess.run(["gcc", "-O2", "-std=c99", "-o", str(lib / "bench"),
                        str(lib / "bench.c"), str(lib / "build" / "libgearcontact.a"), "-lm",
                        f"-I{lib}"], check=True)
        data = Path(tmp) / "ops.bin"
        data.write_bytes(np.int64(len(w)).tobytes() + gaps.tobytes() + w.tobytes()
                         + e.tobytes())
        out = subprocess.run([str(lib / "bench"), str(data)], check=True,
                             capture_output=True, text=True).stdout.splitlines()
        warm = out[out.index("round 1") + 1:]        # the second (warm) round
        rows = {}
        for ln in warm:
            method, name, *fig = ln.split()
            if method in METHODS:
                rows.setdefault(method, []).append((name, *map(float, fig)))
        tsc = next((ln.split()[1:] for ln in out if ln.startswith("tsc ")), None)
        print(f"{len(w)} chain vectors (seed 7, corner cases first); library CFLAGS "
              f"{cflags}; clock_gettime's median {out[0].split()[1]} ns subtracted"
              + (f"; TSC {float(tsc[0]):.4f} GHz, its empty region {tsc[1]} ticks "
                 "subtracted" if tsc else "; no TSC (not x86-64 gcc/clang)"))
        for method, title in METHODS.items():
            if method not in rows:
                continue
            print(title)
            print(f"  {'function':<14} {'median ns':>10} {'p99 ns':>8} {'max ns':>9} "
                  f"{'p99/p50':>8}")
            for name, p50, p99, mx in rows[method]:
                print(f"  {name:<14} {p50:>10.1f} {p99:>8.1f} {mx:>9.1f} "
                      f"{p99 / max(p50, 1.0):>8.2f}")
        print("reference: Python fp64 preview 920 ns median (docs/performance.md); FPGA "
              "chain 806 cycles = 16,120 ns at 50 MHz; targets golden chain <= 200 ns, "
              "fp64 <= 100 ns, p99/p50 <= 1.5")
        if instructions:
            _instructions(lib, data, len(w), cflags)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--vectors", type=int, default=20000, help="random chain vectors")
    ap.add_argument("--steps", type=int, default=200000, help="twin steps timed")
    ap.add_argument("--phases", type=int, default=61, help="TCA phases of the twin's table")
    ap.add_argument("--cpu", type=int, default=None, help="core to pin (default: the last)")
    ap.add_argument("--curvatures", default="stencil", choices=("stencil", "exact"),
                    help="the twin's curvature source (default stencil, the twin's)")
    ap.add_argument("--pair", default=None,
                    help="twin step: a cylindrical pair's TOML instead of s0003 (the line "
                         "law's drivetrain FMU, e.g. examples/ev_reducer_helical_23x67.toml)")
    ap.add_argument("--bending", action="store_true",
                    help="twin step: the teeth's bending in series (the export's --bending)")
    ap.add_argument("--twin-only", action="store_true", help="skip the preview timings")
    ap.add_argument("--previews-only", action="store_true", help="skip the twin step")
    ap.add_argument("--cflags", default="-O2",
                    help="the library's CFLAGS (default -O2, its Makefile's), e.g. "
                         "'-O2 -mavx2'")
    ap.add_argument("--instructions", action="store_true",
                    help="also count instructions per call under valgrind's callgrind")
    args = ap.parse_args(argv)
    print(_pin(args.cpu) + "; load average %.2f %.2f %.2f" % os.getloadavg())
    if not args.twin_only:
        bench_previews(args.vectors, args.instructions, args.cflags)
    if not args.previews_only:
        bench_twin_step(args.steps, args.phases, args.curvatures, args.instructions,
                        args.pair, args.bending)
    print("load average after: %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    main()
