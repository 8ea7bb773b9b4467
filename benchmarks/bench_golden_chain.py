"""Benchmark of the golden C -> D chain: evaluations per second against the 1e6/s target.

Inputs are the seeded C -> D stimulus of :mod:`gearcontact.preview.stimulus` (the
vectors the RTL tests and the golden-vector export use: plausible stencils, saddles,
whole-range codes, loads and E' over their envelopes). Rows:

* scalar golden (Python ints): the fit (``golden_fit``, ``math.isqrt`` fast path as in
  ``chain_golden``), stage D (``hertz_golden``) and the full chain (``chain_golden``);
* vectorized golden (numba kernels, ``--threads`` threads): the fit part
  (``golden_fit_batch``), the Hertz part (``hertz_golden_array`` on the fit's A-, B-)
  and the full chain (``chain_golden_batch``), on the whole stimulus mix and on its
  fully valid vectors only (every vector through the whole datapath).

Two rates per row: ``wall`` = vectors / elapsed time (best of ``--repeat``), and
``cpu`` = vectors x threads / process CPU time of that run, the rate the same work
would reach on ``threads`` otherwise idle cores -- the figure to read when the
machine is shared (the load average is printed). The target (docs/spec.md sec. 6, issue 2) is
>= 1e6 chain evaluations/s on 2 cores.

Run: ``python benchmarks/bench_golden_chain.py [--n-batch 1000000] [--n-scalar 2000]
[--threads 2] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from gearcontact.preview.chain import chain_golden, chain_golden_batch
from gearcontact.preview.fit.golden import golden_fit, golden_fit_batch
from gearcontact.preview.hertz.golden import hertz_golden
from gearcontact.preview.hertz.golden_vec import hertz_golden_array
from gearcontact.preview.stimulus import chain_stimulus

TARGET = 1e6   #: chain evaluations per second on 2 cores


def _measure(fn, count: int, threads: int, repeat: int) -> tuple[float, float]:
    """Best wall rate and best CPU-time rate (count x threads / CPU s) over repeats."""
    best_wall, best_cpu = 0.0, 0.0
    for _ in range(repeat):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        dt, dc = time.perf_counter() - t0, time.process_time() - c0
        best_wall = max(best_wall, count / dt)
        best_cpu = max(best_cpu, count * threads / dc if dc > 0 else float("inf"))
    return best_wall, best_cpu


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n-batch", type=int, default=1_000_000, help="vectors, batch paths")
    ap.add_argument("--n-scalar", type=int, default=2000, help="vectors, scalar paths")
    ap.add_argument("--threads", type=int, default=2, help="numba threads (cores)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per row (best kept)")
    ap.add_argument("--seed", type=int, default=0, help="stimulus seed")
    args = ap.parse_args(argv)

    import numba
    numba.set_num_threads(args.threads)
    st = chain_stimulus(args.n_batch, args.seed, corners=False)
    g, w, e = st.fields["gaps"], st.fields["W"], st.fields["e_prime"]
    chain_golden_batch(g[:64], w[:64], e_prime_code=e[:64])        # compile / load caches
    fit = golden_fit_batch(g)
    ok = np.flatnonzero(chain_golden_batch(g, w, e_prime_code=e).flags == 0)
    gv, wv, ev = g[ok], w[ok], e[ok]
    ns = min(args.n_scalar, len(g))
    rows_py = [[int(x) for x in row] for row in g[:ns]]
    ab = [(int(a), int(b)) for a, b in zip(fit.a_minus_codes[:ns], fit.b_minus_codes[:ns])]
    wl, el = [int(x) for x in w[:ns]], [int(x) for x in e[:ns]]

    t, r = args.threads, args.repeat
    res = {
        "scalar fit (golden_fit)": _measure(
            lambda: [golden_fit(x, bitwise=False) for x in rows_py], ns, 1, 1),
        "scalar Hertz (hertz_golden)": _measure(
            lambda: [hertz_golden(a, b, x, e_prime_code=y) for (a, b), x, y in
                     zip(ab, wl, el)], ns, 1, 1),
        "scalar chain (chain_golden)": _measure(
            lambda: [chain_golden(x, a, e_prime_code=b) for x, a, b in
                     zip(rows_py, wl, el)], ns, 1, 1),
        "vectorized fit (golden_fit_batch)": _measure(lambda: golden_fit_batch(g), len(g),
                                                      t, r),
        "vectorized Hertz (hertz_golden_array)": _measure(
            lambda: hertz_golden_array(fit.a_minus_codes, fit.b_minus_codes, w,
                                       e_prime_code=e), len(g), t, r),
        "vectorized chain, stimulus mix": _measure(
            lambda: chain_golden_batch(g, w, e_prime_code=e), len(g), t, r),
        "vectorized chain, valid vectors only": _measure(
            lambda: chain_golden_batch(gv, wv, e_prime_code=ev), len(gv), t, r),
    }
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"golden C -> D chain, {len(g)} stimulus vectors (seed {args.seed}, "
          f"{len(gv) / len(g):.0%} fully valid), scalar paths on {ns}; numba "
          f"{numba.__version__}, {t} threads ({numba.threading_layer()}), "
          f"{os.cpu_count()} CPUs, load average {load:.1f}")
    print(f"{'path':40s} {'wall /s':>11s} {'cpu /s':>11s} {'cpu/target':>10s}  "
          f"target {TARGET:.0e}/s")
    for name, (wall, cpu) in res.items():
        mark = "meets" if "chain" in name and "vectorized" in name and cpu >= TARGET else ""
        print(f"{name:40s} {wall:11.4g} {cpu:11.4g} {cpu / TARGET:10.3g}  {mark}")
    print("cpu /s = vectors x threads / process CPU seconds (scalar rows: 1 thread); "
          "wall /s is depressed when other processes share the cores.")


if __name__ == "__main__":
    main()
