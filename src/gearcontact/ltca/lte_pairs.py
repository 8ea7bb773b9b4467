"""Tooth pairs of the loaded TE at one mesh phase: potential contacts and their posed
gap fields (see :mod:`.lte` for the formulation).

A potential contact is a neighbouring tooth pair with a mating point on both flanks, or
one at most ``edge_steps`` path steps beyond an end of its contact path (edge pair).
Its field is the separation of the flanks posed as they stand unloaded (gear resting on
the transmitting pair), along the normal lines of the tangent plane at the pair's
(nearest interior) mating point (:func:`gearcontact.tca.stencil.gap_field`), with
off-flank cells set to :data:`.pair_ltca.OFF_FLANK_GAP_MM`. At an edge contact of the
TCA (:mod:`gearcontact.tca.edge_contact`) the field is fitted to the edge instead
(:func:`gearcontact.tca.edge_field.edge_gap_field`): along it and from it into its flank,
so that its least gap is the TCA's touch to the grid's resolution.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 9.4,
15.6 (force transmission, neighbouring pairs).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ..analytic.hertz import hamrock_brewe_hertz
from ..halfspace.grid import TangentGrid
from ..tca.curvature import relative_curvature
from ..tca.edge_field import edge_frame, edge_gap_field
from ..tca.load import torque_lever_mm
from ..tca.stencil import gap_field, tangent_parameters
from ..tca.types import MatingPoint
from .mesh_lcp import PairBlock
from .pair_ltca import ARCSEC_PER_RAD, OFF_FLANK_GAP_MM
from .patch_field import touch_bounds_mm, touch_search

__all__ = ["PairContact", "PairFields", "phase_contacts", "curvature_point"]


@dataclass(frozen=True, eq=False)
class PairContact:
    """One potential contact (tooth pair ``offset`` at one phase): geometry and pose.

    Attributes
    ----------
    offset : int
        Pair index ``j``.
    path_index : int
        Index of the pair's state in the TCA path (pair ``j`` at phase ``k`` is pair 0
        at path index ``base + k + j n``).
    center_index : int
        Path index of the field's centre: ``path_index`` if the pair has a mating point,
        else the nearest interior point of its path (edge contact).
    phi2_rad : float
        Gear rotation of the unloaded pose (pair-0 coordinates): the gear rests on the
        transmitting pair, ``TE = TE0_env``.
    lever_mm : float
        Lever of the normal force about the gear axis, mm.
    opening_arcsec : float
        ``|TE0_j - TE0_env|`` (arcsec of gear rotation); NaN for an edge pair until its
        field is known.
    A_minus_per_mm, B_minus_per_mm : float
        Half relative principal curvatures at the (centre) mating point, 1/mm.
    kappa_mm_per_n23 : float
        Hertzian approach coefficient: ``delta = kappa W^(2/3)`` (mm / N^(2/3)).
    """

    offset: int
    path_index: int
    center_index: int
    phi2_rad: float
    lever_mm: float
    opening_arcsec: float
    A_minus_per_mm: float
    B_minus_per_mm: float
    kappa_mm_per_n23: float

    @property
    def edge(self) -> bool:
        """The pair's unloaded mating point has left the flanks (contact at an edge)."""
        return self.center_index != self.path_index

    @property
    def field_key(self) -> tuple[int, int]:
        """The identity of the pair's field in :class:`PairFields`: ``(path_index,
        center_index)``. Pairs at the pitch ends share a path index; a posed-field row
        (its field centred on another state) and a row on its own state at one path
        index have different fields."""
        return self.path_index, self.center_index

    @property
    def offset_mm(self) -> float:
        """Initial separation along the normal, mm."""
        return self.opening_arcsec / ARCSEC_PER_RAD * self.lever_mm


class PairFields:
    """Gap fields per pair field (:attr:`PairContact.field_key`: the path index and the
    field's centre; pairs at the pitch ends share them).

    Every field is the separation of the flanks posed as they stand unloaded (gear at
    ``pc.phi2_rad``), along the normal lines of the tangent plane at the centre point:
    it contains the pair's opening (its minimum over the flank, ~ ``g_j``) and, for an
    edge pair, the flank boundary that trims the contact. With ``bending``
    (:class:`~.tooth_bending.ToothBending`) each block also carries the bending factor
    of its two teeth at its cells.
    """

    def __init__(self, pinion, gear, kin, cycle, *, torque_nmm, e_prime, cells, extent,
                 bending=None):
        self.args = (pinion, gear, kin)
        self.path = cycle.path
        self.torque, self.e_prime, self.cells, self.extent = torque_nmm, e_prime, cells, extent
        self.bending = bending
        self.cache: dict[tuple[int, int], tuple] = {}
        self.factors: dict[tuple[int, int], np.ndarray] = {}
        self._posed: dict[tuple[int, int], tuple] = {}  # (field, posed point) awaiting a factor
        #: (origin (3,), frame (3, 3): columns e_s, e_t, n) of each field, meshing frame,
        #: by :attr:`PairContact.field_key`
        self.frames: dict[tuple[int, int], tuple] = {}
        #: the posed mating point each field was evaluated around (:mod:`.patch_field`)
        self.points: dict[tuple[int, int], MatingPoint] = {}
        self._touch: dict[tuple[int, int], float] = {}   # refined openings of edge pairs
        self._settled: dict[tuple[int, int], bool] = {}  # ... whose search settled
        self.seconds = 0.0

    def get(self, pc: PairContact):
        """(gap, grid, off-flank mask, lever) of a pair contact."""
        hit = self.cache.get(pc.field_key)
        if hit is None:
            t0 = time.perf_counter()
            pinion, gear, kin = self.args
            mp = self.path.points[pc.center_index]
            if pc.edge:  # the gear point of the nearest interior state, posed
                rot, c = kin.gear_pose(pc.phi2_rad)
                sp = gear.point(mp.u2, mp.v2)
                mp = MatingPoint(self.path.points[pc.path_index].phi1_rad, pc.phi2_rad,
                                 mp.u1, mp.v1, mp.u2, mp.v2, rot @ sp.r + c, rot @ sp.n)
            else:
                mp = replace(mp, phi2_rad=pc.phi2_rad)
            hz = hamrock_brewe_hertz(pc.A_minus_per_mm, pc.B_minus_per_mm,
                                     self.torque / pc.lever_mm, e_prime_mpa=self.e_prime)
            if mp.edge_contact:   # the TCA's edge contact: a field fitted to the edge
                f = self._edge_field(mp, pc.center_index, hz)
            else:
                f = gap_field(pinion, gear, kin, mp, side=self.cells, frame="principal",
                              half_extent_mm=(self.extent[0] * hz.a_mm,
                                              self.extent[1] * hz.b_mm),
                              allow_outside=True)  # same values on the flank; faster Newton
            off = ~f.on_flank  # near its path's end a pair's field is partly off
            s_axis, t_axis = f.s_mm[0, :], f.t_mm[:, 0]
            grid = TangentGrid.uniform(len(s_axis), len(t_axis),
                                       dx_mm=float(s_axis[1] - s_axis[0]),
                                       dy_mm=float(t_axis[1] - t_axis[0]),
                                       x0_mm=float(s_axis[0]), y0_mm=float(t_axis[0]))
            lever = torque_lever_mm(mp.point_mm, mp.normal)
            hit = (np.where(off, OFF_FLANK_GAP_MM, f.gap_mm), grid, off, lever)
            self.cache[pc.field_key] = hit
            self.frames[pc.field_key] = (f.origin_mm, f.frame)
            self.points[pc.field_key] = mp
            if self.bending is not None:  # its factor when a solve first needs it
                self._posed[pc.field_key] = (f, mp)
            self.seconds += time.perf_counter() - t0
        return hit

    def _edge_field(self, mp: MatingPoint, center: int, hz):
        """Gap field of an edge contact (:func:`~gearcontact.tca.edge_field.
        edge_gap_field`), sized by the Hertzian ellipse ``hz`` of the pair's nearest
        surface contact (the one that reached the edge; its axes from that point's
        principal directions): ``extent[0]`` times its half-width along the edge on
        either side, ``2 extent[1]`` times its half-width across the edge into the
        flank (the ellipse, cut by the edge, widens into the flank)."""
        pinion, gear, kin = self.args
        rc = relative_curvature(pinion, gear, kin, curvature_point(self.path, center))
        axes = edge_frame(pinion, gear, kin, mp)
        # half-width of the ellipse along a unit direction u (its support function)
        width = [float(np.hypot(hz.a_mm * (u @ rc.dir_min), hz.b_mm * (u @ rc.dir_max)))
                 for u in axes[:, :2].T]
        return edge_gap_field(pinion, gear, kin, mp, side=self.cells,
                              half_length_mm=self.extent[0] * width[0],
                              depth_mm=2.0 * self.extent[1] * width[1], allow_outside=True)

    def factor(self, pc: PairContact) -> np.ndarray | None:
        """The bending factor of a pair's field (None without bending), made when first
        asked for: pairs whose field only gives their opening (edge pairs out of
        reach) never need one."""
        if self.bending is None:
            return None
        self.get(pc)
        hit = self.factors.get(pc.field_key)
        if hit is None:
            t0 = time.perf_counter()
            hit = self.factors[pc.field_key] = self._bending_factor(
                *self._posed.pop(pc.field_key))
            self.seconds += time.perf_counter() - t0
        return hit

    def _bending_factor(self, f, mp) -> np.ndarray:
        """Bending factor of the teeth at the field's cells (first-order flank map)."""
        pinion, gear, kin = self.args
        st = np.column_stack([f.s_mm.ravel(), f.t_mm.ravel()])
        uv1 = tangent_parameters(pinion, kin.pinion_pose(mp.phi1_rad), f.frame, (mp.u1, mp.v1), st)
        uv2 = tangent_parameters(gear, kin.gear_pose(mp.phi2_rad), f.frame, (mp.u2, mp.v2), st)
        return self.bending.factor(uv1, uv2, f.gap_mm.shape)

    def block(self, pc: PairContact, *, rigid: bool = False) -> tuple[PairBlock, np.ndarray]:
        """(block, off-flank mask) of a pair; ``rigid``: without its bending factor."""
        gap, grid, off, lever = self.get(pc)
        return PairBlock(gap, grid, lever, 0.0,
                         bending_factor=None if rigid else self.factor(pc)), off

    def resolve(self, pc: PairContact) -> PairContact:
        """An edge pair with its opening (smallest separation over the flank of its
        posed field searched, :func:`.patch_field.touch_search`: from its least flank
        node, then globally, or globally alone where no node of the field is on the
        flank; the field's least node sits up to a cell's slope above a touch between
        nodes, and far above one beyond the field; arcsec of rotation) and the lever of its
        field's centre; other pairs unchanged."""
        if not pc.edge:
            return pc
        lever = self.get(pc)[3]
        if pc.field_key not in self._touch:
            self._touch[pc.field_key], self._settled[pc.field_key] = touch_search(self, pc)
        opening = self._touch[pc.field_key] / lever * ARCSEC_PER_RAD
        return replace(pc, opening_arcsec=opening, lever_mm=lever)

    def bound(self, pc: PairContact) -> tuple[PairContact, float]:
        """``(pair, lower_mm)``: an edge pair with the upper bound of its opening (its
        field's least gap on the flank, :func:`.patch_field.touch_bounds_mm`) and its
        field's lever, and the lower bound of the opening (mm), without the touch search
        of :meth:`resolve` where the field encloses the touch; else the pair resolved
        (:meth:`resolve`) with its touch as the lower bound, ``-inf`` if the search did
        not settle (:func:`.patch_field.touch_search`: no bound). Other pairs unchanged
        with their opening (mm)."""
        if not pc.edge:
            return pc, pc.offset_mm
        lever = self.get(pc)[3]
        if pc.field_key not in self._touch:
            lower, upper = touch_bounds_mm(self, pc)
            if lower > -np.inf:
                return replace(pc, opening_arcsec=upper / lever * ARCSEC_PER_RAD,
                               lever_mm=lever), lower
        pc = self.resolve(pc)
        settled = self._settled[pc.field_key]
        return pc, (self._touch[pc.field_key] if settled else -np.inf)


def curvature_point(path, center: int):
    """The mating point whose relative curvature (and preview stencil) a contact centred
    at path index ``center`` carries: that point, or for an edge touching the other
    flank (:mod:`gearcontact.tca.edge_contact`, no Hertzian curvature: unbounded across
    the edge) the surface contact nearest along the path."""
    mp = path.points[center]
    return _nearest_surface_point(path, center) if mp.edge_contact else mp


def _nearest_surface_point(path, index: int):
    """The surface-to-surface mating point of ``path`` nearest to ``index`` (``index``'s
    own point if every point is an edge contact: nothing better exists)."""
    surface = np.flatnonzero(path.surface)
    if surface.size == 0:
        return path.points[index]
    return path.points[int(surface[np.argmin(np.abs(surface - index))])]


def phase_contacts(pinion, gear, kin, cycle, k: int, base: int, e_prime: float,
                    curv_cache: dict, edge_steps: int) -> list[PairContact]:
    """The potential contacts at phase k: pairs with a mating point on both flanks, and
    pairs within ``edge_steps`` path steps beyond an end of their path (edge pairs)."""
    out = []
    env = float(cycle.envelope_arcsec[k])
    n = cycle.step_index
    path = cycle.path
    interior = ~path.edge
    for j, off in enumerate(cycle.pair_offsets):
        te = float(cycle.te0_pairs_arcsec[j, k])
        idx = base + k + off * n
        center = idx
        if not np.isfinite(te):
            near = np.flatnonzero(interior[max(idx - edge_steps, 0):idx + edge_steps + 1])
            if near.size == 0:
                continue
            cand = near + max(idx - edge_steps, 0)
            center = int(cand[np.argmin(np.abs(cand - idx))])
        mp = path.points[center]
        if center not in curv_cache:
            # the LCP resolves an edge contact on its posed field
            rc = relative_curvature(pinion, gear, kin, curvature_point(path, center))
            kap = hamrock_brewe_hertz(rc.A_minus_per_mm, rc.B_minus_per_mm, 1.0,
                                      e_prime_mpa=e_prime).approach_mm
            curv_cache[center] = (torque_lever_mm(mp.point_mm, mp.normal),
                                  rc.A_minus_per_mm, rc.B_minus_per_mm, kap)
        lever, a_m, b_m, kap = curv_cache[center]
        phi2 = (path.phi2_ref_rad + (path.points[idx].phi1_rad - path.phi1_ref_rad)
                / path.ratio + env / ARCSEC_PER_RAD)
        out.append(PairContact(off, idx, center, phi2, lever,
                               abs(te - env) if np.isfinite(te) else np.nan, a_m, b_m, kap))
    return out
