"""Compliance operators of the contact LCP: block-diagonal half-space plus low rank.

The constrained conjugate gradient of :mod:`.constrained_cg` sees the compliance only
through an operator object (as the ``substrate.evaluate_disp`` of ContactMechanics'
``ConstrainedConjugateGradients``, Pastewka & Robbins 2016): :class:`BlockCompliance`
maps a stack of nodal-load fields ``x[k]`` (N) to displacements (mm)

    u[k] = C_k x[k] / s_k + F_k (F_k^T x[k]),

``C_k`` the zero-padded FFT Love operator of block ``k`` (its own cell size; both
half-spaces in E*, :mod:`.influence`), ``s_k`` a scale (the squared lever of a tooth
pair in the torque-constrained LCP, 1 for a single pair) and ``F_k`` an optional
low-rank factor of a further compliance ``G_k = F_k F_k^T`` (tooth bending,
:mod:`.tooth_bending`). Different blocks never interact (different teeth), so the
operator is block diagonal; a single pair is a one-block stack.

The operator also supplies what the iteration needs beside ``evaluate_disp``: the
Boussinesq-inverse preconditioner of the half-space part (Vollebregt 2014), its
real-space kernels (for cell-by-cell displacement updates, exact only without a
low-rank part) and its restriction to one window per block (:meth:`BlockCompliance.window`).

References
----------
L. Pastewka, M. O. Robbins, "Contact area of rough spheres: large scale simulations and
simple scaling laws", Appl. Phys. Lett. 108 (2016) 221601 (ContactMechanics' CG solver).
E. A. H. Vollebregt, J. Comput. Phys. 257 (2014) 333-351 (FFT preconditioner).
M. Kolivand, A. Kahraman, *Mechanism and Machine Theory* 44(10), 2009, 1848-1865
(bending compliance added to the half-space one, block diagonal per tooth).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..validation import InputRangeError
from .influence import StackedFftInfluence

__all__ = ["BlockCompliance", "add_low_rank"]


def add_low_rank(f: np.ndarray, v: np.ndarray, out: np.ndarray) -> np.ndarray:
    """``out[k] += F_k (F_k^T v[k])`` for factors ``f`` (blocks, ny, nx, r) and fields
    ``v`` (blocks, ny, nx); double-precision sums whatever ``f``'s precision."""
    c = np.zeros((f.shape[0], f.shape[3]))
    _project(f, v, c)
    _expand(f, c, out)
    return out


@njit(cache=True, fastmath=True)
def _project(f, v, c):  # pragma: no cover - compiled
    """``c[k] += F_k^T v[k]``, skipping the cells where ``v`` is 0 (the loads and the
    CG directions vanish off the contact set, most of a field)."""
    for k in range(f.shape[0]):
        for j in range(f.shape[1]):
            for i in range(f.shape[2]):
                a = v[k, j, i]
                if a != 0.0:
                    for q in range(f.shape[3]):
                        c[k, q] += a * f[k, j, i, q]


@njit(cache=True, fastmath=True)
def _expand(f, c, out):  # pragma: no cover - compiled
    """``out[k] += F_k c[k]``."""
    for k in range(f.shape[0]):
        for j in range(f.shape[1]):
            for i in range(f.shape[2]):
                acc = 0.0
                for q in range(f.shape[3]):
                    acc += f[k, j, i, q] * c[k, q]
                out[k, j, i] += acc


class BlockCompliance:
    """Block-diagonal compliance ``C_k / s_k + F_k F_k^T`` of a stack of fields.

    Parameters
    ----------
    shape : tuple of int
        Field shape ``(ny, nx)`` shared by the blocks (pad smaller fields).
    cell_sizes : sequence of (float, float)
        ``(dx_mm, dy_mm)`` per block, mm.
    e_star_mpa : float
        Composite modulus E* of the two half-spaces, MPa.
    scales : sequence of float, optional
        ``s_k`` per block (default 1), dimensionless or mm² (the caller's units of
        ``x``: loads N, or torque shares N·mm with ``s_k = l_k²``).
    low_rank : ndarray (blocks, ny, nx, r), optional
        Factors ``F_k`` of the further compliance ``G_k = F_k F_k^T``, in
        (mm/N)^(1/2) per unit of ``x`` (kept in single precision); None: the
        half-space alone.
    pre_shape : tuple of int, optional
        Transform shape of the preconditioner (default the operator's padded one).
    """

    def __init__(self, shape, cell_sizes, *, e_star_mpa: float, scales=None,
                 low_rank: np.ndarray | None = None, pre_shape=None):
        self.cell_sizes = [tuple(float(c) for c in cs) for cs in cell_sizes]
        self.scales = np.ones(len(self.cell_sizes)) if scales is None else \
            np.asarray(scales, float)
        self.e_star_mpa = float(e_star_mpa)
        self.half_space = StackedFftInfluence(shape, self.cell_sizes, e_star_mpa=e_star_mpa,
                                              scales=self.scales, pre_shape=pre_shape)
        self.shape, self.n_blocks = self.half_space.shape, len(self.cell_sizes)
        if low_rank is not None:
            # single precision storage halves the memory the CG streams per step; the
            # sums stay double (G = F F^T exactly for the rounded F: still symmetric
            # and semi-definite, entries within 1e-7 of the double factor's)
            low_rank = np.asarray(low_rank, np.float32)
            if low_rank.shape[:3] != (self.n_blocks,) + self.shape:
                raise InputRangeError("low_rank", f"shape {low_rank.shape}",
                                      f"({self.n_blocks}, {self.shape[0]}, "
                                      f"{self.shape[1]}, rank)")
        self.low_rank = low_rank

    @property
    def exact_kernels(self) -> bool:
        """Whether :meth:`kernel_quadrants` is the whole operator (no low-rank part):
        then a displacement may be updated cell by cell from them."""
        return self.low_rank is None

    def evaluate_disp(self, loads: np.ndarray, out: np.ndarray | None = None,
                      live: np.ndarray | None = None) -> np.ndarray:
        """Displacements (mm) of the loads ``x`` (stack ``(blocks, ny, nx)``).

        ``live`` (bool per block) restricts the half-space work to those blocks: the
        others must carry no load. ``out`` receives the result.
        """
        out = self.half_space.apply(loads, out=out, live=live)
        if self.low_rank is not None:
            add_low_rank(self.low_rank, loads, out)
        return out

    def add_low_rank_cells(self, out: np.ndarray, cells: np.ndarray,
                           values: np.ndarray) -> np.ndarray:
        """``out += F (F^T d)`` for loads ``d`` at a few cells ``(block, row, col)``
        (``values`` in ``x``'s units): the low-rank displacement of sparse loads, one
        product per block instead of a whole-field ``F^T``."""
        f = self.low_rank
        c = np.zeros((f.shape[0], f.shape[3]))
        np.add.at(c, cells[:, 0], f[cells[:, 0], cells[:, 1], cells[:, 2]] * values[:, None])
        _expand(f, c, out)
        return out

    def approx_inverse(self, displacement_mm: np.ndarray, out: np.ndarray | None = None,
                       live: np.ndarray | None = None) -> np.ndarray:
        """The half-space part's Boussinesq-inverse preconditioner
        (:meth:`.influence.StackedFftInfluence.approx_inverse`)."""
        return self.half_space.approx_inverse(displacement_mm, out=out, live=live)

    def kernel_quadrants(self) -> np.ndarray:
        """Half-space kernels ``K_k[|oy|, |ox|] / s_k`` (blocks, ny, nx), mm/N."""
        return self.half_space.kernel_quadrants()

    def window(self, blocks: np.ndarray, origins: np.ndarray, shape) -> "BlockCompliance":
        """The operator of the blocks ``blocks`` restricted to one window each: rows
        ``origins[m, 0]`` + ``0..shape[0]-1`` and columns ``origins[m, 1]`` +
        ``0..shape[1]-1`` of block ``blocks[m]``. The preconditioner is periodic on the
        window (on s0003 as few iterations as padding by half, for half the transform).
        """
        gy, gx = (int(n) for n in shape)
        low = None if self.low_rank is None else np.ascontiguousarray(np.stack(
            [self.low_rank[k, j:j + gy, i:i + gx] for k, (j, i) in zip(blocks, origins)]))
        return BlockCompliance((gy, gx), [self.cell_sizes[k] for k in blocks],
                               e_star_mpa=self.e_star_mpa, scales=self.scales[blocks],
                               low_rank=low, pre_shape=(gy, gx))
