"""Batched one-dimensional searches on arrays of independent problems (numpy, no
loops over the problems): the line searches of the cylindrical TCA
(:mod:`.cylindrical_cycle`, :mod:`.cylindrical_tip`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["affine_interval", "golden_min", "bisect_root"]

_GR = 0.5 * (math.sqrt(5.0) - 1.0)


def affine_interval(zlo, zhi, c_lo, c_hi, lo, hi):
    """Where ``lo <= c(z) <= hi`` on [zlo, zhi] for c affine between its end values."""
    slope = (c_hi - c_lo) / (zhi - zlo)
    flat = np.abs(c_hi - c_lo) < 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        za = zlo + (lo - c_lo) / slope
        zb = zlo + (hi - c_lo) / slope
    a = np.where(slope > 0, za, zb)
    b = np.where(slope > 0, zb, za)
    mid = 0.5 * (c_lo + c_hi)
    inside = (mid >= lo) & (mid <= hi)
    a = np.where(flat, np.where(inside, zlo, np.inf), np.maximum(a, zlo))
    b = np.where(flat, np.where(inside, zhi, -np.inf), np.minimum(b, zhi))
    return a, b


def golden_min(f, a, b, *, steps: int):
    """Vectorized golden-section minimum of the convex ``f`` on [a, b]."""
    c, d = b - _GR * (b - a), a + _GR * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(int(steps)):
        left = fc < fd
        b, a = np.where(left, d, b), np.where(left, a, c)
        c_new = np.where(left, b - _GR * (b - a), d)
        d_new = np.where(left, c, a + _GR * (b - a))
        fnew = f(np.where(left, c_new, d_new))
        fc, fd = np.where(left, fnew, fd), np.where(left, fc, fnew)
        c, d = c_new, d_new
    return 0.5 * (a + b)


def bisect_root(f, a, b, *, steps: int):
    """Vectorized bisection for ``f(a) <= 0 < f(b)`` or ``f(a) > 0 >= f(b)``."""
    fa = f(a)
    for _ in range(int(steps)):
        m = 0.5 * (a + b)
        fm = f(m)
        same = np.sign(fm) == np.sign(fa)
        a, fa = np.where(same, m, a), np.where(same, fm, fa)
        b = np.where(same, b, m)
    return 0.5 * (a + b)
