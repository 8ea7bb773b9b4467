"""Tip-edge contact of a cylindrical pair: the tip edge of either member touching the
mating flank off the plane of action (docs/cylindrical.md sec. 6, "Tip-edge contact").

Conjugate involutes touch only in the plane of action, and a contact line ends where it
meets a tip circle. Beyond that end the tip edge of the member (the top-land edge
``u = u_a``, a straight line on a spur tooth, a helix on a helical one) stands off the
mating flank by a separation that grows about quadratically with the distance beyond
the path end. When the gear lags the perfect mesh by more than that separation -- a
relief or a misalignment that leaves the transmitting pair open, or, loaded, the
deflection of the teeth in contact -- the tip edge touches the mating flank before the
line of action reaches it: the premature (extended) contact at the tip corner of the
driven tooth at the start of mesh, and the prolonged one of the driver's tip at its
end (Niemann & Winter, *Maschinenelemente* II, ch. 21.5; Munro's extended contact).

This is the edge-to-surface contact of :mod:`~gearcontact.tca.edge_contact` with the
edges of a cylindrical flank pair (:data:`TIP_EDGES`, labelled as there, ``"gear
tip"``): for each point ``z`` of the tip edge ``C(z)`` of member ``M`` the gear rotation
``phi2(z)`` that brings it onto the other member's flank solves ``X_1 = X_2`` in the
other flank's ``(u, v)`` and ``phi2`` (pinion phase held; Newton with the Jacobian
``[r_u, r_v, a_2 x X_2]``, the equations of :class:`~gearcontact.tca.edge_contact.
_EdgeSolver`), and the contact is the point of the edge that touches first. Here the
solve is batched over phases and edge points (the cycle's phases at once, where the
scalar solver of the bevel TCA would cost ~0.1 s per phase): the edge is sampled at
:data:`SAMPLES` points and the best one refined by golden section between its
neighbours; a sample at a face end is a corner contact.

The result is expressed as the cycle's *gap* (``g = -rate Δphi2``, ``rate`` the gap's
``d g / d phi2`` at the touching point, :mod:`.cylindrical_cycle`), so that the pair
closing first is the least gap over lines and tip edges alike. A touch beyond the other
flank's box (below its form circle: the fillet), an edge point beyond its own face
(the narrower member's edge ends at its face end) or one that does not converge is no
contact (NaN).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .batched_search import golden_min
from .edge_contact import FlankEdge

__all__ = ["REACH_BASE_PITCHES", "SAMPLES", "TIP_EDGES", "TipContacts", "TipEdgeGaps",
           "beyond_line_edge_gaps", "passage_tip_contacts", "tip_edge_contacts", "tip_edge_gaps"]

#: The edges of a cylindrical flank pair that can touch off the plane of action.
TIP_EDGES = (FlankEdge("pinion", "tip"), FlankEdge("gear", "tip"))
#: Points per tip edge before the refinement (both face ends among them).
SAMPLES = 9
#: Newton iterations of the touch (quadratic from the plane-of-action start: 3-5 used).
_NEWTON = 12
#: Golden-section steps between the best sample's neighbours (0.618^28 of b/4: 1e-5 b).
_GOLDEN = 28
#: Residual of a touch, mm (as the cycle's point solves).
_RESIDUAL_MM = 1e-11
#: A touch must lie inside the other flank's box within this, mm.
_BOX_MM = 1e-9
#: Largest |Δphi2| of a touch, rad: far beyond any micro-geometry or deflection
#: (0.01 rad is 0.3 mm on a 30 mm base radius); larger is another branch.
_MAX_TURN_RAD = 0.01


@dataclass(frozen=True)
class TipContacts:
    """The first touch of the tip edges at each phase (arrays over the phases, M).

    Attributes
    ----------
    gap_mm : ndarray (M,)
        Equivalent gap ``-rate Δphi2`` of the first touching tip-edge point, mm (NaN:
        no tip edge touches the other flank within reach).
    turn_rad : ndarray (M,)
        ``Δphi2``: the gear rotation from the perfect mesh that closes it, rad.
    rate_mm_per_rad : ndarray (M,)
        ``d g / d phi2`` at the touching point, mm/rad.
    edge : ndarray (M,) of int
        Index into :data:`TIP_EDGES` (-1: none).
    u1, v1, u2, v2 : ndarray (M,)
        Flank parameters of the touch (the edge member's ``u`` its tip roll length).
    point_mm : ndarray (M, 3)
        The touching point (meshing frame, gear turned by ``turn_rad``), mm.
    normal : ndarray (M, 3)
        The touched flank's unit normal, oriented out of the gear tooth (the mating
        normal's orientation).
    """

    gap_mm: np.ndarray
    turn_rad: np.ndarray
    rate_mm_per_rad: np.ndarray
    edge: np.ndarray
    u1: np.ndarray
    v1: np.ndarray
    u2: np.ndarray
    v2: np.ndarray
    point_mm: np.ndarray
    normal: np.ndarray

    def label(self, i) -> str:
        """``"pinion tip"`` / ``"gear tip"`` of entry ``i`` ("" none)."""
        return TIP_EDGES[self.edge[i]].label if self.edge[i] >= 0 else ""

    def labels(self) -> np.ndarray:
        """:meth:`label` of every entry (an array of the shape of ``edge``)."""
        names = np.array([e.label for e in TIP_EDGES] + [""])
        return names[np.where(self.edge >= 0, self.edge, len(TIP_EDGES))]


def _cross(a, b):
    """Row-wise a x b of (3,) or (n, 3) by (n, 3) (np.cross is slow on small batches)."""
    a = np.broadcast_to(a, b.shape)
    return np.stack([a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1], a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
                     a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]], axis=-1)


def _posed(rot, x):
    return np.einsum("nij,nj->ni", rot, x)


def _touch(mesh, member: str, phi1, z, y0):
    """Batched touch of the ``member`` tip-edge points ``z`` at phases ``phi1``:
    ``(y, gap, fields)`` with ``y = (u, v, turn)`` on the other flank (gap NaN where
    none). Newton on the points not yet converged only."""
    own, other = (mesh.pinion, mesh.gear) if member == "pinion" else (mesh.gear, mesh.pinion)
    rot1, t1 = mesh.pinion_poses(phi1)
    phi2 = phi1 / mesh.ratio + mesh.phi2_offset
    tip = own.evaluate(np.full_like(z, own.u_range[1]), z, second=False).r
    x_own = _posed(rot1, tip) + t1 if member == "pinion" else None
    a2 = mesh.kin.gear_axis
    y = np.array(y0, float)
    ok = np.zeros(len(z), bool)
    todo = np.arange(len(z))
    for _ in range(_NEWTON):
        if todo.size == 0:
            break
        yt = y[todo]
        rot2 = mesh.gear_rotations(phi2[todo] + yt[:, 2])
        s = other.evaluate(np.maximum(yt[:, 0], 1e-6), yt[:, 1], second=False)
        if member == "pinion":
            x2 = _posed(rot2, s.r)
            res = x2 - x_own[todo]
            cols = [_posed(rot2, s.r_u), _posed(rot2, s.r_v)]
        else:
            r1 = rot1[todo]
            x2 = _posed(rot2, tip[todo])
            res = x2 - (_posed(r1, s.r) + t1)
            cols = [-_posed(r1, s.r_u), -_posed(r1, s.r_v)]
        done = np.max(np.abs(res), axis=1) < _RESIDUAL_MM
        ok[todo[done]] = True
        jac = np.stack(cols + [_cross(a2, x2)], axis=-1)[~done]
        bad = np.abs(np.linalg.det(jac)) < 1e-12
        jac[bad] = np.eye(3)
        step = np.linalg.solve(jac, -res[~done][..., None])[..., 0]
        step[bad] = np.nan
        todo = todo[~done]
        y[todo] += step
        todo = todo[np.isfinite(y[todo]).all(axis=1)]
    (u0, u1), (v0, v1) = other.u_range, other.v_range
    # the edge point on its own face too (a narrower member's edge ends at its face end:
    # beyond it the helicoid's continuation is no material)
    w0, w1 = own.v_range
    with np.errstate(invalid="ignore"):
        ok &= ((y[:, 0] >= u0 - _BOX_MM) & (y[:, 0] <= u1 + _BOX_MM) & (y[:, 1] >= v0 - _BOX_MM)
               & (y[:, 1] <= v1 + _BOX_MM) & (np.abs(y[:, 2]) < _MAX_TURN_RAD)
               & (z >= w0 - _BOX_MM) & (z <= w1 + _BOX_MM))
    return y, ok


def _touch_fields(mesh, member: str, phi1, z, y, ok):
    """The gap (NaN where not ``ok``), its rate, the point and the normal of touches."""
    own, other = (mesh.pinion, mesh.gear) if member == "pinion" else (mesh.gear, mesh.pinion)
    yy = np.where(ok[:, None], y, np.column_stack([np.full_like(z, other.u_range[1]), z,
                                                   np.zeros_like(z)]))
    rot2 = mesh.gear_rotations(phi1 / mesh.ratio + mesh.phi2_offset + yy[:, 2])
    s = other.evaluate(yy[:, 0], yy[:, 1], second=False)
    if member == "pinion":
        x = _posed(rot2, s.r)
        n = _posed(rot2, s.n)
    else:
        x = _posed(rot2, own.evaluate(np.full_like(z, own.u_range[1]), z, second=False).r)
        n = -_posed(mesh.pinion_poses(phi1)[0], s.n)
    rate = _cross(mesh.kin.gear_axis, x) @ mesh.d
    return dict(gap=np.where(ok, -rate * yy[:, 2], np.nan), rate=rate, point=x, normal=n,
                tip_u=own.u_range[1])


def _closing(mesh, member, phi1, z, y0):
    """Score of touches, the gear turn that closes them along the closing sense (the
    first touch has the least; inf where none), and their ``(y, ok)``."""
    y, ok = _touch(mesh, member, phi1, z, y0)
    sense = np.sign(_cross(mesh.kin.gear_axis, mesh.p0[None, :])[0] @ mesh.d)
    return np.where(ok, -sense * y[:, 2], np.inf), y, ok


def _start(mesh, member: str, z):
    """Newton start: the other flank's point where the tip would meet it in the plane of
    action (roll lengths sum to the plane's), same axial position, no turn."""
    own = mesh.pinion if member == "pinion" else mesh.gear
    return np.column_stack([np.full_like(z, mesh.roll_sum - own.u_range[1]), z,
                            np.zeros_like(z)])


def _edge_first_touch(mesh, member: str, phi1):
    """Per phase the first touching point of one tip edge: ``(z, y, fields)``."""
    own = mesh.pinion if member == "pinion" else mesh.gear
    v0, v1 = own.v_range
    zs = np.linspace(v0, v1, SAMPLES)
    m = len(phi1)
    zz = np.tile(zs, m)
    score, y, _ = _closing(mesh, member, np.repeat(phi1, SAMPLES), zz, _start(mesh, member, zz))
    score = score.reshape(m, SAMPLES)
    k = np.argmin(score, axis=1)
    rows = np.arange(m)
    z_end = zs[k]
    y_end = y.reshape(m, SAMPLES, 3)[rows, k]
    best = score[rows, k]
    # golden section between the best sample's neighbours where one touches (the gap
    # along the edge is smooth and single-troughed there: a sum of convex
    # modifications, a linear tilt and the quadratic separation beyond the path end)
    on = np.flatnonzero(np.isfinite(best))
    if on.size:
        h = (v1 - v0) / (SAMPLES - 1)
        a, b = np.maximum(z_end[on] - h, v0), np.minimum(z_end[on] + h, v1)
        ph, yo = phi1[on], y_end[on]

        def score_of(zq):
            return _closing(mesh, member, ph, zq, np.column_stack([yo[:, 0], zq, yo[:, 2]]))[0]

        zg = golden_min(score_of, a, b, steps=_GOLDEN)
        sg, yg, _ = _closing(mesh, member, ph, zg, np.column_stack([yo[:, 0], zg, yo[:, 2]]))
        better = sg < best[on]
        z_end[on[better]] = zg[better]
        y_end[on[better]] = yg[better]
        best[on[better]] = sg[better]
    return z_end, y_end, _touch_fields(mesh, member, phi1, z_end, y_end, np.isfinite(best))


def tip_edge_contacts(mesh, phi1) -> TipContacts:
    """The first touching tip-edge point of one tooth pair at the phases ``phi1``.

    Parameters
    ----------
    mesh
        The cycle's posed flank pair (:class:`~gearcontact.tca.cylindrical_cycle._Mesh`:
        flanks, batched poses, the plane of action's ``d`` and roll sum).
    phi1 : array_like (M,)
        Pinion phases, rad.
    """
    phi1 = np.asarray(phi1, float).ravel()
    m = len(phi1)
    best = dict(gap=np.full(m, np.inf), turn=np.full(m, np.nan), rate=np.full(m, np.nan),
                edge=np.full(m, -1), u1=np.full(m, np.nan), v1=np.full(m, np.nan),
                u2=np.full(m, np.nan), v2=np.full(m, np.nan), point=np.full((m, 3), np.nan),
                normal=np.full((m, 3), np.nan))
    if m == 0:
        return _result(best)
    for i, edge in enumerate(TIP_EDGES):
        z, y, fl = _edge_first_touch(mesh, edge.member, phi1)
        gap = fl["gap"]
        win = np.isfinite(gap) & (gap < best["gap"])
        if not win.any():
            continue
        own = (np.full(m, fl["tip_u"]), z)
        pin, gear = (own, (y[:, 0], y[:, 1])) if edge.member == "pinion" else \
            ((y[:, 0], y[:, 1]), own)
        for key, val in (("gap", gap), ("turn", y[:, 2]), ("rate", fl["rate"]),
                         ("edge", np.full(m, i)), ("u1", pin[0]), ("v1", pin[1]),
                         ("u2", gear[0]), ("v2", gear[1]), ("point", fl["point"]),
                         ("normal", fl["normal"])):
            best[key][win] = val[win]
    return _result(best)


def _result(best) -> TipContacts:
    gap = np.where(np.isfinite(best["gap"]), best["gap"], np.nan)
    return TipContacts(gap_mm=gap, turn_rad=best["turn"], rate_mm_per_rad=best["rate"],
                       edge=best["edge"], u1=best["u1"], v1=best["v1"], u2=best["u2"],
                       v2=best["v2"], point_mm=best["point"], normal=best["normal"])


#: Reach of the tip-edge solve beyond a contact line's passage, in transverse base
#: pitches of roll length: the separation beyond the path end grows about as s^2 / (2 ρ)
#: (measured 36 um at s = 0.85 mm on the spur 20/40 m 3), so 0.3 p_bt reaches several
#: hundred um, beyond any relief or deflection the tip corner could make up.
REACH_BASE_PITCHES = 0.3


def passage_tip_contacts(mesh, phi1, live, *, base_pitch_mm: float) -> TipContacts:
    """:func:`tip_edge_contacts` of pair 0 on its passage grid ``phi1`` (uniform), NaN
    where not solved: from :data:`REACH_BASE_PITCHES` (in roll length) before its first
    phase with a line in the zone (``live``) to as far after its last. A spur pair's
    tip edges lie in one transverse section state, beyond the path or inside it, so
    they are solved only within that reach of either end of the passage; a helical
    pair's over the whole passage (its tip helix crosses sections beyond the path end
    at every phase whose line ends on a tip circle)."""
    phi1 = np.asarray(phi1, float)
    nan = np.full(phi1.shape, np.nan)
    out = _result(dict(gap=np.full(phi1.shape, np.inf), turn=nan.copy(), rate=nan.copy(),
                       edge=np.full(phi1.shape, -1), u1=nan.copy(), v1=nan.copy(),
                       u2=nan.copy(), v2=nan.copy(), point=np.full(phi1.shape + (3,), np.nan),
                       normal=np.full(phi1.shape + (3,), np.nan)))
    on = np.flatnonzero(live)
    if on.size == 0:
        return out
    step = abs(phi1[1] - phi1[0]) * mesh.pinion.base_radius_mm      # roll per phase, mm
    reach = int(math.ceil(REACH_BASE_PITCHES * base_pitch_mm / step))
    k = np.arange(len(phi1))
    solve = (k >= on[0] - reach) & (k <= on[-1] + reach)
    if mesh.pinion.lead_rate_rad_per_mm == 0.0:
        solve &= (k <= on[0] + reach) | (k >= on[-1] - reach)
    got = tip_edge_contacts(mesh, phi1[solve])
    for name in out.__dataclass_fields__:
        getattr(out, name)[solve] = getattr(got, name)
    return out


@dataclass(frozen=True)
class TipEdgeGaps:
    """The gap along the first-touching tip edge of every pair and phase of a mesh
    cycle, at given axial positions (the loaded TE's field of a tip-edge contact).

    Shapes (P, K, N) / (P, K) as :class:`~gearcontact.tca.cylindrical_cycle.LineGaps`;
    NaN where the pair has no tip-edge touch within reach (``cycle.tip``) or the edge
    point at that ``z`` meets no mating flank.

    Attributes
    ----------
    z_mm : ndarray (N,) or (P, K, N)
        Axial positions along the edge, mm.
    gap_mm : ndarray (P, K, N)
        Equivalent gap ``-rate Δphi2`` of each edge point (module docstring), mm.
    normal_gap_per_gap : ndarray (P, K)
        Normal separation per unit equivalent gap at the first touch, ``lever / |rate|``.
    lever_mm : ndarray (P, K)
        Lever of the touched normal about the gear axis, ``|(a2 x X) . n|``, mm.
    slope : ndarray (P, K)
        Sine of the angle between the two flanks at the first touch: the separation's
        slope into the edge's own flank, perpendicular to the edge.
    inv_radius_per_mm : ndarray (P, K)
        Relative normal curvature across the edge, ``cos(beta_b) (1/u_own + 1/u_other)``
        with the transverse radii (roll lengths) of the edge and the touched point, 1/mm.
    u1_mm, u2_mm : ndarray (P, K)
        Pinion and gear roll lengths of that touch, mm (the bending's flank points).
    rate_mm_per_rad : ndarray (P, K)
        ``d g / d phi2`` at that touch, mm/rad.
    """

    z_mm: np.ndarray
    gap_mm: np.ndarray
    normal_gap_per_gap: np.ndarray
    lever_mm: np.ndarray
    slope: np.ndarray
    inv_radius_per_mm: np.ndarray
    u1_mm: np.ndarray
    u2_mm: np.ndarray
    rate_mm_per_rad: np.ndarray


def _touch_geometry(mesh, member: str, phi, own_z, other_u, turn, point, normal):
    """Lever ``|(a2 x X) . n|`` (mm), the sine of the angle between the flanks and the
    relative curvature across the edge (1/mm) of tip-edge touches of ``member`` at the
    phases ``phi`` (edge point ``own_z``, touched roll length ``other_u``, gear turn
    ``turn``, point and touched normal as :func:`_touch_fields`)."""
    own = mesh.pinion if member == "pinion" else mesh.gear
    cb = 1.0 / math.sqrt(1.0 + (mesh.pinion.lead_rate_rad_per_mm
                                * mesh.pinion.base_radius_mm) ** 2)
    lever = np.abs(np.einsum("ni,ni->n", _cross(mesh.kin.gear_axis, point), normal))
    # the edge's own flank normal at the touch, posed as the touch
    s_own = own.evaluate(np.full(len(phi), own.u_range[1]), own_z, second=False)
    if member == "pinion":
        n_own = _posed(mesh.pinion_poses(phi)[0], s_own.n)
    else:
        n_own = _posed(mesh.gear_rotations(phi / mesh.ratio + mesh.phi2_offset + turn),
                       s_own.n)
    slope = np.linalg.norm(_cross(n_own, normal), axis=1)
    return lever, slope, cb * (1.0 / own.u_range[1] + 1.0 / other_u)


def _edge_gaps(z, gaps, fields: dict) -> TipEdgeGaps:
    """:class:`TipEdgeGaps` of sampled ``gaps`` (P, K, N) and the touches' per-pair
    ``fields`` (``lever``, ``rate``, ``slope``, ``inv_r``, ``u1``, ``u2``; (P, K))."""
    return TipEdgeGaps(z_mm=z, gap_mm=gaps,
                       normal_gap_per_gap=fields["lever"] / np.abs(fields["rate"]),
                       lever_mm=fields["lever"], slope=fields["slope"],
                       inv_radius_per_mm=fields["inv_r"], u1_mm=fields["u1"],
                       u2_mm=fields["u2"], rate_mm_per_rad=fields["rate"])


def tip_edge_gaps(mesh, cycle, z_mm, *, where=None) -> TipEdgeGaps:
    """Sample the first-touching tip edge of every pair and phase of ``cycle`` at the
    axial positions ``z_mm`` (the same solve as :func:`tip_edge_contacts`, from the
    cycle's touch).

    Parameters
    ----------
    mesh
        The cycle's :class:`~gearcontact.tca.plane_of_action.PlaneOfAction`.
    cycle : CylindricalMeshCycle
    z_mm : array_like (N,)
        Axial positions (finite), mm.
    where : ndarray (P, K) of bool, optional
        Sample only these pairs and phases (NaN elsewhere); default all.
    """
    z = np.asarray(z_mm, float).ravel()
    tip = cycle.tip
    shape = tip.gap_mm.shape
    gaps = np.full(shape + (len(z),), np.nan)
    per = {k: np.full(shape, np.nan) for k in ("lever", "slope", "inv_r")}
    pitch = 2.0 * math.pi / cycle.pinion_teeth
    phi = cycle.phi1_rad[None, :] + pitch * np.asarray(cycle.pair_offsets, float)[:, None]
    for i, edge in enumerate(TIP_EDGES):
        sel = np.isfinite(tip.gap_mm) & (tip.edge == i)
        if where is not None:
            sel &= np.asarray(where, bool)
        if not sel.any():
            continue
        a = (tip.u2 if edge.member == "pinion" else tip.u1)[sel]
        turn = tip.turn_rad[sel]
        m, n = int(sel.sum()), len(z)
        ph, zz = np.repeat(phi[sel], n), np.tile(z, m)
        y, ok = _touch(mesh, edge.member, ph, zz, np.column_stack([np.repeat(a, n), zz,
                                                                  np.repeat(turn, n)]))
        gaps[sel] = _touch_fields(mesh, edge.member, ph, zz, y, ok)["gap"].reshape(m, n)
        own_z = (tip.v1 if edge.member == "pinion" else tip.v2)[sel]
        got = _touch_geometry(mesh, edge.member, phi[sel], own_z, a, turn,
                              tip.point_mm[sel], tip.normal[sel])
        for key, val in zip(("lever", "slope", "inv_r"), got):
            per[key][sel] = val
    touched = np.isfinite(per["lever"])
    per.update(rate=np.where(touched, tip.rate_mm_per_rad, np.nan),
               u1=np.where(touched, tip.u1, np.nan), u2=np.where(touched, tip.u2, np.nan))
    return _edge_gaps(z, gaps, per)


def beyond_line_edge_gaps(mesh, cycle, z_mm) -> tuple[TipEdgeGaps, TipEdgeGaps]:
    """The tip edges beyond the ends of the contact lines in the zone (a helical pair):
    per edge of :data:`TIP_EDGES`, the gap of its points at the axial positions
    ``z_mm`` whose transverse section lies beyond that member's path end (the section's
    plane-of-action roll length beyond its tip circle, by at most
    :data:`REACH_BASE_PITCHES` base pitches) while the pair's line is in the zone at
    other sections (docs/cylindrical.md sec. 7, "Tip-edge contact").

    The touch is solved as :func:`tip_edge_contacts`' (from the plane of action, no
    turn) at every such point; the per-pair fields of :class:`TipEdgeGaps` are those of
    the point touching first (least gap). The sections are classed on the affine
    plane of action of the unmodified flanks (micro-geometry shifts it by ~0.01 mm of
    roll length, a tenth of a row on the examples): a row off the line within that of
    a tip end may be left out (it stays off-line). NaN where the point is not beyond
    a tip end or meets no mating flank (beyond its box: its face end or its fillet).

    Parameters
    ----------
    mesh, cycle
        As :func:`tip_edge_gaps`.
    z_mm : array_like (N,) or (P, K, N)
        Axial positions (finite), mm, shared by every pair and phase or each row's own
        (the twin's slices beyond each line's ends, :func:`gearcontact.ltca.
        cylindrical_edges.beyond_slices`).

    Returns
    -------
    tuple of TipEdgeGaps
        Pinion tip, gear tip (the order of :data:`TIP_EDGES`).
    """
    lo, hi = cycle.line_ends_zu_mm[..., 0, 0], cycle.line_ends_zu_mm[..., 1, 0]
    z = np.asarray(z_mm, float)
    z = z if z.ndim == 3 else z.ravel()
    live = np.isfinite(lo)
    shape = lo.shape + (z.shape[-1],)
    pitch = 2.0 * math.pi / cycle.pinion_teeth
    phi = cycle.phi1_rad[None, :] + pitch * np.asarray(cycle.pair_offsets, float)[:, None]
    phis = np.broadcast_to(phi[..., None], shape)
    zs = np.broadcast_to(z, shape)
    u1 = mesh.pinion_u_affine(phis, zs)
    with np.errstate(invalid="ignore"):
        off = live[..., None] & ((zs < lo[..., None]) | (zs > hi[..., None]))
    # sections beyond a tip end, within the reach of the tip-edge solve (the separation
    # grows as s^2 / (2 rho): hundreds of um there)
    reach = REACH_BASE_PITCHES * 2.0 * math.pi * mesh.pinion.base_radius_mm / cycle.pinion_teeth
    s1, s2 = u1 - mesh.pinion.u_range[1], mesh.roll_sum - u1 - mesh.gear.u_range[1]
    beyond = (off & (s1 > 0.0) & (s1 <= reach), off & (s2 > 0.0) & (s2 <= reach))
    out = []
    for edge, sel in zip(TIP_EDGES, beyond):
        gaps = np.full(shape, np.nan)
        per = {k: np.full(lo.shape, np.nan)
               for k in ("lever", "slope", "inv_r", "rate", "u1", "u2")}
        if sel.any():
            ph, zz = phis[sel], zs[sel]
            y, ok = _touch(mesh, edge.member, ph, zz, _start(mesh, edge.member, zz))
            f = _touch_fields(mesh, edge.member, ph, zz, y, ok)
            gaps[sel] = f["gap"]
            first = np.isfinite(gaps).any(axis=-1)
            best = np.argmin(np.where(np.isfinite(gaps), gaps, np.inf), axis=-1)
            # the flat index of each pair-phase's first touch among the solved points
            flat = np.full(shape, -1)
            flat[sel] = np.arange(int(sel.sum()))
            i = flat[first, best[first]] if first.any() else np.zeros(0, int)
            if i.size:
                own_u = f["tip_u"]
                got = _touch_geometry(mesh, edge.member, ph[i], zz[i], y[i, 0], y[i, 2],
                                      f["point"][i], f["normal"][i])
                for key, val in zip(("lever", "slope", "inv_r"), got):
                    per[key][first] = val
                per["rate"][first] = f["rate"][i]
                pin, gear = (own_u, y[i, 0]) if edge.member == "pinion" else (y[i, 0], own_u)
                per["u1"][first], per["u2"][first] = pin, gear
        out.append(_edge_gaps(z, gaps, per))
    return tuple(out)
