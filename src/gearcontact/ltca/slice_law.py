"""The slice law: the loaded length of a line contact on the ease-off along the line
(docs/cylindrical.md sec. 10), the one array function the twin's line law
(:mod:`gearcontact.twin.line_law`, per pair and step) and ``analyze``'s cylindrical
preview (:mod:`.cylindrical_preview`, per pair and phase) evaluate (compiled with
numba), and the ease-off it runs on (:func:`line_easeoff_mm`): both callers feed it the
same inputs, so at a table row and load the twin and ``analyze`` find the same loaded
length bit for bit (with tooth bending the preview runs the coupled law of
:mod:`.coupled_slice_law`, this law on the ease-off plus the shells' deflection).

The ease-off along a pair's contact line ``h`` (mm; the normal gap over the line's
least at the centres of ``n`` equal slices of the line's length ``L``, linear between
them; :func:`gearcontact.tca.cylindrical_stencil.contact_line_slices`) sets where the
line carries load: at the contact approach ``d_c`` the slices whose gap lies below it,
``L_c = |{h < d_c}|``, with the interference ``I(d_c) = integral(max(d_c - h, 0) dy)``
carried by the finite line's modulus (a Winkler foundation whose stiffness per length
is that of the Hertz line contact, so that a flat line is the uniform line exactly)::

    I(d_c) = 4 W / (pi E') (ln(4 L_c / b) - 3/4),   b = (4 W / (pi L_c E' B))^(1/2)

(Johnson 1985 sec. 4.3; ``B`` the curvature across the line). On a crowned line (gap
``A y^2``) this is the exact elongated Hertz ellipse's approach within -3.2 % with a
loaded length 1.08 x Hertz's ``2 a`` (tests/ltca/test_slice_law.py). :func:`loaded_line`
solves it for ``d_c``, ``L_c`` and ``I`` at a load.

The foundation's line load is ``w(y) = W max(d_c - h(y), 0) / I``, largest where the
gap is least: the ease-off is the gap over the line's least, so its peak is
:func:`peak_line_load` ``w_peak = W d_c / I`` (the triangle's ``2 W / L_c`` on a straight
gap, ``3 W / (2 L_c)`` on a parabola; ``W / L`` on a flat line). The preview's line chain
(stage D's inputs ``W`` and ``L``) runs on the *equivalent length* ``L_eq = W / w_peak =
I / d_c``: its uniform line of ``W`` over ``L_eq`` is the peak line load, so its
``p_max`` is the Hertz pressure there (docs/cylindrical.md sec. 8, 10).

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 4.3.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..errors import CheckFailed
from ..tca.cylindrical_cycle import LineGaps
from ..tca.cylindrical_stencil import LINE_SLICES, contact_line_slices

__all__ = ["interference", "interference_derivatives", "interference_load", "line_pair_load",
           "loaded_line", "loaded_length_mm", "line_easeoff_mm", "equivalent_length"]


@njit(cache=True, inline="always", error_model="numpy")
def _segment(h, o, n, width, d, shares, so):
    """``(I, L_c, dL_c/dd)`` of one run of ``n`` slices ``h[o:o + n]`` (mm, centres
    ``width`` mm apart) at the approach ``d`` (mm), linear between the centres and
    constant over the two end half-slices; ``shares``: each slice's part of ``I`` added
    into ``h[so:so + n]``."""
    area = 0.0
    lc = 0.0
    dens = 0.0
    for q in range(n - 1):
        a = h[o + q]
        b = h[o + q + 1]
        lo, hi = min(a, b), max(a, b)
        if hi <= d:
            part, t = width * (d - 0.5 * (a + b)), 1.0
        elif lo < d:
            t = (d - lo) / (hi - lo)
            part = 0.5 * width * t * (d - lo)
            dens += width / (hi - lo)
        else:
            continue
        area += part
        lc += width * t
        if shares:
            h[so + q] += 0.5 * part
            h[so + q + 1] += 0.5 * part
    for q in (0, n - 1):
        hq = h[o + q]
        if hq < d:
            area += 0.5 * width * (d - hq)
            lc += 0.5 * width
            if shares:
                h[so + q] += 0.5 * width * (d - hq)
    return area, lc, dens


@njit(cache=True, inline="always", error_model="numpy")
def interference(h, o, n, width, d, shares, nb, wb):
    """``(I, L_c, dL_c/dd)`` of the ease-off ``h[o:o + n]`` (mm, the slices' centres
    ``width`` mm apart) at the approach ``d`` (mm): ``I = integral(max(d - h, 0) dy)``
    (mm^2) and the loaded length ``L_c = |{h < d}|`` (mm), with ``h`` linear between the
    centres and constant over the two end half-slices, so that ``I`` is convex with
    ``dI/dd = L_c``. ``nb`` > 0: the tip edge beyond either end of the line (a helical
    pair's, :func:`beyond_easeoff_mm`), two more runs of ``nb`` slices ``wb`` mm wide
    after the line's, ``h[o + n:o + n + nb]`` and ``h[o + n + nb:o + n + 2 nb]``, each
    from the line's end outwards, added as runs of their own (``m = n + 2 nb`` slices in
    all). ``shares``: each slice's part of ``I`` (half of each segment's to either end)
    into ``h[o + m:o + 2 m]``."""
    m = n + 2 * nb
    if shares:
        for q in range(m):
            h[o + m + q] = 0.0
    area, lc, dens = _segment(h, o, n, width, d, shares, o + m)
    for r in range(2 if nb > 0 else 0):
        ob = o + n + r * nb
        a_b, l_b, d_b = _segment(h, ob, nb, wb, d, shares, ob + m)
        area += a_b
        lc += l_b
        dens += d_b
    return area, lc, dens


@njit(cache=True, inline="always", error_model="numpy")
def loaded_line(h, o, n, length, we, b_max, e_prime, nb, wb):
    """The slice law at the load ``we`` (N) on the ease-off ``h[o:o + n]`` (mm) of a
    line of ``length`` mm (module docstring), with the tip edge beyond its ends on
    ``nb`` slices of ``wb`` mm either side (:func:`interference`; ``nb = 0``: none):
    ``(d_c, L_c, I)``, the contact approach
    (mm) at which ``F(d) = I(d) - lambda' we g(L_c(d)) = 0``, ``g = ln(4 L_c / b) - 3/4`` with ``lambda' = 4 / (pi
    E')`` and ``b = (4 we / (pi L_c E' b_max))^(1/2)`` the line contact's half-width of
    ``we`` on ``L_c`` across ``b_max`` (1/mm), so ``g = 1.5 ln(L_c) + c0``; the
    loaded length ``L_c(d_c)`` and ``I(d_c)``. Newton on ``F`` (``F' = L_c - 1.5
    lambda' we L_c' / L_c``) kept inside a bracket by bisection: ``F < 0`` at the least
    gap (nothing loaded), ``F >= 0`` at ``h_max + lambda' we g(L) / L`` (every slice of
    the line loaded by at least that; edge slices beyond it lengthen ``L_c``, and the
    bracket is widened while ``F < 0`` there)."""
    width = length / n
    h_min = h[o]
    h_max = h_min
    for q in range(1, n):
        h_min = min(h_min, h[o + q])
        h_max = max(h_max, h[o + q])
    h_edge = math.inf       # the edge slices' least gap (none: nb = 0)
    for q in range(n, n + 2 * nb):
        h_edge = min(h_edge, h[o + q])
    h_min = min(h_min, h_edge)
    lam_w = 4.0 * we / (math.pi * e_prime)
    # g(L_c) = ln(4 L_c / b) - 3/4 = 1.5 ln(L_c) + c0; far below 1 N a kink's loaded
    # length nears b (a point's regime): the log is kept >= 0.25 there
    c0 = math.log(4.0) - 0.5 * math.log(4.0 * we / (math.pi * e_prime * b_max)) - 0.75
    lo = h_min
    hi = h_max + lam_w * (1.5 * math.log(length) + c0) / length
    top = hi
    d = hi
    area, lc = 0.0, length
    for _ in range(100):
        area, lc, dens = interference(h, o, n, width, d, False, nb, wb)
        g = 1.5 * math.log(lc) + c0 if lc > 0.0 else -math.inf
        if g < 0.25:
            g, dg = 0.25, 0.0
        else:
            dg = 1.5 * dens / lc
        r = area - lam_w * g
        if r <= 0.0 and d == top and h_edge < d:    # edge slices loaded at the top: widen
            top += top - h_min
            hi = d = top
            continue
        if r > 0.0:
            hi = d
        else:
            lo = d
        slope = lc - lam_w * dg
        d_new = d - r / slope if slope > 0.0 else 0.5 * (lo + hi)
        if not lo < d_new < hi:
            d_new = 0.5 * (lo + hi)
        if abs(d_new - d) <= 1e-14 * abs(d) + 1e-20 or hi - lo <= 1e-15 * abs(hi):
            d = d_new
            break
        d = d_new
    area, lc, _ = interference(h, o, n, width, d, False, nb, wb)
    return d, lc, area


@njit(cache=True, inline="always", error_model="numpy")
def line_pair_load(d, lam, beta, cb, w_prev):
    """Load W (N) of a pair in line mode at approach ``d`` (mm): the root of ``f(W) =
    lam W max(beta - ln(W)/2, 1/2) + cb W - d``. The line law ``lam W (beta - ln(W)/2)``
    is concave (``f'' = -lam / (2 W)``) and increasing while ``g = beta - ln(W)/2 >
    1/2``, i.e. while the half-width stays below ``4 L e^(-5/4) ~ 1.15 L``; beyond, on a
    loaded length shorter than its contact's width (a line just entering or leaving, its
    loaded part a few hundredths of a mm), it has no root past its maximum ``lam W / 2``
    at ``g = 1/2``, and ``f`` continues from it on that secant, ``lam W / 2`` (continuous
    and increasing: one root; before, Newton halved its way to a start-dependent load
    there, tests/twin/test_line_law.py). So Newton from any start lands left of the root
    after at most two steps (on the secant exactly; from there, or on the concave part,
    the tangent lies above ``f``) and then rises monotonically to it; the start is the pair's previous load ``w_prev`` (> 0), else the
    load of the law's secant at 1 N. Stops at a relative step of 1e-14."""
    w = w_prev if w_prev > 0.0 else d / (lam * max(beta, 1.0) + cb)
    for _ in range(60):
        lw = math.log(w)
        g = beta - 0.5 * lw
        if g > 0.5:
            r = lam * w * g + cb * w - d
            slope = lam * (g - 0.5) + cb
        else:                       # past the line law's maximum: its secant there
            r = 0.5 * lam * w + cb * w - d
            slope = 0.5 * lam + cb
        dw = r / slope
        w_new = w - dw
        w = w_new if w_new > 0.0 else 0.5 * w
        if abs(dw) <= 1e-14 * w:
            break
    return w


@njit(cache=True, inline="always", error_model="numpy")
def interference_load(area, lc, b_max, e_prime, w_start):
    """``(W, lambda', beta)``: the load (N) the slice law carries with the interference
    ``area`` (mm^2) on the loaded length ``lc`` (mm) across ``b_max`` (1/mm), the root of
    ``I = lambda' W (beta - ln(W)/2)`` (:func:`line_pair_load` from ``w_start``, N) with
    ``lambda' = 4 / (pi E')`` and ``beta = ln(4 L_c) - ln(4 / (pi L_c E' b_max)) / 2 -
    3/4`` (the line contact's ``b`` of ``W`` on ``L_c``: :func:`loaded_line`'s equation
    solved for ``W`` instead of ``d_c``)."""
    lam = 4.0 / (math.pi * e_prime)
    beta = (math.log(4.0 * lc) - 0.5 * math.log(4.0 / (math.pi * lc * e_prime * b_max))
            - 0.75)
    return line_pair_load(area, lam, beta, 0.0, w_start), lam, beta


@njit(cache=True, inline="always", error_model="numpy")
def _segment_derivatives(h, o, start, cnt, width, d, buf, ob, m):
    """:func:`_segment`'s derivatives (:func:`interference_derivatives`) of the run of
    ``cnt`` slices from slice ``start``, added into ``buf[ob:ob + 5 m]``."""
    for q in range(cnt - 1):
        g = start + q
        a = h[o + g]
        b = h[o + g + 1]
        lo, hi = min(a, b), max(a, b)
        if hi <= d:             # part = width (d - (a + b)/2), half to either end
            c = 0.25 * width
            buf[ob + g] += 0.5 * width
            buf[ob + g + 1] += 0.5 * width
            buf[ob + 2 * m + g] -= c
            buf[ob + 3 * m + g] -= c
            buf[ob + m + g + 1] -= c
            buf[ob + 2 * m + g + 1] -= c
        elif lo < d:            # part = width (d - lo)^2 / (2 (hi - lo)), L_c += width t
            span = hi - lo
            t = (d - lo) / span
            p_lo, p_hi = width * (0.5 * t * t - t), -0.5 * width * t * t
            l_lo, l_hi = width * (t - 1.0) / span, -width * t / span
            if a < b:
                pa, pb, la, lb = p_lo, p_hi, l_lo, l_hi
            else:
                pa, pb, la, lb = p_hi, p_lo, l_hi, l_lo
            buf[ob + g] += 0.5 * width * t
            buf[ob + g + 1] += 0.5 * width * t
            buf[ob + 2 * m + g] += 0.5 * pa
            buf[ob + 3 * m + g] += 0.5 * pb
            buf[ob + m + g + 1] += 0.5 * pa
            buf[ob + 2 * m + g + 1] += 0.5 * pb
            buf[ob + 4 * m + g] += la
            buf[ob + 4 * m + g + 1] += lb
    for q in (0, cnt - 1):      # the end half-slices, constant
        g = start + q
        if h[o + g] < d:
            buf[ob + g] += 0.5 * width
            buf[ob + 2 * m + g] -= 0.5 * width


@njit(cache=True, inline="always", error_model="numpy")
def interference_derivatives(h, o, n, width, d, nb, wb, buf, ob):
    """The exact derivatives of :func:`interference` (its shares ``s``, ``L_c``) at the
    approach ``d`` (mm) on ``h[o:o + m]`` (``m = n + 2 nb``), into ``buf[ob:ob + 5 m]``:
    ``ds/dd`` (m; sums to ``L_c = dI/dd``), the tridiagonal ``ds/dh`` as its sub-,
    main and super-diagonal (3 m: ``ds_i/dh_(i-1)``, ``ds_i/dh_i``, ``ds_i/dh_(i+1)``;
    0 across the runs' ends) and ``dL_c/dh`` (m). Each segment's part ``width (d - (a +
    b)/2)`` (under the approach) or ``width (d - lo)^2 / (2 (hi - lo))`` (crossing it)
    and each end half-slice's ``width (d - h) / 2`` differentiated; piecewise smooth,
    the one-sided derivative of the segment's case at a tie. The coupled slice law's
    Newton Jacobian (:mod:`.coupled_slice_law`)."""
    m = n + 2 * nb
    for q in range(5 * m):
        buf[ob + q] = 0.0
    _segment_derivatives(h, o, 0, n, width, d, buf, ob, m)
    for r in range(2 if nb > 0 else 0):
        _segment_derivatives(h, o, n + r * nb, nb, wb, d, buf, ob, m)


@njit(cache=True, inline="always", error_model="numpy")
def equivalent_length(d_c, area, length):
    """``L_eq = I / d_c`` (mm; module docstring): the length over which the uniform line
    of ``W`` has the slice law's peak line load ``W d_c / I`` at the approach ``d_c`` (mm)
    with the interference ``area`` (mm^2); ``length`` (the line's, mm) where nothing is
    loaded (``d_c <= 0`` or ``area <= 0``). At most ``L_c`` (a flat line), and at least
    ``L_c / 2`` (a straight gap's triangle) on a convex ease-off."""
    if d_c > 0.0 and area > 0.0:
        return area / d_c
    return length


def loaded_length_mm(ease_mm, length_mm: float, load_n: float, b_max_per_mm: float,
                     e_prime_mpa: float) -> tuple[float, float, float]:
    """``(d_c, L_c, I)`` of :func:`loaded_line` for one line: its contact approach (mm),
    loaded length (mm) and interference (mm^2) at ``load_n`` (N) on the ease-off
    ``ease_mm`` (n slices, mm) of a line of ``length_mm`` across the curvature
    ``b_max_per_mm`` (1/mm)."""
    h = np.zeros(2 * len(ease_mm))
    h[:len(ease_mm)] = ease_mm
    d_c, l_c, area = loaded_line(h, 0, len(ease_mm), float(length_mm), float(load_n),
                                 float(b_max_per_mm), float(e_prime_mpa), 0, 0.0)
    return float(d_c), float(l_c), float(area)


def line_easeoff_mm(pair, cycle, valid, *, slices: int = LINE_SLICES
                    ) -> tuple[np.ndarray, LineGaps]:
    """The slice law's ease-off of every pair's contact line (P, K, ``slices``), mm: its
    gap at the slices' centres (:func:`~gearcontact.tca.cylindrical_stencil.
    contact_line_slices`) over the line's least, along the normal (``cos beta_b`` of the
    transverse gap), 0 where ``valid`` (P, K) is False; and the slices themselves.

    Raises
    ------
    CheckFailed
        A valid line's slices left it (NaN gap; docs/cylindrical.md sec. 10).
    """
    sl = contact_line_slices(pair, cycle, slices=slices)
    cos_b = math.cos(math.radians(pair.geometry.base_helix_angle_deg))
    ease = np.where(valid[..., None], cos_b * (sl.gap_mm - cycle.gap_min_mm[..., None]), 0.0)
    if not np.isfinite(ease).all():
        raise CheckFailed("a contact line's slices left it (docs/cylindrical.md sec. 10)")
    return ease, sl
