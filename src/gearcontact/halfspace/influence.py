"""Boussinesq half-space influence operators on tangent-plane grids.

The normal surface displacement at ``(x, y)`` of two elastic half-spaces pressed by a
uniform pressure ``p`` on the rectangle ``|x'| <= a, |y'| <= b`` is Love's closed form
(Love 1929; Johnson 1985, eq. 3.25) written for the composite contact modulus E*
(``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``), i.e. it is the *sum* of the
displacements of both bodies:

    u(x, y) = p / (pi E*) * [G(x+a, y+b) - G(x+a, y-b) - G(x-a, y+b) + G(x-a, y-b)],
    G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|),   G = 0 on the axes.

``G`` is the antiderivative of ``1/r`` over the rectangle; the ``asinh`` form drops
terms that cancel between the corners and stays accurate for points far outside the
loaded cell, where the textbook ``log`` form suffers cancellation.

Two operators map nodal loads ``w`` (N, the cell's force, ``w = p * area``) to
displacements at cell centres (mm):

* :func:`dense_influence_matrix` -- any (also non-uniform) grid, collocation at the
  centres, ``C[k, m] = u_k(unit pressure on cell m) / area_m`` (mm/N);
* :class:`FftInfluence` -- uniform grids: the same operator applied as a linear (not
  circular) convolution by zero padding to at least ``2N - 1`` per axis, with the
  kernel's transform cached per grid geometry.

References
----------
A. E. H. Love, "The stress produced in a semi-infinite solid by pressure on part of the
boundary", Phil. Trans. R. Soc. A 228 (1929) 377-420.
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, section 3.9.
E. A. H. Vollebregt, "A new solver for the elastic normal contact problem using
conjugate gradients, deflation, and an FFT-based preconditioner", J. Comput. Phys. 257
(2014) 333-351.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy import fft as sfft

from ..validation import InputRangeError, check_positive
from .grid import TangentGrid

try:  # scipy.fft's own pocketfft binding, called without the per-call dispatch
    from scipy.fft._pocketfft import pypocketfft as _pocketfft
except ImportError:  # pragma: no cover - depends on the scipy build
    _pocketfft = None

__all__ = ["love_rectangle_displacement", "dense_influence_matrix", "FftInfluence",
           "fft_influence", "boussinesq_inverse", "StackedFftInfluence"]


def _corner(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Love's corner function ``G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)`` (mm)."""
    ax, ay = np.abs(X), np.abs(Y)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(ax > 0.0, X * np.arcsinh(Y / np.where(ax > 0.0, ax, 1.0)), 0.0)
        t2 = np.where(ay > 0.0, Y * np.arcsinh(X / np.where(ay > 0.0, ay, 1.0)), 0.0)
    return t1 + t2


def love_rectangle_displacement(x_mm, y_mm, half_width_x_mm, half_width_y_mm, *,
                                e_star_mpa: float, pressure_mpa: float = 1.0):
    """Normal displacement (mm) due to uniform pressure on a rectangle centred at 0.

    Parameters
    ----------
    x_mm, y_mm : array_like
        Field points in mm, relative to the rectangle's centre (broadcast together).
    half_width_x_mm, half_width_y_mm : array_like
        Half-widths ``a`` and ``b`` of the loaded rectangle in mm (> 0, broadcast).
    e_star_mpa : float
        Composite contact modulus E* in MPa (both bodies; see
        :func:`gearcontact.materials.reduced_modulus_mpa`).
    pressure_mpa : float
        Uniform pressure in MPa.

    Returns
    -------
    ndarray
        Combined normal displacement of both surfaces in mm (Love 1929; Johnson 1985
        eq. 3.25 with ``(1 - nu^2)/E`` replaced by ``1/E*``).
    """
    e_star = check_positive("e_star_mpa", e_star_mpa)
    x, y = np.asarray(x_mm, dtype=float), np.asarray(y_mm, dtype=float)
    a = np.asarray(half_width_x_mm, dtype=float)
    b = np.asarray(half_width_y_mm, dtype=float)
    s = (_corner(x + a, y + b) - _corner(x + a, y - b)
         - _corner(x - a, y + b) + _corner(x - a, y - b))
    return pressure_mpa / (np.pi * e_star) * s


def dense_influence_matrix(grid: TangentGrid, *, e_star_mpa: float,
                           cells=None) -> np.ndarray:
    """Dense influence matrix ``C`` (mm/N) from nodal loads to centre displacements.

    Parameters
    ----------
    grid : TangentGrid
        Any tensor-product grid (uniform or not).
    e_star_mpa : float
        Composite modulus E* in MPa.
    cells : array_like of int, optional
        Flat (C-order, ``k = j * nx + i``) indices of the cells to keep; default all.
        The matrix is then the ``cells x cells`` block.

    Returns
    -------
    ndarray, shape (n, n)
        ``C[k, m]``: displacement at the centre of cell ``k`` per newton spread
        uniformly over cell ``m``. Symmetric on uniform grids; on non-uniform grids the
        collocation matrix is not exactly symmetric.
    """
    X, Y = grid.mesh()
    hx = np.broadcast_to(0.5 * grid.dx_mm[None, :], grid.shape)
    hy = np.broadcast_to(0.5 * grid.dy_mm[:, None], grid.shape)
    idx = np.arange(grid.size) if cells is None else np.asarray(cells, dtype=np.intp)
    xc, yc = X.ravel()[idx], Y.ravel()[idx]
    ax, by = hx.ravel()[idx], hy.ravel()[idx]
    u = love_rectangle_displacement(xc[:, None] - xc[None, :], yc[:, None] - yc[None, :],
                                    ax[None, :], by[None, :], e_star_mpa=e_star_mpa)
    return u / (4.0 * ax * by)[None, :]


def _rfft2_scipy(x: np.ndarray, pad: tuple[int, int]) -> np.ndarray:
    return sfft.rfft2(x, s=pad)


def _irfft2_scipy(f: np.ndarray, pad: tuple[int, int]) -> np.ndarray:
    return sfft.irfft2(f, s=pad)


def _rfft2_direct(x: np.ndarray, pad: tuple[int, int]) -> np.ndarray:
    buf = np.zeros(pad)
    buf[:x.shape[0], :x.shape[1]] = x
    return _pocketfft.r2c(buf, (0, 1), True, 0, None, 1)


def _irfft2_direct(f: np.ndarray, pad: tuple[int, int]) -> np.ndarray:
    return _pocketfft.c2r(f, (0, 1), pad[1], False, 2, None, 1)  # inorm 2: 1/N


def _pick_transforms():
    """The zero-padding ``rfft2`` / ``irfft2`` pair used by the operators.

    :func:`scipy.fft.rfft2` spends ~20 us per call in dispatch and argument handling,
    as long as a whole 64 x 64 transform; the solvers make ~60 small transforms per
    solve, so the pocketfft binding under :mod:`scipy.fft` is called directly (one
    thread: on small fields threads cost more than they save) when it is present and
    agrees with :mod:`scipy.fft` on a test field; otherwise the public functions.
    """
    if _pocketfft is not None:
        try:
            x = np.arange(12.0).reshape(3, 4) ** 1.5
            pad = (5, 7)
            ok = (np.allclose(_rfft2_direct(x, pad), sfft.rfft2(x, s=pad), rtol=1e-13,
                              atol=1e-12)
                  and np.allclose(_irfft2_direct(sfft.rfft2(x, s=pad), pad)[:3, :4], x,
                                  rtol=1e-13, atol=1e-12))
        except (TypeError, ValueError, RuntimeError):  # pragma: no cover
            ok = False
        if ok:
            return _rfft2_direct, _irfft2_direct
    return _rfft2_scipy, _irfft2_scipy  # pragma: no cover


_rfft2, _irfft2 = _pick_transforms()


def _pruned_buffers(n: int, shape: tuple[int, int], pad: tuple[int, int]) -> tuple:
    """Work buffers of :func:`_convolve_pruned` for ``n`` fields."""
    return (np.zeros((n, shape[0], pad[1])),
            np.zeros((n, pad[0], pad[1] // 2 + 1), complex),
            np.empty((n, shape[0], pad[1])))


def _convolve_pruned(x: np.ndarray, symbols: np.ndarray, pad: tuple[int, int],
                     bufs: tuple) -> np.ndarray:
    """``irfft2(symbols * rfft2(x zero-padded to pad))`` cropped to ``x``'s shape.

    ``x`` is a stack ``(n, ny, nx)``; ``symbols`` broadcasts against ``(n, py, px//2+1)``.
    The zero padding is not transformed: the forward real transform (last axis) runs
    over the ``ny`` data rows only, and the inverse one returns only those rows --
    about half the work of a full 2-D transform pair, for the same result to
    round-off. ``bufs`` from :func:`_pruned_buffers` (kept by the callers between
    calls); the result is a view into the last one.
    """
    ny, nx = x.shape[1:]
    rbuf, cbuf, obuf = bufs
    rbuf[:, :, :nx] = x  # the padding columns of rbuf stay zero
    if _pocketfft is None:  # pragma: no cover - depends on the scipy build
        obuf[...] = sfft.irfft2(sfft.rfft2(rbuf, s=pad, axes=(1, 2)) * symbols, s=pad,
                                axes=(1, 2))[:, :ny]
    elif pad == (ny, nx):  # periodic: nothing to prune
        f = _pocketfft.r2c(rbuf, (1, 2), True, 0, cbuf, 1)
        f *= symbols
        _pocketfft.c2r(f, (1, 2), pad[1], False, 2, obuf, 1)
    else:
        _pocketfft.r2c(rbuf, (2,), True, 0, cbuf[:, :ny], 1)
        cbuf[:, ny:] = 0.0
        _pocketfft.c2c(cbuf, (1,), True, 0, cbuf, 1)
        cbuf *= symbols
        _pocketfft.c2c(cbuf, (1,), False, 2, cbuf, 1)
        _pocketfft.c2r(cbuf[:, :ny], (2,), pad[1], False, 2, obuf, 1)
    return obuf[:, :, :nx]


#: Largest kernel quadrant computed per (dx, dy, E*); smaller windows slice it.
_QUADRANTS: dict[tuple[float, float, float], np.ndarray] = {}
_MAX_QUADRANTS = 64


def _kernel_quadrant(ny: int, nx: int, dx_mm: float, dy_mm: float, e_star_mpa: float
                     ) -> np.ndarray:
    """Influence kernel ``K[|oy|, |ox|]`` (mm/N) at offsets ``0..n-1`` per axis.

    Love's kernel is even in both offsets (``G`` is odd in each argument), so one
    quadrant defines it. The largest quadrant per cell size and E* is kept and sliced,
    so the windows the solvers step through cost no new kernel evaluations.
    """
    key = (dx_mm, dy_mm, e_star_mpa)
    q = _QUADRANTS.get(key)
    if q is None or q.shape[0] < ny or q.shape[1] < nx:
        my, mx = (ny, nx) if q is None else (max(ny, q.shape[0]), max(nx, q.shape[1]))
        # Love's four corner terms of cell (j, i) are G on the cell-edge lattice
        # ((m - 1/2) dx, (n - 1/2) dy): one G per lattice point, not four per cell
        gl = _corner(dx_mm * (np.arange(mx + 1) - 0.5)[None, :],
                     dy_mm * (np.arange(my + 1) - 0.5)[:, None])
        q = (gl[1:, 1:] - gl[:-1, 1:] - gl[1:, :-1] + gl[:-1, :-1]) \
            / (np.pi * e_star_mpa * dx_mm * dy_mm)
        q.setflags(write=False)
        if key not in _QUADRANTS and len(_QUADRANTS) >= _MAX_QUADRANTS:
            _QUADRANTS.pop(next(iter(_QUADRANTS)))
        _QUADRANTS[key] = q
    return q[:ny, :nx]


@lru_cache(maxsize=64)
def _kernel_rfft(ny: int, nx: int, dx_mm: float, dy_mm: float, e_star_mpa: float
                 ) -> tuple[np.ndarray, tuple[int, int]]:
    """Cached rfft2 of the zero-padded influence kernel (mm/N, real: the kernel is
    even) and the padded shape."""
    py = sfft.next_fast_len(2 * ny - 1, real=True)
    px = sfft.next_fast_len(2 * nx - 1, real=True)
    q = _kernel_quadrant(ny, nx, dx_mm, dy_mm, e_star_mpa)
    # offsets 0..n-1 at the front, -(n-1)..-1 at the back (wrap-around order)
    pad = np.zeros((py, px))
    pad[:ny, :nx] = q
    pad[:ny, px - (nx - 1):] = q[:, :0:-1]
    pad[py - (ny - 1):, :nx] = q[:0:-1, :]
    pad[py - (ny - 1):, px - (nx - 1):] = q[:0:-1, :0:-1]
    # the kernel is even in both offsets, so its transform is real: keep the real part
    # (the imaginary one is round-off) for the cheaper real-by-complex product
    khat = np.ascontiguousarray(_rfft2(pad, (py, px)).real)
    khat.setflags(write=False)
    return khat, (py, px)


@lru_cache(maxsize=64)
def _inverse_symbol(py: int, px: int, dx_mm: float, dy_mm: float, e_star_mpa: float
                    ) -> np.ndarray:
    """``E* |k| dA / 2`` on a ``(py, px)`` rfft2 grid (N/mm per mm of displacement).

    The mean mode ``k = 0`` (where the continuous symbol vanishes) takes half the lowest
    non-zero wavenumber, which keeps the operator positive definite. A ``1 x 1`` grid
    has no non-zero mode: there the symbol is the exact inverse of the cell's
    self-influence, ``1 / C_ii`` (an infinite value here once made the ``pk_cg``
    preconditioner return NaN when the contact shrank to one cell).
    """
    if py == 1 and px == 1:
        c_ii = love_rectangle_displacement(0.0, 0.0, 0.5 * dx_mm, 0.5 * dy_mm,
                                           e_star_mpa=e_star_mpa) / (dx_mm * dy_mm)
        sym = np.full((1, 1), 1.0 / float(c_ii))
    else:
        ky = 2.0 * np.pi * sfft.fftfreq(py, dy_mm)
        kx = 2.0 * np.pi * sfft.rfftfreq(px, dx_mm)
        k = np.hypot(ky[:, None], kx[None, :])
        k[0, 0] = 0.5 * min(abs(ky[1]) if py > 1 else np.inf, kx[1] if px > 1 else np.inf)
        sym = 0.5 * e_star_mpa * dx_mm * dy_mm * k
    sym.setflags(write=False)
    return sym


def boussinesq_inverse(displacement_mm: np.ndarray, *, dx_mm: float, dy_mm: float,
                       e_star_mpa: float, padded_shape: tuple[int, int]) -> np.ndarray:
    """Loads (N) approximately producing ``displacement_mm``: a preconditioner.

    Applies the inverse of the continuous Boussinesq symbol, ``p^ = E* |k| u^ / 2``
    (from ``u^ = 2 p^ / (E* |k|)``, Johnson 1985 sec. 3.2 in Fourier form), times the
    cell area, on the field zero-padded to ``padded_shape`` (any shape at least the
    field's; more padding is closer to the non-periodic inverse, less is cheaper).
    Symmetric positive definite (see :func:`_inverse_symbol` for the mean mode and the
    single-cell case); the FFT-based preconditioning of Vollebregt (2014).

    Parameters
    ----------
    displacement_mm : ndarray, shape (ny, nx)
        Displacements in mm on a uniform grid.
    dx_mm, dy_mm : float
        Cell widths in mm.
    e_star_mpa : float
        Composite modulus E* in MPa.
    padded_shape : tuple of int
        Transform shape ``(py, px)`` with ``py >= ny``, ``px >= nx``.

    Returns
    -------
    ndarray, shape (ny, nx)
        Nodal loads in N.
    """
    ny, nx = displacement_mm.shape
    py, px = padded_shape
    sym = _inverse_symbol(py, px, dx_mm, dy_mm, e_star_mpa)
    return _convolve_pruned(displacement_mm[None], sym, (py, px),
                            _pruned_buffers(1, (ny, nx), (py, px)))[0]


class FftInfluence:
    """Influence operator on a uniform grid applied by zero-padded FFT convolution.

    Applies exactly the dense collocation operator of :func:`dense_influence_matrix`
    (non-periodic: each axis is padded to at least ``2N - 1``), in
    ``O(N log N)``. The kernel's transform is cached per ``(shape, dx, dy, E*)``; the
    transforms skip the zero padding (:func:`_convolve_pruned`) and keep their work
    buffers on the instance, so one instance must not be called from several threads
    at once.

    Parameters
    ----------
    shape : tuple of int
        Field shape ``(ny, nx)``.
    dx_mm, dy_mm : float
        Cell widths in mm.
    e_star_mpa : float
        Composite modulus E* in MPa.
    """

    def __init__(self, shape: tuple[int, int], *, dx_mm: float, dy_mm: float,
                 e_star_mpa: float):
        ny, nx = (int(n) for n in shape)
        if ny < 1 or nx < 1:
            raise InputRangeError("shape", shape, "(ny, nx) with both >= 1")
        self.shape = (ny, nx)
        self._dx = check_positive("dx_mm", dx_mm)
        self._dy = check_positive("dy_mm", dy_mm)
        self._e_star = check_positive("e_star_mpa", e_star_mpa)
        self._khat, self._pad = _kernel_rfft(ny, nx, self._dx, self._dy, self._e_star)
        self._others: dict[tuple[int, int], FftInfluence] = {}
        self._bufs = None  # transform work space, made on first use

    @property
    def cell_size(self) -> tuple[float, float]:
        """Cell widths ``(dx_mm, dy_mm)``."""
        return self._dx, self._dy

    @property
    def e_star_mpa(self) -> float:
        """Composite modulus E* in MPa."""
        return self._e_star

    def on_shape(self, shape: tuple[int, int]) -> "FftInfluence":
        """The same kernel (cell size, E*) on a window of another ``shape``."""
        shape = (int(shape[0]), int(shape[1]))
        if shape == self.shape:
            return self
        op = self._others.get(shape)
        if op is None:
            op = self._others[shape] = FftInfluence(shape, dx_mm=self._dx, dy_mm=self._dy,
                                                    e_star_mpa=self._e_star)
        return op

    def kernel_quadrant(self) -> np.ndarray:
        """``K[|oy|, |ox|]`` (mm/N), shape ``(ny, nx)``: the operator in real space
        (displacement at offset ``(oy, ox)`` from a unit load; read-only, cached)."""
        return _kernel_quadrant(*self.shape, self._dx, self._dy, self._e_star)

    def approx_inverse(self, displacement_mm: np.ndarray) -> np.ndarray:
        """Loads (N) approximately producing ``displacement_mm``: a preconditioner.

        :func:`boussinesq_inverse` on the operator's padded grid: symmetric positive
        definite, exact on a ``1 x 1`` field (Vollebregt 2014).
        """
        return boussinesq_inverse(displacement_mm, dx_mm=self._dx, dy_mm=self._dy,
                                  e_star_mpa=self._e_star, padded_shape=self._pad)

    def __call__(self, loads_n: np.ndarray) -> np.ndarray:
        """Displacements (mm, shape ``(ny, nx)``) due to nodal loads (N, same shape)."""
        if self._bufs is None:
            self._bufs = _pruned_buffers(1, self.shape, self._pad)
        return _convolve_pruned(np.asarray(loads_n, float)[None], self._khat, self._pad,
                                self._bufs)[0].copy()


def fft_influence(grid: TangentGrid, *, e_star_mpa: float) -> FftInfluence:
    """FFT influence operator for a uniform ``grid`` (raises on a non-uniform one)."""
    if not grid.is_uniform:
        raise InputRangeError("grid", "non-uniform",
                              "a uniform grid for the FFT operator (use the dense one)")
    return FftInfluence(grid.shape, dx_mm=float(grid.dx_mm[0]),
                        dy_mm=float(grid.dy_mm[0]), e_star_mpa=e_star_mpa)


class StackedFftInfluence:
    """Block-diagonal operator over a stack of same-shape fields, one batched FFT.

    Field ``k`` has its own cell size and a scale ``s_k``; :meth:`apply` maps loads
    ``x[k]`` (N) to ``C_k x[k] / s_k`` (mm) with the exact zero-padded operator of
    :class:`FftInfluence`, and :meth:`approx_inverse` maps displacements to
    ``s_k M_k u[k]`` with the Boussinesq preconditioner of :func:`boussinesq_inverse`.
    All fields are transformed in one call per axis, and the zero padding is not
    transformed: the forward real transform runs over the ``ny`` data rows only and
    the inverse real transform returns only those rows (about half the work of a
    full 2-D transform pair). Work buffers are kept between calls (one instance per
    thread).

    Parameters
    ----------
    shape : tuple of int
        Field shape ``(ny, nx)`` shared by all fields.
    cell_sizes : sequence of (float, float)
        ``(dx_mm, dy_mm)`` per field.
    e_star_mpa : float
        Composite modulus E* in MPa.
    scales : sequence of float, optional
        ``s_k`` per field (default 1).
    pre_shape : tuple of int, optional
        Transform shape of the preconditioner (default: the operator's padded shape).
    """

    def __init__(self, shape, cell_sizes, *, e_star_mpa: float, scales=None,
                 pre_shape=None):
        ny, nx = (int(n) for n in shape)
        if ny < 1 or nx < 1:
            raise InputRangeError("shape", shape, "(ny, nx) with both >= 1")
        cells = [(check_positive("dx_mm", dx), check_positive("dy_mm", dy))
                 for dx, dy in cell_sizes]
        e_star = check_positive("e_star_mpa", e_star_mpa)
        sc = np.ones(len(cells)) if scales is None else np.asarray(scales, float)
        self.shape, self.n_fields = (ny, nx), len(cells)
        khats = [_kernel_rfft(ny, nx, dx, dy, e_star) for dx, dy in cells]
        self._pad = khats[0][1]
        self._khat = np.stack([k for k, _ in khats]) / sc[:, None, None]
        self._cells, self._e_star, self._scales = cells, e_star, sc
        self._qad = self._pad if pre_shape is None else tuple(int(n) for n in pre_shape)
        if self._qad[0] < ny or self._qad[1] < nx:
            raise InputRangeError("pre_shape", pre_shape, f">= {self.shape} per axis")
        self._sym = None  # the preconditioner's symbols, made on first use
        self._plans: dict[tuple, tuple] = {}

    def _plan(self, symbols: np.ndarray, pad: tuple[int, int], live) -> tuple:
        """Fields, symbols and work buffers of one transform (cached per ``live``)."""
        key = (id(symbols), None if live is None else live.tobytes())
        plan = self._plans.get(key)
        if plan is None:
            n = self.n_fields
            idx = None if live is None or live.all() else np.flatnonzero(live)
            if idx is not None:
                symbols, n = symbols[idx], idx.size
            plan = self._plans[key] = (idx, symbols, _pruned_buffers(n, self.shape, pad))
        return plan

    def _convolve(self, x, out, symbols, pad, live):
        """``out[k] = (x[k] convolved with the symbol k)`` on the fields ``live``
        (bool per field; None: all), 0 on the others."""
        idx, symbols, bufs = self._plan(symbols, pad, live)
        if idx is not None:
            out[...] = 0.0
            if idx.size == 0:
                return out
            out[idx] = _convolve_pruned(x[idx], symbols, pad, bufs)
        else:
            out[...] = _convolve_pruned(x, symbols, pad, bufs)
        return out

    def kernel_quadrants(self) -> np.ndarray:
        """``K_k[|oy|, |ox|] / s_k`` (mm/N), shape ``(n_fields, ny, nx)``: the operator
        of field ``k`` in real space (displacement at offset ``(oy, ox)`` from a unit
        load), for updates by a few cells."""
        ny, nx = self.shape
        return np.stack([_kernel_quadrant(ny, nx, dx, dy, self._e_star) / s
                         for (dx, dy), s in zip(self._cells, self._scales)])

    def apply(self, loads_n: np.ndarray, out: np.ndarray | None = None,
              live: np.ndarray | None = None) -> np.ndarray:
        """``C_k x[k] / s_k`` (mm) for loads ``x`` (N, shape ``(n_fields, ny, nx)``).

        ``live`` (bool per field) restricts the work to those fields; the others must
        carry no load and get zero displacement. ``out`` receives the result.
        """
        out = np.empty(loads_n.shape) if out is None else out
        return self._convolve(loads_n, out, self._khat, self._pad, live)

    def approx_inverse(self, displacement_mm: np.ndarray, out: np.ndarray | None = None,
                       live: np.ndarray | None = None) -> np.ndarray:
        """``s_k M_k u[k]`` (N): :func:`boussinesq_inverse` per field on the
        preconditioner's transform shape, scaled; ``live`` and ``out`` as in
        :meth:`apply` (fields not live get 0)."""
        if self._sym is None:
            self._sym = np.stack([_inverse_symbol(*self._qad, dx, dy, self._e_star)
                                  for dx, dy in self._cells]) * self._scales[:, None, None]
        out = np.empty(displacement_mm.shape) if out is None else out
        return self._convolve(displacement_mm, out, self._sym, self._qad, live)
