"""The twin's static operating point and linearised chain (:class:`~.model.TwinModel`).

Operating point: the motor torque balances the load (gear) torque through the ratio,
``T_m = T_l / u`` (no losses); the run starts from the static equilibrium at the first
phase (shaft twists ``T/k``, mesh rotation from the torque balance on the backend's
law, :func:`static_rotation`) with the members at the nominal speeds, so that what
follows is the response to the mesh excitation (unloaded TE and
the phase-varying stiffness).

The chain linearised there gives the undamped modes (:func:`linearized_modes`), the
mesh damping (:func:`mesh_damping_n_s_per_mm`), the speed controller's gains
(:func:`speed_controller_gains`) and the RK4 step bound (:func:`check_step`).
"""

from __future__ import annotations

import math

import numpy as np

from ..analytic.hertz import line_contact_approach_mm, line_contact_terms
from ..validation import InputRangeError, check_range
from . import kernel as K
from .layout import LINE_SOURCE, preview_scratch
from .model import TwinModel, _fit_args, _prm

__all__ = ["static_rotation", "linear_matrices", "linearized_modes", "mesh_damping_n_s_per_mm",
           "speed_controller_gains", "check_step", "STABILITY_LIMIT", "STEP_RANGE_US"]

#: Largest h omega_max accepted (RK4 limit 2.83 on the imaginary axis; kernel docstring).
STABILITY_LIMIT = 2.0
#: Accepted fixed steps, us.
STEP_RANGE_US = (1.0, 50.0)


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
             w_eval=None, cache=None) -> tuple[float, np.ndarray]:
    """Loaded-flank elastic torque (N·m) and pair loads (N) at (theta, psi); ``cache``
    (optional, (2, P, N_CACHE) of -1) receives the previews (:mod:`.kernel`'s layout:
    ``[:, j, 2:5]`` a, b, p_max)."""
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
                      np.full((2, n_p, K.N_CACHE), -1.0) if cache is None else cache,
                      a["pow_lut"], a["cbrt_lut"],
                      a["cst"], np.zeros((0, K.N_TRACE), np.int64),
                      np.zeros(K.N_COUNT, np.int64), _fit_args(a, 0), a["tab_theta"],
                      a["tab_t23"], a["tab_w23"], w, np.zeros((2, 4)),
                      np.zeros(preview_scratch(prm, n_p)))
    return t, w[0]



def static_rotation(model: TwinModel) -> tuple[float, np.ndarray]:
    """Mesh rotation theta (rad) and pair loads (N) that carry the load torque at the
    first phase, with the model's own contact law.

    Bisection on the backend's torque (golden: its rounding; table: its
    interpolation) from the bracket ``[0, 4 theta_1]``, ``theta_1 = (g_j + kappa_j
    (T / l_j)^(2/3)) / l_j`` the rotation at which the least open pair ``j`` alone
    carries the torque under the fp64 Hertz law (an upper bound of the balance of
    :func:`~gearcontact.ltca.lte_phase.preview_balance`), doubled until it holds the root.
    The bracket is closed form (no iterative solver) so that the drivetrain FMU's C
    (:mod:`gearcontact.export.fmu_drivetrain`) starts from the same bits. The line chain
    (a cylindrical pair) takes the approach of the line contact of the pair's line
    instead (:func:`~gearcontact.analytic.hertz.line_contact_approach_mm`).
    """
    m = model.mesh
    prm = _prm(model, 0.0)
    ok = np.flatnonzero(m.valid[:, 0] & m.valid[:, 1])
    # the least open pair (first of equals, as the C port's strict <)
    j = int(ok[np.argmin(m.opening_mm[ok, 0] / m.lever_mm[ok, 0])])
    lv, g = float(m.lever_mm[j, 0]), float(m.opening_mm[j, 0])
    w1 = 1e3 * model.torque_nm / lv
    if model.curvature_source == LINE_SOURCE:
        b_max = float(max(m.A_minus_per_mm[j, 0], m.B_minus_per_mm[j, 0]))
        length = float(m.line_length_mm[j, 0])
        _, b = line_contact_terms(b_max, w1, length, m.e_prime_mpa)
        th1 = (g + line_contact_approach_mm(w1, length, b, m.e_prime_mpa)) / lv
    else:
        kap = K._kappa_reference(float(m.A_minus_per_mm[j, 0]),
                                 float(m.B_minus_per_mm[j, 0]), prm, np.empty(K.N_PREVIEW))
        th1 = (g + kap * w1 ** (2.0 / 3.0)) / lv
    target = model.torque_nm
    lo, hi = 0.0, 4.0 * th1
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
