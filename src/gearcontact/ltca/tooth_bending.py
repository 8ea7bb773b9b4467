"""Tooth bending blocks of the multi-pair LCP: the shell compliance at a pair's cells.

A tooth pair's field (:mod:`.lte_pairs`) is a grid of tangent-plane cells around the
pair's mating point. Each cell lies on the pinion flank and on the gear flank at
parameters given, to first order, by the tangent-plane map of the mating point
(:func:`gearcontact.tca.stencil.tangent_parameters`; the compliance is smooth over the
flank, so the first-order position is ample). The bending compliance of the pair at its
cells is that of the pinion tooth plus that of the gear tooth,
``G = G_pinion + G_gear`` (both deflect away from the contact along the common normal),
each the low-rank shell operator of :mod:`gearcontact.structure.shell`. It is handed to
:func:`.mesh_lcp.solve_mesh_lcp` as one factor ``F`` with ``G = F F^T``: evaluated
exactly on an 8 x 24 sub-lattice of the cells, compressed there by a pivoted Cholesky
factorization of ``F F^T`` (dropped entries below 1e-6 of the largest compliance), and
interpolated to all cells by cubic splines (:meth:`ToothBending.factor`). The rows
at the sub-lattice are themselves interpolated, by a tensor cubic spline over a fine
lattice of the whole flank made once per tooth and side (:func:`flank_rows`), so a
field costs a few small products instead of the Ritz functions at 192 points.

Cells outside a flank's parameter box (off-flank cells, which never carry load) take
the compliance of the nearest box point.

With ``near_field`` (:func:`tooth_bending`, off by default) a tooth without a block
below its fillet is the Ritz solid tooth instead of the plate, and its part of ``G`` is
the solid's *far field* by Vijayakar's split
(:func:`gearcontact.structure.near_field.solid_far_field_matrix`: the solid's
displacement at the mid-surface below a cell minus the half-space's there; the LCP's
half-space supplies the rest). That part is symmetric but indefinite (negative near the
root, docs/bending.md sec. 13), so the block's compliance is compressed at the
sub-lattice by a symmetric eigendecomposition that keeps the signs
(:class:`SignedFactor`, ``G = F+ F+^T - F- F-^T``) instead of the pivoted Cholesky.

References
----------
N. J. Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM, 2002,
sec. 10.3 (pivoted Cholesky).
M. Kolivand, A. Kahraman, "A load distribution model for hypoid gears using ease-off
topography and shell theory", *Mechanism and Machine Theory* 44(10), 2009, 1848-1865
(block-diagonal bending compliance per tooth, added to the half-space compliance).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit
from scipy.interpolate import CubicSpline, make_interp_spline

from ..analytic.hertz import hamrock_brewe_hertz
from ..structure.near_field import solid_far_field_matrix
from ..structure.shell import ORDER, ORDER_FACE, ShellModel, build_shell, tooth_shell
from ..threads import one_blas_thread
from ..validation import InputRangeError, check_range

__all__ = ["conjugate_compliance", "pair_bending_compliance", "ToothBending", "FlankRows",
           "tooth_bending", "bending_stack", "flank_map", "flank_rows", "SignedFactor",
           "solid_tooth"]

#: Relative cut of the compressed bending factor: the pivoted Cholesky stops when the
#: largest remaining diagonal of F F^T is below this fraction of the largest diagonal
#: (every entry of the dropped part is then below it too, G being semi-definite).
#: 1e-6 is far below the flank-rows spline's error (~1e-4) and keeps rank ~69 per s0003
#: field instead of ~105 at 1e-10, with TE, rotation, shares and CP_max unchanged to
#: 1e-5 relative.
_CUT = 1e-6
#: Lattice (face, height) of tooth coordinates on which :func:`flank_map` reduces a
#: flank's compliance (the Ritz functions are polynomials of order <= 16 along the face).
_MAP_GRID = (97, 33)
#: Relative eigenvalue cut of :func:`flank_map`: the dropped part changes a compliance
#: entry by at most cut x (lattice points) = 3e-9 of the largest diagonal.
_MAP_CUT = 1e-12
#: Sub-lattice (rows along the field's minor axis t, columns along its major axis s,
#: which runs along the face) on which the shell operator is evaluated exactly.
_NODES = (8, 24)
#: Lattice (face, height) of tooth coordinates over which :func:`flank_rows` splines a
#: flank's factor rows: the compliance from them is within 8.5e-5 (pinion) and 1.8e-5
#: (gear) of the largest self-compliance of the exact rows on s0003 (97 x 33: 5e-3,
#: 129 x 33: 1.2e-3; the error falls as h^4 along the face, where the Ritz functions
#: reach degree 16), well inside the 2e-3 of the sub-lattice interpolation.
_ROWS_GRID = (193, 33)


@dataclass(frozen=True, eq=False)
class SignedFactor:
    """A symmetric, possibly indefinite compliance over a field's cells,
    ``G = F+ F+^T - F- F-^T`` (mm/N).

    Attributes
    ----------
    positive, negative : ndarray (ny, nx, r+) and (ny, nx, r-)
        The factors of the positive and negative parts, (mm/N)^(1/2) (r- may be 0).
    """

    positive: np.ndarray
    negative: np.ndarray

    def __post_init__(self):
        for name in ("positive", "negative"):
            f = np.asarray(getattr(self, name), dtype=float)
            if f.ndim != 3 or not np.isfinite(f).all():
                raise InputRangeError(f"signed factor {name}", f"shape {f.shape}",
                                      "a finite array (ny, nx, rank)")
            object.__setattr__(self, name, f)
        if self.positive.shape[:2] != self.negative.shape[:2]:
            raise InputRangeError("signed factor shapes",
                                  (self.positive.shape, self.negative.shape),
                                  "the same cells (ny, nx) in both parts")

    @property
    def shape(self) -> tuple[int, int]:
        """Cells (ny, nx) of the field."""
        return self.positive.shape[:2]

    @classmethod
    def from_dense(cls, matrix: np.ndarray, shape, *, cut: float = _CUT) -> "SignedFactor":
        """The signed factor of a dense symmetric ``matrix`` (n, n) over the cells of
        ``shape`` (row-major, n = ny nx; mm/N): its eigenvectors scaled by
        ``sqrt(|lambda|)``, split by the sign of ``lambda``; eigenvalues with ``|lambda|``
        below ``cut`` of its largest |entry| are dropped (every entry of the dropped part
        is below that; the plate's compression cut).

        Raises
        ------
        InputRangeError
            For a matrix of the wrong shape, not finite or not symmetric (relative
            1e-10 of its largest entry).
        """
        ny, nx = (int(n) for n in shape)
        g = np.asarray(matrix, dtype=float)
        if g.shape != (ny * nx, ny * nx) or not np.isfinite(g).all():
            raise InputRangeError("correction matrix", f"shape {g.shape}",
                                  f"a finite ({ny * nx}, {ny * nx}) matrix")
        top = float(np.abs(g).max()) or 1.0
        asym = float(np.abs(g - g.T).max())
        if asym > 1e-10 * top:
            raise InputRangeError("correction matrix asymmetry |G - G^T| (mm/N)", asym,
                                  f"<= 1e-10 x its largest entry {top:.3e}")
        pos, neg = _signed_compress(0.5 * (g + g.T), cut)
        return cls(pos.reshape(ny, nx, -1), neg.reshape(ny, nx, -1))

    def matrix(self) -> np.ndarray:
        """The dense ``G`` (n, n), mm/N, over the cells in row-major order."""
        n = self.shape[0] * self.shape[1]
        p = self.positive.reshape(n, self.positive.shape[2])
        m = self.negative.reshape(n, self.negative.shape[2])
        return p @ p.T - m @ m.T


def _signed_compress(gram: np.ndarray, cut: float) -> tuple[np.ndarray, np.ndarray]:
    """(F+ (n, r+), F- (n, r-)) with ``F+ F+^T - F- F-^T`` = the symmetric ``gram`` up to
    its eigenvalues below ``cut`` x its largest |entry| (LAPACK's symmetric eigensolver,
    one BLAS thread): every entry of the dropped part is below that too
    (``|sum_k lambda_k v_ik v_jk| <= max |lambda_k|`` over unit eigenvectors), the plate's
    bound (:func:`_pivoted_cholesky`)."""
    with one_blas_thread():
        lam, vec = np.linalg.eigh(gram)
    keep = np.abs(lam) > cut * max(float(np.abs(gram).max()), np.finfo(float).tiny)
    pos, neg = keep & (lam > 0.0), keep & (lam < 0.0)
    return vec[:, pos] * np.sqrt(lam[pos]), vec[:, neg] * np.sqrt(-lam[neg])


@dataclass(frozen=True, eq=False)
class ToothBending:
    """Shell models of one pinion and one gear tooth for the contacts of one side.

    Attributes
    ----------
    pinion, gear : ShellModel
    side : str
        "drive" or "coast".
    scale : float
        Factor on the bending compliance (1: the model; 0: rigid teeth, the
        zero-compliance limit; > 1: softer teeth, e.g. a lower Young's modulus E/scale).
    near_field : bool
        A tooth that is a Ritz solid (``solid_degrees`` set, :func:`solid_tooth`)
        contributes its far field by Vijayakar's split (module docstring), and
        :meth:`factor` returns a :class:`SignedFactor`; False: every tooth's full
        shell compliance, a semi-definite factor (the default path, unchanged).
    """

    pinion: ShellModel
    gear: ShellModel
    side: str
    scale: float = 1.0
    near_field: bool = False

    def factor(self, uv_pinion: np.ndarray, uv_gear: np.ndarray, shape, *,
               nodes: tuple[int, int] = _NODES) -> np.ndarray:
        """Bending factor ``F`` (ny, nx, r), single precision, at a grid of cells with
        pinion / gear flank parameters ``uv_*`` (ny * nx, 2, row-major over ``shape``),
        mm: ``G = F F^T`` (mm/N; the LCP applies it in single precision with double
        sums, :class:`~..halfspace.compliance.BlockCompliance`).

        The shell operator is evaluated exactly on a ``nodes`` (rows, columns)
        sub-lattice of the cells (all cells of a shorter axis), compressed there, and
        its rows are interpolated to every cell by tensor cubic splines over the cell
        indices (the compliance varies on the Ritz scale along the face, ~1 mm, the
        cells on ~0.1-0.2 mm; the interpolation error is checked below 2e-3 of the
        largest entry in the tests).
        """
        ny, nx = (int(n) for n in shape)
        if self.scale == 0.0:
            return np.zeros((ny, nx, 1))
        jy = _sub_lattice(ny, nodes[0])
        jx = _sub_lattice(nx, nodes[1])
        pick = (jy[:, None] * nx + jx[None, :]).ravel()
        if self.near_field:
            return self._signed_factor(uv_pinion[pick], uv_gear[pick], jy, jx, ny, nx)
        f = np.concatenate([flank_rows(shell, self.side).rows(uv[pick]) for shell, uv in
                            ((self.pinion, uv_pinion), (self.gear, uv_gear))], axis=1)
        f *= np.sqrt(self.scale)
        # compress on the nodes: pivoted Cholesky (compiled) of the Gram matrix F F^T
        # (BLAS on one thread; LAPACK's SVD / eigh, or threaded BLAS, cost 30-60x more
        # on a busy machine). The Gram in single precision (half the time): its entries
        # err by < 5e-7 of the largest, below the cut and 100x below the rows' spline
        # error; s0003's TE, rotation, shares and CP_max move by < 3e-6 relative
        with one_blas_thread():
            f32 = f.astype(np.float32)
            gram = (f32 @ f32.T).astype(np.float64)
        fc = _pivoted_cholesky(gram, _CUT).reshape(len(jy), len(jx), -1)
        wy, wx = _spline_weights(jy, ny), _spline_weights(jx, nx)
        # two small contractions, BLAS on one thread (threaded: ~20 ms each on a busy
        # machine; einsum's loops: 2-3 ms)
        with one_blas_thread():
            half = np.matmul(wx, fc.astype(np.float32))             # (a, nx, r)
            return (wy @ half.reshape(len(jy), -1)).reshape(ny, nx, -1)


    def _signed_factor(self, uv_pinion, uv_gear, jy, jx, ny, nx) -> SignedFactor:
        """:meth:`factor` with ``near_field``: the nodes' compliance ``G`` (a solid
        tooth's far field, :func:`~gearcontact.structure.near_field.solid_far_field_matrix`,
        plus the other tooth's ``F F^T``) compressed with its signs
        (:func:`_signed_compress`, cut :data:`_CUT`) and each part interpolated to the
        cells by the same splines."""
        gram = np.zeros((len(uv_pinion),) * 2)
        with one_blas_thread():
            for shell, uv in ((self.pinion, uv_pinion), (self.gear, uv_gear)):
                if shell.solid_degrees is not None:
                    gram += solid_far_field_matrix(shell, _flank_points(shell, self.side, uv))
                else:
                    f = flank_rows(shell, self.side).rows(uv)
                    gram += f @ f.T
        pos, neg = _signed_compress(self.scale * gram, _CUT)
        wy, wx = (w.astype(np.float64) for w in (_spline_weights(jy, ny),
                                                 _spline_weights(jx, nx)))
        out = []
        for part in (pos, neg):
            fc = part.reshape(len(jy), len(jx), -1)
            half = np.matmul(wx, fc)
            out.append((wy @ half.reshape(len(jy), -1)).reshape(ny, nx, -1))
        return SignedFactor(*out)


def _flank_points(shell: ShellModel, side: str, uv: np.ndarray):
    """The tooth's load points at flank parameters ``uv`` (n, 2), mm, clipped to the
    flank box as :meth:`FlankRows.rows` clips them."""
    tooth = shell.body
    flank = getattr(tooth, side)
    u = np.clip(uv[:, 0], *flank.u_range)
    v = np.clip(uv[:, 1], *flank.v_range)
    return tooth.points_at(side, *tooth.tooth_coordinates(side, u, v))


@lru_cache(maxsize=16)
def solid_tooth(shell: ShellModel) -> ShellModel:
    """The Ritz solid tooth of a shell whose fillet leaves no block below it (the
    no-block branch of :func:`~gearcontact.structure.shell.build_shell` with
    ``solid_tooth``, its default degrees, docs/bending.md sec. 13); a shell with a block
    (or a solid already) is returned as it is. Cached per shell model."""
    if shell.rim_block or shell.solid_degrees is not None or shell.rim is None:
        return shell
    return build_shell(shell.body, order=shell.order, order_face=shell.order_face,
                       rim=shell.rim, rim_block=True, solid_tooth=True)


@lru_cache(maxsize=16)
def flank_map(shell: ShellModel, side: str) -> np.ndarray:
    """``M = L^-T V_r`` (m, r): factor rows of the tooth's flank ``side`` are
    ``phi(x) M`` (mm/N)^(1/2), ``phi`` the Ritz load vectors of the points.

    ``V_r``: the eigenvectors of ``B^T B`` (``B = Phi L^-T`` on a :data:`_MAP_GRID`
    lattice over the whole flank) with eigenvalues above :data:`_MAP_CUT` of the
    largest: the compliance ``B B^T`` of the flank in the fewest Ritz directions
    (pinion 228, gear 195 of 561 on s0003). Made once per shell model and side, so a
    field's factor is one product instead of a triangular solve per point.
    """
    xi, eta = np.meshgrid(np.linspace(-1.0, 1.0, _MAP_GRID[0]),
                          np.linspace(-1.0, 1.0, _MAP_GRID[1]), indexing="ij")
    b = shell.compliance(shell.body.points_at(side, xi.ravel(), eta.ravel())).factor
    with one_blas_thread():
        lam, vec = np.linalg.eigh(b.T @ b)
        out = shell.inverse_cholesky_t @ vec[:, lam > _MAP_CUT * lam.max()]
    out.setflags(write=False)
    return out


@dataclass(frozen=True, eq=False)
class FlankRows:
    """Factor rows ``phi(x) M`` (:func:`flank_map`) of one tooth flank as a tensor
    cubic spline over tooth coordinates (not-a-knot, on :data:`_ROWS_GRID`).

    Attributes
    ----------
    shell : ShellModel
    side : str
    knots_xi, knots_eta : ndarray
        B-spline knots along the face (xi) and the height (eta).
    coef : ndarray (n_xi, n_eta, r), float32
        Spline coefficients, (mm/N)^(1/2).
    """

    shell: ShellModel
    side: str
    knots_xi: np.ndarray
    knots_eta: np.ndarray
    coef: np.ndarray

    def rows(self, uv: np.ndarray) -> np.ndarray:
        """Rows (n, r) at flank parameters ``uv`` (n, 2), mm (clipped to the flank
        box: off-flank cells take the nearest box point's compliance)."""
        tooth = self.shell.body
        flank = getattr(tooth, self.side)
        u = np.clip(uv[:, 0], *flank.u_range)
        v = np.clip(uv[:, 1], *flank.v_range)
        xi, eta = tooth.tooth_coordinates(self.side, u, v)
        ix, wx = _basis(self.knots_xi, xi)
        ie, we = _basis(self.knots_eta, eta)
        return _tensor_rows(self.coef, ix, wx, ie, we)


@lru_cache(maxsize=16)
def flank_rows(shell: ShellModel, side: str) -> FlankRows:
    """The :class:`FlankRows` of a tooth's flank ``side`` (made once per shell model
    and side: the rows at the lattice, then a spline along each axis)."""
    xi, eta = (np.linspace(-1.0, 1.0, n) for n in _ROWS_GRID)
    x, e = np.meshgrid(xi, eta, indexing="ij")
    phi = shell.load_vectors(shell.body.points_at(side, x.ravel(), e.ravel()))
    with one_blas_thread():
        rows = (phi @ flank_map(shell, side)).reshape(len(xi), len(eta), -1)
    along_xi = make_interp_spline(xi, rows, k=3, axis=0)
    along_eta = make_interp_spline(eta, along_xi.c, k=3, axis=1)
    # single precision: half the memory a field's rows stream (~20 MB for both
    # teeth); the rows' error stays the spline's (<= 1e-4 of the largest compliance,
    # the rounding adds < 1e-9), and the sums of _tensor_rows stay double
    coef = np.ascontiguousarray(np.moveaxis(along_eta.c, 0, 1), dtype=np.float32)
    for a in (along_xi.t, along_eta.t, coef):
        a.setflags(write=False)
    return FlankRows(shell=shell, side=side, knots_xi=along_xi.t, knots_eta=along_eta.t,
                     coef=coef)


@njit(cache=True)
def _basis(knots, x):  # pragma: no cover - compiled
    """(first index (n,), values (n, 4)) of the four cubic B-splines not zero at x
    (``x`` within the knots' base interval): Cox-de Boor, Piegl & Tiller, *The NURBS
    Book*, 2nd ed., 1997, algorithm A2.2."""
    n_coef = knots.size - 4
    first = np.empty(x.size, np.int64)
    out = np.empty((x.size, 4))
    left, right = np.empty(4), np.empty(4)
    for p in range(x.size):
        xv = x[p]
        m = min(max(np.searchsorted(knots, xv, side="right") - 1, 3), n_coef - 1)
        first[p] = m - 3
        out[p, 0] = 1.0
        for j in range(1, 4):
            left[j] = xv - knots[m + 1 - j]
            right[j] = knots[m + j] - xv
            saved = 0.0
            for r in range(j):
                tmp = out[p, r] / (right[r + 1] + left[j - r])
                out[p, r] = saved + right[r + 1] * tmp
                saved = left[j - r] * tmp
            out[p, j] = saved
    return first, out


@njit(cache=True)
def _tensor_rows(coef, ix, wx, ie, we):  # pragma: no cover - compiled
    """sum_ab wx[p, a] we[p, b] coef[ix[p] + a, ie[p] + b, :] per point p."""
    n, r = ix.shape[0], coef.shape[2]
    out = np.zeros((n, r))
    for p in range(n):
        for a in range(4):
            for b in range(4):
                w = wx[p, a] * we[p, b]
                c = coef[ix[p] + a, ie[p] + b]
                for q in range(r):
                    out[p, q] += w * c[q]
    return out


@njit(cache=True)
def _pivoted_cholesky(g, cut):  # pragma: no cover - compiled
    """R (n, r) with R R^T = G (the Gram matrix F F^T, n x n) up to entries below
    ``cut`` x its largest diagonal: diagonally pivoted, stopped early (Higham 2002,
    sec. 10.3). The columns are built as rows of R^T by contiguous updates (the
    same sums in the same order as dot products, 2.5x faster)."""
    n = g.shape[0]
    d = np.empty(n)
    for i in range(n):
        d[i] = g[i, i]
    top = d.max()
    rt = np.zeros((n, n))
    col = np.empty(n)
    rank = 0
    for k in range(n):
        p = np.argmax(d)
        if d[p] <= cut * top:
            break
        piv = np.sqrt(d[p])
        for i in range(n):
            col[i] = g[i, p]
        for q in range(k):
            c = rt[q, p]
            for i in range(n):
                col[i] -= rt[q, i] * c
        for i in range(n):
            v = col[i] / piv
            rt[k, i] = v
            d[i] -= v * v
        d[p] = 0.0
        rank = k + 1
    return rt[:max(rank, 1)].T.copy()


def _sub_lattice(n: int, nodes: int) -> np.ndarray:
    """Indices of ``min(n, nodes)`` cells spread evenly over 0..n-1 (ends included)."""
    return np.unique(np.rint(np.linspace(0, n - 1, min(n, nodes))).astype(int))


def _spline_weights(at: np.ndarray, n: int) -> np.ndarray:
    """(n, len(at)) weights of the not-a-knot cubic spline through samples at ``at``
    evaluated at 0..n-1 (identity when every index is a sample)."""
    return _spline_weights_cached(tuple(int(a) for a in at), int(n))


@lru_cache(maxsize=64)
def _spline_weights_cached(at: tuple, n: int) -> np.ndarray:
    # every field of one LTE has the same cell count: built once, not once per field
    if len(at) == n:
        out = np.eye(n)
    elif len(at) < 4:
        out = np.stack([np.interp(np.arange(n), at, e) for e in np.eye(len(at))], axis=1)
    else:
        out = CubicSpline(np.asarray(at, float), np.eye(len(at)))(np.arange(n))
    out = out.astype(np.float32)  # the factor is used in single precision (compliance)
    out.setflags(write=False)
    return out


def tooth_bending(flanks, pair, *, side: str, order: int = ORDER, order_face: int = ORDER_FACE,
                  scale: float = 1.0, near_field: bool = False) -> ToothBending:
    """The :class:`ToothBending` of a pair (shell models cached per flank set; orders
    and the members' rims as calibrated, :func:`~gearcontact.structure.shell.tooth_shell`).

    ``near_field``: a tooth without a block below its fillet becomes the Ritz solid
    (:func:`solid_tooth`) and contributes its far field by Vijayakar's split (module
    docstring; docs/bending.md sec. 13, session 27); teeth with a block are unchanged,
    and a pair whose teeth all have one keeps the default path exactly (its
    :class:`ToothBending` has ``near_field`` False). Off by default: the split is
    validated against the FE at patch widths of 0.6-1 mm, not below (docs/bending.md
    sec. 13, session 27)."""
    check_range("bending scale", scale, 0.0, 1e6)
    if not isinstance(near_field, bool):
        raise InputRangeError("near_field", near_field, "True or False")
    shells = [tooth_shell(flanks, member, material=getattr(pair, f"{member}_material"),
                          order=order, order_face=order_face) for member in ("pinion", "gear")]
    if near_field:
        shells = [solid_tooth(s) for s in shells]
    # teeth that all have a block keep the plate-and-block path exactly (no solid tooth)
    return ToothBending(pinion=shells[0], gear=shells[1], side=side, scale=float(scale),
                        near_field=any(s.solid_degrees is not None for s in shells))


def bending_stack(blocks, shape, *, part: str = "positive") -> np.ndarray | None:
    """Bending factors ``F_j / l_j`` of all blocks on one padded shape (blocks, ny, nx,
    r_max), zero where a block has none or is padded; None if no block has one.

    A block's factor is its ``bending_factor`` array, or the ``part`` ("positive" or
    "negative") of a :class:`SignedFactor`; an array has no negative part."""
    factors = [_part(b.bending_factor, part) for b in blocks]
    if all(f is None for f in factors):
        return None
    r = max(f.shape[2] for f in factors if f is not None)
    out = np.zeros((len(blocks),) + tuple(shape) + (r,), np.float32)  # see compliance
    for k, (b, f) in enumerate(zip(blocks, factors)):
        if f is not None:
            out[k, :f.shape[0], :f.shape[1], :f.shape[2]] = f / b.lever_mm
    return out


def _part(factor, part: str):
    """A block factor's ``part``: None where it has none (or an empty one)."""
    if isinstance(factor, SignedFactor):
        f = getattr(factor, part)
        return f if f.shape[2] else None
    return factor if part == "positive" else None


def pair_bending_compliance(fields, pc, torque_nmm: float) -> float:
    """Bending compliance of a pair's two teeth under its Hertzian pressure, mm/N.

    ``c_b = p^T G p / W^2 = |F^T p|^2 / W^2`` with ``G = F F^T`` the shell compliance
    of the pinion and gear tooth at the cells of the pair's field
    (:class:`gearcontact.ltca.tooth_bending.ToothBending`, as the loaded TE's LCP
    uses it) and ``p`` the semi-ellipsoidal Hertz pressure of the pair carrying the
    torque alone (its semi-axes from Hamrock–Brewe; the field's own sizing load): the
    work-conjugate compliance of that pressure shape (Castigliano), so that ``W c_b``
    is the pressure-weighted mean bending deflection along the normal. Cells off the
    flank carry no pressure. ``fields``: the loaded mesh's
    :class:`~gearcontact.ltca.lte_pairs.PairFields` (with bending); the twin's table
    (:mod:`gearcontact.twin.mesh`) and the loaded TE's preview take it.
    """
    gap, grid, off, lever = fields.get(pc)
    f = fields.factor(pc)
    hz = hamrock_brewe_hertz(pc.A_minus_per_mm, pc.B_minus_per_mm, torque_nmm / pc.lever_mm,
                             e_prime_mpa=fields.e_prime)
    s, t = np.meshgrid(grid.x_mm, grid.y_mm)
    q = np.sqrt(np.clip(1.0 - (s / hz.a_mm) ** 2 - (t / hz.b_mm) ** 2, 0.0, None)) * ~off
    return conjugate_compliance(f, q)


def conjugate_compliance(factor: np.ndarray, weights: np.ndarray) -> float:
    """Work-conjugate compliance ``q^T G q = |F^T q|^2`` (mm/N) of the load shape
    ``weights`` (any shape S, scaled to a unit total; all zero: 0) on the bending factor
    ``factor`` (S + (r,), ``G = F F^T`` mm/N; or a :class:`SignedFactor`,
    ``|F+^T q|^2 - |F-^T q|^2``, which may be negative): the mean deflection along the
    normal, weighted by the load, per newton of it (Castigliano)."""
    w = np.asarray(weights, float)
    if not w.any():
        return 0.0
    if isinstance(factor, SignedFactor):   # q^T (F+ F+^T - F- F-^T) q
        return conjugate_compliance(factor.positive, w) - (
            conjugate_compliance(factor.negative, w) if factor.negative.shape[2] else 0.0)
    v = np.tensordot(w / w.sum(), np.asarray(factor, float), axes=w.ndim)
    return float(v @ v)
