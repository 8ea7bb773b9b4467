"""The drivetrain twin's time run: :func:`simulate` integrates a :class:`~.model.TwinModel`
at a fixed step with the compiled loop of :mod:`.kernel` (equations and integrator
documented there), from the static operating point of :mod:`.statics`.

The model set-up (:mod:`.model`) and the static point and modes (:mod:`.statics`) are
re-exported here: ``gearcontact.twin.simulate`` is the twin's one entry point.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from tqdm import tqdm

from ..ltca.pair_ltca import ARCSEC_PER_RAD
from ..ltca.cylindrical_edges import OFF_LINE_GAP_MM
from ..errors import CheckFailed, RtlMismatch
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM
from ..preview.hertz.reference import LAW_BEYOND_RANGE, LAW_OK, law_status
from ..validation import InputRangeError, check_array_finite, check_positive, check_range
from . import kernel as K
from .layout import LINE_SOURCE
from .mesh import CONTACT_MODES
# the set-up and the static point, re-exported: the twin's one entry point
from .model import (BACKENDS, CURVATURE_SOURCES, TwinModel, _fit_args,  # noqa: F401
                    _prm, build_model, model_for_pair)
from .statics import (STABILITY_LIMIT, STEP_RANGE_US, _elastic, check_step,  # noqa: F401
                      linear_matrices, linearized_modes, mesh_damping_n_s_per_mm,
                      speed_controller_gains, static_rotation)

__all__ = ["TwinModel", "TwinResult", "build_model", "model_for_pair", "simulate",
           "linearized_modes", "linear_matrices", "check_step", "static_rotation",
           "speed_controller_gains",
           "mesh_damping_n_s_per_mm", "BACKENDS", "CURVATURE_SOURCES", "STABILITY_LIMIT",
           "STEP_RANGE_US", "MAX_SPEED_RPM",
           "LOCKSTEP_MAX_STEPS"]

#: Highest pinion speed a run accepts, rpm.
MAX_SPEED_RPM = 1e5
_CHUNK = 256          # steps per compiled call: the step-time percentiles' granularity
#: Longest lockstep runs (the trace holds every preview; the SoC driver takes ~0.3 s per
#: preview in simulation), steps.
LOCKSTEP_MAX_STEPS = {"rtl": 200_000, "soc": 1_000}


@dataclass(frozen=True, eq=False)
class TwinResult:
    """A twin run.

    Attributes
    ----------
    columns : dict of str -> ndarray
        Time series (:data:`~.kernel.RECORD_COLUMNS` plus ``te_arcsec``, the dynamic TE
        in the TCA's sign, comparable with ``gearcontact lte``).
    summary : dict
        Plain-JSON scalars (see :func:`simulate`); deterministic: identical runs give
        identical summaries (no timings).
    natural_frequencies_hz : ndarray
        Linearised modes at the static point.
    timings : dict
        Wall-clock measurements of this run (see :func:`simulate`), kept out of
        ``summary`` so that result files are byte-identical across identical runs
        (the CLI writes these into ``run.json``).
    """

    columns: dict
    summary: dict
    natural_frequencies_hz: np.ndarray
    timings: dict = field(default_factory=dict)


def simulate(model: TwinModel, *, speed_rpm: float, duration_s: float, step_s: float,
             record_every: int = 1, settle_fraction: float = 0.5, initial_velocity=None,
             progress: bool = False, board: tuple | None = None) -> TwinResult:
    """Integrate the twin (kernel docstring for equations and integrator).

    Parameters
    ----------
    model : TwinModel
    speed_rpm : float
        Nominal pinion (motor) speed, rpm (>= 0; 0 gives a free vibration about the
        static point).
    duration_s : float
        Simulated time, s (> 0).
    step_s : float
        Fixed step, s, within :data:`STEP_RANGE_US` and ``h omega_max <=``
        :data:`STABILITY_LIMIT`.
    record_every : int
        Record every n-th step (>= 1).
    settle_fraction : float
        Leading fraction of the run left out of the summary statistics (transient from
        the static start), in [0, 1).
    initial_velocity : array_like (4,) or None
        Added to the nominal speeds of motor, pinion, gear, load at t = 0, rad/s.
    progress : bool
        Progress bar over the steps.
    board : (str, int) or None
        ``soc`` backend: ``(host, port)`` of the ``litex_server`` in front of the board
        (or of ``gearcontact rtl serve``) that the previews are replayed on; None: the
        SoC's simulation in this process.

    Returns
    -------
    TwinResult
        ``summary`` keys: ``backend, steps, step_us, duration_s, speed_rpm, torque_nm,
        mesh_frequency_hz, static_mesh_torque_nm, static_mesh_load_n,
        mean_mesh_torque_nm, mean_mesh_load_n, dynamic_factor, contact_loss,
        dte_pp_arcsec, natural_frequencies_hz, h_omega_max, mesh_damping_n_s_per_mm,
        bending``; but for the table backend ``previews_outside_datapath,
        steps_outside_datapath, outside_datapath_evaluated_by,
        previews_without_contact_law`` (previews whose curvatures lie outside the
        fixed-point datapath's domain, :data:`~gearcontact.preview.hertz.reference.
        ENVELOPE`, evaluated by the fp64 law instead; saddles, whose pair carries
        nothing) and ``hertz_law_status, hertz_law_rows, hertz_law_rows_beyond_range,
        hertz_law_ratio_max`` (mesh rows beyond the Hamrock–Brewe law's 5 % range,
        :func:`_law_summary`; not for a cylindrical pair's line chain). Statistics over
        the recorded steps after ``settle_fraction``.
        ``rtl`` / ``soc`` add the replay's ``<backend>_previews, _mismatches``.
        ``timings`` keys: ``real_time_factor, step_time_p50_us, step_time_p99_us,
        wall_s`` (and ``<backend>_seconds, _previews_per_s`` of a replay);
        ``step_time_p*`` are percentiles of the mean step time of blocks of ``256
        record_every`` steps (one compiled call each).

    Raises
    ------
    InputRangeError
        Bad speed, duration, step (range and stability), record_every, settle_fraction,
        initial_velocity; a lockstep run longer than :data:`LOCKSTEP_MAX_STEPS`.
    ArithmeticError
        Non-finite state or a lockstep mismatch; :class:`~gearcontact.errors.CheckFailed`
        (exit 4) naming the steps where the compiled law's own check failed (the
        coupled slice law's Newton not converging, :mod:`.line_law`).
    """
    speed = check_range("speed_rpm", speed_rpm, 0.0, MAX_SPEED_RPM)
    dur = check_positive("duration_s", duration_s)
    h_us = check_range("step_us", 1e6 * float(step_s), *STEP_RANGE_US)
    h = 1e-6 * h_us
    if int(record_every) != record_every or record_every < 1:
        raise InputRangeError("record_every", record_every, "an integer >= 1")
    check_range("settle_fraction", settle_fraction, 0.0, 1.0, hi_open=True)
    if board is not None and model.backend != "soc":
        raise InputRangeError("board", f"{board[0]}:{board[1]}",
                              f"only with the soc backend (not {model.backend})")
    freqs, h_omega = check_step(model, h)
    n_steps = int(round(dur / h))
    if n_steps < 1:
        raise InputRangeError("duration_s", dur, f">= one step ({h:g} s)")
    cap = LOCKSTEP_MAX_STEPS.get(model.backend)
    if cap is not None and n_steps > cap:
        raise InputRangeError("duration_s", dur, f"<= {cap * h:g} s ({cap} steps) for the "
                              f"{model.backend} backend (lockstep replay: short runs)")
    if initial_velocity is not None:
        initial_velocity = check_array_finite("initial_velocity (rad/s)", initial_velocity)
        if initial_velocity.shape != (4,):
            raise InputRangeError("initial_velocity shape", initial_velocity.shape,
                                  "(4,): motor, pinion, gear, load")
    m, dt = model.mesh, model.drivetrain
    c_m = mesh_damping_n_s_per_mm(model)
    prm = _prm(model, c_m)
    theta0, w0 = static_rotation(model)
    omega = speed * 2.0 * math.pi / 60.0
    prm[K.P_OMEGA] = omega
    prm[K.P_KP], prm[K.P_KI] = speed_controller_gains(model)
    y = np.zeros(K.N_STATE)
    y[0] = model.torque_nm / m.ratio / dt.input_stiffness_nm_per_rad
    y[2] = m.eps_rad[0] - theta0
    y[3] = y[2] - model.torque_nm / dt.output_stiffness_nm_per_rad
    y[4:8] = omega, omega, omega / m.ratio, omega / m.ratio
    if initial_velocity is not None:
        y[4:8] += initial_velocity
    w_eval = np.full((2, w0.size), K.W_EVAL_MIN_N)
    w_eval[0] = np.where(w0 > 0, w0, K.W_EVAL_MIN_N)
    a = model.arrays
    code = K.BACKEND_CODES[model.backend]
    args = (prm, a["eps"], a["lever"], a["opening"], a["cv"], a["valid"], a["cb"], code)
    n_p = a["lever"].shape[1]
    # rtl: the golden loop records every preview for the lockstep replay (.cosim)
    lockstep = model.backend in ("rtl", "soc")
    trace = np.zeros(((n_steps * (n_p + 2)) if lockstep else 0, K.N_TRACE), np.int64)
    tcount = np.zeros(K.N_COUNT, np.int64)
    line = model.curvature_source == LINE_SOURCE
    stencil = line or prm[K.P_STAGEC] == K.CURVATURE_SOURCES["stencil"]
    fit = _fit_args(a, trace.shape[0] if stencil else 0)
    tail = (a["pow_lut"], a["cbrt_lut"], a["cst"], trace, tcount, fit, a["tab_theta"],
            a["tab_t23"], a["tab_w23"])
    warm = (a["pow_lut"], a["cbrt_lut"], a["cst"], trace[:0], np.zeros(K.N_COUNT, np.int64),
            _fit_args(a, 0), a["tab_theta"], a["tab_t23"], a["tab_w23"])
    # compile (or load the cache) outside the timed loop
    K.run_steps(y.copy(), 0.0, 1, h, *args, w_eval.copy(), *warm, np.zeros((1, K.N_REC)), 0, 1)
    n_rec = (n_steps + record_every - 1) // record_every
    rec = np.zeros((n_rec, K.N_REC))
    chunk = _CHUNK * record_every
    times = []
    rows = 0
    bar = tqdm(total=n_steps, desc=f"twin {model.backend}", unit="step", disable=not progress,
               leave=False)
    done = 0
    wall0 = time.perf_counter()
    while done < n_steps:
        n = min(chunk, n_steps - done)
        t0 = time.perf_counter()
        try:
            rows += K.run_steps(y, done * h, n, h, *args, w_eval, *tail, rec, rows,
                                record_every)
        except ArithmeticError as exc:      # the compiled law's own check failed
            raise CheckFailed(f"twin, steps {done}..{done + n - 1} (t from {done * h:.6g} "
                              f"s): {exc}") from exc
        times.append((time.perf_counter() - t0) / n)
        done += n
        bar.update(n)
    bar.close()
    rtl = {}
    if lockstep:
        from . import cosim
        if tcount[0] >= trace.shape[0]:
            raise ArithmeticError(f"{model.backend} trace full ({trace.shape[0]} previews)")
        be = model.backend
        kw = {"stencils": fit[4][:tcount[0]] if stencil else None}
        if be == "soc":
            kw["board"] = board
        if line:        # the line chain: its L codes and modes (ChainLineCore, line_core)
            kw["line"] = True
        replay = cosim.replay_on_rtl if be == "rtl" else cosim.replay_on_soc
        rtl = replay(trace[:tcount[0]], int(prm[K.P_ECODE]), **kw)
        if rtl[f"{be}_mismatches"]:
            hint = ("" if board is None else f" (was the board built with E' code "
                    f"{int(prm[K.P_ECODE])} MPa, this pair's?)")
            raise RtlMismatch(f"{be} != golden in {rtl[f'{be}_mismatches']} previews, "
                                  f"first at step {rtl[f'{be}_first_mismatch_step']}{hint}")
    wall = time.perf_counter() - wall0
    cols = {name: rec[:rows, i] for i, name in enumerate(K.RECORD_COLUMNS)}
    eps = np.interp(np.mod(cols["psi_p_rad"], m.pitch_rad), m.psi_rad, m.eps_rad)
    cols["te_arcsec"] = m.motion_sign * (eps - cols["theta_rad"]) * ARCSEC_PER_RAD
    if not np.all(np.isfinite(rec[:rows])):
        raise CheckFailed("twin: non-finite state (step too large for this load?)")
    sel = cols["t_s"] >= settle_fraction * dur
    if not sel.any():
        sel[:] = True
    t_mesh, w_mesh = cols["mesh_torque_nm"][sel], cols["mesh_load_n"][sel]
    static_t = model.torque_nm
    st = np.array(times) * 1e6
    summary = {
        "backend": model.backend,
        "curvatures": "table" if model.backend == "table" else model.curvatures,
        "steps": n_steps, "step_us": h_us, "duration_s": dur,
        "speed_rpm": speed, "torque_nm": model.torque_nm,
        "mesh_frequency_hz": m.pinion_teeth * speed / 60.0,
        "static_mesh_torque_nm": static_t, "static_mesh_load_n": float(w0.sum()),
        "mean_mesh_torque_nm": float(t_mesh.mean()), "mean_mesh_load_n": float(w_mesh.mean()),
        "dynamic_factor": float(t_mesh.max() / static_t),
        "contact_loss": float(np.mean(t_mesh == 0.0)),
        "dte_pp_arcsec": float(np.ptp(cols["te_arcsec"][sel])),
        "natural_frequencies_hz": [float(f) for f in freqs], "h_omega_max": h_omega,
        "mesh_damping_n_s_per_mm": c_m,
        **_bending_summary(model), **_domain_summary(model, tcount), **_law_summary(model),
        **_mode_summary(model),
        **_beyond_summary(model),
        "reverse_flank": model.reverse_note, **_free_play_summary(model),
        **{k: v for k, v in rtl.items() if not k.endswith(("_seconds", "_per_s"))}}
    timings = {"real_time_factor": dur / wall,
               "step_time_p50_us": float(np.percentile(st, 50)),
               "step_time_p99_us": float(np.percentile(st, 99)), "wall_s": wall,
               **{k: v for k, v in rtl.items() if k.endswith(("_seconds", "_per_s"))}}
    return TwinResult(cols, summary, freqs, timings)


def _domain_summary(model: TwinModel, tcount: np.ndarray) -> dict:
    """How many previews (and steps with one) lay outside the fixed-point datapath's
    domain, which law evaluated them, and how many had no contact law (:mod:`.kernel`):
    a result of the run, never an abort."""
    if model.backend == "table":
        return {}
    src = model.curvature_source
    fit = "the TCA's curvatures" if src == "exact" else "stage C's fp64 fit of the stencil"
    law = "the fp64 line chain (line contact or Hamrock-Brewe)" if src == LINE_SOURCE \
        else "fp64 Hamrock-Brewe" if model.hertz_form == DEFAULT_HERTZ_FORM \
        else "fp64 exact Hertz"
    return {"previews_outside_datapath": int(tcount[3]),
            "steps_outside_datapath": int(tcount[4]),
            "outside_datapath_evaluated_by": f"{law} on {fit}",
            "previews_without_contact_law": int(tcount[5])}


def _law_summary(model: TwinModel) -> dict:
    """Whether the Hertzian law holds on the loaded flank's rows (pairs x phases of the
    mesh table with an ellipse: its A-, B- > 0, the TCA's curvatures, which the stencil
    source fits closely): ``hertz_law_status`` ``beyond_hamrock_brewe_range``
    if a row's curvature ratio lies beyond where Hamrock–Brewe, the law of every preview
    backend (fp64, and the datapath's published form), is within 5 % of exact Hertz
    (:func:`gearcontact.preview.hertz.reference.law_status`, docs/hertz.md sec. 7), the
    count of such rows and the largest ratio; a reported result. Nothing for the table
    backend (no Hertzian law) or the line chain (cylindrical pairs: docs/cylindrical.md).
    With ``hertz_form="exact"`` the law is exact Hertz (:mod:`.exact_hertz`): status
    ``ok``, no row beyond, and the key ``hertz_form`` (absent for the default form, so
    that its ``twin.json`` is unchanged)."""
    if model.backend == "table" or model.curvature_source == LINE_SOURCE:
        return {}
    m = model.mesh
    ab = [(a, b) for a, b in zip(m.A_minus_per_mm[m.valid], m.B_minus_per_mm[m.valid])
          if min(a, b) > 0.0]
    beyond = sum(law_status(a, b, hertz_form=model.hertz_form) != LAW_OK for a, b in ab)
    form = {} if model.hertz_form == DEFAULT_HERTZ_FORM else {"hertz_form": model.hertz_form}
    return {**form, "hertz_law_status": LAW_BEYOND_RANGE if beyond else LAW_OK,
            "hertz_law_rows": len(ab), "hertz_law_rows_beyond_range": int(beyond),
            "hertz_law_ratio_max": max((max(a, b) / min(a, b) for a, b in ab), default=1.0)}


#: The contact law of an edge row (:mod:`.mesh`), as ``twin.json`` states it.
EDGE_CONTACT_LAW = ("opening and lever of the edge contact (edge-contact TCA); Hertzian law "
                    "of the pair's nearest surface contact along its path, its approach "
                    "scaled by the LCP on the edge's own field (the patch bounded by the "
                    "edge; surface rows whose ellipse a flank boundary cuts likewise, "
                    "against their untrimmed field), baked in as equivalent curvatures "
                    "(ltca.edge_law)")


def _mode_summary(model: TwinModel) -> dict:
    """How the loaded side's rows were found (:data:`.mesh.CONTACT_MODES`): valid rows
    per mode, edge rows per edge, phases whose transmitting pair (opening 0) is an
    edge contact, and the law of an edge row; nothing for a table without modes."""
    m = model.mesh
    if m.contact_mode is None:
        return {}
    rows = {name: int(np.sum(m.valid & (m.contact_mode == i)))
            for i, name in enumerate(CONTACT_MODES)}
    edges = m.edge_label[m.valid & (m.contact_mode == 1)]
    carry = m.valid & (m.opening_mm == 0.0) & (m.contact_mode == 1)
    out = {"mesh_rows_by_mode": rows,
           "mesh_edge_rows": {e: int(np.sum(edges == e)) for e in sorted(set(edges))},
           "transmitting_edge_phases": int(carry.any(axis=0).sum()),
           "mesh_phases": int(m.valid.shape[1]), "edge_contact_law": EDGE_CONTACT_LAW}
    if m.edge_compliance_scale is not None:
        c = m.edge_compliance_scale[m.valid]
        out["compliance_scaled_rows"] = int(np.sum(c != 1.0))
        out["compliance_scale_max"] = float(c.max()) if c.size else 1.0
        out["compliance_uncalibrated_rows"] = int(np.sum(m.edge_exponent[m.valid] == 0.0))
    if m.out_of_reach is not None:     # no touch search, no edge law (.mesh "reach")
        out["mesh_rows_out_of_reach"] = int(np.sum(m.valid & m.out_of_reach))
    return out


#: How a helical line's tip edge beyond its ends enters the twin, as ``twin.json`` states it.
BEYOND_LINE_LAW = ("edge slices of the line's slice law (ltca.slice_law): the tip edge "
                   "beyond the line's ends, its gap at the line's lever as the loaded TE's "
                   "edge rows beyond a line (ltca.cylindrical_edges.beyond_slices), adds "
                   "to the loaded length and interference on the foundation of the edge's "
                   "section against the mating flank (ltca.edge_section; "
                   "stiffness_relative_to_line), so to the line chain's W and "
                   "L_eq on every backend (rtl and soc replay those codes)")


def _beyond_summary(model: TwinModel) -> dict:
    """The loaded side's edge slices beyond its helical lines (:mod:`.line_law`): slices
    per end, their width, the valid rows with an edge point beyond a line end and the
    least gap of one (um, over the line's least); nothing without them (a spur pair,
    point contact)."""
    m = model.mesh
    if m.beyond_gap_mm is None:
        return {}
    g = np.where(m.valid[..., None, None], m.beyond_gap_mm, OFF_LINE_GAP_MM)
    hit = g < OFF_LINE_GAP_MM
    return {"beyond_line_edges": {
        "slices_per_end": int(g.shape[-1]), "slice_width_mm": float(m.beyond_width_mm),
        "stiffness_relative_to_line": float(m.beyond_stiffness),
        "rows": int(hit.any(axis=(2, 3)).sum()),
        "least_gap_um": float(1e3 * g[hit].min()) if hit.any() else None,
        "law": BEYOND_LINE_LAW}}


def _bending_summary(model: TwinModel) -> dict:
    """Whether tooth bending is in the law, and the mean pair bending compliance of the
    loaded side's valid pairs, mm/N."""
    cb = model.mesh.bending_mm_per_n
    on = cb is not None and bool(np.any(cb > 0.0))
    return {"bending": on, "bending_compliance_mean_mm_per_n":
            float(cb[model.mesh.valid].mean()) if on else 0.0}


def _free_play_summary(model: TwinModel) -> dict:
    """Normal free play between the loaded and the reverse flanks along the pitch, mm at
    the reference lever: geometric (the generated teeth) and total (+ backlash_mm)."""
    m, dt = model.mesh, model.drivetrain
    if model.reverse is None:
        return {"free_play_min_mm": dt.backlash_mm, "free_play_max_mm": dt.backlash_mm}
    from .mesh import free_play_rad
    geo = free_play_rad(m, model.reverse, m.psi_rad) * m.reference_lever_mm
    return {"geometric_free_play_min_mm": float(geo.min()),
            "geometric_free_play_max_mm": float(geo.max()),
            "free_play_min_mm": float(geo.min()) + dt.backlash_mm,
            "free_play_max_mm": float(geo.max()) + dt.backlash_mm}
