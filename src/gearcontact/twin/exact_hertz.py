"""The exact elliptic Hertz law of the twin (``hertz_form="exact"``): a table over the
log curvature ratio, built once with scipy, interpolated in the compiled law.

Exact Hertz (Johnson 1985, eqs. 4.39-4.41; :func:`gearcontact.analytic.hertz.
exact_elliptic_hertz`) depends on the curvature ratio ``alpha = B_max/A_min`` only
through ``p = (b/a)^2`` (the root of the eccentricity equation) and the complete
elliptic integrals at it; with them

    a = c_a(alpha) (W / (E' A_min))^(1/3),   c_a = (R_D(0, p, 1)/pi)^(1/3),
    b = a sqrt(p),   p_max = 3 W/(2 pi a b),   delta = 3 W K(p)/(pi a E'),  K = R_F(0, p, 1).

The table holds, on the uniform grid ``u_i = i h`` of ``u = ln alpha`` (:data:`STEP`,
``i = 0 ..`` :data:`ROWS` - 1, up to :data:`RATIO_MAX`), the three smooth functions
``ln c_a``, ``ln sqrt(p)``, ``ln K``: ``p`` by the package's Brent solve
(:func:`gearcontact.analytic.hertz._solve_p`, 4 eps), ``R_D``, ``R_F`` by scipy's
Carlson integrals, the same as the exact solution. The compiled law interpolates each
with the 4-point Lagrange cubic on the rows ``i-1 .. i+2`` around ``u`` (one-sided at
the table's ends); the error of the cubic is ``h^4 |f''''| 3/128`` at most, and at
``h = 0.02`` measured below 1e-10 in each log over ratios 1 .. 1.4e5 against the
solution at the point: the declared bound :data:`REL_BOUND` = 1e-8 on a, b, p_max,
the approach and the stiffness (tests/twin/test_exact_hertz.py). No special function
is evaluated in the compiled code (``log``, ``exp`` and the library's cube root only).

Beyond :data:`RATIO_MAX` (1e8: a semi-axis ratio of ~3e4, a line contact on any flank)
the table has no answer: the twin's kernel counts such a preview without a contact law
(:func:`~.contact_law._fp64_law`) and :func:`~.model.build_model` refuses a mesh row
beyond it before the run.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit
from scipy.special import elliprd, elliprf

from ..analytic.cube_root import cbrt_positive
from ..analytic.hertz import _solve_p

__all__ = ["STEP", "RATIO_MAX", "ROWS", "COLUMNS", "REL_BOUND", "exact_hertz_table",
           "exact_hertz_terms"]

#: Grid step of the table in ``ln alpha`` (dimensionless).
STEP = 0.02
#: Largest curvature ratio the table covers (dimensionless).
RATIO_MAX = 1e8
#: Rows of the table: ``u = 0 .. (ROWS - 1) STEP >= ln RATIO_MAX``.
ROWS = int(math.ceil(math.log(RATIO_MAX) / STEP)) + 1
#: Columns per row: ``ln c_a``, ``ln sqrt(p)``, ``ln K`` (module docstring).
COLUMNS = 3
#: Declared relative bound of the interpolated law against exact Hertz at the point
#: (a, b, p_max, approach, stiffness; module docstring).
REL_BOUND = 1e-8

_INV_STEP = 1.0 / STEP
_THREE_OVER_PI = 3.0 / math.pi
_THREE_OVER_2PI = 1.5 / math.pi
_cbrt = njit(cache=True, inline="always", error_model="numpy")(cbrt_positive)


@lru_cache(maxsize=1)
def exact_hertz_table() -> np.ndarray:
    """The table, ``(ROWS * COLUMNS,)`` row-major, read-only (built once per process,
    ~0.1 s)."""
    u = np.arange(ROWS) * STEP
    p = np.array([1.0] + [_solve_p(math.exp(x)) for x in u[1:]])
    tab = np.column_stack([np.log(elliprd(0.0, p, 1.0) / math.pi) / 3.0, 0.5 * np.log(p),
                           np.log(elliprf(0.0, p, 1.0))]).ravel()
    tab.setflags(write=False)
    return tab


@njit(cache=True, inline="always", error_model="numpy")
def exact_hertz_terms(a_min, b_max, load_n, e_prime_mpa, tab, offset):
    """``(a_mm, b_mm, p_max_mpa, approach_mm)`` of exact Hertz from the table
    ``tab[offset:]`` (:func:`exact_hertz_table`). The caller guarantees ``0 < a_min <=
    b_max <= RATIO_MAX a_min`` (1/mm), ``load_n > 0`` (N), ``e_prime_mpa > 0`` (MPa)."""
    t = math.log(b_max / a_min) * _INV_STEP
    i = min(max(int(t), 1), ROWS - 3)
    s = t - i
    w0 = -s * (s - 1.0) * (s - 2.0) / 6.0
    w1 = (s + 1.0) * (s - 1.0) * (s - 2.0) * 0.5
    w2 = -(s + 1.0) * s * (s - 2.0) * 0.5
    w3 = (s + 1.0) * s * (s - 1.0) / 6.0
    r = offset + COLUMNS * (i - 1)
    ln_ca = (w0 * tab[r] + w1 * tab[r + 3] + w2 * tab[r + 6] + w3 * tab[r + 9])
    ln_q = (w0 * tab[r + 1] + w1 * tab[r + 4] + w2 * tab[r + 7] + w3 * tab[r + 10])
    ln_k = (w0 * tab[r + 2] + w1 * tab[r + 5] + w2 * tab[r + 8] + w3 * tab[r + 11])
    a = math.exp(ln_ca) * _cbrt(load_n / (e_prime_mpa * a_min))
    b = a * math.exp(ln_q)
    p_max = _THREE_OVER_2PI * load_n / (a * b)
    delta = _THREE_OVER_PI * load_n * math.exp(ln_k) / (a * e_prime_mpa)
    return a, b, p_max, delta
