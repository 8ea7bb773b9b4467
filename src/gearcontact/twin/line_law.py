"""The twin's contact law on a cylindrical pair: the preview's line chain per loaded pair
and step (compiled with numba; called by :mod:`.kernel`; docs/cylindrical.md sec. 10).

The flanks of a spur or helical pair touch along lines, which the preview answers with
the *line chain* (:mod:`gearcontact.preview.chain`: stage C on the pair's 7 x 7 gap
stencil into the line core of stage D with the equivalent length ``L_eq`` of the
pair's contact line, below; docs/hertz.md sec. 6): in ``elliptic`` mode (the ellipse
fits the line, or its peak is the higher bound) or in ``line`` mode (the Hertz line
contact of length ``L_eq``). One preview per loaded pair and step, at the phase of the
step's start and the pair's load ``W_e`` of the previous step (as :mod:`.contact_law`),
gives the law held over the step's four stages, ``d = d_c(W) + c_b W`` (``c_b`` the
tooth-bending compliance, 0 for rigid teeth; ``d`` the approach at the line's least
gap):

* ``elliptic``: Hertz ``d_c = kappa W^(2/3)``, ``kappa`` from the preview's ``a`` and
  ``k`` by Hamrock-Brewe's approach (:func:`.contact_law.hertz_kappa`);
* ``line``: the approach of the finite line on the two half-spaces
  (:func:`gearcontact.analytic.hertz.line_contact_approach_mm`) over the part of the
  line that carries load, ``d_c = h_bar + lambda W (beta - ln(W)/2)`` with ``lambda = 4 /
  (pi E' L_c)`` and ``beta = ln(4 L_c / b_e) - 3/4 + ln(W_e)/2``: the preview's
  half-width ``b_e`` at ``W_e`` carried to ``W`` by the line contact's similarity ``b ~
  W^(1/2)`` at fixed ``L_c`` (``L_c = 2 a``, the preview's half-length). Solved per pair
  and stage by Newton on ``W`` (:func:`line_pair_load`).

The loaded length ``L_c`` and the offset ``h_bar`` come from the ease-off along the
line (crowning, relief, misalignment: the mesh table's ``line_gap_mm``, the normal gap
over the line's least at the centres of ``n`` equal slices, linear between them): at
the approach ``d_c`` the line carries load where its gap lies below ``d_c``, ``L_c =
|{h < d_c}|``, with the interference ``I(d_c) = integral(max(d_c - h, 0) dy)`` carried
by the finite line's modulus (a Winkler foundation whose stiffness per length is that
of the line law, so that a flat line is the uniform line exactly)::

    I(d_c) = 4 W / (pi E') (ln(4 L_c / b) - 3/4),   b = b(W, L_c)

On a crowned line (gap ``A y^2``) this is the exact elongated Hertz ellipse's approach
within -3.2 % (as the uniform line against the LCP of a finite cylinder) with a loaded
length 1.08 x Hertz's ``2 a`` (tests/ltca/test_slice_law.py). Per preview (once per
pair and step, at ``W_e``) the slice law (:func:`gearcontact.ltca.slice_law.loaded_line`,
the function ``analyze``'s cylindrical preview evaluates too) solves it for ``d_c`` and
``L_c``. The line chain reports the peak of the slice law's line load, ``w_peak = W_e
d_c / I`` where the line's gap is least (a triangle's ``2 W / L_c`` on an end-loaded
wedge, ``W / L`` on a flat line): stage D takes ``W`` and ``L``, so it runs on the
equivalent length ``L_eq = W_e / w_peak = I / d_c``
(:func:`gearcontact.ltca.slice_law.equivalent_length`; golden and RTL see the same
``L`` code, traced), and its ``p_max = (w_peak E' B_max / pi)^(1/2)`` and ``b`` are those
of the peak line load (``a`` is reported as ``L_c / 2``). The law is the uniform line of
``W`` on ``L_c``, not on ``L_eq``: its ``beta`` takes the chain's ``b`` to ``L_c`` by the
line contact's ``b ~ (W / L)^(1/2)`` (:func:`_line_coefficient`). The step's law is
``I`` linearised at ``d_c`` (``dI/dd = L_c``): ``L_c (d_c - h_bar) = lambda' W (...)``,
``h_bar = d_c - I(d_c) / L_c``, the uniform line's law shifted by ``h_bar``, exact at
``W_e``. On a helical pair the tip edge beyond either end of the line (mesh table
``beyond_gap_mm``, ``prm[P_NBEYOND]`` slices per end ``prm[P_BEYOND_W]`` mm wide) adds
two runs of slices to ``I`` and ``L_c`` (:func:`gearcontact.ltca.slice_law.
interference`): an edge point carries where the approach exceeds its gap, on the
foundation of the edge's own section against the mating flank (``prm[P_BEYOND_W]`` is
the slices' width times its stiffness relative to the line's,
:func:`gearcontact.ltca.edge_section.edge_stiffness_factor`), as the loaded TE's edge
rows beyond a line join its block.
With tooth bending the preview solves the coupled slice law at the step's approach
(:func:`gearcontact.ltca.coupled_slice_law.coupled_solve`, the law ``analyze``'s
cylindrical preview runs at a load: ``w = K (d - h - G f)``, ``G`` the shells' Gram
matrix at the slices, mesh table ``line_bending_gram_mm_per_n``): the teeth's
deflection under the slice forces joins the ease-off, ``x = h + G f``, and the state
above is the slice law's on ``x`` (``d_c`` over its least). The step's law holds the
bending's secant compliance ``c_b = (d - d_c) / W_e`` in series, ``d = d_c(W) + c_b W``
(exact at the preview's ``W_e``, as the contact part; ``G = c 1 1^T``: ``c_b = c``, the
series law). The coupled law starts from the series state with the pair's last
``c_b`` (a fresh preview: the mesh table's uniform-load compliance).

Per backend (the codes of :data:`~.layout.BACKEND_CODES`):

* ``reference`` (0): the fp64 line chain -- stage C's fit interpolated between the
  rows (it is linear in the samples), its principal curvatures, the fit's resolution
  rule for ``B- ~ 0`` (:func:`gearcontact.preview.chain.line_b_minus`), the line
  contact (:func:`gearcontact.analytic.hertz.line_contact_terms`), Hamrock-Brewe's
  ellipse where the datapath evaluates one (ratio within its POW table) and the line
  core's SELECT (:func:`gearcontact.preview.hertz.reference.keeps_ellipse`);
* ``golden`` (1): the stencil samples interpolated and quantized (STENCIL_GAP
  Q(32,21)), the bit-exact fit core (:func:`gearcontact.preview.fit.golden_vec.
  fit_element`), the fit's B- rule on its code, the bit-exact line core (:func:`gearcontact.preview.hertz.
  line_vec.line_element`) at ``W_e`` in LOAD Q(32,8) and ``L_eq`` in Q(32,20); each run
  is traced with its ``L`` code and mode for the ``rtl`` replay on the ChainLineCore
  (:func:`.cosim.replay_on_rtl`, ``line=True``).

An ``L_eq`` below the line core's 1 mm runs on ``(2^s W_e, 2^s L_eq)``, the host's lift
(:func:`gearcontact.preview.hertz.line.length_lift`, :func:`~gearcontact.preview.hertz.
line.unlift_line`; traced as run), exact in line mode. A preview outside the datapath's
domain (``B_max`` or ``L`` outside the line core's envelope, the lift's ellipse kept;
golden: flagged by the chain) is counted and evaluated by the fp64 line chain,
as :mod:`.contact_law` does; a saddle (B- below the fit's resolution) has no law (the
pair carries nothing, counted).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..analytic.hertz import line_contact_terms
from ..contract.qformat import CURVATURE, STENCIL_GAP
from ..ltca.coupled_slice_law import MAX_STEPS, core_scratch, coupled_solve, start_offset
from ..ltca.slice_law import (equivalent_length, interference, interference_load,
                              line_pair_load, loaded_line)
from ..preview.chain import LINE_B_ZERO_CODES, LINE_CHAIN_FIT_FLAGS
from ..preview.fit.golden_vec import fit_element
from ..preview.hertz.line import length_lift, unlift_line
from ..preview.hertz.line_vec import line_constants, line_element
from ..preview.hertz.reference import (LINE_ENVELOPE, keeps_ellipse, lifted_keeps_ellipse,
                                       line_lift)
from .contact_law import W_EVAL_MIN_N, _W_EVAL_MAX_N, _hb, _principal, _row, hertz_kappa
from .layout import (N_PREVIEW, P_AHI, P_BEYOND_W, P_CHI, P_CLO, P_ECODE, P_EP, P_NBEYOND,
                     P_NSLICE, P_SLICE_CB, PV_LINE_BENDING, PV_LINE_OFFSET, PV_LOAD)

__all__ = ["line_pair_load", "line_law_constants", "MODE_LINE"]

#: ``pv[3]`` of a preview answered in line mode (:func:`_line_law`).
MODE_LINE = 1.0
_line_terms = njit(cache=True, inline="always")(line_contact_terms)
_B_ZERO = LINE_B_ZERO_CODES * CURVATURE.lsb        # 1/mm: the fit's resolution of B-
_L_HI = LINE_ENVELOPE["line_length_mm"][1]
_S_GAP = math.ldexp(1.0, STENCIL_GAP.frac)      # STENCIL_GAP codes per mm (2^21)
_S20 = 1048576.0


def line_law_constants() -> np.ndarray:
    """The line core's constants (:func:`~gearcontact.preview.hertz.line_vec.
    line_constants`), element 5 of the kernel's ``fit`` tuple."""
    return line_constants()


@njit(cache=True, inline="always", error_model="numpy")
def _line_coefficient(l_c, l_eq, b, w, e_prime, pv):
    """The line mode's ``lambda`` (mm/N) and, into ``pv[4]``, ``beta`` of the uniform
    line of ``w`` (N) on the loaded length ``l_c`` (mm) from the chain's half-width ``b``
    (mm) of ``w`` on its ``L = l_eq`` (mm; module docstring): ``b ~ (w / L)^(1/2)``
    carries it to ``l_c``, so ``d_c(w) = lambda w (beta - ln(w)/2)`` is the approach of
    :func:`~gearcontact.analytic.hertz.line_contact_approach_mm` on ``l_c`` at ``w``
    exactly (``l_eq = l_c``: the same numbers as without the ratio). Sets ``pv[0] = l_c /
    2``, the line's half-length."""
    pv[0] = 0.5 * l_c
    pv[4] = math.log(4.0 * l_c / b) - 0.5 * math.log(l_eq / l_c) - 0.75 + 0.5 * math.log(w)
    return 4.0 / (math.pi * e_prime * l_c)


@njit(cache=True, inline="always", error_model="numpy")
def _line_fp64(A, B, length, l_c, we, prm, tcount, pv, flagged):
    """The fp64 line chain on the fitted principal curvatures (any order) and ``L =
    length`` (mm, the equivalent length ``L_eq``): the law's coefficient (``kappa``
    elliptic, ``lambda`` line on the loaded length ``l_c``; -1 without a law, a saddle,
    counted in ``tcount[5]``), ``pv = (a, b, p_max, mode, beta)`` at ``we``.
    Counts the preview in ``tcount[3]`` outside the line core's domain (``flagged``:
    the golden chain said so)."""
    lo, hi = min(A, B), max(A, B)
    if -_B_ZERO <= lo < 0.0:        # within the fit's resolution: a line (chain rule)
        lo = 0.0
    # the line core's domain: B_max, and L from 1 mm or lifted below it (line mode only)
    lift = line_lift(we, length) if 0.0 < length <= _L_HI else 0.0
    outside = flagged or not prm[P_CLO] <= hi <= prm[P_CHI] or lift == 0.0
    if lo < 0.0 or hi <= 0.0 or length <= 0.0:
        if outside:
            tcount[3] += 1
        tcount[5] += 1
        return -1.0
    ep = prm[P_EP]
    p_l, b_l = _line_terms(hi, we, length, ep)
    if lo > 0.0 and hi <= prm[P_AHI] * lo:
        a, b, k, p, delta, alpha, e_e, f, r = _hb(lo, hi, we, ep)
        outside = outside or (lift > 1.0 and lifted_keeps_ellipse(a, p, p_l, length, lift))
        if outside:
            tcount[3] += 1
        if keeps_ellipse(a, p, p_l, length):
            pv[0], pv[1], pv[2], pv[3], pv[4] = a, b, p, 0.0, 0.0
            return delta / we ** (2.0 / 3.0)
    else:
        if outside:
            tcount[3] += 1
    pv[1], pv[2], pv[3] = b_l, p_l, MODE_LINE
    return _line_coefficient(l_c, length, b_l, we, ep, pv)


@njit(cache=True, error_model="numpy", _nrt=False)
def _line_golden(s, j, i, f, we, prm, cv_t, trace, tcount, fit, pow_lut, cbrt_lut, cst,
                 length, l_c, pv):
    """The golden line chain on pair j's interpolated stencil (module docstring): the
    law's coefficient and ``pv`` as :func:`_line_fp64`, -1 when the chain flags (the
    caller then evaluates the fp64 chain). Traces the run: ``[step, A_min, B_max, W,
    flags, a, b, p_max, k, L, mode, lift]`` codes (:data:`.cosim.TRACE_COLUMNS`), the 49 gap
    codes into the stencil trace."""
    g = fit[2]
    for q in range(g.shape[1]):
        g[0, q] = np.int64(math.floor(_row(cv_t, s, j, i, f, q) * _S_GAP + 0.5))
    am, bm, ff = fit_element(g, 0, fit[0], fit[1], fit[3])
    ff = 1 if ff < 0 else ff & LINE_CHAIN_FIT_FLAGS     # a sample overflow: a coefficient one
    if -LINE_B_ZERO_CODES <= bm < 0:
        bm = np.int64(0)
    a_min, b_max = min(am, bm), max(am, bm)
    # a line below the core's 1 mm: the host's lift (W << s, L << s), traced as run
    w_code = np.int64(math.floor(we * 256.0 + 0.5))
    l_code = np.int64(math.floor(length * _S20 + 0.5))
    lift = length_lift(w_code, l_code)
    w_code <<= lift
    l_code <<= lift
    flags, a_c, b_c, p_c, k_c, mode, scale = line_element(
        a_min, b_max, w_code, l_code, np.int64(prm[P_ECODE]), pow_lut, cbrt_lut, cst, fit[5])
    flags |= ff << 8
    t = tcount[0]
    if t < trace.shape[0]:
        row = (tcount[1], a_min, b_max, w_code, flags, a_c, b_c, p_c, k_c, l_code, mode, lift)
        for q in range(12):
            trace[t, q] = row[q]
        tg = fit[4]
        if t < tg.shape[0]:
            for q in range(tg.shape[1]):
                tg[t, q] = g[0, q]
        tcount[0] = t + 1
    a_c, b_c, p_c, k_c, mode, flags = unlift_line(a_c, b_c, p_c, k_c, mode, flags, lift)
    if flags != 0 or a_c == 0 or b_c == 0:
        return -1.0
    wq = (w_code >> lift) / 256.0
    pv[0], pv[1], pv[2] = a_c / _S20, b_c / _S20, p_c / 256.0
    if mode == 0:
        pv[3], pv[4] = 0.0, 0.0
        return hertz_kappa(pv[0], k_c / _S20, wq, prm[P_ECODE])
    pv[3] = MODE_LINE
    return _line_coefficient(l_c, 2.0 * pv[0], pv[1], wq, prm[P_ECODE], pv)


@njit(cache=True, inline="always", error_model="numpy")
def _contact_load(pv, n, nb, wb, length, d_c, b_max, e_prime, w_start):
    """``(W, L_c, I, dW/dd_c)`` the slice law carries at the contact approach ``d_c``
    (mm; module docstring): ``I(d_c) = lambda' W (beta_c - ln(W)/2)`` with ``beta_c =
    ln(4 L_c) - ln(4 / (pi L_c E' b_max)) / 2 - 3/4`` (the line contact's ``b`` of ``W``
    on ``L_c``), solved by :func:`line_pair_load` from ``w_start``; 0 where nothing is
    loaded. ``nb`` edge slices of ``wb`` mm beyond either end (:func:`~gearcontact.ltca.
    slice_law.interference`)."""
    area, lc, dens = interference(pv, N_PREVIEW, n, length / n, d_c, False, nb, wb)
    if area <= 0.0 or lc <= 0.0:
        return 0.0, lc, area, 0.0
    w, lam, beta = interference_load(area, lc, b_max, e_prime, w_start)
    # dI = L_c dd = lam [(beta - 1/2 - ln(W)/2) dW + W 1.5 (dL_c/dd) / L_c dd]
    slope = lam * (beta - 0.5 - 0.5 * math.log(w))
    dw = (lc - 1.5 * lam * w * dens / lc) / slope if slope > 0.0 else 0.0
    return w, lc, area, max(dw, 0.0)


@njit(cache=True, inline="always", error_model="numpy")
def _line_state(pv, n, nb, wb, length, d, cb, b_max, e_prime, w_start):
    """``(d_c, W, L_c, I)`` of the slice law in series with the bending compliance ``cb``
    (mm/N) at the approach ``d`` (mm): the root of ``d_c + cb W(d_c) = d`` on ``[h_min,
    d]`` (increasing in ``d_c``), Newton kept in the bracket by bisection, from the bent
    share of ``w_start`` (N, the pair's last load: in a run the load moves ~1 % in a
    step, and the root is reached in 3-4 evaluations where the start from the rigid
    load at ``d`` took 5-7; measured on the EV example)."""
    lo, hi = pv[N_PREVIEW], d
    for q in range(1, n + 2 * nb):
        lo = min(lo, pv[N_PREVIEW + q])
    if cb <= 0.0 or not lo < d:     # rigid, or nothing loaded at d
        w, lc, area, dw = _contact_load(pv, n, nb, wb, length, d, b_max, e_prime, w_start)
        return d, w, lc, area
    w = w_start
    d_c = d - cb * w
    for _ in range(60):
        if not lo < d_c < hi:
            d_c = 0.5 * (lo + hi)
        w, lc, area, dw = _contact_load(pv, n, nb, wb, length, d_c, b_max, e_prime, w)
        r = d_c + cb * w - d
        if abs(r) <= 1e-12 * d or hi - lo <= 1e-14 * d:
            break
        if r > 0.0:
            hi = d_c
        else:
            lo = d_c
        step = r / (1.0 + cb * dw)
        d_c -= step
        if abs(step) <= 1e-14 * d:
            break
    return d_c, w, lc, area


@njit(cache=True, inline="always", error_model="numpy")
def _coupled_state(cv_t, s, j, i, f, c_g, pv, n, nb, wb, length, d, d_c, w, area, b_max,
                   e_prime, ow):
    """``(d_c, W, L_c, I, c_b)`` of the coupled slice law (:func:`gearcontact.ltca.
    coupled_slice_law.coupled_solve`) at the approach ``d`` (mm) from the series law's
    state ``(d_c, w, area)``: the ease-off (``pv``) and the Gram matrix ``G`` (columns
    from ``c_g``, linear between the rows) into the core's scratch after the slice
    vectors, its start ``x = h + G f`` with the series state's slice forces ``f``
    (``ow < 0``) or the pair's last ``x`` at ``pv[ow:]`` (a run, the series state
    unused); ``d_c`` over the least of ``x``, ``c_b = (d - d_c) / W`` (mm/N) the bending's secant
    compliance at the least gap.

    Raises
    ------
    ArithmeticError
        The core's Newton did not converge (not met on the examples).
    """
    m = n + 2 * nb
    ob = N_PREVIEW + 2 * m
    for q in range(m):
        pv[ob + q] = pv[N_PREVIEW + q]
    for q in range(m * m):
        pv[ob + m + q] = _row(cv_t, s, j, i, f, c_g + q)
    ox = start_offset(ob, m)
    if ow >= 0:
        for q in range(m):
            pv[ox + q] = pv[ow + q]
    else:
        interference(pv, N_PREVIEW, n, length / n, d_c, True, nb, wb)
        c = w / area
        for a in range(m):
            acc = 0.0
            for b in range(m):
                acc += pv[ob + m + a * m + b] * pv[N_PREVIEW + m + b]
            pv[ox + a] = pv[ob + a] + c * acc
    # the argument types of ltca.coupled_slice_law.coupled_line's call (a bool, not the
    # literal True; MAX_STEPS given): one compiled coupled_solve for both
    d_c, l_c, area, w, steps = coupled_solve(pv, ob, m, n, length, b_max, e_prime, nb, wb, d,
                                             np.bool_(True), w, np.int64(MAX_STEPS))
    if steps < 0:
        raise ArithmeticError("coupled slice law: no convergence (docs/cylindrical.md "
                              "sec. 10)")
    return d_c, w, l_c, area, (d - d_c) / w if w > 0.0 else 0.0


# compiled once, not inlined: one call per loaded pair and step (its array arguments'
# reference counting is off, as the kernel's)
@njit(cache=True, error_model="numpy", _nrt=False)
def _line_law(s, slot, j, i, f, d, cb, we, prm, cv_t, backend, pow_lut, cbrt_lut, cst,
              trace, tcount, fit, pv):
    """The law of pair j of table s at row interval (i, f) and the approach ``d`` (mm)
    of the step's start (module docstring): the slice law's state there (with bending
    the coupled law's, started from the series state with ``|cb|``: the pair's last
    secant compliance, mm/N, or minus the uniform load's on a fresh preview), ``we``
    (N) the Newton start. Returns ``kappa`` (elliptic, ``pv[3] = 0``) or
    ``lambda`` (line, ``pv[3] =`` :data:`MODE_LINE`, ``pv[4] = beta``), -1 without a
    law; ``pv[0:3]`` the preview's a, b (mm), p_max (MPa) at the load ``pv[PV_LOAD]``
    (N) it was sampled at, ``pv[PV_LINE_OFFSET]`` the line law's approach offset
    ``h_bar`` (mm), ``pv[PV_LINE_BENDING]`` the bending's secant compliance ``c_b``
    (mm/N; -1: rigid teeth, the mesh table's).
    ``cv_t`` columns: (golden) the 49 gap samples, then stage C's fp64 c3, c4, c5, ``L``
    (mm), the slices' ease-off (mm) and their bending Gram matrix
    (:data:`~.layout.P_NSLICE`)."""
    n = int(prm[P_NSLICE])
    nb = int(prm[P_NBEYOND])
    wb = prm[P_BEYOND_W]
    m = n + 2 * nb
    c0 = cv_t.shape[3] - (4 + m + m * m)
    length = _row(cv_t, s, j, i, f, c0 + 3)
    # stage C is linear in the samples: the interpolated rows' fits (contact_law._kappa)
    A, B, _ = _principal(_row(cv_t, s, j, i, f, c0), _row(cv_t, s, j, i, f, c0 + 1),
                         _row(cv_t, s, j, i, f, c0 + 2))
    d_c, w0, l_c, area = 0.0, 0.0, length, 0.0
    hi = max(A, B)
    bent = prm[P_SLICE_CB] != 0.0
    ep = prm[P_EP]
    if hi > 0.0 and length > 0.0:
        for q in range(m):
            pv[N_PREVIEW + q] = _row(cv_t, s, j, i, f, c0 + 4 + q)
        # rigid: the slice law at d. Bent: the coupled law, started in a run from the
        # pair's last effective ease-off (``slot``: pair and flank) if it was found in
        # this row interval or the one before, else from the slice law's state in
        # series with the pair's last secant compliance (a fresh preview: the uniform
        # load's)
        ow = N_PREVIEW + 2 * m + core_scratch(m) + slot * (m + 1)
        warm = bent and cb > 0.0 and (pv[ow + m] == i or pv[ow + m] == i - 1)
        cb = abs(cb) if bent else 0.0
        w0 = we
        if not warm:
            d_c, w0, l_c, area = _line_state(pv, n, nb, wb, length, d, cb, hi, ep, we)
        if bent and w0 > 0.0:
            d_c, w0, l_c, area, cb = _coupled_state(cv_t, s, j, i, f, c0 + 4 + m, pv, n,
                                                    nb, wb, length, d, d_c, w0, area, hi,
                                                    ep, ow if warm else -1)
            ox = start_offset(N_PREVIEW + 2 * m, m)
            for q in range(m):
                pv[ow + q] = pv[ox + q]
            pv[ow + m] = i
        elif bent:
            pv[ow + m] = -2.0
        if w0 < W_EVAL_MIN_N:       # barely closed: the law at the datapath's least load
            w0 = W_EVAL_MIN_N
            d_c, l_c, area = loaded_line(pv, N_PREVIEW, n, length, w0, hi, ep, nb, wb)
    w0 = min(max(w0, W_EVAL_MIN_N), _W_EVAL_MAX_N)
    pv[PV_LOAD] = w0
    # the chain's L: the equivalent length of the slice law's peak line load
    l_eq = equivalent_length(d_c, area, l_c)
    golden = backend != 0
    lam = -1.0
    if golden:
        lam = _line_golden(s, j, i, f, w0, prm, cv_t, trace, tcount, fit, pow_lut, cbrt_lut,
                           cst, l_eq, l_c, pv)
    if lam <= 0.0:
        lam = _line_fp64(A, B, l_eq, l_c, w0, prm, tcount, pv, golden)
    # the law's linearisation of I at d_c: L_c (d - h_bar) = lambda' W (ln(4 L_c/b) - 3/4)
    pv[PV_LINE_OFFSET] = d_c - area / l_c if (pv[3] == MODE_LINE and l_c > 0.0) else 0.0
    pv[PV_LINE_BENDING] = cb if bent and hi > 0.0 and length > 0.0 else -1.0
    return lam


@njit(cache=True, inline="always", error_model="numpy")
def line_potential_j(w, d, cb, lam):
    """Mesh potential (J) of a pair in line mode at load ``w`` (N) and approach ``d``
    (mm): ``integral(W dd) = W d_c / 2 - lam W^2 / 8 + cb W^2 / 2`` with ``d_c = d - cb
    W`` the contact's share (the line law integrated by parts)."""
    return 1e-3 * (0.5 * w * (d - cb * w) - 0.125 * lam * w * w + 0.5 * cb * w * w)
