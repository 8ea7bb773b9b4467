"""Edge contact as a result: which flank edge a contact or its pattern reaches.

Misalignment, a short face or a strong ease-off move the contact towards a flank
boundary. Mounting checks are run precisely to see that (Stadtfeld 1993, ch. 6: the
V/H check moves the pattern to toe/heel and tip/root), so an edge is reported, never
fatal: per phase of the pitch the transmitting contact is either interior with its
paint ellipse inside both flanks (``""``), or its pattern or its mating point reaches an
edge, named ``"<member> <edge>"`` with ``member`` pinion or gear and ``edge`` one of
toe / heel / tip / root (:class:`~gearcontact.geometry.formate.FlankBoundary`: ``u`` runs
root -> tip, ``v`` toe -> heel on both members).

Only a contact that has left the flanks at every phase tried is an error,
:class:`PatternOffFlank`, which names the way it left.

References
----------
H. J. Stadtfeld, *Handbook of Bevel and Hypoid Gears*, RIT, 1993, ch. 6 (contact
pattern movement with the V, H, J mounting errors).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from ..validation import UnusableInput
from .stencil import tangent_frame, tangent_parameters

__all__ = ["EDGES", "edge_name", "solver_boundary", "exit_counts", "PatternOffFlank",
           "ContactGap", "pattern_edges",
           "PatchEdges", "loaded_patch_edges"]

#: Edge name of each parameter-box side (``u`` root -> tip, ``v`` toe -> heel).
EDGES = {"u min": "root", "u max": "tip", "v min": "toe", "v max": "heel"}


def solver_boundary(label: str) -> str:
    """The solver boundary (``"pinion v min"``) of an edge label (``"pinion toe"``);
    the inverse of :func:`edge_name`."""
    member, _, edge = label.partition(" ")
    sides = {name: side for side, name in EDGES.items()}
    return f"{member} {sides[edge]}" if edge in sides else label


def edge_name(where: str) -> str:
    """``"<member> <edge>"`` for a solver boundary such as ``"pinion v max"``."""
    member, _, side = where.partition(" ")
    return f"{member} {EDGES.get(side, side)}" if side in EDGES else where


class PatternOffFlank(UnusableInput):
    """The contact has left the flanks at every phase tried.

    Attributes
    ----------
    where : str
        The edge the contact crossed most often (``"gear root"``, ``"pinion toe"``, ...;
        ``"unknown edge"`` if no trial reached an edge, e.g. none converged).
    counts : dict
        How many of the trial contacts left by each edge (or did not converge).
    """

    def __init__(self, counts: dict, *, context: str = ""):
        self.counts = dict(counts)
        named = {k: v for k, v in self.counts.items()
                 if k.split(" ")[-1] in EDGES.values()}
        self.where = max(named, key=named.get) if named else "unknown edge"
        tried = sum(self.counts.values())
        detail = ", ".join(f"{k} {v}" for k, v in sorted(self.counts.items(),
                                                         key=lambda kv: -kv[1]))
        super().__init__(
            f"contact pattern off the flank: no interior mating point at any of the "
            f"{tried} start contacts tried{context}; the contact leaves towards the "
            f"{self.where} (exits: {detail}). Reduce the assembly errors or the ease-off.")


class ContactGap(UnusableInput):
    """At some phase of the pitch no tooth pair has an interior mating point: the
    contact paths are shorter than one pinion pitch (contact ratio below one), e.g. a
    short face or a strong misalignment.

    Attributes
    ----------
    phi1_rad : float
        First phase without a contact, rad.
    gap_phases : int or None
        Phases of the pitch without a contact, of ``phases_per_pitch`` (None: not
        counted).
    phases_per_pitch : int or None
        Phase steps per pitch of the run that found the gap.
    """

    def __init__(self, phi1_rad: float, *, gap_phases: int | None = None,
                 phases_per_pitch: int | None = None):
        self.phi1_rad = float(phi1_rad)
        self.gap_phases = None if gap_phases is None else int(gap_phases)
        self.phases_per_pitch = None if phases_per_pitch is None else int(phases_per_pitch)
        super().__init__(f"no tooth pair in contact at phi1 = {np.degrees(phi1_rad):.4f} deg: "
                         "the contact path is shorter than one pinion pitch (contact ratio "
                         "< 1); the unloaded mesh has a gap there")


def _edge_of(surface: Surface, u: float, v: float) -> tuple[str, float]:
    """Edge of the box nearest (or beyond) ``(u, v)`` and its signed margin, mm
    (negative: outside)."""
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    margins = {"root": u - u0, "tip": u1 - u, "toe": v - v0, "heel": v1 - v}
    name = min(margins, key=margins.get)
    return name, float(margins[name])


def pattern_edges(pinion: Surface, gear: Surface, kin: MeshKinematics, cycle,
                  on_flank: np.ndarray, *, outline_points: int = 16) -> tuple[str, ...]:
    """Per phase of ``cycle``: the edge the transmitting contact reaches, or ``""``.

    A phase without contact reports its solver boundary; an edge-to-surface contact
    (:mod:`gearcontact.tca.edge_contact`) reports its edge.
    A phase whose paint ellipse is not on both flanks (``on_flank`` False, from the
    exact normal-line projection of :func:`~gearcontact.tca.analysis.pattern_on_flank`)
    reports the edge that the ellipse outline crosses furthest, located by mapping the
    outline into each flank's parameters to first order (``[r_u r_v] d(u, v) = q``,
    least squares in the tangent plane).
    """
    theta = 2.0 * np.pi * np.arange(int(outline_points)) / int(outline_points)
    out = []
    for k, (mp, rc, ell) in enumerate(zip(cycle.contact, cycle.curvature, cycle.ellipse)):
        if mp.edge:
            out.append(edge_name(mp.edge_where))
            continue
        if mp.edge_contact:     # an edge touching the other flank
            out.append(mp.edge_contact)
            continue
        if on_flank[k]:
            out.append("")
            continue
        major = ell.semi_major_mm if np.isfinite(ell.semi_major_mm) else 1e3
        ring = (np.outer(major * np.cos(theta), rc.dir_min)
                + np.outer(ell.semi_minor_mm * np.sin(theta), rc.dir_max))
        worst = ("", np.inf)
        for member, surf, (u, v), rot in (
                ("pinion", pinion, (mp.u1, mp.v1), kin.pinion_pose(mp.phi1_rad)[0]),
                ("gear", gear, (mp.u2, mp.v2), kin.gear_pose(mp.phi2_rad)[0])):
            sp = surf.point(u, v)
            jac = rot @ np.column_stack([sp.r_u, sp.r_v])
            duv = np.linalg.lstsq(jac, ring.T, rcond=None)[0]
            for du, dv in duv.T:
                name, margin = _edge_of(surf, u + du, v + dv)
                if margin < worst[1]:
                    worst = (f"{member} {name}", margin)
        out.append(worst[0])
    return tuple(out)


def exit_counts(wheres) -> dict:
    """Counts of the named edges of solver boundaries (for :class:`PatternOffFlank`)."""
    return dict(Counter(edge_name(w) for w in wheres))


@dataclass(frozen=True)
class PatchEdges:
    """Where a loaded contact patch meets the flank boundary (the meaning of the LTCA's
    ``edge_contact`` flag: a loaded cell borders a cell beyond a flank).

    Attributes
    ----------
    edges : tuple of str
        Flank edges the loaded patch reaches (``"pinion tip"``, ...), most cells first;
        empty if the patch lies inside both flanks.
    boundary_cells : int
        Loaded cells next to an off-flank cell.
    boundary_pressure_ratio : float
        Largest pressure on those cells over the patch's p90 (0 if none): about 1 or
        more is load carried at the edge (an edge spike above ~2); well below 1 the
        patch only grazes the edge with its low-pressure rim.
    """

    edges: tuple
    boundary_cells: int
    boundary_pressure_ratio: float

    def as_dict(self) -> dict:
        return {"edge_contact_edges": list(self.edges),
                "edge_contact_cells": self.boundary_cells,
                "edge_pressure_ratio_p90": self.boundary_pressure_ratio}


def loaded_patch_edges(pinion: Surface, gear: Surface, kin: MeshKinematics, mp, case, *,
                       frame: str = "principal") -> PatchEdges:
    """The flank edges a loaded patch reaches.

    ``case`` is a :class:`~gearcontact.ltca.pair_ltca.PairLoadCase` solved at the
    mating point ``mp`` (its grid lies in the ``frame`` tangent plane there, its
    ``on_flank`` mask marks the
    cells whose normal line meets both flanks). The off-flank cells next to loaded
    cells are mapped into each flank's parameters to first order
    (:func:`~gearcontact.tca.stencil.tangent_parameters`) and named by the box side
    they lie beyond.
    """

    patch = case.patch
    off = ~np.asarray(case.on_flank, bool)
    loaded = patch.lcp.contact_mask
    near_off = np.zeros_like(off)
    near_loaded = np.zeros_like(off)
    for a, b in ((slice(1, None), slice(None, -1)), (slice(None, -1), slice(1, None))):
        near_off[a, :] |= off[b, :]
        near_off[:, a] |= off[:, b]
        near_loaded[a, :] |= loaded[b, :]
        near_loaded[:, a] |= loaded[:, b]
    boundary = loaded & near_off
    if not boundary.any():
        return PatchEdges((), 0, 0.0)
    axes = tangent_frame(pinion, gear, kin, mp, frame)
    s, t = np.meshgrid(patch.grid.x_mm, patch.grid.y_mm)
    cells = off & near_loaded
    st = np.column_stack([s[cells], t[cells]])
    names: Counter = Counter()
    for member, surf, pose, uv in (
            ("pinion", pinion, kin.pinion_pose(mp.phi1_rad), (mp.u1, mp.v1)),
            ("gear", gear, kin.gear_pose(mp.phi2_rad), (mp.u2, mp.v2))):
        for u, v in tangent_parameters(surf, pose, axes, uv, st):
            name, margin = _edge_of(surf, u, v)
            if margin < 0.0:
                names[f"{member} {name}"] += 1
    ratio = float(patch.pressure_mpa[boundary].max() / patch.p90_mpa)
    return PatchEdges(tuple(n for n, _ in names.most_common()), int(boundary.sum()), ratio)

