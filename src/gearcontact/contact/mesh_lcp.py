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

from ..validation import InputRangeError, check_finite, check_positive
from .grid import TangentGrid
from .influence import FftInfluence
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


class _Block:
    """Scaled operator of one pair: ``x -> C x / l^2``."""

    def __init__(self, block: PairBlock, e_star: float):
        g = block.grid
        self.op = FftInfluence(g.shape, dx_mm=float(g.dx_mm[0]), dy_mm=float(g.dy_mm[0]),
                               e_star_mpa=e_star)
        self.l2 = block.lever_mm ** 2
        self.h = (block.gap_mm + block.offset_mm) / block.lever_mm
        self.shape = g.shape

    def apply(self, x: np.ndarray) -> np.ndarray:
        return self.op(x) / self.l2

    def boxes(self, idx: np.ndarray):
        """Operator and 2-D coordinates for the cells ``idx``. Unlike :mod:`.lcp`
        (bounding box of the contact set) the operators act on the whole field: the
        fields of the LTE are small, and one cached kernel per field is cheaper than a
        new kernel per box shape, for the same iteration count (measured on s0003)."""
        return self.op, np.divmod(idx, self.shape[1])


def _box_apply(op: FftInfluence, loc, values: np.ndarray, inverse: bool) -> np.ndarray:
    """``op`` (or its approximate inverse) applied to ``values`` placed at ``loc``."""
    if inverse and op.shape == (1, 1):  # the symbol has no k != 0 mode: exact inverse
        return values / op(np.ones((1, 1)))[0, 0]
    buf = np.zeros(op.shape)
    buf[loc] = values
    return (op.approx_inverse(buf) if inverse else op(buf))[loc]


def _pk_cg_blocks(blocks: list[_Block], x: list[np.ndarray], torque: float, tol: float,
                  max_iter: int, precondition: bool) -> tuple[list[np.ndarray], int, bool]:
    """Polonsky-Keer CG over block-diagonal operators with ``sum(x) = torque``.

    The iteration of :func:`gearcontact.contact.lcp.solve_lcp` (``pk_cg``), with every
    vector split over the blocks and the inner products summed over all of them.
    """
    x = [xi.ravel().copy() for xi in x]
    t = [np.zeros_like(xi) for xi in x]
    gz_old, conj = 1.0, False
    for it in range(1, max_iter + 1):
        idx = [np.flatnonzero(xi) for xi in x]
        g = [b.apply(xi.reshape(b.shape)).ravel() + b.h.ravel() for b, xi in zip(blocks, x)]
        n_c = sum(i.size for i in idx)
        gbar = sum(gi[i].sum() for gi, i in zip(g, idx)) / n_c
        for gi in g:
            gi -= gbar
        gc = [gi[i] for gi, i in zip(g, idx)]
        boxes = [b.boxes(i) if i.size else (None, None) for b, i in zip(blocks, idx)]
        if precondition:
            z = [_box_apply(op, loc, c, True) * b.l2 if c.size else c
                 for (op, loc), c, b in zip(boxes, gc, blocks)]
            zbar = sum(zi.sum() for zi in z) / n_c
            z = [zi - zbar for zi in z]
        else:
            z = gc
        gz = float(sum(c @ zi for c, zi in zip(gc, z)))
        tc = [zi + (gz / gz_old) * ti[i] if conj else zi for zi, ti, i in zip(z, t, idx)]
        t = [np.zeros_like(xi) for xi in x]
        for ti, i, c in zip(t, idx, tc):
            ti[i] = c
        gz_old = gz if gz > 0.0 else 1.0
        r = [_box_apply(op, loc, c, False) / b.l2 if c.size else c
             for (op, loc), c, b in zip(boxes, tc, blocks)]
        rt = float(sum(ri @ c for ri, c in zip(r, tc)))
        if rt <= 0.0:
            return x, it, gz == 0.0 or rt == 0.0
        tau = float(sum(c @ ti for c, ti in zip(gc, tc))) / rt
        x_old = [xi.copy() for xi in x]
        overlap_any = False
        for xi, i, c, gi in zip(x, idx, tc, g):
            xi[i] -= tau * c
            np.maximum(xi, 0.0, out=xi)
            overlap = np.flatnonzero((xi == 0.0) & (gi < 0.0))
            if overlap.size:
                overlap_any = True
                xi[overlap] -= tau * gi[overlap]
        conj = not overlap_any
        total = sum(xi.sum() for xi in x)
        for xi in x:
            xi *= torque / total
        change = sum(np.abs(xi - xo).sum() for xi, xo in zip(x, x_old))
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
    ops = [_Block(b, e_star) for b in blocks]
    hmin = min(float(o.h.min()) for o in ops)
    theta0 = check_finite("rotation_guess_rad", rotation_guess_rad) \
        if rotation_guess_rad is not None else None
    x0 = []
    for k, (b, o) in enumerate(zip(blocks, ops)):
        p = None if warm_start is None else warm_start[k]
        if p is not None and np.shape(p) == o.shape and np.max(p) > 0.0:
            x0.append(np.maximum(p, 0.0) * b.grid.cell_area_mm2 * b.lever_mm)
        elif theta0 is not None and theta0 > hmin:
            x0.append(np.sqrt(np.maximum(theta0 - o.h, 0.0)))
        else:
            x0.append(np.zeros(o.shape))
    if sum(float(xi.sum()) for xi in x0) <= 0.0:
        # cold start: Hertz-like caps over the (about) 64 lowest cells of all pairs
        h_all = np.sort(np.concatenate([o.h.ravel() for o in ops]))
        level = h_all[min(63, h_all.size - 1)]
        x0 = [np.sqrt(np.maximum(level - o.h, 0.0)) + (o.h == hmin) for o in ops]
    total = sum(float(xi.sum()) for xi in x0)
    x0 = [xi * (torque / total) for xi in x0]
    x, iters, ok = _pk_cg_blocks(ops, x0, torque, tol, int(max_iter), precondition)
    x = [xi.reshape(o.shape) for xi, o in zip(x, ops)]
    u = [o.apply(xi) for o, xi in zip(ops, x)]
    contact = [xi > 0.0 for xi in x]
    theta = float(np.concatenate([(ui + o.h)[c] for ui, o, c in zip(u, ops, contact)]).mean())
    # residuals over all cells of all blocks (see LcpResult)
    scale = max(theta - hmin, np.finfo(float).tiny)
    xmax = max(float(xi.max()) for xi in x) or 1.0
    comp = max(float(np.abs(np.minimum(xi / xmax, (ui + o.h - theta) / scale)).max())
               for xi, ui, o in zip(x, u, ops))
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
