"""The drivetrain twin: model set-up, static operating point, linearised modes, time run.

A :class:`TwinModel` joins the drivetrain (:mod:`.params`), the mesh of the pair
(:mod:`.mesh`; and for the ``table`` backend the loaded-TE table of :mod:`.ltca_table`)
and one contact backend; :func:`simulate` integrates it at a fixed step with the
compiled loop of :mod:`.kernel` (equations and integrator documented there).

Operating point: the motor torque balances the load (gear) torque through the ratio,
``T_m = T_l / u`` (no losses); the run starts from the static equilibrium at the first
phase (shaft twists ``T/k``, mesh rotation from the Hertzian torque balance of
:func:`gearcontact.ltca.lte.preview_balance`) with the members at the nominal
speeds, so that what follows is the response to the mesh excitation (unloaded TE and
the phase-varying stiffness).

Tooth bending (switchable: ``mesh_table(..., bending=...)``, ``model_for_pair(...,
bending=True)``, ``gearcontact twin --bending``): each pair's bending compliance of the
pinion and gear tooth (:func:`~.mesh.pair_bending_compliance`, the shell operator of
:mod:`gearcontact.ltca.tooth_bending` weighted by the pair's Hertz pressure) is in
series with its Hertzian approach, ``d_j = kappa_j W_j^(2/3) + c_b,j W_j``, solved per
pair and step in the kernel; without it the teeth are rigid.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from tqdm import tqdm

from ..ltca.lte import preview_balance
from ..ltca.pair_ltca import ARCSEC_PER_RAD
from ..errors import CheckFailed, RtlMismatch
from ..preview.fit.golden import element_constants
from ..preview.fit.pinv import N_COEFFS, N_TAPS, baked_pinv
from ..preview.hertz.golden import encode_e_prime
from ..preview.hertz.golden_vec import golden_constants
from ..preview.hertz.reference import ENVELOPE
from ..validation import InputRangeError, check_array_finite, check_positive, check_range
from . import kernel as K
from .mesh import MeshTable
from .params import DrivetrainParams

__all__ = ["TwinModel", "TwinResult", "build_model", "model_for_pair", "simulate",
           "linearized_modes", "linear_matrices", "check_step", "static_rotation",
           "speed_controller_gains",
           "mesh_damping_n_s_per_mm", "BACKENDS", "CURVATURE_SOURCES", "STABILITY_LIMIT",
           "STEP_RANGE_US", "MAX_SPEED_RPM",
           "LOCKSTEP_MAX_STEPS"]

BACKENDS = tuple(K.BACKEND_CODES)
#: Curvature sources of the preview (:class:`TwinModel` ``curvatures``).
CURVATURE_SOURCES = tuple(K.CURVATURE_SOURCES)
#: Largest h omega_max accepted (RK4 limit 2.83 on the imaginary axis; kernel docstring).
STABILITY_LIMIT = 2.0
#: Accepted fixed steps, us.
STEP_RANGE_US = (1.0, 50.0)
#: Highest pinion speed a run accepts, rpm.
MAX_SPEED_RPM = 1e5
_CHUNK = 256          # steps per compiled call: the step-time percentiles' granularity
#: Longest lockstep runs (the trace holds every preview; the SoC driver takes ~0.3 s per
#: preview in simulation), steps.
LOCKSTEP_MAX_STEPS = {"rtl": 200_000, "soc": 1_000}


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
                reverse_note: str = "", curvatures: str = "stencil") -> TwinModel:
    """Check the inputs and pack the compiled loop's arrays.

    Tooth bending comes with the mesh tables (their ``bending_mm_per_n``).

    Curvatures outside the fixed-point datapath's domain are not refused: the run
    counts and reports the previews that leave it (:func:`simulate`).

    Raises
    ------
    InputRangeError
        Unknown backend or curvature source, ``table`` backend without a table, torque
        <= 0, a designed backlash that does not clear an interference of the generated
        flanks.
    """
    if backend not in BACKENDS:
        raise InputRangeError("backend", backend, f"one of {list(BACKENDS)}")
    if curvatures not in CURVATURE_SOURCES:
        raise InputRangeError("curvatures", curvatures, f"one of {list(CURVATURE_SOURCES)}")
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
              "fit_w": fit_w, "fit_cst": fit_cst}
    return TwinModel(mesh, drivetrain, backend, t, table, arrays, reverse, reverse_note,
                     curvatures)


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
    """(P, K, C) curvature source of one table (:func:`_stack`)."""
    if source == "exact":
        return np.stack([mesh.A_minus_per_mm, mesh.B_minus_per_mm], axis=-1)
    if golden:      # the samples for the fit core, the fp64 fit for the fp64 fallback
        return np.concatenate([np.asarray(mesh.stencil_gaps_mm, float),
                               _fitted_coefficients(mesh)], axis=-1)
    return _fitted_coefficients(mesh)


def _fitted_coefficients(mesh: MeshTable) -> np.ndarray:
    """fp64 stage-C coefficients c3, c4, c5 (1/mm) of every row's stencil (P, K, 3): the
    fit of :func:`gearcontact.preview.fit.reference.fit_curvatures` (the baked ROM's
    weights), for all rows at once."""
    return np.asarray(mesh.stencil_gaps_mm, float) @ baked_pinv().weights[3:6].T


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
    prm[K.P_STAGEC] = K.CURVATURE_SOURCES[model.curvature_source]
    prm[K.P_CLO], prm[K.P_CHI] = ENVELOPE["curvature_per_mm"]
    prm[K.P_AHI] = ENVELOPE["alpha"][1]
    return prm


def speed_controller_gains(model: TwinModel) -> tuple[float, float]:
    """PI gains ``(K_p N·m·s/rad, K_i N·m/rad)`` of the motor speed controller, (0, 0)
    when ``speed_control_bandwidth_hz`` is 0 (constant motor torque).

    Designed on the rigid chain (inertia reflected to the motor ``J = J_m + J_p + (J_g +
    J_l)/u^2``): ``K_p = 2 pi f_c J``, ``K_i = K_p 2 pi f_c / 4``, which places both
    closed-loop poles at ``-pi f_c`` (critically damped, ``s^2 J + K_p s + K_i = 0``);
    the bandwidth must stay below a third of the first elastic mode so that the rigid
    design holds.

    Raises
    ------
    InputRangeError
        ``speed_control_bandwidth_hz`` >= f_1 / 3.
    """
    dt, m = model.drivetrain, model.mesh
    f_c = dt.speed_control_bandwidth_hz
    if f_c == 0.0:
        return 0.0, 0.0
    f1 = float(linearized_modes(model)[1])
    if f_c >= f1 / 3.0:
        raise InputRangeError("drivetrain.speed_control_bandwidth_hz", f_c,
                              f"< {f1 / 3.0:.4g} Hz (a third of the first mode {f1:.4g} Hz)")
    j = (dt.motor_inertia_kgm2 + dt.pinion_inertia_kgm2
         + (dt.gear_inertia_kgm2 + dt.load_inertia_kgm2) / m.ratio ** 2)
    kp = 2.0 * math.pi * f_c * j
    return kp, kp * 2.0 * math.pi * f_c / 4.0


def _elastic(model: TwinModel, prm, theta: float, psi: float = 0.0,
             w_eval=None) -> tuple[float, np.ndarray]:
    """Loaded-flank elastic torque (N·m) and pair loads (N) at (theta, psi)."""
    a = model.arrays
    n_p = a["lever"].shape[1]
    w_ev = np.full((2, n_p), 1e3)
    if w_eval is not None:
        w_ev[0] = w_eval
    w = np.zeros((2, n_p))
    x = float(np.mod(psi, prm[K.P_PITCH])) / prm[K.P_DPSI]      # as kernel._phase
    i = min(int(x), int(prm[K.P_NROW]) - 2)
    t, _ = K._elastic(theta, i, x - i, 0, 0, prm, a["lever"], a["opening"], a["cv"],
                      a["valid"], a["cb"], K.BACKEND_CODES[model.backend], w_ev,
                      np.full((2, n_p, 7), -1.0), a["pow_lut"], a["cbrt_lut"], a["cst"],
                      np.zeros((0, 9), np.int64), np.zeros(K.N_COUNT, np.int64), _fit_args(a, 0),
                      a["tab_theta"], a["tab_t23"], a["tab_w23"], w, np.zeros((2, 4)),
                      np.zeros(3))
    return t, w[0]


def _fit_args(a: dict, trace_rows: int) -> tuple:
    """The kernel's ``fit`` tuple: the golden stage C's ROM and constants, its scratch,
    and a stencil trace of ``trace_rows`` rows (:func:`.kernel.run_steps`)."""
    return (a["fit_w"], a["fit_cst"], np.zeros((1, N_TAPS), np.int64),
            np.zeros((1, N_COEFFS), np.int64), np.zeros((trace_rows, N_TAPS), np.int64))


def static_rotation(model: TwinModel) -> tuple[float, np.ndarray]:
    """Mesh rotation theta (rad) and pair loads (N) that carry the load torque at the
    first phase, with the model's own contact law.

    The Hertzian balance of :func:`~gearcontact.ltca.lte.preview_balance` gives the
    starting point; it is then refined by bisection on the backend's torque (golden:
    its rounding; table: its interpolation).
    """
    m = model.mesh
    prm = _prm(model, 0.0)
    ok = m.valid[:, 0] & m.valid[:, 1]
    kap = np.array([K._kappa_reference(a, b, 1e3, prm, np.empty(3)) for a, b in
                    zip(m.A_minus_per_mm[ok, 0], m.B_minus_per_mm[ok, 0])])
    th0, _ = preview_balance(m.lever_mm[ok, 0], m.opening_mm[ok, 0], kap,
                             1e3 * model.torque_nm)
    target = model.torque_nm
    lo, hi = 0.0, 4.0 * th0
    while _elastic(model, prm, hi)[0] < target:
        hi *= 2.0
    w_eval = np.full(model.arrays["lever"].shape[1], 1e3)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        t, w = _elastic(model, prm, mid, w_eval=w_eval)
        w_eval = np.where(w > 0, w, w_eval)
        if t < target:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * hi:
            break
    return hi, _elastic(model, prm, hi, w_eval=w_eval)[1]


def _mesh_stiffness(model: TwinModel, prm, theta: float) -> float:
    """Linearised mesh stiffness dT/dtheta at the first phase, N·m/rad (central
    difference, 1e-4 relative step: the torque is smooth there)."""
    d = 1e-4 * theta
    return (_elastic(model, prm, theta + d)[0] - _elastic(model, prm, theta - d)[0]) / (2 * d)


def linear_matrices(model: TwinModel) -> tuple[np.ndarray, np.ndarray, float]:
    """Mass and stiffness matrices (4x4, SI) of the chain linearised at the static point
    of the first phase, and the mesh stiffness k_theta (N·m/rad).

    Coordinates ``psi_m, psi_p, psi_g, psi_l``; the mesh couples ``psi_p`` and ``psi_g``
    through ``theta = psi_p (1/u + eps') - psi_g``.
    """
    dt, m = model.drivetrain, model.mesh
    prm = _prm(model, 0.0)
    theta, _ = static_rotation(model)
    k_th = _mesh_stiffness(model, prm, theta)
    de = (m.eps_rad[1] - m.eps_rad[0]) / m.step_rad
    v = np.array([0.0, 1.0 / m.ratio + de, -1.0, 0.0])
    k1, k2 = dt.input_stiffness_nm_per_rad, dt.output_stiffness_nm_per_rad
    stiff = k_th * np.outer(v, v)
    stiff[0:2, 0:2] += k1 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    stiff[2:4, 2:4] += k2 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    mass = np.diag([dt.motor_inertia_kgm2, dt.pinion_inertia_kgm2, dt.gear_inertia_kgm2,
                    dt.load_inertia_kgm2])
    return mass, stiff, k_th


def linearized_modes(model: TwinModel) -> np.ndarray:
    """Undamped natural frequencies of the linearised chain, Hz, ascending (the rigid
    mode 0 included): ``sqrt(eig(M^-1 K)) / 2 pi``."""
    mass, stiff, _ = linear_matrices(model)
    lam = np.linalg.eigvals(np.linalg.solve(mass, stiff)).real
    return np.sort(np.sqrt(np.clip(lam, 0.0, None))) / (2.0 * math.pi)


def mesh_damping_n_s_per_mm(model: TwinModel) -> float:
    """``c_m = 2 zeta_m sqrt(k_m m_e)`` along the reference line of action, N·s/mm, with
    ``k_m = k_theta / l_0^2`` and ``m_e`` the two members' inertias on their levers
    ``l_0 / u`` (pinion) and ``l_0`` (gear)."""
    dt, m = model.drivetrain, model.mesh
    _, _, k_th = linear_matrices(model)
    l0 = 1e-3 * m.reference_lever_mm
    k_m = k_th / l0 ** 2
    m_p = dt.pinion_inertia_kgm2 / (l0 / m.ratio) ** 2
    m_g = dt.gear_inertia_kgm2 / l0 ** 2
    m_e = m_p * m_g / (m_p + m_g)
    return 1e-3 * 2.0 * dt.mesh_damping_ratio * math.sqrt(k_m * m_e)


def check_step(model: TwinModel, step_s: float) -> tuple[np.ndarray, float]:
    """Linearised modes (Hz) and ``h omega_max``; raises :class:`InputRangeError`
    (field ``step_us``) when the step is outside :data:`STEP_RANGE_US` or ``h omega_max
    >`` :data:`STABILITY_LIMIT`."""
    h_us = check_range("step_us", 1e6 * float(step_s), *STEP_RANGE_US)
    freqs = linearized_modes(model)
    h_omega = 1e-6 * h_us * 2.0 * math.pi * float(freqs[-1])
    if h_omega > STABILITY_LIMIT:
        h_max = STABILITY_LIMIT / (2.0 * math.pi * freqs[-1]) * 1e6
        raise InputRangeError("step_us", h_us, f"<= {h_max:.3g} us (RK4 stability: h omega_max"
                              f" <= {STABILITY_LIMIT}, highest mode {freqs[-1]:.4g} Hz)")
    return freqs, h_omega


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
        nothing). Statistics over the recorded steps after ``settle_fraction``.
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
        Non-finite state or a lockstep mismatch.
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
    trace = np.zeros(((n_steps * (n_p + 2)) if lockstep else 0, 9), np.int64)
    tcount = np.zeros(K.N_COUNT, np.int64)
    stencil = prm[K.P_STAGEC] == K.CURVATURE_SOURCES["stencil"]
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
        rows += K.run_steps(y, done * h, n, h, *args, w_eval, *tail, rec, rows, record_every)
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
        **_bending_summary(model), **_domain_summary(model, tcount),
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
    fit = ("the TCA's curvatures" if model.curvature_source == "exact"
           else "stage C's fp64 fit of the stencil")
    return {"previews_outside_datapath": int(tcount[3]),
            "steps_outside_datapath": int(tcount[4]),
            "outside_datapath_evaluated_by": f"fp64 Hamrock-Brewe on {fit}",
            "previews_without_contact_law": int(tcount[5])}


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


def model_for_pair(pair, *, torque_nm: float, backend: str = "reference",
                   drivetrain: DrivetrainParams | None = None, side: str = "drive",
                   phases: int = 61, table_source: str = "lcp", table_cells: int = 32,
                   bending: bool = False, curvatures: str = "stencil",
                   progress: bool = False) -> TwinModel:
    """TCA of ``pair``, its mesh table and (``table`` backend) the loaded-TE table, then
    :func:`build_model`. ``drivetrain`` None uses :func:`~.params.default_drivetrain`.
    The TCA is surface-to-surface (``edge_contact=False``: the Hertzian law has no
    meaning at an edge touching the other flank). The reverse flank is the other side's
    own TCA (mirrored loaded law if that side is in line contact). ``bending``: tooth bending of both members in series with the
    Hertzian law of both sides (:func:`~.mesh.pair_bending_compliance`). ``curvatures``:
    the preview's curvature source (:class:`TwinModel`)."""
    from ..tca.analysis import analyze_pair
    from ..tca.line_contact import LineContact
    from .ltca_table import torque_table
    from .mesh import mesh_table
    from .params import default_drivetrain

    t = check_positive("torque_nm (N·m)", torque_nm)
    if backend not in BACKENDS:     # before the expensive stages
        raise InputRangeError("backend", backend, f"one of {list(BACKENDS)}")
    if curvatures not in CURVATURE_SOURCES:
        raise InputRangeError("curvatures", curvatures, f"one of {list(CURVATURE_SOURCES)}")
    from ..ltca.tooth_bending import tooth_bending

    # Surface-to-surface TCA (edge_contact=False): the twin's contact law is Hertzian,
    # and an edge touching the other flank has no Hertzian law; pairs beyond the end of
    # their path enter as edge pairs resolved on their posed fields, as in the loaded TE
    tca, flanks = analyze_pair(pair, side=side, phases=phases, edge_contact=False,
                               progress=progress)
    bend = (lambda s: tooth_bending(flanks, pair, side=s)) if bending else (lambda s: None)
    mesh = mesh_table(tca, flanks, pair, side=side, torque_nm=t, bending=bend(side))
    other = "coast" if side == "drive" else "drive"
    reverse, note = None, ""
    try:
        rtca, _ = analyze_pair(pair, side=other, phases=phases, flanks=flanks,
                               edge_contact=False, progress=progress)
        reverse = mesh_table(rtca, flanks, pair, side=other, torque_nm=t,
                             bending=bend(other))
    except LineContact as exc:     # conjugate flanks: no contact ellipse to load
        note = (f"loaded side's law mirrored about backlash_mm: the {other} flanks are in "
                f"line contact ({str(exc).split(';')[0]}), outside the Hertzian preview")
    table = None
    if backend == "table":
        table = torque_table(tca, flanks, pair, mesh, t, side=side, source=table_source,
                             cells=table_cells, bending=bend(side), progress=progress)
    return build_model(mesh, drivetrain or default_drivetrain(pair), t, backend=backend,
                       table=table, reverse=reverse, reverse_note=note,
                       curvatures=curvatures)
