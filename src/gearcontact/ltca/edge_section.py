"""The edge-against-flank section: how much more a tip edge's section of a line contact
yields than the line's own Hertz section under the same load per unit length
(docs/cylindrical.md sec. 10, "The edge slices' own law").

The slice law (:mod:`.slice_law`) carries a line on a Winkler foundation whose
stiffness per unit length is the finite line's, ``w = (d - h) / (lambda' g)`` with
``lambda' = 4 / (pi E')`` and ``g = ln(4 L_c / b) - 3/4``. Of ``g`` the length term
``ln(4 L_c)`` is the line's (the far field of the load along it), ``-ln(b) - 3/4`` its
*section's*: the logarithmic energy of the semi-elliptic pressure across the line and
the gap it fills (Johnson 1985 sec. 4.3 and 5.6; the energy mean of
:func:`gearcontact.analytic.hertz.line_contact_approach_mm`). A tip edge beyond the
line's end (the loaded TE's edge rows, :mod:`.cylindrical_edges`) touches the mating
flank with its section cut at the edge: pressure only on ``x >= 0``, into the edge's own
flank, against the gap ``s x + x^2 / (2 R)`` (``s`` the sine of the angle between the
flanks, ``1/R`` the relative curvature across; no material beyond the edge). Its
section term differs from the line's by

    Delta(chi) = (d_edge - d_line) / (lambda' w),   chi = s (R / (lambda' w))^(1/2)

the difference of the two plane sections' approaches (at the edge, at the line's
centre) under the same load per length ``w``, in the foundation's units; the length
term is shared. So an edge slice's foundation is ``w = (d - h) / (lambda' (g +
Delta))``: softer than the line's by the factor ``g / (g + Delta)``
(:func:`edge_stiffness_factor`). ``chi`` is the only parameter: lengths scale with
``(lambda' w R)^(1/2)`` (the Hertz section's ``b / 2^(1/2)``), the log kernel's scale
cancels in the difference. ``Delta(0)`` is the half section cut at its centre, and
``Delta`` grows with the slope (a narrower contact, a deeper logarithm).

The plane sections are solved on the log kernel of the plane-strain half-planes
(``u(x) = -lambda' integral(p(x') ln|x - x'| dx')`` for the two bodies together), the
pressure piecewise constant on ``cells`` cells, by the exact active set of the
load-constrained complementarity problem (:func:`section_approach`).

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 2.2, 4.3, 5.6.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ..errors import CheckFailed
from ..halfspace.lcp import bordered_active_set
from ..validation import check_range

__all__ = ["SECTION_CELLS", "edge_section_excess", "edge_stiffness_factor",
           "section_approach"]

#: Cells of a plane section (:func:`section_approach`): Delta within 5e-3 (0.3 %) of
#: 1600 cells over chi = 0-2 (tests/ltca/test_edge_section.py), the edge's stiffness
#: factor g / (g + Delta) within 0.1 %.
SECTION_CELLS = 200
#: Half-width of the sections' domain in the unit length ``(lambda' w R)^(1/2)``: the
#: Hertz section's half-width is 2^(1/2), the cut one's contact 1.63 at ``chi = 0`` and
#: narrower with the slope.
_DOMAIN = 2.5
_ACTIVE_SET_PASSES = 200


def _log_kernel(xc, dx):
    """``-integral(ln|x_i - x'| dx')`` over cell j (width ``dx``) at the centres ``xc``."""
    def prim(t):
        return np.where(t == 0.0, 0.0, t * np.log(np.abs(np.where(t == 0.0, 1.0, t))) - t)
    t = xc[:, None] - xc[None, :]
    return -(prim(t + 0.5 * dx) - prim(t - 0.5 * dx))


def section_approach(chi: float, *, one_sided: bool, cells: int = SECTION_CELLS) -> float:
    """Approach of a plane section under a unit load per length, in ``lambda' w`` and on
    the log kernel's unit length ``(lambda' w R)^(1/2)`` (module docstring): the gap
    ``chi x + x^2 / 2`` on ``x >= 0`` only (``one_sided``, the edge; its approach at the
    edge ``x = 0``) or ``x^2 / 2`` on both sides (the line's Hertz section, ``chi``
    unused; at its centre). The exact solution of the discretised problem: ``K p + h =
    d`` where loaded, ``>= d`` elsewhere, ``p >= 0``, ``sum(p) dx = 1``."""
    x = np.linspace(0.0 if one_sided else -_DOMAIN, _DOMAIN, int(cells) + 1)
    xc, dx = 0.5 * (x[1:] + x[:-1]), x[1] - x[0]
    h = (chi * xc if one_sided else 0.0) + 0.5 * xc * xc
    # forces w = p dx on the cells: K/dx w + h - d >= 0, sum(w) = 1 (the half-space
    # LCP's bordered active set); start from the contact of chi = 0 (the Hertz
    # half-width 2^(1/2); the cut section's 1.63), which the slope narrows
    on = np.abs(xc) <= (1.7 if one_sided else 1.45)
    w, d, _, ok, msg = bordered_active_set(_log_kernel(xc, dx) / dx, h, 1.0, on, 1e-12,
                                           _ACTIVE_SET_PASSES, False)
    if not ok:
        raise CheckFailed(f"plane section (chi {chi:g}): {msg}")
    if w[-1] > 0.0:
        raise CheckFailed(f"plane section (chi {chi:g}): the contact reaches the domain's end")
    return float(d)


def edge_section_excess(chi: float, *, cells: int = SECTION_CELLS) -> float:
    """``Delta(chi)`` (module docstring): the edge section's approach at the edge over the
    line's Hertz section's at its centre, at the same load per length, in ``lambda' w``;
    ``chi >= 0`` the edge's slope parameter."""
    c = check_range("chi (edge section slope parameter)", chi, 0.0, 1e3)
    return section_approach(c, one_sided=True, cells=cells) - _line_section(cells)


@functools.lru_cache(maxsize=4)
def _line_section(cells: int) -> float:
    return section_approach(0.0, one_sided=False, cells=cells)


def edge_stiffness_factor(*, slope: float, edge_radius_mm: float, line_load_n_per_mm: float,
                          line_length_mm: float, line_radius_mm: float,
                          e_prime_mpa: float) -> tuple[float, float, float]:
    """``(g / (g + Delta), Delta, chi)``: the edge slices' foundation stiffness relative to
    the line's (module docstring) at the load per length ``line_load_n_per_mm`` (N/mm)
    on a line of ``line_length_mm`` across the relative radius ``line_radius_mm`` (its
    ``g = ln(4 L / b) - 3/4``, ``b = (4 w R / (pi E'))^(1/2)``), for an edge of ``slope``
    (sine of the angle between the flanks) and relative radius across it
    ``edge_radius_mm``; ``e_prime_mpa`` Hamrock-Brewe's ``E' = 2 E*``."""
    lam = 4.0 / (math.pi * e_prime_mpa)
    w = line_load_n_per_mm
    chi = slope * math.sqrt(edge_radius_mm / (lam * w))
    delta = edge_section_excess(chi)
    g = math.log(4.0 * line_length_mm / math.sqrt(lam * w * line_radius_mm)) - 0.75
    return g / (g + delta), delta, chi
