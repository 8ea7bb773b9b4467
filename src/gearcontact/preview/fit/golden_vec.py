"""Compiled batch kernel of the stage-C golden model, bit-identical to
:func:`.golden.golden_fit`.

The scalar model (:mod:`.golden`) is the readable specification; this module runs the
same operation sequence per stencil in a numba kernel (``cache=True``,
``parallel=True``, one stencil per ``prange`` iteration; without numba the same
kernel runs as plain Python, slowly). :func:`.golden.golden_fit_batch` calls it.

Register widths in the kernel (formats of :mod:`.golden`):

=========  =========  ===========================================================
value      dtype      why it cannot wrap
=========  =========  ===========================================================
acc_j      int64      ``|acc_j| <= 2^31 sum_i |M_ji| < 2^62`` (the caller checks
                      ``sum_i |M_ji| < 2^31`` for the ROM, ACC Q(72,41) values)
c_j        int64      ``round_shift(acc_j, 21)``, checked against COEFF Q(32,20)
h, e       int64      ``|c3 +- c5| < 2^32`` (Q(33,20))
d          uint64     computed only when ``|e| <= isqrt(2^63 - 1)`` (else D overflow),
                      so ``e^2 + c4^2 < 2^63 + 2^62 < 2^64``; checked against
                      D Q(64,40) (``d <= 2^63 - 1``)
r          int64      ``floor(sqrt(d)) < 2^31.5``, the value of the Li-Chu
                      non-restoring isqrt (exact floor, see ``_isqrt``)
A-, B-     int64      ``round_shift(h +- r, 1)``, checked against CURVATURE Q(32,20)
=========  =========  ===========================================================

The kernel also range-checks the gap codes in the same pass over the stencil (an
out-of-range stencil gets the internal flag -1 and :func:`fit_kernel` raises, naming
the code), so a batch is read from memory once. Flag priority and zeroing are those
of the scalar model: coefficient overflow, then
D overflow, then curvature overflow (every numeric output 0), else ``NOT_ELLIPTIC``
when ``B- <= 0`` (outputs kept). The tests compare every code and flag with the
scalar model on more than 10 000 seeded stencils plus the corner stencils.
"""

from __future__ import annotations

import math

import numpy as np

try:  # numba is optional: the kernel is also valid Python (numpy int64 scalars)
    from numba import njit, prange
    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    HAVE_NUMBA = False
    prange = range

    def njit(*args, **kwargs):
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

from ...validation import InputRangeError
from ...contract.qformat import CURVATURE, STENCIL_GAP, FixedPointOverflow
from .pinv import COEFF, N_COEFFS, N_TAPS

__all__ = ["HAVE_NUMBA", "fit_kernel", "fit_element", "fit_constants"]

_U = np.uint64
_FLAG_COEFF, _FLAG_D, _FLAG_CURV, _FLAG_NOT_ELLIPTIC = 1, 2, 4, 8   # .golden FLAG_*


@njit(cache=True, inline="always")
def _isqrt(d):
    """floor(sqrt(d)) for 0 <= d < 2^63: float64 estimate, corrected to the exact floor.

    ``r^2 <= d < (r + 1)^2`` is enforced with uint64 products (``(r + 1)^2 < 2^64`` for
    ``r < 2^31.5 + 1``), so the result is the integer square root, which is what the
    Li-Chu non-restoring algorithm of the scalar model computes bit by bit (32 serial
    steps, about 10 x slower here).
    """
    r = np.int64(math.sqrt(np.float64(d)))
    ud = _U(d)
    while _U(r) * _U(r) > ud:
        r -= 1
    while _U(r + 1) * _U(r + 1) <= ud:
        r += 1
    return r


@njit(cache=True, inline="always")
def fit_element(g, k, w, cst, c_out):
    """The fit datapath on stencil ``g[k]`` (49 STENCIL_GAP codes): coefficient codes into
    ``c_out[k]``; returns ``(a_minus, b_minus, flags)`` (flags -1: a gap code outside
    STENCIL_GAP, the caller names it).

    The per-stencil body of the batch kernel, callable from other compiled loops (the
    drivetrain twin runs stage C once per loaded tooth pair and step, :mod:`gearcontact.
    twin.kernel`). No allocation: ``g`` and ``c_out`` are the caller's 2-D arrays.
    """
    gap_lo, gap_hi, coeff_lo, coeff_hi = cst[0], cst[1], cst[2], cst[3]
    curv_lo, curv_hi, e_max, d_max, shift = cst[4], cst[5], cst[6], cst[7], cst[8]
    half = np.int64(1) << np.int64(shift - 1)
    n_taps = g.shape[1]
    n_coeffs = w.shape[0]
    lo = g[k, 0]
    hi = g[k, 0]
    for i in range(n_taps):          # min/max reduction: vectorizes, unlike a branch
        lo = min(lo, g[k, i])
        hi = max(hi, g[k, i])
    bad_input = lo < gap_lo or hi > gap_hi
    cov = False
    for j in range(n_coeffs):
        acc = np.int64(0)
        for i in range(n_taps):
            acc += w[j, i] * g[k, i]
        cj = (acc + half) >> np.int64(shift)
        c_out[k, j] = cj
        if cj < coeff_lo or cj > coeff_hi:
            cov = True
    flags = 0
    a_minus = np.int64(0)
    b_minus = np.int64(0)
    if bad_input:
        flags = -1
    elif cov:
        flags = _FLAG_COEFF
    else:
        h = c_out[k, 3] + c_out[k, 5]
        e = c_out[k, 3] - c_out[k, 5]
        if abs(e) > e_max:
            flags = _FLAG_D
        else:
            d_u = _U(e * e) + _U(c_out[k, 4] * c_out[k, 4])
            if d_u > _U(d_max):
                flags = _FLAG_D
            else:
                r = _isqrt(np.int64(d_u))
                a_minus = (h + r + np.int64(1)) >> np.int64(1)
                b_minus = (h - r + np.int64(1)) >> np.int64(1)
                if (a_minus < curv_lo or a_minus > curv_hi or b_minus < curv_lo
                        or b_minus > curv_hi):
                    flags = _FLAG_CURV
                elif b_minus <= 0:
                    flags = _FLAG_NOT_ELLIPTIC
    if flags != 0 and flags != _FLAG_NOT_ELLIPTIC:
        for j in range(n_coeffs):
            c_out[k, j] = 0
        a_minus = np.int64(0)
        b_minus = np.int64(0)
    return a_minus, b_minus, flags


@njit(cache=True, parallel=True)
def _kernel(g, w, cst, c_out, a_out, b_out, flags_out):
    for k in prange(g.shape[0]):
        a_minus, b_minus, flags = fit_element(g, k, w, cst, c_out)
        a_out[k] = a_minus
        b_out[k] = b_minus
        flags_out[k] = flags


def fit_constants(shift: int, d_max: int) -> np.ndarray:
    """The constants vector ``cst`` of :func:`fit_element` (int64, 9 entries)."""
    return np.array([STENCIL_GAP.min_code, STENCIL_GAP.max_code, COEFF.min_code, COEFF.max_code,
                     CURVATURE.min_code,
                     CURVATURE.max_code, math.isqrt(d_max), d_max, shift], dtype=np.int64)


def fit_kernel(gap_codes: np.ndarray, weight_codes: np.ndarray, *, coeff_shift: int,
               d_max_code: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Run the compiled fit datapath over validated stencils.

    Parameters
    ----------
    gap_codes : numpy.ndarray of int64, shape (n, 49)
        STENCIL_GAP Q(32,21) codes (checked inside the kernel, in the same pass as the
        MAC).
    weight_codes : numpy.ndarray of int64, shape (6, 49)
        WEIGHT Q(32,20) ROM codes with ``sum_i |M_ji| < 2^31`` per row (caller checks).
    coeff_shift : int, keyword-only
        ACC -> COEFF round shift (21: Q(72,41) -> Q(32,20)).
    d_max_code : int, keyword-only
        Largest D Q(64,40) code (``2^63 - 1``).

    Returns
    -------
    c_codes : numpy.ndarray of int64, shape (n, 6)
        COEFF Q(32,20) codes of c0..c5 (0 on overflow).
    a_minus, b_minus : numpy.ndarray of int64, shape (n,)
        CURVATURE Q(32,20) codes, 1/mm (0 on overflow).
    flags : numpy.ndarray of int64, shape (n,)
        ``FLAG_*`` of :mod:`.golden` (4 bits).

    Raises
    ------
    gearcontact.validation.InputRangeError
        Wrong shapes.
    gearcontact.contract.qformat.FixedPointOverflow
        A gap code outside STENCIL_GAP Q(32,21), named ``gap_codes[k, i]`` (stencil k,
        tap i).
    """
    g = np.ascontiguousarray(gap_codes, dtype=np.int64)
    w = np.ascontiguousarray(weight_codes, dtype=np.int64)
    if g.ndim != 2 or g.shape[1] != N_TAPS or w.shape != (N_COEFFS, N_TAPS):
        raise InputRangeError("gap_codes.shape, weight_codes.shape", (g.shape, w.shape),
                              f"(n, {N_TAPS}), ({N_COEFFS}, {N_TAPS})")
    n = g.shape[0]
    c = np.empty((n, N_COEFFS), np.int64)
    a_minus = np.empty(n, np.int64)
    b_minus = np.empty(n, np.int64)
    flags = np.empty(n, np.int64)
    _kernel(g, w, fit_constants(int(coeff_shift), int(d_max_code)), c, a_minus, b_minus, flags)
    bad = np.flatnonzero(flags < 0)
    if bad.size:                      # name the first code outside STENCIL_GAP
        k = int(bad[0])
        i = int(np.flatnonzero(~STENCIL_GAP.fits(g[k]))[0])
        raise FixedPointOverflow(f"gap_codes[{k}, {i}]", int(g[k, i]), STENCIL_GAP)
    return c, a_minus, b_minus, flags
