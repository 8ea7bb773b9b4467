"""Tangent-plane grids of rectangular cells for the contact (LTCA) solvers.

A :class:`TangentGrid` is a tensor-product grid in the common tangent plane of the two
flanks: cell centres ``x_mm`` (``nx``) and ``y_mm`` (``ny``) with cell widths ``dx_mm``
and ``dy_mm``. Uniform grids (equal widths along each axis) allow the FFT influence
operator; non-uniform grids (the adaptive grids of gear LTCA) use the dense operator.

Array layout
------------
Every field on a grid (gap ``h``, pressure, nodal loads, contact mask) is a 2-D array of
shape ``(ny, nx)`` indexed ``h[j, i]``: ``j`` runs along y (rows), ``i`` along x
(columns), i.e. ``h[j, i]`` is the value at ``(x_mm[i], y_mm[j])``. Flattened vectors use
C order (``k = j * nx + i``), the order of the dense influence matrix.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError, check_array_finite, check_finite, check_positive

__all__ = ["TangentGrid"]

#: Relative tolerance under which cell widths count as equal (uniform grid).
_UNIFORM_RTOL = 1e-9


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class TangentGrid:
    """A tensor-product grid of rectangular cells in the tangent plane (mm).

    Parameters
    ----------
    x_mm : ndarray, shape (nx,)
        Cell-centre x coordinates in mm, strictly increasing.
    y_mm : ndarray, shape (ny,)
        Cell-centre y coordinates in mm, strictly increasing.
    dx_mm : ndarray, shape (nx,)
        Cell widths along x in mm (> 0).
    dy_mm : ndarray, shape (ny,)
        Cell widths along y in mm (> 0).

    Notes
    -----
    Fields on the grid have shape ``(ny, nx)`` with x along the second index
    (``h[j, i]`` at ``(x_mm[i], y_mm[j])``). Use :meth:`uniform`, :meth:`centered` or
    :meth:`from_edges` to build one.
    """

    x_mm: np.ndarray
    y_mm: np.ndarray
    dx_mm: np.ndarray
    dy_mm: np.ndarray

    def __post_init__(self):
        for name in ("x_mm", "y_mm", "dx_mm", "dy_mm"):
            arr = check_array_finite(name, getattr(self, name))
            if arr.ndim != 1 or arr.size == 0:
                raise InputRangeError(name, arr.shape, "a non-empty 1-D array")
            object.__setattr__(self, name, _readonly(arr))
        if self.dx_mm.shape != self.x_mm.shape:
            raise InputRangeError("dx_mm", self.dx_mm.shape, f"shape {self.x_mm.shape}")
        if self.dy_mm.shape != self.y_mm.shape:
            raise InputRangeError("dy_mm", self.dy_mm.shape, f"shape {self.y_mm.shape}")
        for name in ("dx_mm", "dy_mm"):
            arr = getattr(self, name)
            if not np.all(arr > 0.0):
                raise InputRangeError(name, float(arr.min()), "cell widths > 0 mm")
        for name in ("x_mm", "y_mm"):
            arr = getattr(self, name)
            if arr.size > 1 and not np.all(np.diff(arr) > 0.0):
                raise InputRangeError(name, arr, "strictly increasing cell centres")
        object.__setattr__(self, "_uniform", _widths_uniform(self.dx_mm, self.dy_mm))

    # ------------------------------------------------------------------ builders
    @classmethod
    def uniform(cls, nx: int, ny: int, *, dx_mm: float, dy_mm: float,
                x0_mm: float = 0.0, y0_mm: float = 0.0) -> "TangentGrid":
        """Uniform grid whose first cell centre is at ``(x0_mm, y0_mm)``.

        Parameters
        ----------
        nx, ny : int
            Number of cells along x and y (>= 1).
        dx_mm, dy_mm : float
            Cell widths in mm (> 0).
        x0_mm, y0_mm : float
            Centre of cell ``[0, 0]`` in mm.
        """
        nx, ny = _check_count("nx", nx), _check_count("ny", ny)
        dx = check_positive("dx_mm", dx_mm)
        dy = check_positive("dy_mm", dy_mm)
        x0, y0 = check_finite("x0_mm", x0_mm), check_finite("y0_mm", y0_mm)
        # valid by construction (finite, widths > 0, increasing, uniform): the checks of
        # __post_init__ are skipped (a loaded TE builds one grid per field)
        grid = object.__new__(cls)
        for name, arr in (("x_mm", x0 + dx * np.arange(nx)), ("y_mm", y0 + dy * np.arange(ny)),
                          ("dx_mm", np.full(nx, dx)), ("dy_mm", np.full(ny, dy))):
            object.__setattr__(grid, name, _readonly(arr))
        object.__setattr__(grid, "_uniform", True)
        return grid

    @classmethod
    def centered(cls, nx: int, ny: int, *, dx_mm: float, dy_mm: float,
                 cx_mm: float = 0.0, cy_mm: float = 0.0) -> "TangentGrid":
        """Uniform grid centred on ``(cx_mm, cy_mm)`` (odd counts put a cell centre there)."""
        nx, ny = _check_count("nx", nx), _check_count("ny", ny)
        dx = check_positive("dx_mm", dx_mm)
        dy = check_positive("dy_mm", dy_mm)
        return cls.uniform(nx, ny, dx_mm=dx, dy_mm=dy,
                           x0_mm=cx_mm - 0.5 * (nx - 1) * dx,
                           y0_mm=cy_mm - 0.5 * (ny - 1) * dy)

    @classmethod
    def from_edges(cls, x_edges_mm, y_edges_mm) -> "TangentGrid":
        """Grid from strictly increasing cell edges (``nx + 1`` and ``ny + 1`` values, mm)."""
        xe = check_array_finite("x_edges_mm", x_edges_mm)
        ye = check_array_finite("y_edges_mm", y_edges_mm)
        for name, e in (("x_edges_mm", xe), ("y_edges_mm", ye)):
            if e.ndim != 1 or e.size < 2 or not np.all(np.diff(e) > 0.0):
                raise InputRangeError(name, e, "at least two strictly increasing edges")
        return cls(0.5 * (xe[1:] + xe[:-1]), 0.5 * (ye[1:] + ye[:-1]),
                   np.diff(xe), np.diff(ye))

    # ---------------------------------------------------------------- properties
    @property
    def nx(self) -> int:
        """Number of cells along x."""
        return int(self.x_mm.size)

    @property
    def ny(self) -> int:
        """Number of cells along y."""
        return int(self.y_mm.size)

    @property
    def shape(self) -> tuple[int, int]:
        """Field shape ``(ny, nx)``."""
        return (self.ny, self.nx)

    @property
    def size(self) -> int:
        """Number of cells."""
        return self.nx * self.ny

    @property
    def is_uniform(self) -> bool:
        """True when all cells have the same width along x and along y."""
        return self._uniform

    @property
    def cell_area_mm2(self) -> np.ndarray:
        """Cell areas in mm^2, shape ``(ny, nx)``."""
        return np.outer(self.dy_mm, self.dx_mm)

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """Cell-centre coordinates ``(X, Y)`` in mm, each of shape ``(ny, nx)``."""
        return np.meshgrid(self.x_mm, self.y_mm, indexing="xy")

    def sub(self, rows: slice, cols: slice) -> "TangentGrid":
        """The sub-grid ``[rows, cols]`` (a window; slices with unit step).

        The window shares (read-only) views of this grid's arrays; a non-empty slice of
        a checked grid needs no new checks, which keeps this cheap inside solvers.
        """
        g = object.__new__(TangentGrid)
        parts = {"x_mm": self.x_mm[cols], "y_mm": self.y_mm[rows],
                 "dx_mm": self.dx_mm[cols], "dy_mm": self.dy_mm[rows]}
        for name, arr in parts.items():
            if arr.size == 0:
                raise InputRangeError(name, (rows, cols), "a non-empty window")
            object.__setattr__(g, name, arr)
        object.__setattr__(g, "_uniform", self._uniform or
                           _widths_uniform(parts["dx_mm"], parts["dy_mm"]))
        return g

    def check_field(self, field: str, values) -> np.ndarray:
        """Return ``values`` as a finite float array of shape ``(ny, nx)`` or raise.

        Raises
        ------
        InputRangeError
            Wrong shape, or a NaN/inf entry (named by its ``[j, i]`` index).
        """
        arr = np.asarray(values, dtype=float)
        if arr.shape != self.shape:
            raise InputRangeError(f"{field}.shape", arr.shape,
                                  f"{self.shape} = (ny, nx) of the grid, x along axis 1")
        return check_array_finite(field, arr)


def _widths_uniform(dx_mm: np.ndarray, dy_mm: np.ndarray) -> bool:
    """True when the widths along each axis agree to :data:`_UNIFORM_RTOL`."""
    return bool(np.allclose(dx_mm, dx_mm[0], rtol=_UNIFORM_RTOL, atol=0.0)
                and np.allclose(dy_mm, dy_mm[0], rtol=_UNIFORM_RTOL, atol=0.0))


def _check_count(field: str, n) -> int:
    if int(n) != n or int(n) < 1:
        raise InputRangeError(field, n, "an integer >= 1")
    return int(n)
