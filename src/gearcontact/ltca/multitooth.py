"""Multi-tooth loaded contact at the reference phase P0, rigid and with tooth bending.

The coupled multi-pair LCP of the loaded TE (:mod:`.lte`, :mod:`.mesh_lcp`) solved at
the one phase of the mesh cycle nearest the reference mating point
(``cycle.mean_index``), twice: with rigid teeth (Love half-space only) and with the
shell bending compliance of both teeth of every pair (:mod:`.tooth_bending`). Both
solves use the same pairs, posed fields and solver as :func:`.lte.loaded_te` at that
phase (so the rigid rotation equals the LTE's ``rotation_lcp_arcsec`` at P0).

Reported per engaged pair (reference pair first): total normal load and share of the
gear torque's normal loads, pressure map, and the incomplete-ellipse line-contact peak
(:mod:`..halfspace.line_peak`); overall: the loaded mesh rotation rigid and with bending,
the preview's (``TE_pre``'s law at P0, :func:`.edge_rows.preview_edge_balance`: Hertz
per pair with the edge law's LCP-calibrated scale where a flank boundary cuts a pair's
patch, the one function the loaded TE's preview and the twin's table take; its rotation
also starts the LCPs, as in :func:`.lte.loaded_te`),
``CP_max`` (largest line-contact peak over the engaged pairs, bending solution) beside
the raw cell peak and the Hamrock–Brewe preview of the reference pair at the load the
LCP gives it (``preview_p_max_mpa``; docs/spec.md sec. 5: *paper* 2714 MPa vs 2038 MPa).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 9.
M. Kolivand, A. Kahraman, Mech. Mach. Theory 44 (2009) 1848-1865 (loaded tooth contact
of hypoid gears with tooth bending). docs/spec.md sec. 5.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..materials import effective_modulus_mpa
from ..preview.engine import ReferenceEngine
from ..validation import InputRangeError, check_positive, check_range
from ..halfspace.grid import TangentGrid
from ..halfspace.line_peak import LinePeak, contact_line_length_mm, line_contact_peak, trimmed_gap
from ..halfspace.result import ContactResult, SolveStatus
from .edge_rows import preview_edge_balance
from .tooth_bending import pair_bending_compliance
from .lte_phase import ACTIVE_SHARE, check_loaded, solve_phase
from .lte_pairs import PairFields, phase_contacts
from .mesh_lcp import solve_mesh_lcp
from .pair_ltca import ARCSEC_PER_RAD, OFF_FLANK_GAP_MM

__all__ = ["EngagedPair", "MultiToothCase", "PreviewPair", "multi_tooth_ltca"]


@dataclass(frozen=True)
class PreviewPair:
    """One pair of the multi-tooth step's preview (TE_pre's law at P0).

    Attributes
    ----------
    offset : int
        Pair index ``j``.
    lever_mm, opening_mm : float
        Lever about the gear axis and opening ``g`` of the pair's (posed) field, mm.
    load_n : float
        Preview load ``W``, N.
    scale : float
        Compliance scale ``c`` of the edge law at ``W`` (1: untruncated Hertz).
    kappa_mm_per_n23 : float
        The scaled approach coefficient: ``l theta_pre - g = kappa W^(2/3)`` where loaded,
        mm/N^(2/3).
    """

    offset: int
    lever_mm: float
    opening_mm: float
    load_n: float
    scale: float
    kappa_mm_per_n23: float


@dataclass(frozen=True, eq=False)
class EngagedPair:
    """One tooth pair of the multi-tooth solution.

    Attributes
    ----------
    offset : int
        Pair index ``j`` of the mesh cycle (0: the transmitting pair at P0).
    lever_mm : float
        Lever of the pair's normal force about the gear axis, mm.
    opening_arcsec : float
        Unloaded opening ``|TE0_j - TE0_env|``, arcsec of gear rotation.
    edge : bool
        The pair's unloaded mating point lies beyond its flanks (edge contact).
    load_n, load_rigid_n : float
        Normal load with bending and with rigid teeth, N.
    loads_n : ndarray (ny, nx)
        Nodal loads with bending, N.
    grid : TangentGrid
        The pair's principal-frame field.
    off_flank : ndarray (ny, nx) of bool
        Cells beyond a flank boundary.
    origin_mm, frame : ndarray (3,), ndarray (3, 3)
        Field origin and axes (columns ``e_s, e_t, n``) in the meshing frame (gear axis
        = z), mm.
    peak : LinePeak
        Line-contact peak of the bending solution.
    load_resolved_n : float
        Normal load of the bending solution re-solved without the flanks' boundary
        rows (:func:`..halfspace.line_peak.trimmed_gap`), N (= ``load_n`` when not re-solved).
    peak_resolved : LinePeak
        Line-contact peak of the re-solved solution (= ``peak`` when not re-solved).
    """

    offset: int
    lever_mm: float
    opening_arcsec: float
    edge: bool
    load_n: float
    load_rigid_n: float
    loads_n: np.ndarray
    grid: TangentGrid
    off_flank: np.ndarray
    origin_mm: np.ndarray
    frame: np.ndarray
    peak: LinePeak
    load_resolved_n: float
    peak_resolved: LinePeak

    @property
    def pressure_mpa(self) -> np.ndarray:
        """Pressure map with bending, MPa."""
        return self.loads_n / self.grid.cell_area_mm2

    def cell_points_mm(self) -> np.ndarray:
        """Cell centres in the meshing frame (ny, nx, 3), mm."""
        s, t = self.grid.mesh()
        return self.origin_mm + s[..., None] * self.frame[:, 0] + t[..., None] * self.frame[:, 1]


@dataclass(frozen=True, eq=False)
class MultiToothCase:
    """Multi-tooth LTCA at P0 (module docstring).

    Attributes
    ----------
    torque_nm : float
        Gear torque, N·m.
    side : str
        Flank pair.
    phase_index : int
        Phase of the mesh cycle (``cycle.mean_index``).
    pairs : tuple of EngagedPair
        Pairs loaded in either solution (> ``ACTIVE_SHARE`` of the load), the
        transmitting pair first, then by distance from it (the later pair first).
    rotation_rigid_arcsec, rotation_arcsec : float
        Loaded gear rotation ``theta`` rigid and with bending, arcsec (equal without
        bending).
    preview_p_max_mpa : float
        Preview p_max of the reference pair at its LCP load with bending, MPa: the
        Hamrock–Brewe ellipse or, when the flank truncates it, the Hertz line contact of
        the contact line's length (fp64 line-core rule,
        :func:`gearcontact.preview.hertz.reference.truncated_preview`).
    preview_mode : str
        Which of the two answered (``"elliptic"`` | ``"line"``).
    rotation_pre_arcsec : float
        Loaded rotation of the preview (:func:`.edge_rows.preview_edge_balance`: Hertz
        per pair, the edge law's LCP-calibrated scale where a flank boundary cuts the
        pair's patch, with ``bending`` each pair's teeth's bending in series; TE_pre's
        and the twin's law), arcsec; it also starts the LCPs.
    preview_pairs : tuple of PreviewPair
        The preview's pairs (load, scale, scaled approach coefficient).
    line_length_mm : float or None
        Length of the reference pair's contact line on the flank through its contact
        point (:func:`..halfspace.line_peak.contact_line_length_mm`), mm; None: no on-flank cell
        on the field's centre row (plain ellipse).
    bending : bool
        The second solve had tooth bending (False: both solves are rigid).
    status, status_rigid : SolveStatus
        LCP status of the two solves.
    solve_ms, solve_rigid_ms : float
        LCP solve times, ms (run.json only).
    edge_contact : bool
        A loaded cell borders a flank boundary (bending solution).
    rotation_resolved_arcsec : float
        Rotation of the bending solution re-solved without the boundary-inadmissible
        cells, arcsec (= ``rotation_arcsec`` when no boundary cell carried load).
    resolved : bool
        The bending solution loaded a flank's boundary row and was re-solved.
    status_resolved : SolveStatus
        LCP status of the re-solve (that of the bending solve when not re-solved).
    """

    torque_nm: float
    side: str
    phase_index: int
    pairs: tuple
    rotation_rigid_arcsec: float
    rotation_arcsec: float
    preview_p_max_mpa: float
    bending: bool
    status: SolveStatus
    status_rigid: SolveStatus
    solve_ms: float
    solve_rigid_ms: float
    edge_contact: bool
    rotation_resolved_arcsec: float
    resolved: bool
    status_resolved: SolveStatus
    preview_mode: str = "elliptic"
    line_length_mm: float | None = None
    rotation_pre_arcsec: float = float("nan")
    preview_pairs: tuple = ()

    @property
    def converged(self) -> bool:
        """Both LCP solves converged."""
        return (self.status is SolveStatus.CONVERGED
                and self.status_rigid is SolveStatus.CONVERGED
                and self.status_resolved is SolveStatus.CONVERGED)

    def _shares(self, attr: str) -> list[float]:
        w = np.array([getattr(p, attr) for p in self.pairs])
        return [float(v) for v in 100.0 * w / w.sum()]

    @property
    def load_share_pct(self) -> list[float]:
        """Load shares with bending, %, in the order of ``pairs``."""
        return self._shares("load_n")

    @property
    def load_share_rigid_pct(self) -> list[float]:
        """Load shares with rigid teeth, %, in the order of ``pairs``."""
        return self._shares("load_rigid_n")

    @property
    def cp_max_mpa(self) -> float:
        """Largest line-contact peak ``CP_max`` over the pairs (bending), MPa."""
        return max(p.peak.cp_max_mpa for p in self.pairs)

    @property
    def p_peak_cell_mpa(self) -> float:
        """Largest raw cell pressure over the pairs (bending), MPa."""
        return max(p.peak.p_peak_cell_mpa for p in self.pairs)

    def summary(self) -> dict:
        """Plain-JSON scalars (``multitooth.json``; no timings)."""
        total = sum(p.load_n for p in self.pairs)
        return {
            "torque_nm": self.torque_nm, "side": self.side, "phase_index": self.phase_index,
            "bending": self.bending,
            "pair_offsets": [p.offset for p in self.pairs],
            "load_share_pct": self.load_share_pct,
            "load_share_rigid_pct": self.load_share_rigid_pct,
            "pair_loads_n": [p.load_n for p in self.pairs],
            "pair_loads_rigid_n": [p.load_rigid_n for p in self.pairs],
            "n_engaged": sum(p.load_n > ACTIVE_SHARE * total for p in self.pairs),
            "n_engaged_rigid": sum(p.load_rigid_n > 0.0 for p in self.pairs),
            "mesh_rotation_rigid_arcsec": self.rotation_rigid_arcsec,
            "mesh_rotation_arcsec": self.rotation_arcsec,
            "mesh_rotation_increase_pct": 100.0 * (self.rotation_arcsec
                                                   / self.rotation_rigid_arcsec - 1.0),
            "cp_max_mpa": self.cp_max_mpa,
            "cp_max_pair": self.pairs[int(np.argmax([p.peak.cp_max_mpa
                                                     for p in self.pairs]))].offset,
            "pair_cp_max_mpa": [p.peak.cp_max_mpa for p in self.pairs],
            "p_peak_cell_mpa": self.p_peak_cell_mpa,
            "p_peak_admissible_mpa": max(p.peak.p_peak_admissible_mpa for p in self.pairs),
            "trimmed_cells": sum(p.peak.trimmed_cells for p in self.pairs),
            "trimmed_load_n": sum(p.peak.trimmed_load_n for p in self.pairs),
            "preview_p_max_mpa": self.preview_p_max_mpa,
            "preview_mode": self.preview_mode, "line_length_mm": self.line_length_mm,
            "mesh_rotation_pre_arcsec": self.rotation_pre_arcsec,
            "preview_pair_offsets": [p.offset for p in self.preview_pairs],
            "preview_pair_loads_n": [p.load_n for p in self.preview_pairs],
            "preview_compliance_scale": [p.scale for p in self.preview_pairs],
            "edge_resolved": self.resolved,
            "p_peak_trimmed_resolved_mpa": max(float(p.peak_resolved.p_peak_cell_mpa)
                                               for p in self.pairs),
            "cp_max_resolved_mpa": max(p.peak_resolved.cp_max_mpa for p in self.pairs),
            "load_share_resolved_pct": self._shares("load_resolved_n"),
            "mesh_rotation_resolved_arcsec": self.rotation_resolved_arcsec,
            "status_resolved": self.status_resolved,
            "edge_contact": self.edge_contact,
            "status": self.status, "status_rigid": self.status_rigid,
            "converged": self.converged}


def _solve(contacts, fields: PairFields, torque: float, materials, tol: float,
           torque_nm: float, th_pre: float, *, rigid: bool
           ) -> tuple[ContactResult, list, list, list, bool]:
    """The coupled LCP at one phase as :func:`.lte.loaded_te` solves it (cold start from
    the preview's rotation ``th_pre``; ``rigid``: without the fields' bending factors)."""
    res, reach, blocks, offs = solve_phase(contacts, fields, torque, materials, tol=tol,
                                            warm={}, theta_pre=th_pre, rigid=rigid)
    edge = check_loaded(res, reach, offs, torque_nm)
    return res, reach, blocks, offs, edge


def multi_tooth_ltca(tca, flanks, pair, torque_nm: float, *, side: str | None = None,
                     bending=None, cells: int = 40,
                     extent_factor: tuple[float, float] = (1.6, 2.0), tol: float = 1e-8,
                     edge_reach: float = 0.5, edge_law: bool = True) -> MultiToothCase:
    """Coupled multi-pair LCP at P0, rigid and with tooth bending (module docstring).

    Parameters
    ----------
    tca : gearcontact.tca.analysis.TcaAnalysis
        Unloaded analysis (its mesh cycle gives the pairs and the phase of P0).
    flanks : gearcontact.geometry.flank.FlankSet
        The flanks the TCA ran on.
    pair : gearcontact.geometry.pair.GearPair
        The pair (kinematics, materials).
    torque_nm : float
        Gear torque, N·m (> 0).
    side : str, optional
        ``"drive"`` or ``"coast"``; default the pair's ``design_side``.
    bending : ToothBending or None
        Tooth bending of both members (:func:`.tooth_bending.tooth_bending`); None:
        the second solve is rigid too.
    cells, extent_factor, tol, edge_reach, edge_law
        As :func:`.lte.loaded_te` (``edge_law``: the preview's law where a flank boundary
        cuts a pair's patch, :func:`.edge_rows.preview_edge_balance`).

    Returns
    -------
    MultiToothCase
    """
    side = pair.design_side if side is None else side
    t = check_positive("torque_nm (N·m)", torque_nm)
    if int(cells) < 16:
        raise InputRangeError("cells", cells, ">= 16 per side")
    for i, f in enumerate(extent_factor):
        if not f >= 1.1:
            raise InputRangeError(f"extent_factor[{i}]", f, ">= 1.1 Hertzian semi-axes")
    check_range("edge_reach", edge_reach, 0.0, 1.0)
    if bending is not None and bending.side != side:
        raise InputRangeError("bending.side", bending.side, f"'{side}' (the side of the LTCA)")
    cycle = tca.cycle
    kin = pair.kinematics()
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    materials = (pair.pinion_material, pair.gear_material)
    e_prime = effective_modulus_mpa(*materials)
    torque = 1e3 * t
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    k = cycle.mean_index
    edge_steps = round(edge_reach * cycle.step_index)
    # one set of fields for both solves: the rigid one leaves the bending factors out
    fields = PairFields(pinion, gear, kin, cycle, torque_nmm=torque, e_prime=e_prime,
                        cells=int(cells), extent=tuple(map(float, extent_factor)),
                        bending=bending)
    contacts = [fields.resolve(pc) for pc in
                phase_contacts(pinion, gear, kin, cycle, k, base, e_prime, {}, edge_steps)]
    # the preview of TE_pre and the twin (the edge law where a flank cuts a patch)
    # each solve starts from its own preview (the rigid one from the rigid teeth's)
    laws = {} if edge_law else None
    _, _, th_rigid, _ = preview_edge_balance(contacts, fields, torque, materials=materials,
                                             cache=laws)
    cb = (None if bending is None else
          [pair_bending_compliance(fields, pc, torque) for pc in contacts])
    previewed, scales, th_pre, w_pre = preview_edge_balance(
        contacts, fields, torque, materials=materials, cache=laws, bending_mm_per_n=cb)
    rig, reach_r, *_ = _solve(contacts, fields, torque, materials, tol, t, th_rigid,
                              rigid=True)
    res, reach, blocks, offs, edge = _solve(contacts, fields, torque, materials, tol, t,
                                            th_pre, rigid=bending is None)
    # boundary-inadmissible cells (docs/spec.md sec. 5): re-solve without the flanks'
    # boundary rows when the bending solution loaded them (warm from it)
    gaps = [trimmed_gap(b.gap_mm, off, m, OFF_FLANK_GAP_MM)
            for b, off, m in zip(blocks, offs, res.contact_masks)]
    fin, trimmed_offs = res, offs
    if any(g is not None for g in gaps):
        gaps = [b.gap_mm if g is None else g for b, g in zip(blocks, gaps)]
        trimmed_offs = [g >= OFF_FLANK_GAP_MM for g in gaps]
        fin = solve_mesh_lcp([replace(b, gap_mm=g) for b, g in zip(blocks, gaps)], torque,
                             materials=materials, tol=tol, rotation_guess_rad=res.rotation_rad,
                             warm_start=[np.where(o, 0.0, p) for o, p in
                                         zip(trimmed_offs, res.pressures_mpa(blocks))])
    rigid_load = {pc.offset: float(w.sum()) for pc, w in zip(reach_r, rig.loads_n)}
    total = float(sum(w.sum() for w in res.loads_n))
    main = next(pc for pc in reach if pc.opening_arcsec == 0.0 and not pc.edge)
    engaged = []
    for pc, w, b, off, wf, of in zip(reach, res.loads_n, blocks, offs, fin.loads_n,
                                     trimmed_offs):
        load = float(w.sum())
        if load <= ACTIVE_SHARE * total and rigid_load.get(pc.offset, 0.0) <= 0.0:
            continue
        origin, frame = fields.frames[pc.field_key]
        engaged.append(EngagedPair(
            offset=pc.offset, lever_mm=float(b.lever_mm), opening_arcsec=float(pc.opening_arcsec),
            edge=pc.edge, load_n=load, load_rigid_n=rigid_load.get(pc.offset, 0.0),
            loads_n=w, grid=b.grid, off_flank=off, origin_mm=np.asarray(origin, float),
            frame=np.asarray(frame, float), peak=line_contact_peak(w, b.grid, off),
            load_resolved_n=float(wf.sum()), peak_resolved=line_contact_peak(wf, b.grid, of)))
    engaged.sort(key=lambda p: (abs(p.offset - main.offset), -p.offset))
    ref = engaged[0]
    # host-side fp64 preview: the datapath's envelope is no input check here (an
    # ordinary pair's reduced radius exceeds its 1 m curvature range along the path)
    engine = ReferenceEngine(material=pair.pinion_material, material2=pair.gear_material,
                             envelope=False)
    length = contact_line_length_mm(ref.off_flank, ref.grid)
    pre = engine.hertz(main.A_minus_per_mm, main.B_minus_per_mm, ref.load_n,
                       line_length_mm=length)
    return MultiToothCase(
        torque_nm=t, side=side, phase_index=int(k), pairs=tuple(engaged),
        rotation_rigid_arcsec=float(rig.rotation_rad * ARCSEC_PER_RAD),
        rotation_arcsec=float(res.rotation_rad * ARCSEC_PER_RAD),
        preview_p_max_mpa=float(pre.p_max_mpa), bending=bending is not None,
        status=res.status, status_rigid=rig.status, solve_ms=float(res.solve_time_ms),
        solve_rigid_ms=float(rig.solve_time_ms), edge_contact=bool(edge),
        rotation_resolved_arcsec=float(fin.rotation_rad * ARCSEC_PER_RAD),
        resolved=fin is not res, status_resolved=fin.status, preview_mode=pre.mode,
        line_length_mm=length, rotation_pre_arcsec=float(th_pre * ARCSEC_PER_RAD),
        preview_pairs=tuple(PreviewPair(pc.offset, float(pc.lever_mm), float(pc.offset_mm),
                                        float(w), float(c), float(pc.kappa_mm_per_n23))
                            for pc, w, c in zip(previewed, w_pre, scales)))
