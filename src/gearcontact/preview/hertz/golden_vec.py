"""Vectorized stage-D golden model, bit-identical to :func:`.golden.hertz_golden`.

The scalar model (:mod:`.golden`) is the readable specification; this module runs the
same operation sequence over numpy arrays in a numba kernel (``cache=True``,
``parallel=True``; without numba the same kernel runs as plain Python, slowly).
Every register is a ``uint64`` (after the envelope check all values are
non-negative and below 2^64, see :mod:`.formats`); the three dividends
wider than 64 bits (C_a < 2^75, b < 2^66, p_n2 < 2^80) are divided exactly by
schoolbook long division in five 16-bit digits (each partial remainder is below the
divisor < 2^42, so ``rem * 2^16 + digit`` fits 64 bits) — Knuth, TAOCP vol. 2,
sec. 4.3.1, Algorithm D with a single-word divisor. The tests compare codes and flags
with the scalar model on more than 20 000 seeded vectors plus the envelope corners, and
on 5 000 more with ``hertz_form="exact"`` (the kernel then takes the E_e dividend from
the EEX table, which shares the POW geometry, instead of the constant N5).

Every divisor is provably positive once the envelope check has passed (A_min >= 2^9,
alpha >= 2^24, E' >= 2^12, K >= 2^24, a_w >= 2^27, b_w >= 2^23), so the scalar
model's zero-divisor branch (``FLAG_DIV_ZERO``) is unreachable and not replicated.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

try:  # numba is optional: the kernel is also valid Python (numpy uint64 scalars)
    from numba import njit, prange
    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    HAVE_NUMBA = False
    prange = range

    def njit(*args, **kwargs):
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

from ...contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS
from . import formats as F
from .luts import CBRT_SPEC, EE_DIVIDEND_SHIFT, EE_EXACT_SPEC, POW_SPEC, POW_SPECS, lut_array

__all__ = ["HertzCodesArray", "hertz_golden_array", "hertz_element", "golden_constants",
           "run_batch", "HAVE_NUMBA"]

_U = np.uint64


@dataclass(frozen=True)
class HertzCodesArray:
    """Output registers of a batch of stage-D runs (``int64`` arrays, same shape).

    Fields as in :class:`.golden.HertzCodes`: ``a_code, b_code`` (Q(32,20), mm),
    ``p_max_code`` (Q(32,8), MPa), ``k_code`` (Q(32,20)), ``A_min_code, B_max_code``
    (Q(32,20), 1/mm), ``R_x_code, R_y_code`` (Q(32,20), mm), ``alpha_code``
    (UQ(32,24)) and ``flags``.
    """

    a_code: np.ndarray
    b_code: np.ndarray
    p_max_code: np.ndarray
    k_code: np.ndarray
    A_min_code: np.ndarray
    B_max_code: np.ndarray
    R_x_code: np.ndarray
    R_y_code: np.ndarray
    alpha_code: np.ndarray
    flags: np.ndarray

    @property
    def valid(self) -> np.ndarray:
        """Boolean array: no flag set."""
        return self.flags == 0


@njit(cache=True, inline="always")
def _rs(x, n):
    """Round-half-up right shift of a uint64 by n >= 1 bits."""
    return (x + (_U(1) << _U(n - 1))) >> _U(n)


@njit(cache=True)
def _div_wide(x, s, d):
    """floor(x * 2^s / d) for uint64 x, x 2^s < 2^80, 0 < d < 2^48, quotient < 2^64."""
    rem = _U(0)
    q = _U(0)
    for j in range(5):
        t = 64 - 16 * j
        if t >= s:
            digit = (x >> _U(t - s)) & _U(0xFFFF)
        else:
            digit = (x << _U(s - t)) & _U(0xFFFF)
        cur = (rem << _U(16)) | digit
        qd = cur // d
        rem = cur - qd * d
        q = (q << _U(16)) | qd
    return q


@njit(cache=True)
def _msb(x):
    """Index of the most significant set bit of a uint64 x > 0."""
    n = 0
    for sh in (32, 16, 8, 4, 2, 1):
        if x >> _U(sh):
            x >>= _U(sh)
            n += sh
    return n


@njit(cache=True, inline="always")
def _interp(arg, lut, x0, tbits, qbits, corr_shift):
    """LUT interpolation, see :func:`.luts.lut_interpolate`."""
    off = arg - _U(x0)
    i = np.int64(off >> _U(tbits))
    r = off & ((_U(1) << _U(tbits)) - _U(1))
    w0 = _U(lut[i])
    v0 = w0 >> _U(qbits)
    q0 = w0 & ((_U(1) << _U(qbits)) - _U(1))
    v1 = _U(lut[i + 1]) >> _U(qbits)
    t_full = _U(1) << _U(tbits)
    return v0 * t_full + r * (v1 - v0) + _rs(r * (t_full - r) * q0, corr_shift)


@njit(cache=True, inline="always")
def hertz_element(a_min, b_max, w, e, pow_lut, cbrt_lut, cst):
    """Stage D on one set of codes (sorted curvatures ``a_min <= b_max``, load, E').

    The per-element body of the batch kernel, callable from other compiled loops (the
    drivetrain twin calls it once per loaded tooth pair and step). ``pow_lut`` is the
    POW ROM of the form; for the exact form it holds POWX followed by EEX (one 512-word
    ROM, as in the RTL), ``cst[25]`` being the EEX offset (:func:`golden_constants`).

    Returns
    -------
    tuple of int
        ``(flags, a_code, b_code, p_max_code, k_code, R_x_code, R_y_code, alpha_code)``;
        all outputs 0 when ``flags != 0``.
    """
    curv_lo, curv_hi, w_lo, w_hi, e_lo, e_hi = cst[0], cst[1], cst[2], cst[3], cst[4], cst[5]
    alpha_max, c6, n5, c3 = cst[6], cst[7], cst[8], cst[9]
    pow_x0, pow_t, pow_qb, pow_cs, pow_of = cst[10], cst[11], cst[12], cst[13], cst[14]
    cbrt_x0, cbrt_t, cbrt_qb, cbrt_cs = cst[15], cst[16], cst[17], cst[18]
    k_max, axis_max, pmax_max, curv_max_out = cst[19], cst[20], cst[21], cst[22]
    exact, ee_shift, ee_off = cst[23], cst[24], cst[25]
    flags = 0
    if a_min <= 0:
        flags |= 1
    elif a_min < curv_lo or b_max > curv_hi:
        flags |= 2
    if w < w_lo or w > w_hi:
        flags |= 4
    if e < e_lo or e > e_hi:
        flags |= 8
    if flags != 0:
        return flags, 0, 0, 0, 0, 0, 0, 0
    ua = _U(a_min)
    ub = _U(b_max)
    uw = _U(w)
    ue = _U(e)
    r_x = _rs((_U(1) << _U(40)) // ua, 1)
    r_y = _rs((_U(1) << _U(40)) // ub, 1)
    alpha = (ub << _U(24)) // ua
    if alpha > _U(alpha_max):
        return 16, 0, 0, 0, 0, 0, 0, 0
    radius = (_U(1) << _U(42)) // (ua + ub)
    k_int = _rs(_interp(alpha, pow_lut, pow_x0, pow_t, pow_qb, pow_cs), pow_of)
    if exact:      # EEX table (same geometry as POW) instead of N5
        n_ee = _interp(alpha, pow_lut[ee_off:], pow_x0, pow_t, pow_qb, pow_cs) \
            << _U(ee_shift)
    else:
        n_ee = _U(n5)
    e6 = _U(c6) + n_ee // alpha
    k2 = _rs(k_int * k_int, 20)
    t1 = _rs(k2 * e6, 32)
    t2 = _rs(t1 * radius, 18)
    t3 = t2 * uw
    c_a = _div_wide(t3, 11, ue)
    p = (_msb(c_a) - 45) // 3
    sh = 45 + 3 * p - 29
    if sh >= 0:
        m = c_a >> _U(sh)
    else:
        m = c_a << _U(-sh)
    cbrt = _interp(m, cbrt_lut, cbrt_x0, cbrt_t, cbrt_qb, cbrt_cs)
    a_w = _rs(cbrt, 10 - p)
    b_w = _div_wide(a_w, 24, k_int)
    pn2 = _div_wide(uw * _U(c3), 16, a_w)
    p_max = _rs((pn2 << _U(17)) // b_w, 1)
    a_c = _rs(a_w, 16)
    b_c = _rs(b_w, 16)
    k_c = _rs(k_int, 4)
    if (a_c > _U(axis_max) or b_c > _U(axis_max) or p_max > _U(pmax_max)
            or k_c > _U(k_max) or r_x > _U(curv_max_out) or r_y > _U(curv_max_out)):
        return 32, 0, 0, 0, 0, 0, 0, 0
    return (0, np.int64(a_c), np.int64(b_c), np.int64(p_max), np.int64(k_c),
            np.int64(r_x), np.int64(r_y), np.int64(alpha))


@njit(cache=True, parallel=True)
def _kernel(A, B, W, E, pow_lut, cbrt_lut, cst, out):
    n = A.shape[0]
    for j in prange(n):
        a_min = min(A[j], B[j])
        b_max = max(A[j], B[j])
        out[4, j] = a_min
        out[5, j] = b_max
        flags, a_c, b_c, p_max, k_c, r_x, r_y, alpha = hertz_element(
            a_min, b_max, W[j], E[j], pow_lut, cbrt_lut, cst)
        out[0, j] = a_c
        out[1, j] = b_c
        out[2, j] = p_max
        out[3, j] = k_c
        out[6, j] = r_x
        out[7, j] = r_y
        out[8, j] = alpha
        out[9, j] = flags


def golden_constants(hertz_form: str = F.DEFAULT_HERTZ_FORM
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(pow_lut, cbrt_lut, constants)``: the ROMs and the constant vector that
    :func:`hertz_element` takes for ``hertz_form`` (the exact form's POW ROM is POWX
    followed by EEX)."""
    exact = F.check_hertz_form(hertz_form) == "exact"
    pow_lut = lut_array(POW_SPECS[hertz_form])
    if exact:
        pow_lut = np.concatenate([pow_lut, lut_array(EE_EXACT_SPEC)])
    return pow_lut, lut_array(CBRT_SPEC), _constants(exact, ee_offset=len(pow_lut) // 2)


def _constants(exact: bool, *, ee_offset: int) -> np.ndarray:
    vals = (F.CURV_MIN_CODE, F.CURV_MAX_CODE, F.LOAD_MIN_CODE, F.LOAD_MAX_CODE,
            F.E_PRIME_MIN_CODE, F.E_PRIME_MAX_CODE, F.ALPHA_MAX_CODE, F.C6, F.N5, F.C3,
            # POW geometry serves POW, POWX and EEX (luts.same_geometry)
            POW_SPEC.x0_code, POW_SPEC.tbits, POW_SPEC.qbits, POW_SPEC.corr_shift,
            POW_SPEC.out_frac - F.K_INT.frac, CBRT_SPEC.x0_code, CBRT_SPEC.tbits,
            CBRT_SPEC.qbits, CBRT_SPEC.corr_shift, F.K_OUT.max_code, SEMI_AXIS.max_code,
            PMAX.max_code, CURVATURE.max_code, int(exact), EE_DIVIDEND_SHIFT, int(ee_offset))
    return np.array(vals, dtype=np.int64)


def _kernel_shifts_match_formats() -> bool:
    """The literal shifts in the kernel are the format differences of :mod:`.formats`."""
    return ((F.K_INT.frac * 2 - F.K2.frac, F.K2.frac + F.E6.frac - F.T1.frac,
             F.T1.frac + F.RADIUS.frac - F.T2.frac, F.CA.frac - F.T3.frac, F.CA.frac,
             F.M_RED.frac, F.CBRT_VAL.frac - F.AXIS_W.frac, F.K_INT.frac,
             F.AXIS_W.frac - SEMI_AXIS.frac, F.K_INT.frac - F.K_OUT.frac, F.ALPHA.frac,
             F.PN2_SHIFT, F.PMAX_SHIFT)
            == (20, 32, 18, 11, 45, 29, 10, 24, 16, 4, 24, 16, 17))


assert _kernel_shifts_match_formats()


def _as_codes(x, fmt, field: str) -> np.ndarray:
    arr = np.asarray(x)
    if arr.dtype.kind not in "iu":
        raise TypeError(f"{field} must be an integer array, got dtype {arr.dtype}")
    arr = arr.astype(np.int64)
    fmt.check(arr, field=field)
    return arr


def hertz_golden_array(A_code, B_code, W_code, *, e_prime_code,
                       hertz_form: str = F.DEFAULT_HERTZ_FORM) -> HertzCodesArray:
    """Stage-D golden model over broadcastable integer arrays (bit-identical to
    :func:`.golden.hertz_golden`).

    Parameters
    ----------
    A_code, B_code : array_like of int
        CURVATURE Q(32,20) codes, 1/mm.
    W_code : array_like of int
        LOAD Q(32,8) codes, N.
    e_prime_code : int or array_like of int
        E' codes, Q(32,0) MPa.
    hertz_form : {"hamrock-brewe", "exact"}
        As in :func:`.golden.hertz_golden`.

    Returns
    -------
    HertzCodesArray
        ``int64`` arrays of the broadcast shape.

    Raises
    ------
    FixedPointOverflow
        A code that does not fit its 32-bit register (naming field and index).
    InputRangeError
        Unknown ``hertz_form``.
    """
    F.check_hertz_form(hertz_form)
    return run_batch(_kernel, HertzCodesArray, 10,
                     ((A_code, CURVATURE, "A_code"), (B_code, CURVATURE, "B_code"),
                      (W_code, LOAD, "W_code"), (e_prime_code, F.E_PRIME, "e_prime_code")),
                     golden_constants(hertz_form))


def run_batch(kernel, result_type, n_rows: int, inputs, constants):
    """Check and broadcast ``inputs`` ((value, format, field) triples: integer codes
    that must fit their register), run ``kernel(*flat inputs, *constants, out)`` over
    them and return ``result_type`` of the ``n_rows`` output rows in the broadcast shape.

    Raises
    ------
    TypeError
        A non-integer array.
    FixedPointOverflow
        A code that does not fit its register (naming field and index).
    """
    arrs = np.broadcast_arrays(*(_as_codes(v, fmt, name) for v, fmt, name in inputs))
    shape = arrs[0].shape
    flat = [np.array(a.reshape(-1), dtype=np.int64) for a in arrs]   # owned copies
    out = np.zeros((n_rows, flat[0].size), dtype=np.int64)
    kernel(*flat, *constants, out)
    return result_type(*(out[i].reshape(shape) for i in range(n_rows)))
