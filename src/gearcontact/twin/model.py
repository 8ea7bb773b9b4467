"""The drivetrain twin's model: a :class:`TwinModel` joins the drivetrain (:mod:`.params`),
the mesh of the pair (:mod:`.mesh`; and for the ``table`` backend the loaded-TE table of
:mod:`.ltca_table`) and one contact backend, laid out as the compiled loop of
:mod:`.kernel` takes it (:func:`build_model`, :func:`model_for_pair`); its static
operating point and linearised modes are :mod:`.statics`, its time run
:mod:`.simulate`.

Tooth bending (switchable: ``mesh_table(..., bending=...)``, ``model_for_pair(...,
bending=True)``, ``gearcontact twin --bending``): each pair's bending compliance of the
pinion and gear tooth (:func:`~gearcontact.ltca.tooth_bending.pair_bending_compliance`, the shell operator of
:mod:`gearcontact.ltca.tooth_bending` weighted by the pair's Hertz pressure) is in
series with its Hertzian approach, ``d_j = kappa_j W_j^(2/3) + c_b,j W_j``, solved per
pair and step in the kernel; without it the teeth are rigid.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..analytic.hertz import hamrock_brewe_terms
from ..preview.fit.golden import element_constants
from ..preview.fit.pinv import N_COEFFS, N_TAPS
from ..preview.fit.reference import fitted_coefficients
from ..preview.hertz.golden import encode_e_prime
from ..preview.hertz.golden_vec import golden_constants
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM, check_hertz_form
from ..preview.hertz.reference import ENVELOPE
from ..validation import InputRangeError, check_positive
from . import kernel as K
from .exact_hertz import RATIO_MAX, exact_hertz_table, exact_hertz_terms
from .layout import LINE_SOURCE
from .line_law import line_law_constants
from .mesh import MeshTable
from .params import DrivetrainParams

__all__ = ["TwinModel", "build_model", "model_for_pair", "exact_form_mesh", "BACKENDS",
           "CURVATURE_SOURCES"]

BACKENDS = tuple(K.BACKEND_CODES)
#: Curvature sources of the preview (:class:`TwinModel` ``curvatures``).
CURVATURE_SOURCES = tuple(K.CURVATURE_SOURCES)


@dataclass(frozen=True, eq=False)
class TwinModel:
    """Everything a run needs (build with :func:`build_model`).

    Attributes
    ----------
    mesh : MeshTable
    drivetrain : DrivetrainParams
    backend : str
        One of :data:`BACKENDS`.
    torque_nm : float
        Load torque on the gear, N·m (the motor gives ``torque / u``).
    table : gearcontact.twin.ltca_table.TorqueTable or None
        The loaded-TE table (``table`` backend).
    reverse : MeshTable or None
        The other flank side's table (its own TCA): the law of the reverse flank
        (torque reversal through the backlash). None: the loaded side's law mirrored
        about the designed backlash (``reverse_note`` says why).
    reverse_note : str
        How the reverse flank is modelled (written to ``twin.json``).
    curvatures : str
        Where the preview's curvatures come from (:data:`CURVATURE_SOURCES`):
        ``"stencil"``, stage C per step on the 7 x 7 gap stencil (the whole C -> D
        preview); ``"exact"``, the TCA's shape-operator curvatures (the law of the
        loaded TE's preview).
    hertz_form : str
        The fp64 Hertz law (:data:`~gearcontact.preview.hertz.formats.HERTZ_FORMS`):
        ``"hamrock-brewe"`` (default) or ``"exact"`` (:mod:`.exact_hertz`; reference
        backend, point-contact curvature sources).
    """

    mesh: MeshTable
    drivetrain: DrivetrainParams
    backend: str
    torque_nm: float
    table: object = None
    arrays: dict = field(default_factory=dict, repr=False)
    reverse: MeshTable | None = None
    reverse_note: str = ""
    curvatures: str = "stencil"
    hertz_form: str = DEFAULT_HERTZ_FORM

    @property
    def curvature_source(self) -> str:
        """The curvature source the kernel runs (:func:`_curvature_source`)."""
        return _curvature_source(self.backend, self.curvatures)


def _curvature_source(backend: str, curvatures: str) -> str:
    """The table backend has no preview: its arrays are packed with the exact
    curvatures, never read; every other backend runs ``curvatures``."""
    return "exact" if backend == "table" else curvatures


def build_model(mesh: MeshTable, drivetrain: DrivetrainParams, torque_nm: float, *,
                backend: str = "reference", table=None, reverse: MeshTable | None = None,
                reverse_note: str = "", curvatures: str = "stencil",
                hertz_form: str = DEFAULT_HERTZ_FORM) -> TwinModel:
    """Check the inputs and pack the compiled loop's arrays.

    Tooth bending comes with the mesh tables (their ``bending_mm_per_n``).

    Curvatures outside the fixed-point datapath's domain are not refused: the run
    counts and reports the previews that leave it (:func:`~.simulate.simulate`).
    ``hertz_form="exact"`` evaluates the fp64 law as exact Hertz (:mod:`.exact_hertz`).

    Raises
    ------
    InputRangeError
        Unknown backend or curvature source, ``table`` backend without a table, torque
        <= 0, a designed backlash that does not clear an interference of the generated
        flanks; ``hertz_form`` not one of ``HERTZ_FORMS``, ``"exact"`` with another
        backend than ``reference`` (the datapath's golden form evaluates its own law) or
        with the line chain, or with a mesh row whose curvature ratio exceeds
        :data:`~.exact_hertz.RATIO_MAX`.
    """
    if backend not in BACKENDS:
        raise InputRangeError("backend", backend, f"one of {list(BACKENDS)}")
    if curvatures not in CURVATURE_SOURCES + (LINE_SOURCE,):
        raise InputRangeError("curvatures", curvatures, f"one of {list(CURVATURE_SOURCES)}")
    if curvatures == LINE_SOURCE and any(m is not None and (m.line_length_mm is None
                                                            or m.line_gap_mm is None)
                                         for m in (mesh, reverse)):
        raise InputRangeError("curvatures", curvatures, "a mesh table with the pairs' "
                                                        "contact-line lengths and ease-off "
                                                        "along them (a cylindrical pair's) "
                                                        "for the line chain")
    _check_hertz_form(hertz_form, backend, curvatures, (mesh, reverse))
    if hertz_form != DEFAULT_HERTZ_FORM:
        mesh, reverse = _exact_equivalent(mesh), _exact_equivalent(reverse)
    t = check_positive("torque_nm (N·m)", torque_nm)
    if backend == "table" and table is None:
        raise InputRangeError("table", None, "a loaded-TE table for the table backend")
    if reverse is not None:
        from .mesh import free_play_rad
        # opposite motion signs (reverse_law), and a positive total free play: the
        # designed backlash must exceed an interference of the generated flanks
        geo = float(free_play_rad(mesh, reverse, mesh.psi_rad).min()) * mesh.reference_lever_mm
        if geo + drivetrain.backlash_mm <= 0.0:
            raise InputRangeError("drivetrain.backlash_mm", drivetrain.backlash_mm,
                                  f"> {-geo:.4g} mm (the generated {mesh.side} and "
                                  f"{reverse.side} flanks interfere by {-1e3 * geo:.3g} um)")
        reverse_note = reverse_note or (f"own law: the {reverse.side} flanks' TCA (levers, "
                                        "openings, curvatures, TE0), geometric free play "
                                        "plus backlash_mm")
    else:
        reverse_note = reverse_note or "loaded side's law mirrored about backlash_mm"
    pow_lut, cbrt_lut, cst = golden_constants()
    if table is not None:
        tab = (np.ascontiguousarray(table.theta_rad),
               np.ascontiguousarray(np.broadcast_to(table.torques_nm ** (2.0 / 3.0),
                                                    table.theta_rad.shape)),
               np.ascontiguousarray(table.load_n ** (2.0 / 3.0)))
    else:
        tab = (np.ones((1, 2)), np.zeros((1, 2)), np.zeros((1, 2)))
    fit_w, fit_cst = element_constants()
    source = _curvature_source(backend, curvatures)
    arrays = {**_stack(mesh, reverse if reverse is not None else mesh, source,
                       golden=backend not in ("reference", "table")),
              "pow_lut": pow_lut, "cbrt_lut": cbrt_lut, "cst": cst,
              "tab_theta": tab[0], "tab_t23": tab[1], "tab_w23": tab[2],
              "fit_w": fit_w, "fit_cst": fit_cst, "line_cst": line_law_constants()}
    return TwinModel(mesh, drivetrain, backend, t, table, arrays, reverse, reverse_note,
                     curvatures, hertz_form)


def _exact_equivalent(mesh: MeshTable | None) -> MeshTable | None:
    """``mesh`` with its LCP-calibrated edge rows re-based on exact Hertz.

    An edge row's compliance scale ``c`` is the LCP's approach over Hamrock-Brewe's
    (:func:`gearcontact.ltca.edge_law.edge_compliance`), baked in as curvatures (and
    stencil) times ``c^3`` (:mod:`.mesh`). At a fixed curvature ratio the approach of
    either law scales as the cube root of the curvatures, and the ratio of the two laws
    depends on the curvature ratio only, so the same LCP approach under exact Hertz is
    the row times ``(delta_HB / delta_exact)^3`` at its own ratio. Surface rows (their
    scale an LCP-over-LCP ratio, :func:`~gearcontact.ltca.edge_law.trim_compliance`,
    law-free) and uncalibrated rows (``edge_exponent`` 0: Hertz) are unchanged; so is
    the operating load the scale was read at (the table's Hamrock-Brewe balance)."""
    if mesh is None or mesh.edge_compliance_scale is None or mesh.contact_mode is None:
        return mesh
    a, b = mesh.A_minus_per_mm, mesh.B_minus_per_mm
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    rows = (mesh.valid & (mesh.contact_mode != 0) & (mesh.edge_exponent != 0.0)
            & np.isfinite(mesh.edge_exponent) & (lo > 0.0))
    if not rows.any():
        return mesh
    tab, ep = exact_hertz_table(), mesh.e_prime_mpa
    factor = np.ones(a.shape)
    for i, k in zip(*np.nonzero(rows)):
        hb = hamrock_brewe_terms(lo[i, k], hi[i, k], 1.0, ep)[4]
        factor[i, k] = (hb / exact_hertz_terms(lo[i, k], hi[i, k], 1.0, ep, tab, 0)[3]) ** 3
    sten = mesh.stencil_gaps_mm
    return replace(mesh, A_minus_per_mm=a * factor, B_minus_per_mm=b * factor,
                   stencil_gaps_mm=None if sten is None else sten * factor[..., None])


def exact_form_mesh(mesh: MeshTable, hertz_form: str) -> MeshTable:
    """The mesh table the fp64 law of ``hertz_form`` runs on, as :func:`build_model`
    makes it (the reference backend, the TCA's curvatures): ``mesh`` itself for the
    default form; for ``"exact"`` its LCP-calibrated edge rows re-based on exact Hertz
    (:func:`_exact_equivalent`), after :func:`build_model`'s refusals (a row beyond the
    exact table's curvature ratio: InputRangeError)."""
    _check_hertz_form(hertz_form, "reference", "exact", (mesh,))
    return mesh if hertz_form == DEFAULT_HERTZ_FORM else _exact_equivalent(mesh)


def _check_hertz_form(hertz_form: str, backend: str, curvatures: str, meshes) -> None:
    """Refuse a ``hertz_form`` the twin cannot run (:func:`build_model`'s Raises)."""
    check_hertz_form(hertz_form)
    if hertz_form == DEFAULT_HERTZ_FORM:
        return
    if backend != "reference":
        raise InputRangeError("hertz_form", hertz_form,
                              f"hamrock-brewe with the {backend} backend (the exact form "
                              "is the fp64 law of the reference backend)")
    if curvatures == LINE_SOURCE:
        raise InputRangeError("hertz_form", hertz_form,
                              "hamrock-brewe with the line chain (cylindrical pairs)")
    for m in meshes:
        if m is None:
            continue
        lo = np.minimum(m.A_minus_per_mm, m.B_minus_per_mm)[m.valid]
        hi = np.maximum(m.A_minus_per_mm, m.B_minus_per_mm)[m.valid]
        bad = (lo > 0.0) & (hi > RATIO_MAX * lo)
        if bad.any():
            raise InputRangeError("hertz_form", hertz_form,
                                  f"hamrock-brewe for mesh rows of curvature ratio beyond "
                                  f"{RATIO_MAX:g} (the exact table's end; largest "
                                  f"{float((hi[bad] / lo[bad]).max()):.4g})")


def _stack(mesh: MeshTable, rev: MeshTable, source: str, *, golden: bool) -> dict:
    """The kernel's per-flank arrays: index 0 the loaded side, 1 the reverse side, padded
    to the larger pair and row counts (padding is never valid). ``cv``: the preview's
    curvature source per row (:mod:`.kernel`): A-, B- (``exact``); the stencil's fitted
    c3, c4, c5 (``stencil``, fp64) or its 49 samples and then c3, c4, c5 (``stencil``,
    golden: the fp64 fit evaluates the previews the datapath flags)."""
    n_p = max(mesh.lever_mm.shape[0], rev.lever_mm.shape[0])
    n_k = max(mesh.lever_mm.shape[1], rev.lever_mm.shape[1])
    out = {"eps": np.zeros((2, n_k))}
    for s, m in enumerate((mesh, rev)):
        out["eps"][s, :m.eps_rad.size] = m.eps_rad
    for key, attr in (("lever", "lever_mm"), ("opening", "opening_mm"), ("valid", "valid"),
                      ("cb", "bending_mm_per_n")):
        arr = np.zeros((2, n_p, n_k), bool if key == "valid" else float)
        for s, m in enumerate((mesh, rev)):
            v = getattr(m, attr)
            if v is None:
                continue
            arr[s, :v.shape[0], :v.shape[1]] = v
        out[key] = arr
    srcs = [_curvature_rows(m, source, golden=golden) for m in (mesh, rev)]
    cv = np.zeros((2, n_p, n_k, srcs[0].shape[2]))
    for s, v in enumerate(srcs):
        cv[s, :v.shape[0], :v.shape[1]] = v
    out["cv"] = cv
    return out


def _curvature_rows(mesh: MeshTable, source: str, *, golden: bool) -> np.ndarray:
    """(P, K, C) curvature source of one table (:func:`_stack`); the line chain
    (:data:`~.layout.LINE_SOURCE`) appends the contact-line length L, mm."""
    if source == "exact":
        return np.stack([mesh.A_minus_per_mm, mesh.B_minus_per_mm], axis=-1)
    cols = [fitted_coefficients(mesh.stencil_gaps_mm)]
    if golden:      # the samples for the fit core, the fp64 fit for the fp64 fallback
        cols.insert(0, np.asarray(mesh.stencil_gaps_mm, float))
    if source == LINE_SOURCE:      # L, the slices' ease-off (the line's, then the edge's
        # beyond its ends) and their bending Gram (.line_law)
        gaps = np.asarray(mesh.line_gap_mm, float)
        if mesh.beyond_gap_mm is not None:
            gaps = np.concatenate([gaps, np.asarray(mesh.beyond_gap_mm, float).reshape(
                gaps.shape[:2] + (-1,))], axis=-1)
        n = gaps.shape[-1]
        gram = (np.zeros(gaps.shape[:2] + (n * n,)) if mesh.line_bending_gram_mm_per_n is None
                else np.asarray(mesh.line_bending_gram_mm_per_n, float).reshape(
                    gaps.shape[:2] + (n * n,)))
        cols += [np.asarray(mesh.line_length_mm, float)[..., None], gaps, gram]
    return np.concatenate(cols, axis=-1) if len(cols) > 1 else cols[0]


def _prm(model: TwinModel, c_mesh_n_s_per_mm: float) -> np.ndarray:
    dt, m = model.drivetrain, model.mesh
    c1, c2 = dt.shaft_damping()
    prm = np.zeros(K.N_PRM)
    prm[[K.P_JM, K.P_JP, K.P_JG, K.P_JL]] = (dt.motor_inertia_kgm2, dt.pinion_inertia_kgm2,
                                             dt.gear_inertia_kgm2, dt.load_inertia_kgm2)
    prm[K.P_K1], prm[K.P_K2] = dt.input_stiffness_nm_per_rad, dt.output_stiffness_nm_per_rad
    prm[K.P_C1], prm[K.P_C2], prm[K.P_CM] = c1, c2, c_mesh_n_s_per_mm
    prm[K.P_THB] = dt.backlash_mm / m.reference_lever_mm
    prm[K.P_U] = m.ratio
    prm[K.P_TL] = model.torque_nm
    prm[K.P_TM] = model.torque_nm / m.ratio
    prm[K.P_L0] = m.reference_lever_mm
    rev = model.reverse
    if rev is None:
        prm[K.P_MIRROR] = 1.0
        prm[K.P_DPSIR], prm[K.P_NROWR] = m.step_rad, len(m.psi_rad)
    else:
        from .mesh import reverse_law
        prm[K.P_PSIR], prm[K.P_CR] = reverse_law(m, rev)
        prm[K.P_DPSIR], prm[K.P_NROWR] = rev.step_rad, len(rev.psi_rad)
    prm[K.P_EP] = m.e_prime_mpa
    prm[K.P_DPSI] = m.step_rad
    prm[K.P_PITCH] = m.pitch_rad
    prm[K.P_ECODE] = encode_e_prime(m.e_prime_mpa)
    prm[K.P_NROW] = len(m.psi_rad)
    prm[K.P_STAGEC] = K.CURVATURE_SOURCES.get(model.curvature_source, K.LINE_SOURCE_CODE)
    prm[K.P_CLO], prm[K.P_CHI] = ENVELOPE["curvature_per_mm"]
    prm[K.P_AHI] = ENVELOPE["alpha"][1]
    if model.hertz_form != DEFAULT_HERTZ_FORM:
        prm[K.P_HFORM] = K.HERTZ_FORM_CODES[model.hertz_form]
        prm = np.concatenate([prm, exact_hertz_table()])
    if model.curvature_source == LINE_SOURCE:
        prm[K.P_NSLICE] = m.line_gap_mm.shape[-1]
        prm[K.P_SLICE_CB] = float(m.line_bending_gram_mm_per_n is not None)
        if m.beyond_gap_mm is not None:
            prm[K.P_NBEYOND] = m.beyond_gap_mm.shape[-1]
            # the edge section's softer foundation: the slices' width scaled
            prm[K.P_BEYOND_W] = m.beyond_width_mm * m.beyond_stiffness
    return prm


def _fit_args(a: dict, trace_rows: int) -> tuple:
    """The kernel's ``fit`` tuple: the golden stage C's ROM and constants, its scratch,
    a stencil trace of ``trace_rows`` rows (:func:`.kernel.run_steps`) and the line
    core's constants (:mod:`.line_law`)."""
    return (a["fit_w"], a["fit_cst"], np.zeros((1, N_TAPS), np.int64),
            np.zeros((1, N_COEFFS), np.int64), np.zeros((trace_rows, N_TAPS), np.int64),
            a["line_cst"])


def model_for_pair(pair, *, torque_nm: float, backend: str = "reference",
                   drivetrain: DrivetrainParams | None = None, side: str = "drive",
                   phases: int = 61, table_source: str = "lcp", table_cells: int = 32,
                   bending: bool = False, curvatures: str = "stencil",
                   flanks=None, progress: bool = False,
                   hertz_form: str = DEFAULT_HERTZ_FORM) -> TwinModel:
    """TCA of ``pair``, its mesh table and (``table`` backend) the loaded-TE table, then
    :func:`build_model`. ``drivetrain`` None uses :func:`~.params.default_drivetrain`.
    The TCA is the edge-contact one ``analyze`` runs (a pair's path continues through
    an edge of one flank touching the other; its rows carry the edge's own opening and
    lever and the Hertzian law of the nearest surface contact scaled by the LCP's
    compliance where a flank boundary cuts the patch, :mod:`.mesh`, :mod:`.edge_law`). The
    reverse flank is the other side's own TCA (mirrored loaded law if that side is in
    line contact, or if its unloaded mesh has a gap: ``design`` checks the contact ratio
    of the design side only; ``reverse_note`` says which). ``bending``: tooth bending of both members in series with the
    Hertzian law of both sides (:func:`~gearcontact.ltca.tooth_bending.pair_bending_compliance`). ``curvatures``:
    the preview's curvature source, ``hertz_form`` its fp64 law (:class:`TwinModel`). ``flanks``: ``build_flanks(pair)``
    if already built (a prepared pair's, :class:`~gearcontact.tca.synthesis.PreparedPair`)."""
    from ..tca.edges import ContactGap
    from ..tca.line_contact import LineContact
    from .ltca_table import torque_table
    from .mesh import pair_mesh_table
    from .params import default_drivetrain

    t = check_positive("torque_nm (N·m)", torque_nm)
    if backend not in BACKENDS:     # before the expensive stages
        raise InputRangeError("backend", backend, f"one of {list(BACKENDS)}")
    if curvatures not in CURVATURE_SOURCES:
        raise InputRangeError("curvatures", curvatures, f"one of {list(CURVATURE_SOURCES)}")
    _check_hertz_form(hertz_form, backend, curvatures, ())
    from ..ltca.tooth_bending import tooth_bending

    # The edge-contact TCA (analyze's, .mesh.pair_mesh_table): an approaching pair that
    # touches first at an edge closes where the edge touches (issue 28: a 7/60 pair on
    # its pinion root edge lost contact 10 % of the time at 3000 rpm without it); pairs
    # beyond even their edge contacts enter as edge pairs resolved on their posed fields
    tca, flanks, mesh = pair_mesh_table(pair, side=side, torque_nm=t, phases=phases,
                                        flanks=flanks, bending=bending, progress=progress)
    other = "coast" if side == "drive" else "drive"
    reverse, note = None, ""
    try:
        _, _, reverse = pair_mesh_table(pair, side=other, torque_nm=t, phases=phases,
                                        flanks=flanks, bending=bending, progress=progress)
    except LineContact as exc:     # conjugate flanks: no contact ellipse to load
        note = (f"loaded side's law mirrored about backlash_mm: the {other} flanks are in "
                f"line contact ({str(exc).split(';')[0]}), outside the Hertzian preview")
    except ContactGap as exc:
        # design checks the contact ratio of the design side only: the other side's
        # unloaded mesh may have a gap (issue 28 audit: 9/9, E 0, 55 deg, coast), which
        # the reverse flank meets only after crossing the backlash
        note = (f"loaded side's law mirrored about backlash_mm: the {other} flanks' "
                f"unloaded mesh has a gap (contact ratio < 1: no tooth pair in contact at "
                f"phi1 = {np.degrees(exc.phi1_rad):.4f} deg)")
    table = None
    if backend == "table":
        table = torque_table(tca, flanks, pair, mesh, t, side=side, source=table_source,
                             cells=table_cells,
                             bending=tooth_bending(flanks, pair, side=side) if bending else None,
                             progress=progress)
    return build_model(mesh, drivetrain or default_drivetrain(pair), t, backend=backend,
                       table=table, reverse=reverse, reverse_note=note,
                       curvatures=curvatures, hertz_form=hertz_form)
