"""Compiled (numba) step loop of the twin: contact law per backend and the RK4 integrator.

State (SI, angles along the motion, absolute): ``y = [psi_m, psi_p, psi_g, psi_l,
w_m, w_p, w_g, w_l, D, W_in, I]`` with ``D`` the energy dissipated by the dampers,
``W_in`` the work of the motor and load torques (J), integrated with the motion so that
the energy balance is checked to the integrator's order, and ``I`` the integral of the
motor speed error (rad) of the optional PI speed controller::

    T_m = T_l / u + K_p (Omega - w_m) + K_i I,       I' = Omega - w_m

Equations of motion (torques N·m; module :mod:`.simulate` for the parameters)::

    J_m w_m' = T_m - k1 (psi_m - psi_p) - c1 (w_m - w_p)
    J_p w_p' = k1 (psi_m - psi_p) + c1 (w_m - w_p) - T_mesh (1/u + eps'(psi_p))
    J_g w_g' = T_mesh - k2 (psi_g - psi_l) - c2 (w_g - w_l)
    J_l w_l' = k2 (psi_g - psi_l) + c2 (w_g - w_l) - T_l

with the mesh rotation ``theta = psi_p/u + eps(psi_p) - psi_g`` (:mod:`.mesh`); the
pinion's factor ``1/u + eps'`` is ``d theta / d psi_p``, which makes the mesh
conservative in the unloaded TE (the torque is the derivative of the mesh potential).


Reverse flank (torque reversal through the backlash): its own table (index 1 of the
stacked arrays, the other side's TCA: levers, openings, curvatures, TE0, bending) along
its own pinion angle ``psi_r = c_r - psi_p`` and its own closure ``theta_r = psi_g -
psi_p/u + eps_r(psi_r) - C - theta_b`` (:func:`.mesh.reverse_law`: ``C`` from the two
TCA data, so the geometric free play between the flanks is in it; ``theta_b =
backlash / l_0`` is the designed backlash added to it); it pushes the gear back and the
pinion forward through its own ``d theta_r / d psi_p``. Where the other side has no
contact ellipse (line contact), ``P_MIRROR`` makes it the loaded law mirrored about
``theta_b`` (``theta_r = -theta - theta_b``). In between both flanks the teeth fly free
(``T_mesh = 0``, contact loss). Nothing divides by a load or an approach, so contact
loss gives 0, never NaN.

The contact law that gives the loaded flank its torque, per backend, is
:mod:`.contact_law`; the layout of ``prm``, ``y``, the counters and the record is
:mod:`.layout` (its names are re-exported here, the kernel's interface).


Integrator: classical 4th-order Runge–Kutta at a fixed step ``h`` (4 mesh evaluations per
step). Linear stability on the imaginary axis (undamped modes): ``h omega <= 2 sqrt(2)
~ 2.83`` (Hairer & Wanner, Solving ODEs II, sec. IV.2); :mod:`.simulate` requires
``h omega_max <= 2.0`` at the linearised static operating point, margin for the
Hertzian stiffening at dynamic overload (``k ~ W^(1/3)``, ``omega ~ W^(1/6)``: the RK4
limit is reached only at 8x the static load). Global error O(h^4) where the force is smooth; the contact opening/closing
and the phase-table kinks reduce it locally to O(h).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# the contact law's entry points and the layout, re-exported as the kernel's interface
from .contact_law import (W_EVAL_MIN_N, _W_EVAL_MAX_N, _kappa, _kappa_reference,  # noqa: F401
                          _pair_load, _table_torque)
from ..ltca.coupled_slice_law import core_scratch
from .line_law import MODE_LINE, _line_law, line_pair_load, line_potential_j
from .layout import (  # noqa: F401
                     LINE_SOURCE_CODE, N_CACHE, N_PREVIEW, N_TRACE, PV_LINE_BENDING,
                     PV_LINE_OFFSET, PV_LOAD,
                     BACKEND_CODES, CURVATURE_SOURCES, HERTZ_FORM_CODES, N_COUNT, N_PRM,
                     N_REC, N_STATE, P_AHI, P_BEYOND_W, P_C1, P_C2, P_CHI, P_CLO, P_CM,
                     P_CR, P_DPSI, P_DPSIR, P_ECODE, P_EP, P_HFORM, P_JG, P_JL, P_JM, P_JP,
                     P_K1, P_K2, P_KI, P_KP,
                     P_L0, P_MIRROR, P_NBEYOND, P_NROW, P_NROWR, P_NSLICE, P_OMEGA,
                     P_SLICE_CB, P_PITCH, P_PSIR, P_STAGEC, P_THB, P_TL,
                     P_TM, P_U, RECORD_COLUMNS, R_A, R_B, R_D, R_KE, R_NPAIRS, R_P, R_PE,
                     R_PSI, R_T, R_THETA, R_TMESH, R_V, R_W, R_WG, R_WIN, R_WP)


@njit(cache=True, inline="always", error_model="numpy")
def _phase(psi, pitch, dpsi, nrow):
    """Row interval and fraction of the pinion angle psi (periodic in the pitch) on a
    table of ``nrow`` rows ``dpsi`` apart."""
    x = psi - pitch * math.floor(psi / pitch)
    u = x / dpsi
    i = min(int(u), int(nrow) - 2)     # rounding can put x/dpsi at K-1
    return i, u - i




@njit(cache=True, inline="always", error_model="numpy")
def _elastic(theta, i, f, s, sd, prm, lever, opening, cv_t, valid, cb_t, backend,
             w_eval, cache, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23,
             tab_w23, w_pairs, abp, pv):
    """Elastic mesh torque T_el (N·m) and total normal load (N) of one flank's law at
    its rotation theta >= 0 and row interval (i, f) of table ``s`` (0 loaded side, 1
    reverse side); per-pair loads into ``w_pairs[sd]``, (a, b, p) of the most loaded
    pair into ``abp[sd, 0:3]`` (zeros when none), ``abp[sd, 3]`` flags a pair without
    a contact law; ``w_eval[sd]``, ``cache[sd]`` are the slot's preview loads and
    cache, ``pv`` (:data:`~.layout.N_PREVIEW`,) the preview's outputs (scratch). Plain indexing throughout (no array views in the
    loop compiled without the runtime's reference counting)."""
    n_p = lever.shape[1]
    t_el = 0.0
    w_tot = 0.0
    abp[sd, 0] = 0.0
    abp[sd, 1] = 0.0
    abp[sd, 2] = 0.0
    abp[sd, 3] = 0.0
    for j in range(n_p):
        w_pairs[sd, j] = 0.0
    if backend == 2:
        return _table_torque(theta, i, f, tab_theta, tab_t23, tab_w23)
    w_max = 0.0
    line = prm[P_STAGEC] == LINE_SOURCE_CODE
    for j in range(n_p):
        if not (valid[s, j, i] and valid[s, j, i + 1]):
            continue
        lv = lever[s, j, i] + f * (lever[s, j, i + 1] - lever[s, j, i])
        g = opening[s, j, i] + f * (opening[s, j, i + 1] - opening[s, j, i])
        d = lv * theta - g
        if d <= 0.0:
            continue
        # one preview per pair and step, held into the next row interval (its kappa is
        # continuous across the row); again on any other row (the pitch's wrap relabels
        # the pairs; a row back)
        r = cache[sd, j, 0]
        if r < 0.0 or (i != r and i != r + 1.0):
            we = min(max(w_eval[sd, j], W_EVAL_MIN_N), _W_EVAL_MAX_N)
            pv[3] = 0.0
            pv[4] = 0.0
            pv[PV_LOAD] = we
            pv[PV_LINE_OFFSET] = 0.0
            pv[PV_LINE_BENDING] = -1.0
            if line:    # sampled at the slice law's load of the approach d (.line_law)
                cb0 = cache[sd, j, 10]      # the pair's last, else minus the uniform's
                if not cb0 > 0.0:
                    cb0 = -(cb_t[s, j, i] + f * (cb_t[s, j, i + 1] - cb_t[s, j, i]))
                # np.int64(s): one compiled _line_law for both flanks (a literal 0 from
                # _flank(0, ...) compiled a second copy; docs/performance.md, "Session 28")
                kap = _line_law(np.int64(s), sd * n_p + j, j, i, f, d, cb0, we, prm, cv_t,
                                backend, pow_lut, cbrt_lut, cst, trace, tcount, fit, pv)
            else:
                kap = _kappa(s, j, i, f, we, prm, cv_t, backend, pow_lut, cbrt_lut, cst,
                             trace, tcount, fit, pv)
            cache[sd, j, 0] = i
            cache[sd, j, 1] = kap
            cache[sd, j, 2] = pv[0]
            cache[sd, j, 3] = pv[1]
            cache[sd, j, 4] = pv[2]
            cache[sd, j, 5] = pv[PV_LOAD]     # the load of a, b, p
            cache[sd, j, 7] = pv[3]
            cache[sd, j, 8] = pv[4]
            cache[sd, j, 9] = pv[PV_LINE_OFFSET]
            cache[sd, j, 10] = pv[PV_LINE_BENDING]
        kap = cache[sd, j, 1]
        if kap <= 0.0:      # no contact law (a saddle): counted by _kappa, reported
            abp[sd, 3] = 1.0
            continue
        we = cache[sd, j, 5]
        cb = cache[sd, j, 10]       # the coupled law's secant (line chain with bending)
        if cb < 0.0:
            cb = cb_t[s, j, i] + f * (cb_t[s, j, i + 1] - cb_t[s, j, i])
        in_line = cache[sd, j, 7] == MODE_LINE
        if in_line:     # the line law (.line_law): kap is its lambda, d from h_bar on
            d -= cache[sd, j, 9]
            if d <= 0.0:
                continue
            w = line_pair_load(d, kap, cache[sd, j, 8], cb, cache[sd, j, 6])
            cache[sd, j, 6] = w
        else:
            w, s_new = _pair_load(d, kap, cb, cache[sd, j, 6])
            if cb > 0.0:
                cache[sd, j, 6] = s_new
        w_pairs[sd, j] = w
        t_el += 1e-3 * w * lv
        w_tot += w
        if w > w_max:
            w_max = w
            # similarity: Hertz a, b, p ~ W^(1/3); line a = L/2, b, p ~ W^(1/2)
            scale = (w / we) ** (0.5 if in_line else 1.0 / 3.0)
            abp[sd, 0] = cache[sd, j, 2] * (1.0 if in_line else scale)
            abp[sd, 1] = cache[sd, j, 3] * scale
            abp[sd, 2] = cache[sd, j, 4] * scale
    return t_el, w_tot


@njit(cache=True, inline="always", error_model="numpy")
def _flank(sd, theta, theta_dot, i, f, prm, lever, opening, cv_t, valid, cb_t, backend,
           w_eval, cache, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23,
           tab_w23, w_pairs, abp, pv, ip, fp):
    """(T N·m >= 0, T_el N·m, W N) of flank ``sd`` (0: loaded side, 1: reverse) at its
    rotation theta and rate theta_dot; 0 out of contact (``theta < 0``). The table
    backend and a mirrored reverse law use the loaded side's rows (ip, fp)."""
    if theta < 0.0:
        for j in range(w_pairs.shape[1]):
            w_pairs[sd, j] = 0.0
        abp[sd, 0] = 0.0
        abp[sd, 1] = 0.0
        abp[sd, 2] = 0.0
        return 0.0, 0.0, 0.0
    s = 0 if prm[P_MIRROR] != 0.0 else sd
    if s == 0 or backend == 2:      # the table holds the loaded side's rows only
        i, f = ip, fp
    t_el, w_tot = _elastic(theta, i, f, s, sd, prm, lever, opening, cv_t, valid, cb_t,
                           backend, w_eval, cache, pow_lut, cbrt_lut, cst, trace, tcount, fit,
                           tab_theta, tab_t23, tab_w23, w_pairs, abp, pv)
    if t_el <= 0.0:
        return 0.0, 0.0, w_tot
    l0 = prm[P_L0]
    # the flanks cannot pull: damping only while it does not reverse the contact force
    return max(t_el + 1e-3 * prm[P_CM] * l0 * l0 * theta_dot, 0.0), t_el, w_tot


@njit(cache=True, inline="always", error_model="numpy")
def _deriv(y, prm, eps, lever, opening, cv_t, valid, cb_t, backend, w_eval, cache,
           pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23, dy, row, w_pairs,
           abp, pv):
    """dy/dt into dy[row]; returns (theta, theta_r, T_mesh N·m, total normal load N)."""
    u = prm[P_U]
    psi_p = y[1]
    pitch = prm[P_PITCH]
    i, f = _phase(psi_p, pitch, prm[P_DPSI], prm[P_NROW])
    e = eps[0, i] + f * (eps[0, i + 1] - eps[0, i])
    de = (eps[0, i + 1] - eps[0, i]) / prm[P_DPSI]
    theta = psi_p / u + e - y[2]
    theta_dot = y[5] * (1.0 / u + de) - y[6]
    # reverse flank: its own table along its own motion psi_r = c_r - psi_p
    if prm[P_MIRROR] != 0.0:
        ir, fr, der = i, f, de
        theta_r = -theta - prm[P_THB]
    else:
        ir, fr = _phase(prm[P_PSIR] - psi_p, pitch, prm[P_DPSIR], prm[P_NROWR])
        er = eps[1, ir] + fr * (eps[1, ir + 1] - eps[1, ir])
        der = (eps[1, ir + 1] - eps[1, ir]) / prm[P_DPSIR]
        theta_r = y[2] - psi_p / u + er - prm[P_CR] - prm[P_THB]
    theta_r_dot = y[6] - y[5] * (1.0 / u + der)
    t_p, el_p, w_p = _flank(0, theta, theta_dot, i, f, prm, lever, opening, cv_t,
                            valid, cb_t, backend, w_eval, cache, pow_lut, cbrt_lut, cst,
                            trace, tcount, fit, tab_theta, tab_t23, tab_w23, w_pairs, abp, pv, i, f)
    t_r, el_r, w_r = _flank(1, theta_r, theta_r_dot, ir, fr, prm, lever, opening, cv_t,
                            valid, cb_t, backend, w_eval, cache, pow_lut, cbrt_lut, cst,
                            trace, tcount, fit, tab_theta, tab_t23, tab_w23, w_pairs, abp, pv, i, f)
    t_mesh = t_p - t_r
    tw1 = prm[P_K1] * (y[0] - y[1]) + prm[P_C1] * (y[4] - y[5])
    tw2 = prm[P_K2] * (y[2] - y[3]) + prm[P_C2] * (y[6] - y[7])
    dy[row, 0] = y[4]
    dy[row, 1] = y[5]
    dy[row, 2] = y[6]
    dy[row, 3] = y[7]
    # motor: constant torque T_l/u, plus the PI speed controller when its gains are set
    t_m = prm[P_TM] + prm[P_KP] * (prm[P_OMEGA] - y[4]) + prm[P_KI] * y[10]
    dy[row, 4] = (t_m - tw1) / prm[P_JM]
    # each flank acts through d theta / d psi_p of its own law (conservative in its TE)
    dy[row, 5] = (tw1 - t_p * (1.0 / u + de) + t_r * (1.0 / u + der)) / prm[P_JP]
    dy[row, 6] = (t_mesh - tw2) / prm[P_JG]
    dy[row, 7] = (tw2 - prm[P_TL]) / prm[P_JL]
    # dissipated power: shaft dampers + the non-elastic part of each flank's torque (the
    # damper, or the clamp that keeps the flanks from pulling), (T - T_el) theta'
    p_mesh = (t_p - el_p) * theta_dot + (t_r - el_r) * theta_r_dot
    dw1 = y[4] - y[5]
    dw2 = y[6] - y[7]
    dy[row, 8] = prm[P_C1] * dw1 * dw1 + prm[P_C2] * dw2 * dw2 + p_mesh
    dy[row, 9] = t_m * y[4] - prm[P_TL] * y[7]
    dy[row, 10] = prm[P_OMEGA] - y[4]
    return theta, theta_r, t_mesh, w_p + w_r


@njit(cache=True, inline="always", error_model="numpy")
def _pair_potential(w, d, cb):
    """Mesh potential of one pair at load w (N) and approach d (mm), J: the integral of
    W dd, ``(2/5) kap W^(5/3) + (1/2) cb W^2`` with ``kap W^(2/3) = d - cb W``."""
    return 1e-3 * (0.4 * (d - cb * w) * w + 0.5 * cb * w * w)


@njit(cache=True, error_model="numpy", _nrt=False)
def _mesh_potential(theta, theta_r, psi, prm, lever, opening, cb_t, w_pairs, cache):
    """Mesh potential of both flanks (J) at the loads in w_pairs (each pair's law in
    ``cache``: Hertz, or the line law's lambda in column 1 where column 7 says line)."""
    pitch = prm[P_PITCH]
    v = 0.0
    for sd in range(2):
        th = theta if sd == 0 else theta_r
        if th < 0.0:
            continue
        mirror = prm[P_MIRROR] != 0.0
        s = 0 if (sd == 0 or mirror) else 1
        if s == 0:
            i, f = _phase(psi, pitch, prm[P_DPSI], prm[P_NROW])
        else:
            i, f = _phase(prm[P_PSIR] - psi, pitch, prm[P_DPSIR], prm[P_NROWR])
        for j in range(lever.shape[1]):
            w = w_pairs[sd, j]
            if w > 0.0:
                lv = lever[s, j, i] + f * (lever[s, j, i + 1] - lever[s, j, i])
                g = opening[s, j, i] + f * (opening[s, j, i + 1] - opening[s, j, i])
                cb = cache[sd, j, 10]
                if cb < 0.0:
                    cb = cb_t[s, j, i] + f * (cb_t[s, j, i + 1] - cb_t[s, j, i])
                if cache[sd, j, 7] == MODE_LINE:
                    v += line_potential_j(w, lv * th - g - cache[sd, j, 9], cb,
                                          cache[sd, j, 1])
                else:
                    v += _pair_potential(w, lv * th - g, cb)
    return v


@njit(cache=True, error_model="numpy")
def run_steps(y, t0, n_steps, h, prm, eps, lever, opening, cv_t, valid, cb_t, backend,
              w_eval, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23, rec,
              rec_start, record_every):
    """Advance ``y`` (in place) by ``n_steps`` RK4 steps of ``h`` s from time ``t0``.

    The mesh arrays are stacked per flank: index 0 the loaded side, 1 the reverse
    side (``eps`` (2, K), ``lever, opening, valid, cb_t`` (2, P, K) with ``cb_t`` the
    tooth-bending compliance per pair, mm/N, 0 for rigid teeth; ``cv_t`` (2, P, K, C)
    the preview's curvature source per row, :data:`CURVATURE_SOURCES`).
    ``fit = (weights (6, 49), constants (9,), stencil scratch (1, 49), coefficient
    scratch (1, 6), stencil trace (rows, 49))``, int64: the golden stage C
    (:func:`gearcontact.preview.fit.golden_vec.fit_element`; its ROM and constants).
    Rows ``rec[rec_start + n // record_every]`` receive the state at the start of every
    ``record_every``-th step (columns :data:`RECORD_COLUMNS`); ``w_eval`` (2, P) carries
    the pair loads of both flanks from step to step (the loads at which the preview is
    sampled). ``trace`` (int64, rows x 9) receives every golden stage-D evaluation while
    rows remain, ``[step, A_code, B_code, W_code, flags, a_code, b_code, p_max_code,
    k_code]`` (A <= B the stage-D inputs; with stage C the flags word is the chain's and
    the stencil trace receives the 49 gap codes), counted in ``tcount[0]``; a trace of
    0 rows records nothing. ``tcount`` (:data:`N_COUNT`): ``[2]`` counts the steps,
    ``[3]`` the previews outside the datapath's domain (evaluated by the fp64 law,
    :func:`~.contact_law._kappa`), ``[4]`` the steps with at least one, ``[5]`` the previews without
    a contact law (the pair then carries nothing). Returns the number of rows written
    to ``rec``.
    """
    n_y = y.shape[0]
    n_p = lever.shape[1]
    if n_y != N_STATE:
        raise ValueError("run_steps: the state vector must have N_STATE entries")
    k = np.zeros((4, n_y))      # RK4 stage derivatives
    ys = np.zeros(n_y)
    pairs0 = np.zeros((2, n_p))     # pair loads per flank: stage 0 (recorded), later stages
    pairs1 = np.zeros((2, n_p))
    abp0 = np.zeros((2, 4))
    abp1 = np.zeros((2, 4))
    # layout.preview_scratch, compiled
    m = int(prm[P_NSLICE]) + 2 * int(prm[P_NBEYOND])
    pv = np.zeros(N_PREVIEW + 2 * m + core_scratch(m) + 2 * n_p * (m + 1))
    # preview per pair: interval, law, a, b, p, their load, the last W^(1/3) (Hertz) or W
    # (line), mode, the line law's beta, its approach offset h_bar and bending
    # compliance (-1: the table's c_b) (N_CACHE columns)
    cache = np.zeros((2, n_p, N_CACHE))
    return _run(y, t0, n_steps, h, prm, eps, lever, opening, cv_t, valid, cb_t, backend,
                w_eval, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23,
                rec, rec_start, record_every, k, ys, pairs0, pairs1, abp0, abp1, pv, cache)


# Without the runtime's reference counting: every array is owned by run_steps, and the
# inlined helpers would otherwise pay an atomic incref/decref per array argument and
# call (measured ~200 ns per mesh evaluation, more than the evaluation itself). The
# loop indexes its arrays and never takes views of them.
@njit(cache=True, error_model="numpy", _nrt=False)
def _run(y, t0, n_steps, h, prm, eps, lever, opening, cv_t, valid, cb_t, backend, w_eval,
         pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23, rec, rec_start,
         record_every, k, ys, pairs0, pairs1, abp0, abp1, pv, cache):
    n_y = y.shape[0]
    n_p = lever.shape[1]
    rows = 0
    for n in range(n_steps):
        for sd in range(2):
            for j in range(n_p):
                cache[sd, j, 0] = -1.0      # a fresh preview of every loaded pair each step
        tcount[1] = tcount[2]       # step index of the trace rows
        tcount[2] += 1
        outside = tcount[3]
        for st in range(4):
            if st == 0:
                for m in range(n_y):
                    ys[m] = y[m]
            else:
                c = 1.0 if st == 3 else 0.5
                for m in range(n_y):
                    ys[m] = y[m] + c * h * k[st - 1, m]
            if st == 0:
                theta, theta_r, t_mesh, w_tot = _deriv(
                    ys, prm, eps, lever, opening, cv_t, valid, cb_t, backend, w_eval,
                    cache, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23,
                    k, st, pairs0, abp0, pv)
                if n % record_every == 0:
                    _record(rec, rec_start + rows, t0 + n * h, theta, theta_r, t_mesh, w_tot,
                            y, prm, lever, opening, cb_t, backend, pairs0, abp0, cache)
                    rows += 1
                for sd in range(2):
                    for j in range(n_p):
                        if pairs0[sd, j] > 0.0:
                            w_eval[sd, j] = pairs0[sd, j]
            else:
                _deriv(ys, prm, eps, lever, opening, cv_t, valid, cb_t, backend, w_eval,
                       cache, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23,
                       tab_w23, k, st, pairs1, abp1, pv)
        for m in range(n_y):
            y[m] += h / 6.0 * (k[0, m] + 2.0 * k[1, m] + 2.0 * k[2, m] + k[3, m])
        if tcount[3] > outside:
            tcount[4] += 1
    return rows


@njit(cache=True, error_model="numpy", _nrt=False)
def _record(rec, r, t, theta, theta_r, t_mesh, w_tot, y, prm, lever, opening, cb_t, backend,
            w_pairs, abp, cache):
    """One row of :data:`RECORD_COLUMNS` (state at the start of a step)."""
    n_p = lever.shape[1]
    rec[r, R_T] = t
    rec[r, R_THETA] = theta
    rec[r, R_PSI] = y[1]
    rec[r, R_TMESH] = t_mesh
    rec[r, R_W] = w_tot
    sd = 0 if abp[0, 0] >= abp[1, 0] else 1     # the flank in contact (a > 0)
    rec[r, R_A] = abp[sd, 0]
    rec[r, R_B] = abp[sd, 1]
    rec[r, R_P] = abp[sd, 2]
    cnt = 0
    for s in range(2):
        for j in range(n_p):
            if w_pairs[s, j] > 0.0:
                cnt += 1
    rec[r, R_NPAIRS] = cnt
    rec[r, R_KE] = 0.5 * (prm[P_JM] * y[4] ** 2 + prm[P_JP] * y[5] ** 2
                          + prm[P_JG] * y[6] ** 2 + prm[P_JL] * y[7] ** 2)
    rec[r, R_PE] = 0.5 * (prm[P_K1] * (y[0] - y[1]) ** 2 + prm[P_K2] * (y[2] - y[3]) ** 2)
    rec[r, R_V] = _mesh_potential(theta, theta_r, y[1], prm, lever, opening, cb_t,
                                  w_pairs, cache) if backend != 2 else 0.0
    rec[r, R_D] = y[8]
    rec[r, R_WIN] = y[9]
    rec[r, R_WP] = y[5]
    rec[r, R_WG] = y[6]
