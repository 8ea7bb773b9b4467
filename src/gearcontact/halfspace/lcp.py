"""Normal-contact linear complementarity problem (LCP) with a load constraint.

For nodal loads ``w`` (N) on the cells of a tangent-plane grid, gap ``h`` (mm) and
rigid approach ``delta`` (mm), find

    s = C w + h - delta * 1 >= 0,   w >= 0,   w . s = 0,   sum(w) = W,

with ``C`` the Boussinesq (Love) influence operator of :mod:`.influence`. Three solvers
return the contact family's one result type, :class:`.result.ContactResult`:

``"pk_cg"`` (fast)
    Polonsky & Keer's constrained conjugate gradient (Wear 231 (1999) 206-219) with the
    zero-padded FFT operator, on uniform grids, preconditioned by the inverse
    Boussinesq symbol (Vollebregt 2014), warm-startable from a previous pressure
    (:mod:`.constrained_cg`, the package's one iteration, on a one-block stack).
``"nnls"`` (reference)
    The Lawson & Hanson (1974) NNLS active-set algorithm (``scipy.optimize.nnls``) on
    the Cholesky factor ``C = L L^T`` -- ``min ||L^T w - L^-1 (delta - h)||, w >= 0`` has
    exactly the LCP's KKT conditions for fixed ``delta`` -- closed by a safeguarded root
    find on ``delta`` such that ``sum(w(delta)) = W`` (monotone, piecewise linear; each
    step is the exact bordered solve on the current NNLS support).
``"active_set"`` (direct)
    Block active-set iteration; each step solves the active block with the bordered
    load constraint by Cholesky (LU for the non-symmetric collocation matrices of
    non-uniform grids). For small/dense problems and non-convolution operators.

Windowing (all solvers)
    A cell in contact has ``h = delta - u <= delta`` (``u >= 0``), so the solvers work on
    the window ``{h <= b}`` (its bounding box for FFT). If the window's solution has
    ``delta <= b`` it is the solution on the whole grid (cells outside have
    ``s >= h - delta > 0``); otherwise ``b`` grows and the solve is repeated, warm.
    ``b`` starts from a flat-punch estimate of the approach (rigid circular punch,
    Johnson 1985 ch. 3).

References
----------
I. A. Polonsky, L. M. Keer, "A numerical method for solving rough contact problems based
on the multi-level multi-summation and conjugate gradient techniques", Wear 231 (1999)
206-219.
E. A. H. Vollebregt, J. Comput. Phys. 257 (2014) 333-351 (FFT-based preconditioner).
C. L. Lawson, R. J. Hanson, *Solving Least Squares Problems*, Prentice-Hall, 1974, ch. 23.
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985.
"""

from __future__ import annotations

import time

import numpy as np
from scipy import linalg, optimize

from ..deprecation import moved_names
from ..errors import CheckFailed
from ..materials import STEEL, Material, reduced_modulus_mpa
from ..validation import InputRangeError, check_positive
from .ellipse import warn_if_coarse
from .grid import TangentGrid
from .compliance import BlockCompliance
from .constrained_cg import constrained_cg
from .influence import dense_influence_matrix
from .result import ContactResult, SolveStatus

__all__ = ["LcpConvergenceError", "bordered_active_set", "solve_lcp", "SOLVERS",
           "resolve_e_star", "warm_up"]

#: Deprecated for one release: the LCP's result is the family's :class:`.result.ContactResult`.
__getattr__ = moved_names(__name__, {"LcpResult": "gearcontact.halfspace.result:ContactResult"})

#: Solver names accepted by :func:`solve_lcp`.
SOLVERS = ("pk_cg", "nnls", "active_set")

_DEFAULT_MAX_ITER = {"pk_cg": 2000, "nnls": 200, "active_set": 200}
#: Window bound = hmin + this factor x (flat-punch estimate of the approach).
_WINDOW_FACTOR = 2.0
#: Window growth when a window's approach exceeds its bound.
_WINDOW_GROWTH = 1.5
_MAX_WINDOWS = 8


class LcpConvergenceError(CheckFailed, RuntimeError):
    """An LCP solve did not converge (a failed check, exit 4); ``.result`` holds the
    (unconverged) result."""

    def __init__(self, result: ContactResult):
        self.result = result
        super().__init__(f"{result.solver}: {result.status}: {result.message}")


def resolve_e_star(materials=None, e_star_mpa=None) -> float:
    """E* in MPa from ``e_star_mpa``, a :class:`Material`, or a pair of them.

    Defaults to steel on steel (:data:`gearcontact.materials.STEEL`) when both are None.
    """
    if e_star_mpa is not None:
        if materials is not None:
            raise InputRangeError("materials", materials, "None when e_star_mpa is given")
        return check_positive("e_star_mpa", e_star_mpa)
    if materials is None:
        return reduced_modulus_mpa(STEEL, STEEL)
    if isinstance(materials, Material):
        return reduced_modulus_mpa(materials, materials)
    m1, m2 = materials
    return reduced_modulus_mpa(m1, m2)


# ---------------------------------------------------------------------------- kernels
def _bordered_solve(c_aa: np.ndarray, h_a: np.ndarray, load_n: float, symmetric: bool
                    ) -> tuple[np.ndarray, float]:
    """Solve ``C_AA w - delta 1 = -h_A, 1.w = W`` (Cholesky, or LU if non-symmetric)."""
    rhs = np.column_stack([np.ones_like(h_a), h_a])
    if symmetric:
        x = linalg.cho_solve(linalg.cho_factor(c_aa, lower=True, check_finite=False),
                             rhs, check_finite=False)
    else:
        x = linalg.lu_solve(linalg.lu_factor(c_aa, check_finite=False), rhs,
                            check_finite=False)
    delta = (load_n + x[:, 1].sum()) / x[:, 0].sum()
    return delta * x[:, 0] - x[:, 1], float(delta)


def _nnls_reference(c: np.ndarray, h: np.ndarray, load_n: float, max_iter: int,
                    delta_guess: float) -> tuple[np.ndarray, float, int, bool, str]:
    """Lawson-Hanson NNLS on the Cholesky factor, closed by a safeguarded root find.

    ``sum(w(delta))`` is continuous, non-decreasing and linear on each NNLS support
    ``S`` (slope ``1' C_SS^-1 1``), so the step to the next ``delta`` is the exact
    bordered solve on the current support (Newton on a piecewise-linear function),
    safeguarded by bisection inside the bracket ``[lo, hi]``. It stops when the support
    repeats, where the bordered solution is the exact LCP solution.
    """
    lower = linalg.cholesky(c, lower=True, check_finite=False)
    v1 = linalg.solve_triangular(lower, np.ones_like(h), lower=True, check_finite=False)
    vh = linalg.solve_triangular(lower, h, lower=True, check_finite=False)
    a = lower.T.copy()
    lo, hi = float(h.min()), np.inf
    delta = max(float(delta_guess), lo + 1e-12)
    support_prev = None
    for calls in range(1, max_iter + 1):
        w = optimize.nnls(a, delta * v1 - vh, maxiter=50 * h.size)[0]
        support = w > 0.0
        if support_prev is not None and np.array_equal(support, support_prev):
            w_a, d_a = _bordered_solve(c[np.ix_(support, support)], h[support], load_n,
                                       True)
            if np.all(w_a >= 0.0):
                w = np.zeros_like(h)
                w[support] = w_a
                return w, d_a, calls, True, f"nnls support fixed after {calls} solves"
        if w.sum() < load_n:
            lo = delta
        else:
            hi = delta
        support_prev = support
        if support.any():
            _, step = _bordered_solve(c[np.ix_(support, support)], h[support], load_n,
                                      True)
        else:
            step = lo + 2.0 * (delta - lo) + 1e-12
        if not lo < step < hi:  # safeguard: bisect, or expand until bracketed
            step = 0.5 * (lo + hi) if np.isfinite(hi) else lo + 2.0 * (delta - lo)
        delta = step
    return w, delta, max_iter, False, "nnls root find hit max_iter"


def bordered_active_set(c: np.ndarray, h: np.ndarray, load_n: float, active0: np.ndarray,
                        tol: float, max_iter: int, symmetric: bool
                        ) -> tuple[np.ndarray, float, int, bool, str]:
    """Block active-set (principal pivoting) with the bordered load constraint: ``w >= 0``,
    ``C w + h - delta >= 0`` with equality where ``w > 0``, ``sum(w) = load_n``; returns
    ``(w, delta, iterations, converged, message)`` (also the plane sections of
    :mod:`gearcontact.ltca.edge_section`)."""
    active = active0.copy()
    if not active.any():
        active[np.argmin(h)] = True
    seen: set[bytes] = set()
    single = False
    delta = float(h.min())
    for it in range(1, max_iter + 1):
        w_a, delta = _bordered_solve(c[np.ix_(active, active)], h[active], load_n,
                                     symmetric)
        w = np.zeros_like(h)
        w[active] = w_a
        neg = w < -1e-14 * load_n
        if neg.any():
            drop = neg if not single else (w == w.min())
            active &= ~drop
            if not active.any():
                active[np.argmin(h)] = True
        else:
            s = c[:, active] @ w_a + h - delta
            scale = max(delta - float(h.min()), np.finfo(float).tiny)
            pen = ~active & (s < -tol * scale)
            if not pen.any():
                return np.maximum(w, 0.0), delta, it, True, "active set converged"
            add = pen if not single else (s == s[pen].min()) & pen
            active |= add
        key = np.packbits(active).tobytes()
        if key in seen:
            single = True  # a block cycle: continue with single pivots
        seen.add(key)
    return np.maximum(w, 0.0), delta, max_iter, False, "active set hit max_iter"


# ---------------------------------------------------------------------------- driver
def _initial_bound(h: np.ndarray, area: np.ndarray, load_n: float, e_star: float
                   ) -> float:
    """Gap level ``b*`` at which the flat-punch approach of ``{h <= b*}`` equals ``b* - hmin``.

    A rigid circular punch of radius ``a`` under ``W`` sinks ``W / (2 a E*)`` (Johnson
    1985 ch. 3, both bodies in E*). For a Hertzian gap ``b* - hmin`` is about half the
    true approach. Returns ``inf`` if the whole grid does not reach it. Only the lowest
    cells are sorted (1,024, then four times more until the level is found).
    """
    k = min(h.size, 1024)
    while True:
        low = np.argpartition(h, k - 1)[:k] if k < h.size else np.arange(h.size)
        order = low[np.argsort(h[low], kind="stable")]
        hs = h[order]
        radius = np.sqrt(np.cumsum(area[order]) / np.pi)
        ok = (hs - hs[0]) >= load_n / (2.0 * radius * e_star)
        if ok.any():
            return float(hs[np.argmax(ok)])
        if k == h.size:
            return np.inf
        k = min(4 * k, h.size)


def _residuals(u: np.ndarray, h: np.ndarray, w: np.ndarray, load_n: float,
               delta: float) -> tuple[float, float]:
    """(complementarity, load) residuals on a window, see :class:`.result.ContactResult`."""
    s = u + h - delta
    scale = max(delta - float(h.min()), np.finfo(float).tiny)
    wmax = float(w.max()) if w.size and w.max() > 0 else 1.0
    comp = float(np.abs(np.minimum(w / wmax, s / scale)).max())
    return comp, abs(float(w.sum()) - load_n) / load_n


def solve_lcp(gap_mm, grid: TangentGrid, load_n: float, *, materials=None,
              e_star_mpa: float | None = None, solver: str = "pk_cg",
              tol: float = 1e-8, max_iter: int | None = None, warm_start=None,
              residual_tol: float = 1e-6, raise_on_failure: bool = False,
              warn_coarse: bool = True, precondition: bool = True) -> ContactResult:
    """Solve the load-constrained normal-contact LCP on a tangent-plane grid.

    Parameters
    ----------
    gap_mm : array_like, shape (ny, nx)
        Unloaded gap ``h[j, i]`` in mm at the cell centres (x along axis 1).
    grid : TangentGrid
        The grid (uniform for ``pk_cg`` and ``nnls``; any for ``active_set``).
    load_n : float
        Total normal load ``W`` in N (> 0).
    materials : Material or (Material, Material), optional
        The two bodies; default steel on steel. Mutually exclusive with ``e_star_mpa``.
    e_star_mpa : float, optional
        Composite modulus E* in MPa (``1/E* = sum (1 - nu^2)/E``).
    solver : {"pk_cg", "nnls", "active_set"}
        See the module docstring.
    tol : float
        pk_cg: stop when ``sum|w - w_prev| <= tol W``; active_set: penetration allowed
        as a fraction of the approach; nnls: unused (exact support solve).
    max_iter : int, optional
        Iteration cap per window (defaults: pk_cg 2000, nnls 200, active_set 200).
    warm_start : ContactResult or array_like (ny, nx), optional
        A previous solution (its pressure in MPa) to start pk_cg from / seed the
        active set. Ignored by the nnls reference, which always starts cold.
    residual_tol : float
        The complementarity residual above which a finished solve is not "converged".
    raise_on_failure : bool
        Raise :class:`LcpConvergenceError` instead of returning an unconverged result.
    warn_coarse : bool
        Emit :class:`~.ellipse.CoarseGridWarning` when the patch has too few cells per
        minor semi-axis.
    precondition : bool
        pk_cg only: use the FFT-based preconditioner (Vollebregt 2014); ``False`` gives
        the plain Polonsky-Keer iteration.

    Returns
    -------
    ContactResult
        The one-body fields: ``pressure_mpa``, ``loads_n``, ``delta_mm``,
        ``contact_mask``, ``load_n``, ``load_residual``, ``complementarity_residual``,
        ``window``, and the solve record (``status``, ``message``, ``iterations``,
        ``solver``, ``solve_time_ms``).

    Raises
    ------
    InputRangeError
        Non-positive or non-finite load, NaN/inf in the gap, wrong shapes, unknown
        solver, or ``pk_cg``/``nnls`` on a non-uniform grid.
    """
    t_start = time.perf_counter()
    load = check_positive("load_n", load_n)
    h_full = grid.check_field("gap_mm", gap_mm)
    e_star = resolve_e_star(materials, e_star_mpa)
    check_positive("tol", tol)
    if solver not in SOLVERS:
        raise InputRangeError("solver", solver, f"one of {SOLVERS}")
    if solver in ("pk_cg", "nnls") and not grid.is_uniform:
        raise InputRangeError("grid", "non-uniform", f"a uniform grid for solver="
                              f"'{solver}' (use solver='active_set')")
    n_iter = _DEFAULT_MAX_ITER[solver] if max_iter is None else int(max_iter)
    if n_iter < 1:
        raise InputRangeError("max_iter", max_iter, "an integer >= 1")
    area_full = grid.cell_area_mm2
    w_prev = None
    if warm_start is not None:
        p_prev = warm_start.pressure_mpa if isinstance(warm_start, ContactResult) else \
            grid.check_field("warm_start", warm_start)
        if p_prev.shape != grid.shape:
            raise InputRangeError("warm_start.shape", p_prev.shape, f"{grid.shape}")
        w_prev = np.maximum(p_prev, 0.0) * area_full

    hmin = float(h_full.min())
    b_star = _initial_bound(h_full.ravel(), area_full.ravel(), load, e_star)
    bound = hmin + _WINDOW_FACTOR * (b_star - hmin)
    iterations, notes = 0, []
    ok, msg, max_iter_hit = False, "", False
    for _round in range(_MAX_WINDOWS):
        cand = h_full <= bound
        rows, cols = np.flatnonzero(cand.any(axis=1)), np.flatnonzero(cand.any(axis=0))
        j0, j1, i0, i1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
        whole = bool(cand.all())
        box = (slice(j0, j1), slice(i0, i1))
        h = h_full[box]
        if w_prev is not None and w_prev[box].sum() > 0.0:
            w0 = w_prev[box]
        else:
            w0 = np.sqrt(np.maximum(b_star - h, 0.0)) if np.isfinite(b_star) else \
                np.ones_like(h)
            if not w0.any():
                w0 = (h == h.min()).astype(float)
        if solver == "pk_cg":  # the package's constrained CG on a one-block stack
            op = BlockCompliance(h.shape, [(float(grid.dx_mm[0]), float(grid.dy_mm[0]))],
                                 e_star_mpa=e_star)
            out = constrained_cg(op, h[None], w0[None], load, tol=tol, max_iter=n_iter,
                                 precondition=precondition)
            w, u, it, ok = out.x_stack[0], out.u_stack_mm[0], out.iterations, out.converged
            contact = w > 0.0
            delta = float((u + h)[contact].mean())
            msg = f"pk_cg {out.status}"
            max_iter_hit = out.status is SolveStatus.MAX_ITER
        else:
            sub = grid.sub(*box)
            sel = cand[box].ravel()
            c = dense_influence_matrix(sub, e_star_mpa=e_star, cells=np.flatnonzero(sel))
            hs = h.ravel()[sel]
            try:
                if solver == "nnls":
                    guess = 2.1 * (b_star - hmin) if np.isfinite(b_star) else np.ptp(hs)
                    ws, delta, it, ok, msg = _nnls_reference(c, hs, load, n_iter,
                                                             hmin + guess)
                    max_iter_hit = not ok
                else:
                    ws, delta, it, ok, msg = bordered_active_set(
                        c, hs, load, w0.ravel()[sel] > 0.0, tol, n_iter, sub.is_uniform)
                    max_iter_hit = not ok
            except linalg.LinAlgError as exc:  # a non-SPD / singular active block
                ws, delta, it, ok = np.zeros_like(hs), np.nan, 0, False
                msg = f"{solver} failed: {exc}"
            w = np.zeros(h.size)
            w[np.flatnonzero(sel)] = ws
            w = w.reshape(h.shape)
            u_s = c @ ws
            u = np.full(h.size, np.inf)  # cells outside {h <= b} satisfy s > 0
            u[np.flatnonzero(sel)] = u_s
            u = u.reshape(h.shape)
        iterations += it
        if not ok or whole or delta <= bound:
            cert = "whole grid" if whole else (f"window {j1 - j0}x{i1 - i0} certified "
                                               f"(delta <= bound)")
            notes.append(f"{msg}; {cert}")
            break
        notes.append(f"window {j1 - j0}x{i1 - i0} too small (delta > bound), grown")
        bound = hmin + _WINDOW_GROWTH * (delta - hmin)
        full = np.zeros(grid.shape)
        full[box] = w
        w_prev = full
    else:
        ok, msg = False, "window kept growing"
        notes.append(msg)

    finite = np.isfinite(u)
    comp, load_res = _residuals(np.where(finite, u, 0.0), np.where(finite, h, np.inf),
                                w, load, delta)
    if ok and comp > residual_tol:
        ok = False
        notes.append(f"complementarity residual {comp:.2e} > {residual_tol:.1e}")
    loads_full = np.zeros(grid.shape)
    loads_full[box] = w
    loads_full.setflags(write=False)
    pressure = loads_full / area_full
    pressure.setflags(write=False)
    mask = loads_full > 0.0
    mask.setflags(write=False)
    status = SolveStatus.CONVERGED if ok else (SolveStatus.MAX_ITER if max_iter_hit
                                               else SolveStatus.FAILED)
    result = ContactResult(pressure_mpa=pressure, loads_n=loads_full, delta_mm=float(delta),
                           contact_mask=mask, iterations=int(iterations),
                           complementarity_residual=float(comp),
                           load_residual=float(load_res), status=status,
                           message="; ".join(notes),
                           solve_time_ms=1e3 * (time.perf_counter() - t_start),
                           solver=solver, load_n=load,
                           window=(int(j0), int(j1), int(i0), int(i1)))
    if raise_on_failure and not result.converged:
        raise LcpConvergenceError(result)
    if warn_coarse and mask.any():  # the contact's bounding box: same moments, less work
        rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
        cbox = (slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1))
        warn_if_coarse(grid.sub(*cbox), mask[cbox])
    return result


def warm_up(solver: str = "pk_cg") -> float:
    """Compile (or load from numba's on-disk cache) the kernels of ``solver`` on a
    small Hertzian problem, so that the ``solve_time_ms`` of a following solve measures
    the solve alone, not the JIT compilation (seconds in a fresh install).

    Returns
    -------
    float
        Wall-clock seconds the warm-up took (compilation included), s.
    """
    t0 = time.perf_counter()
    # a Hertzian patch (R = 10 mm, steel) on a 40 x 40 field at three loads: a third of
    # the field, most of it, and beyond it (as an edge contact): the solver's windows
    # then shrink, grow and span whole rows as in real solves, so every array layout the
    # kernels see there (contiguous or a strided window) is compiled here
    n, d = 40, 0.01
    grid = TangentGrid.uniform(n, n, dx_mm=d, dy_mm=d, x0_mm=-0.5 * d * (n - 1),
                               y0_mm=-0.5 * d * (n - 1))
    x, y = np.meshgrid(grid.x_mm, grid.y_mm)
    for load_n in (2.0, 20.0, 400.0):
        solve_lcp(0.05 * (x ** 2 + y ** 2), grid, load_n, solver=solver, warn_coarse=False)
    return time.perf_counter() - t0
