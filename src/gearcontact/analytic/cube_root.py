"""The cube root of the twin's fp64 contact law, the same bits in Python, numba and C.

:func:`cbrt_positive` is a seed polynomial on the mantissa and one Halley step, within 5
ulp of the exact cube root of a positive normal double (libm's ``cbrt`` elsewhere). It
replaces libm's ``cbrt`` in the twin's compiled Hamrock–Brewe law and libm's ``pow(W,
2/3)`` in its golden kappa (:mod:`gearcontact.twin.contact_law`), and in the exported C
(``gc_cbrt.h``'s ``gc_cbrt_positive``, every constant printed from
:func:`seed_coefficients`): the
drivetrain FMU must repeat the twin bit for bit (through rattle an ulp of difference
grows to ~5e-8 in 2,000 steps), and glibc's ``cbrt`` costs ~130 instructions with its
``frexp`` and ``ldexp`` calls, this one ~35 (docs/export.md). Every operation is an IEEE
operation in a fixed order (``frexp`` and ``ldexp`` and the scaling by ``2^r`` are
exact), so the three agree to the bit wherever no fused multiply-add is formed (numba
without ``fastmath``; the C compiled with ``-ffp-contract=off``).

The seed ``p(m - 3/2) ~ m^(1/3)`` on ``m in [1, 2)`` interpolates at the
``SEED_DEGREE + 1`` Chebyshev points of [1, 2] (nodes on a 2^-20 grid), solved in exact
rationals from cube roots in integer arithmetic, coefficients rounded to 2^-SEED_BITS:
the same literals on every machine; its relative error is below 2^-18 (measured by
:func:`gearcontact.export.c_constants.cbrt_seed`), so one Halley step leaves
``2 eps^3 / 3 < 2^-54`` before rounding (the proof: ``gc_hertz_fp64.c``).
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from functools import lru_cache

import numpy as np

__all__ = ["SEED_DEGREE", "SEED_BITS", "seed_coefficients", "cbrt_fraction",
           "cbrt_positive"]

#: Degree of the seed polynomial and the grid (2^-SEED_BITS) its coefficients are
#: rounded to.
SEED_DEGREE, SEED_BITS = 5, 50


def _icbrt(n: int) -> int:
    """floor(n^(1/3)) of an integer n >= 0 (integer Newton from above)."""
    if n < 2:
        return n
    y = 1 << -(-n.bit_length() // 3)              # > n^(1/3)
    while True:
        z = (2 * y + n // (y * y)) // 3
        if z >= y:
            return y
        y = z


def cbrt_fraction(x: Fraction, bits: int = 80) -> Fraction:
    """x^(1/3) of a rational x > 0 within 2^-bits (integer arithmetic: the same on
    every machine)."""
    return Fraction(_icbrt(math.floor(x * 2 ** (3 * bits))), 2 ** bits)


@lru_cache(maxsize=1)
def seed_coefficients() -> tuple[tuple[float, ...], tuple[float, ...]]:
    """``(poly, scale)``: the seed polynomial's coefficients (constant first) and
    ``2^(r/3)`` for ``r = 0, 1, 2``, each rounded to 2^-SEED_BITS (module docstring)."""
    n = SEED_DEGREE + 1
    grid = 2 ** 20
    nodes = [Fraction(round(math.cos(math.pi * (k + 0.5) / n) * grid / 2), grid)
             for k in range(n)]                     # u = m - 3/2 in [-1/2, 1/2]
    values = [cbrt_fraction(Fraction(3, 2) + u) for u in nodes]
    # Vandermonde solve in exact rationals (Gauss-Jordan)
    a = [[u ** j for j in range(n)] + [v] for u, v in zip(nodes, values)]
    for col in range(n):
        piv = next(r for r in range(col, n) if a[r][col] != 0)
        a[col], a[piv] = a[piv], a[col]
        a[col] = [x / a[col][col] for x in a[col]]
        for r in range(n):
            if r != col and a[r][col] != 0:
                a[r] = [x - a[r][col] * y for x, y in zip(a[r], a[col])]
    step = 2 ** SEED_BITS
    poly = tuple(float(Fraction(round(a[j][n] * step), step)) for j in range(n))
    scale = tuple(float(Fraction(round(cbrt_fraction(Fraction(2 ** r)) * step), step))
                  for r in range(3))
    return poly, scale


_POLY, _SCALE = seed_coefficients()
_P0, _P1, _P2, _P3, _P4, _P5 = _POLY
_DBL_MIN, _DBL_MAX = sys.float_info.min, sys.float_info.max


def cbrt_positive(x: float) -> float:
    """x^(1/3) within 5 ulp for a positive normal double x; libm's cube root otherwise
    (numba compiles this function as it stands: no Python helper inside).

    ``x = 2^(3q + r) m`` with ``m in [1, 2)``, ``r in {0, 1, 2}``; ``t = 2^r m``; seed
    ``y0 = p(m - 3/2) 2^(r/3)``, one Halley step ``y0 (y0^3 + 2t) / (2 y0^3 + t)``, then
    the exact scaling by ``2^q`` -- the operations of ``gc_hertz_fp64.c``'s
    ``cbrt_positive`` in its order."""
    if not (x >= _DBL_MIN and x <= _DBL_MAX):
        return float(np.cbrt(x))
    half_m, e = math.frexp(x)                      # x = half_m 2^e, half_m in [1/2, 1)
    m = 2.0 * half_m
    e -= 1
    q = e // 3
    r = e - 3 * q
    t = m * float(1 << r)
    u = m - 1.5                                    # exact: m and 1.5 share an exponent
    y = (((((_P5 * u + _P4) * u + _P3) * u + _P2) * u + _P1) * u + _P0)
    y *= _SCALE[r]
    y3 = y * y * y
    y = y * (y3 + 2.0 * t) / (2.0 * y3 + t)
    return math.ldexp(y, q)
