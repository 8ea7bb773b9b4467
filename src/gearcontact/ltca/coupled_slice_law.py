"""The coupled slice law: the slice law (:mod:`.slice_law`) on a line whose teeth also
bend (docs/cylindrical.md sec. 8, 10).

The slice law distributes a line's load ``W`` along its ``n`` slices on the half-space
foundation alone: the line load ``w = K (d - h)^+`` with the Winkler modulus ``K`` of the
finite Hertz line (:func:`.slice_law.loaded_line`). The loaded TE's LCP also bends both
teeth (:mod:`.cylindrical_bending`), which closes the gap where the neighbours carry
load and so spreads the load along the line. The coupled law adds that deflection to
the ease-off::

    w = K (d - h - G f)^+,     f_j = w_j dy (the slice forces, N),  sum f = W

with ``G`` (n, n), mm/N, the bending compliance of the pinion and the gear tooth at the
slices' line points (:func:`line_bending_compliance`: the shell operators the loaded TE
uses, restricted to the line's slice positions of both members), so that ``G f`` is the
normal deflection at each slice's centre. It is the slice law on the *effective
ease-off* ``x = h + G f(x)`` (over its least), with ``f(x)`` the slice law's forces on
``x`` (each slice's part of the interference, :func:`.slice_law.interference`'s
shares, times ``W / I``: they sum to ``W``). The fixed point is solved by Newton on
``R(x) = x - h - G f(x)`` with the exact Jacobian ``1 - G df/dx`` (the shares'
and the loaded length's derivatives, :func:`.slice_law.interference_derivatives`, and
the law's equation differentiated implicitly for ``d_c``: one slice-law solve per step;
``-df/dx`` has ones in its null space, so ``(1 - G df/dx) 1 = 1``, and with ``G``
positive semi-definite the step was regular in every case met, 2-4 steps on the
examples), solved on the active slices only (the rows of ``df/dx`` vanish elsewhere:
an ``|A| x |A|`` system by Woodbury's identity), and a halving line search on ``max
|R|`` (:func:`coupled_solve`, compiled and allocation-free). The twin solves the same
fixed point at an approach instead of a load (``W`` implicit,
:func:`.slice_law.interference_load`), once per loaded pair and step from the pair's last
``x``: there the Newton steps from a small residual (:data:`CHORD_FROM`) are followed by
chord steps on their LU factors (the same tolerance; a step that does not shrink ``max
|R|`` to :data:`CHORD_RATE` brings the next Newton step). The tip edge's slices beyond
the line's ends (``edge_slices``, as the
twin's law takes them) join the same fixed point with their rows and columns of ``G``. ``w >= 0`` holds by the foundation's ``(.)^+``: the
active set is the slice law's own loaded length. The peak line load, the loaded and the
equivalent length are then the slice law's on ``x`` (``w_peak = W d_c / I``,
``L_eq = I / d_c``). ``G = 0`` returns the uncoupled slice law itself (the same call, bit
for bit), and so does ``G = c 1 1^T`` (bending in series: every slice deflects alike).

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 4.3 (the line's foundation).
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np
from numba import njit

from ..errors import CheckFailed
from ..tca.cylindrical_cycle import LineGaps
from ..validation import InputRangeError
from .cylindrical_bending import line_bending_factor
from .slice_law import (interference, interference_derivatives, interference_load,
                         loaded_line)
from .tooth_bending import ToothBending

__all__ = ["CoupledLine", "core_scratch", "coupled_line", "coupled_solve",
           "line_bending_compliance", "start_offset"]

#: Convergence of the effective ease-off: ``max |R| <= TOL_REL * max |G f| + TOL_ABS``
#: (mm): 1e-10 of the bending deflection is far below the slice law's own resolution
#: (its Newton stops at 1e-14 of ``d``).
TOL_REL = 1e-10
TOL_ABS = 1e-15
MAX_STEPS = 60
#: The halving line search's least step.
MIN_STEP = 2.0 ** -20

# the core's scratch (:func:`core_scratch`): the ease-off h (m), G (m^2, row-major),
# then vectors of m (offsets in units of m, :func:`_at`): the iterate x and its shares,
# the derivatives of slice_law.interference_derivatives (5 m), R, the step, the last
# accepted x, f, G s, v, u, the active slices, G^T v, G^T u, the reduced right-hand
# side, the factorisation's row pivots, the factorised iterate's
# D rows on the active slices (sub-, main, super-diagonal of S, c_a ds/dd, s: 5 m),
# its v and u, its (c_s, |A|); then the reduced Jacobian's LU factors (up to m^2)
(_X, _DER, _R, _DEL, _XO, _F, _GS, _V, _U, _IDX, _VG, _UG, _RHS, _PIV, _DR, _VO, _UO,
 _CS, _JAC) = (0, 2, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 24, 25, 26, 27)
#: The chord iteration (:func:`coupled_solve` at an approach): after a Newton step from
#: a residual ``max |R| <= CHORD_FROM max |G f|`` (a small step: its Jacobian is the
#: solution's to about that fraction) the next steps reuse its factors, while each
#: shrinks ``max |R|`` to at most ``CHORD_RATE`` of the last; a step that shrinks it
#: less is kept and the next is Newton's; one that does not shrink it is undone and
#: replaced by Newton's.
CHORD_FROM = 1e-3
CHORD_RATE = 0.25


@njit(cache=True, inline="always")
def _at(ob, m, k):
    """Offset of the scratch's vector ``k`` (after ``h`` and ``G``)."""
    return ob + m * (m + 1) + k * m


@njit(cache=True)
def core_scratch(m):
    """Length of :func:`coupled_solve`'s scratch for ``m`` slices (line and edge)."""
    return _at(0, m, _JAC) + m * m


@njit(cache=True, inline="always")
def start_offset(ob, m):
    """Where :func:`coupled_solve` takes its start ``x`` (and leaves the solution) in
    a scratch at ``ob`` of ``m`` slices (``h`` at ``ob``, ``G`` at ``ob + m``)."""
    return _at(ob, m, _X)


@dataclass(frozen=True)
class CoupledLine:
    """The coupled slice law of one line (module docstring).

    Attributes
    ----------
    approach_mm : float
        ``d_c`` on the effective ease-off (over its least), mm.
    loaded_length_mm : float
        ``L_c``, mm.
    interference_mm2 : float
        ``I``, mm^2.
    effective_ease_mm : ndarray (n,)
        ``x = h + G f`` over its least, mm.
    slice_load_n : ndarray (n,)
        The slice forces ``f`` (N), summing to ``W``.
    steps : int
        Newton steps taken (0: ``G = 0`` or no load).
    """

    approach_mm: float
    loaded_length_mm: float
    interference_mm2: float
    effective_ease_mm: np.ndarray
    slice_load_n: np.ndarray
    steps: int


def line_bending_compliance(teeth: ToothBending, slices: LineGaps, j: int, k: int
                            ) -> np.ndarray:
    """``G`` (n, n), mm/N, of pair ``j``'s line at phase ``k``: the bending compliance of
    the pinion plus the gear tooth between the line points of its slices
    (:func:`.cylindrical_bending.line_bending_factor` at the slices' axial positions and
    roll lengths, one cell across: the loaded TE's rows, ``G = F F^T``).

    Raises
    ------
    CheckFailed
        A slice's line point is missing (NaN roll length): the line's slices left it.
    """
    z = np.broadcast_to(slices.z_mm, slices.gap_mm.shape)[j, k]
    u1, u2 = slices.pinion_roll_mm[j, k], slices.gear_roll_mm[j, k]
    if not (np.isfinite(u1).all() and np.isfinite(u2).all()):
        raise CheckFailed(f"pair {j} phase {k}: a slice of the line has no line point "
                          "(docs/cylindrical.md sec. 10)")
    f = np.asarray(line_bending_factor(teeth, z, u1, u2, 1)[:, 0, :], np.float64)
    return f @ f.T


@njit(cache=True, inline="always", error_model="numpy")
def _evaluate(buf, ob, m, n, length, b_max, e_prime, nb, wb, value, at_approach, w_start):
    """The slice law on the iterate ``x`` (``buf``, :func:`coupled_solve`): its forces
    ``f = W s / I`` into ``_F``, the residual ``R = x - h - G f`` into ``_R`` (over its
    least at a given load: ``f`` does not see a shift of ``x``), the derivatives of
    ``f`` as ``D = c_s S + c_a ds/dd v^T + s u^T`` (``S = ds/dx`` tridiagonal; ``v``, ``u``
    into ``_V``, ``_U``) and ``G s`` into ``_GS``. At a load
    (``value`` = W, N): ``d_c`` from :func:`.slice_law.loaded_line`, ``v = dd_c/dx``
    from its equation ``F = I - lambda' W g(L_c) = 0`` (``g`` kept >= 1/4 as there),
    ``u = -(W / I^2) (dI/dx + L_c v)``. At an approach (``value`` = d, mm): ``W`` from
    :func:`.slice_law.interference_load` (from ``w_start``), ``v = dW/dx`` from ``dI =
    lambda' ((g - 1/2) dW + 1.5 W dL_c / L_c)`` (past the law's maximum its secant
    ``dI = lambda' dW / 2``), ``u = v / I - (W / I^2) dI/dx``. Returns ``(d_c, L_c, I, W,
    max |R|, max |G f|, c_s, c_a)``, ``d_c`` over the least of ``x`` (at a load: in
    ``x``'s datum, which a step keeps at least 0)."""
    ox, od = _at(ob, m, _X), _at(ob, m, _DER)
    width = length / n
    x_min = buf[ox]
    for q in range(1, m):
        x_min = min(x_min, buf[ox + q])
    if at_approach:
        d = value
        area, lc, dens = interference(buf, ox, n, width, d, True, nb, wb)
        w, lam, beta = 0.0, 0.0, 0.0
        if area > 0.0 and lc > 0.0:
            w, lam, beta = interference_load(area, lc, b_max, e_prime, w_start)
    else:
        w = value
        d, lc, area = loaded_line(buf, ox, n, length, w, b_max, e_prime, nb, wb)
        area, lc, dens = interference(buf, ox, n, width, d, True, nb, wb)
    interference_derivatives(buf, ox, n, width, d, nb, wb, buf, od)
    loaded = area > 0.0 and lc > 0.0 and w > 0.0
    c_s = w / area if loaded else 0.0
    c_a = 0.0
    for q in range(m):
        buf[_at(ob, m, _F) + q] = c_s * buf[ox + m + q]
    # v and u (dI/dx: the column sums of the tridiagonal S, into _U first)
    for q in range(m):
        ix = buf[od + 2 * m + q]
        if q > 0:
            ix += buf[od + 3 * m + q - 1]
        if q < m - 1:
            ix += buf[od + m + q + 1]
        buf[_at(ob, m, _U) + q] = ix
        buf[_at(ob, m, _V) + q] = 0.0
    if loaded:
        if at_approach:
            g = beta - 0.5 * math.log(w)
            for q in range(m):
                ix = buf[_at(ob, m, _U) + q]
                v = (ix - 1.5 * lam * w * buf[od + 4 * m + q] / lc) / (lam * (g - 0.5)) \
                    if g > 0.5 else ix / (0.5 * lam)
                buf[_at(ob, m, _V) + q] = v
                buf[_at(ob, m, _U) + q] = v / area - c_s * ix / area
        else:
            lam_w = 4.0 * w / (math.pi * e_prime)
            c0 = math.log(4.0) - 0.5 * math.log(4.0 * w / (math.pi * e_prime * b_max)) - 0.75
            floored = 1.5 * math.log(lc) + c0 < 0.25
            f_d = lc if floored else lc - 1.5 * lam_w * dens / lc
            c_a = c_s
            for q in range(m):
                ix = buf[_at(ob, m, _U) + q]
                f_x = ix if floored else ix - 1.5 * lam_w * buf[od + 4 * m + q] / lc
                v = -f_x / f_d
                buf[_at(ob, m, _V) + q] = v
                buf[_at(ob, m, _U) + q] = -c_s * (ix + lc * v) / area
    r_max, gf_max, r_min = 0.0, 0.0, math.inf
    og = ob + m
    for i in range(m):
        gs = 0.0
        for k in range(m):
            if buf[ox + m + k] != 0.0:      # the loaded slices (the C: over their list)
                gs += buf[og + i * m + k] * buf[ox + m + k]
        buf[_at(ob, m, _GS) + i] = gs
        gf = c_s * gs
        gf_max = max(gf_max, abs(gf))
        r = buf[ox + i] - buf[ob + i] - gf
        buf[_at(ob, m, _R) + i] = r
        r_min = min(r_min, r)
    for i in range(m):
        if not at_approach:
            buf[_at(ob, m, _R) + i] -= r_min
        r_max = max(r_max, abs(buf[_at(ob, m, _R) + i]))
    # at a load, x is kept at least 0 after a step (and h, the start, is over its least)
    return (d - x_min) if at_approach else d, lc, area, w, r_max, gf_max, c_s, c_a


@njit(cache=True, inline="always", error_model="numpy")
def _reduced_solve(buf, ob, m, na, c_s, ov, ou, odr):
    """``delta = -R - G_A z`` (into ``_DEL``) with ``(1 - D_A G_A) z = D_A R`` on the
    factorised reduced Jacobian (``_JAC``: its LU factors, the row pivots ``_PIV``) of
    :func:`_newton_step`: ``D_A R`` from ``D``'s rows on the active slices (``odr``: the
    5 vectors of ``_DR``), its ``v``, ``u`` (``ov``, ``ou``) and ``c_s``, the
    pivots' interchanges and the two triangular solves (each entry's operations those of
    the elimination interleaved with the factorisation, in the same order)."""
    og = ob + m
    oi, oj, op = _at(ob, m, _IDX), _at(ob, m, _JAC), _at(ob, m, _PIV)
    orr, orhs, odl = _at(ob, m, _R), _at(ob, m, _RHS), _at(ob, m, _DEL)
    vr, ur = 0.0, 0.0
    for k in range(m):
        vr += buf[ov + k] * buf[orr + k]
        ur += buf[ou + k] * buf[orr + k]
    for p in range(na):
        i = int(buf[oi + p])
        sub, dia, sup = buf[odr + p], buf[odr + m + p], buf[odr + 2 * m + p]
        sd_i, s_i = buf[odr + 3 * m + p], buf[odr + 4 * m + p]
        sr = dia * buf[orr + i]
        if i > 0:
            sr += sub * buf[orr + i - 1]
        if i < m - 1:
            sr += sup * buf[orr + i + 1]
        buf[orhs + p] = c_s * sr + sd_i * vr + s_i * ur
    for c in range(na):     # the row interchanges, then L's forward substitution
        p = int(buf[op + c])
        if p != c:
            t = buf[orhs + c]
            buf[orhs + c] = buf[orhs + p]
            buf[orhs + p] = t
    for c in range(na):
        for i in range(c + 1, na):
            e = buf[oj + i * na + c]
            if e != 0.0:
                buf[orhs + i] -= e * buf[orhs + c]
    for c in range(na - 1, -1, -1):
        t = buf[orhs + c]
        for j in range(c + 1, na):
            t -= buf[oj + c * na + j] * buf[orhs + j]
        buf[orhs + c] = t / buf[oj + c * na + c]
    for i in range(m):
        t = -buf[orr + i]
        for q in range(na):
            t -= buf[og + i * m + int(buf[oi + q])] * buf[orhs + q]
        buf[odl + i] = t


@njit(cache=True, inline="always", error_model="numpy")
def _newton_step(buf, ob, m, c_s, c_a):
    """The Newton step ``J delta = -R``, ``J = 1 - G D`` (:func:`_evaluate`'s ``D``),
    into ``_DEL``. ``D``'s rows vanish outside the active slices ``A`` (``s`` or
    ``ds/dd`` nonzero: under the approach or on a segment crossing it), so ``J = 1 -
    G_A D_A`` and (Woodbury) ``delta = -R - G_A z`` with ``(1 - D_A G_A) z = D_A R``, an
    ``|A| x |A|`` system: LU with partial pivoting (whole rows swapped, the multipliers
    kept below the diagonal), then :func:`_reduced_solve`. Keeps the factors, ``D``'s
    rows, ``v``, ``u``, ``c_s`` and ``|A|`` for :func:`_chord_step`."""
    og, od = ob + m, _at(ob, m, _DER)
    ox, oi, oj = _at(ob, m, _X), _at(ob, m, _IDX), _at(ob, m, _JAC)
    ov, ou, ovg, oug = _at(ob, m, _V), _at(ob, m, _U), _at(ob, m, _VG), _at(ob, m, _UG)
    op, odr, ocs = _at(ob, m, _PIV), _at(ob, m, _DR), _at(ob, m, _CS)
    ovo, ouo = _at(ob, m, _VO), _at(ob, m, _UO)
    na = 0
    for i in range(m):
        if buf[ox + m + i] != 0.0 or buf[od + i] != 0.0:
            buf[oi + na] = i
            na += 1
    for k in range(m):
        buf[ovo + k] = buf[ov + k]
        buf[ouo + k] = buf[ou + k]
    buf[ocs], buf[ocs + 1] = c_s, na
    for q in range(na):
        c = int(buf[oi + q])
        vg, ug = 0.0, 0.0
        for k in range(m):      # the C sums the nonzero terms only: the same sums
            vg += buf[ov + k] * buf[og + k * m + c]
            ug += buf[ou + k] * buf[og + k * m + c]
        buf[ovg + q] = vg
        buf[oug + q] = ug
    for p in range(na):
        i = int(buf[oi + p])
        sub, dia, sup = buf[od + m + i], buf[od + 2 * m + i], buf[od + 3 * m + i]
        sd_i, s_i = c_a * buf[od + i], buf[ox + m + i]
        buf[odr + p], buf[odr + m + p], buf[odr + 2 * m + p] = sub, dia, sup
        buf[odr + 3 * m + p], buf[odr + 4 * m + p] = sd_i, s_i
        for q in range(na):
            c = int(buf[oi + q])
            sg = dia * buf[og + i * m + c]
            if i > 0:
                sg += sub * buf[og + (i - 1) * m + c]
            if i < m - 1:
                sg += sup * buf[og + (i + 1) * m + c]
            buf[oj + p * na + q] = ((1.0 if p == q else 0.0) - c_s * sg - sd_i * buf[ovg + q]
                                    - s_i * buf[oug + q])
    for c in range(na):
        p = c
        for i in range(c + 1, na):
            if abs(buf[oj + i * na + c]) > abs(buf[oj + p * na + c]):
                p = i
        buf[op + c] = p
        if p != c:
            for j in range(na):
                t = buf[oj + c * na + j]
                buf[oj + c * na + j] = buf[oj + p * na + j]
                buf[oj + p * na + j] = t
        piv = buf[oj + c * na + c]
        for i in range(c + 1, na):
            e = buf[oj + i * na + c] / piv
            buf[oj + i * na + c] = e
            if e != 0.0:
                for j in range(c + 1, na):
                    buf[oj + i * na + j] -= e * buf[oj + c * na + j]
    _reduced_solve(buf, ob, m, na, c_s, ov, ou, odr)


@njit(cache=True, inline="always", error_model="numpy")
def _chord_step(buf, ob, m):
    """The chord step: :func:`_reduced_solve` on the last :func:`_newton_step`'s
    factorised Jacobian with the current residual ``R`` (into ``_DEL``)."""
    ocs = _at(ob, m, _CS)
    _reduced_solve(buf, ob, m, int(buf[ocs + 1]), buf[ocs], _at(ob, m, _VO), _at(ob, m, _UO),
                   _at(ob, m, _DR))


@njit(cache=True, error_model="numpy", _nrt=False)
def coupled_solve(buf, ob, m, n, length, b_max, e_prime, nb, wb, value, at_approach,
                  w_start, max_steps=MAX_STEPS):
    """The coupled slice law (module docstring) on the scratch ``buf[ob:ob +``
    :func:`core_scratch` ``(m)]`` (no allocation: the twin's step loop calls it), which
    holds the ease-off ``h`` (m slices: the line's ``n``, then ``nb`` edge slices of
    ``wb`` mm beyond either end), ``G`` (m x m, row-major, mm/N) and the start ``x``
    (at 0, m and :func:`_at` ``(0, m, _X)``): Newton on ``R(x) = x - h - G f(x)``
    with the exact Jacobian ``1 - G df/dx`` (:func:`.slice_law.interference_derivatives`
    and the implicit derivative of the law's equation, :func:`_evaluate`) and a halving
    line search on ``max |R|``, to ``max |R| <= TOL_REL max |G f| + TOL_ABS``. At a
    load (``at_approach`` False, ``value`` = W, N; ``x`` kept at least 0, as
    :func:`coupled_line`) or at an approach (``value`` = d, mm, from the line's least
    gap: the twin, ``x = h + G f`` absolute; ``w_start`` the load's Newton start). At
    an approach, after a Newton step from a residual within :data:`CHORD_FROM` of ``max
    |G f|``, chord steps on its factors while each shrinks ``max |R|`` to
    :data:`CHORD_RATE` of the last (a step that shrinks it less is kept, and the next is
    Newton's; one that does not is undone and replaced by Newton's with its line
    search): the same tolerance, fewer factorisations (docs/twin.md, "Speed of the bent
    cylindrical twin"). Returns ``(d_c,
    L_c, I, W, steps)``: the approach over the least of ``x``, the loaded length, the
    interference, the load, the iterations (Newton and chord; -1: no convergence in
    ``max_steps``, :data:`MAX_STEPS` but for a test of that path); ``f`` and ``x`` in
    the scratch at :func:`_at` ``(ob, m, _F)``, ``(ob, m, _X)``."""
    ox, oo, od = _at(ob, m, _X), _at(ob, m, _XO), _at(ob, m, _DEL)
    res = _evaluate(buf, ob, m, n, length, b_max, e_prime, nb, wb, value, at_approach,
                    w_start)
    if not value > 0.0:
        return res[0], res[1], res[2], res[3], 0
    fresh = True        # the next step refactorises
    for step in range(1, max_steps + 1):
        d_c, lc, area, w, r_max, gf_max, c_s, c_a = res
        if r_max <= TOL_REL * gf_max + TOL_ABS:
            return d_c, lc, area, w, step - 1
        chord = at_approach and not fresh
        if chord:
            _chord_step(buf, ob, m)
        else:
            _newton_step(buf, ob, m, c_s, c_a)
        fresh = not at_approach or not (chord or r_max <= CHORD_FROM * gf_max)
        for q in range(m):
            buf[oo + q] = buf[ox + q]
        t = 1.0
        while True:
            x_min = math.inf
            for q in range(m):
                buf[ox + q] = buf[oo + q] + t * buf[od + q]
                x_min = min(x_min, buf[ox + q])
            if not at_approach:
                for q in range(m):
                    buf[ox + q] -= x_min
            res = _evaluate(buf, ob, m, n, length, b_max, e_prime, nb, wb, value,
                            at_approach, w if w > 0.0 else w_start)
            if chord:
                if res[4] > CHORD_RATE * r_max:
                    fresh = True
                if res[4] < r_max:
                    break
                # no decrease: back to the step's start, whose Newton step is next
                for q in range(m):
                    buf[ox + q] = buf[oo + q]
                res = _evaluate(buf, ob, m, n, length, b_max, e_prime, nb, wb, value,
                                at_approach, w if w > 0.0 else w_start)
                break
            if res[4] < r_max or t < MIN_STEP:
                break
            t *= 0.5
    ok = res[4] <= TOL_REL * res[5] + TOL_ABS
    return res[0], res[1], res[2], res[3], max_steps if ok else -1


def coupled_line(ease_mm, length_mm: float, load_n: float, b_max_per_mm: float,
                 e_prime_mpa: float, compliance_mm_per_n=None, *, edge_slices: int = 0,
                 edge_width_mm: float = 0.0) -> CoupledLine:
    """The coupled slice law (module docstring) of one line: the ease-off ``ease_mm``
    (m = n + 2 ``edge_slices`` slices, mm: the line's n, then the tip edge's beyond
    either end, as :func:`.slice_law.interference` takes them on ``edge_width_mm``,
    the edge slices' width times their foundation's relative stiffness) of a line of
    ``length_mm``, loaded by ``load_n`` (N) across the curvature ``b_max_per_mm``
    (1/mm) with the modulus ``e_prime_mpa``, its teeth's bending compliance
    ``compliance_mm_per_n`` ((m, m) mm/N, symmetric; None or all 0: the uncoupled slice
    law, bit for bit). :func:`coupled_solve` at the load, from ``x = h``.

    Raises
    ------
    InputRangeError
        ``compliance_mm_per_n`` not (n, n), not finite or not symmetric.
    CheckFailed
        Newton did not reach the tolerance in ``MAX_STEPS`` steps.
    """
    h = np.asarray(ease_mm, np.float64)
    nb, wb = int(edge_slices), float(edge_width_mm)
    m = h.size
    n = m - 2 * nb
    if n < 2 or nb < 0:
        raise InputRangeError("edge_slices", edge_slices,
                              f"0 .. {(h.size - 2) // 2} (ease_mm has {h.size} slices)")
    g = None if compliance_mm_per_n is None else np.asarray(compliance_mm_per_n, np.float64)
    if g is not None:
        if g.shape != (m, m) or not np.isfinite(g).all() \
                or np.abs(g - g.T).max() > 1e-9 * max(np.abs(g).max(), 1e-300):
            raise InputRangeError("compliance_mm_per_n", f"shape {g.shape}",
                                  f"a finite symmetric ({m}, {m}) matrix, mm/N")
    buf = np.zeros(core_scratch(m))
    buf[:m] = h
    if g is not None:
        buf[m:m + m * m] = g.ravel()
    x = buf[_at(0, m, _X):_at(0, m, _X) + m]
    x[:] = h
    # max_steps given, not omitted: one compiled specialization with the tests of the cap
    # (tests/ltca/test_coupled_slice_law.py; docs/performance.md, "Session 26")
    d_c, l_c, area, _, steps = coupled_solve(buf, 0, m, n, float(length_mm), float(b_max_per_mm),
                                             float(e_prime_mpa), nb, wb, float(load_n),
                                             False, 0.0, MAX_STEPS)
    if steps < 0:
        r = buf[_at(0, m, _R):_at(0, m, _R) + m]
        raise CheckFailed(f"coupled slice law: no convergence in {MAX_STEPS} Newton steps "
                          f"(max |R| {np.abs(r).max():.3e} mm; docs/cylindrical.md sec. 8)")
    return CoupledLine(float(d_c), float(l_c), float(area), x - x.min(),
                       buf[_at(0, m, _F):_at(0, m, _F) + m].copy(), int(steps))
