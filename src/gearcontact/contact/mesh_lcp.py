"""Torque-constrained contact of several tooth pairs under one shared rigid rotation.

Each tooth pair ``j`` (rigid teeth, elastic half-space contact) has its own
tangent-plane grid with unloaded gap ``h_j`` (mm, datum: its own mating point), an
initial separation ``g_j >= 0`` (mm along the normal: how far the pair stands open when
the gear rests on the transmitting pair) and an effective lever ``l_j`` (mm) of its
normal force about the gear axis. A gear rotation ``theta`` (rad) from the unloaded rest
position closes pair ``j`` by ``l_j theta``, so its approach is
``delta_j = l_j theta - g_j``. With nodal loads ``w_j`` (N) and the pair's influence
operator ``C_j`` the contact conditions and the torque balance are

    s_j = C_j w_j + h_j + g_j - l_j theta >= 0,   w_j >= 0,   w_j . s_j = 0,
    sum_j l_j sum(w_j) = T                                     (T in N·mm).

Coupled formulation: with the torque shares ``x_j = l_j w_j`` (N·mm) the system becomes
the load-constrained LCP of :mod:`.lcp`,

    s~ = C~ x + h~ - theta 1 >= 0,  x >= 0,  x . s~ = 0,  sum(x) = T,
    C~ = blockdiag(C_j / l_j^2),  h~_j = (h_j + g_j) / l_j,  s~_j = s_j / l_j,

with the rotation in the place of the approach: the pairs are uncoupled elastically
(different teeth), coupled only through ``theta`` and the torque constraint. It is solved
in one go by Polonsky & Keer's constrained conjugate gradient (mean over the contact
set of all pairs eliminates ``theta``; rescaling to ``sum(x) = T`` after each step),
each block applied by its zero-padded FFT Love operator
(:class:`~.influence.FftInfluence`) and preconditioned by its inverse Boussinesq symbol
(Vollebregt 2014) scaled by ``l_j^2`` (both on the whole field of the pair). For a single pair with ``l = 1``, ``g = 0`` this
is exactly the problem :func:`.lcp.solve_lcp` solves; the tests check that, and check
two-pair solutions against a nested root find built on :func:`.lcp.solve_lcp`.

References
----------
M. Polonsky, L. M. Keer, Wear 231 (1999) 206-219 (constrained CG).
E. A. H. Vollebregt, J. Comput. Phys. 257 (2014) 333-351 (FFT preconditioner).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 9
(force transmission); K. L. Johnson, *Contact Mechanics*, 1985, ch. 3 and 4.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..validation import InputRangeError, check_finite, check_positive
from .grid import TangentGrid
from .influence import StackedFftInfluence
from .lcp import resolve_e_star

__all__ = ["MeshLcpResult", "PairBlock", "solve_mesh_lcp"]


@dataclass(frozen=True, eq=False)
class PairBlock:
    """One tooth pair of the torque-constrained LCP.

    Attributes
    ----------
    gap_mm : ndarray (ny, nx)
        Unloaded gap over the pair's grid, mm (finite; off-flank cells carry a large
        separation), datum the pair's mating point.
    grid : TangentGrid
        Uniform grid of the field.
    lever_mm : float
        Effective lever of the pair's normal force about the gear axis, mm (> 0).
    offset_mm : float
        Initial separation ``g_j`` of the pair along its normal, mm (>= 0).
    """

    gap_mm: np.ndarray
    grid: TangentGrid
    lever_mm: float
    offset_mm: float = 0.0

    def __post_init__(self):
        if not self.grid.is_uniform:
            raise InputRangeError("grid", "non-uniform", "a uniform grid (FFT operator)")
        object.__setattr__(self, "gap_mm", self.grid.check_field("gap_mm", self.gap_mm))
        object.__setattr__(self, "lever_mm", check_positive("lever_mm", self.lever_mm))
        g = check_finite("offset_mm", self.offset_mm)
        if g < 0.0:
            raise InputRangeError("offset_mm", g, ">= 0 mm (initial separation)")
        object.__setattr__(self, "offset_mm", g)


@dataclass(frozen=True, eq=False)
class MeshLcpResult:
    """Solution of the torque-constrained multi-pair LCP.

    Attributes
    ----------
    rotation_rad : float
        Shared gear rotation ``theta`` from the unloaded rest position, rad.
    loads_n : tuple of ndarray
        Nodal loads ``w_j`` (N) per pair, each of its grid's shape.
    pair_loads_n : ndarray (P,)
        Total normal load per pair, N.
    approach_mm : ndarray (P,)
        ``delta_j = l_j theta - g_j`` per pair, mm (negative: the pair stays open).
    contact_masks : tuple of ndarray of bool
        Loaded cells per pair.
    torque_nmm : float
        Prescribed torque, N·mm.
    iterations : int
        Conjugate-gradient steps.
    complementarity_residual : float
        ``max |min(x / max x, s~ / (theta - min h~))|`` over all cells, dimensionless.
    torque_residual : float
        ``|sum_j l_j W_j - T| / T``.
    status : str
        ``"converged"``, ``"max_iter"`` or ``"failed"``.
    message : str
        Account of the solve.
    solve_time_ms : float
        Wall time, ms.
    """

    rotation_rad: float
    loads_n: tuple
    pair_loads_n: np.ndarray
    approach_mm: np.ndarray
    contact_masks: tuple
    torque_nmm: float
    iterations: int
    complementarity_residual: float
    torque_residual: float
    status: str
    message: str
    solve_time_ms: float

    @property
    def converged(self) -> bool:
        """True when ``status == "converged"``."""
        return self.status == "converged"

    def pressures_mpa(self, blocks) -> tuple:
        """Pressure maps (MPa) per pair on the blocks' grids."""
        return tuple(w / b.grid.cell_area_mm2 for w, b in zip(self.loads_n, blocks))


#: The incrementally updated displacement is recomputed at least this often (steps).
_REFRESH = 50


@njit(cache=True)
def _mesh_gap(u, h, x, g, gm, count):  # pragma: no cover - compiled
    """``g = u + h`` centred on its mean over the contact set (``x > 0``, all blocks);
    ``gm = g`` there, 0 elsewhere; ``count[k]``: contact cells of block ``k``."""
    total, n = 0.0, 0
    for k in range(x.shape[0]):
        count[k] = 0
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                v = u[k, j, i] + h[k, j, i]
                g[k, j, i] = v
                if x[k, j, i] > 0.0:
                    total += v
                    count[k] += 1
        n += count[k]
    mean = total / n
    for k in range(x.shape[0]):
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                g[k, j, i] -= mean
                gm[k, j, i] = g[k, j, i] if x[k, j, i] > 0.0 else 0.0


@njit(cache=True)
def _mesh_direction(z, x, g, t, gz_old, conj):  # pragma: no cover - compiled
    """Project ``z`` on the contact set (zero mean there, 0 off it) and make the new
    direction ``t <- z + (gz / gz_old) t`` (``conj``), 0 off the contact set.
    Returns ``(gz, g.t)`` with ``gz = g.z``."""
    total, n = 0.0, 0
    for k in range(x.shape[0]):
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                if x[k, j, i] > 0.0:
                    total += z[k, j, i]
                    n += 1
    mean, gz = total / n, 0.0
    for k in range(x.shape[0]):
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                if x[k, j, i] > 0.0:
                    z[k, j, i] -= mean
                    gz += g[k, j, i] * z[k, j, i]
    beta, gt = (gz / gz_old if conj else 0.0), 0.0
    for k in range(x.shape[0]):
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                if x[k, j, i] > 0.0:
                    t[k, j, i] = z[k, j, i] + beta * t[k, j, i]
                    gt += g[k, j, i] * t[k, j, i]
                else:
                    t[k, j, i] = 0.0
    return gz, gt


@njit(cache=True)
def _mesh_step(x, x_old, t, g, r, u, tau, torque, live):  # pragma: no cover - compiled
    """``x <- max(x - tau t, 0)``, re-admission of cells with ``x = 0, g < 0`` at
    ``-tau g``, rescaling to ``torque``; for a linear step (no clipping, no
    re-admission) ``u <- s (u - tau r)`` (``r = C t``: ``u`` stays ``C x``).
    ``live[k]``: block ``k`` carries load. Returns ``(conj, linear, change)``."""
    conj, linear, total = True, True, 0.0
    for k in range(x.shape[0]):
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                x_old[k, j, i] = x[k, j, i]
                v = x[k, j, i] - tau * t[k, j, i]
                if v < 0.0:
                    v, linear = 0.0, False
                if v == 0.0 and g[k, j, i] < 0.0:
                    v, conj = -tau * g[k, j, i], False
                x[k, j, i] = v
                total += v
    scale, change = torque / total, 0.0
    for k in range(x.shape[0]):
        live[k] = False
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                x[k, j, i] *= scale
                change += abs(x[k, j, i] - x_old[k, j, i])
                if x[k, j, i] > 0.0:
                    live[k] = True
                if conj and linear:
                    u[k, j, i] = scale * (u[k, j, i] - tau * r[k, j, i])
    return conj, linear, change


def _stack(blocks, e_star: float, hs, xs):
    """Batched operator ``x -> C_k x / l_k^2`` and the stacks of ``h~`` and ``x``.

    Fields of other shapes are padded to the largest one: padded cells carry no load
    (exact: the operator is a linear convolution) and an infinite gap, so they are
    never re-admitted.
    """
    ny = max(hk.shape[0] for hk in hs)
    nx = max(hk.shape[1] for hk in hs)
    h, x = np.full((len(hs), ny, nx), np.inf), np.zeros((len(hs), ny, nx))
    for k, (hk, xk) in enumerate(zip(hs, xs)):
        h[k, :hk.shape[0], :hk.shape[1]] = hk
        x[k, :hk.shape[0], :hk.shape[1]] = xk
    op = StackedFftInfluence((ny, nx), [(float(b.grid.dx_mm[0]), float(b.grid.dy_mm[0]))
                                        for b in blocks], e_star_mpa=e_star,
                             scales=[b.lever_mm ** 2 for b in blocks])
    return op, h, x


def _pk_cg_blocks(op: StackedFftInfluence, h: np.ndarray, x: np.ndarray, torque: float,
                  tol: float, max_iter: int, precondition: bool
                  ) -> tuple[np.ndarray, int, bool]:
    """Polonsky-Keer CG over block-diagonal operators with ``sum(x) = torque``.

    The iteration of :func:`gearcontact.contact.lcp.solve_lcp` (``pk_cg``) on the stack
    ``x`` (blocks, ny, nx) of scaled loads, with the inner products summed over all
    blocks: the gap is centred on its mean over the contact set of all blocks (which
    eliminates ``theta``), conjugacy restarts when cells are re-admitted, the torque is
    restored after every step. ``op`` applies all blocks in one batched transform
    (only the blocks carrying load). The displacement ``u = C~ x`` is updated from the
    step's ``C~ t`` (``u <- s (u - tau C~ t)``, ``s`` the rescaling), so a step costs
    two batched transforms (``C~ t`` and the preconditioner); it is recomputed when
    cells are clipped or re-admitted and every :data:`_REFRESH` steps. ``x`` is
    updated in place.
    """
    n_b = x.shape[0]
    live = np.array([bool((xk > 0.0).any()) for xk in x])
    u, r, z = op.apply(x, live=live), np.empty(x.shape), np.empty(x.shape)
    g, gm, x_old, t = (np.empty(x.shape), np.empty(x.shape), np.empty(x.shape),
                       np.zeros(x.shape))
    count = np.zeros(n_b, np.int64)
    gz_old, conj = 1.0, False
    for it in range(1, max_iter + 1):
        _mesh_gap(u, h, x, g, gm, count)
        on = count > 0
        if precondition:
            op.approx_inverse(gm, out=z, live=on)
        else:
            z[...] = gm
        gz, gt = _mesh_direction(z, x, g, t, gz_old, conj)
        gz_old = gz if gz > 0.0 else 1.0
        op.apply(t, out=r, live=on)
        rt = float(np.vdot(r, t))
        if rt <= 0.0:  # converged to round-off (t == 0) or lost descent
            return x, it, gz == 0.0 or rt == 0.0
        conj, linear, change = _mesh_step(x, x_old, t, g, r, u, gt / rt, torque, live)
        if not (conj and linear) or it % _REFRESH == 0:
            op.apply(x, out=u, live=live)
        if change <= tol * torque:
            return x, it, True
    return x, max_iter, False


def solve_mesh_lcp(blocks, torque_nmm: float, *, materials=None,
                   e_star_mpa: float | None = None, tol: float = 1e-8,
                   max_iter: int = 2000, warm_start=None, rotation_guess_rad=None,
                   residual_tol: float = 1e-6, precondition: bool = True) -> MeshLcpResult:
    """Solve the torque-constrained LCP of several tooth pairs (module docstring).

    Parameters
    ----------
    blocks : sequence of PairBlock
        The pairs within reach (>= 1).
    torque_nmm : float
        Gear torque, N·mm (> 0).
    materials, e_star_mpa
        As :func:`.lcp.solve_lcp` (default steel on steel).
    tol : float
        Stop when ``sum |x - x_prev| <= tol T``.
    max_iter : int
        Iteration cap.
    warm_start : sequence of (ndarray or None), optional
        Previous pressure maps (MPa) per block, same shapes; a block's map that is
        None or all zero starts cold.
    rotation_guess_rad : float, optional
        Estimate of ``theta`` (e.g. from the Hertzian preview) for the cold start: the
        initial loads are ``sqrt(max(theta - h~, 0))`` (Hertz-like caps).
    residual_tol : float
        Complementarity residual above which a finished solve is not "converged".
    precondition : bool
        Use the FFT preconditioner.

    Returns
    -------
    MeshLcpResult
        Check ``.converged`` (never raises on non-convergence).
    """
    t_start = time.perf_counter()
    blocks = list(blocks)
    if not blocks:
        raise InputRangeError("blocks", blocks, "at least one tooth pair")
    torque = check_positive("torque_nmm", torque_nmm)
    check_positive("tol", tol)
    if int(max_iter) < 1:
        raise InputRangeError("max_iter", max_iter, "an integer >= 1")
    e_star = resolve_e_star(materials, e_star_mpa)
    hs = [(b.gap_mm + b.offset_mm) / b.lever_mm for b in blocks]  # h~ per block
    hmin = min(float(hk.min()) for hk in hs)
    theta0 = check_finite("rotation_guess_rad", rotation_guess_rad) \
        if rotation_guess_rad is not None else None
    x0 = []
    for k, (b, hk) in enumerate(zip(blocks, hs)):
        p = None if warm_start is None else warm_start[k]
        if p is not None and np.shape(p) == hk.shape and np.max(p) > 0.0:
            x0.append(np.maximum(p, 0.0) * b.grid.cell_area_mm2 * b.lever_mm)
        elif theta0 is not None and theta0 > hmin:
            x0.append(np.sqrt(np.maximum(theta0 - hk, 0.0)))
        else:
            x0.append(np.zeros(hk.shape))
    if sum(float(xi.sum()) for xi in x0) <= 0.0:
        # cold start: Hertz-like caps over the (about) 64 lowest cells of all pairs
        h_all = np.sort(np.concatenate([hk.ravel() for hk in hs]))
        level = h_all[min(63, h_all.size - 1)]
        x0 = [np.sqrt(np.maximum(level - hk, 0.0)) + (hk == hmin) for hk in hs]
    total = sum(float(xi.sum()) for xi in x0)
    op, h, x = _stack(blocks, e_star, hs, [xi * (torque / total) for xi in x0])
    x, iters, ok = _pk_cg_blocks(op, h, x, torque, tol, int(max_iter), precondition)
    u = op.apply(x)  # exact, for theta and the residuals
    x = [x[k][:hk.shape[0], :hk.shape[1]] for k, hk in enumerate(hs)]
    u = [u[k][:hk.shape[0], :hk.shape[1]] for k, hk in enumerate(hs)]
    contact = [xi > 0.0 for xi in x]
    theta = float(np.concatenate([(ui + hk)[c] for ui, hk, c in zip(u, hs, contact)]).mean())
    # residuals over all cells of all blocks (see LcpResult)
    scale = max(theta - hmin, np.finfo(float).tiny)
    xmax = max(float(xi.max()) for xi in x) or 1.0
    comp = max(float(np.abs(np.minimum(xi / xmax, (ui + hk - theta) / scale)).max())
               for xi, ui, hk in zip(x, u, hs))
    loads = tuple(xi / b.lever_mm for xi, b in zip(x, blocks))
    pair_loads = np.array([float(w.sum()) for w in loads])
    levers = np.array([b.lever_mm for b in blocks])
    torque_res = abs(float(pair_loads @ levers) - torque) / torque
    msg = f"block pk_cg over {len(blocks)} pair(s): " + \
        ("converged" if ok else f"stopped after {iters} iterations")
    if ok and comp > residual_tol:
        ok = False
        msg += f"; complementarity residual {comp:.2e} > {residual_tol:.1e}"
    status = "converged" if ok else ("max_iter" if iters >= int(max_iter) else "failed")
    for w in loads:
        w.setflags(write=False)
    return MeshLcpResult(
        rotation_rad=theta, loads_n=loads, pair_loads_n=pair_loads,
        approach_mm=levers * theta - np.array([b.offset_mm for b in blocks]),
        contact_masks=tuple(contact), torque_nmm=torque, iterations=int(iters),
        complementarity_residual=comp, torque_residual=float(torque_res), status=status,
        message=msg, solve_time_ms=1e3 * (time.perf_counter() - t_start))
