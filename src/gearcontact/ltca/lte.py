"""Loaded transmission error (LTE) along the mesh phase, rigid teeth.

At each phase of one pinion pitch of the unloaded mesh cycle
(:class:`~gearcontact.tca.mesh.MeshCycle`) every neighbouring tooth pair ``j`` is a
potential contact if its mating point lies on both flanks, or if it lies at most
``edge_reach`` of a pitch beyond an end of its contact path (an *edge pair*: the teeth
still touch at a flank boundary, e.g. the tip, entering or leaving mesh). Each has

* its own tangent-plane gap field around its own mating point (edge pair: around the
  nearest interior point of its path), principal frame, real flanks
  (:func:`~gearcontact.tca.stencil.gap_field`), with both flanks posed as they stand
  unloaded -- the gear resting on the transmitting pair, ``TE = TE0_env`` -- so the
  field contains the pair's opening: its minimum is ``g_j = |TE0_j - TE0_env| / 206264.8
  * l_j`` mm (a gear rotation ``dphi2`` moves a gear point by ``l dphi2`` along the
  normal: the lever is the moment arm of the normal, Litvin & Fuentes 2004, sec. 9.4);
  cells off a flank get :data:`~.pair_ltca.OFF_FLANK_GAP_MM` as in
  :func:`~.pair_ltca.single_pair_ltca`, which trims an edge pair's contact at the
  boundary; the field is sized by the Hertzian ellipse of the pair carrying the whole
  torque (``extent_factor`` semi-axes); at an edge contact of the TCA the field is fitted
  to the edge, along it and into its flank (:func:`~gearcontact.tca.edge_field.
  edge_gap_field`), so that its least gap is the TCA's touch;
* its lever ``l_j`` about the gear axis (:func:`~..tca.load.torque_lever_mm`).

Under the gear torque ``T`` the gear turns by one shared rotation ``theta >= 0``
(towards the pinion, i.e. lagging) and closes pair ``j`` by ``l_j theta`` (on the posed
field, i.e. approach ``l_j theta - g_j`` from its own contact); the torque balance
``sum_j W_j l_j = T`` closes the problem. Two models of the pairs' contact compliance:

* **LCP** (``TE_LCP``): the half-space LCP of each pair on its gap field, all pairs
  solved together as one torque-constrained LCP with the rotation as the multiplier
  (coupled formulation, :func:`.mesh_lcp.solve_mesh_lcp`), warm-started from the
  previous phase;
* **preview** (``TE_pre``): Hamrock–Brewe Hertz per pair from its own relative
  curvatures (an edge pair: those of its nearest interior mating point, with the
  opening of its posed field; ``preview_edges``), ``delta_j(W) = c_j kappa_j W^(2/3)``
  (:func:`~gearcontact.analytic.hertz.hamrock_brewe_hertz`), i.e. ``W_j = ((l_j theta
  - g_j)_+ / (c_j kappa_j))^(3/2)``; the balance is a monotone scalar equation in
  ``theta`` solved by Brent's method. ``c_j = 1`` except where a flank boundary cuts
  the pair's patch (an edge pair, the TCA's edge contact, an ellipse leaving the
  flank): there ``c_j`` is the twin's LCP-calibrated compliance scale
  (:mod:`.edge_rows`, :mod:`.edge_law`; ``edge_law=False``: the untruncated law), so
  that ``TE_pre`` is the twin's static law (docs/twin.md "Edge contact").

Sign convention: TE keeps the TCA's sign (``TE = (phi2 - phi2_0) - (z1/z2)(phi1 -
phi1_0)``). The loaded gear lags the unloaded one by ``theta`` towards the open pairs, so

    TE_LCP = TE0_env + s theta,   s = +1 if the envelope is the min over the pairs
                                  (the pinion pushes the gear towards -phi2, s0003 drive),
                                  s = -1 if it is the max.

``rotation_*_arcsec`` hold ``theta >= 0``. With a single pair in contact the LCP
rotation is that pair's approach over its lever (the single-pair
``mesh_rotation_arcsec`` of :mod:`.pair_ltca`).

Compliances at the reference phase P0, by a central difference in torque
(``T (1 +- compliance_step)``), for LCP and preview, as ``c = l_0^2 d theta / d T``
(approach ``delta = l_0 theta`` and load ``W = T / l_0`` on the lever ``l_0`` of the
transmitting pair):

* contact compliance ``c = d delta / d W`` of the transmitting pair carrying the whole
  torque alone (for a Hertzian gap ``(2/3) delta / W``);
* mesh compliance: the same with all pairs within reach sharing the torque.

Tooth bending (optional, ``bending=``): the shell compliance of the pinion and gear
tooth of every pair (:mod:`.tooth_bending`) is added to its half-space compliance in
the same coupled LCP (:mod:`.mesh_lcp`); without it the teeth are rigid. The preview
takes it too (``preview_bending``): each pair's compliance under its Hertzian pressure
(:func:`.tooth_bending.pair_bending_compliance`) in series with its contact law, the
twin's law (:func:`gearcontact.analytic.series_contact.series_pair_load`).

Scope: no base / shaft rotation; the edge is the sharp flank boundary
(no tip radius); a pair beyond ``edge_reach`` is not considered: if it still carried
load at the previous phase, TE_LCP steps there and the load is reported
(``dropped_load_n``); loaded cells next to a flank boundary are reported
(``edge_contact``). The pairs come from the TCA's mesh cycle, whose continuation can
lose a pair's path end at coarse phase steps (s0003: use >= 11 phases per pitch).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 9, 15.
B. J. Hamrock, D. E. Brewe, J. Lubrication Technol. 105 (1983) 171-177.
K. L. Johnson, *Contact Mechanics*, 1985, ch. 3-4. docs/spec.md sec. 5.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from tqdm import tqdm

from ..materials import effective_modulus_mpa
from ..validation import InputRangeError, check_positive, check_range
from ..halfspace.result import SolveStatus
from .lte_pairs import PairContact, PairFields, phase_contacts
from .edge_rows import preview_edge_balance
from .tooth_bending import pair_bending_compliance
from .lte_phase import (ACTIVE_SHARE, check_loaded, check_pair_window, field_edge_reached,
                        reference_compliances, solve_phase)
from .pair_ltca import ARCSEC_PER_RAD

__all__ = ["LoadedTE", "PairContact", "loaded_te"]


@dataclass(frozen=True, eq=False)
class LoadedTE:
    """Loaded transmission error over one pinion pitch (see module docstring).

    Attributes
    ----------
    torque_nm : float
        Gear torque, N·m.
    phi1_rad : ndarray (K,)
        Pinion phases, rad.
    te0_arcsec, te_lcp_arcsec, te_pre_arcsec : ndarray (K,)
        Unloaded envelope, LCP-loaded and preview-loaded TE, arcsec.
    rotation_lcp_arcsec, rotation_pre_arcsec : ndarray (K,)
        Loaded gear rotation ``theta >= 0`` (LCP, preview), arcsec.
    te_sign : int
        ``s`` of ``TE = TE0_env + s theta``.
    pair_offsets : tuple of int
        Pair indices (rows of the load arrays).
    pair_loads_lcp_n, pair_loads_pre_n : ndarray (P, K)
        Normal load per pair and phase (0 for open or out-of-reach pairs), N.
    lever_mm : ndarray (P, K)
        Levers (NaN where the pair has no mating point).
    active_lcp, active_pre : ndarray (K,) of int
        Pairs carrying more than :data:`.lte_phase.ACTIVE_SHARE` of the load.
    edge_contact : ndarray (K,) of bool
        A loaded cell borders a flank boundary (tip, root or end) at that phase.
    field_edge : ndarray (K,) of bool
        A patch reaches the edge of its field (field too small; results truncated).
    dropped_load_n : ndarray (K,)
        LCP load that pairs carried at the previous phase when their mating point has
        left the flanks at this one (they are dropped: no tip-edge contact model, so
        TE_LCP steps there), N.
    status : tuple of SolveStatus
        LCP status per phase.
    solve_ms, field_ms : ndarray (K,)
        LCP solve time and gap-field time per phase, ms.
    reference_index : int
        Phase of P0 (where the compliances are taken).
    reference_lever_mm : float
        Lever ``l_0`` of the transmitting pair at P0, mm.
    compliance_lcp_mm_per_n, compliance_pre_mm_per_n : float
        Contact compliance ``c = d delta / d W`` of the transmitting pair alone at P0
        (LCP, Hamrock–Brewe preview), mm/N.
    mesh_compliance_lcp_mm_per_n, mesh_compliance_pre_mm_per_n : float
        ``l_0^2 d theta / d T`` at P0 with all pairs within reach, mm/N.
    cells : int
        Cells per side of each pair's field.
    bending : bool
        Tooth bending was in the LCP (then the LCP compliances include it).
    stiffness_rigid_nm_per_rad, stiffness_bending_nm_per_rad : ndarray (K,) or None
        Mesh stiffness ``k = dT / dtheta`` per phase with rigid teeth and with tooth
        bending (``loaded_te(stiffness=True)``; the bending one only with ``bending``),
        N·m/rad; central difference at ``T (1 +- compliance_step)``, each warm-started
        from the phase's solution. ``mesh_stiffness_n_per_mm`` refers it to the normal
        at the reference lever: ``k / l_0^2``.
    timings_s : dict
        Wall-clock seconds per stage.
    compliance_scale_pre : ndarray (P, K) or None
        ``c_j`` of the preview's law per pair and phase (1 where Hertz; module
        docstring); None: ``edge_law=False``.
    preview_bending : bool
        The preview's pairs had the teeth's bending in series (``TE_pre`` with bending;
        its reference compliances stay rigid Hertz).
    """

    torque_nm: float
    phi1_rad: np.ndarray
    te0_arcsec: np.ndarray
    te_lcp_arcsec: np.ndarray
    te_pre_arcsec: np.ndarray
    rotation_lcp_arcsec: np.ndarray
    rotation_pre_arcsec: np.ndarray
    te_sign: int
    pair_offsets: tuple
    pair_loads_lcp_n: np.ndarray
    pair_loads_pre_n: np.ndarray
    lever_mm: np.ndarray
    active_lcp: np.ndarray
    active_pre: np.ndarray
    edge_contact: np.ndarray
    field_edge: np.ndarray
    dropped_load_n: np.ndarray
    status: tuple
    solve_ms: np.ndarray
    field_ms: np.ndarray
    reference_index: int
    reference_lever_mm: float
    compliance_lcp_mm_per_n: float
    compliance_pre_mm_per_n: float
    mesh_compliance_lcp_mm_per_n: float
    mesh_compliance_pre_mm_per_n: float
    cells: int
    bending: bool = False
    stiffness_rigid_nm_per_rad: np.ndarray | None = None
    stiffness_bending_nm_per_rad: np.ndarray | None = None
    timings_s: dict = field(default_factory=dict)
    compliance_scale_pre: np.ndarray | None = None
    preview_bending: bool = False

    def mesh_stiffness_n_per_mm(self, k_nm_per_rad: np.ndarray) -> np.ndarray:
        """A mesh stiffness (N·m/rad) along the normal at the reference lever ``l_0``:
        ``1e3 k / l_0^2``, N/mm (the inverse of ``mesh_compliance_*`` at P0)."""
        return 1e3 * np.asarray(k_nm_per_rad) / self.reference_lever_mm ** 2

    def _stiffness_models(self) -> list[tuple[str, np.ndarray]]:
        return [(name, k) for name, k in (("rigid", self.stiffness_rigid_nm_per_rad),
                                          ("bending", self.stiffness_bending_nm_per_rad))
                if k is not None]

    @property
    def te0_pp_arcsec(self) -> float:
        """Peak-to-peak of the unloaded envelope, arcsec."""
        return float(np.ptp(self.te0_arcsec))

    @property
    def te_lcp_pp_arcsec(self) -> float:
        """Peak-to-peak of TE_LCP, arcsec."""
        return float(np.ptp(self.te_lcp_arcsec))

    @property
    def te_pre_pp_arcsec(self) -> float:
        """Peak-to-peak of TE_pre, arcsec."""
        return float(np.ptp(self.te_pre_arcsec))

    @property
    def converged(self) -> bool:
        """True when every phase's LCP converged."""
        return all(s is SolveStatus.CONVERGED for s in self.status)

    def summary(self) -> dict:
        """Plain-JSON scalars (the keys of ``lte.json``)."""
        k0 = self.reference_index
        share = self.pair_loads_lcp_n[:, k0] / self.pair_loads_lcp_n[:, k0].sum()
        return {"torque_nm": self.torque_nm, "phases": len(self.phi1_rad),
                "te0_pp_arcsec": self.te0_pp_arcsec,
                "te_lcp_pp_arcsec": self.te_lcp_pp_arcsec,
                "te_pre_pp_arcsec": self.te_pre_pp_arcsec,
                "te_pre_vs_lcp_pp_pct": 100.0 * (self.te_pre_pp_arcsec
                                                 / self.te_lcp_pp_arcsec - 1.0),
                "compliance_lcp_mm_per_n": self.compliance_lcp_mm_per_n,
                "compliance_pre_mm_per_n": self.compliance_pre_mm_per_n,
                "mesh_compliance_lcp_mm_per_n": self.mesh_compliance_lcp_mm_per_n,
                "mesh_compliance_pre_mm_per_n": self.mesh_compliance_pre_mm_per_n,
                "preview_law": "hertz" if self.compliance_scale_pre is None else
                               "edge law (LCP-calibrated c where a flank boundary cuts)",
                "preview_bending": self.preview_bending,
                **self._scale_summary(),
                "mean_rotation_lcp_arcsec": float(self.rotation_lcp_arcsec.mean()),
                "mean_rotation_pre_arcsec": float(self.rotation_pre_arcsec.mean()),
                "reference_rotation_lcp_arcsec": float(self.rotation_lcp_arcsec[k0]),
                "reference_lever_mm": self.reference_lever_mm,
                "reference_load_share": {str(o): float(s) for o, s
                                         in zip(self.pair_offsets, share)},
                "active_pairs_lcp_min": int(self.active_lcp.min()),
                "active_pairs_lcp_max": int(self.active_lcp.max()),
                "active_pairs_pre_min": int(self.active_pre.min()),
                "active_pairs_pre_max": int(self.active_pre.max()),
                "edge_contact_phases": int(self.edge_contact.sum()),
                "field_edge_phases": int(self.field_edge.sum()),
                "max_dropped_load_n": float(self.dropped_load_n.max()),
                "converged": self.converged,
                "unconverged_phases": int(sum(s is not SolveStatus.CONVERGED for s in self.status)),
                **self._stiffness_summary(),
                "te_sign": self.te_sign, "cells": self.cells, "bending": self.bending,
                "solve_ms_per_phase": float(self.solve_ms.mean()),
                "field_ms_per_phase": float(self.field_ms.mean()),
                "timings_s": dict(self.timings_s)}

    def _scale_summary(self) -> dict:
        """Loaded (pair, phase) entries of the preview whose law is scaled, and the
        range of their ``c``."""
        if self.compliance_scale_pre is None:
            return {}
        c = self.compliance_scale_pre[(self.pair_loads_pre_n > 0.0)
                                      & (self.compliance_scale_pre != 1.0)]
        return {"preview_scaled_entries": int(c.size),
                "preview_scale_min": float(c.min()) if c.size else 1.0,
                "preview_scale_max": float(c.max()) if c.size else 1.0}

    def _stiffness_summary(self) -> dict:
        out = {}
        k0 = self.reference_index
        for name, k in self._stiffness_models():
            kn = self.mesh_stiffness_n_per_mm(k)
            out |= {f"mesh_stiffness_{name}_nm_per_rad_mean": float(k.mean()),
                    f"mesh_stiffness_{name}_nm_per_rad_min": float(k.min()),
                    f"mesh_stiffness_{name}_nm_per_rad_max": float(k.max()),
                    f"mesh_stiffness_{name}_n_per_mm_mean": float(kn.mean()),
                    f"mesh_stiffness_{name}_n_per_mm_min": float(kn.min()),
                    f"mesh_stiffness_{name}_n_per_mm_max": float(kn.max()),
                    f"reference_mesh_stiffness_{name}_n_per_mm": float(kn[k0])}
        return out

    def table(self) -> tuple[list[str], list[list]]:
        """Header and per-phase rows of ``lte.csv``."""
        header = ["phase", "phi1_deg", "te0_arcsec", "te_lcp_arcsec", "te_pre_arcsec",
                  "rotation_lcp_arcsec", "rotation_pre_arcsec", "active_lcp", "active_pre"]
        header += [f"load_lcp_pair{o:+d}_n" for o in self.pair_offsets]
        header += [f"load_pre_pair{o:+d}_n" for o in self.pair_offsets]
        models = self._stiffness_models()
        for name, _ in models:
            header += [f"mesh_stiffness_{name}_nm_per_rad", f"mesh_stiffness_{name}_n_per_mm"]
        header += ["edge_contact", "field_edge", "dropped_load_n", "status", "solve_ms",
                   "field_ms"]
        rows = []
        for k in range(len(self.phi1_rad)):
            rows.append([k, float(np.degrees(self.phi1_rad[k])), float(self.te0_arcsec[k]),
                         float(self.te_lcp_arcsec[k]), float(self.te_pre_arcsec[k]),
                         float(self.rotation_lcp_arcsec[k]),
                         float(self.rotation_pre_arcsec[k]), int(self.active_lcp[k]),
                         int(self.active_pre[k])]
                        + [float(w) for w in self.pair_loads_lcp_n[:, k]]
                        + [float(w) for w in self.pair_loads_pre_n[:, k]]
                        + [float(v) for _, st in models
                           for v in (st[k], self.mesh_stiffness_n_per_mm(st[k]))]
                        + [int(self.edge_contact[k]), int(self.field_edge[k]),
                           float(self.dropped_load_n[k]), self.status[k], float(self.solve_ms[k]),
                           float(self.field_ms[k])])
        return header, rows


def loaded_te(tca, flanks, pair, torque_nm: float, *, side: str | None = None,
              cells: int = 40, extent_factor: tuple[float, float] = (1.6, 2.0),
              tol: float = 1e-8, compliance_step: float = 0.05, stride: int = 1,
              edge_reach: float = 0.5, preview_edges: bool = True, edge_law: bool = True,
              bending=None, stiffness: bool = False, progress: bool = False,
              preview_bending: bool = True) -> LoadedTE:
    """Loaded TE over the pitch of ``tca.cycle`` under a gear torque (module docstring).

    Parameters
    ----------
    tca : gearcontact.tca.analysis.TcaAnalysis
        Unloaded analysis; its mesh cycle sets the phases (>= 61 per pitch for
        reports) and the neighbouring pairs.
    flanks : gearcontact.geometry.flank.FlankSet
        The flanks the TCA ran on.
    pair : gearcontact.geometry.pair.GearPair
        The pair (kinematics with assembly errors, materials).
    torque_nm : float
        Gear torque, N·m (> 0).
    side : str, optional
        ``"drive"`` or ``"coast"`` (the side the TCA ran on); default the pair's
        ``design_side``.
    cells : int
        Cells per side of each pair's field (>= 16; 40 resolves the minor semi-axis of
        the fully loaded pair with 10 cells, which puts the approach within about 1 %
        of the converged value; 80 matches :func:`~.pair_ltca.single_pair_ltca`).
    extent_factor : (float, float)
        Half extents of each field in Hertzian semi-axes at the full load (>= 1.1).
    tol : float
        LCP tolerance (:func:`.mesh_lcp.solve_mesh_lcp`).
    compliance_step : float
        Relative torque step of the central difference, in (0, 0.5].
    edge_reach : float
        Pairs up to this fraction of a pitch beyond an end of their contact path are
        kept as edge contacts (their posed field is trimmed by the flank boundary), in
        [0, 1]; 0 drops a pair as soon as its mating point leaves the flanks.
    preview_edges : bool
        Give the edge pairs to the preview too, as Hertzian contacts with the
        curvatures of their nearest interior mating point and the opening of their posed
        field; False: the preview sees only pairs with a mating point.
    edge_law : bool
        The preview's law at a contact whose patch a flank boundary cuts (an edge pair,
        the TCA's edge contact, a surface contact whose ellipse leaves the flank): Hertz
        with the approach scaled by the LCP calibration's ``c`` at the contact's load
        (:func:`.edge_rows.row_law`), the twin's law (module docstring); False:
        the untruncated Hertz law there too.
    stride : int
        Use every ``stride``-th phase of the cycle (>= 1), plus the last one and P0: a
        cheaper LTE on a fine TCA (e.g. 61 TCA phases, stride 6 -> 11 LTE phases).
    bending : ToothBending or None
        Tooth bending compliance of both members
        (:func:`~.tooth_bending.tooth_bending`) added to every pair's half-space
        compliance in the coupled LCP; None (default): rigid teeth, exactly the
        rigid-tooth solution.
    stiffness : bool
        Also the mesh stiffness ``dT / dtheta`` at every phase (central difference
        with ``compliance_step``, warm-started; 2 more solves per phase and model): with
        rigid teeth, and with ``bending`` also with bending (4 more solves per phase).
    progress : bool
        Show a progress bar over the phases.
    preview_bending : bool
        With ``bending``, the preview's pairs bend too: each pair's shell compliance
        under its Hertzian pressure (:func:`.tooth_bending.pair_bending_compliance`,
        the twin's) in series with its contact law (:func:`.lte_phase.preview_balance`,
        the twin's :func:`gearcontact.analytic.series_contact.series_pair_load`); False:
        the preview keeps rigid teeth.

    Returns
    -------
    LoadedTE
        Per-phase LCP status in ``.status``; ``.converged`` is False if any failed.
    """
    side = pair.design_side if side is None else side
    t_all = time.perf_counter()
    t = check_positive("torque_nm (N·m)", torque_nm)
    if int(cells) < 16:
        raise InputRangeError("cells", cells, ">= 16 per side")
    for i, f in enumerate(extent_factor):
        if not f >= 1.1:
            raise InputRangeError(f"extent_factor[{i}]", f, ">= 1.1 Hertzian semi-axes")
    eps = check_range("compliance_step", compliance_step, 0.0, 0.5, lo_open=True)
    if int(stride) != stride or stride < 1:
        raise InputRangeError("stride", stride, "an integer >= 1")
    stride = int(stride)
    check_range("edge_reach", edge_reach, 0.0, 1.0)
    cycle = tca.cycle
    kin = pair.kinematics()
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    materials = (pair.pinion_material, pair.gear_material)
    e_prime = effective_modulus_mpa(*materials)
    torque = 1e3 * t
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    if bending is not None and bending.side != side:
        raise InputRangeError("bending.side", bending.side, f"'{side}' (the side of the LTE)")
    fields = PairFields(pinion, gear, kin, cycle, torque_nmm=torque, e_prime=e_prime,
                        cells=int(cells), extent=tuple(map(float, extent_factor)),
                        bending=bending)
    curv: dict = {}
    k_full = len(cycle.phi1_rad)
    sel = np.array(sorted(set(range(0, k_full, stride)) | {k_full - 1, cycle.mean_index}))
    n_k, n_p = len(sel), len(cycle.pair_offsets)
    row = {o: i for i, o in enumerate(cycle.pair_offsets)}
    rot_lcp, rot_pre = np.zeros(n_k), np.zeros(n_k)
    w_lcp, w_pre, levers = np.zeros((n_p, n_k)), np.zeros((n_p, n_k)), np.full((n_p, n_k), np.nan)
    edge, fedge = np.zeros(n_k, bool), np.zeros(n_k, bool)
    considered = np.zeros((n_p, n_k), bool)
    edge_steps = round(edge_reach * cycle.step_index)
    solve_ms, field_ms, status = np.zeros(n_k), np.zeros(n_k), []
    models = ([(True, np.zeros(n_k))] + ([(False, np.zeros(n_k))] if bending is not None
                                          else [])) if stiffness else []
    warm: dict = {}
    laws: dict = {}
    scale_pre = np.ones((n_p, n_k))
    k_ref = int(np.flatnonzero(sel == cycle.mean_index)[0])
    ref = None
    for k in tqdm(range(n_k), desc=f"LTE {t:g} N·m", disable=not progress, leave=False):
        f0 = fields.seconds
        contacts = [fields.resolve(pc) for pc in
                    phase_contacts(pinion, gear, kin, cycle, int(sel[k]), base, e_prime,
                                   curv, edge_steps)]
        valid = contacts if preview_edges else [pc for pc in contacts if not pc.edge]
        considered[[row[pc.offset] for pc in contacts], k] = True
        cb = ([pair_bending_compliance(fields, pc, torque) for pc in valid]
              if bending is not None and preview_bending else None)
        valid, scales, th_pre, wp = preview_edge_balance(
            valid, fields, torque, materials=materials, cache=laws if edge_law else None,
            bending_mm_per_n=cb)
        scale_pre[[row[pc.offset] for pc in valid], k] = scales
        res, reach, blocks, offs = solve_phase(contacts, fields, torque, materials,
                                                tol=tol, warm=warm, theta_pre=th_pre)
        field_ms[k] = 1e3 * (fields.seconds - f0)
        solve_ms[k] = res.solve_time_ms
        status.append(res.status)
        edge[k] = check_loaded(res, reach, offs, t)
        fedge[k] = field_edge_reached(res.contact_masks)
        rot_lcp[k], rot_pre[k] = res.rotation_rad, th_pre
        for pc, w in zip(valid, wp):
            w_pre[row[pc.offset], k] = w
            levers[row[pc.offset], k] = pc.lever_mm
        warm = {}
        for pc, w, b in zip(reach, res.loads_n, blocks):
            w_lcp[row[pc.offset], k] = float(w.sum())
            levers[row[pc.offset], k] = b.lever_mm
            warm[pc.offset] = w / b.grid.cell_area_mm2
        for rigid, k_arr in models:
            th = []
            for sgn in (1.0, -1.0):
                r2, *_ = solve_phase(contacts, fields, torque * (1.0 + sgn * eps), materials,
                                      tol=tol, warm=warm, theta_pre=th_pre,
                                      rigid=rigid or bending is None)
                if not r2.converged and status[-1] is SolveStatus.CONVERGED:
                    status[-1] = r2.status
                th.append(r2.rotation_rad)
            k_arr[k] = 2.0 * eps * t / (th[0] - th[1])          # N·m/rad
        if k == k_ref:
            ref = (contacts, valid, warm)
    check_pair_window(w_lcp, cycle.pair_offsets)   # sel holds the first and last phase
    comp = reference_compliances(ref, fields, torque, eps, materials, tol)
    # loads of pairs that lose their mating point; pair j at phase 0 is pair j - 1 at
    # phase K-1 (the next pitch starts there), so its predecessor is pair j - 1 at K-2
    prev = np.zeros_like(w_lcp)
    prev[:, 1:] = w_lcp[:, :-1]
    if n_k > 2:
        prev[1:, 0] = w_lcp[:-1, -2]
    dropped = (prev * ~considered).sum(axis=0)
    sign = -1 if cycle.envelope_is_max else 1
    env = np.asarray(cycle.envelope_arcsec, float)[sel]
    share = ACTIVE_SHARE
    timings = {"fields_s": fields.seconds, "solves_s": float(solve_ms.sum()) / 1e3,
               "total_s": time.perf_counter() - t_all}
    return LoadedTE(
        torque_nm=t, phi1_rad=np.asarray(cycle.phi1_rad, float)[sel], te0_arcsec=env,
        te_lcp_arcsec=env + sign * rot_lcp * ARCSEC_PER_RAD,
        te_pre_arcsec=env + sign * rot_pre * ARCSEC_PER_RAD,
        rotation_lcp_arcsec=rot_lcp * ARCSEC_PER_RAD,
        rotation_pre_arcsec=rot_pre * ARCSEC_PER_RAD, te_sign=sign,
        pair_offsets=tuple(cycle.pair_offsets), pair_loads_lcp_n=w_lcp,
        pair_loads_pre_n=w_pre, lever_mm=levers,
        active_lcp=(w_lcp > share * w_lcp.sum(axis=0)).sum(axis=0),
        active_pre=(w_pre > share * w_pre.sum(axis=0)).sum(axis=0),
        edge_contact=edge, field_edge=fedge, dropped_load_n=dropped, status=tuple(status), solve_ms=solve_ms,
        field_ms=field_ms, reference_index=int(k_ref), cells=int(cells),
        bending=bending is not None, timings_s=timings,
        stiffness_rigid_nm_per_rad=models[0][1] if models else None,
        stiffness_bending_nm_per_rad=models[1][1] if len(models) > 1 else None,
        compliance_scale_pre=scale_pre if edge_law else None,
        preview_bending=bending is not None and preview_bending, **comp)
