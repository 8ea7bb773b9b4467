"""Vectorized line-core golden model, bit-identical to :func:`.line.line_golden`.

The scalar model (:mod:`.line`) is the readable specification; this module runs the
same operation sequence over numpy arrays in a numba kernel (``cache=True``,
``parallel=True``; without numba the kernel runs as plain Python, slowly), as
:mod:`.golden_vec` does for the published core, whose per-element body
(:func:`.golden_vec.hertz_element`) it calls for the SCALEd elliptic run.

Registers are ``uint64`` once the line envelope has passed (all values non-negative;
bounds in :mod:`.line`): ``(W C_IPI) << 4 < 2^60``, ``QPI E' < 2^61``,
``P0SQ = Y B_max < 2^64``. The two operations wider than 64 bits are done exactly:

* SQRT, ``floor(sqrt(P0SQ << 9))`` of a 73-bit radicand: the 40-iteration restoring
  recurrence of :mod:`.sqrt` itself, taking the radicand's bit pairs straight from
  ``P0SQ`` (remainder <= 2 root < 2^38);
* DIV_BL, ``(QPI << 29) // S`` (< 2^69 over S < 2^37): the schoolbook long division
  of :func:`.golden_vec._div_wide` (Knuth, TAOCP vol. 2, sec. 4.3.1).

The tests compare every output register, the mode, the scale and the flags with the
scalar model on seeded vectors of :func:`gearcontact.preview.stimulus.line_stimulus`
(corners included).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS
from . import formats as F
from . import line as LN
from .golden_vec import (_div_wide, _rs, golden_constants, hertz_element, njit, prange,
                         run_batch)

__all__ = ["LineCodesArray", "line_golden_array", "line_element", "line_constants",
           "lift_lengths", "unlift_line_array", "lifted_line_golden_array"]

_U = np.uint64
#: Output rows of the kernel, in :class:`LineCodesArray` field order.
_FIELDS = ("a_code", "b_code", "p_max_code", "k_code", "A_min_code", "B_max_code", "mode",
           "scale", "flags")


@dataclass(frozen=True)
class LineCodesArray:
    """Output registers of a batch of line-core runs (``int64`` arrays, same shape).

    Fields as in :class:`.line.LineCodes`: ``a_code, b_code`` (SEMI_AXIS Q(32,20), mm),
    ``p_max_code`` (PMAX Q(32,8), MPa), ``k_code`` (Q(32,20); 0 in line mode),
    ``A_min_code, B_max_code`` (CURVATURE Q(32,20), 1/mm), ``mode``
    (:data:`.line.MODE_ELLIPTIC` / :data:`.line.MODE_LINE`), ``scale`` (SCALE's n) and
    ``flags`` (line-core flags word, :data:`.line.LINE_FLAG_NAMES`).
    """

    a_code: np.ndarray
    b_code: np.ndarray
    p_max_code: np.ndarray
    k_code: np.ndarray
    A_min_code: np.ndarray
    B_max_code: np.ndarray
    mode: np.ndarray
    scale: np.ndarray
    flags: np.ndarray

    @property
    def valid(self) -> np.ndarray:
        """Boolean array: no flag set."""
        return self.flags == 0

    @property
    def mode_names(self) -> np.ndarray:
        """``"elliptic"``, ``"line"`` or ``"flagged"`` per element (str array)."""
        names = np.where(self.mode == LN.MODE_LINE, LN.MODE_NAMES[LN.MODE_LINE],
                         LN.MODE_NAMES[LN.MODE_ELLIPTIC])
        return np.where(self.flags == 0, names, "flagged")


@njit(cache=True, inline="always")
def _isqrt_shifted(x, sh):
    """floor(sqrt(x 2^sh)) for uint64 x, 0 <= sh < 64, x 2^sh < 2^80 (restoring, 40 steps)."""
    rem = _U(0)
    root = _U(0)
    for i in range(39, -1, -1):
        lo = 2 * i - sh              # position in x of the pair's lower bit
        if lo >= 64:
            two = _U(0)
        elif lo >= 0:
            two = (x >> _U(lo)) & _U(3)
        elif lo == -1:
            two = (x << _U(1)) & _U(3)
        else:
            two = _U(0)
        rem = (rem << _U(2)) | two
        trial = (root << _U(2)) | _U(1)
        if rem >= trial:
            rem = rem - trial
            root = (root << _U(1)) | _U(1)
        else:
            root = root << _U(1)
    return root


@njit(cache=True, inline="always")
def line_element(a_min, b_max, w, length, e, pow_lut, cbrt_lut, cst, lcst):
    """The line core on one set of codes (sorted curvatures ``a_min <= b_max``, load,
    contact-line length L, E'); ``cst`` as for :func:`.golden_vec.hertz_element`,
    ``lcst`` :func:`line_constants`.

    Returns
    -------
    tuple of int
        ``(flags, a_code, b_code, p_max_code, k_code, mode, scale)``; outputs 0 when
        ``flags != 0``.
    """
    curv_lo, curv_hi, w_lo, w_hi, e_lo, e_hi = cst[0], cst[1], cst[2], cst[3], cst[4], cst[5]
    len_lo, len_hi, c_ipi, axis_max, pmax_max = lcst[0], lcst[1], lcst[2], lcst[3], lcst[4]
    flags = 0
    if a_min < 0:
        flags |= 1
    if b_max < curv_lo or b_max > curv_hi:
        flags |= 2
    if w < w_lo or w > w_hi:
        flags |= 4
    if e < e_lo or e > e_hi:
        flags |= 8
    if length < len_lo or length > len_hi:
        flags |= 128
    if flags != 0:
        return flags, 0, 0, 0, 0, 0, 0
    # SCALE (line.scale_exponent)
    n_a = 0
    if a_min > 0:
        while n_a < 3 and (a_min << (3 * n_a)) < curv_lo:
            n_a += 1
    n_b = 0
    while n_b < 3 and (b_max << (3 * (n_b + 1))) <= curv_hi:
        n_b += 1
    n = min(n_a, n_b)
    # ELLIPTIC + UNSCALE
    hz_flags, a_h, b_h, p_h, k_h, _, _, _ = hertz_element(
        a_min << (3 * n), b_max << (3 * n), w, e, pow_lut, cbrt_lut, cst)
    a_e = np.int64(a_h) << n
    b_e = np.int64(b_h) << n
    p_e = np.int64(p_h)
    if n > 0:
        p_e = np.int64(_rs(_U(p_e), 2 * n))
    # line stage: QPI, Y, P0SQ, SQRT, DIV_BL
    ul = _U(length)
    qpi = ((_U(w) * _U(c_ipi)) << _U(4)) // ul
    y = _rs(qpi * _U(e), 21)
    p0sq = y * _U(b_max)
    s = _isqrt_shifted(p0sq, 9)
    p_c = np.int64(_rs(s, 8))
    # SELECT
    if hz_flags == 0 and (2 * a_e <= length or p_e >= p_c):
        if a_e > axis_max:
            return 32, 0, 0, 0, 0, 0, n
        return 0, a_e, b_e, p_e, np.int64(k_h), 0, n
    if s == _U(0):
        return 64, 0, 0, 0, 0, 0, n
    b_l = _div_wide(qpi, 29, s)
    a_c = np.int64(_rs(ul, 1))
    b_c = np.int64(_rs(b_l, 16))
    if b_c > axis_max or p_c > pmax_max:
        return 32, 0, 0, 0, 0, 0, n
    return 0, a_c, b_c, p_c, 0, 1, n


@njit(cache=True, parallel=True)
def _kernel(A, B, W, L, E, pow_lut, cbrt_lut, cst, lcst, out):
    for j in prange(A.shape[0]):
        a_min = min(A[j], B[j])
        b_max = max(A[j], B[j])
        flags, a_c, b_c, p_c, k_c, mode, scale = line_element(
            a_min, b_max, W[j], L[j], E[j], pow_lut, cbrt_lut, cst, lcst)
        out[0, j] = a_c
        out[1, j] = b_c
        out[2, j] = p_c
        out[3, j] = k_c
        out[4, j] = a_min
        out[5, j] = b_max
        out[6, j] = mode
        out[7, j] = scale
        out[8, j] = flags


def line_constants() -> np.ndarray:
    """The line stage's constants :func:`line_element` takes: L envelope (codes),
    C_IPI, the SEMI_AXIS and PMAX output maxima."""
    return np.array([LN.LENGTH_MIN_CODE, LN.LENGTH_MAX_CODE, LN.C_IPI, SEMI_AXIS.max_code,
                     PMAX.max_code], dtype=np.int64)


def _kernel_literals_match_line() -> bool:
    """The literal shifts, flag bits and SCALE bounds of the kernel are :mod:`.line`'s."""
    return ((LN.QPI_SHIFT, LN.Y_SHIFT, LN.SQRT_SHIFT, LN.BL_SHIFT,
             LN.SQRT_OUT.frac - PMAX.frac, LN.B_LINE.frac - SEMI_AXIS.frac, LN.SCALE_MAX,
             LN.FLAG_LENGTH_RANGE, F.FLAG_NOT_ELLIPTIC, F.FLAG_CURV_RANGE,
             F.FLAG_LOAD_RANGE, F.FLAG_E_PRIME_RANGE, F.FLAG_OVERFLOW, F.FLAG_DIV_ZERO,
             LN.MODE_ELLIPTIC, LN.MODE_LINE)
            == (4, 21, 9, 29, 8, 16, 3, 128, 1, 2, 4, 8, 32, 64, 0, 1))


assert _kernel_literals_match_line()


def line_golden_array(A_code, B_code, W_code, L_code, *, e_prime_code,
                      hertz_form: str = F.DEFAULT_HERTZ_FORM) -> LineCodesArray:
    """Line-core golden model over broadcastable integer arrays (bit-identical to
    :func:`.line.line_golden`).

    Parameters
    ----------
    A_code, B_code : array_like of int
        CURVATURE Q(32,20) codes, 1/mm, any order.
    W_code : array_like of int
        LOAD Q(32,8) codes, N.
    L_code : array_like of int
        Contact-line lengths, :data:`.line.LINE_LENGTH` Q(32,20) codes, mm.
    e_prime_code : int or array_like of int
        E' codes, Q(32,0) MPa.
    hertz_form : {"hamrock-brewe", "exact"}
        Form of the wrapped elliptic datapath.

    Returns
    -------
    LineCodesArray
        ``int64`` arrays of the broadcast shape.

    Raises
    ------
    FixedPointOverflow
        A code that does not fit its 32-bit register (naming field and index).
    InputRangeError
        Unknown ``hertz_form``.
    """
    F.check_hertz_form(hertz_form)
    return run_batch(_kernel, LineCodesArray, len(_FIELDS),
                     ((A_code, CURVATURE, "A_code"), (B_code, CURVATURE, "B_code"),
                      (W_code, LOAD, "W_code"), (L_code, LN.LINE_LENGTH, "L_code"),
                      (e_prime_code, F.E_PRIME, "e_prime_code")),
                     (*golden_constants(hertz_form), line_constants()))


# ---- the host's lift of a line shorter than the core's 1 mm (.line, *Short lines*) ----
@njit(cache=True)
def _lift_kernel(W, L, out):
    for j in range(W.shape[0]):
        s = LN.length_lift(W[j], L[j])
        out[0, j] = W[j] << s
        out[1, j] = L[j] << s
        out[2, j] = s


def lift_lengths(W_code, L_code) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(W << s, L << s, s)`` elementwise (``int64`` arrays of the broadcast shape), with
    the host's lift ``s`` of :func:`.line.length_lift` (0 for a line of 1 mm or more, or
    one the lift cannot bring into the envelope: the core then flags it)."""
    w, length = (np.asarray(x, dtype=np.int64) for x in np.broadcast_arrays(W_code, L_code))
    out = np.zeros((3, w.size), np.int64)
    _lift_kernel(np.ascontiguousarray(w.ravel()), np.ascontiguousarray(length.ravel()), out)
    return tuple(r.reshape(w.shape) for r in out)


@njit(cache=True)
def _unlift_kernel(a, b, p, k, mode, flags, lift):
    for j in range(a.shape[0]):
        a[j], b[j], p[j], k[j], mode[j], flags[j] = LN.unlift_line(
            a[j], b[j], p[j], k[j], mode[j], flags[j], lift[j])


def unlift_line_array(codes: LineCodesArray, lift) -> LineCodesArray:
    """:func:`.line.unlift_line` elementwise: the outputs of runs on lifted inputs
    (:func:`lift_lengths`) as those of the unlifted ``(W, L)``; a new array set."""
    cols = [np.array(getattr(codes, f), dtype=np.int64).ravel()
            for f in ("a_code", "b_code", "p_max_code", "k_code", "mode", "flags")]
    _unlift_kernel(*cols, np.ascontiguousarray(np.broadcast_to(
        np.asarray(lift, dtype=np.int64), codes.a_code.shape).ravel()))
    shape = np.shape(codes.a_code)
    return replace(codes, **{f: c.reshape(shape) for f, c in zip(
        ("a_code", "b_code", "p_max_code", "k_code", "mode", "flags"), cols)})


def lifted_line_golden_array(A_code, B_code, W_code, L_code, *, e_prime_code,
                             hertz_form: str = F.DEFAULT_HERTZ_FORM
                             ) -> tuple[LineCodesArray, np.ndarray]:
    """The host's line path over a batch (:mod:`.line`, *Short lines*): the line core on
    the lifted ``(W << s, L << s)`` (:func:`lift_lengths`), undone by
    :func:`unlift_line_array`; what :func:`gearcontact.preview.engine` answers and the
    exported C ``gc_line_golden`` computes. Arguments as :func:`line_golden_array`.

    Returns
    -------
    codes : LineCodesArray
        The unlifted outputs.
    lift : numpy.ndarray
        The lift ``s`` of each element (``int64``, 0..:data:`.line.LIFT_MAX_SHIFT`).
    """
    w, length, lift = lift_lengths(W_code, L_code)
    codes = line_golden_array(A_code, B_code, w, length, e_prime_code=e_prime_code,
                              hertz_form=hertz_form)
    return unlift_line_array(codes, lift), lift
