"""Memory layout of the twin's compiled step loop (:mod:`.kernel`): the backend and
curvature-source codes, the parameter vector ``prm``, the counters ``tcount``, the
state vector ``y`` and the record columns."""


#: Contact backends; ``rtl`` and ``soc`` run the golden loop and replay its previews on
#: the RTL core / through the SoC register driver (:mod:`.cosim`).
BACKEND_CODES = {"reference": 0, "golden": 1, "table": 2, "rtl": 1, "soc": 1}


# prm indices
(P_JM, P_JP, P_JG, P_JL, P_K1, P_K2, P_C1, P_C2, P_CM, P_THB, P_U, P_TM, P_TL, P_L0,
 P_EP, P_DPSI, P_PITCH, P_ECODE, P_NROW, P_KP, P_KI, P_OMEGA, P_DPSIR, P_NROWR, P_PSIR,
 P_CR, P_MIRROR, P_STAGEC, P_CLO, P_CHI, P_AHI, P_NSLICE, P_SLICE_CB, P_NBEYOND,
 P_BEYOND_W, P_HFORM) = range(36)
#: Length of ``prm``; with the exact Hertz form (``prm[P_HFORM]`` = 1, :data:`HERTZ_FORM_CODES`)
#: the table of :func:`~.exact_hertz.exact_hertz_table` follows from index N_PRM.
N_PRM = 36
#: The fp64 Hertz law's form (``prm[P_HFORM]``; :data:`gearcontact.preview.hertz.formats.
#: HERTZ_FORMS`): Hamrock-Brewe's closed forms, or exact Hertz (:mod:`.exact_hertz`).
HERTZ_FORM_CODES = {"hamrock-brewe": 0, "exact": 1}
#: Entries of the counters ``tcount``: trace rows written, step index of the trace rows,
#: steps, previews outside the datapath's domain, steps with such a preview, previews
#: without a contact law (:func:`~.kernel.run_steps`).
N_COUNT = 6
#: Curvature sources of the preview (``prm[P_STAGEC]``): the TCA's shape-operator
#: curvatures per row (``cv`` columns A-, B-), or stage C per step on the 7 x 7 stencil
#: (fp64: ``cv`` the fitted c3, c4, c5 per row; golden: ``cv`` the 49 gap samples).
CURVATURE_SOURCES = {"exact": 0, "stencil": 1}
#: The line chain of a cylindrical pair (``prm[P_STAGEC]``): stage C per step on the 7 x 7
#: stencil into the line core with the pair's contact-line length (``cv`` the fitted
#: c3, c4, c5 and L; golden: the 49 gap samples before them; :mod:`.line_law`).
LINE_SOURCE = "line"
LINE_SOURCE_CODE = 2
#: The line chain's ease-off along the line (``prm[P_NSLICE]``, :mod:`.line_law`): ``cv``
#: columns after L hold the pair's normal gap at the centres of P_NSLICE equal slices of
#: its line, then the tip edge beyond either end of a helical line on ``prm[P_NBEYOND]``
#: slices each (from the line's end outwards; ``prm[P_BEYOND_W]``: their width, mm, times
#: the edge section's stiffness relative to the line's; 0 on a spur pair), then the bending Gram matrix G of all ``m = P_NSLICE + 2 P_NBEYOND`` slices
#: (m^2, row-major, mm/N; zeros for rigid teeth).
#: Preview outputs per pair evaluation (``pv``): a, b, p_max, mode, the line law's beta,
#: the load (N) at which a, b, p_max hold (:data:`PV_LOAD`), the line law's approach
#: offset (mm, :data:`PV_LINE_OFFSET`) and bending compliance (mm/N; -1: the mesh
#: table's, :data:`PV_LINE_BENDING`); then 2 m scratch entries
#: (:func:`preview_scratch`).
N_PREVIEW = 8
#: Index in ``pv`` of the load of its a, b, p_max: the evaluation load ``W_e``, 1 N
#: where the fp64 Hertz law answered (:func:`~.contact_law._kappa_reference`), or the
#: load the line chain was sampled at (:func:`~.line_law._line_law`).
PV_LOAD = 5
#: Index in ``pv`` of the line law's approach offset ``h_bar`` (mm).
PV_LINE_OFFSET = 6
#: Index in ``pv`` of the line law's bending compliance in series (mm/N; -1: the table's).
PV_LINE_BENDING = 7
#: Columns of the kernel's per-pair preview cache (:func:`~.kernel.run_steps`).
N_CACHE = 11
#: Columns of the golden preview trace (:data:`~.cosim.TRACE_COLUMNS`).
N_TRACE = 12
#: Length of the state vector y.
N_STATE = 11
# record columns
(R_T, R_THETA, R_PSI, R_TMESH, R_W, R_A, R_B, R_P, R_NPAIRS, R_KE, R_PE, R_V, R_D, R_WIN,
 R_WP, R_WG) = range(16)
N_REC = 16
#: Recorded columns (SI; loads N, semi-axes mm, pressure MPa). The table backend holds no
#: contact state: its a_mm, b_mm, p_max_mpa, pairs_loaded and mesh_energy_j are 0.
RECORD_COLUMNS = ("t_s", "theta_rad", "psi_p_rad", "mesh_torque_nm", "mesh_load_n",
                  "a_mm", "b_mm", "p_max_mpa", "pairs_loaded", "kinetic_j",
                  "shaft_energy_j", "mesh_energy_j", "dissipated_j", "input_work_j",
                  "pinion_speed_rad_s", "gear_speed_rad_s")


def preview_scratch(prm, n_pairs: int) -> int:
    """Length of the kernel's ``pv`` for ``n_pairs`` pairs per flank: :data:`N_PREVIEW`
    outputs, the line law's two slice vectors, the coupled slice law's scratch
    (:func:`~gearcontact.ltca.coupled_slice_law.core_scratch`) and each pair's and
    flank's last effective ease-off with its row (the next step's start; :mod:`.line_law`)."""
    from ..ltca.coupled_slice_law import core_scratch
    m = int(prm[P_NSLICE]) + 2 * int(prm[P_NBEYOND])
    return N_PREVIEW + 2 * m + int(core_scratch(m)) + 2 * int(n_pairs) * (m + 1)
