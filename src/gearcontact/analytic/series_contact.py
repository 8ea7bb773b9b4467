"""Hertzian contact in series with a linear compliance: the load of a pair at an approach.

A tooth pair whose contact approach is Hertzian, ``kappa W^(2/3)``, and whose teeth bend
linearly, ``c_b W`` (the shell bending of both teeth under the pair's pressure,
:func:`gearcontact.ltca.tooth_bending.pair_bending_compliance`), closes by ``d = kappa
W^(2/3) + c_b W``. :func:`series_pair_load` inverts that for ``W``: the one law of the
twin's compiled kernel (:mod:`gearcontact.twin.contact_law`, which compiles this
function with numba) and of the loaded TE's preview with bending
(:func:`gearcontact.ltca.lte_phase.preview_balance`). Plain Python on scalars, numba
compatible.

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 3.4 (Hertzian approach).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["series_pair_load"]


def series_pair_load(d, kap, cb, s_prev):
    """(W N, s = W^(1/3)) of a pair at approach ``d`` (mm, > 0): Hertz ``d = kap W^(2/3)``
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
