"""The mesh of the twin: per phase and tooth pair, what the contact law needs.

From the unloaded TCA over one pinion pitch (:class:`~gearcontact.tca.mesh.MeshCycle`)
and the potential contacts of the loaded TE (:func:`~gearcontact.ltca.lte_pairs.
phase_contacts`, edge pairs resolved on their posed fields), at each of the ``K`` phases
and for each neighbouring pair ``j``:

* ``lever_mm``: lever ``l_j`` of the pair's normal about the gear axis, mm;
* ``opening_mm``: initial separation ``g_j`` along the normal with the gear resting on
  the transmitting pair (0 for that pair), mm;
* ``A_minus, B_minus``: half relative principal curvatures at its mating point, 1/mm,
  the inputs of the Hertz stage of the preview;
* ``stencil_gaps_mm``: the 49 gap samples of the preview's 7 x 7 stage-C stencil at the
  same point (:func:`gearcontact.tca.stencil.hardware_stencil`; a window reaching
  beyond the flank is the osculating quadric), the input of the whole C -> D preview;
* ``contact_mode``: how the row's opening was found (:data:`CONTACT_MODES`): a surface
  contact of the TCA, an *edge contact* of the TCA (an edge of one flank touching the
  other flank, :mod:`gearcontact.tca.edge_contact`: the TCA the twin runs is the
  edge-contact one ``analyze`` runs), or a pair beyond even its edge contacts resolved
  on its *posed field* (:meth:`~gearcontact.ltca.lte_pairs.PairFields.resolve`);

The contact law at an edge row (issue 28; docs/twin.md "Edge contact"): the opening
and the lever are the edge contact's own (its TE0 from the edge-contact TCA, its point
and the touched flank's normal), so the pair closes at the phase where the edge
really touches; the curvatures (and the stencil) are those of the pair's nearest
surface contact along its path (:func:`~gearcontact.ltca.lte_pairs.curvature_point`),
i.e. the Hertzian law with which the surface contact reached the edge, its approach
scaled by the row's compliance scale ``c`` from the LCP on the edge's own field
(:mod:`gearcontact.ltca.edge_law`: the edge bounds the patch, so the untruncated
ellipse was 1.8-5 times too stiff; the rows and ``c`` chosen by
:mod:`gearcontact.ltca.edge_rows`, as for the loaded TE's ``TE_pre``), baked into the row as equivalent curvatures (A-, B- and stencil times
``c^3``) so that every backend evaluates it unchanged; ``edge_compliance_scale`` holds
``c`` (1 on other rows), ``edge_exponent`` the LCP's own power of the load.

and the unloaded TE envelope. Everything is re-expressed along the *motion*: the
pinion angle ``psi`` and the gear angle increase in the direction the pinion drives the
gear on the analysed flank (``psi = m (phi1 - phi1_0)`` with ``m = +1`` if the TE0
envelope is the max over the pairs, i.e. the pinion pushes the gear towards +phi2, and
``m = -1`` otherwise; :mod:`gearcontact.tca.mesh`), so that

    theta = psi_p / u + eps(psi_p) - psi_g          (gear lag behind its unloaded pose)

closes pair ``j`` by ``d_j = l_j theta - g_j`` exactly as the rotation ``theta`` of
:mod:`gearcontact.ltca.lte`, with ``eps = m TE0_env`` (rad). The loaded TE in the
TCA's sign is ``TE = TE0_env - m theta`` (the ``TE = TE0_env + s theta`` of the LTE,
``s = -m``).

Phases are kept with both ends of the pitch: the last row is the next pitch's first
with the pairs renumbered, so that an interval between two rows always uses one pair
numbering (the force is a sum over the pairs and does not care about their names).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..ltca.lte_pairs import PairFields, curvature_point, phase_contacts
from ..preview.fit.pinv import N_TAPS
from ..tca.stencil import hardware_stencil
from ..ltca.pair_ltca import ARCSEC_PER_RAD
from ..materials import effective_modulus_mpa
from ..validation import InputRangeError, check_positive
from ..ltca.edge_law import operating_scales
from ..ltca.edge_rows import is_cut, row_law
from ..ltca.tooth_bending import conjugate_compliance, pair_bending_compliance
from ..ltca.off_flank import is_wholly_off, touch_bending_compliance, touch_field, touch_law

__all__ = ["MeshTable", "mesh_table", "pair_mesh_table", "reverse_law", "free_play_rad",
           "pair_bending_compliance", "conjugate_compliance", "CONTACT_MODES",
           "REACH_TORQUE_FACTOR"]

#: Codes of :attr:`MeshTable.contact_mode`: 0 a surface contact (or no contact, where
#: not ``valid``), 1 an edge contact of the TCA, 2 an edge pair on its posed field.
CONTACT_MODES = ("surface", "edge", "posed field")
#: Torque, in multiples of the table's, up to which a row counts as *within reach*
#: (:func:`mesh_table`): above the largest dynamic factor measured on the design space
#: (5.31 on MITER_PAIR, docs/performance.md) with a margin of about 2.
REACH_TORQUE_FACTOR = 10.0


@dataclass(frozen=True, eq=False)
class MeshTable:
    """Per-phase, per-pair mesh data along the motion (module docstring).

    Attributes
    ----------
    psi_rad : ndarray (K,)
        Pinion angle along the motion from the first row, rad, increasing, spanning one
        pinion pitch ``2 pi / z1``.
    eps_rad : ndarray (K,)
        Unloaded TE envelope along the motion ``m TE0_env``, rad of gear rotation.
    lever_mm, opening_mm, A_minus_per_mm, B_minus_per_mm : ndarray (P, K)
        Per pair; rows of pairs without a contact at that phase hold 0 and
        ``valid`` False.
    valid : ndarray (P, K) of bool
        The pair is a potential contact at that phase.
    motion_sign : int
        ``m``: +1 if the motion runs along +phi1, -1 along -phi1.
    ratio : float
        ``u = z2 / z1``.
    pinion_teeth : int
        z1.
    reference_lever_mm : float
        Lever of the transmitting pair at the reference (mean) phase, mm; the line of
        action on which forces and the mesh damping are reported.
    reference_index : int
        Row of the reference phase.
    e_prime_mpa : float
        Effective modulus E' = 2E* of the two members, MPa.
    phi1_rad : ndarray (K,)
        The TCA phases of the rows, rad (TCA sign).
    te0_arcsec : ndarray (K,)
        The TCA envelope of the rows, arcsec (TCA sign).
    gear_datum_rad : float
        ``phi2_ref + (phi1_0 - phi1_ref) / u`` of the TCA path (pair-0 coordinates,
        ``phi1_0`` the first row): the unloaded gear angle of the row-0 phase is this
        plus ``TE0_env`` of the row; with the other side's datum it gives the free play
        between the two flanks (:func:`free_play_rad`).
    side : str
        ``"drive"`` or ``"coast"``.
    bending_mm_per_n : ndarray (P, K)
        Tooth-bending compliance of each pair (pinion + gear tooth in series with the
        contact), mm/N; zeros for rigid teeth (:func:`mesh_table` ``bending``).
    stencil_gaps_mm : ndarray (P, K, 49)
        The stage-C stencil of each pair at each phase (zeros where not ``valid``), mm,
        in the order of :mod:`gearcontact.contract.stencil`.
    line_length_mm : ndarray (P, K) or None
        Length of each pair's contact line in the zone of action, mm (a cylindrical
        pair's: the line core's ``L``, :mod:`.line_law`); None for point contact.
    contact_mode : ndarray (P, K) of int8 or None
        Index into :data:`CONTACT_MODES` of each row (module docstring); None: every
        row a surface (or line) contact.
    edge_label : ndarray (P, K) of str or None
        The touching edge of an edge row (``"pinion root"``, ...), else ``""``.
    line_gap_mm : ndarray (P, K, n) or None
        The ease-off along each pair's line: its normal gap over the line's least one at
        the centres of ``n`` equal slices between the line's ends, mm (the line law's
        loaded length, :mod:`.line_law`); None for point contact.
    line_bending_gram_mm_per_n : ndarray (P, K, m, m) or None
        Tooth-bending Gram matrix ``G = F F^T`` of the pinion and gear shells at those
        slices and the ``2 nb`` beyond them (``m = n + 2 nb``; unit loads on the
        slices), mm/N; None for rigid teeth.
    beyond_gap_mm : ndarray (P, K, 2, nb) or None
        The tip edge beyond either end of a helical pair's line (docs/cylindrical.md
        sec. 10): the normal gap of its points over the line's least one, at the line's
        lever, at ``nb`` axial positions ``beyond_width_mm`` apart (along the line) from
        each end outwards, mm; :data:`~gearcontact.ltca.cylindrical_edges.OFF_LINE_GAP_MM`
        where no edge point lies beyond that end; None: no such edge (a spur pair, point
        contact).
    beyond_width_mm : float or None
        Width along the line of those slices, mm.
    beyond_stiffness : float
        Foundation stiffness of those slices relative to the line's (the tip edge's
        section against the mating flank, :func:`gearcontact.ltca.edge_section.
        edge_stiffness_factor`; 1: the line's own): the slice law carries them on
        ``beyond_stiffness x beyond_width_mm``.
    edge_compliance_scale : ndarray (P, K) or None
        ``c`` of each edge row (:mod:`gearcontact.ltca.edge_law`; its curvatures and
        stencil carry ``c^3``), 1 elsewhere; None: no edge row calibrated.
    edge_exponent : ndarray (P, K) or None
        Exponent ``n`` of the LCP's ``delta = C W^n`` at each calibrated row (2/3 where
        the patch stayed on the flanks; 0 where the calibration failed -- an LCP not
        converged or a field that does not close -- and the row kept the Hertzian law,
        ``c = 1``), NaN at rows no flank boundary cuts and at rows out of reach.
    out_of_reach : ndarray (P, K) of bool or None
        Rows the mesh cannot close under :data:`REACH_TORQUE_FACTOR` times the table's
        torque (:func:`mesh_table`, "reach"): open by at least the lower bound of their
        opening, which exceeds that reach; their opening is the field's least gap where
        the field bounds the touch (no touch search), else the searched touch; their law
        uncalibrated (Hertz). Such rows whose field lies wholly off the flank are left
        out (not ``valid``); within reach, those take the law of :mod:`~gearcontact.ltca.off_flank`.
    """

    psi_rad: np.ndarray
    eps_rad: np.ndarray
    lever_mm: np.ndarray
    opening_mm: np.ndarray
    A_minus_per_mm: np.ndarray
    B_minus_per_mm: np.ndarray
    valid: np.ndarray
    motion_sign: int
    ratio: float
    pinion_teeth: int
    reference_lever_mm: float
    reference_index: int
    e_prime_mpa: float
    phi1_rad: np.ndarray
    te0_arcsec: np.ndarray
    gear_datum_rad: float = 0.0
    side: str = "drive"
    bending_mm_per_n: np.ndarray | None = None
    stencil_gaps_mm: np.ndarray | None = None
    line_length_mm: np.ndarray | None = None
    contact_mode: np.ndarray | None = None
    edge_label: np.ndarray | None = None
    line_gap_mm: np.ndarray | None = None
    line_bending_gram_mm_per_n: np.ndarray | None = None
    beyond_gap_mm: np.ndarray | None = None
    beyond_width_mm: float | None = None
    beyond_stiffness: float = 1.0
    edge_compliance_scale: np.ndarray | None = None
    edge_exponent: np.ndarray | None = None
    out_of_reach: np.ndarray | None = None
    reach_rad: np.ndarray | None = None

    @property
    def pitch_rad(self) -> float:
        """Pinion pitch ``2 pi / z1``, rad."""
        return 2.0 * np.pi / self.pinion_teeth

    @property
    def step_rad(self) -> float:
        """Uniform phase step of the rows, rad."""
        return float(self.psi_rad[1] - self.psi_rad[0])


def mesh_table(tca, flanks, pair, *, side: str = "drive", torque_nm: float = 64.5,
               edge_reach: float = 0.5, cells: int = 40, bending=None,
               edge_law: bool = True) -> MeshTable:
    """Mesh data of ``tca`` over one pitch (module docstring).

    Parameters
    ----------
    tca : gearcontact.tca.analysis.TcaAnalysis
        Unloaded analysis of ``side``.
    flanks : gearcontact.geometry.flank.FlankSet
        Its flanks.
    pair : gearcontact.geometry.pair.GearPair
        The pair (kinematics, materials).
    side : str
        ``"drive"`` or ``"coast"``.
    torque_nm : float
        Gear torque that sizes the posed fields of edge pairs (their opening is the
        smallest separation on the flank; the size only has to cover it), N·m.
    edge_reach : float
        As in :func:`gearcontact.ltca.lte.loaded_te`: pairs up to this fraction of a
        pitch beyond their path end are kept as edge contacts.
    cells : int
        Cells per side of an edge pair's posed field, whose smallest separation on the
        flank is the pair's opening (resolution dependent: use the ``cells`` of the
        loaded TE the twin is compared with; 40 is its default).
    bending : gearcontact.ltca.tooth_bending.ToothBending or None
        Tooth bending of both members: each pair's bending compliance
        :func:`pair_bending_compliance` at every phase into ``bending_mm_per_n`` (in
        series with the Hertzian approach in the twin's contact law); None: rigid
        teeth (zeros).
    edge_law : bool
        Calibrate every edge row on its edge field's LCP
        (:mod:`gearcontact.ltca.edge_rows`, at ``torque_nm``; about 0.1 s per row);
        False: the untruncated Hertzian law of the nearest surface contact (the loaded
        TE preview's with ``loaded_te(edge_law=False)``).

    Notes
    -----
    *Reach.* Pairs far past their path's end (a pitch's worth of edge pairs on a miter
    pair, open by up to 2 mm) need neither the touch search of their posed field nor an
    edge law: the mesh never closes them. A row is *out of reach* when the lower bound
    of its opening (:meth:`~gearcontact.ltca.lte_pairs.PairFields.bound`: the field's
    where the field encloses the touch, else the searched touch) over its lever exceeds
    the phase's rotation bound under :data:`REACH_TORQUE_FACTOR` times the torque
    (:func:`_reach_rad`); it keeps its opening's upper bound (or its touch) and the
    Hertzian law (``out_of_reach``). Rows within reach are the unlimited table's bit for
    bit (tests/twin/test_mesh_reach.py; docs/twin.md "Reach of the mesh table"). A row
    whose field lies wholly off the flank (no flank cell: no field bound, no patch for
    an edge law) has its touch searched over the whole flank
    (:func:`~gearcontact.ltca.patch_field.touch_search`); beyond the reach it is left
    out of the table (not ``valid``, as a pair whose flanks do not overlap), within it
    kept with its touch as its opening and the edge law of a field placed at its touch
    (:mod:`~gearcontact.ltca.off_flank`: the LCP calibration of the TCA's edge rows; where it fails, the
    Hertzian law, ``edge_exponent`` 0), with ``bending`` the bending compliance of that
    field's LCP pressure (:func:`~gearcontact.ltca.off_flank.touch_bending_compliance`).
    """
    t = check_positive("torque_nm (N·m)", torque_nm)
    cycle = tca.cycle
    kin = pair.kinematics()
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    if bending is not None and bending.side != side:
        raise InputRangeError("bending.side", bending.side, f"'{side}' (the side of the mesh)")
    fields = PairFields(pinion, gear, kin, cycle, torque_nmm=1e3 * t, e_prime=e_prime,
                        cells=int(cells), extent=(1.6, 2.0), bending=bending)
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    n_k, n_p = len(cycle.phi1_rad), len(cycle.pair_offsets)
    row = {o: i for i, o in enumerate(cycle.pair_offsets)}
    arrays = {name: np.zeros((n_p, n_k)) for name in ("lever", "opening", "A", "B", "cb",
                                                      "kappa")}
    valid = np.zeros((n_p, n_k), bool)
    mode = np.zeros((n_p, n_k), np.int8)
    label = np.full((n_p, n_k), "", dtype=object)
    stencils = np.zeros((n_p, n_k, N_TAPS))
    curv: dict = {}
    sten: dict = {}
    edges = np.full((n_p, n_k), None, dtype=object)
    far = np.zeros((n_p, n_k), bool)
    steps = round(edge_reach * cycle.step_index)
    materials = (pair.pinion_material, pair.gear_material)
    laws: dict = {}
    rows = {}       # (pair row, phase) -> (contact, lower bound of its opening in mm)
    touch_rows = {}     # (pair row, phase) -> (wholly-off contact within reach, its field)
    for k in range(n_k):
        for pc in phase_contacts(pinion, gear, kin, cycle, k, base, e_prime, curv, steps):
            pc, lower = fields.bound(pc)
            if np.isfinite(pc.opening_arcsec):
                rows[row[pc.offset], k] = (pc, lower)
    reach = _reach_rad(fields, rows, n_k, torque_nmm=1e3 * t, materials=materials,
                       cache=laws if edge_law else None, bending=bending is not None)
    for (i, k), (pc, lower) in rows.items():
        far[i, k] = lower / pc.lever_mm > reach[k]
        wholly = pc.edge and is_wholly_off(fields, pc)
        if far[i, k] and wholly:
            far[i, k] = False       # no flank cell in its field: left out (Notes, Reach)
            continue
        if not far[i, k]:
            pc = fields.resolve(pc)
        valid[i, k] = True
        label[i, k] = cycle.path.points[pc.path_index].edge_contact
        mode[i, k] = 2 if pc.edge else 1 if label[i, k] else 0
        arrays["lever"][i, k] = pc.lever_mm
        arrays["opening"][i, k] = pc.offset_mm
        arrays["A"][i, k] = pc.A_minus_per_mm
        arrays["B"][i, k] = pc.B_minus_per_mm
        arrays["kappa"][i, k] = pc.kappa_mm_per_n23
        if pc.center_index not in sten:
            mp = curvature_point(cycle.path, pc.center_index)
            sten[pc.center_index] = hardware_stencil(pinion, gear, kin, mp,
                                                     off_flank="quadric").gap_mm
        stencils[i, k] = sten[pc.center_index]
        # a wholly-off row's field at its touch, built once for its bending and its law
        touch = touch_field(fields, pc, torque_nmm=1e3 * t) if wholly and (
            bending is not None or edge_law) else None
        if bending is not None:
            arrays["cb"][i, k] = (touch_bending_compliance(fields, pc, materials=materials,
                                                           torque_nmm=1e3 * t, touch=touch)
                                  if wholly else pair_bending_compliance(fields, pc, 1e3 * t))
        if edge_law and wholly:
            touch_rows[i, k] = pc, touch
        elif edge_law and not far[i, k] and is_cut(fields, pc, torque_nmm=1e3 * t):
            edges[i, k] = pc
    laws, expo = _calibrate_edges(fields, edges, materials, 1e3 * t, laws)
    for (i, k), (pc, touch) in touch_rows.items():   # the edge law at the touch (Notes, Reach)
        laws[i, k] = touch_law(fields, pc, materials=materials, torque_nmm=1e3 * t,
                               touch=touch)
        expo[i, k] = 0.0 if laws[i, k] is None else laws[i, k].exponent
    m = 1 if cycle.envelope_is_max else -1
    phi1 = np.asarray(cycle.phi1_rad, float)
    env = np.asarray(cycle.envelope_arcsec, float)
    shift = _first_touch(arrays, valid)
    env = env + m * ARCSEC_PER_RAD * shift
    # each cut row's scale at the load it carries in the table's quasi-static mesh
    scale, _ = operating_scales(laws, arrays["lever"], arrays["opening"], arrays["kappa"],
                                valid, torque_nmm=1e3 * t)
    factor = scale ** 3         # equivalent curvatures (gearcontact.ltca.edge_law)
    arrays["A"] *= factor
    arrays["B"] *= factor
    stencils *= factor[..., None]
    order = np.arange(n_k) if m == 1 else np.arange(n_k)[::-1]
    k0 = cycle.mean_index
    main = [i for i in range(n_p) if valid[i, k0] and arrays["opening"][i, k0] == 0.0]
    if not main:
        raise ValueError("mesh_table: no transmitting pair at the reference phase (the TCA "
                         "lost the path of pair 0; use more phases)")
    ref_lever = float(arrays["lever"][main[0], k0])
    return MeshTable(
        psi_rad=m * (phi1[order] - phi1[order][0]), eps_rad=m * env[order] / ARCSEC_PER_RAD,
        lever_mm=arrays["lever"][:, order], opening_mm=arrays["opening"][:, order],
        A_minus_per_mm=arrays["A"][:, order], B_minus_per_mm=arrays["B"][:, order],
        valid=valid[:, order], motion_sign=m, ratio=float(pair.gear_teeth / pair.pinion_teeth),
        pinion_teeth=int(pair.pinion_teeth), reference_lever_mm=ref_lever,
        reference_index=int(np.flatnonzero(order == k0)[0]), e_prime_mpa=float(e_prime),
        phi1_rad=phi1[order], te0_arcsec=env[order],
        gear_datum_rad=float(cycle.path.phi2_ref_rad + (phi1[order][0] - cycle.path.phi1_ref_rad)
                             / cycle.path.ratio),
        side=side, bending_mm_per_n=arrays["cb"][:, order], stencil_gaps_mm=stencils[:, order],
        contact_mode=mode[:, order], edge_label=label[:, order],
        edge_compliance_scale=scale[:, order] if edge_law else None,
        edge_exponent=expo[:, order] if edge_law else None, out_of_reach=far[:, order],
        reach_rad=(reach - shift)[order])


def _calibrate_edges(fields: PairFields, edges: np.ndarray, materials, torque_nmm: float,
                     done: dict) -> tuple[np.ndarray, np.ndarray]:
    """``(law, n)`` per row: :func:`gearcontact.ltca.edge_rows.row_law` of each row's
    contact in ``edges`` (the calibration ``TE_pre`` takes too), once per row
    (``done``; ``law`` None and ``n = 0`` where it failed); None and NaN elsewhere."""
    laws, expo = np.full(edges.shape, None, dtype=object), np.full(edges.shape, np.nan)
    for (i, k), pc in np.ndenumerate(edges):
        if pc is not None:
            law = row_law(fields, pc, materials=materials, torque_nmm=torque_nmm, cache=done)
            laws[i, k], expo[i, k] = law, (0.0 if law is None else law.exponent)
    return laws, expo


def pair_mesh_table(pair, *, side: str, torque_nm: float, phases: int = 61, flanks=None,
                    bending: bool = False, progress: bool = False):
    """The twin's TCA of one side of ``pair`` and its :func:`mesh_table`: ``(tca,
    flanks, mesh)``. The TCA is the edge-contact one ``analyze`` runs
    (:func:`~gearcontact.tca.analysis.analyze_pair`, ``edge_contact=True``): a pair
    whose path continues through an edge of one flank touching the other closes where
    that edge touches (module docstring), not where a surface-only TCA's posed field
    sees it. ``bending``: the shell tooth bending of both members
    (:func:`~gearcontact.ltca.tooth_bending.tooth_bending`) in the table; else rigid.

    Raises
    ------
    LineContact
        The side's flanks are conjugate (zero ease-off).
    """
    from ..ltca.tooth_bending import tooth_bending
    from ..tca.analysis import analyze_pair

    tca, flanks = analyze_pair(pair, side=side, phases=phases, edge_contact=True,
                               flanks=flanks, progress=progress)
    teeth = tooth_bending(flanks, pair, side=side) if bending else None
    return tca, flanks, mesh_table(tca, flanks, pair, side=side, torque_nm=torque_nm,
                                   bending=teeth)


def _reach_rad(fields: PairFields, rows: dict, n_k: int, *, torque_nmm: float, materials,
               cache: dict | None, bending: bool) -> np.ndarray:
    """Per phase, a bound of the rotation ``theta`` (rad, gear) the mesh reaches under
    :data:`REACH_TORQUE_FACTOR` times the table's torque ``tau``: the rotation at which
    the phase's first-closing pair ``j`` (least ``g_j / l_j`` of the rows' upper
    openings, its touch then searched) carries ``tau`` alone, ``(g_j + c kappa_j W^(2/3)
    + c_b W) / l_j`` with ``W = tau / l_j`` and ``c`` the largest ratio of its edge law
    (:meth:`~gearcontact.ltca.edge_law.EdgeCompliance.scale_at` stays within them; 1 for
    Hertz). Other pairs carrying part of ``tau`` only lower the rotation (module
    docstring of :func:`mesh_table`, "reach"). ``cache``: the edge laws (None: no edge
    law)."""
    tau = REACH_TORQUE_FACTOR * torque_nmm
    reach = np.full(n_k, np.inf)
    for k in range(n_k):
        here = [pc for (_, kk), (pc, _) in rows.items() if kk == k]
        if not here:
            continue
        pc = fields.resolve(min(here, key=lambda p: p.offset_mm / p.lever_mm))
        scale = 1.0
        if cache is not None and is_cut(fields, pc, torque_nmm=torque_nmm):
            law = row_law(fields, pc, materials=materials, torque_nmm=torque_nmm, cache=cache)
            scale = 1.0 if law is None else max(1.0, float(np.max(law.ratio)))
        w = tau / pc.lever_mm
        bend = pair_bending_compliance(fields, pc, torque_nmm) if bending else 0.0
        reach[k] = (pc.offset_mm + scale * pc.kappa_mm_per_n23 * w ** (2.0 / 3.0)
                    + bend * w) / pc.lever_mm
    return reach


def _first_touch(arrays: dict, valid: np.ndarray) -> np.ndarray:
    """Rotation (rad, along the motion) per phase by which an edge pair touches before
    the transmitting pair of the surface TCA's envelope (0 where none does); the
    openings are re-based on it in place, so that the first-touching pair is open by 0.

    An edge pair resolved on its posed field may close at a negative opening ``g_j``
    (it interferes where the envelope's pair would touch): the unloaded mesh then rests
    on it, at ``theta = max_j (-g_j / l_j)``. Taking that into the envelope ``eps`` keeps
    the mesh conservative in it (the pinion's factor ``1/u + eps'`` is then the
    derivative of the first touch, as the kernel assumes), instead of a pre-loaded
    pair whose closing opening pushes the gear at no cost to the pinion.
    """
    lever, opening = arrays["lever"], arrays["opening"]
    ahead = np.where(valid, -opening / np.where(valid, lever, 1.0), 0.0)
    shift = np.maximum(ahead.max(axis=0), 0.0)
    first = np.argmax(ahead, axis=0)
    opening += np.where(valid, lever * shift, 0.0)
    cols = np.flatnonzero(shift > 0.0)
    opening[first[cols], cols] = 0.0        # exactly: the pair the mesh rests on
    return shift




def reverse_law(loaded: MeshTable, reverse: MeshTable) -> tuple[float, float]:
    """``(c_r, C)`` relating the reverse flank's table to the loaded one's motion.

    With the motion signs ``m`` (loaded) and ``m_r = -m`` (the reverse flank stops the
    gear the other way), the reverse table's pinion angle is ``psi_r = m_r (phi1 -
    phi1_r0) = c_r - psi`` and its closure (penetration along its own law, rad of gear
    rotation) is

        theta_r = psi_g - psi / u + eps_r(psi_r) - C - theta_b

    with ``C = m [(phi2_r0 - phi1_r0 / u) - (phi2_0 - phi1_0 / u)]`` from the two TCA
    data (reduced modulo the gear pitch: both paths use their own pair 0) and
    ``theta_b`` the designed backlash over the reference lever. The geometric free play
    between the flanks (``theta_b = 0``) is ``b(psi) = C - eps_r(psi_r) - eps(psi)``
    (:func:`free_play_rad`).

    Raises
    ------
    ValueError
        Both tables have the same motion sign (not a flank pair of opposite sides).
    """
    m, mr = loaded.motion_sign, reverse.motion_sign
    if mr != -m:
        raise ValueError(f"reverse_law: the {reverse.side} table runs the same way as the "
                         f"{loaded.side} table (motion signs {mr}, {m})")
    u = loaded.ratio
    c_r = mr * float(loaded.phi1_rad[0] - reverse.phi1_rad[0])
    big = m * ((reverse.gear_datum_rad - reverse.phi1_rad[0] / u)
               - (loaded.gear_datum_rad - loaded.phi1_rad[0] / u))
    p2 = 2.0 * np.pi / (u * loaded.pinion_teeth)
    return c_r, float(big - p2 * np.round(big / p2))


def free_play_rad(loaded: MeshTable, reverse: MeshTable, psi_rad) -> np.ndarray:
    """Geometric angular free play ``b(psi)`` (rad of gear rotation) between the loaded
    and the reverse flanks of the generated teeth (no designed backlash) at the loaded
    table's pinion angles ``psi``; negative: the flanks interfere."""
    c_r, big = reverse_law(loaded, reverse)
    psi = np.asarray(psi_rad, float)
    p = loaded.pitch_rad
    eps = np.interp(np.mod(psi, p), loaded.psi_rad, loaded.eps_rad)
    eps_r = np.interp(np.mod(c_r - psi, p), reverse.psi_rad, reverse.eps_rad)
    return big - eps_r - eps
