"""Single-patch loaded tooth contact: gap field + load -> pressure and its statistics.

Input is a tangent-plane gap field as the TCA stage provides it (e.g. the 80 x 80 field
around the mating point): a :class:`~.grid.TangentGrid` and ``h[j, i]`` in mm with shape
``(ny, nx)``, ``x`` along ``i`` (axis 1), ``y`` along ``j`` (axis 0); any constant offset
of ``h`` only shifts the approach. :func:`solve_patch` solves the load-constrained LCP
(:func:`.lcp.solve_lcp`) and summarises the patch as gear engineers read it: mean,
p90 and peak pressure over the contacting cells (the peak with its location, where
tooth-tip edge spikes show), rigid approach, number of contacting cells, whether the
contact reaches the edge of the field (a flank edge or a too-small field), and the
moment-equivalent contact ellipse for overlays (:mod:`.ellipse`).

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, ch. 4 (the
Hertzian patch these statistics reduce to: mean = 2/3 p0, p90 = sqrt(0.9) p0).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .ellipse import ContactEllipse, fit_contact_ellipse
from .grid import TangentGrid
from .lcp import solve_lcp
from .result import ContactResult

__all__ = ["PatchContact", "ContactAtEdgeWarning", "solve_patch", "patch_statistics",
           "plot_patch"]


class ContactAtEdgeWarning(UserWarning):
    """The loaded contact reaches the edge of the gap field (flank edge or small field)."""


@dataclass(frozen=True, eq=False)
class PatchContact:
    """The statistics of a solved single contact patch.

    Not a second solver result: the solve is ``lcp``, the contact family's one result
    type (:class:`.result.ContactResult`); this adds what gear engineers read of it.

    Attributes
    ----------
    grid : TangentGrid
        The tangent-plane grid (fields are ``(ny, nx)``, x along axis 1).
    lcp : ContactResult
        The solver's result (pressure map, loads, residuals, status, timing).
    load_n : float
        Normal load W in N.
    delta_mm : float
        Rigid approach in mm (same datum as the gap).
    n_contact_cells : int
        Cells carrying load.
    contact_area_mm2 : float
        Sum of the contacting cells' areas.
    p_mean_mpa : float
        Mean contact pressure ``W / contact area`` (area-weighted mean over contacting
        cells), MPa.
    p90_mpa : float
        90th percentile of the contacting cells' pressures (linear interpolation), MPa.
    p_peak_mpa : float
        Largest cell pressure, MPa.
    peak_x_mm, peak_y_mm : float
        Centre of the peak cell, mm.
    peak_index : tuple of int
        ``(j, i)`` of the peak cell.
    edge_sides : tuple of str
        Grid sides the contact reaches: subset of ``("x_min", "x_max", "y_min",
        "y_max")``; empty when the patch lies inside the field.
    cells_per_semi_axis : float
        Minor semi-axis of the fitted ellipse in cells (resolution figure).
    ellipse : ContactEllipse
        Moment-equivalent ellipse of the contacting cells.
    """

    grid: TangentGrid
    lcp: ContactResult
    load_n: float
    delta_mm: float
    n_contact_cells: int
    contact_area_mm2: float
    p_mean_mpa: float
    p90_mpa: float
    p_peak_mpa: float
    peak_x_mm: float
    peak_y_mm: float
    peak_index: tuple[int, int]
    edge_sides: tuple[str, ...]
    cells_per_semi_axis: float
    ellipse: ContactEllipse

    @property
    def pressure_mpa(self) -> np.ndarray:
        """Pressure map ``(ny, nx)`` in MPa."""
        return self.lcp.pressure_mpa

    @property
    def touches_edge(self) -> bool:
        """True when the contact reaches the edge of the gap field."""
        return bool(self.edge_sides)

    @property
    def converged(self) -> bool:
        """True when the LCP solve converged."""
        return self.lcp.converged

    def summary(self) -> dict:
        """Plain-JSON scalars for reports (``ltca.json`` fields)."""
        return {"load_n": self.load_n, "p_mean_mpa": self.p_mean_mpa,
                "p90_mpa": self.p90_mpa, "p_peak_mpa": self.p_peak_mpa,
                "peak_x_mm": self.peak_x_mm, "peak_y_mm": self.peak_y_mm,
                "delta_mm": self.delta_mm, "n_contact_cells": self.n_contact_cells,
                "contact_area_mm2": self.contact_area_mm2,
                "touches_edge": self.touches_edge, "edge_sides": list(self.edge_sides),
                "cells_per_semi_axis": self.cells_per_semi_axis,
                "ellipse_semi_major_mm": self.ellipse.semi_major_mm,
                "ellipse_semi_minor_mm": self.ellipse.semi_minor_mm,
                "ellipse_angle_deg": float(np.degrees(self.ellipse.angle_rad)),
                "solver": self.lcp.solver, "status": self.lcp.status,
                "solve_ms": self.lcp.solve_time_ms, "iterations": self.lcp.iterations}


def patch_statistics(grid: TangentGrid, result: ContactResult, *,
                     warn_edge: bool = True) -> PatchContact:
    """Contacting-cell statistics of a solved LCP (see :class:`PatchContact`).

    Raises
    ------
    InputRangeError
        If no cell carries load.
    """
    mask = result.contact_mask
    ellipse = fit_contact_ellipse(grid, mask)
    p = result.pressure_mpa
    area = float((grid.cell_area_mm2 * mask).sum())
    j, i = np.unravel_index(int(np.argmax(p)), p.shape)
    sides = tuple(name for name, hit in (("x_min", mask[:, 0].any()),
                                         ("x_max", mask[:, -1].any()),
                                         ("y_min", mask[0, :].any()),
                                         ("y_max", mask[-1, :].any())) if hit)
    if sides and warn_edge:
        warnings.warn(f"contact reaches the edge of the gap field at {', '.join(sides)}: "
                      "the patch is truncated (flank edge, or enlarge the field)",
                      ContactAtEdgeWarning, stacklevel=3)
    return PatchContact(grid=grid, lcp=result, load_n=result.load_n,
                        delta_mm=result.delta_mm, n_contact_cells=int(mask.sum()),
                        contact_area_mm2=area,
                        p_mean_mpa=float(result.loads_n.sum() / area),
                        p90_mpa=float(np.percentile(p[mask], 90.0)),
                        p_peak_mpa=float(p[j, i]), peak_x_mm=float(grid.x_mm[i]),
                        peak_y_mm=float(grid.y_mm[j]), peak_index=(int(j), int(i)),
                        edge_sides=sides,
                        cells_per_semi_axis=ellipse.cells_per_semi_minor,
                        ellipse=ellipse)


def solve_patch(gap_mm, grid: TangentGrid, load_n: float, *, materials=None,
                e_star_mpa: float | None = None, solver: str = "pk_cg",
                tol: float = 1e-8, max_iter: int | None = None, warm_start=None,
                raise_on_failure: bool = False, warn_edge: bool = True,
                warn_coarse: bool = True) -> PatchContact:
    """Solve one loaded contact patch from its tangent-plane gap field.

    Parameters
    ----------
    gap_mm : array_like, shape (ny, nx)
        Unloaded gap ``h[j, i]`` in mm at ``(grid.x_mm[i], grid.y_mm[j])``.
    grid : TangentGrid
        The field's grid.
    load_n : float
        Normal load W in N (> 0).
    materials, e_star_mpa, solver, tol, max_iter, warm_start, raise_on_failure
        As :func:`.lcp.solve_lcp` (``warm_start`` may be a previous
        :class:`PatchContact`).
    warn_edge : bool
        Emit :class:`ContactAtEdgeWarning` when the contact reaches the field's edge.
    warn_coarse : bool
        Emit :class:`~.ellipse.CoarseGridWarning` when the patch has fewer than
        :data:`~.ellipse.MIN_CELLS_PER_SEMI_AXIS` cells per minor semi-axis (the
        figure is always in ``cells_per_semi_axis``).

    Returns
    -------
    PatchContact

    Raises
    ------
    InputRangeError
        Bad load or gap field (see :func:`.lcp.solve_lcp`).
    LcpConvergenceError
        Only with ``raise_on_failure``; otherwise check ``.converged`` / ``.lcp.status``.
    """
    if isinstance(warm_start, PatchContact):
        warm_start = warm_start.lcp
    res = solve_lcp(gap_mm, grid, load_n, materials=materials, e_star_mpa=e_star_mpa,
                    solver=solver, tol=tol, max_iter=max_iter, warm_start=warm_start,
                    raise_on_failure=raise_on_failure, warn_coarse=warn_coarse)
    return patch_statistics(grid, res, warn_edge=warn_edge)


#: Peak / p90 ratio above which :func:`plot_patch` treats the peak as an edge spike ...
EDGE_SPIKE_RATIO = 1.5
#: ... and clips the colour scale at this multiple of p90.
EDGE_SPIKE_CLIP = 1.2


def plot_patch(patch: PatchContact, ax=None, *, ellipse: ContactEllipse | None = None,
               cmap: str = "inferno"):
    """Pressure map (MPa) with an ellipse overlaid (default: the fitted one).

    Pass e.g. the Hertzian preview's ellipse as ``ellipse`` to compare. Returns the
    Matplotlib axes. Cells are drawn at their true (possibly non-uniform) extents.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.5))
    g = patch.grid
    xe = np.concatenate([g.x_mm - g.dx_mm / 2, [g.x_mm[-1] + g.dx_mm[-1] / 2]])
    ye = np.concatenate([g.y_mm - g.dy_mm / 2, [g.y_mm[-1] + g.dy_mm[-1] / 2]])
    p = np.ma.masked_where(~patch.lcp.contact_mask, patch.pressure_mpa)
    # an edge spike (tip or end of the flank) can be several times the body of the
    # patch; a colour scale up to it would paint the whole patch dark, so the scale
    # stops at EDGE_SPIKE_CLIP x p90 and the spike shows as the clipped colour (+)
    vmax = None
    if patch.p_peak_mpa > EDGE_SPIKE_RATIO * patch.p90_mpa:
        vmax = EDGE_SPIKE_CLIP * patch.p90_mpa
    mesh = ax.pcolormesh(xe, ye, p, cmap=cmap, shading="flat", vmin=0.0, vmax=vmax)
    # short label: a long one overlaps the colour bars of stacked panels; the peak
    # itself is in the title
    label = "pressure (MPa)" if vmax is None else "pressure (MPa), clipped"
    ax.figure.colorbar(mesh, ax=ax, label=label, extend="neither" if vmax is None else "max")
    (ellipse or patch.ellipse).draw(ax, color="cyan")
    ax.plot(patch.peak_x_mm, patch.peak_y_mm, "w+", ms=8)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_aspect("equal")
    ax.set_title(f"W = {patch.load_n:.0f} N, p_peak = {patch.p_peak_mpa:.0f} MPa")
    return ax
