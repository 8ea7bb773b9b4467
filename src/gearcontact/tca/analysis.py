"""The complete unloaded analysis of one flank pair: mesh cycle, phase table, gap field,
hardware stencil and pattern check, as one call (what ``gearcontact tca`` runs).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from tqdm import tqdm

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from .line_contact import LineContact, found_line_contact, is_conjugate, line_contact
from .edge_contact import pushes_forward, solve_edge_contact
from .edges import PatternOffFlank, exit_counts, pattern_edges
from .curvature import (ContactEllipse, RelativeCurvature, contact_ellipse,
                        relative_curvature)
from .mesh import MeshCycle, mesh_cycle
from .phase_table import PhaseTable, phase_table
from .mating import solve_mating_point
from .types import ContactGuess, EdgeContact, MatingPoint, TcaConvergenceError
from .stencil import GapField, gap_at, gap_field_80, hardware_stencil

__all__ = ["TcaAnalysis", "analyze", "analyze_pair", "pattern_on_flank", "reference_start"]


@dataclass(frozen=True)
class TcaAnalysis:
    """Everything the TCA stage hands downstream.

    Attributes
    ----------
    cycle : MeshCycle
        Mesh cycle with neighbouring pairs (TE0 envelope, transmitting contacts).
    table : PhaseTable
        Per-phase table over one pitch.
    mean_point : MatingPoint
        The reference mating point P0 (TE0 = 0 there).
    mean_curvature : RelativeCurvature
    mean_ellipse : ContactEllipse
        Paint ellipse at P0.
    gap_field : GapField
        80 x 80 host gap field around P0 (principal frame).
    stencil : GapField
        49-sample hardware stencil around P0 (flank frame, baked spacing).
    pattern_on_flank : ndarray (K,) of bool
        Per phase of the pitch: the paint ellipse of the transmitting contact lies
        inside both flanks (its outline maps into the parameter boxes).
    edges : tuple of str
        Per phase of the pitch: ``""`` or the flank edge the transmitting contact or
        its pattern reaches (``"pinion toe"``, ``"gear tip"``, ...;
        :func:`~gearcontact.tca.edges.pattern_edges`).
    timings_s : dict
        Wall-clock seconds per stage.
    """

    cycle: MeshCycle
    table: PhaseTable
    mean_point: MatingPoint
    mean_curvature: RelativeCurvature
    mean_ellipse: ContactEllipse
    gap_field: GapField
    stencil: GapField
    pattern_on_flank: np.ndarray
    edges: tuple
    timings_s: dict

    @property
    def edge_contact_counts(self) -> dict:
        """Phases of the pitch whose transmitting contact is an edge touching the other
        flank (:mod:`gearcontact.tca.edge_contact`), per edge."""
        counts: dict = {}
        for mp in self.cycle.contact:
            if mp.edge_contact:
                counts[mp.edge_contact] = counts.get(mp.edge_contact, 0) + 1
        return counts

    @property
    def edge_counts(self) -> dict:
        """Phases of the pitch per flank edge reached (empty: pattern inside)."""
        counts: dict = {}
        for e in self.edges:
            if e:
                counts[e] = counts.get(e, 0) + 1
        return counts


def pattern_on_flank(pinion: Surface, gear: Surface, kin: MeshKinematics,
                     cycle: MeshCycle, *, outline_points: int = 16) -> np.ndarray:
    """Per phase: does the paint ellipse of the transmitting contact lie on both flanks?

    ``outline_points`` points of the ellipse outline (in the principal frame, vertices
    included) are projected along the common normal onto both flanks; the phase passes
    if all of them land inside both parameter boxes.
    """
    theta = 2.0 * np.pi * np.arange(int(outline_points)) / int(outline_points)
    ok = np.zeros(len(cycle.contact), dtype=bool)
    for k, (mp, ell) in enumerate(zip(cycle.contact, cycle.ellipse)):
        if mp.edge_contact or not np.isfinite(ell.semi_major_mm):
            continue        # an edge contact's pattern reaches its edge
        field = gap_at(pinion, gear, kin, mp, ell.semi_major_mm * np.cos(theta),
                       ell.semi_minor_mm * np.sin(theta), frame="principal")
        ok[k] = bool(field.on_flank.all())
    return ok


def analyze(pinion: Surface, gear: Surface, kin: MeshKinematics, *, pinion_teeth: int,
            start: ContactGuess, start_fixed: str = "phi1", phases: int = 61,
            pairs: int = 3, stencil_off_flank: str = "quadric",
            edge_contact: bool = True, progress: bool = False) -> TcaAnalysis:
    """Run the whole unloaded analysis.

    Parameters
    ----------
    pinion, gear : Surface
        One flank of each member (same side).
    kin : MeshKinematics
        Kinematics with assembly errors.
    pinion_teeth : int
        z1.
    start, start_fixed
        Reference mating point guess (see :func:`~gearcontact.tca.solve.solve_tca`).
    phases : int
        Phases per pinion pitch including both ends (>= 61 for reports).
    pairs : int
        Neighbouring pairs either side.
    stencil_off_flank : str
        Fill of a 7 x 7 stencil (fixed +-0.6 mm window) that reaches beyond a flank
        boundary (:func:`~gearcontact.tca.stencil.hardware_stencil`; ``"quadric"``:
        the osculating quadric at every sample); the samples beyond it are recorded in
        ``stencil.on_flank``. The 80 x 80 field never
        extrapolates (NaN, ``on_flank`` False).
    edge_contact : bool
        Edge-to-surface contact where the surface contact leaves a flank (default), or
        surface contact only (:func:`~gearcontact.tca.mesh.mesh_cycle`).
    progress : bool
        Show progress bars.

    Raises
    ------
    LineContact
        Line contact at the reference point (B- within
        :func:`~.line_contact.found_line_contact`'s tolerance): the contact line is
        followed and reported (its TE0 along the pitch) instead of an ellipse.
    """
    timings = {}
    stages = tqdm(total=4, desc="TCA stages", disable=not progress, leave=False)
    t0 = time.perf_counter()
    cycle = mesh_cycle(pinion, gear, kin, pinion_teeth=pinion_teeth, start=start,
                       start_fixed=start_fixed, phases=phases, pairs=pairs,
                       edge_contact=edge_contact, progress=progress)
    timings["mesh_cycle"] = time.perf_counter() - t0
    stages.update(1)
    table = phase_table(cycle)
    mean = cycle.reference_point
    t0 = time.perf_counter()
    rc = relative_curvature(pinion, gear, kin, mean)
    if found_line_contact(rc.B_minus_per_mm):
        stages.close()      # conjugate flanks (e.g. cut uncrowned): the line, reported
        # the line through the reference point, else through the cycle's start
        raise LineContact(line_contact(pinion, gear, kin, mean.as_guess(), also=(start,),
                                       pinion_teeth=pinion_teeth, phases=phases),
                          found=rc.B_minus_per_mm)
    ell = contact_ellipse(rc)
    field = gap_field_80(pinion, gear, kin, mean)
    timings["gap_field_80"] = time.perf_counter() - t0
    stages.update(1)
    t0 = time.perf_counter()
    stencil = hardware_stencil(pinion, gear, kin, mean, off_flank=stencil_off_flank)
    timings["stencil"] = time.perf_counter() - t0
    stages.update(1)
    t0 = time.perf_counter()
    inside = pattern_on_flank(pinion, gear, kin, cycle)
    edges = pattern_edges(pinion, gear, kin, cycle, inside)
    timings["pattern_check"] = time.perf_counter() - t0
    stages.update(1)
    stages.close()
    return TcaAnalysis(cycle, table, mean, rc, ell, field, stencil, inside, edges, timings)


def analyze_pair(pair, *, side: str | None = None, phases: int = 61, pairs: int = 3,
                 flanks=None, edge_contact: bool = True,
                 progress: bool = False) -> tuple[TcaAnalysis, object]:
    """Build the flanks of a :class:`~gearcontact.geometry.pair.GearPair` and analyze
    one side (default the pair's ``design_side``) with the pair's assembly errors.

    The reference point is the mating point at ``phi1_0 = u phi2_0`` of the conjugate
    mean contact reported by :func:`~gearcontact.geometry.flank.build_flanks`.
    ``edge_contact`` (default True) continues the paths through edge-to-surface
    contact (:mod:`gearcontact.tca.edge_contact`); False: surface contact only.
    ``flanks``: the pair's flanks if already built (a prepared pair's,
    :meth:`~gearcontact.tca.synthesis.PreparedPair.flank_set`); without them they are
    built here, after the pair's typed machine settings are checked against its blank
    (:func:`~gearcontact.geometry.settings_check.checked_settings`: a gross slip raises
    naming its key, any other disagreement is a ``SettingsWarning``).

    Returns
    -------
    (TcaAnalysis, FlankSet)

    Raises
    ------
    InputRangeError
        Typed machine settings that do not cut the blank's tooth (a gross slip; flanks
        not given).
    LineContact
        Zero ease-off and no assembly errors: the flanks are conjugate (line contact,
        TE0 = 0); the exception carries the :class:`~.line_contact.LineContactResult`.
        Also when the TCA finds line contact (``found``: B- at the mean point within
        :func:`~.line_contact.found_line_contact`'s tolerance; e.g. an uncrowned pinion
        cut by the gear's complementary generating surface).
    PatternOffFlank
        The contact has left the flanks at every phase tried.
    """
    from ..geometry.flank import build_flanks
    from ..geometry.formate import SIDES
    from ..geometry.settings_check import checked_settings

    if side is None:
        side = pair.design_side
    if side not in SIDES:
        raise ValueError(f"side = {side!r} is not one of {SIDES}")
    if flanks is None:      # built here: the pair's typed settings checked first
        checked_settings(pair, stacklevel=2)
        flanks = build_flanks(pair)
    kin = pair.kinematics()
    if is_conjugate(pair, side):
        mean = flanks.mean_contact[side]
        phi2 = float(mean["phi2_rad"])
        start = ContactGuess(*map(float, mean["pinion_uv"]), *map(float, mean["gear_uv"]),
                             pair.ratio * phi2, phi2)
        raise LineContact(line_contact(flanks.flank("pinion", side), flanks.flank("gear", side),
                                       kin, start, pinion_teeth=pair.pinion_teeth,
                                       phases=phases), side=side)
    start, fixed = reference_start(pair, flanks, side, edge_contact=edge_contact)
    try:
        result = analyze(flanks.flank("pinion", side), flanks.flank("gear", side), kin,
                         pinion_teeth=pair.pinion_teeth, start=start, start_fixed=fixed,
                         phases=phases, pairs=pairs, edge_contact=edge_contact,
                         progress=progress)
    except LineContact as line:     # found by the TCA: named with its side
        raise LineContact(line.result, side=side, found=line.found) from None
    return result, flanks


def _contact_of(conj, gear, pair, u1: float, v1: float, mean: dict) -> ContactGuess:
    """The contact state of the pinion point (u1, v1) with the gear: exact for today's
    conjugate pinion (:func:`~.design_point.conjugate_contact`); for flanks cut from
    machine settings (no conjugate reference) the nearest touch
    (:func:`~gearcontact.geometry.generated.mean_contact_guess`)."""
    from ..geometry.generated import mean_contact_guess
    from .design_point import conjugate_contact

    if hasattr(conj, "exact"):
        return conjugate_contact(conj, gear, pair, u1, v1)
    got = mean_contact_guess(conj, gear, pair.kinematics(with_errors=False),
                             pinion_uv=(u1, v1), gear_uv=mean["gear_uv"])
    return ContactGuess(u1, v1, *map(float, got["gear_uv"]), float(got["phi1_rad"]),
                        float(got["phi2_rad"]))


def reference_start(pair, flanks, side: str, *,
                    edge_contact: bool = True) -> tuple[ContactGuess, str]:
    """A contact state from which the mesh cycle of ``side`` can start, and the variable
    its first solve holds.

    First the conjugate contact at the pinion's mean node (``phi1`` held); if the eased
    contact at that phase lies beyond the flank (a bearing placed far from the mean
    node, e.g. at the tip edge), the conjugate contacts of pinion points around the
    least-relief point of the ease-off are tried with their height ``u1`` held (the
    phase free), since the eased path need not cross a given conjugate contact line.

    If neither yields an interior mating point, a 7 x 7 grid over the whole pinion
    flank is tried the same way (a misaligned pair's bearing can be anywhere on it).

    Raises
    ------
    PatternOffFlank
        If no candidate yields an interior mating point (the bearing has left the
        flank at every phase tried); it names the edge most trial contacts left by.
    """
    from ..geometry.easeoff import EaseOff

    mean = flanks.mean_contact[side]
    kin = pair.kinematics()
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    conj = flanks.pinion_conjugate.side(side)
    phi2 = float(mean["phi2_rad"])
    first = ContactGuess(*map(float, mean["pinion_uv"]), *map(float, mean["gear_uv"]),
                         pair.ratio * phi2, phi2)
    try:
        solve_mating_point(pinion, gear, kin, first, fixed="phi1")
        return first, "phi1"
    except (EdgeContact, TcaConvergenceError) as exc:
        error = exc
    b = conj.boundary
    eo = EaseOff.from_coefficients(getattr(pair, f"easeoff_{side}"),
                                   u_mean_mm=mean["pinion_uv"][0], v_mean_mm=mean["pinion_uv"][1])
    U, V = np.meshgrid(np.linspace(b.u_root, b.u_tip, 25), np.linspace(b.v_toe, b.v_heel, 25),
                       indexing="ij")
    k = np.unravel_index(int(np.argmin(eo.relief_mm(U, V))), U.shape)
    du, dv = 0.1 * (b.u_tip - b.u_root), 0.1 * (b.v_heel - b.v_toe)
    near = [(float(np.clip(U[k] + fu * du, b.u_root + 0.5 * du, b.u_tip - 0.5 * du)),
             float(np.clip(V[k] + fv * dv, b.v_toe + 0.5 * dv, b.v_heel - 0.5 * dv)))
            for fu, fv in ((0, 0), (-1, 0), (-2, 0), (-1, -1), (-1, 1), (-3, 0), (-2, -2),
                           (-2, 2))]
    # then the whole flank, nearest the least-relief point first: a misaligned pair
    # (assembly errors) moves its bearing anywhere on the flank, up to an edge
    grid = [(float(u), float(v)) for u in np.linspace(b.u_root + 0.5 * du, b.u_tip - 0.5 * du, 7)
            for v in np.linspace(b.v_toe + 0.5 * dv, b.v_heel - 0.5 * dv, 7)]
    grid.sort(key=lambda uv: ((uv[0] - U[k]) / du) ** 2 + ((uv[1] - V[k]) / dv) ** 2)
    exits = [error.where if isinstance(error, EdgeContact) else "no convergence"]
    tried = [first]
    # a candidate clipped onto one already tried (the near points at the flank's border)
    # fails as it did: its exit is counted again, not solved again
    failed: dict = {}
    for u1, v1 in near + grid:
        if (u1, v1) in failed:
            guess, where = failed[(u1, v1)]
            tried.append(guess)
            exits.append(where)
            continue
        guess = _contact_of(conj, gear, pair, u1, v1, mean)
        tried.append(guess)
        try:
            solve_mating_point(pinion, gear, kin, guess, fixed="u1")
            return guess, "u1"
        except EdgeContact as exc:
            exits.append(exc.where)
        except TcaConvergenceError:
            exits.append("no convergence")
        failed[(u1, v1)] = (guess, exits[-1])
    # no surface contact anywhere: an edge of one flank touching the other (the bearing
    # lies beyond the edge at every phase, e.g. a large offset error); a repeated
    # candidate finds no edge either
    for guess in dict.fromkeys(tried[:1 + len(near)]) if edge_contact else ():
        mp = solve_edge_contact(pinion, gear, kin, guess.phi1_rad, guess=guess,
                                forward=pushes_forward(gear, kin, guess))
        if mp is not None:
            return mp.as_guess(), "phi1"
    raise PatternOffFlank(exit_counts(exits), context=f" on the {side} side")
