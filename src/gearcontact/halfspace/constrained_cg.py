"""ONE constrained conjugate-gradient iteration for every normal-contact LCP.

For a stack of fields ``x[k]`` (nodal loads, or torque shares ``l_k w_k``) with gaps
``h[k]`` and a block-diagonal compliance operator ``C`` (:class:`.compliance.BlockCompliance`:
FFT half-space per block plus an optional low-rank part) find

    s = C x + h - lambda >= 0,   x >= 0,   x . s = 0,   sum(x) = X,

``lambda`` the rigid approach (one pair: ``delta``; several pairs of one mesh: the
shared rotation ``theta``). This is the iteration of Polonsky & Keer (1999), section 3:
the gap is centred on its mean over the contact set of all blocks (which eliminates
``lambda``), the conjugate directions restart whenever non-contacting cells with
negative gap are re-admitted, and the total is restored by rescaling after every step;
preconditioned by the inverse Boussinesq symbol of each block (projected preconditioned
CG, Vollebregt 2014). The operator is an object, as the ``substrate.evaluate_disp`` of
ContactMechanics' ``ConstrainedConjugateGradients``: the single-pair solver
(:func:`.lcp.solve_lcp`, a one-block stack) and the torque-constrained multi-pair solver
(:func:`.mesh_lcp.solve_mesh_lcp`) both call :func:`constrained_cg`.

Work is confined to one window per loaded block (its contact box grown by
:data:`_MARGIN` cells, where cells are re-admitted; all windows of one shape, one
batched transform, :meth:`.compliance.BlockCompliance.window`); the windows grow (and
the conjugacy restarts) when a contact box leaves its window. The displacement
``u = C x`` is updated from the step's ``C t`` (``u <- s (u - tau C t)``, ``s`` the
rescaling) plus the cells the step clipped or re-admitted, from the real-space kernels
(and the low-rank part at those cells), so a step costs two batched transforms; it is
recomputed after a step departing in more than :data:`_TRACKED` cells and every
:data:`_REFRESH` steps. A step that re-admits
cells never ends the iteration. The gap is checked on the whole fields once when the
change first falls below :data:`_PROBE` and again at convergence; penetration outside
the windows (e.g. an unloaded pair closing) widens those blocks' windows over it, and
after :data:`_CHECKS` such rounds the iteration uses the whole fields. (The early probe
finds a pair that starts without load before the windows' iteration has converged to
the tolerance: s0003's multi-tooth solve with bending, where pair -3 closes only under
the larger rotation, takes 38 steps instead of 56.)

References
----------
I. A. Polonsky, L. M. Keer, Wear 231 (1999) 206-219 (constrained CG).
E. A. H. Vollebregt, J. Comput. Phys. 257 (2014) 333-351 (FFT preconditioner).
L. Pastewka, M. O. Robbins, Appl. Phys. Lett. 108 (2016) 221601 (ContactMechanics).
"""

from __future__ import annotations

from enum import Enum

import numpy as np
from numba import njit

from ..deprecation import moved_names
from ..threads import one_blas_thread
from .compliance import BlockCompliance
from .result import ContactResult, SolveStatus

__all__ = ["constrained_cg"]

#: Deprecated for one release: the CG's result is the family's :class:`.result.ContactResult`.
__getattr__ = moved_names(__name__, {"CgOutcome": "gearcontact.halfspace.result:ContactResult"})


class _Stop(Enum):
    """Why the iteration on one set of windows stopped."""

    CONVERGED = 1  # change below tolerance on a step without re-admissions
    GROW = 2       # a contact box left its window
    STALLED = 3    # rt <= 0 with t == 0: converged to round-off
    LOST = 4       # rt <= 0 otherwise: lost descent
    MAX_ITER = 5
    PENETRATES = 6  # the probe found cells outside the windows closing


#: The incrementally updated displacement is recomputed at least this often (steps).
_REFRESH = 50
#: At most this many clipped or re-admitted cells per step are added to ``C x`` one by
#: one (a cell costs one window of work, a recomputation about 30 windows).
_TRACKED = 16
#: Whole-field checks that may widen the windows before the whole fields are used.
_CHECKS = 3
#: Relative change at which the windows' iteration first checks the whole fields for
#: closing cells outside the windows (a pair that carried nothing at the start):
#: widening then saves converging to the tolerance twice.
_PROBE = 1e-2
#: Cells by which a block's window exceeds its contact box (where cells are re-admitted).
_MARGIN = 3


@njit(cache=True)
def _gap(u, h, x, g, gm, count):  # pragma: no cover - compiled
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
def _direction(z, x, g, t, gz_old, conj):  # pragma: no cover - compiled
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
def _step(x, x_old, t, g, r, u, kern, tau, goal, box, cells, dval
          ):  # pragma: no cover - compiled
    """``x <- max(x - tau t, 0)``, re-admission of cells with ``x = 0, g < 0`` at
    ``-tau g``, rescaling to ``sum(x) = goal``; ``box[k] = (j0, j1, i0, i1)``: contact
    box of block ``k`` after the step (``j1 = 0``: none).

    ``u = C x`` follows: ``u <- s (u - tau r + C d)`` with ``r = C t``, ``s`` the
    rescaling and ``d`` the departures from the linear step (clipped and re-admitted
    cells), added cell by cell from the kernel quadrants ``kern`` (``kern[k, |dj|,
    |di|]``, the operator's kernel) when there are at most ``len(dval)`` of them
    (``cells``, ``dval``: work space). Returns ``(conj, change, tracked, n_d, scale)``;
    ``tracked`` False: too many departures, ``u`` must be recomputed; otherwise the
    departures ``scale * dval[:n_d]`` at ``cells[:n_d]`` are what an operator's part
    outside the kernels (its low rank) still has to add.
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
    scale, change, tracked = goal / total, 0.0, n_d <= dval.size
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
    return conj, change, tracked, min(n_d, dval.size), scale


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


class _Windows:
    """One window per loaded block and the operator restricted to them.

    Block ``blocks[m]`` is seen through rows ``org[m, 0]:org[m, 0] + gy`` and columns
    ``org[m, 1]:org[m, 1] + gx`` of its field, a window holding its contact box grown by
    :data:`_MARGIN` cells (clamped to the field); ``whole``: every block on its whole
    field.
    """

    def __init__(self, op: BlockCompliance, box: np.ndarray, whole: bool):
        n_b, (ny, nx) = op.n_blocks, op.shape
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
        self.op = op.window(self.blocks, org, (gy, gx))

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



def constrained_cg(op: BlockCompliance, h: np.ndarray, x: np.ndarray, total: float, *,
                   tol: float, max_iter: int, precondition: bool = True) -> ContactResult:
    """Solve the load-constrained LCP of the module docstring.

    Parameters
    ----------
    op : BlockCompliance
        Compliance of the stack (its shape is the fields' shape).
    h : ndarray (blocks, ny, nx)
        Gaps, mm per unit of ``x``'s scale (``inf`` for padding cells: never loaded).
    x : ndarray (blocks, ny, nx)
        Start (>= 0, not all zero; rescaled to ``total``); not modified.
    total : float
        ``sum(x)`` to hold (> 0), in ``x``'s units.
    tol : float
        Stop when ``sum |x - x_prev| <= tol total`` on a step without re-admissions.
    max_iter : int
        Cap on the CG steps (all window rounds together).
    precondition : bool
        Use the Boussinesq-inverse preconditioner.

    Returns
    -------
    ContactResult
        ``x_stack`` (the solution, in ``x``'s units), ``u_stack_mm`` (``C x`` on the
        whole fields, computed exactly at the end, mm), ``iterations`` (CG steps) and
        ``status`` (CONVERGED, MAX_ITER or FAILED: lost descent).
    """
    x = np.asarray(x, float) * (total / float(np.sum(x)))
    if op.low_rank is None:
        return _solve(op, h, x, total, tol, max_iter, precondition)
    with one_blas_thread():  # the low-rank products: threaded BLAS spins on small sizes
        return _solve(op, h, x, total, tol, max_iter, precondition)


def _solve(op, h, x, total, tol, max_iter, precondition) -> ContactResult:
    """:func:`constrained_cg` after the start is scaled (``x`` is the iterate)."""
    box, whole, it, checks = _boxes(x), False, 0, 0
    while True:
        win = _Windows(op, box, whole)
        xr = win.gather(x)
        probed = []  # the probe's mask (it ends the windows' iteration when not None)

        def probe(xw):
            x.fill(0.0)
            win.scatter(xw, x)
            probed.append(_penetration(op, h, x, win))
            return probed[-1]

        stop, it, rbox = _window_steps(win, win.gather(h), xr, total, tol, it, max_iter,
                                       precondition, None if whole else probe)
        x.fill(0.0)
        win.scatter(xr, x)
        if stop is _Stop.GROW:
            box[win.blocks] = rbox + np.repeat(win.org, 2, axis=1)
            continue
        if stop is _Stop.PENETRATES:
            pen = probed[-1]
        else:
            u = op.evaluate_disp(x)
            ok = stop in (_Stop.CONVERGED, _Stop.STALLED)
            if not ok or whole:
                break
            pen = _penetration(op, h, x, win, u)
            if pen is None:
                break
        # a block closing outside the windows (e.g. a pair that carried nothing): widen
        # those blocks' windows over the penetrating cells; after a few rounds use the
        # whole fields
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
    status = SolveStatus.CONVERGED if ok else (
        SolveStatus.MAX_ITER if stop is _Stop.MAX_ITER else SolveStatus.FAILED)
    return ContactResult(x_stack=x, u_stack_mm=u, iterations=int(it), status=status,
                         solver="pk_cg")


def _penetration(op, h, x, win, u=None):
    """Cells outside ``win``'s windows that the loads ``x`` (whole fields) make
    penetrate (gap below the contact set's mean), as a mask over the fields; None if
    there are none. ``u``: ``C x`` when already computed."""
    s = (op.evaluate_disp(x) if u is None else u) + h
    on = x > 0.0
    s -= s[on].mean()
    for k, (j, i) in zip(win.blocks, win.org):  # the windows re-admitted cells
        s[k, j:j + win.shape[0], i:i + win.shape[1]] = 0.0
    pen = (s < 0.0) & ~on
    return pen if pen.any() else None


def _window_steps(win: _Windows, h, x, total, tol, it, max_iter, precondition, probe):
    """CG steps on ``win``'s windows (``h``, ``x``: window stacks; ``x`` updated in
    place). Returns ``(stop, it, box)``: a :class:`_Stop`, the step count so far and
    the contact boxes in window coordinates.

    ``probe(x)`` (or None), called once when the change first falls below
    :data:`_PROBE`, tells whether cells outside the windows close (a mask, else
    None): then the windows are widened at once, not after converging on them."""
    op = win.op
    box = _boxes(x)
    u = op.evaluate_disp(x, live=box[:, 1] > box[:, 0])
    r, z = np.empty(x.shape), np.empty(x.shape)
    g, gm, x_old, t = (np.empty(x.shape), np.empty(x.shape), np.empty(x.shape),
                       np.zeros(x.shape))
    count = np.zeros(x.shape[0], np.int64)
    kern = op.kernel_quadrants()
    cells, dval = np.zeros((_TRACKED, 3), np.int64), np.zeros(_TRACKED)
    gz_old, conj = 1.0, False
    while it < max_iter:
        it += 1
        _gap(u, h, x, g, gm, count)
        on = count > 0
        if precondition:
            op.approx_inverse(gm, out=z, live=on)
        else:
            z[...] = gm
        gz, gt = _direction(z, x, g, t, gz_old, conj)
        gz_old = gz if gz > 0.0 else 1.0
        op.evaluate_disp(t, out=r, live=on)
        rt = _dot(r, t)  # not np.vdot: BLAS threads spin on a busy machine
        if rt <= 0.0:  # converged to round-off (t == 0) or lost descent
            return (_Stop.STALLED if gz == 0.0 or rt == 0.0 else _Stop.LOST), it, box
        conj, change, tracked, n_d, scale = _step(x, x_old, t, g, r, u, kern, gt / rt,
                                                  total, box, cells, dval)
        if change <= tol * total and conj:  # not on a step that re-admitted cells:
            return _Stop.CONVERGED, it, box  # their loads are not balanced yet
        if probe is not None and change <= _PROBE * total and conj:
            if probe(x) is not None:
                return _Stop.PENETRATES, it, box
            probe = None
        if not win.holds(box):
            return _Stop.GROW, it, box
        if not tracked or it % _REFRESH == 0:
            op.evaluate_disp(x, out=u, live=box[:, 1] > box[:, 0])
        elif n_d and not op.exact_kernels:  # the departures' low-rank part
            op.add_low_rank_cells(u, cells[:n_d], scale * dval[:n_d])
    return _Stop.MAX_ITER, it, box
