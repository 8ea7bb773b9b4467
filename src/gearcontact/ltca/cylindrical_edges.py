"""Tip-edge blocks of a cylindrical pair's loaded TE (docs/cylindrical.md sec. 7,
"Tip-edge contact (edge rows)").

A tip edge touching the mating flank off the plane of action is a block of the mesh
LCP (:mod:`.mesh_lcp`) along that edge: rows at the grid's axial positions with the
edge points' normal gap ``(lever / |rate|) (g_e(z) - g_first)``, across only ``x >= 0``
into the edge's own flank (no material beyond the edge) with
``sin(angle between the flanks) x + x^2 / (2 R)``; lever the touched normal's about the
gear axis, opening that lever over ``|rate|`` times the edge's closing gap behind the
mesh's; bending at the touch's roll lengths. Two kinds (:mod:`~gearcontact.tca.
cylindrical_tip`):

* a pair with no line in the zone whose tip edge touches within reach (premature
  contact of the driven tooth's tip, prolonged of the driver's): its edge's rows
  (:func:`~gearcontact.tca.cylindrical_tip.tip_edge_gaps`);
* a pair whose line is in the zone at some sections, at the sections beyond its tip
  end (a helical pair: the line crosses the zone diagonally, the tooth's sections past
  the path end stand off by a separation growing quadratically from the line's end):
  the rows beyond the end (:func:`~gearcontact.tca.cylindrical_tip.
  beyond_line_edge_gaps`) join the line's own block (:func:`join_beyond`), coupled with
  the line through the half-space and the bending of the same teeth, closing at the
  line's lever under the shared rotation.

Either enters the LCP where it may close: its closing turn (the edge's gap behind the
mesh's over ``|rate|``) below twice the previous phase's rotation, and any other whose
turn the solved rotation exceeds (:func:`closing_turn_rad`, :func:`beyond_rows`; the
phase is then solved again), so that the edges left out stand open (complementarity).
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from ..tca.cylindrical_tip import (REACH_BASE_PITCHES, TIP_EDGES, TipEdgeGaps,
                                   beyond_line_edge_gaps, tip_edge_gaps)
from ..tca.plane_of_action import PlaneOfAction
from .cylindrical_bending import line_bending_factor
from .mesh_lcp import PairBlock

__all__ = ["OFF_LINE_GAP_MM", "BEYOND_SLICES", "BeyondLoads", "BeyondSlices", "beyond_rows",
           "beyond_slices", "closing_turn_rad", "edge_block", "edge_row_slices", "join_beyond"]

#: Separation of cells off a pair's contact line, mm (far above any approach, ~10 um).
OFF_LINE_GAP_MM = 1.0
#: Slices of the tip edge beyond either end of a helical line in the twin's slice law
#: (:func:`beyond_slices`): over the tip solve's reach, 0.56 mm apart axially on the EV
#: example (its loaded TE's 40 rows: 0.8 mm).
BEYOND_SLICES = 8


def closing_turn_rad(gap_mm: float, closing_gap_mm: float, rate_mm_per_rad: float) -> float:
    """Gear turn (rad) behind the mesh's closing that closes an edge of least gap
    ``gap_mm`` (the cycle's gaps, mm; 0 where it closes with the mesh)."""
    return max(float(gap_mm) - float(closing_gap_mm), 0.0) / abs(float(rate_mm_per_rad))


def edge_block(tg: TipEdgeGaps, j: int, k: int, grid, g_first: float, g_env: float, teeth,
               nx: int) -> PairBlock:
    """The LCP block of the tip edge of pair ``j`` at phase ``k`` sampled in ``tg``
    (module docstring): ``g_first`` its least gap, ``g_env`` the mesh's closing gap
    (mm, the cycle's), ``teeth`` the :class:`~.tooth_bending.ToothBending` or None
    (rigid), ``nx`` the grid's cells across."""
    ratio, gt = tg.normal_gap_per_gap[j, k], tg.gap_mm[j, k]
    on = np.isfinite(gt)
    x = grid.x_mm[None, :]
    across = tg.slope[j, k] * x + 0.5 * tg.inv_radius_per_mm[j, k] * x * x
    h = np.where(on[:, None] & (x >= 0.0), ratio * np.where(on, gt - g_first, 0.0)[:, None]
                 + across, OFF_LINE_GAP_MM)
    factor = None
    if teeth is not None:
        factor = line_bending_factor(teeth, tg.z_mm, np.where(on, tg.u1_mm[j, k], np.nan),
                                     np.where(on, tg.u2_mm[j, k], np.nan), nx)
    return PairBlock(h, grid, float(tg.lever_mm[j, k]), ratio * max(g_first - g_env, 0.0),
                     bending_factor=factor)


def beyond_rows(beyond, j: int, k: int, g_env: float, limit_rad: float) -> np.ndarray:
    """Rows (N,) beyond pair ``j``'s line at phase ``k`` that may close: the edge (index
    into :data:`~gearcontact.tca.cylindrical_tip.TIP_EDGES`) of each row whose closing
    turn (:func:`closing_turn_rad`) is below ``limit_rad``, else -1 (``beyond``: the
    :func:`~gearcontact.tca.cylindrical_tip.beyond_line_edge_gaps` of the cycle;
    ``g_env`` the mesh's closing gap, mm)."""
    out = np.full(beyond[0].gap_mm.shape[-1], -1, dtype=np.int8)
    for i, bg in enumerate(beyond):
        g = bg.gap_mm[j, k]
        on = np.isfinite(g)
        if on.any():
            turn = np.maximum(np.where(on, g, np.inf) - g_env, 0.0) / abs(bg.rate_mm_per_rad[j, k])
            out[on & (turn < limit_rad)] = i
    return out


def join_beyond(h, u1, u2, rows, beyond, j: int, k: int, x_mm, lever_mm: float,
                offset_mm: float, g_env: float) -> None:
    """Fill the edge rows ``rows`` (:func:`beyond_rows`) into pair ``j``'s line block at
    phase ``k`` in place: its field ``h`` (N, nx; the line's datum, opening
    ``offset_mm``, lever ``lever_mm``) with the edge's normal gap behind the mesh's
    closing ``g_env`` across ``x >= 0`` (module docstring), scaled to close at the line's
    lever under the shared rotation (the edge's own lever differs by < 0.5 %: the
    elastic term of those rows is scaled alike), and the bending's roll lengths ``u1``,
    ``u2`` (N,) with the touch's."""
    x = np.asarray(x_mm)[None, :]
    for i, bg in enumerate(beyond):
        sel = rows == i
        if not sel.any():
            continue
        across = bg.slope[j, k] * x + 0.5 * bg.inv_radius_per_mm[j, k] * x * x
        normal = bg.normal_gap_per_gap[j, k] * (bg.gap_mm[j, k][sel] - g_env)[:, None] + across
        h[sel] = np.where(x >= 0.0, normal * (lever_mm / bg.lever_mm[j, k]) - offset_mm,
                          OFF_LINE_GAP_MM)
        u1[sel], u2[sel] = bg.u1_mm[j, k], bg.u2_mm[j, k]


class BeyondLoads:
    """Tally of the edges beyond the lines over a cycle of P pairs, K phases, N rows, per
    edge of :data:`~gearcontact.tca.cylindrical_tip.TIP_EDGES`: ``share`` (P, K, 2) of
    ``F_n``, ``lever_mm`` (P, K, 2; the line's, 0 where no row was in the LCP) and
    ``rows`` (P, K, N), the edge index of each row in the LCP (-1 none)."""

    def __init__(self, n_pairs: int, n_phase: int, n_rows: int):
        self.share = np.zeros((n_pairs, n_phase, len(TIP_EDGES)))
        self.lever_mm = np.zeros_like(self.share)
        self.rows = np.full((n_pairs, n_phase, n_rows), -1, dtype=np.int8)

    def add(self, j: int, k: int, i: int, rows, share: float, lever_mm: float) -> None:
        """Edge ``i`` beyond pair ``j``'s line at phase ``k`` on ``rows`` (bool, N)
        carrying ``share`` of ``F_n`` with the lever ``lever_mm``."""
        self.share[j, k, i] = share
        self.lever_mm[j, k, i] = lever_mm
        self.rows[j, k][rows] = i


@dataclass(frozen=True)
class BeyondSlices:
    """The tip edge beyond either end of every helical line of a cycle, on ``nb`` slices
    per end (:func:`beyond_slices`). Shapes (P, K, 2, nb): end 0 below the line's lower
    axial end, end 1 above its upper one, slice 0 next to the end.

    Attributes
    ----------
    gap_mm : ndarray
        Normal gap of the edge point over the line's least gap, behind the mesh's
        closing and scaled to the line's lever (:func:`join_beyond` at ``x = 0``, the
        edge), mm; :data:`OFF_LINE_GAP_MM` where no edge point lies beyond (a line end
        on the face end, beyond the tip solve's reach, no line).
    z_mm : ndarray
        Axial positions of the slices' centres, mm.
    u1_mm, u2_mm : ndarray
        Pinion and gear roll lengths of the edge's first touch (the bending's flank
        points, as the loaded TE's rows), mm; NaN where no edge point.
    width_mm : float
        Width of a slice along the line (``dz / cos beta_b``, as the loaded TE's rows), mm.
    slope, inv_radius_per_mm : ndarray (P, K, 2) or None
        Per pair, phase and edge of :data:`~gearcontact.tca.cylindrical_tip.TIP_EDGES`
        (pinion tip, gear tip), at its first touch beyond the line: the sine of the angle
        between the flanks and the relative curvature across the edge, 1/mm (NaN where
        that edge has no point beyond; the edge section's parameters,
        :mod:`.edge_section`).
    """

    gap_mm: np.ndarray
    z_mm: np.ndarray
    u1_mm: np.ndarray
    u2_mm: np.ndarray
    width_mm: float
    slope: np.ndarray | None = None
    inv_radius_per_mm: np.ndarray | None = None


def beyond_slices(pair, cycle, valid, opening_mm, lever_mm: float, *,
                  slices: int = BEYOND_SLICES) -> BeyondSlices | None:
    """The tip edge beyond the ends of every line in the zone (``valid`` (P, K)) of a
    helical pair's ``cycle``, on ``slices`` slices per end over the tip solve's reach
    (:data:`~gearcontact.tca.cylindrical_tip.REACH_BASE_PITCHES` base pitches of roll
    length, ``tan beta_b`` per mm axially) for the twin's slice law
    (docs/cylindrical.md sec. 10): the edge points' gap
    (:func:`~gearcontact.tca.cylindrical_tip.beyond_line_edge_gaps` at the slices'
    own axial positions) as :func:`join_beyond` takes it into the loaded TE's line
    block, over the line's least gap (``opening_mm`` (P, K) the line's opening behind
    the mesh's closing, mm; ``lever_mm`` the line's). None on a spur pair (a line spans
    the face in one transverse state: nothing beyond it)."""
    g = pair.geometry
    beta_b = math.radians(g.base_helix_angle_deg)
    if beta_b == 0.0:
        return None
    reach = REACH_BASE_PITCHES * math.pi * g.base_diameter_pinion_mm / cycle.pinion_teeth
    dz = reach / math.tan(beta_b) / slices
    ends = cycle.line_ends_zu_mm[..., 0]
    on = np.asarray(valid, bool) & np.isfinite(ends).all(axis=-1)
    ends = np.where(on[..., None], ends, 0.0)
    lo, hi = np.min(ends, axis=-1), np.max(ends, axis=-1)
    t = dz * (np.arange(slices) + 0.5)
    z = np.stack([lo[..., None] - t, hi[..., None] + t], axis=-2)
    shape = z.shape
    found = beyond_line_edge_gaps(PlaneOfAction(pair, cycle.facing), cycle,
                                  z.reshape(shape[:2] + (-1,)))
    g_env = np.asarray(cycle.closing_gap_mm, float)[None, :, None]
    gap = np.full(shape, OFF_LINE_GAP_MM)
    u1, u2 = np.full(shape, np.nan), np.full(shape, np.nan)
    for bg in found:
        hit = np.isfinite(bg.gap_mm).reshape(shape) & on[..., None, None]
        with np.errstate(invalid="ignore"):
            normal = (bg.normal_gap_per_gap[..., None] * (bg.gap_mm - g_env)
                      * (lever_mm / bg.lever_mm[..., None])).reshape(shape)
        gap = np.where(hit, normal - np.asarray(opening_mm)[..., None, None], gap)
        u1 = np.where(hit, bg.u1_mm[..., None, None], u1)
        u2 = np.where(hit, bg.u2_mm[..., None, None], u2)
    return BeyondSlices(gap_mm=gap, z_mm=z, u1_mm=u1, u2_mm=u2,
                        width_mm=dz / math.cos(beta_b),
                        slope=np.stack([bg.slope for bg in found], axis=-1),
                        inv_radius_per_mm=np.stack([bg.inv_radius_per_mm for bg in found],
                                                   axis=-1))


def edge_row_slices(pair, cycle, rows, nearest, line_z_mm, beyond: BeyondSlices):
    """The tip edge of every pair that touches at its tip with no line in the zone
    (``rows`` (P, K), the twin's edge rows; ``nearest`` (P, K, 2) the row of the same
    tooth pair's nearest line in the zone), sampled at that line's slices (``line_z_mm``
    (P, K, n), axial positions, mm) and edge slices (``beyond``): the edge's own normal
    gap over its first touch, ``(lever / |rate|) (g_e(z) - g_first)``, as the loaded TE's
    block of that edge takes it (:func:`edge_block`), so that the row's slice law runs
    on the edge that touches (a corner at a face end opens along the edge as the
    separation beyond the path end grows) on the slice layout of the line it continues.
    :data:`OFF_LINE_GAP_MM` where the edge point meets no mating flank.

    Returns
    -------
    line_gap_mm : ndarray (P, K, n)
    beyond_gap_mm : ndarray (P, K, 2, nb)
    u1_mm, u2_mm : ndarray (P, K)
        Pinion and gear roll lengths of the first touch (the bending's flank points);
        NaN off ``rows``.
    """
    line_z = np.asarray(line_z_mm, float)
    n, nb = line_z.shape[-1], beyond.gap_mm.shape[-1]
    line_gap = np.zeros(line_z.shape)
    edge_gap = np.full(beyond.gap_mm.shape, OFF_LINE_GAP_MM)
    u1 = np.full(line_z.shape[:2], np.nan)
    u2 = np.full_like(u1, np.nan)
    poa = PlaneOfAction(pair, cycle.facing)
    for j, k in zip(*np.nonzero(rows)):
        jn, kn = nearest[j, k]
        z = np.concatenate([line_z[jn, kn], beyond.z_mm[jn, kn].ravel()])
        where = np.zeros(rows.shape, bool)
        where[j, k] = True
        tg = tip_edge_gaps(poa, cycle, z, where=where)
        g = tg.normal_gap_per_gap[j, k] * (tg.gap_mm[j, k] - cycle.tip.gap_mm[j, k])
        g = np.where(np.isfinite(g), g, OFF_LINE_GAP_MM)
        line_gap[j, k] = g[:n]
        edge_gap[j, k] = g[n:].reshape(2, nb)
        u1[j, k], u2[j, k] = tg.u1_mm[j, k], tg.u2_mm[j, k]
    return line_gap, edge_gap, u1, u2
