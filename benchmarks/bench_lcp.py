"""Benchmark: LCP solvers on windowed Hertz problems (issue 4, solver targets).

Problems: steel paraboloid gaps ``h = A x^2 + B y^2`` (curvature ratio B/A = 1 and 10)
on a grid of +-2.5 contact semi-axes, with 8, 16 and 32 cells per semi-axis, i.e.
~200 (the paper's 196-cell size), ~800 and ~3,200 contacting cells. The solvers work
in their certified window; Tamaas (if importable) solves the same grid with its
non-periodic ("dcfft") Polonsky-Keer-Rey solver, cold (traction zeroed) each run, and
ContactMechanics (if importable) with its Polonsky-Keer CG on a free (non-periodic) FFT
half-space at its default tolerances. ASPHER ships as a C++ source build only and is
not driven.

Columns: best and median wall time over the repeats (ms), best CPU time of this
process (ms; the fairer figure on a shared machine), iterations, max pressure difference
vs the direct active-set solution (relative to p_max), and speed-up ratios measured in
this run: nnls / solver by best wall and by best CPU time, and tamaas / solver (wall).
``pk_cg no-pre`` is the plain Polonsky-Keer iteration; ``pk_cg warm`` starts from the
solution at 1.02 W (the previous mesh phase). The paper's NNLS reference costs 2005 ms
per mesh phase at 196 contacting cells. Targets: pk_cg <= 5 ms at ~800 cells and >= 300x
faster than the NNLS reference.

Usage::

    python benchmarks/bench_lcp.py            # nnls at ~200 and ~800 cells
    python benchmarks/bench_lcp.py --full     # also nnls at ~3,200 cells (minutes, ~1 GB)
    python benchmarks/bench_lcp.py --no-nnls  # skip the reference entirely
"""

from __future__ import annotations

import os

# Single-threaded BLAS before numpy loads: the dense solvers (active_set, nnls) run
# ~10x slower with OpenBLAS threads spinning on a shared 2-core machine, and one
# thread makes every solver's figure a single-core figure.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from gearcontact.analytic.hertz import exact_elliptic_hertz  # noqa: E402
from gearcontact.halfspace.grid import TangentGrid  # noqa: E402
from gearcontact.halfspace.lcp import solve_lcp  # noqa: E402
from gearcontact.materials import STEEL, reduced_modulus_mpa  # noqa: E402

E_STAR = reduced_modulus_mpa(STEEL, STEEL)
A_PER_MM = 1.0 / 40.0
LOAD_N = 1000.0
PAPER_NNLS_MS = 2005.0

try:  # optional peer, never a dependency
    import tamaas as tm
    tm.set_log_level(tm.LogLevel.error)
except ImportError:  # pragma: no cover - depends on the machine
    tm = None
try:  # optional peer: ContactMechanics (Pastewka group), Polonsky-Keer CG, free FFT
    import ContactMechanics as cm
    from ContactMechanics.Optimization import constrained_conjugate_gradients
    from ContactMechanics.Tools.Logger import quiet
    from SurfaceTopography import Topography
except ImportError:  # pragma: no cover - depends on the machine
    cm = None


def hertz_case(ratio: float, n: int, extent: float = 2.5):
    """(grid, gap, HertzContact) with n cells per semi-axis on +-extent semi-axes."""
    hz = exact_elliptic_hertz(A_PER_MM, ratio * A_PER_MM, LOAD_N, e_prime_mpa=2 * E_STAR)
    half = int(np.ceil(extent * n))
    grid = TangentGrid.centered(2 * half + 1, 2 * half + 1, dx_mm=hz.a_mm / n,
                                dy_mm=hz.b_mm / n)
    X, Y = grid.mesh()
    return grid, A_PER_MM * X ** 2 + ratio * A_PER_MM * Y ** 2, hz


def time_solver(fn, repeat: int):
    """Run ``fn`` ``repeat`` times; return (best wall ms, median wall ms, best CPU ms,
    last result). CPU time (this process) is the fairer figure on a shared machine."""
    times, cpu, out = [], [], None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        times.append(1e3 * (time.perf_counter() - t0))
        cpu.append(1e3 * (time.process_time() - c0))
    return min(times), statistics.median(times), min(cpu), out


def tamaas_solver(grid, gap):
    """A cold non-periodic Tamaas PKR solve on the same grid; returns a callable."""
    lx, ly = grid.nx * grid.dx_mm[0], grid.ny * grid.dy_mm[0]
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [ly, lx],
                                        [grid.ny, grid.nx])
    model.E, model.nu = E_STAR, 0.0  # Tamaas' E* = E / (1 - nu^2) = our E*
    tm.ModelFactory.registerNonPeriodic(model, "dcfft")
    solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(-gap), 1e-10)
    solver.setIntegralOperator("dcfft")

    def run():
        model.traction[...] = 0.0
        solver.solve(LOAD_N / (lx * ly))
        return np.array(model.traction)

    return run


def contactmechanics_solver(grid, gap):
    """A cold ContactMechanics PK-CG solve (free, non-periodic FFT half-space, its
    default tolerances) on the same grid; returns a callable giving pressure (MPa)."""
    nx, ny = grid.nx, grid.ny
    size = (nx * grid.dx_mm[0], ny * grid.dy_mm[0])
    substrate = cm.FreeFFTElasticHalfSpace((nx, ny), E_STAR, size)  # young = E*
    topography = Topography(np.ascontiguousarray(-gap.T), size)  # [i, j], x first
    area = grid.dx_mm[0] * grid.dy_mm[0]

    def run():
        res = constrained_conjugate_gradients(substrate, topography,
                                              external_force=LOAD_N, logger=quiet)
        return np.asarray(res.jac).T / area

    return run


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7, help="repeats for fast solvers")
    ap.add_argument("--full", action="store_true", help="nnls also at ~3,200 cells")
    ap.add_argument("--no-nnls", action="store_true", help="skip the NNLS reference")
    args = ap.parse_args(argv)

    print(f"# bench_lcp  python {platform.python_version()}  numpy {np.__version__}  "
          f"cpus {os.cpu_count()}  load avg {os.getloadavg()[0]:.2f}")
    print(f"# tamaas: {'%s (dcfft non-periodic PKR)' % tm.__version__ if tm else 'absent'}"
          f"; ContactMechanics: {'PK-CG, FreeFFT, default tol' if cm else 'absent'}"
          f"; ASPHER: absent (no Python package)")
    head = (f"{'case':<14}{'cells':>6} {'solver':<15}{'best ms':>9}{'median ms':>10}"
            f"{'cpu ms':>9}{'iters':>6}{'max|dp|/p0':>11}{'nnls/x':>8}{'cpu':>7}"
            f"{'tamaas/x':>9}")
    print(head)
    print("-" * len(head))
    for ratio in (1.0, 10.0):
        for n in (8, 16, 32):
            grid, gap, hz = hertz_case(ratio, n)
            rows = {}
            # the reference for max|dp|: direct active set (pk_cg at tol 1e-13 for n = 32
            # unless --full: the dense direct solve there takes minutes)
            ref = solve_lcp(gap, grid, LOAD_N, e_star_mpa=E_STAR, solver="active_set") \
                if n <= 16 or args.full else \
                solve_lcp(gap, grid, LOAD_N, e_star_mpa=E_STAR, tol=1e-13, max_iter=5000)
            ncells = ref.n_contact_cells
            rows["pk_cg"] = time_solver(
                lambda: solve_lcp(gap, grid, LOAD_N, e_star_mpa=E_STAR), args.repeat)
            prev = solve_lcp(gap, grid, 1.02 * LOAD_N, e_star_mpa=E_STAR)
            rows["pk_cg no-pre"] = time_solver(
                lambda: solve_lcp(gap, grid, LOAD_N, e_star_mpa=E_STAR, precondition=False),
                args.repeat)
            rows["pk_cg warm"] = time_solver(
                lambda: solve_lcp(gap, grid, LOAD_N, e_star_mpa=E_STAR, warm_start=prev),
                args.repeat)
            if n <= 16 or args.full:
                rows["active_set"] = time_solver(
                    lambda: solve_lcp(gap, grid, LOAD_N, e_star_mpa=E_STAR,
                                      solver="active_set"), max(1, args.repeat // 3))
            if not args.no_nnls and (n <= 16 or args.full):
                rows["nnls"] = time_solver(
                    lambda: solve_lcp(gap, grid, LOAD_N, e_star_mpa=E_STAR,
                                      solver="nnls"), 1)
            if tm is not None:
                rows["tamaas PKR"] = time_solver(tamaas_solver(grid, gap), args.repeat)
            if cm is not None:
                rows["contactmech"] = time_solver(contactmechanics_solver(grid, gap),
                                                  max(1, args.repeat // 3))
            t_nnls = rows["nnls"][0] if "nnls" in rows else None
            c_nnls = rows["nnls"][2] if "nnls" in rows else None
            t_tm = rows["tamaas PKR"][0] if "tamaas PKR" in rows else None
            for name, (best, med, cpu, res) in rows.items():
                p = res if isinstance(res, np.ndarray) else res.pressure_mpa
                iters = "" if isinstance(res, np.ndarray) else str(res.iterations)
                dp = np.abs(p - ref.pressure_mpa).max() / hz.p_max_mpa
                r_nnls = f"{t_nnls / best:8.0f}" if t_nnls else f"{'n/a':>8}"
                r_nnls += f"{c_nnls / cpu:7.0f}" if c_nnls and cpu > 0 else f"{'n/a':>7}"
                r_tm = f"{t_tm / best:9.2f}" if t_tm else f"{'n/a':>9}"
                print(f"{f'B/A={ratio:g} n={n}':<14}{ncells:>6} {name:<15}{best:9.2f}"
                      f"{med:10.2f}{cpu:9.2f}{iters:>6}{dp:11.1e}{r_nnls}{r_tm}")
            if n == 8:
                print(f"{'':<14}{'':>6} {'paper NNLS':<15}{PAPER_NNLS_MS:9.0f}   "
                      f"(196 cells; paper / our pk_cg best = "
                      f"{PAPER_NNLS_MS / rows['pk_cg'][0]:.0f}x)")
    print(f"# load avg at end {os.getloadavg()[0]:.2f} (shared machine: compare ratios, "
          "which are measured back to back)")


if __name__ == "__main__":
    main()
