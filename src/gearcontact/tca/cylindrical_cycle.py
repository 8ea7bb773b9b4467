"""Unloaded TCA of a cylindrical pair over a mesh cycle: every tooth pair in the zone of
action, its contact line, the gap along it and TE0 (docs/cylindrical.md sec. 6).

Plane of action. Unmodified involute helicoids of parallel axes touch along straight
lines of the plane of action, the plane tangent to both base cylinders (ISO 21771;
Litvin & Fuentes 2004, ch. 14). Every flank point of the
:mod:`~gearcontact.geometry.cylindrical.flank` lies on a generator of its base cylinder
(micro-geometry moves it along that generator), so a pinion flank point lies in the
plane of action exactly when its generator is the line of action of its transverse
section: at a roll length ``u1`` linear in the phase and in ``z``. From that pinion
point the gear flank is met along the transverse line of action ``d`` (a ray solve on
the gear's posed flank, with the gear axis tilted by the ``[assembly]`` errors): the
*gap* ``g(z)`` is the distance along ``d`` (> 0 apart). For unmodified aligned flanks
``g = 0`` on the whole line; the micro-geometry of both members and a tilted gear axis
open it by ``δ1 + δ2`` and the tilt's linear term. The gap is measured in the plane of
action, where the unmodified flanks touch: the true first contact of modified flanks
lies off that plane by a distance of the order of the modification slope times the
relative radius of curvature, which changes the gap by second order in that slope
(checked against the point-contact solver :func:`~gearcontact.tca.mesh.mesh_cycle` of
the shared TCA on a crowned pair: tests/tca/test_cylindrical_cycle.py).

Per phase and tooth pair: the ends of the contact line are *solved* where the line
leaves a parameter box (a face end, a tip or form circle of either member: chord
iterations on the constraint, linear in ``z`` up to the micro-geometry), the gap's
minimum along the line by golden-section search (the gap is convex along the line:
``δ`` is a sum of convex parabolas of ``u`` and ``v``, each affine along the line, plus
the tilt's linear term), and the painted part (gap within the paint thickness of the
closed gap) by bisection.

Tip edges. Beyond the ends of its line a pair can still touch: the tip edge of either
member meets the mating flank off the plane of action when the gear lags by more than
the edge's separation there (premature contact of the driven tooth's tip, prolonged of
the driver's; :mod:`.cylindrical_tip`). Its touch is put as a gap ``g = -rate Δφ2`` and
the pair closes at the least of its line's and its tip edges' gaps.

TE0. Turning the gear by ``Δφ2`` changes the gap by ``Δφ2 (a2 × G)·d`` (``≈ r_b2``
per rad); unloaded, the gear rests on the pair that closes first (line or tip edge), so
``TE0 = -min_j g_j / rate`` (rad; reported in arcsec), measured from the perfect
involute mesh at the working centre distance (``phi2 = phi1 / u``): 0 for unmodified
aligned flanks, negative (the gear lags) where material is removed. Tooth pair ``j``
(pinion and gear tooth ``j``) at phase ``phi1`` is pair 0 at ``phi1 + 2π j / z1``
(:mod:`.mesh`), so pair 0 is solved once over its whole passage and indexed.

References
----------
ISO 21771:2007, clause 5 (contact ratios, length of path of contact).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 14.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry.cylindrical.flank import FACINGS
from ..geometry.cylindrical.pair import CylindricalPair
from ..validation import InputRangeError
from .curvature import PAINT_THICKNESS_MM
from .batched_search import affine_interval, bisect_root, golden_min
from .cylindrical_tip import TipContacts, passage_tip_contacts
from .plane_of_action import PlaneOfAction
from .types import ARCSEC_PER_RAD, MatingPoint

__all__ = ["CONTACT_TOLERANCE_MM", "FACING_OF_SIDE", "CylindricalMeshCycle", "LineGaps", "contact_line_gaps",
           "cylindrical_mesh_cycle", "pair_contact_points"]

#: ``side`` of a cylindrical pair (the commands' ``--side``) -> the flank facing in mesh.
FACING_OF_SIDE = {"drive": "cw", "coast": "ccw"}
#: A pair touches (unloaded) if its closed gap is within this, mm: far above the solves'
#: residual (1e-11 mm), far below any modification (0.1 um and up).
CONTACT_TOLERANCE_MM = 1e-6
#: Golden-section and bisection steps (0.618^60 and 2^-45 of a face width < 1e-11 mm).
_GOLDEN, _BISECT = 60, 45
#: Roll-length margin of the lines solved beyond the zone of action, mm (far above the
#: micro-geometry's and the tilt's shifts of the zone, ~0.01 mm).
_SCREEN_MM = 1.0


@dataclass(frozen=True)
class CylindricalMeshCycle:
    """Unloaded TCA of a cylindrical pair over one pinion pitch (field names as
    :class:`~gearcontact.tca.mesh.MeshCycle` where the meaning is the same).

    Shapes: K phases, P tooth pairs (``pair_offsets``); arrays NaN where a pair has no
    line in the zone of action. Pinion flank coordinates ``(z, u)``: axial position
    and roll length, mm (:mod:`~gearcontact.geometry.cylindrical.flank`).

    Attributes
    ----------
    phi1_rad : ndarray (K,)
        Pinion phases of one pitch, both ends included, centred on the pitch-point
        phase of pair 0, rad.
    pair_offsets : tuple of int
        Tooth pairs ``j`` with a line in the zone at some phase of the pitch.
    te0_pairs_arcsec : ndarray (P, K)
        TE0 each pair alone would give (its line or, touching first, its tip edge),
        arcsec.
    envelope_arcsec : ndarray (K,)
        TE0 of the mesh (the pair that closes first), arcsec, from the perfect mesh.
    te0_pp_arcsec : float
        Peak-to-peak of the envelope, arcsec.
    active_pair : ndarray (K,) of int
        The pair that closes first.
    pairs_in_zone : ndarray (K,) of int
        Pairs whose contact line crosses the zone of action (potential contact).
    pairs_in_contact : ndarray (K,) of int
        Pairs touching (line or tip edge): closed gap within :data:`CONTACT_TOLERANCE_MM`.
    gap_min_mm : ndarray (P, K)
        Least gap along each line before closure, mm.
    line_ends_mm : ndarray (P, K, 2, 3)
        Ends of each contact line in the meshing frame, mm.
    line_ends_zu_mm : ndarray (P, K, 2, 2)
        Those ends on the pinion flank, ``(z, u)`` mm.
    contact_zu_mm : ndarray (P, K, 2)
        Least-gap point of each line on the pinion flank, mm.
    painted_ends_zu_mm : ndarray (P, K, 2, 2)
        Ends of the painted part (closed gap <= ``paint_mm``) on the pinion flank, mm.
    line_length_mm : ndarray (K,)
        Total length of the contact lines in the zone of action, mm (the contact-line
        length of unmodified flanks).
    painted_length_mm : ndarray (K,)
        Total length of the painted parts, mm.
    contact : tuple of MatingPoint
        The transmitting contact per phase (meshing frame; gear normal; TE0); a tip
        edge touching first has ``edge_contact`` ``"pinion tip"`` / ``"gear tip"``.
    tip : TipContacts
        Per pair and phase (arrays (P, K, ...)) the first touch of its tip edges against
        the mating flank off the plane of action (:mod:`.cylindrical_tip`; NaN where
        none within reach).
    tip_first : ndarray (P, K) of bool
        The pair closes first at a tip edge (before its line, or with no line in the
        zone: premature or prolonged contact beyond the path of contact).
    pair_gap_mm : ndarray (P, K)
        Gap at which each pair closes first, line or tip edge, mm (TE0 of the pair is
        ``-pair_gap / rate``); NaN where it has neither.
    closing_gap_mm : ndarray (K,)
        The least of them: the mesh's closing gap (the envelope's), mm.
    paint_mm : float
    facing : str
        The flanks in mesh ("cw": pinion turning clockwise seen from +z drives).
    pinion_teeth, gear_teeth : int
    pinion_u_range_mm, pinion_v_range_mm : tuple of float
        The pinion flank's parameter box (form circle to tip; face).
    pinion_base_radius_mm : float
    """

    phi1_rad: np.ndarray
    pair_offsets: tuple[int, ...]
    te0_pairs_arcsec: np.ndarray
    envelope_arcsec: np.ndarray
    te0_pp_arcsec: float
    active_pair: np.ndarray
    pairs_in_zone: np.ndarray
    pairs_in_contact: np.ndarray
    gap_min_mm: np.ndarray
    line_ends_mm: np.ndarray
    line_ends_zu_mm: np.ndarray
    contact_zu_mm: np.ndarray
    painted_ends_zu_mm: np.ndarray
    line_length_mm: np.ndarray
    painted_length_mm: np.ndarray
    contact: tuple[MatingPoint, ...]
    tip: TipContacts
    tip_first: np.ndarray
    pair_gap_mm: np.ndarray
    closing_gap_mm: np.ndarray
    paint_mm: float
    facing: str
    pinion_teeth: int
    gear_teeth: int
    pinion_u_range_mm: tuple[float, float]
    pinion_v_range_mm: tuple[float, float]
    pinion_base_radius_mm: float

    @property
    def step_index(self) -> int:
        """Phases per pinion pitch (``K - 1``)."""
        return len(self.phi1_rad) - 1

    @property
    def mean_pairs_in_zone(self) -> float:
        """Mean number of pairs in the zone over the pitch (one end left out: periodic);
        the contact ratio ε_γ sampled at the phase step."""
        return float(np.mean(self.pairs_in_zone[:-1]))

    @property
    def mean_line_length_mm(self) -> float:
        """Mean total contact-line length over the pitch (periodic), mm."""
        return float(np.mean(self.line_length_mm[:-1]))


def _line_ends(mesh: PlaneOfAction, phi1: np.ndarray):
    """Solved ends ``(z_lo, z_hi)`` of the contact line in the zone at each phase (NaN
    where it misses the zone)."""
    lo, hi = np.full_like(phi1, np.nan), np.full_like(phi1, np.nan)
    # lines beyond the zone by more than _SCREEN_MM in roll length are not solved (the
    # involutes are singular at their base circles, u = 0)
    (pu0, pu1), (gu0, gu1) = mesh.pinion.u_range, mesh.gear.u_range
    ua, ub = (mesh.pinion_u_affine(phi1, z) for z in mesh.pinion.v_range)
    # the line's pinion roll lengths against those where both flanks are (u1 + u2 is the
    # roll_sum on the plane of action)
    near = ((np.maximum(ua, ub) > max(pu0, mesh.roll_sum - gu1) - _SCREEN_MM)
            & (np.minimum(ua, ub) < min(pu1, mesh.roll_sum - gu0) + _SCREEN_MM))
    if near.any():
        lo[near], hi[near] = _solved_ends(mesh, phi1[near])
    return lo, hi


def _solved_ends(mesh: PlaneOfAction, phi1: np.ndarray):
    p, gflank = mesh.pinion, mesh.gear
    z0, z1 = p.v_range
    za, zb = np.full_like(phi1, z0), np.full_like(phi1, z1)
    sa, sb = mesh.section(phi1, za), mesh.section(phi1, zb)
    checks = (("u1", p.u_range), ("u2", gflank.u_range), ("v2", gflank.v_range))
    lo, hi = za.copy(), zb.copy()
    which_lo = np.full(phi1.shape, -1)
    which_hi = np.full(phi1.shape, -1)
    for i, (key, (a_, b_)) in enumerate(checks):
        ia, ib = affine_interval(za, zb, sa[key], sb[key], a_, b_)
        which_lo = np.where(ia > lo, i, which_lo)
        which_hi = np.where(ib < hi, i, which_hi)
        lo, hi = np.maximum(lo, ia), np.minimum(hi, ib)
    ok = hi > lo
    # polish the ends set by a gear constraint (u2, v2 are affine in z only up to the
    # micro-geometry and the tilt): chord iterations with the end-to-end slope
    for ends, which in ((lo, which_lo), (hi, which_hi)):
        for i in (1, 2):
            key, (a_, b_) = checks[i]
            sel = ok & (which == i)
            if not sel.any():
                continue
            slope = (sb[key][sel] - sa[key][sel]) / (zb[sel] - za[sel])
            z = ends[sel]
            for _ in range(6):
                c = mesh.section(phi1[sel], z)[key]
                target = np.where(np.abs(c - a_) < np.abs(c - b_), a_, b_)
                step = (c - target) / slope
                z = z - step
                if np.max(np.abs(step)) < 1e-11:
                    break
            ends[sel] = z
    lo, hi = np.where(ok, lo, np.nan), np.where(ok, hi, np.nan)
    return lo, hi


def _on_live(live: np.ndarray, solve) -> dict:
    """``solve()``'s section fields on the ``live`` phases, NaN-filled to all phases."""
    got = solve()
    out = {}
    for key, val in got.items():
        full = np.full(live.shape + val.shape[1:], np.nan)
        full[live] = val
        out[key] = full
    return out


def cylindrical_mesh_cycle(pair: CylindricalPair, *, facing: str = "cw", phases: int = 61,
                           paint_mm: float = PAINT_THICKNESS_MM) -> CylindricalMeshCycle:
    """TCA over one pinion pitch with every tooth pair in the zone of action.

    Parameters
    ----------
    pair : CylindricalPair
        With its micro-geometry and ``[assembly]`` misalignment.
    facing : str
        "cw" (default; the pinion turning clockwise seen from +z drives with these
        flanks) or "ccw".
    phases : int
        Phases per pinion pitch including both ends, >= 3.
    paint_mm : float
        Paint thickness of the pattern, mm (default the TCA's 6.35 um).
    """
    if facing not in FACINGS:
        raise InputRangeError("facing", facing, f"one of {FACINGS}")
    if isinstance(phases, bool) or int(phases) != phases or phases < 3:
        raise InputRangeError("phases", phases, "an integer >= 3")
    if not paint_mm > 0.0:
        raise InputRangeError("paint_mm", paint_mm, "> 0 mm")
    mesh = PlaneOfAction(pair, facing)
    z1, n = pair.pinion_teeth, int(phases) - 1
    pitch = 2.0 * math.pi / z1
    h = pitch / n
    # pair 0 over its whole passage: eps_gamma pitches about the pitch point, and margin
    span = int(math.ceil(pair.geometry.total_contact_ratio)) + 1
    ks = np.arange(-span * n, span * n + 1)
    phi = mesh.phi1_p + h * ks
    lo, hi = _line_ends(mesh, phi)
    live = np.isfinite(lo)
    if live[0] or live[-1]:
        raise RuntimeError("the contact-line passage exceeds the solved span")  # a bug
    gmin = np.full(phi.shape, np.nan)
    zstar = np.full(phi.shape, np.nan)
    pl, zl, zh = phi[live], lo[live], hi[live]
    zs = golden_min(lambda z: mesh.gap(pl, z), zl, zh, steps=_GOLDEN)
    # the convex minimum may sit at an end: compare with the ends themselves
    cand = np.stack([zl, zs, zh])
    gc = np.stack([mesh.gap(pl, c) for c in cand])
    best = np.argmin(gc, axis=0)
    zstar[live] = cand[best, np.arange(len(pl))]
    gmin[live] = gc[best, np.arange(len(pl))]
    # solved on the live phases only: far beyond the zone a tilted gear's ray solve need
    # not converge from the plane of action's start (NaN there, never read)
    ends = _on_live(live, lambda: mesh.section(np.repeat(phi[live, None], 2, 1),
                                               np.column_stack([lo[live], hi[live]])))
    at = _on_live(live, lambda: mesh.section(phi[live], zstar[live]))
    tips = passage_tip_contacts(mesh, phi, live,
                                base_pitch_mm=pair.geometry.transverse_base_pitch_mm)
    near = live | np.isfinite(tips.gap_mm)

    # pair j at window phase k is pair 0 at grid index base + k + j n
    k0 = n // 2
    base = span * n - k0
    offsets = [j for j in range(-span, span + 1)
               if 0 <= base + j * n and base + n + j * n < len(phi)
               and near[base + j * n: base + n + j * n + 1].any()]
    idx = np.array([[base + k + j * n for k in range(n + 1)] for j in offsets])
    L = live[idx]
    g_pairs = np.where(L, gmin[idx], np.nan)
    tip = TipContacts(**{f: getattr(tips, f)[idx] for f in TipContacts.__dataclass_fields__})
    # a pair closes first at a tip edge where that touches before its line (by more
    # than the contact tolerance: at a line's end on a tip circle the two coincide)
    on_tip = np.isfinite(tip.gap_mm) & ~(tip.gap_mm >= np.where(L, g_pairs, np.inf)
                                         - CONTACT_TOLERANCE_MM)
    filled = np.where(on_tip, tip.gap_mm, np.where(L, g_pairs, np.inf))
    rate = np.where(on_tip, tip.rate_mm_per_rad, at["rate"][idx])
    te_pairs = np.where(np.isfinite(filled), -filled / rate * ARCSEC_PER_RAD, np.nan)
    if not L.any(axis=0).all():
        raise RuntimeError("a phase without a pair in the zone (eps_alpha >= 1 is checked "
                           "on load)")
    win = np.argmin(filled, axis=0)
    cols = np.arange(n + 1)
    g_env = filled[win, cols]
    envelope = te_pairs[win, cols]
    in_contact = (filled - g_env[None, :] <= CONTACT_TOLERANCE_MM).sum(axis=0)

    # painted part of each line: closed gap <= paint, an interval about the minimum
    level = g_env[None, :] + paint_mm
    painted = L & (g_pairs <= level)
    pz = np.full(idx.shape + (2,), np.nan)
    if painted.any():
        ii = idx[painted]
        lev = np.broadcast_to(level, idx.shape)[painted]
        ph, zlo_, zhi_, zs_ = phi[ii], lo[ii], hi[ii], zstar[ii]
        f = (lambda z: mesh.gap(ph, z) - lev)
        a = np.where(f(zlo_) <= 0.0, zlo_, bisect_root(f, zlo_, zs_, steps=_BISECT))
        b = np.where(f(zhi_) <= 0.0, zhi_, bisect_root(f, zs_, zhi_, steps=_BISECT))
        pz[painted] = np.column_stack([a, b])
    pu = mesh.pinion_u(phi[idx][..., None], pz)
    painted_zu = np.where(np.isfinite(pz)[..., None], np.stack([pz, pu], -1), np.nan)
    ends_P = ends["P"][idx]                                  # (P, K, 2, 3)
    ends_zu = np.stack([np.stack([lo[idx], hi[idx]], -1), ends["u1"][idx]], -1)
    ends_zu = np.where(L[..., None, None], ends_zu, np.nan)
    ends_P = np.where(L[..., None, None], ends_P, np.nan)
    length = np.where(L, np.linalg.norm(ends_P[:, :, 1] - ends_P[:, :, 0], axis=-1), 0.0)
    painted_P = np.where(painted, np.abs(pz[..., 1] - pz[..., 0]), 0.0)
    # the painted length along the line: axial extent over the line's axial extent
    span_z = np.where(L, hi[idx] - lo[idx], np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        frac = np.where(span_z > 0, painted_P / span_z, np.where(painted, 1.0, 0.0))
    painted_len = np.where(painted, frac * length, 0.0)
    contact_zu = np.where(L[..., None], np.stack([zstar[idx], at["u1"][idx]], -1), np.nan)

    contact = []
    for k, w in enumerate(win):
        i = idx[w, k]
        phi2 = float(phi[i] / mesh.ratio + mesh.phi2_offset + envelope[k] / ARCSEC_PER_RAD)
        if on_tip[w, k]:
            contact.append(MatingPoint(
                phi1_rad=float(phi[i]), phi2_rad=phi2, u1=float(tips.u1[i]),
                v1=float(tips.v1[i]), u2=float(tips.u2[i]), v2=float(tips.v2[i]),
                point_mm=tips.point_mm[i].copy(), normal=tips.normal[i].copy(),
                te0_arcsec=float(envelope[k]), edge_contact=tips.label(i)))
            continue
        contact.append(MatingPoint(
            phi1_rad=float(phi[i]), phi2_rad=phi2,
            u1=float(at["u1"][i]), v1=float(zstar[i]), u2=float(at["u2"][i]),
            v2=float(at["v2"][i]), point_mm=at["G"][i].copy(), normal=at["n2"][i].copy(),
            te0_arcsec=float(envelope[k])))
    return CylindricalMeshCycle(
        phi1_rad=phi[idx[0]] - offsets[0] * pitch, pair_offsets=tuple(offsets),
        te0_pairs_arcsec=te_pairs, envelope_arcsec=envelope,
        te0_pp_arcsec=float(envelope.max() - envelope.min()), active_pair=np.array(
            [offsets[w] for w in win]), pairs_in_zone=L.sum(axis=0), pairs_in_contact=in_contact,
        gap_min_mm=g_pairs, line_ends_mm=ends_P, line_ends_zu_mm=ends_zu,
        contact_zu_mm=contact_zu, painted_ends_zu_mm=painted_zu,
        line_length_mm=length.sum(axis=0), painted_length_mm=painted_len.sum(axis=0),
        contact=tuple(contact), tip=tip, tip_first=on_tip, pair_gap_mm=np.where(
            np.isfinite(filled), filled, np.nan), closing_gap_mm=g_env,
        paint_mm=float(paint_mm), facing=facing,
        pinion_teeth=z1, gear_teeth=pair.gear_teeth,
        pinion_u_range_mm=tuple(mesh.pinion.u_range), pinion_v_range_mm=tuple(mesh.pinion.v_range),
        pinion_base_radius_mm=mesh.pinion.base_radius_mm)


@dataclass(frozen=True)
class LineGaps:
    """The gap along the contact lines of a mesh cycle, sampled at given axial positions.

    Shapes (P, K, N): pairs of the cycle, its phases, the axial samples ``z_mm``; NaN
    where the sample lies off the pair's line in the zone of action.

    Attributes
    ----------
    z_mm : ndarray (N,) or (P, K, N)
        Axial positions on the pinion flank, mm (common, or each line's own).
    gap_mm : ndarray (P, K, N)
        Gap along the transverse line of action ``d`` (> 0 apart), mm, with both members
        posed on the perfect mesh ``phi2 = phi1 / u`` (the cycle's datum, before TE0).
    pinion_roll_mm, gear_roll_mm : ndarray (P, K, N)
        Roll lengths ``u1``, ``u2`` of the line point (transverse radii of curvature of
        the involutes), mm.
    rate_mm_per_rad : ndarray (P, K, N)
        ``d g / d phi2`` (about ``r_b2``, signed by the facing), mm/rad.
    """

    z_mm: np.ndarray
    gap_mm: np.ndarray
    pinion_roll_mm: np.ndarray
    gear_roll_mm: np.ndarray
    rate_mm_per_rad: np.ndarray


def contact_line_gaps(pair: CylindricalPair, cycle: CylindricalMeshCycle, z_mm) -> LineGaps:
    """Sample the gap of every contact line of ``cycle`` at the axial positions ``z_mm``.

    The same plane-of-action solve as the cycle's (module docstring): the gap field the
    loaded contact starts from (docs/cylindrical.md sec. 7).

    Parameters
    ----------
    pair : CylindricalPair
        The pair ``cycle`` was computed for.
    cycle : CylindricalMeshCycle
    z_mm : array_like (N,) or (P, K, N)
        Axial positions, mm: the same for every line (finite), or each line's own
        (NaN where the pair has no line).
    """
    lo, hi = cycle.line_ends_zu_mm[..., 0, 0], cycle.line_ends_zu_mm[..., 1, 0]
    z = np.asarray(z_mm, dtype=float)
    per_line = z.ndim == 3 and z.shape[:2] == lo.shape
    if not per_line:
        z = z.ravel()
    if z.size == 0 or not (np.isfinite(z).any() if per_line else np.isfinite(z).all()):
        raise InputRangeError("z_mm", z_mm, "a non-empty array of finite axial positions, mm "
                                            f"(N,), or (P, K, N) = {lo.shape} + (N,) per line")
    mesh = PlaneOfAction(pair, cycle.facing)
    pitch = 2.0 * math.pi / cycle.pinion_teeth
    phi = cycle.phi1_rad[None, :] + pitch * np.asarray(cycle.pair_offsets, float)[:, None]
    with np.errstate(invalid="ignore"):
        on = np.isfinite(lo)[..., None] & (z >= np.where(np.isfinite(lo), lo, 0.0)[..., None]) \
            & (z <= np.where(np.isfinite(hi), hi, 0.0)[..., None])
    shape = on.shape
    out = {k: np.full(shape, np.nan) for k in ("g", "u1", "u2", "rate")}
    if on.any():
        ph = np.broadcast_to(phi[..., None], shape)[on]
        s = mesh.section(ph, np.broadcast_to(z, shape)[on])
        for k in out:
            out[k][on] = s[k]
    return LineGaps(z_mm=z, gap_mm=out["g"], pinion_roll_mm=out["u1"],
                    gear_roll_mm=out["u2"], rate_mm_per_rad=out["rate"])


def pair_contact_points(pair: CylindricalPair, cycle: CylindricalMeshCycle
                        ) -> list[list[MatingPoint | None]]:
    """The least-gap point of every pair's contact line as a :class:`MatingPoint`.

    Same solve as the cycle's (module docstring): pinion point on the plane of action at
    the line's least-gap axial position, gear point along ``d``, gear normal; both
    members posed with the gear resting on the transmitting pair (``phi2`` of the perfect
    mesh plus the envelope's TE0), so a pair that is not transmitting stands open by its
    gap there. Returns rows per pair of ``cycle.pair_offsets``, one entry per phase
    (None where the pair has no line in the zone of action).
    """
    mesh = PlaneOfAction(pair, cycle.facing)
    pitch = 2.0 * math.pi / cycle.pinion_teeth
    phi = cycle.phi1_rad[None, :] + pitch * np.asarray(cycle.pair_offsets, float)[:, None]
    z = cycle.contact_zu_mm[..., 0]
    on = np.isfinite(z)
    out: list[list[MatingPoint | None]] = [[None] * z.shape[1] for _ in range(z.shape[0])]
    if not on.any():
        return out
    s = mesh.section(phi[on], z[on])
    te = np.broadcast_to(cycle.envelope_arcsec[None, :], z.shape)[on]
    for i, (j, k) in enumerate(zip(*np.nonzero(on))):
        out[j][k] = MatingPoint(
            phi1_rad=float(phi[j, k]), phi2_rad=float(s["phi2"][i] + te[i] / ARCSEC_PER_RAD),
            u1=float(s["u1"][i]), v1=float(z[j, k]), u2=float(s["u2"][i]), v2=float(s["v2"][i]),
            point_mm=s["G"][i].copy(), normal=s["n2"][i].copy(), te0_arcsec=float(te[i]))
    return out
