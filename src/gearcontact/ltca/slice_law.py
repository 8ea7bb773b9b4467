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

__all__ = ["interference", "loaded_line", "loaded_length_mm", "line_easeoff_mm",
           "equivalent_length"]


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
