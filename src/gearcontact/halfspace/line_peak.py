"""Incomplete-ellipse line-contact peak ``CP_max`` of a loaded patch (docs/spec.md sec. 5).

At a tip-edge bearing the contact ellipse is cut by the flank boundary: an *incomplete
ellipse*. On rigid teeth with a sharp edge the half-space LCP puts an edge spike into
the cells next to the boundary (a pressure singularity of a sharp punch corner, Johnson
1985 sec. 5.2: its cell value grows without bound as the grid is refined), so the raw
cell peak is not a pressure of the tooth. ``CP_max`` replaces it by a mesh-independent
peak in two steps:

1. **Trimming**: a loaded cell that borders an off-flank cell (4-neighbour) is
   *boundary-inadmissible*: it carries the edge spike. It is removed (pressure and
   load); its load is reported (``trimmed_load_n``).
2. **Line-contact peak**: the admissible pressure is cut into strips across the patch,
   one per cell column (fixed ``s`` along the major axis of the principal frame, the
   cells along ``t``). Each strip is a line contact: across a strip of a Hertz ellipse
   the pressure is the semi-ellipse ``p(t) = p_s sqrt(1 - (t - t_s)^2 / b_s^2)``
   (Johnson 1985 sec. 4.2). The strip's equivalent Hertz line contact has its load per
   length and the second moment of its pressure about the centroid ``t_c``:

       q_s   = sum_adm w(s, t) / dx                                  (N/mm)
       sig^2 = sum_adm p (t - t_c)^2 / sum_adm p + dy^2 / 12
       b_s   = 2 sig                          (a semi-ellipse has sig^2 = b^2 / 4)
       p_s   = 2 q_s / (pi b_s)               (Hertz line-contact peak)

   ``dy^2 / 12`` is the variance inside a cell of uniform pressure (Sheppard's
   correction). ``CP_max = max_s p_s`` over strips with at least
   :data:`MIN_STRIP_CELLS` admissible loaded cells.

For a complete Hertz ellipse ``p_s`` equals the Hertz pressure on the strip's centre
line, ``p_0 sqrt(1 - s^2 / a^2)``, so ``CP_max = p_0``. For an *incomplete* strip,
a semi-ellipse cut at its centre line (the edge through the ellipse's axis), the
moments give ``sig^2 = b^2 (1/4 - 16 / (9 pi^2))`` and ``p_s = 0.945 p_0``: the
line-contact peak reads the pressure level of the cut ellipse from its remaining part,
without the edge singularity. The tests check both closed forms on sampled fields.

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, sec. 4.2 (Hertz
line and elliptical contact), sec. 5.2 (flat punch edge singularity).
W. F. Sheppard, Proc. London Math. Soc. 29 (1898) 353-380 (grouping correction).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError
from .grid import TangentGrid

__all__ = ["LinePeak", "MIN_STRIP_CELLS", "boundary_cells", "contact_line_length_mm",
           "inadmissible_cells",
           "line_contact_peak", "trimmed_gap"]

#: Strips with fewer admissible loaded cells carry no width estimate (a single cell
#: has only the Sheppard variance).
MIN_STRIP_CELLS = 2


@dataclass(frozen=True)
class LinePeak:
    """``CP_max`` of one patch (module docstring).

    Attributes
    ----------
    cp_max_mpa : float
        Largest strip line-contact peak, MPa (0 if no strip qualifies).
    strip_peak_mpa : ndarray (nx,)
        ``p_s`` per cell column, MPa (NaN where the strip does not qualify).
    p_peak_cell_mpa : float
        Largest raw cell pressure (edge cells included), MPa.
    p_peak_admissible_mpa : float
        Largest cell pressure after trimming, MPa.
    trimmed_cells : int
        Loaded cells trimmed as boundary-inadmissible.
    trimmed_load_n : float
        Load on the trimmed cells, N (not in any strip).
    """

    cp_max_mpa: float
    strip_peak_mpa: np.ndarray
    p_peak_cell_mpa: float
    p_peak_admissible_mpa: float
    trimmed_cells: int
    trimmed_load_n: float


def boundary_cells(off_flank: np.ndarray) -> np.ndarray:
    """On-flank cells with an off-flank 4-neighbour: the boundary row of the flank."""
    near = np.zeros_like(off_flank, dtype=bool)
    near[1:, :] |= off_flank[:-1, :]
    near[:-1, :] |= off_flank[1:, :]
    near[:, 1:] |= off_flank[:, :-1]
    near[:, :-1] |= off_flank[:, 1:]
    return near & ~off_flank


def inadmissible_cells(loaded: np.ndarray, off_flank: np.ndarray) -> np.ndarray:
    """Loaded cells with an off-flank 4-neighbour (boundary-inadmissible)."""
    return loaded & boundary_cells(off_flank)


def contact_line_length_mm(off_flank: np.ndarray, grid: TangentGrid) -> float | None:
    """Length of the contact line on the flank through the contact point, mm.

    The line is the cell row through the field's centre (``t = 0``: the principal
    frame's major axis through P0, along ``s``); its length is the width of the run of
    on-flank cells around ``s = 0`` (the flank's boundaries cut the line; a run that
    reaches the field's edge is cut there, at no less than the field's extent). This is
    the ``L`` that truncates a Hertz ellipse longer than the flank
    (:mod:`gearcontact.preview.hertz.line`). None when the row has no on-flank cell.
    """
    off = np.asarray(off_flank, bool)
    row = off[int(np.argmin(np.abs(grid.y_mm)))]
    on = np.flatnonzero(~row)
    if on.size == 0:
        return None
    i = int(on[np.argmin(np.abs(grid.x_mm[on]))])   # on-flank cell nearest s = 0
    lo = i
    while lo > 0 and not row[lo - 1]:
        lo -= 1
    hi = i
    while hi < row.size - 1 and not row[hi + 1]:
        hi += 1
    return float(grid.dx_mm[lo:hi + 1].sum())


def trimmed_gap(gap_mm: np.ndarray, off_flank: np.ndarray, loaded: np.ndarray,
                separation_mm: float) -> np.ndarray | None:
    """The gap for the LCP re-solved without the boundary-inadmissible cells.

    When a solution loads a boundary cell (:func:`boundary_cells`), the whole boundary
    row is removed from the potential contact (its gap set to ``separation_mm``, the
    off-flank separation, mm): the flank is eroded by one cell, a set fixed by the
    geometry alone, so one re-solve is final (removing only the loaded boundary cells
    could load their neighbours along the edge). Returns None when no boundary cell
    is loaded (the solution stands: cells without load keep ``s > 0`` when their gap
    grows).
    """
    bnd = boundary_cells(np.asarray(off_flank, bool))
    if not (bnd & loaded).any():
        return None
    return np.where(bnd, separation_mm, gap_mm)


def line_contact_peak(loads_n: np.ndarray, grid: TangentGrid,
                      off_flank: np.ndarray | None = None) -> LinePeak:
    """``CP_max`` of nodal loads on a principal-frame grid (module docstring).

    Parameters
    ----------
    loads_n : ndarray (ny, nx)
        Nodal loads, N (rows along ``t`` across the patch, columns along ``s``).
    grid : TangentGrid
        Uniform grid of the field (``dx`` along ``s``, ``dy`` along ``t``), mm.
    off_flank : ndarray (ny, nx) of bool, optional
        Cells beyond a flank boundary; None: none (no trimming).

    Returns
    -------
    LinePeak
    """
    w = grid.check_field("loads_n", loads_n)
    if (w < 0.0).any():
        raise InputRangeError("loads_n", float(w.min()), ">= 0 N (nodal loads)")
    off = np.zeros(w.shape, bool) if off_flank is None else np.asarray(off_flank, bool)
    if off.shape != w.shape:
        raise InputRangeError("off_flank", f"shape {off.shape}", f"shape {w.shape}")
    if not grid.is_uniform:
        raise InputRangeError("grid", "non-uniform", "a uniform grid (cell strips)")
    loaded = w > 0.0
    bad = inadmissible_cells(loaded, off)
    adm = loaded & ~bad
    p = w / grid.cell_area_mm2
    dx, dy = float(grid.dx_mm[0]), float(grid.dy_mm[0])
    t = grid.y_mm[:, None]
    pa = np.where(adm, p, 0.0)
    q = np.where(adm, w, 0.0).sum(axis=0) / dx               # N/mm per strip
    n_adm = adm.sum(axis=0)
    mass = pa.sum(axis=0)
    ok = (n_adm >= MIN_STRIP_CELLS) & (mass > 0.0)
    peak = np.full(w.shape[1], np.nan)
    if ok.any():
        m = np.where(ok, mass, 1.0)
        tc = (pa * t).sum(axis=0) / m
        var = (pa * (t - tc) ** 2).sum(axis=0) / m + dy * dy / 12.0
        b = 2.0 * np.sqrt(var)
        peak[ok] = (2.0 * q / (np.pi * b))[ok]
    return LinePeak(cp_max_mpa=float(np.nanmax(peak)) if ok.any() else 0.0,
                    strip_peak_mpa=peak, p_peak_cell_mpa=float(p.max()),
                    p_peak_admissible_mpa=float(np.where(adm, p, 0.0).max()),
                    trimmed_cells=int(bad.sum()), trimmed_load_n=float(w[bad].sum()))
