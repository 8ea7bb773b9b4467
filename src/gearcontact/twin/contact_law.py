"""The twin's contact law per backend (compiled with numba; called by :mod:`.kernel`).

Mesh torque, loaded flank (``theta >= 0``; the side the TCA ran on, e.g. coast for
s0003): the Hertzian pairs of the current phase, ``W_j`` from ``d_j = l_j theta - g_j >
0`` (else 0) by ``d_j = kappa_j W_j^(2/3) + c_b,j W_j`` (closed form
``W = (d/kappa)^(3/2)`` for rigid teeth, ``c_b = 0``; with the tooth-bending compliance
``c_b`` of :func:`gearcontact.ltca.tooth_bending.pair_bending_compliance` in series, Newton on ``s = W^(1/3)``),
``T_el = sum W_j l_j``, plus the mesh damping ``c_m l_0^2 theta'`` while a pair is
closed; the flanks cannot pull, so ``T = max(T_el + T_d, 0)``.

``kappa_j`` (mm / N^(2/3)) is the Hertzian approach coefficient ``delta = kappa W^(2/3)``
(Johnson 1985 sec. 4.2: the approach of two elastic bodies in point contact grows as
``W^(2/3)``; Hamrock & Brewe 1983 for the elliptical closed form), taken from one preview
per loaded pair and step -- at the phase of the step's start (of the first RK4 stage
that closes the pair, if a later one does) and at the pair's load of the previous step
-- and held over the step's four stages, also where a later stage enters the next phase
interval (the preview's count per step is the loaded pairs', a bounded step for a
real-time target; its kappa is continuous across the rows, so held one step it errs as
much as within a row): ``delta = 3 W F / (pi a E')`` with ``F = pi/2 +
(pi/2 - 1) ln alpha`` and ``alpha = k^(pi/2)`` (Hamrock–Brewe's ``k = alpha^(2/pi)``
inverted), i.e. from the preview's outputs ``a`` and ``k`` whatever backend computed
them. The curvatures the preview takes (``prm[P_STAGEC]``, :data:`~.layout.CURVATURE_SOURCES`):

* ``stencil``: the whole C -> D preview per step -- the pair's 7 x 7 gap stencil at
  the step's phase (linear between the TCA rows), stage C's curvature fit, stage D.
  fp64: the fit is linear in the samples, so the rows' fitted coefficients c3, c4, c5
  are interpolated instead (identical, 3 values instead of 49) and the principal
  curvatures formed from them; golden: the interpolated samples are quantized to
  STENCIL_GAP Q(32,21) codes and run through the bit-exact fit core
  (:func:`gearcontact.preview.fit.golden_vec.fit_element`) into the golden stage D, as
  the tri_core chain does;
* ``exact``: the TCA's shape-operator curvatures A-, B- interpolated between rows
  (the law of the loaded TE's preview, :mod:`gearcontact.ltca.lte`).

Per backend:

* ``reference`` (0): the fp64 Hamrock–Brewe forms, the package's one implementation
  (:func:`gearcontact.analytic.hertz.hamrock_brewe_terms`) compiled here; or, with the
  model's ``hertz_form="exact"`` (``prm[P_HFORM]``, reference backend only), exact
  elliptic Hertz interpolated in a table over the log curvature ratio
  (:mod:`.exact_hertz`, within 1e-8 of the exact solution);
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

For Hertz ``kappa`` does not depend on the load: the fp64 law takes it as the approach at
the unit load (1 N, ``delta = kappa W^(2/3)``), with a, b, p_max there (``pv``'s load,
:data:`~.layout.PV_LOAD`, says so), instead of ``delta(W_e) / W_e^(2/3)``: no power of
the load per preview, the same value to rounding. The fixed point adds its rounding at
the evaluation load, which is clamped to the datapath envelope (:data:`W_EVAL_MIN_N` ..
2^17 N).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numba.extending import overload

from ..analytic.cube_root import cbrt_positive
from ..analytic.hertz import hamrock_brewe_terms
from ..analytic.series_contact import series_pair_load
from ..contract.qformat import STENCIL_GAP
from ..preview.fit.golden_vec import fit_element
from ..preview.fit.reference import principal_curvatures
from ..preview.hertz.golden_vec import hertz_element
from .exact_hertz import RATIO_MAX, exact_hertz_terms
from .layout import N_PRM, P_AHI, P_CHI, P_CLO, P_ECODE, P_EP, P_HFORM, P_STAGEC, PV_LOAD

@overload(math.cbrt)
def _cbrt_overload(x):
    # numba 0.6x has no math.cbrt. The Hamrock-Brewe law's cube root (hamrock_brewe_terms'
    # math.cbrt) compiles as the seed polynomial and Halley step of the exported C
    # (analytic.cube_root, within 5 ulp of the root; ~35 instead of ~130 instructions in
    # the drivetrain FMU, which repeats this law bit for bit)
    return lambda x: _cbrt_positive(x)


_cbrt_positive = njit(cache=True, inline="always", error_model="numpy")(cbrt_positive)


_hb = njit(cache=True)(hamrock_brewe_terms)
#: The package's closed-form eigen-solve of the fitted quadric (stage C's last step).
_principal = njit(cache=True, inline="always")(principal_curvatures)
#: Smallest load at which a pair's preview is sampled, N (the datapath's envelope starts
#: at 1 N; a pair that just closes is sampled here).
W_EVAL_MIN_N = 1.0
_W_EVAL_MAX_N = 131072.0
_HB_E = 0.5 * math.pi - 1.0
#: Scale of a stencil sample's STENCIL_GAP code (2^21 per mm), of a curvature code (2^20).
_S_GAP = math.ldexp(1.0, STENCIL_GAP.frac)
_S20 = 1048576.0


@njit(cache=True, error_model="numpy", _nrt=False)
def _kappa_golden(a_code, b_code, fit_flags, w, prm, pow_lut, cbrt_lut, cst, trace, tcount,
                  fit, out3):
    """kappa (mm/N^(2/3)) from the golden stage D on the curvature codes ``a_code <=
    b_code`` (Q(32,20)) at the load w; out3 <- (a, b, p_max) at w_q, out3[PV_LOAD] <- w
    (the twin scales a, b, p from there). ``fit_flags``: the stage-C flags
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
    wq = w_code / 256.0
    out3[0] = a
    out3[1] = b_c / _S20
    out3[2] = p_c / 256.0
    out3[PV_LOAD] = w
    return hertz_kappa(a, k_c / _S20, wq, prm[P_ECODE])


@njit(cache=True, inline="always", error_model="numpy")
def hertz_kappa(a, k, w, e_prime):
    """kappa (mm/N^(2/3)) of a preview's semi-axis ``a`` (mm) and ellipticity ``k`` at
    the load ``w`` (N, a positive normal double): Hamrock-Brewe's approach ``3 W F /
    (pi a E')``, ``F = pi/2 + (pi/2 - 1) ln alpha``, ``alpha = k^(pi/2)`` (module
    docstring), over ``w^(2/3)``, i.e. ``3 F w^(1/3) / (pi a E')``.

    ``w^(1/3)`` is the library's cube root (:func:`gearcontact.analytic.cube_root.
    cbrt_positive`, within 5 ulp), not libm's ``pow(w, 2/3)`` and a division (~120
    instructions per preview in the drivetrain FMU, which repeats this function bit for
    bit: ``gc_contact_law.c``'s ``kappa_golden``). Against the exact formula on the same
    (a, k, w) (the golden domain: ``k = b/a >= 1``, so ``F >= pi/2`` and ``ln k``'s
    rounding enters F with weight <= 1) within 11 ulp (2^-52 relative each): the cube
    root 5, ``ln k`` 1, F's roundings and constants 2, the five products and the
    division 3; measured 2.7 (tests/twin/test_kernel.py, against mpmath)."""
    f = 0.5 * math.pi + _HB_E * (0.5 * math.pi) * math.log(k)
    return 3.0 * f * _cbrt_positive(w) / (math.pi * a * e_prime)


@njit(cache=True, inline="always", error_model="numpy")
def _row(cv_t, s, j, i, f, q):
    """Column ``q`` of pair j's curvature source, linear between rows i and i + 1."""
    return cv_t[s, j, i, q] + f * (cv_t[s, j, i + 1, q] - cv_t[s, j, i, q])


@njit(cache=True, inline="always", error_model="numpy")
def _fp64_law(A, B, prm, tcount, out3, flagged):
    """kappa of the fp64 law on A-, B- (:func:`_kappa_reference`); counts the preview in
    ``tcount[3]`` if it lies outside the datapath's domain (``flagged``: the golden chain
    said so; else ``prm[P_CLO..P_AHI]``, the curvature range and alpha_max of
    :data:`gearcontact.preview.hertz.reference.ENVELOPE`), and returns -1, counted in
    ``tcount[5]``, without a contact law (a saddle, B- <= 0; with the exact form, a
    curvature ratio beyond :data:`~.exact_hertz.RATIO_MAX`)."""
    lo, hi = min(A, B), max(A, B)
    if flagged or not (lo >= prm[P_CLO] and hi <= prm[P_CHI] and hi <= prm[P_AHI] * lo):
        tcount[3] += 1
    if lo <= 0.0 or (prm[P_HFORM] != 0.0 and hi > RATIO_MAX * lo):
        tcount[5] += 1      # a saddle, or (exact form) beyond the exact table's ratios
        return -1.0
    return _kappa_reference(A, B, prm, out3)


@njit(cache=True, inline="always", error_model="numpy")
def _kappa(s, j, i, f, we, prm, cv_t, backend, pow_lut, cbrt_lut, cst, trace, tcount, fit,
           out3):
    """kappa of pair j of table s at row interval (i, f) and evaluation load ``we``:
    the preview's stage D on the curvatures of the source ``prm[P_STAGEC]``
    (:data:`~.layout.CURVATURE_SOURCES`); outside the datapath's domain the fp64 law
    (:func:`_fp64_law`; golden: on the TCA's curvatures, or on stage C's fp64 fit,
    ``cv_t`` columns ``N_TAPS..+3``); -1 without a contact law."""
    golden = backend != 0
    if prm[P_STAGEC] == 0.0:
        A, B = _row(cv_t, s, j, i, f, 0), _row(cv_t, s, j, i, f, 1)
        if golden:
            kap = _kappa_golden(np.int64(math.floor(min(A, B) * _S20 + 0.5)),
                                np.int64(math.floor(max(A, B) * _S20 + 0.5)),
                                np.int64(0), we, prm,   # as ff's type below: one compile
                                pow_lut, cbrt_lut, cst, trace, tcount, fit, out3)
            if kap > 0.0:
                return kap
        return _fp64_law(A, B, prm, tcount, out3, golden)
    c0 = 0
    if golden:
        # the samples interpolated and quantized (STENCIL_GAP, round half up), the
        # bit-exact fit core, its latched codes into stage D (the C -> D chain)
        g = fit[2]
        for q in range(g.shape[1]):
            g[0, q] = np.int64(math.floor(_row(cv_t, s, j, i, f, q) * _S_GAP + 0.5))
        am, bm, ff = fit_element(g, 0, fit[0], fit[1], fit[3])
        if ff < 0:      # a sample beyond +-1024 mm: flagged like a coefficient overflow
            ff = 1
        kap = _kappa_golden(min(am, bm), max(am, bm), ff, we, prm, pow_lut, cbrt_lut, cst,
                            trace, tcount, fit, out3)
        if kap > 0.0:
            return kap
        c0 = g.shape[1]
        if cv_t.shape[3] < c0 + 3:      # no fp64 fit stacked with the samples
            return _fp64_law(0.0, 0.0, prm, tcount, out3, True)
    # stage C is linear in the samples: the fit of the samples interpolated between two
    # rows is the interpolation of the rows' fitted coefficients (exactly)
    A, B, _ = _principal(_row(cv_t, s, j, i, f, c0), _row(cv_t, s, j, i, f, c0 + 1),
                         _row(cv_t, s, j, i, f, c0 + 2))
    return _fp64_law(A, B, prm, tcount, out3, golden)


@njit(cache=True, error_model="numpy", _nrt=False)
def _kappa_reference(A, B, prm, out3):
    """kappa (mm/N^(2/3)) of the fp64 law on A-, B- > 0 (1/mm): the approach at W = 1 N
    (``delta = kappa W^(2/3)`` in the closed form: no power of the load); out3 <- (a, b,
    p_max) at 1 N, ``out3[PV_LOAD]`` <- 1. The law: Hamrock-Brewe's forms, or with
    ``prm[P_HFORM]`` = 1 exact Hertz from the table that follows ``prm[N_PRM]``
    (:func:`~.exact_hertz.exact_hertz_terms`; the caller keeps the ratio within
    :data:`~.exact_hertz.RATIO_MAX`)."""
    if prm[P_HFORM] != 0.0:
        a, b, p, delta = exact_hertz_terms(min(A, B), max(A, B), 1.0, prm[P_EP], prm, N_PRM)
    else:
        a, b, k, p, delta, alpha, e_e, f, r = _hb(min(A, B), max(A, B), 1.0, prm[P_EP])
    out3[0] = a
    out3[1] = b
    out3[2] = p
    out3[PV_LOAD] = 1.0
    return delta




#: (W, W^(1/3)) of a pair at an approach, Hertz with tooth bending in series: the
#: loaded TE's preview takes the same function (:mod:`gearcontact.analytic.series_contact`).
_pair_load = njit(cache=True, inline="always", error_model="numpy")(series_pair_load)


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


