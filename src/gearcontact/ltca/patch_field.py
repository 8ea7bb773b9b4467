"""Gap fields fitted to an edge row's contact patch at one load, and the touch of a
posed field: the resolution of the edge law's calibration (:mod:`.edge_law`).

The loaded TE's field of a pair (:class:`.lte_pairs.PairFields`) is sized by the
Hertzian ellipse of the pair carrying the whole torque. At an *edge row* (the TCA's edge
contact, :func:`gearcontact.tca.edge_field.edge_gap_field`, or a pair past its path's
end on its posed principal field) the patch is not that ellipse: the surfaces recede
from the touching edge with their inward slope, so the patch is a few cells across the
edge (s0003 coast's tip and heel-corner rows: 1-3 of 40 rows at ``T/16 .. T/4``, 3 at
``T``), and on a posed field it lies at the field's border, two of its 40 columns wide
and cut by the field's own extent (s0003 coast's entering pair). The LCP's approach
there is not converged in the cells (an 80-cell field moved it by 5-13 % at the TCA's
edge rows, up to 36 % at the entering pair) and the field's least gap on the flank sits
up to a cell's slope above the true touch (2.6 um on the heel corner, 4-12 um on the
posed fields near contact; docs/twin.md, "Edge rows on fields fitted to the patch").

Two remedies, both on the row's own frame (origin and axes of its field, the same
flanks posed the same way, :func:`gearcontact.tca.stencil.gap_at`):

* :func:`patch_approach`: the LCP at a load solved again on a field fitted to the patch
  it found: the contact's bounding box widened by :data:`PATCH_MARGIN` and one cell of
  the field it came from on every side, ``cells`` cells per side (the row's field's),
  twice (from the row's field, then from the first fit), and widened again (doubled)
  while the patch reaches a border of its field that is on the flank. Cell borders sit on
  ``s = 0`` and ``t = 0`` (the edge of an edge field is a cell border: its least gap
  half a cell inside, :mod:`gearcontact.tca.edge_field`). No load acts outside the
  patch, so the smaller field holds the same problem; its cells are a few times finer
  where the pressure is.
* :func:`touch_gap_mm`: the least gap of the posed flanks on both flanks, searched from
  the field's least node by windows of ``TOUCH_SIDE`` x ``TOUCH_SIDE`` points
  :data:`TOUCH_SPAN` cells either way, moved downhill (the touch may lie beyond the
  field's border) and shrunk 4 times :data:`TOUCH_LEVELS` times: a posed field's opening
  to a small fraction of a cell's slope; then over the whole flank
  (:mod:`.flank_touch`: the flank region's edges and interior minima), whose touch
  replaces the descent's where lower by more than :data:`GLOBAL_MARGIN_MM` (the descent
  stalls where the flank's border cuts its windows obliquely); alone where the field
  lies wholly off the flank.
* :func:`touch_bounds_mm`: bounds of that touch from the field alone (its least gap on
  the flank, less twice the largest rise between neighbouring flank cells, only where
  the field encloses the touch): the twin's table searches the touch only of rows whose
  lower bound is within the mesh's reach (:mod:`gearcontact.twin.mesh`).

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 5.2 (contact bounded by an edge).
"""

from __future__ import annotations

import numpy as np

from ..halfspace.grid import TangentGrid
from ..halfspace.lcp import solve_lcp
from ..tca.stencil import gap_at
from .flank_touch import edge_samples, edge_touch_mm, interior_seeds
from .pair_ltca import OFF_FLANK_GAP_MM

__all__ = ["GLOBAL_MARGIN_MM", "PATCH_MARGIN", "PATCH_PASSES", "TOUCH_LEVELS", "TOUCH_SIDE",
           "patch_approach", "patch_grid", "touch_bounds_mm", "touch_gap_mm", "touch_search"]

#: Relative widening of a patch's bounding box into the field fitted to it (beyond one
#: cell of the field the patch was found on, each side).
PATCH_MARGIN = 0.25
#: Fits of the field to the patch (from the row's field, then from the first fit).
PATCH_PASSES = 2
#: Doublings of a fitted field whose patch reaches its on-flank border.
PATCH_GROWTHS = 3
#: Zoom levels and points per side of :func:`touch_gap_mm`; the first window spans
#: TOUCH_SPAN cells either way (then a cell, a quarter, ...).
TOUCH_LEVELS, TOUCH_SIDE, TOUCH_SPAN = 5, 9, 4.0
#: Moves of the window along the flanks before it shrinks, over all levels.
TOUCH_MOVES = 32
#: Doublings of the window's span after TOUCH_MOVES moves still ended on its border
#: (:func:`touch_search`): 2^20 cells, beyond any flank.
FAR_DOUBLINGS = 20
#: The global search's touch (:mod:`.flank_touch`) replaces the descent's where it is
#: lower by more than this (mm): half the 0.1 um the touch is tested to against an
#: exhaustive scan (tests/twin/test_mesh_reach.py), the other half left to the global
#: search's own resolution (within 0.01 um of the scan on F.2, MITER_PAIR and s0003
#: coast). A row whose descent came within it keeps its touch bit for bit (s0003
#: coast's descents lie 0.011-0.029 um above the global search at 6 of its 20 rows).
GLOBAL_MARGIN_MM = 5e-5


def patch_grid(box, cells: int) -> tuple[np.ndarray, np.ndarray, TangentGrid]:
    """Cell centres ``(s_axis, t_axis)`` (mm) and their :class:`TangentGrid` of a field
    covering ``box = (s_lo, s_hi, t_lo, t_hi)`` (mm) with ``cells`` cells per side, its
    borders widened to whole cells from ``s = 0`` and ``t = 0`` (both cell borders)."""
    axes = []
    for lo, hi in (box[:2], box[2:]):
        h = (hi - lo) / cells
        k0 = int(np.floor(lo / h))
        axes.append((k0 + np.arange(int(np.ceil(hi / h)) - k0) + 0.5) * h)
    s_axis, t_axis = axes
    grid = TangentGrid.uniform(len(s_axis), len(t_axis), dx_mm=float(s_axis[1] - s_axis[0]),
                               dy_mm=float(t_axis[1] - t_axis[0]), x0_mm=float(s_axis[0]),
                               y0_mm=float(t_axis[0]))
    return s_axis, t_axis, grid


def _field(fields, pc, s_axis, t_axis):
    """(gap with off-flank cells lifted, off-flank mask) on the row's frame."""
    pinion, gear, kin = fields.args
    _, frame = fields.frames[pc.field_key]
    s, t = np.meshgrid(s_axis, t_axis)
    f = gap_at(pinion, gear, kin, fields.points[pc.field_key], s, t, frame="patch",
               axes=frame, allow_outside=True)
    off = ~f.on_flank
    return np.where(off, OFF_FLANK_GAP_MM, f.gap_mm), off


def _box(mask, grid: TangentGrid, h_s: float, h_t: float):
    """The patch's bounding box widened by one cell ``(h_s, h_t)`` and PATCH_MARGIN."""
    rows, cols = np.nonzero(mask)
    s, t = grid.x_mm[cols], grid.y_mm[rows]
    box = []
    for lo, hi, h in ((s.min(), s.max(), h_s), (t.min(), t.max(), h_t)):
        pad = h + 0.5 * PATCH_MARGIN * (hi - lo)
        box += [lo - pad, hi + pad]
    return box


def _reaches_border(mask, off) -> bool:
    """A loaded cell on the field's border with an on-flank neighbour beyond it: the
    patch may continue outside."""
    return bool((mask[0] & ~off[0]).any() or (mask[-1] & ~off[-1]).any()
                or (mask[:, 0] & ~off[:, 0]).any() or (mask[:, -1] & ~off[:, -1]).any())


def patch_approach(fields, pc, load_n: float, materials, *, datum_mm, warm=None):
    """The LCP's approach at ``load_n`` (N) from the datum on fields fitted to its patch
    (module docstring).

    Parameters
    ----------
    fields : gearcontact.ltca.lte_pairs.PairFields
        The row's fields (its field, frame and posed point).
    pc : gearcontact.ltca.lte_pairs.PairContact
        The row.
    load_n : float
        Normal load, N.
    materials : (Material, Material)
    datum_mm : float
        The closing datum of the row's approach, mm (its opening,
        :func:`~.edge_law.edge_datum_mm`).
    warm : ContactResult, optional
        Warm start on the row's own field.

    Returns
    -------
    (approach_mm, result) : (float, ContactResult or None)
        ``delta_LCP - datum`` on the last fitted field (NaN if an LCP failed, or if the
        row's field has no flank cell: its touch lies beyond it and the LCP would press
        the lifted off-flank cells, ``result`` then None) and the row's own field's
        result (the next load's warm start).
    """
    gap, grid, off, _ = fields.get(pc)
    if off.all():
        return np.nan, None
    res = solve_lcp(gap, grid, float(load_n), materials=materials, warm_start=warm,
                    warn_coarse=False)
    if not res.converged and warm is not None:
        res = solve_lcp(gap, grid, float(load_n), materials=materials, warn_coarse=False)
    if not res.converged:
        return np.nan, res
    first, fit, h = res, res, (float(grid.dx_mm[0]), float(grid.dy_mm[0]))
    for _ in range(PATCH_PASSES):
        box = _box(fit.contact_mask, grid, *h)
        for _ in range(PATCH_GROWTHS + 1):
            s_axis, t_axis, grid = patch_grid(box, fields.cells)
            gap, off = _field(fields, pc, s_axis, t_axis)
            fit = solve_lcp(gap, grid, float(load_n), materials=materials, warn_coarse=False)
            if not fit.converged:
                return np.nan, first
            if not _reaches_border(fit.contact_mask, off):
                break
            mid_s, mid_t = 0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3])
            box = [mid_s + 2.0 * (box[0] - mid_s), mid_s + 2.0 * (box[1] - mid_s),
                   mid_t + 2.0 * (box[2] - mid_t), mid_t + 2.0 * (box[3] - mid_t)]
        h = (float(grid.dx_mm[0]), float(grid.dy_mm[0]))
    return float(fit.delta_mm) - datum_mm, first


def touch_gap_mm(fields, pc) -> float:
    """The least gap of the row's flanks around its field's least node on the flank
    (module docstring): a pattern search of :data:`TOUCH_SIDE` x :data:`TOUCH_SIDE`
    windows spanning :data:`TOUCH_SPAN` cells either way, moved while the least point is
    on the window's border (the touch may lie beyond the field; at most
    :data:`TOUCH_MOVES` moves) and then shrunk 4 times, :data:`TOUCH_LEVELS` times;
    then over the whole flank (:func:`touch_search`, which also says whether the search
    settled); ``inf`` if the members' flanks do not overlap on the row's plane."""
    return touch_search(fields, pc)[0]


def touch_search(fields, pc) -> tuple[float, bool]:
    """``(touch_mm, settled)``: :func:`touch_gap_mm` and whether its search settled.

    The least gap of the row's flanks over the whole flank: the descent from the
    field's least node (:func:`_descent`: settled when every move ended inside its
    window before the :data:`TOUCH_MOVES` cap, else continued by :func:`_far_touch`),
    then the global search of :mod:`.flank_touch` (the flank region's edges, and its
    interior minima refined as the descent's windows, both to the descent's last
    resolution); its touch replaces the descent's where it lies more than
    :data:`GLOBAL_MARGIN_MM` below (then settled: the whole flank was searched). An
    unsettled search's touch is only an upper bound of the flanks' least gap
    (docs/twin.md, "Reach of the mesh table"). Where the row's field lies wholly off
    the flank (a pair far past its path's end: no node to descend from) the global
    search alone, settled; ``(inf, True)`` where it finds no point on both flanks (the
    members do not overlap on the row's plane: no gap exists)."""
    gap, grid, off, _ = fields.get(pc)
    # no flank node to descend from: the global search alone (the whole flank)
    best, settled = (np.inf, True) if off.all() else _descent(fields, pc, gap, grid, off)
    fine_s, fine_t = (TOUCH_SPAN * float(grid.dx_mm[0]) / 4.0 ** (TOUCH_LEVELS - 1),
                      TOUCH_SPAN * float(grid.dy_mm[0]) / 4.0 ** (TOUCH_LEVELS - 1))
    samples = edge_samples(fields, pc)
    other = edge_touch_mm(fields, pc, samples, best_mm=best - GLOBAL_MARGIN_MM,
                          fine_mm=0.25 * min(fine_s, fine_t))
    for least, s0, t0, hs, ht in interior_seeds(fields, pc, samples,
                                                best_mm=min(best, other) - GLOBAL_MARGIN_MM):
        other = min(other, _shrink(fields, pc, least, s0, t0, hs, ht, fine_s, fine_t)[0])
    if other < best - GLOBAL_MARGIN_MM:
        return other, True
    return best, settled


def _descent(fields, pc, gap, grid, off) -> tuple[float, bool]:
    """The pattern search of :func:`touch_gap_mm` from the field's least flank node:
    ``(touch_mm, settled)``."""
    j, i = np.unravel_index(np.argmin(np.where(off, np.inf, gap)), gap.shape)
    best = float(gap[j, i])
    s0, t0 = float(grid.x_mm[i]), float(grid.y_mm[j])
    hs, ht = TOUCH_SPAN * float(grid.dx_mm[0]), TOUCH_SPAN * float(grid.dy_mm[0])
    u = np.linspace(-1.0, 1.0, TOUCH_SIDE)
    moves = 0
    for _ in range(TOUCH_LEVELS):
        while True:
            s_ax, t_ax = s0 + hs * u, t0 + ht * u
            g, o = _field(fields, pc, s_ax, t_ax)
            g = np.where(o, np.inf, g)
            jj, ii = np.unravel_index(np.argmin(g), g.shape)
            if not g[jj, ii] < best:
                break
            best, s0, t0 = float(g[jj, ii]), float(s_ax[ii]), float(t_ax[jj])
            inner = 0 < jj < TOUCH_SIDE - 1 and 0 < ii < TOUCH_SIDE - 1
            moves += 1
            if inner or moves > TOUCH_MOVES:
                break
        hs, ht = hs / 4.0, ht / 4.0
    if moves <= TOUCH_MOVES:
        return best, True
    return _far_touch(fields, pc, best, s0, t0, TOUCH_SPAN * float(grid.dx_mm[0]),
                      TOUCH_SPAN * float(grid.dy_mm[0]))


def _window(fields, pc, s0, t0, hs, ht):
    """``(least, s, t, inner)`` of a :data:`TOUCH_SIDE`-point window of half-spans
    ``(hs, ht)`` (mm) centred on ``(s0, t0)``: its least flank gap (``inf`` if none on
    the flank), where, and whether that point is inside the window."""
    u = np.linspace(-1.0, 1.0, TOUCH_SIDE)
    s_ax, t_ax = s0 + hs * u, t0 + ht * u
    g, o = _field(fields, pc, s_ax, t_ax)
    g = np.where(o, np.inf, g)
    jj, ii = np.unravel_index(np.argmin(g), g.shape)
    inner = 0 < jj < TOUCH_SIDE - 1 and 0 < ii < TOUCH_SIDE - 1
    return float(g[jj, ii]), float(s_ax[ii]), float(t_ax[jj]), inner


def _far_touch(fields, pc, best, s0, t0, hs, ht) -> tuple[float, bool]:
    """The search of :func:`touch_search` continued past its move cap: from its last
    point, square windows (the first level's larger half-span both ways: a field fitted
    to a thin Hertzian ellipse moves its windows by hundredths of a millimetre across
    it) of doubling span, at most :data:`FAR_DOUBLINGS` times, until one holds its least
    point inside, then shrunk 4 times per level (moved while on the border,
    :data:`TOUCH_MOVES` moves per level) until each half-span is at most the first
    search's last one; settled when every level ends inside."""
    fine_s, fine_t = hs / 4.0 ** (TOUCH_LEVELS - 1), ht / 4.0 ** (TOUCH_LEVELS - 1)
    hs = ht = max(hs, ht)
    for _ in range(FAR_DOUBLINGS):
        least, s, t, inner = _window(fields, pc, s0, t0, hs, ht)
        if least < best:
            best, s0, t0 = least, s, t
        if inner:
            break
        hs, ht = 2.0 * hs, 2.0 * ht
    else:
        return best, False
    best, _, _, settled = _shrink(fields, pc, best, s0, t0, hs, ht, fine_s, fine_t)
    return best, settled


def _shrink(fields, pc, best, s0, t0, hs, ht, fine_s, fine_t):
    """``(least, s, t, settled)``: windows of half-spans ``(hs, ht)`` (mm) from ``(s0,
    t0)`` where the gap is ``best``, moved while their least point is lower and on their
    border (:data:`TOUCH_MOVES` moves per level), shrunk 4 times per level until each
    half-span is at most ``(fine_s, fine_t)``; settled when every level ended inside."""
    settled = True
    while True:
        for _ in range(TOUCH_MOVES):
            least, s, t, inner = _window(fields, pc, s0, t0, hs, ht)
            if not least < best:
                inner = True
                break
            best, s0, t0 = least, s, t
            if inner:
                break
        settled &= inner
        if hs <= fine_s * (1.0 + 1e-9) and ht <= fine_t * (1.0 + 1e-9):
            return best, s0, t0, settled
        hs, ht = hs / 4.0, ht / 4.0


def touch_bounds_mm(fields, pc) -> tuple[float, float]:
    """``(lower, upper)`` bounds (mm) of the least gap of the row's posed flanks from its
    field alone: the upper its least gap on the flank (where :func:`touch_gap_mm`
    starts), the lower that less twice the largest rise ``r`` between neighbouring flank
    cells where the field encloses the touch, else ``-inf`` (no bound: search it).

    The field *encloses* the touch when its least flank node ``p`` has all 8 neighbours
    on the flank and every flank node on the border of the field's flank nodes (a node
    on the field's border, or one with an off-flank neighbour) lies more than ``r``
    above ``p``. Assumed: the gap ``g`` is convex over the flank near the touch, and the
    flank (its projection on the field's plane) is convex there -- one minimum ``x*``,
    at most on the flank's boundary. Then, (a) were ``x*`` outside the region of cells
    whose corners are flank nodes, the segment from ``p`` to it would leave that region
    between two border nodes ``a``, ``b`` at a point ``y`` with ``g(y) <= g(p)``, and
    convexity along the border (the one-sided difference bounds the slope) gives ``g(y)
    >= g(a) - r``: some border node within ``r`` of ``p``, excluded; (b) inside a cell,
    the tangent plane at a corner ``q`` whose neighbours opposite ``x*`` are flank nodes
    bounds ``g(x*) >= g(q) - r_s - r_t >= g(p) - 2 r`` (the one-sided differences bound
    the slopes of a convex function). At an edge pair the touch usually lies on a flank
    boundary (next to an off-flank node, where the gap between nodes is bounded by no
    node) or beyond the field's border: the field bounds nothing and the row is searched
    (docs/twin.md, "Reach of the mesh table": no field of the 120 edge rows of MITER_PAIR,
    s0003 coast and the F.2 machine pair encloses its touch). ``(-inf, inf)`` if no cell
    is on the flank (the touch lies beyond the field: searched).
    """
    gap, _, off, _ = fields.get(pc)
    if off.all():
        return -np.inf, np.inf
    on = np.where(off, np.nan, gap)
    rise = [np.abs(np.diff(on, axis=a)) for a in (0, 1)]
    step = max(float(np.nanmax(r)) if np.isfinite(r).any() else 0.0 for r in rise)
    least = float(np.nanmin(on))
    return (least - 2.0 * step if _encloses(on, step) else -np.inf), least


def _encloses(on: np.ndarray, rise: float) -> bool:
    """The least node of ``on`` (gap, NaN off the flank) has 8 flank neighbours and every
    border flank node lies more than ``rise`` above it (:func:`touch_bounds_mm`)."""
    j, i = np.unravel_index(np.nanargmin(on), on.shape)
    if not (0 < j < on.shape[0] - 1 and 0 < i < on.shape[1] - 1):
        return False
    if np.isnan(on[j - 1:j + 2, i - 1:i + 2]).any():
        return False
    flank = np.pad(~np.isnan(on), 1, constant_values=False)
    inner = np.ones(on.shape, bool)
    for dj in (0, 1, 2):
        for di in (0, 1, 2):
            inner &= flank[dj:dj + on.shape[0], di:di + on.shape[1]]
    border = ~np.isnan(on) & ~inner
    return not border.any() or float(np.min(on[border])) > float(on[j, i]) + rise
