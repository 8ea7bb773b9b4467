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

Mesh torque, loaded flank (``theta >= 0``; the side the TCA ran on, e.g. coast for
s0003): the Hertzian pairs of the current phase, ``W_j`` from ``d_j = l_j theta - g_j >
0`` (else 0) by ``d_j = kappa_j W_j^(2/3) + c_b,j W_j`` (closed form
``W = (d/kappa)^(3/2)`` for rigid teeth, ``c_b = 0``; with the tooth-bending compliance
``c_b`` of :func:`.mesh.pair_bending_compliance` in series, Newton on ``s = W^(1/3)``),
``T_el = sum W_j l_j``, plus the mesh damping ``c_m l_0^2 theta'`` while a pair is
closed; the flanks cannot pull, so ``T = max(T_el + T_d, 0)``.

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

``kappa_j`` (mm / N^(2/3)) is the Hertzian approach coefficient ``delta = kappa W^(2/3)``
(Johnson 1985 sec. 4.2: the approach of two elastic bodies in point contact grows as
``W^(2/3)``; Hamrock & Brewe 1983 for the elliptical closed form), taken from one preview
per loaded pair and step -- at the phase of the step's start (again if a later RK4
stage enters the next phase interval) and at the pair's load of the previous step --
and held over the step's four stages: ``delta = 3 W F / (pi a E')`` with ``F = pi/2 +
(pi/2 - 1) ln alpha`` and ``alpha = k^(pi/2)`` (Hamrock–Brewe's ``k = alpha^(2/pi)``
inverted), i.e. from the preview's outputs ``a`` and ``k`` whatever backend computed
them. The curvatures the preview takes (``prm[P_STAGEC]``, :data:`CURVATURE_SOURCES`):

* ``stencil``: the whole C -> D preview per step -- the pair's 7 x 7 gap stencil at
  the step's phase (linear between the TCA rows), stage C's curvature fit, stage D.
  fp64: the fit is linear in the samples, so the rows' fitted coefficients c3, c4, c5
  are interpolated instead (identical, 3 values instead of 49) and the principal
  curvatures formed from them; golden: the interpolated samples are quantized to GAP
  codes and run through the bit-exact fit core (:func:`gearcontact.preview.fit.
  golden_vec.fit_element`) into the golden stage D, as the tri_core chain does;
* ``exact``: the TCA's shape-operator curvatures A-, B- interpolated between rows
  (the law of the loaded TE's preview, :mod:`gearcontact.ltca.lte`).

Per backend:

* ``reference`` (0): the fp64 Hamrock–Brewe forms, the package's one implementation
  (:func:`gearcontact.analytic.hertz.hamrock_brewe_terms`) compiled here;
* ``golden`` (1): the bit-exact fixed-point stage D (:func:`gearcontact.preview.hertz.
  golden_vec.hertz_element`) on the fit core's codes (stencil) or the round-half-up
  codes of A-, B- (exact), and W's;
* ``table`` (2): no preview; ``T_el`` from the offline loaded-TE table
  (:mod:`.ltca_table`);
* ``rtl`` / ``soc``: the golden loop, every preview traced and replayed on the RTL core
  (the C -> D chain core with stencils, the stage-D core without) or through the
  SoC's register driver (:mod:`.cosim`).

A preview outside the datapath's domain (B- below its curvature format, ratio beyond
alpha_max: ordinary long bearings) is a result, not an error: counted (previews, steps)
and evaluated by the fp64 Hamrock–Brewe law on the fp64 curvatures, by the reference
backend (the datapath would flag it) and the golden one (where its chain flags).

For Hertz ``kappa`` does not depend on the load (fp64: exactly); the fixed point adds its
rounding, and the load at which it is sampled is clamped to the datapath envelope
(:data:`W_EVAL_MIN_N` .. 2^17 N).

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
from numba.extending import overload

from ..analytic.hertz import hamrock_brewe_terms
from ..preview.fit.golden_vec import fit_element
from ..preview.fit.reference import principal_curvatures
from ..preview.hertz.golden_vec import hertz_element


@overload(math.cbrt)
def _cbrt_overload(x):   # numba 0.6x has no math.cbrt; libm cbrt is the same function
    return lambda x: np.cbrt(x)


_hb = njit(cache=True)(hamrock_brewe_terms)
#: The package's closed-form eigen-solve of the fitted quadric (stage C's last step).
_principal = njit(cache=True, inline="always")(principal_curvatures)

#: Contact backends; ``rtl`` and ``soc`` run the golden loop and replay its previews on
#: the RTL core / through the SoC register driver (:mod:`.cosim`).
BACKEND_CODES = {"reference": 0, "golden": 1, "table": 2, "rtl": 1, "soc": 1}
#: Smallest load at which a pair's preview is sampled, N (the datapath's envelope starts
#: at 1 N; a pair that just closes is sampled here).
W_EVAL_MIN_N = 1.0
_W_EVAL_MAX_N = 131072.0
_HB_E = 0.5 * math.pi - 1.0

# prm indices
(P_JM, P_JP, P_JG, P_JL, P_K1, P_K2, P_C1, P_C2, P_CM, P_THB, P_U, P_TM, P_TL, P_L0,
 P_EP, P_DPSI, P_PITCH, P_ECODE, P_NROW, P_KP, P_KI, P_OMEGA, P_DPSIR, P_NROWR, P_PSIR,
 P_CR, P_MIRROR, P_STAGEC, P_CLO, P_CHI, P_AHI) = range(31)
N_PRM = 31
#: Entries of the counters ``tcount``: trace rows written, step index of the trace rows,
#: steps, previews outside the datapath's domain, steps with such a preview, previews
#: without a contact law (:func:`run_steps`).
N_COUNT = 6
#: Curvature sources of the preview (``prm[P_STAGEC]``): the TCA's shape-operator
#: curvatures per row (``cv`` columns A-, B-), or stage C per step on the 7 x 7 stencil
#: (fp64: ``cv`` the fitted c3, c4, c5 per row; golden: ``cv`` the 49 gap samples).
CURVATURE_SOURCES = {"exact": 0, "stencil": 1}
_S16 = 65536.0
_S20 = 1048576.0
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


@njit(cache=True, error_model="numpy", _nrt=False)
def _kappa_golden(a_code, b_code, fit_flags, w, prm, pow_lut, cbrt_lut, cst, trace, tcount,
                  fit, out3):
    """kappa (mm/N^(2/3)) from the golden stage D on the curvature codes ``a_code <=
    b_code`` (Q(32,20)); out3 <- (a, b, p_max) at w_q. ``fit_flags``: the stage-C flags
    of the codes (0 without stage C), in bits 8.. of the traced flags word (the chain's,
    :mod:`gearcontact.preview.chain`); with stage C the stencil codes ``fit[2][0]`` are
    traced too (``fit[4]``)."""
    w_code = np.int64(math.floor(w * 256.0 + 0.5))
    flags, a_c, b_c, p_c, k_c, rx, ry, al = hertz_element(
        a_code, b_code, w_code, np.int64(prm[P_ECODE]), pow_lut, cbrt_lut, cst)
    flags |= fit_flags << 8
    t = tcount[0]
    if t < trace.shape[0]:      # the rtl backend replays these on the hardware
        trace[t, 0] = tcount[1]
        trace[t, 1] = a_code
        trace[t, 2] = b_code
        trace[t, 3] = w_code
        trace[t, 4] = flags
        trace[t, 5] = a_c
        trace[t, 6] = b_c
        trace[t, 7] = p_c
        trace[t, 8] = k_c
        tg = fit[4]
        if t < tg.shape[0]:
            for q in range(tg.shape[1]):
                tg[t, q] = fit[2][0, q]
        tcount[0] = t + 1
    if flags != 0 or a_c == 0 or k_c == 0:
        return -1.0
    a = a_c / _S20
    k = k_c / _S20
    wq = w_code / 256.0
    f = 0.5 * math.pi + _HB_E * (0.5 * math.pi) * math.log(k)
    delta = 3.0 * wq * f / (math.pi * a * prm[P_ECODE])
    out3[0] = a
    out3[1] = b_c / _S20
    out3[2] = p_c / 256.0
    return delta / wq ** (2.0 / 3.0)


@njit(cache=True, inline="always", error_model="numpy")
def _row(cv_t, s, j, i, f, q):
    """Column ``q`` of pair j's curvature source, linear between rows i and i + 1."""
    return cv_t[s, j, i, q] + f * (cv_t[s, j, i + 1, q] - cv_t[s, j, i, q])


@njit(cache=True, inline="always", error_model="numpy")
def _fp64_law(A, B, we, prm, tcount, out3, flagged):
    """kappa of the fp64 law on A-, B-; counts the preview in ``tcount[3]`` if it lies
    outside the datapath's domain (``flagged``: the golden chain said so; else
    ``prm[P_CLO..P_AHI]``, the curvature range and alpha_max of :data:`gearcontact.
    preview.hertz.reference.ENVELOPE`; the load is clamped into it by the caller), and
    returns -1, counted in ``tcount[5]``, without a contact law (a saddle, B- <= 0)."""
    lo, hi = min(A, B), max(A, B)
    if flagged or not (lo >= prm[P_CLO] and hi <= prm[P_CHI] and hi <= prm[P_AHI] * lo):
        tcount[3] += 1
    if lo <= 0.0:
        tcount[5] += 1
        return -1.0
    return _kappa_reference(A, B, we, prm, out3)


@njit(cache=True, inline="always", error_model="numpy")
def _kappa(s, j, i, f, we, prm, cv_t, backend, pow_lut, cbrt_lut, cst, trace, tcount, fit,
           out3):
    """kappa of pair j of table s at row interval (i, f) and evaluation load ``we``:
    the preview's stage D on the curvatures of the source ``prm[P_STAGEC]``
    (:data:`CURVATURE_SOURCES`); outside the datapath's domain the fp64 law
    (:func:`_fp64_law`; golden: on the TCA's curvatures, or on stage C's fp64 fit,
    ``cv_t`` columns ``N_TAPS..+3``); -1 without a contact law."""
    golden = backend != 0
    if prm[P_STAGEC] == 0.0:
        A, B = _row(cv_t, s, j, i, f, 0), _row(cv_t, s, j, i, f, 1)
        if golden:
            kap = _kappa_golden(np.int64(math.floor(min(A, B) * _S20 + 0.5)),
                                np.int64(math.floor(max(A, B) * _S20 + 0.5)), 0, we, prm,
                                pow_lut, cbrt_lut, cst, trace, tcount, fit, out3)
            if kap > 0.0:
                return kap
        return _fp64_law(A, B, we, prm, tcount, out3, golden)
    c0 = 0
    if golden:
        # the samples interpolated and quantized (GAP Q(32,16), round half up), the
        # bit-exact fit core, its latched codes into stage D (the C -> D chain)
        g = fit[2]
        for q in range(g.shape[1]):
            g[0, q] = np.int64(math.floor(_row(cv_t, s, j, i, f, q) * _S16 + 0.5))
        am, bm, ff = fit_element(g, 0, fit[0], fit[1], fit[3])
        if ff < 0:      # a sample beyond GAP's +-32768 mm: flagged like a coefficient overflow
            ff = 1
        kap = _kappa_golden(min(am, bm), max(am, bm), ff, we, prm, pow_lut, cbrt_lut, cst,
                            trace, tcount, fit, out3)
        if kap > 0.0:
            return kap
        c0 = g.shape[1]
        if cv_t.shape[3] < c0 + 3:      # no fp64 fit stacked with the samples
            return _fp64_law(0.0, 0.0, we, prm, tcount, out3, True)
    # stage C is linear in the samples: the fit of the samples interpolated between two
    # rows is the interpolation of the rows' fitted coefficients (exactly)
    A, B, _ = _principal(_row(cv_t, s, j, i, f, c0), _row(cv_t, s, j, i, f, c0 + 1),
                         _row(cv_t, s, j, i, f, c0 + 2))
    return _fp64_law(A, B, we, prm, tcount, out3, golden)


@njit(cache=True, error_model="numpy", _nrt=False)
def _kappa_reference(A, B, w, prm, out3):
    a, b, k, p, delta, alpha, e_e, f, r = _hb(min(A, B), max(A, B), w, prm[P_EP])
    out3[0] = a
    out3[1] = b
    out3[2] = p
    return delta / w ** (2.0 / 3.0)


@njit(cache=True, inline="always", error_model="numpy")
def _phase(psi, pitch, dpsi, nrow):
    """Row interval and fraction of the pinion angle psi (periodic in the pitch) on a
    table of ``nrow`` rows ``dpsi`` apart."""
    x = psi - pitch * math.floor(psi / pitch)
    u = x / dpsi
    i = min(int(u), int(nrow) - 2)     # rounding can put x/dpsi at K-1
    return i, u - i


@njit(cache=True, inline="always", error_model="numpy")
def _pair_load(d, kap, cb, s_prev):
    """(W N, s = W^(1/3)) of a pair at approach ``d`` (mm): Hertz ``d = kap W^(2/3)``
    alone (closed form; s is then not formed and returned as 0), or with the
    tooth-bending compliance ``cb`` (mm/N) in series, ``d = kap W^(2/3) + cb W``: Newton
    on ``f(s) = cb s^3 + kap s^2 - d = 0``. ``f`` is convex increasing for s > 0, so
    Newton from any s > 0 lands right of the root after at most one step and then falls
    monotonically to it; the start is the pair's previous solution ``s_prev`` (> 0; the
    load changes little per stage: 2-3 iterations), else ``min(sqrt(d/kap),
    cbrt(d/cb))`` (where ``f >= 0``). Stops at a relative step of 1e-14. Returning s
    saves the caller a cube root per pair and stage (the next start)."""
    x = d / kap
    if cb <= 0.0:
        return x * math.sqrt(x), 0.0
    s = s_prev if s_prev > 0.0 else min(math.sqrt(x), np.cbrt(d / cb))
    for _ in range(60):
        r = (cb * s + kap) * s * s - d
        ds = r / ((3.0 * cb * s + 2.0 * kap) * s)
        s -= ds
        if s <= 0.0:            # (only from a far start): restart where f >= 0
            s = min(math.sqrt(x), np.cbrt(d / cb))
        elif abs(ds) <= 1e-14 * s:
            break
    return s * s * s, s


@njit(cache=True, inline="always", error_model="numpy")
def _table_torque(theta, i, f, tab_theta, tab_t23, tab_w23):
    """(T_el N·m, W N) from the loaded-TE table at rows i, i+1 and rotation theta."""
    t_out = 0.0
    w_out = 0.0
    for r, wr in ((i, 1.0 - f), (i + 1, f)):
        th = tab_theta[r]
        n = th.shape[0]
        # segment through (0, 0) and the ladder; the last one extrapolates
        j = 0
        while j < n - 1 and theta > th[j]:
            j += 1
        if j == 0:
            x0, y0, z0 = 0.0, 0.0, 0.0
        else:
            x0, y0, z0 = th[j - 1], tab_t23[r, j - 1], tab_w23[r, j - 1]
        x1, y1, z1 = th[j], tab_t23[r, j], tab_w23[r, j]
        s = (theta - x0) / (x1 - x0)
        y = y0 + s * (y1 - y0)
        z = z0 + s * (z1 - z0)
        if y > 0.0:
            t_out += wr * y * math.sqrt(y)
        if z > 0.0:
            w_out += wr * z * math.sqrt(z)
    return t_out, w_out


@njit(cache=True, inline="always", error_model="numpy")
def _elastic(theta, i, f, s, sd, prm, lever, opening, cv_t, valid, cb_t, backend,
             w_eval, cache, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23,
             tab_w23, w_pairs, abp, out3):
    """Elastic mesh torque T_el (N·m) and total normal load (N) of one flank's law at
    its rotation theta >= 0 and row interval (i, f) of table ``s`` (0 loaded side, 1
    reverse side); per-pair loads into ``w_pairs[sd]``, (a, b, p) of the most loaded
    pair into ``abp[sd, 0:3]`` (zeros when none), ``abp[sd, 3]`` flags a pair without
    a contact law; ``w_eval[sd]``, ``cache[sd]`` are the slot's preview loads and
    cache, ``out3`` (3,) scratch. Plain indexing throughout (no array views in the
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
    for j in range(n_p):
        if not (valid[s, j, i] and valid[s, j, i + 1]):
            continue
        lv = lever[s, j, i] + f * (lever[s, j, i + 1] - lever[s, j, i])
        g = opening[s, j, i] + f * (opening[s, j, i + 1] - opening[s, j, i])
        d = lv * theta - g
        if d <= 0.0:
            continue
        if cache[sd, j, 0] != i:    # one preview per pair and step (and per new interval)
            we = min(max(w_eval[sd, j], W_EVAL_MIN_N), _W_EVAL_MAX_N)
            kap = _kappa(s, j, i, f, we, prm, cv_t, backend, pow_lut, cbrt_lut, cst, trace,
                         tcount, fit, out3)
            cache[sd, j, 0] = i
            cache[sd, j, 1] = kap
            cache[sd, j, 2] = out3[0]
            cache[sd, j, 3] = out3[1]
            cache[sd, j, 4] = out3[2]
            cache[sd, j, 5] = we
        kap = cache[sd, j, 1]
        if kap <= 0.0:      # no contact law (a saddle): counted by _kappa, reported
            abp[sd, 3] = 1.0
            continue
        we = cache[sd, j, 5]
        cb = cb_t[s, j, i] + f * (cb_t[s, j, i + 1] - cb_t[s, j, i])
        w, s_new = _pair_load(d, kap, cb, cache[sd, j, 6])
        if cb > 0.0:
            cache[sd, j, 6] = s_new
        w_pairs[sd, j] = w
        t_el += 1e-3 * w * lv
        w_tot += w
        if w > w_max:
            w_max = w
            scale = (w / we) ** (1.0 / 3.0)     # Hertz similarity a, b, p ~ W^(1/3)
            abp[sd, 0] = cache[sd, j, 2] * scale
            abp[sd, 1] = cache[sd, j, 3] * scale
            abp[sd, 2] = cache[sd, j, 4] * scale
    return t_el, w_tot


@njit(cache=True, inline="always", error_model="numpy")
def _flank(sd, theta, theta_dot, i, f, prm, lever, opening, cv_t, valid, cb_t, backend,
           w_eval, cache, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23,
           tab_w23, w_pairs, abp, out3, ip, fp):
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
                           tab_theta, tab_t23, tab_w23, w_pairs, abp, out3)
    if t_el <= 0.0:
        return 0.0, 0.0, w_tot
    l0 = prm[P_L0]
    # the flanks cannot pull: damping only while it does not reverse the contact force
    return max(t_el + 1e-3 * prm[P_CM] * l0 * l0 * theta_dot, 0.0), t_el, w_tot


@njit(cache=True, inline="always", error_model="numpy")
def _deriv(y, prm, eps, lever, opening, cv_t, valid, cb_t, backend, w_eval, cache,
           pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23, dy, row, w_pairs,
           abp, out3):
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
                            trace, tcount, fit, tab_theta, tab_t23, tab_w23, w_pairs, abp, out3, i, f)
    t_r, el_r, w_r = _flank(1, theta_r, theta_r_dot, ir, fr, prm, lever, opening, cv_t,
                            valid, cb_t, backend, w_eval, cache, pow_lut, cbrt_lut, cst,
                            trace, tcount, fit, tab_theta, tab_t23, tab_w23, w_pairs, abp, out3, i, f)
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
def _mesh_potential(theta, theta_r, psi, prm, lever, opening, cb_t, w_pairs):
    """Mesh potential of both flanks (J) at the loads in w_pairs."""
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
                cb = cb_t[s, j, i] + f * (cb_t[s, j, i + 1] - cb_t[s, j, i])
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
    :func:`_kappa`), ``[4]`` the steps with at least one, ``[5]`` the previews without
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
    out3 = np.zeros(3)
    cache = np.zeros((2, n_p, 7))     # preview per pair; column 6 the last W^(1/3)
    return _run(y, t0, n_steps, h, prm, eps, lever, opening, cv_t, valid, cb_t, backend,
                w_eval, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23,
                rec, rec_start, record_every, k, ys, pairs0, pairs1, abp0, abp1, out3, cache)


# Without the runtime's reference counting: every array is owned by run_steps, and the
# inlined helpers would otherwise pay an atomic incref/decref per array argument and
# call (measured ~200 ns per mesh evaluation, more than the evaluation itself). The
# loop indexes its arrays and never takes views of them.
@njit(cache=True, error_model="numpy", _nrt=False)
def _run(y, t0, n_steps, h, prm, eps, lever, opening, cv_t, valid, cb_t, backend, w_eval,
         pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23, tab_w23, rec, rec_start,
         record_every, k, ys, pairs0, pairs1, abp0, abp1, out3, cache):
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
                    k, st, pairs0, abp0, out3)
                if n % record_every == 0:
                    _record(rec, rec_start + rows, t0 + n * h, theta, theta_r, t_mesh, w_tot,
                            y, prm, lever, opening, cb_t, backend, pairs0, abp0)
                    rows += 1
                for sd in range(2):
                    for j in range(n_p):
                        if pairs0[sd, j] > 0.0:
                            w_eval[sd, j] = pairs0[sd, j]
            else:
                _deriv(ys, prm, eps, lever, opening, cv_t, valid, cb_t, backend, w_eval,
                       cache, pow_lut, cbrt_lut, cst, trace, tcount, fit, tab_theta, tab_t23,
                       tab_w23, k, st, pairs1, abp1, out3)
        for m in range(n_y):
            y[m] += h / 6.0 * (k[0, m] + 2.0 * k[1, m] + 2.0 * k[2, m] + k[3, m])
        if tcount[3] > outside:
            tcount[4] += 1
    return rows


@njit(cache=True, error_model="numpy", _nrt=False)
def _record(rec, r, t, theta, theta_r, t_mesh, w_tot, y, prm, lever, opening, cb_t, backend,
            w_pairs, abp):
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
                                  w_pairs) if backend != 2 else 0.0
    rec[r, R_D] = y[8]
    rec[r, R_WIN] = y[9]
    rec[r, R_WP] = y[5]
    rec[r, R_WG] = y[6]
