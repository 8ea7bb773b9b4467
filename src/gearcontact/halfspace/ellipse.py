"""Ellipse fitted to a discrete contact patch, and the grid-resolution check.

The contact region (cells with positive pressure) is summarised by the ellipse with
the same area centroid and second moments: for a uniformly filled ellipse of semi-axes
``a >= b`` the area covariance has eigenvalues ``a^2/4`` and ``b^2/4`` (each cell adds
its own ``dx^2/12``, ``dy^2/12``). This is what is overlaid on pressure maps, and its
minor semi-axis measured in cells is the resolution figure behind the coarse-grid
warning (Johnson 1985, ch. 4, for the Hertzian ellipse it approximates).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError
from .grid import TangentGrid

__all__ = ["ContactEllipse", "CoarseGridWarning", "fit_contact_ellipse",
           "cells_per_semi_axis", "warn_if_coarse", "MIN_CELLS_PER_SEMI_AXIS"]

#: Below this many cells across the minor semi-axis the solvers warn. Measured on
#: Hertzian patches (ratios 1 and 10): at 4-6 cells the stair-cased contact area, the
#: mean pressure and the minor semi-axis are off by 5-15 % (the peak pressure, on a
#: centred cell, only by ~1 %); at 8 cells by ~3-6 %; at 16 cells by ~1 %.
MIN_CELLS_PER_SEMI_AXIS = 8.0


class CoarseGridWarning(UserWarning):
    """The grid resolves the contact with too few cells per semi-axis."""


@dataclass(frozen=True)
class ContactEllipse:
    """Moment-equivalent ellipse of a contact patch.

    Attributes
    ----------
    center_x_mm, center_y_mm : float
        Area centroid of the contacting cells, mm.
    semi_major_mm, semi_minor_mm : float
        Semi-axes ``a >= b`` in mm.
    angle_rad : float
        Angle of the major axis from +x, in (-pi/2, pi/2].
    area_mm2 : float
        Contact area (sum of contacting cell areas), mm^2.
    cells_per_semi_minor : float
        Minor semi-axis divided by the cell width along the minor axis.
    """

    center_x_mm: float
    center_y_mm: float
    semi_major_mm: float
    semi_minor_mm: float
    angle_rad: float
    area_mm2: float
    cells_per_semi_minor: float

    def outline_mm(self, n: int = 181) -> tuple[np.ndarray, np.ndarray]:
        """``n`` points ``(x, y)`` in mm on the ellipse, for drawing."""
        t = np.linspace(0.0, 2.0 * np.pi, n)
        c, s = np.cos(self.angle_rad), np.sin(self.angle_rad)
        ex, ey = self.semi_major_mm * np.cos(t), self.semi_minor_mm * np.sin(t)
        return self.center_x_mm + c * ex - s * ey, self.center_y_mm + s * ex + c * ey

    def draw(self, ax, **kwargs):
        """Draw the outline on a Matplotlib axes (x along the horizontal); returns the line."""
        x, y = self.outline_mm()
        kwargs.setdefault("color", "white")
        kwargs.setdefault("lw", 1.2)
        (line,) = ax.plot(x, y, **kwargs)
        return line


def fit_contact_ellipse(grid: TangentGrid, contact_mask) -> ContactEllipse:
    """Fit the moment-equivalent ellipse to the contacting cells.

    Parameters
    ----------
    grid : TangentGrid
        The grid of the mask.
    contact_mask : array_like of bool, shape (ny, nx)
        True on contacting cells (e.g. ``pressure_mpa > 0``).

    Returns
    -------
    ContactEllipse

    Raises
    ------
    InputRangeError
        If the mask has the wrong shape or no contacting cell.
    """
    mask = np.asarray(contact_mask, dtype=bool)
    if mask.shape != grid.shape:
        raise InputRangeError("contact_mask.shape", mask.shape, f"{grid.shape} (ny, nx)")
    if not mask.any():
        raise InputRangeError("contact_mask", "no contacting cell", ">= 1 contacting cell")
    X, Y = grid.mesh()
    area = grid.cell_area_mm2 * mask
    dx2 = np.broadcast_to(grid.dx_mm[None, :] ** 2, grid.shape)
    dy2 = np.broadcast_to(grid.dy_mm[:, None] ** 2, grid.shape)
    tot = area.sum()
    cx, cy = (area * X).sum() / tot, (area * Y).sum() / tot
    sxx = (area * ((X - cx) ** 2 + dx2 / 12.0)).sum() / tot
    syy = (area * ((Y - cy) ** 2 + dy2 / 12.0)).sum() / tot
    sxy = (area * (X - cx) * (Y - cy)).sum() / tot
    lam, vec = np.linalg.eigh(np.array([[sxx, sxy], [sxy, syy]]))
    a, b = 2.0 * np.sqrt(lam[1]), 2.0 * np.sqrt(lam[0])
    ux, uy = vec[:, 1]
    angle = float(np.arctan2(uy, ux))
    if angle <= -0.5 * np.pi:
        angle += np.pi
    elif angle > 0.5 * np.pi:
        angle -= np.pi
    # cell width along the minor axis, at the cell nearest the centroid
    i = int(np.argmin(np.abs(grid.x_mm - cx)))
    j = int(np.argmin(np.abs(grid.y_mm - cy)))
    vx, vy = vec[:, 0]
    width = float(np.hypot(grid.dx_mm[i] * vx, grid.dy_mm[j] * vy))
    return ContactEllipse(float(cx), float(cy), float(a), float(b), angle, float(tot),
                          float(b / width))


def cells_per_semi_axis(grid: TangentGrid, contact_mask) -> float:
    """Cells across the minor semi-axis of the contact patch (0 if no contact)."""
    mask = np.asarray(contact_mask, dtype=bool)
    return fit_contact_ellipse(grid, mask).cells_per_semi_minor if mask.any() else 0.0


def warn_if_coarse(grid: TangentGrid, contact_mask, *, stacklevel: int = 3) -> float:
    """Warn (:class:`CoarseGridWarning`) when the patch has too few cells per semi-axis.

    Returns the cells-per-semi-axis figure.
    """
    n = cells_per_semi_axis(grid, contact_mask)
    if n < MIN_CELLS_PER_SEMI_AXIS:
        warnings.warn(f"grid too coarse for the contact: {n:.1f} cells per minor "
                      f"semi-axis (< {MIN_CELLS_PER_SEMI_AXIS:g}); refine the grid",
                      CoarseGridWarning, stacklevel=stacklevel)
    return n
