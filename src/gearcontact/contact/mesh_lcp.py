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
each block applied by its zero-padded FFT Love operator and preconditioned by its
inverse Boussinesq symbol (Vollebregt 2014) scaled by ``l_j^2``, all blocks in one
batched transform (:class:`~.influence.StackedFftInfluence`) on a window per loaded
pair around its contact (certified on the whole fields at convergence, as the
windows of :mod:`.lcp`). For a single pair with ``l = 1``, ``g = 0`` this
is exactly the problem :func:`.lcp.solve_lcp` solves; the tests check that, and check
two-pair solutions against a nested root find built on :func:`.lcp.solve_lcp`.

Tooth bending (optional): a block may carry the bending compliance of its two teeth at
its cells as a low-rank factor ``F_j`` (``PairBlock.bending_factor``, from
:mod:`gearcontact.structure.shell`), so that its compliance is ``C_j + F_j F_j^T``
(Love half-space of both bodies plus the pinion and gear tooth deflections; different
pairs load different teeth, so the bending part is block diagonal too). The same
iteration runs with ``C~_j = (C_j + F_j F_j^T) / l_j^2``; the low-rank part is applied
as ``F (F^T x)`` on the windows, the FFT preconditioner stays the half-space one, and
the displacement is recomputed every step instead of updated cell by cell. Without any
bending factor the code path is exactly the rigid-tooth one.

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
from .tooth_bending import add_low_rank, bending_stack

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
    bending_factor : ndarray (ny, nx, r) or None
        Low-rank factor F of the teeth's bending compliance at the cells,
        ``G = F F^T`` (mm/N; F in (mm/N)^(1/2)); None: rigid teeth.
    """

    gap_mm: np.ndarray
    grid: TangentGrid
    lever_mm: float
    offset_mm: float = 0.0
    bending_factor: np.ndarray | None = None

    def __post_init__(self):
        if not self.grid.is_uniform:
            raise InputRangeError("grid", "non-uniform", "a uniform grid (FFT operator)")
        object.__setattr__(self, "gap_mm", self.grid.check_field("gap_mm", self.gap_mm))
        object.__setattr__(self, "lever_mm", check_positive("lever_mm", self.lever_mm))
        g = check_finite("offset_mm", self.offset_mm)
        if g < 0.0:
            raise InputRangeError("offset_mm", g, ">= 0 mm (initial separation)")
        object.__setattr__(self, "offset_mm", g)
        if self.bending_factor is not None:
            f = np.asarray(self.bending_factor, dtype=float)
            if f.ndim != 3 or f.shape[:2] != self.gap_mm.shape or not np.isfinite(f).all():
                raise InputRangeError("bending_factor", f"shape {f.shape}",
                                      f"a finite array of shape {self.gap_mm.shape} + (rank,)")
            object.__setattr__(self, "bending_factor", f)


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
#: At most this many clipped or re-admitted cells per step are added to ``C x`` one by
#: one (a cell costs one window of work, a recomputation about 30 windows).
_TRACKED = 16
#: Whole-field checks that may widen the windows before the whole fields are used.
_CHECKS = 3
#: Cells by which a block's window exceeds its contact box (where cells are re-admitted).
_MARGIN = 3


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
def _dot(a, b):  # pragma: no cover - compiled
    """``a . b`` over all elements (same shapes), single-threaded."""
    total = 0.0
    fa, fb = a.ravel(), b.ravel()
    for m in range(fa.size):
        total += fa[m] * fb[m]
    return total


@njit(cache=True)
def _mesh_step(x, x_old, t, g, r, u, kern, tau, torque, box, cells, dval
               ):  # pragma: no cover - compiled
    """``x <- max(x - tau t, 0)``, re-admission of cells with ``x = 0, g < 0`` at
    ``-tau g``, rescaling to ``torque``; ``box[k] = (j0, j1, i0, i1)``: contact box of
    block ``k`` after the step (``j1 = 0``: none).

    ``u = C x`` follows: ``u <- s (u - tau r + C d)`` with ``r = C t``, ``s`` the
    rescaling and ``d`` the departures from the linear step (clipped and re-admitted
    cells), added cell by cell from the kernel quadrants ``kern`` (``kern[k, |dj|,
    |di|]``, the operator's kernel) when there are at most ``len(dval)`` of them
    (``cells``, ``dval``: work space). Returns ``(conj, change, tracked)``; ``tracked``
    False: too many departures, ``u`` must be recomputed.
    """
    conj, total, n_d = True, 0.0, 0
    for k in range(x.shape[0]):
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                x_old[k, j, i] = x[k, j, i]
                lin = x[k, j, i] - tau * t[k, j, i]
                v = max(lin, 0.0)
                if v == 0.0 and g[k, j, i] < 0.0:
                    v, conj = -tau * g[k, j, i], False
                if v != lin:
                    if n_d < dval.size:
                        cells[n_d, 0], cells[n_d, 1], cells[n_d, 2] = k, j, i
                        dval[n_d] = v - lin
                    n_d += 1
                x[k, j, i] = v
                total += v
    scale, change, tracked = torque / total, 0.0, n_d <= dval.size
    for k in range(x.shape[0]):
        box[k, 0], box[k, 1], box[k, 2], box[k, 3] = x.shape[1], 0, x.shape[2], 0
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                x[k, j, i] *= scale
                change += abs(x[k, j, i] - x_old[k, j, i])
                if x[k, j, i] > 0.0:
                    box[k, 0], box[k, 1] = min(box[k, 0], j), max(box[k, 1], j + 1)
                    box[k, 2], box[k, 3] = min(box[k, 2], i), max(box[k, 3], i + 1)
                if tracked:
                    u[k, j, i] = scale * (u[k, j, i] - tau * r[k, j, i])
    if tracked:
        for m in range(n_d):
            k, jc, ic, d = cells[m, 0], cells[m, 1], cells[m, 2], scale * dval[m]
            for j in range(x.shape[1]):
                for i in range(x.shape[2]):
                    u[k, j, i] += d * kern[k, abs(j - jc), abs(i - ic)]
    return conj, change, tracked


@njit(cache=True)
def _boxes(x):  # pragma: no cover - compiled
    """Contact box ``(j0, j1, i0, i1)`` per block of ``x`` (``j1 = 0``: no contact)."""
    box = np.zeros((x.shape[0], 4), np.int64)
    for k in range(x.shape[0]):
        box[k, 0], box[k, 2] = x.shape[1], x.shape[2]
        for j in range(x.shape[1]):
            for i in range(x.shape[2]):
                if x[k, j, i] > 0.0:
                    box[k, 0], box[k, 1] = min(box[k, 0], j), max(box[k, 1], j + 1)
                    box[k, 2], box[k, 3] = min(box[k, 2], i), max(box[k, 3], i + 1)
    return box


class _Region:
    """Batched operator and data on one window per loaded block.

    Block ``k`` of ``blocks`` is seen through rows ``org[k, 0]:org[k, 0] + gy`` and
    columns ``org[k, 1]:org[k, 1] + gx`` of its field, a window holding its contact box
    grown by :data:`_MARGIN` cells (clamped to the field); ``whole``: every block on
    its whole field. ``bending``: the windows of the bending factors (or None).
    """

    def __init__(self, x, box, cells, scales, e_star, whole, bend=None):
        n_b, ny, nx = x.shape
        if whole:
            self.blocks = np.arange(n_b)
            gy, gx, org = ny, nx, np.zeros((n_b, 2), np.int64)
        else:
            self.blocks = np.flatnonzero(box[:, 1] > box[:, 0])
            bx = box[self.blocks]
            gy = min(ny, int((bx[:, 1] - bx[:, 0]).max()) + 2 * _MARGIN)
            gx = min(nx, int((bx[:, 3] - bx[:, 2]).max()) + 2 * _MARGIN)
            org = np.column_stack([np.clip(bx[:, 0] - _MARGIN, 0, ny - gy),
                                   np.clip(bx[:, 2] - _MARGIN, 0, nx - gx)])
        self.whole, self.shape, self.org, self.field = whole, (gy, gx), org, (ny, nx)
        self.op = StackedFftInfluence((gy, gx), [cells[k] for k in self.blocks],
                                      e_star_mpa=e_star, scales=scales[self.blocks],
                                      pre_shape=(gy, gx))
        self.bending = None if bend is None else np.ascontiguousarray(
            np.stack([bend[k, j:j + gy, i:i + gx] for k, (j, i) in zip(self.blocks, org)]))

    def gather(self, a: np.ndarray) -> np.ndarray:
        gy, gx = self.shape
        return np.stack([a[k, j:j + gy, i:i + gx] for k, (j, i) in zip(self.blocks, self.org)])

    def scatter(self, a: np.ndarray, out: np.ndarray) -> None:
        gy, gx = self.shape
        for v, k, (j, i) in zip(a, self.blocks, self.org):
            out[k, j:j + gy, i:i + gx] = v

    def holds(self, box: np.ndarray) -> bool:
        """Whether every block's contact box (window coordinates) grown by the margin
        still lies in its window (or reaches the field's edge)."""
        return self.whole or _holds(box, self.org, *self.shape, *self.field, _MARGIN)


@njit(cache=True)
def _holds(box, org, gy, gx, ny, nx, margin):  # pragma: no cover - compiled
    """:meth:`_Region.holds` for windows of ``gy x gx`` cells in ``ny x nx`` fields."""
    for k in range(box.shape[0]):
        if box[k, 1] <= box[k, 0]:
            continue  # no contact left in the block
        if ((box[k, 0] < margin and org[k, 0] > 0)
                or (box[k, 1] + margin > gy and org[k, 0] + gy < ny)
                or (box[k, 2] < margin and org[k, 1] > 0)
                or (box[k, 3] + margin > gx and org[k, 1] + gx < nx)):
            return False
    return True


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


def _pk_cg_window(reg: _Region, h, x, torque, tol, it, max_iter, precondition):
    """Steps of the block iteration on ``reg``'s windows (``h``, ``x``: window
    stacks; ``x`` updated in place). Returns ``(reason, it, box)`` with ``reason`` one
    of ``"converged"``, ``"grow"`` (a contact box left its window), ``"stalled"``
    (``rt <= 0``: round-off, converged if ``t == 0``), ``"lost"`` (lost descent),
    ``"max_iter"``; ``box``: the contact boxes in window coordinates."""
    op, bend = reg.op, reg.bending
    box = _boxes(x)
    live = box[:, 1] > box[:, 0]
    u, r, z = op.apply(x, live=live), np.empty(x.shape), np.empty(x.shape)
    if bend is not None:
        add_low_rank(bend, x, u)
    g, gm, x_old, t = (np.empty(x.shape), np.empty(x.shape), np.empty(x.shape),
                       np.zeros(x.shape))
    count = np.zeros(x.shape[0], np.int64)
    kern = op.kernel_quadrants()
    cells, dval = np.zeros((_TRACKED, 3), np.int64), np.zeros(_TRACKED)
    gz_old, conj = 1.0, False
    while it < max_iter:
        it += 1
        _mesh_gap(u, h, x, g, gm, count)
        on = count > 0
        if precondition:
            op.approx_inverse(gm, out=z, live=on)
        else:
            z[...] = gm
        gz, gt = _mesh_direction(z, x, g, t, gz_old, conj)
        gz_old = gz if gz > 0.0 else 1.0
        op.apply(t, out=r, live=on)
        if bend is not None:
            add_low_rank(bend, t, r)
        rt = _dot(r, t)  # not np.vdot: BLAS threads spin on a busy machine
        if rt <= 0.0:  # converged to round-off (t == 0) or lost descent
            return ("stalled" if gz == 0.0 or rt == 0.0 else "lost"), it, box
        conj, change, tracked = _mesh_step(x, x_old, t, g, r, u, kern, gt / rt, torque,
                                           box, cells, dval)
        if change <= tol * torque and conj:  # not on a step that re-admitted cells:
            return "converged", it, box     # their loads are not balanced yet
        if not reg.holds(box):
            return "grow", it, box
        if bend is not None or not tracked or it % _REFRESH == 0:
            # (with bending the cell-by-cell update lacks the low-rank part: recompute)
            op.apply(x, out=u, live=box[:, 1] > box[:, 0])
            if bend is not None:
                add_low_rank(bend, x, u)
    return "max_iter", it, box


def _pk_cg_blocks(blocks, e_star: float, h: np.ndarray, x: np.ndarray, torque: float,
                  tol: float, max_iter: int, precondition: bool, bend=None
                  ) -> tuple[np.ndarray, np.ndarray, int, bool]:
    """Polonsky-Keer CG over block-diagonal operators with ``sum(x) = torque``.

    The iteration of :func:`gearcontact.contact.lcp.solve_lcp` (``pk_cg``) on the stack
    ``x`` (blocks, ny, nx) of scaled loads, with the inner products summed over all
    blocks: the gap is centred on its mean over the contact set of all blocks (which
    eliminates ``theta``), conjugacy restarts when cells are re-admitted, the torque is
    restored after every step, and the preconditioner is the Boussinesq inverse per
    block (periodic on the window: on s0003 as few iterations as padded by half, for
    about half the transform).

    As in :func:`gearcontact.contact.lcp.solve_lcp` the gap is evaluated only on a
    window per loaded block (its contact box grown by :data:`_MARGIN` cells, where
    cells are re-admitted; all windows of one shape, one batched transform for all
    blocks, :class:`_Region`); the windows grow (and the conjugacy restarts) when a
    contact box leaves its window. The displacement ``u = C~ x`` is updated from the
    step's ``C~ t`` (``u <- s (u - tau C~ t)``, ``s`` the rescaling) plus the cells the
    step clipped or re-admitted, from the real-space kernels, so a step costs two
    batched transforms (``C~ t`` and the preconditioner); it is recomputed after a step
    departing in more than :data:`_TRACKED` cells and every :data:`_REFRESH` steps. A step that re-admits cells never ends the iteration. At
    convergence the gap is checked on the whole fields; penetration outside the
    windows (e.g. an unloaded pair closing) widens those blocks' windows over it, and
    after :data:`_CHECKS` such rounds the iteration uses the whole fields.

    Returns ``(x, u, iterations, ok)`` with ``u = C~ x`` computed exactly.
    """
    ny, nx = x.shape[1:]
    cells = [(float(b.grid.dx_mm[0]), float(b.grid.dy_mm[0])) for b in blocks]
    scales = np.array([b.lever_mm ** 2 for b in blocks])
    full = StackedFftInfluence((ny, nx), cells, e_star_mpa=e_star, scales=scales)
    box, whole, it, checks = _boxes(x), False, 0, 0
    while True:
        reg = _Region(x, box, cells, scales, e_star, whole, bend)
        xr = reg.gather(x)
        reason, it, rbox = _pk_cg_window(reg, reg.gather(h), xr, torque, tol, it,
                                         max_iter, precondition)
        x.fill(0.0)
        reg.scatter(xr, x)
        if reason == "grow":
            box[reg.blocks] = rbox + np.repeat(reg.org, 2, axis=1)
            continue
        u, ok = full.apply(x), reason in ("converged", "stalled")
        if bend is not None:
            add_low_rank(bend, x, u)
        if not ok or whole:
            return x, u, it, ok
        s = u + h
        on = x > 0.0
        s -= s[on].mean()
        for k, (j, i) in zip(reg.blocks, reg.org):  # the windows re-admitted cells
            s[k, j:j + reg.shape[0], i:i + reg.shape[1]] = 0.0
        pen = (s < 0.0) & ~on
        if not pen.any():
            return x, u, it, True
        # a pair closing outside the windows (e.g. one that carried nothing): widen
        # those blocks' windows over the penetrating cells, after a few rounds use
        # the whole fields
        checks += 1
        whole = checks > _CHECKS
        box = _boxes(x)
        for k in np.flatnonzero(pen.any(axis=(1, 2))):
            rows = np.flatnonzero(pen[k].any(axis=1))
            cols = np.flatnonzero(pen[k].any(axis=0))
            if box[k, 1] <= box[k, 0]:
                box[k] = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
            else:
                box[k] = (min(box[k, 0], rows[0]), max(box[k, 1], rows[-1] + 1),
                          min(box[k, 2], cols[0]), max(box[k, 3], cols[-1] + 1))


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
    h, x = _stack(hs, [xi * (torque / total) for xi in x0])
    x, u, iters, ok = _pk_cg_blocks(blocks, e_star, h, x, torque, tol, int(max_iter),
                                    precondition, bending_stack(blocks, h.shape[1:]))
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
