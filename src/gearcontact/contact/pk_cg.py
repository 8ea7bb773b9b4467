"""Polonsky-Keer constrained conjugate gradient on a uniform window (``pk_cg``).

The fast solver of :func:`.lcp.solve_lcp`: for nodal loads ``w`` (N) on a uniform
window with gap ``h`` (mm) find ``s = C w + h - delta >= 0``, ``w >= 0``, ``w . s = 0``,
``sum(w) = W`` with the zero-padded FFT Love operator ``C`` of :mod:`.influence`
(Polonsky & Keer 1999, preconditioned after Vollebregt 2014). The element-wise work of
a step is compiled (numba); the transforms are the padding-pruned ones of
:mod:`.influence`.

References
----------
I. A. Polonsky, L. M. Keer, Wear 231 (1999) 206-219.
E. A. H. Vollebregt, J. Comput. Phys. 257 (2014) 333-351.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numba import njit, types
from scipy import fft as sfft

from .influence import FftInfluence, boussinesq_inverse

__all__ = ["pk_cg"]

#: pk_cg evaluates gaps on the contact bounding box grown by this many cells.
_PK_MARGIN = 3
#: pk_cg recomputes its incrementally updated displacement at least this often (steps).
_PK_REFRESH = 50
#: At most this many clipped or re-admitted cells per step are added to ``C w`` one by
#: one (a cell costs one pass over the gap region, a recomputation about 30).
_PK_TRACKED = 16


@lru_cache(maxsize=256)
def _pre_shape(shape: tuple[int, int]) -> tuple[int, int]:
    """Transform shape of the pk_cg preconditioner: the box padded by half per axis."""
    return tuple(sfft.next_fast_len(n + (n + 1) // 2, real=True) for n in shape)


@njit(cache=True)
def _pk_gap(ug, hg, wg, b0, b1, c0, c1, g, gmb):  # pragma: no cover - compiled
    """``g = C w + h`` centred on its mean over the contact set (``w > 0``); ``gmb`` is
    ``g`` on the box ``[b0:b1, c0:c1]`` at contact cells, 0 elsewhere."""
    # loops, not ``g[:] = ug + hg``: an array slice assignment makes numba compile its
    # shape-mismatch message formatting (~3 s of a fresh install's first solve)
    total, count = 0.0, 0
    for j in range(g.shape[0]):
        for i in range(g.shape[1]):
            g[j, i] = ug[j, i] + hg[j, i]
            if wg[j, i] > 0.0:
                total += g[j, i]
                count += 1
    mean = total / count
    for j in range(g.shape[0]):
        for i in range(g.shape[1]):
            g[j, i] -= mean
    for j in range(b0, b1):
        for i in range(c0, c1):
            gmb[j - b0, i - c0] = g[j, i] if wg[j, i] > 0.0 else 0.0


@njit(cache=True)
def _pk_direction(z, wb, gmb, tb, gz_old, conj):  # pragma: no cover - compiled
    """Project ``z`` onto the contact set (zero mean there, 0 off it), then make it
    the new direction ``z + (gz / gz_old) t`` (``conj``) in place; returns
    ``(gz, g.t)`` with ``gz = g.z``."""
    total, count = 0.0, 0
    for j in range(z.shape[0]):
        for i in range(z.shape[1]):
            if wb[j, i] > 0.0:
                total += z[j, i]
                count += 1
    mean, gz = total / count, 0.0
    for j in range(z.shape[0]):
        for i in range(z.shape[1]):
            z[j, i] = z[j, i] - mean if wb[j, i] > 0.0 else 0.0
            gz += gmb[j, i] * z[j, i]
    beta, gt = (gz / gz_old if conj else 0.0), 0.0
    for j in range(z.shape[0]):
        for i in range(z.shape[1]):
            if wb[j, i] > 0.0:
                z[j, i] += beta * tb[j, i]
            gt += gmb[j, i] * z[j, i]
    return gz, gt


@njit(cache=True)
def _dot(a, b):  # pragma: no cover - compiled
    """``a . b`` over all elements of two 2-D arrays (views) of one shape."""
    total = 0.0
    for j in range(a.shape[0]):
        for i in range(a.shape[1]):
            total += a[j, i] * b[j, i]
    return total


@njit(cache=True)
def _pk_step(wg, w_old, tg, g, rg, ug, kern, tau, load_n, cells, dval
             ):  # pragma: no cover - compiled
    """``w <- max(w - tau t, 0)``, re-admission of cells with ``w = 0, g < 0`` at
    ``-tau g``, rescaling to ``load_n``.

    ``rg`` (``C t`` on the region) becomes ``C w``: ``s (ug - tau rg + C d)``, ``s`` the
    rescaling, ``d`` the departures from the linear step (clipped and re-admitted
    cells), added cell by cell from the kernel quadrant ``kern`` (``kern[|dj|, |di|]``)
    when there are at most ``len(dval)`` of them (``cells``, ``dval``: work space).
    Returns ``(conj, tracked, change, j0, j1, i0, i1)``: ``tracked`` False means ``rg``
    is not ``C w`` (recompute); the contact box of the new ``w`` in region indices.
    """
    conj, total, n_d = True, 0.0, 0
    for j in range(wg.shape[0]):
        for i in range(wg.shape[1]):
            w_old[j, i] = wg[j, i]
            lin = wg[j, i] - tau * tg[j, i]
            v = max(lin, 0.0)
            if v == 0.0 and g[j, i] < 0.0:
                v, conj = -tau * g[j, i], False
            if v != lin:
                if n_d < dval.size:
                    cells[n_d, 0], cells[n_d, 1], dval[n_d] = j, i, v - lin
                n_d += 1
            wg[j, i] = v
            total += v
    scale, change, tracked = load_n / total, 0.0, n_d <= dval.size
    j0, j1, i0, i1 = wg.shape[0], 0, wg.shape[1], 0
    for j in range(wg.shape[0]):
        for i in range(wg.shape[1]):
            wg[j, i] *= scale
            change += abs(wg[j, i] - w_old[j, i])
            if tracked:
                rg[j, i] = scale * (ug[j, i] - tau * rg[j, i])
            if wg[j, i] > 0.0:
                j0, j1, i0, i1 = min(j0, j), max(j1, j + 1), min(i0, i), max(i1, i + 1)
    if tracked:
        for m in range(n_d):
            jc, ic, d = cells[m, 0], cells[m, 1], scale * dval[m]
            for j in range(wg.shape[0]):
                for i in range(wg.shape[1]):
                    rg[j, i] += d * kern[abs(j - jc), abs(i - ic)]
    return conj, tracked, change, j0, j1, i0, i1


#: The one compiled signature of each element-wise kernel: float64 arrays of any layout
#: (inputs read-only, so read-only views convert too). The views pk_cg passes are
#: contiguous or strided depending on the window, and numba would otherwise compile
#: every combination it meets (11 in one ``gearcontact analyze``, ~1 s each when fresh).
_IO = types.float64[:, :]
_IN = types.Array(types.float64, 2, "A", readonly=True)
_SIGNATURES = (
    (_pk_gap, (_IN, _IN, _IN) + (types.int64,) * 4 + (_IO, _IO)),
    (_pk_direction, (_IO, _IN, _IN, _IN, types.float64, types.boolean)),
    (_dot, (_IN, _IN)),
    (_pk_step, (_IO, _IO, _IN, _IN, _IO, _IN, _IN, types.float64, types.float64,
                types.int64[:, :], types.float64[:])),
)


def _compile_kernels() -> None:
    """Compile (or load from numba's cache) the kernels' one signature on first use,
    then let numba convert every other array layout to it instead of compiling."""
    for kernel, signature in _SIGNATURES:
        if kernel._can_compile:
            kernel.compile(signature)
            kernel.disable_compile()


def pk_cg(op: FftInfluence, h: np.ndarray, load_n: float, w0: np.ndarray, tol: float,
           max_iter: int, precondition: bool
           ) -> tuple[np.ndarray, np.ndarray, int, bool]:
    """Polonsky-Keer CG on a uniform window (loads in N).

    Returns ``(w, u, iterations, ok)`` with ``u = C w`` on the whole window.

    Follows Polonsky & Keer (1999), section 3: the gap is centred on its mean over the
    contact set (which eliminates the approach), conjugate directions restart whenever
    non-contacting cells with negative gap are re-admitted, and the load is rescaled
    to ``W`` after every step. With ``precondition`` the centred gap is replaced by
    ``z = P M P g`` (``M``: :func:`~.influence.boussinesq_inverse` on the contact set's
    bounding box padded by half its size, ``P``: removal of the mean over the contact
    set), i.e. projected preconditioned CG (Vollebregt 2014); this cuts the iterations
    about threefold.

    The gap is evaluated on the contact set's bounding box grown by
    :data:`_PK_MARGIN` cells (where cells are re-admitted). Its displacement ``C w`` is
    updated from the step's ``C t`` (``C w <- s (C w - tau C t)``, ``s`` the load
    rescaling) and, for the few cells a step clips or re-admits (at most
    :data:`_PK_TRACKED`), from the kernel in real space, so a step costs two transforms
    (``C t`` and the preconditioner); it is recomputed after steps that depart in more
    cells, when the box grows, and every :data:`_PK_REFRESH` steps. The element-wise work of a step is compiled
    (:func:`_pk_gap`, :func:`_pk_direction`, :func:`_pk_step`). At convergence the gap
    is checked on the whole window, and any penetration found there switches the
    iteration to whole-window gaps.
    """
    _compile_kernels()
    ny, nx = h.shape
    dx, dy = op.cell_size
    w = w0 * (load_n / w0.sum())
    t = np.zeros_like(w)
    gz_old, conj, whole = 1.0, False, False
    u, ur = None, (0, ny, 0, nx)  # u = C w on rows ur[0]:ur[1], columns ur[2]:ur[3]
    rows, cols = np.flatnonzero(w.any(axis=1)), np.flatnonzero(w.any(axis=0))
    j0, j1, i0, i1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1  # contact box
    cells, dval = np.zeros((_PK_TRACKED, 2), np.int64), np.zeros(_PK_TRACKED)
    for it in range(1, max_iter + 1):
        if whole:
            g0, g1, k0, k1 = 0, ny, 0, nx
        else:
            g0, g1 = max(j0 - _PK_MARGIN, 0), min(j1 + _PK_MARGIN, ny)
            k0, k1 = max(i0 - _PK_MARGIN, 0), min(i1 + _PK_MARGIN, nx)
        gs = (slice(g0, g1), slice(k0, k1))
        op_g = op.on_shape((g1 - g0, k1 - k0))
        wg = w[gs]  # a view holding all of w's support
        if (u is not None and it % _PK_REFRESH and ur[0] <= g0 and g1 <= ur[1]
                and ur[2] <= k0 and k1 <= ur[3]):
            ug = u[g0 - ur[0]:g1 - ur[0], k0 - ur[2]:k1 - ur[2]]
        else:
            ug = op_g(wg)
        g, gmb = np.empty(ug.shape), np.empty((j1 - j0, i1 - i0))
        _pk_gap(ug, h[gs], wg, j0 - g0, j1 - g0, i0 - k0, i1 - k0, g, gmb)
        # contiguous always: one compiled layout of _pk_direction (the FFT crop is a
        # strided view for some window shapes; a fresh install would compile it mid-solve)
        z = np.ascontiguousarray(boussinesq_inverse(
            gmb, dx_mm=dx, dy_mm=dy, e_star_mpa=op.e_star_mpa,
            padded_shape=_pre_shape(gmb.shape))) if precondition else gmb.copy()
        gz, gt = _pk_direction(z, w[j0:j1, i0:i1], gmb, t[j0:j1, i0:i1], gz_old, conj)
        t.fill(0.0)
        t[j0:j1, i0:i1] = z
        gz_old = gz if gz > 0.0 else 1.0
        tg = t[gs]
        rg = op_g(tg)  # C t on the gap region
        rt = _dot(rg, tg)  # not np.vdot: BLAS threads spin on a busy machine
        if rt <= 0.0:  # converged to round-off (t == 0) or lost descent
            return w, op(w), it, gz == 0.0 or rt == 0.0
        conj, tracked, change, b0, b1, c0, c1 = _pk_step(
            wg, np.empty(wg.shape), tg, g, rg, ug, op_g.kernel_quadrant(), gt / rt, load_n,
            cells, dval)
        u, ur = (rg if tracked else op_g(wg)), (g0, g1, k0, k1)
        j0, j1, i0, i1 = g0 + b0, g0 + b1, k0 + c0, k0 + c1
        if change <= tol * load_n:
            u_all = op(w)
            if whole:
                return w, u_all, it, True
            s = u_all + h
            s -= s[w > 0.0].mean()
            s[gs] = 0.0  # inside the gap region the iteration re-admitted cells
            if not (s < 0.0).any():
                return w, u_all, it, True
            whole = True  # penetration outside the margin box: use the whole window
            u, ur = u_all, (0, ny, 0, nx)
    return w, op(w), max_iter, False
