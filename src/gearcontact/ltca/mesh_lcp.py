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
the load-constrained LCP of :mod:`..halfspace.lcp`,

    s~ = C~ x + h~ - theta 1 >= 0,  x >= 0,  x . s~ = 0,  sum(x) = T,
    C~ = blockdiag(C_j / l_j^2),  h~_j = (h_j + g_j) / l_j,  s~_j = s_j / l_j,

with the rotation in the place of the approach: the pairs are uncoupled elastically
(different teeth), coupled only through ``theta`` and the torque constraint. It is solved
in one go by the package's one constrained conjugate gradient,
:func:`..halfspace.constrained_cg.constrained_cg` (mean over the contact set of all pairs
eliminates ``theta``; rescaling to ``sum(x) = T`` after each step), with the
compliance operator :class:`..halfspace.compliance.BlockCompliance`: each block its zero-padded
FFT Love operator scaled by ``1 / l_j^2``, preconditioned by its inverse Boussinesq
symbol (Vollebregt 2014), all blocks in one batched transform on a window per loaded
pair around its contact (certified on the whole fields at convergence). For a single
pair with ``l = 1``, ``g = 0`` this is exactly the problem :func:`..halfspace.lcp.solve_lcp`
solves; the tests check that, and check two-pair solutions against a nested root find built on :func:`..halfspace.lcp.solve_lcp`.

Tooth bending (optional): a block may carry the bending compliance of its two teeth at
its cells as a low-rank factor ``F_j`` (``PairBlock.bending_factor``, from
:mod:`gearcontact.structure.shell`), so that its compliance is ``C_j + F_j F_j^T``
(Love half-space of both bodies plus the pinion and gear tooth deflections; different
pairs load different teeth, so the bending part is block diagonal too). The same
iteration runs with ``C~_j = (C_j + F_j F_j^T) / l_j^2`` (the operator's low-rank part
``F_j / l_j``); the FFT preconditioner stays the half-space one. Without any bending
factor the code path is exactly the rigid-tooth one.

Signed corrections (optional): a block's bending may instead be symmetric and
indefinite, ``G_j = F+ F+^T - F- F-^T`` (a :class:`~.tooth_bending.SignedFactor`, or a
dense matrix over its cells, ``PairBlock.correction_mm_per_n``): the far field of
Vijayakar's split, negative near a tooth's root (docs/bending.md sec. 13). The CG needs
the total ``C_j + G_j`` positive definite on the cells that carry load; after the solve
it is factored (Cholesky) on each pair's contact cells, and a pair where it is not is
refused with :class:`IndefiniteCompliance` (never clipped). A CG step that loses
descent on the way stops as FAILED, as without a correction.

References
----------
M. Polonsky, L. M. Keer, Wear 231 (1999) 206-219 (constrained CG).
E. A. H. Vollebregt, J. Comput. Phys. 257 (2014) 333-351 (FFT preconditioner).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 9
(force transmission); K. L. Johnson, *Contact Mechanics*, 1985, ch. 3 and 4.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np
from scipy.linalg import eigh

from ..deprecation import moved_names
from ..errors import CheckFailed
from ..validation import InputRangeError, check_finite, check_positive
from ..halfspace.compliance import BlockCompliance, add_low_rank
from ..halfspace.constrained_cg import constrained_cg
from ..halfspace.grid import TangentGrid
from ..halfspace.lcp import resolve_e_star
from ..halfspace.result import ContactResult, SolveStatus
from .tooth_bending import SignedFactor, bending_stack

__all__ = ["PairBlock", "solve_mesh_lcp", "warm_up_mesh_lcp", "IndefiniteCompliance",
           "SignedBlockCompliance", "contact_eigenvalues"]

#: Deprecated for one release: the result is the contact family's one type.
__getattr__ = moved_names(__name__, {
    "MeshLcpResult": "gearcontact.halfspace.result:ContactResult"})


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
    bending_factor : ndarray (ny, nx, r), SignedFactor or None
        Low-rank factor F of the teeth's bending compliance at the cells,
        ``G = F F^T`` (mm/N; F in (mm/N)^(1/2)); a
        :class:`~.tooth_bending.SignedFactor`: ``G = F+ F+^T - F- F-^T``, possibly
        indefinite (module docstring); None: rigid teeth.
    correction_mm_per_n : ndarray (ny nx, ny nx) or None
        A dense symmetric (possibly indefinite) compliance over the cells (row-major),
        mm/N, added to ``bending_factor``'s: stored as its signed factor
        (:meth:`~.tooth_bending.SignedFactor.from_dense`, eigenvalues below 1e-6 of its
        largest |entry| dropped) merged into ``bending_factor``; the attribute is then
        None (the correction lives in ``bending_factor``).
    """

    gap_mm: np.ndarray
    grid: TangentGrid
    lever_mm: float
    offset_mm: float = 0.0
    bending_factor: np.ndarray | SignedFactor | None = None
    correction_mm_per_n: np.ndarray | None = None

    def __post_init__(self):
        if not self.grid.is_uniform:
            raise InputRangeError("grid", "non-uniform", "a uniform grid (FFT operator)")
        object.__setattr__(self, "gap_mm", self.grid.check_field("gap_mm", self.gap_mm))
        object.__setattr__(self, "lever_mm", check_positive("lever_mm", self.lever_mm))
        g = check_finite("offset_mm", self.offset_mm)
        if g < 0.0:
            raise InputRangeError("offset_mm", g, ">= 0 mm (initial separation)")
        object.__setattr__(self, "offset_mm", g)
        if self.correction_mm_per_n is not None:
            corr = SignedFactor.from_dense(self.correction_mm_per_n, self.gap_mm.shape)
            object.__setattr__(self, "bending_factor", _merged(self.bending_factor, corr))
            # merged once: a dataclasses.replace of the block must not add it again
            object.__setattr__(self, "correction_mm_per_n", None)
        if isinstance(self.bending_factor, SignedFactor):
            if self.bending_factor.shape != self.gap_mm.shape:
                raise InputRangeError("bending_factor", f"cells {self.bending_factor.shape}",
                                      f"the field's cells {self.gap_mm.shape}")
        elif self.bending_factor is not None:
            f = np.asarray(self.bending_factor, dtype=float)
            if f.ndim != 3 or f.shape[:2] != self.gap_mm.shape or not np.isfinite(f).all():
                raise InputRangeError("bending_factor", f"shape {f.shape}",
                                      f"a finite array of shape {self.gap_mm.shape} + (rank,)")
            object.__setattr__(self, "bending_factor", f)

    @property
    def signed(self) -> bool:
        """Whether the block's bending is a signed (possibly indefinite) factor."""
        return isinstance(self.bending_factor, SignedFactor)


def _merged(factor, corr: SignedFactor) -> SignedFactor:
    """A block's bending ``factor`` (None, an array or a signed factor) plus ``corr``."""
    if factor is None:
        return corr
    pos, neg = (factor.positive, factor.negative) if isinstance(factor, SignedFactor) \
        else (np.asarray(factor, float), np.zeros(corr.shape + (0,)))
    if pos.shape[:2] != corr.shape:
        raise InputRangeError("bending_factor", f"cells {pos.shape[:2]}",
                              f"the field's cells {corr.shape}")
    return SignedFactor(np.concatenate([pos, corr.positive], axis=2),
                        np.concatenate([neg, corr.negative], axis=2))


class IndefiniteCompliance(CheckFailed):
    """The total compliance of a pair (half-space plus a signed bending correction) is
    not positive definite on the cells that carry load: the contact problem is not
    convex there and its solution is not the contact's (a failed check, exit 4).
    ``pair``, ``contact_cells`` and ``least_eigenvalue_mm_per_n`` name where."""

    def __init__(self, pair: int, contact_cells: int, least_eigenvalue_mm_per_n: float):
        self.pair, self.contact_cells = pair, contact_cells
        self.least_eigenvalue_mm_per_n = least_eigenvalue_mm_per_n
        super().__init__(
            f"pair {pair}: half-space + signed bending correction not positive definite "
            f"on its {contact_cells} contact cells (least eigenvalue "
            f"{least_eigenvalue_mm_per_n:.3e} mm/N): the near-field correction is more "
            "negative than the half-space there (docs/bending.md sec. 13)")


class SignedBlockCompliance(BlockCompliance):
    """:class:`~..halfspace.compliance.BlockCompliance` with a negative low-rank part:
    ``u[k] = C_k x[k] / s_k + F+_k (F+_k^T x[k]) - F-_k (F-_k^T x[k])``.

    ``low_rank`` carries ``F+`` (None: none), ``negative`` (blocks, ny, nx, r-) ``F-``,
    both in (mm/N)^(1/2) per unit of ``x`` (single precision, double sums)."""

    def __init__(self, shape, cell_sizes, *, e_star_mpa: float, scales=None,
                 low_rank=None, negative: np.ndarray, pre_shape=None):
        super().__init__(shape, cell_sizes, e_star_mpa=e_star_mpa, scales=scales,
                         low_rank=low_rank, pre_shape=pre_shape)
        negative = np.asarray(negative, np.float32)
        if negative.shape[:3] != (self.n_blocks,) + self.shape:
            raise InputRangeError("negative", f"shape {negative.shape}",
                                  f"({self.n_blocks}, {self.shape[0]}, {self.shape[1]}, rank)")
        self.negative = negative

    @property
    def exact_kernels(self) -> bool:
        return False

    def evaluate_disp(self, loads, out=None, live=None):
        out = super().evaluate_disp(loads, out=out, live=live)
        neg = add_low_rank(self.negative, loads, np.zeros_like(out))
        out -= neg
        return out

    def add_low_rank_cells(self, out, cells, values):
        if self.low_rank is not None:
            super().add_low_rank_cells(out, cells, values)
        f = self.negative
        c = np.zeros((f.shape[0], f.shape[3]))
        np.add.at(c, cells[:, 0], f[cells[:, 0], cells[:, 1], cells[:, 2]] * values[:, None])
        out -= np.einsum("kjiq,kq->kji", f, c)
        return out

    def window(self, blocks, origins, shape):
        gy, gx = (int(n) for n in shape)
        low = None if self.low_rank is None else np.ascontiguousarray(np.stack(
            [self.low_rank[k, j:j + gy, i:i + gx] for k, (j, i) in zip(blocks, origins)]))
        neg = np.ascontiguousarray(np.stack(
            [self.negative[k, j:j + gy, i:i + gx] for k, (j, i) in zip(blocks, origins)]))
        return SignedBlockCompliance((gy, gx), [self.cell_sizes[k] for k in blocks],
                                     e_star_mpa=self.e_star_mpa, scales=self.scales[blocks],
                                     low_rank=low, negative=neg, pre_shape=(gy, gx))


def contact_eigenvalues(blocks, result, *, e_star_mpa: float) -> list[float | None]:
    """The least eigenvalue (mm/N) of each pair's total compliance, Love's half-space
    (E*) plus its bending (``F F^T`` or the signed factor), restricted to the cells that
    carry load in ``result`` (:func:`solve_mesh_lcp`'s); None for a pair without
    contact. Dense on the contact cells: a few hundred at most on a field."""
    out = []
    for b, mask in zip(blocks, result.contact_masks):
        idx = np.flatnonzero(mask)
        if idx.size == 0:
            out.append(None)
            continue
        out.append(_least(_contact_matrix(b, idx, e_star_mpa)))
    return out


def _contact_matrix(block: PairBlock, idx: np.ndarray, e_star_mpa: float) -> np.ndarray:
    """Love's compliance plus the block's bending between the cells ``idx`` (flat
    indices, row-major), mm/N."""
    ny, nx = block.gap_mm.shape
    kern = BlockCompliance((ny, nx), [(float(block.grid.dx_mm[0]), float(block.grid.dy_mm[0]))],
                           e_star_mpa=e_star_mpa).kernel_quadrants()[0]
    j, i = np.divmod(idx, nx)
    g = kern[np.abs(j[:, None] - j[None, :]), np.abs(i[:, None] - i[None, :])]
    f = block.bending_factor
    if isinstance(f, SignedFactor):
        p = f.positive.reshape(ny * nx, -1)[idx]
        m = f.negative.reshape(ny * nx, -1)[idx]
        g = g + p @ p.T - m @ m.T
    elif f is not None:
        p = f.reshape(ny * nx, -1)[idx]
        g = g + p @ p.T
    return 0.5 * (g + g.T)


def _least(g: np.ndarray) -> float:
    """The least eigenvalue of the symmetric ``g`` (LAPACK's selected-eigenvalue solver)."""
    return float(eigh(g, eigvals_only=True, subset_by_index=[0, 0])[0])


def _check_contact(blocks, result, e_star_mpa: float) -> float:
    """Cholesky of each signed pair's total compliance on its contact cells; raises
    :class:`IndefiniteCompliance` (with the least eigenvalue) where it fails. Returns
    the least eigenvalue over the signed pairs (mm/N), for the solve's message."""
    least = np.inf
    for k, (b, mask) in enumerate(zip(blocks, result.contact_masks)):
        idx = np.flatnonzero(mask)
        if not b.signed or idx.size == 0:
            continue
        g = _contact_matrix(b, idx, e_star_mpa)
        lam = _least(g)
        try:
            np.linalg.cholesky(g)
        except np.linalg.LinAlgError:
            raise IndefiniteCompliance(k, int(idx.size), lam) from None
        if lam <= 0.0:
            raise IndefiniteCompliance(k, int(idx.size), lam)
        least = min(least, lam)
    return least


def _cold_start(hs, hmin: float) -> list[np.ndarray]:
    """Hertz-like caps over the (about) 64 lowest cells of all pairs (``hs``: ``h~`` per
    block, ``hmin`` their least)."""
    h_all = np.sort(np.concatenate([hk.ravel() for hk in hs]))
    level = h_all[min(63, h_all.size - 1)]
    return [np.sqrt(np.maximum(level - hk, 0.0)) + (hk == hmin) for hk in hs]


def _solve_from(op, h, hs, x0, torque: float, *, tol: float, max_iter: int,
                precondition: bool):
    """:func:`constrained_cg` from the start ``x0`` (per block, scaled to the torque):
    ``(result, x, u, theta, complementarity residual)`` with ``x``, ``u`` per block on
    its own shape and the residual over all cells of all blocks (see ContactResult)."""
    total = sum(float(xi.sum()) for xi in x0)
    _, x = _stack(hs, [xi * (torque / total) for xi in x0])
    out = constrained_cg(op, h, x, torque, tol=tol, max_iter=max_iter,
                         precondition=precondition)
    x = [out.x_stack[k][:hk.shape[0], :hk.shape[1]] for k, hk in enumerate(hs)]
    u = [out.u_stack_mm[k][:hk.shape[0], :hk.shape[1]] for k, hk in enumerate(hs)]
    contact = [xi > 0.0 for xi in x]
    theta = float(np.concatenate([(ui + hk)[c] for ui, hk, c in zip(u, hs, contact)]).mean())
    hmin = min(float(hk.min()) for hk in hs)
    scale = max(theta - hmin, np.finfo(float).tiny)
    xmax = max(float(xi.max()) for xi in x) or 1.0
    comp = max(float(np.abs(np.minimum(xi / xmax, (ui + hk - theta) / scale)).max())
               for xi, ui, hk in zip(x, u, hs))
    return out, x, u, theta, comp


def _stack(hs, xs) -> tuple[np.ndarray, np.ndarray]:
    """Stacks of ``h~`` and ``x`` on one shape.

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
    return h, x


def solve_mesh_lcp(blocks, torque_nmm: float, *, materials=None,
                   e_star_mpa: float | None = None, tol: float = 1e-8,
                   max_iter: int = 2000, warm_start=None, rotation_guess_rad=None,
                   residual_tol: float = 1e-6, precondition: bool = True) -> ContactResult:
    """Solve the torque-constrained LCP of several tooth pairs (module docstring).

    Parameters
    ----------
    blocks : sequence of PairBlock
        The pairs within reach (>= 1).
    torque_nmm : float
        Gear torque, N·mm (> 0).
    materials, e_star_mpa
        As :func:`..halfspace.lcp.solve_lcp` (default steel on steel).
    tol : float
        Stop when ``sum |x - x_prev| <= tol T``.
    max_iter : int
        Iteration cap.
    warm_start : sequence of (ndarray or None), optional
        Previous pressure maps (MPa) per block, same shapes; a block's map that is
        None or all zero starts cold.
    rotation_guess_rad : float, optional
        Estimate of ``theta`` (e.g. from the Hertzian preview) for the cold start: the
        initial loads are ``sqrt(max(theta - h~, 0))`` (Hertz-like caps). A warm or
        guessed start that does not end converged and complementary is solved again
        from the cold start (the LCP has one solution; ``iterations`` counts both).
    residual_tol : float
        Complementarity residual above which a finished solve is not "converged".
    precondition : bool
        Use the FFT preconditioner.

    Returns
    -------
    ContactResult
        The tooth-pair fields: ``rotation_rad``, ``loads_n`` (a tuple of fields, one
        per pair), ``pair_loads_n``, ``approach_mm``, ``contact_masks``, ``torque_nmm``,
        ``torque_residual``, ``complementarity_residual``, and the solve record
        (``status``: CONVERGED, MAX_ITER or FAILED, also for a converged iteration whose
        complementarity residual exceeds ``residual_tol``; ``message``,
        ``iterations``: CG steps, ``solve_time_ms``). Check ``.converged`` (never
        raises on non-convergence).
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
    cold = sum(float(xi.sum()) for xi in x0) <= 0.0
    h, _ = _stack(hs, [np.zeros(hk.shape) for hk in hs])   # the gaps, padded
    signed = any(b.signed for b in blocks)
    op_args = dict(e_star_mpa=e_star, scales=[b.lever_mm ** 2 for b in blocks],
                   low_rank=bending_stack(blocks, h.shape[1:]))
    sizes = [(float(b.grid.dx_mm[0]), float(b.grid.dy_mm[0])) for b in blocks]
    if signed:
        neg = bending_stack(blocks, h.shape[1:], part="negative")
        op = SignedBlockCompliance(h.shape[1:], sizes, negative=np.zeros(
            (len(blocks),) + h.shape[1:] + (1,)) if neg is None else neg, **op_args)
    else:
        op = BlockCompliance(h.shape[1:], sizes, **op_args)

    def solve(start):
        return _solve_from(op, h, hs, start, torque, tol=tol, max_iter=int(max_iter),
                           precondition=precondition)

    out, x, u, theta, comp = solve(_cold_start(hs, hmin) if cold else x0)
    iters = out.iterations
    if not cold and not (out.converged and comp <= residual_tol):
        # The pairs' LCP is a strictly convex QP (bending adds G = F F^T, positive
        # semi-definite; a signed G is checked positive definite with the half-space on
        # the contact after the solve) with one solution, whatever the start: a warm or
        # guessed start on which the CG stalls at a non-complementary point (the preview's rotation
        # guess at the 12/12 design-space pair's hand-over at T/20: residual 0.67) is
        # solved again from the cold start.
        out, x, u, theta, comp = solve(_cold_start(hs, hmin))
        iters += out.iterations
    ok = out.converged
    contact = [xi > 0.0 for xi in x]
    loads = tuple(xi / b.lever_mm for xi, b in zip(x, blocks))
    pair_loads = np.array([float(w.sum()) for w in loads])
    levers = np.array([b.lever_mm for b in blocks])
    torque_res = abs(float(pair_loads @ levers) - torque) / torque
    msg = f"block pk_cg over {len(blocks)} pair(s): " + \
        ("converged" if ok else f"stopped after {iters} iterations")
    if ok and comp > residual_tol:
        ok = False
        msg += f"; complementarity residual {comp:.2e} > {residual_tol:.1e}"
    status = SolveStatus.CONVERGED if ok else (
        out.status if out.status is not SolveStatus.CONVERGED else SolveStatus.FAILED)
    for w in loads:
        w.setflags(write=False)
    result = ContactResult(
        solver="pk_cg", rotation_rad=theta, loads_n=loads, pair_loads_n=pair_loads,
        approach_mm=levers * theta - np.array([b.offset_mm for b in blocks]),
        contact_masks=tuple(contact), torque_nmm=torque, iterations=int(iters),
        complementarity_residual=comp, torque_residual=float(torque_res), status=status,
        message=msg, solve_time_ms=1e3 * (time.perf_counter() - t_start))
    if signed:
        least = _check_contact(blocks, result, e_star)
        if np.isfinite(least):
            result = replace(result, message=msg + "; total compliance positive definite on "
                             f"the contact cells (least eigenvalue {least:.3e} mm/N)")
    return result


def warm_up_mesh_lcp() -> float:
    """Compile (or load from numba's disk cache) the kernels of :func:`solve_mesh_lcp`,
    rigid and with a bending factor, on two small Hertzian pairs, so that the
    ``solve_time_ms`` of a following solve excludes the JIT compilation.

    Returns
    -------
    float
        Wall-clock seconds the warm-up took, s.
    """
    t0 = time.perf_counter()
    n, d = 32, 0.01
    grid = TangentGrid.uniform(n, n, dx_mm=d, dy_mm=d, x0_mm=-0.5 * d * (n - 1),
                               y0_mm=-0.5 * d * (n - 1))
    x, y = np.meshgrid(grid.x_mm, grid.y_mm)
    gap = 0.05 * (x ** 2 + y ** 2)
    factor = np.full((n, n, 1), 1e-3)            # a uniform rank-1 compliance, mm/N
    for bend in (None, factor):
        for torque in (200.0, 4000.0):       # a small patch, then one beyond the field
            solve_mesh_lcp([PairBlock(gap, grid, 10.0, 0.0, bending_factor=bend),
                            PairBlock(gap, grid, 10.0, 1e-4, bending_factor=bend)], torque)
    return time.perf_counter() - t0
