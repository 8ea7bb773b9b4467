"""TCA over the mesh cycle: neighbouring tooth pairs, TE0 envelope, per-phase contact.

Tooth pair ``j`` is pinion tooth ``j`` (the reference flank turned by ``2 pi j / z1``
about the pinion axis) against gear tooth ``j`` (turned by ``2 pi j / z2``). Because a
turned tooth posed at ``phi1`` is the reference tooth posed at ``phi1 + 2 pi j/z1``
(and likewise for the gear), pair ``j`` touches at pinion phase ``phi1`` exactly where
pair 0 touches at ``phi1 + 2 pi j / z1``, at the same point of the meshing frame, and
its transmission error is the shifted curve (Litvin & Fuentes 2004, sec. 15.6):

    TE0_j(phi1) = TE0_0(phi1 + 2 pi j / z1)      (the z1/z2 terms cancel).

So one continuation path of pair 0 on a grid whose step divides the pinion pitch
gives every pair by an index shift, without interpolation.

Envelope: unloaded, the gear rests on the first pair it meets. If the pinion pushes the
gear towards +phi2 (the gear's normal at the contact, pointing at the pinion, opposes
the gear's velocity: ``n2 . (w2 x X) < 0``) no pair may penetrate for
``phi2 < phi2_j``, so the gear angle is the *largest* of the pair solutions; if it
pushes towards -phi2 (as on the s0003 drive side of :mod:`gearcontact.geometry.flank`)
it is the smallest. TE0 is the max (resp. min) over the pairs. Its
peak-to-peak over one pinion pitch is the figure of merit ``te0_pp_arcsec``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from ..validation import check_positive
from .curvature import (PAINT_THICKNESS_MM, ContactEllipse, RelativeCurvature,
                        contact_ellipse, relative_curvature)
from .edge_contact import contact_state
from .edges import ContactGap
from .mating import solve_mating_point
from .solve import solve_tca
from .types import EDGE_TE_LIMIT_ARCSEC, ContactGuess, MatingPoint, TcaPath

__all__ = ["CONTINUATION_STEPS_PER_PITCH", "MeshCycle", "mesh_cycle", "rebase"]

#: The path is continued in steps of at most a pitch / this (coarser phase grids are
#: crossed in unrecorded substeps, so that they follow the paths to their ends).
CONTINUATION_STEPS_PER_PITCH = 30


def rebase(path: TcaPath, index: int) -> TcaPath:
    """The same path with its TE0 reference moved to the phase ``path.points[index]``.

    ``TE0' = (phi2 - phi2_v) - (phi1 - phi1_v)/u = TE0 - TE0(index)`` exactly.
    """
    ref = path.points[index]
    if ref.edge:
        raise ValueError(f"cannot rebase TE0 on an edge phase (index {index})")
    shift = ref.te0_arcsec
    pts = tuple(p if p.edge else replace(p, te0_arcsec=p.te0_arcsec - shift)
                for p in path.points)
    return TcaPath(pts, ref.phi1_rad, ref.phi2_rad, path.ratio)


@dataclass(frozen=True)
class MeshCycle:
    """TCA over one pinion pitch with the neighbouring tooth pairs.

    Attributes
    ----------
    phi1_rad : ndarray (K,)
        Phases of one pinion pitch, both ends included (``K = phases``), rad; centred
        on the reference (mean) mating point.
    pair_offsets : tuple of int
        Pair indices ``j`` considered (``-pairs .. pairs``).
    te0_pairs_arcsec : ndarray (P, K)
        TE0 of each pair, arcsec (NaN where that pair is out of its flanks).
    envelope_arcsec : ndarray (K,)
        TE0 of the transmitting contact, arcsec.
    active_pair : ndarray (K,) of int
        Offset ``j`` of the pair that carries the contact.
    te0_pp_arcsec : float
        Peak-to-peak of the envelope over the pitch, arcsec.
    contact : tuple of MatingPoint
        Mating point of the transmitting pair at each phase (meshing frame).
    curvature : tuple of RelativeCurvature
        Relative curvature there.
    ellipse : tuple of ContactEllipse
        Instantaneous contact ellipse at the paint thickness.
    pairs_in_contact : ndarray (K,) of int
        Number of pairs with an interior mating point (potential contacts).
    path : TcaPath
        The full continuation path of pair 0 (``pairs`` pitches either side).
    step_index : int
        Path phases per pinion pitch (``K - 1``).
    envelope_is_max : bool
        True if the pinion pushes the gear forwards (+phi2), so TE0 is the max over
        the pairs; False: the min.
    pinion_teeth, gear_teeth : int
        z1 and z2 (``z2 = z1 u`` rounded).
    """

    phi1_rad: np.ndarray
    pair_offsets: tuple[int, ...]
    te0_pairs_arcsec: np.ndarray
    envelope_arcsec: np.ndarray
    active_pair: np.ndarray
    te0_pp_arcsec: float
    contact: tuple[MatingPoint, ...]
    curvature: tuple[RelativeCurvature, ...]
    ellipse: tuple[ContactEllipse, ...]
    pairs_in_contact: np.ndarray
    path: TcaPath
    step_index: int
    envelope_is_max: bool
    pinion_teeth: int
    gear_teeth: int

    @property
    def reference_point(self) -> MatingPoint:
        """The reference (mean) mating point P0 of pair 0 (TE0 = 0 there)."""
        i = int(np.argmin(np.abs(self.path.phi1_rad - self.path.phi1_ref_rad)))
        return self.path.points[i]

    @property
    def mean_index(self) -> int:
        """Index of the phase nearest the reference mating point."""
        return int(np.argmin(np.abs(self.phi1_rad - self.path.phi1_ref_rad)))


#: Restarts of the continuation when the TE0 vertex lies beyond the pitch window.
_RECENTRE_TRIES = 4


def mesh_cycle(pinion: Surface, gear: Surface, kin: MeshKinematics, *, pinion_teeth: int,
               start: ContactGuess, start_fixed: str = "phi1", phases: int = 61,
               pairs: int = 3, paint_mm: float = PAINT_THICKNESS_MM,
               center: str = "vertex", edge_contact: bool = True,
               progress: bool = False) -> MeshCycle:
    """Run TCA of pair 0 over ``2 pairs + 1`` pitches (plus one either side to find the
    vertex) and assemble the mesh cycle.

    Parameters
    ----------
    pinion, gear : Surface
        One flank of each member (same side, e.g. drive).
    kin : MeshKinematics
        Kinematics with assembly errors.
    pinion_teeth : int
        z1; the pinion pitch is ``2 pi / z1``.
    start : ContactGuess
        Guess of the reference (mean) mating point; see :func:`solve_tca`.
    start_fixed : str
        Variable held while solving the reference point.
    phases : int
        Phases per pitch including both ends (>= 3; 61 or more for reports). Below
        ``CONTINUATION_STEPS_PER_PITCH + 1`` the continuation takes unrecorded
        substeps between the phases.
    pairs : int
        Neighbouring pairs on each side (``j = -pairs .. pairs``); default 3: a hypoid
        pair with a contact ratio near 3 loads pairs -3..0 over one pitch of the
        reference window (s0003), and a window one pair too narrow drops a loaded pair
        at the pitch's end (:func:`gearcontact.ltca.lte.loaded_te` checks it).
    paint_mm : float
        Paint thickness of the instantaneous ellipses, mm.
    center : str
        ``"vertex"`` (default): the reference point P0 (TE0 = 0, centre of the pitch
        window) is the path phase of least relief, i.e. the extremum of the pair's TE0
        (the vertex of the parabola); ``"start"``: the solved ``start`` point.
    edge_contact : bool
        Continue each pair's path through edge-to-surface contact (default;
        :mod:`gearcontact.tca.edge_contact`) or stop it at the first flank boundary
        (surface contact only, as surface-only TCA codes report).
    progress : bool
        Show a progress bar over the phases.

    Raises
    ------
    ContactGap
        If at some phase of the pitch no pair has an interior mating point (the paths
        are shorter than a pitch: contact ratio below one); a ValueError.
    """
    if int(pinion_teeth) < 1:
        raise ValueError(f"pinion_teeth = {pinion_teeth!r} must be >= 1")
    if int(phases) < 3:
        raise ValueError(f"phases = {phases!r} must be >= 3")
    if int(pairs) < 0:
        raise ValueError(f"pairs = {pairs!r} must be >= 0")
    pairs = int(pairs)
    check_positive("paint_mm", paint_mm)
    if center not in ("vertex", "start"):
        raise ValueError(f"center = {center!r} is not 'vertex' or 'start'")
    n = int(phases) - 1
    step = 2.0 * np.pi / int(pinion_teeth) / n
    first = (contact_state(pinion, gear, kin, start, fixed=start_fixed) if edge_contact
             else solve_mating_point(pinion, gear, kin, start, fixed=start_fixed))
    rot2, t2 = kin.gear_pose(first.phi2_rad)
    envelope_is_max = bool(first.normal @ np.cross(kin.gear_axis, first.point_mm - t2) < 0.0)
    k0 = n // 2
    span = pairs * n
    margin = (n if center == "vertex" else 0)
    ks = np.arange(-k0 - span - margin, n - k0 + span + margin + 1)
    lo, hi = k0 + span, len(ks) - 1 - (n - k0) - span   # vertices the window can centre
    # the edge tails of each path are followed while they can carry (TE0 within a limit of
    # the path's first touch); a mesh whose TE0 p-p exceeds half the limit, or that has a
    # gap, is redone with the limit widened 4x (up to 16x)
    limit, start_point = EDGE_TE_LIMIT_ARCSEC, first
    while True:
        first = start_point
        for _ in range(_RECENTRE_TRIES):
            grid = first.phi1_rad + step * ks
            path = solve_tca(pinion, gear, kin, grid, start=first.as_guess(), progress=progress,
                             edges=edge_contact, edge_te_limit_arcsec=limit,
                             max_step_rad=2.0 * np.pi / int(pinion_teeth)
                             / CONTINUATION_STEPS_PER_PITCH)
            if center != "vertex":
                i_ref = int(np.flatnonzero(ks == 0)[0])
                break
            # P0 = the point of least relief along the path: the TE0 extremum of one pair
            te = np.where(path.edge, -np.inf if envelope_is_max else np.inf, path.te0_arcsec)
            i_v = int(np.argmax(te) if envelope_is_max else np.argmin(te))
            if lo <= i_v <= hi or not np.isfinite(te[i_v]):
                break
            # the start was more than a pitch from the vertex (a bearing far from the mean
            # node): restart the continuation from the path point nearest the vertex
            first = path.points[i_v]
        if center == "vertex":
            i_ref = int(np.clip(i_v, lo, hi))
            path = rebase(path, i_ref)
        offsets = tuple(range(-pairs, pairs + 1))
        te0 = path.te0_arcsec
        base = i_ref - k0                         # grid index of the pitch's first phase
        idx = np.array([[base + k + j * n for k in range(n + 1)] for j in offsets])
        te_pairs = te0[idx]
        valid = np.isfinite(te_pairs)
        if not valid.any(axis=0).all():
            if edge_contact and limit < 16.0 * EDGE_TE_LIMIT_ARCSEC:
                limit *= 4.0            # a gap the cut edge tails may bridge
                continue
            touched = valid.any(axis=0)
            k = int(np.argmin(touched))
            # columns 0 and n are one phase a pitch apart: the pitch's phases are 0..n-1
            raise ContactGap(grid[base + k], gap_phases=int(np.sum(~touched[:n])),
                             phases_per_pitch=n)
        filled = np.where(valid, te_pairs, -np.inf if envelope_is_max else np.inf)
        winner = np.argmax(filled, axis=0) if envelope_is_max else np.argmin(filled, axis=0)
        cols = np.arange(n + 1)
        envelope = te_pairs[winner, cols]
        if (not edge_contact or float(envelope.max() - envelope.min()) <= 0.5 * limit
                or limit >= 16.0 * EDGE_TE_LIMIT_ARCSEC):
            break
        limit *= 4.0
    contact = tuple(path.points[idx[w, k]] for k, w in enumerate(winner))
    curv = tuple(relative_curvature(pinion, gear, kin, mp) for mp in contact)
    ell = tuple(contact_ellipse(rc, paint_mm=paint_mm) for rc in curv)
    return MeshCycle(grid[base:base + n + 1], offsets, te_pairs, envelope,
                     np.array([offsets[w] for w in winner]),
                     float(envelope.max() - envelope.min()), contact, curv, ell,
                     valid.sum(axis=0), path, n, envelope_is_max, int(pinion_teeth),
                     int(round(int(pinion_teeth) * kin.ratio)))
