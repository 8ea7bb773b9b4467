"""Bit-exact integer golden model of the stage-C fit core (and its timing model).

Datapath (all integers, no floating point; Q formats as in docs/spec.md sec. 6):

==========  ==============  ===================================================
signal      format          definition
==========  ==============  ===================================================
g_i         STENCIL_GAP     gap sample i, mm (input, 49 words)
            Q(32,21)
M_ji        ROM Q(40,20)    baked degree-6 weight (Q(32,20) value, :mod:`.pinv`)
acc_j       ACC Q(72,41)    ``sum_i M_ji g_i``, exact (cannot wrap, see pinv)
c_j         COEFF Q(32,20)  ``round_shift(acc_j, 21)``; overflow -> flag
h           Q(33,20)        ``c3 + c5``, 1/mm (exact)
e           Q(33,20)        ``c3 - c5``, 1/mm (exact)
d           D Q(64,40)      ``e^2 + c4^2``, (1/mm)^2 (exact); > max -> flag
r           UQ(32,20)       ``floor(sqrt(d))``, non-restoring isqrt [1]_
A-, B-      CURVATURE       ``round_shift(h + r, 1)``, ``round_shift(h - r, 1)``
            Q(32,20)        1/mm; overflow -> flag; B- <= 0 -> not elliptic
==========  ==============  ===================================================

``round_shift`` is round-half-up by arithmetic shift (:mod:`gearcontact.contract.qformat`).
A- >= B- by construction (r >= 0 and rounding is monotone). Nothing wraps: whenever an
overflow flag is set, *every* numeric output of that run reads 0 and the flags word says
why.

Error bound against the exact eigenvalues (used by the tests): the coefficient error
``|c_q - c|`` is bounded by :func:`.pinv.coefficient_error_bound`; by Weyl's
inequality [2]_ an eigenvalue of ``[[c3, c4/2], [c4/2, c5]]`` moves by at most the
Frobenius norm ``sqrt(dc3^2 + dc4^2/2 + dc5^2)`` of the coefficient error; the floor
isqrt (error in (-1, 0] LSB, halved) and the final half-up shift add at most 1 LSB.

Timing model (cycle-exact with :mod:`.rtl`)
-------------------------------------------
``FIT_CYCLES = 52`` clock edges from the edge that samples ``go`` to the edge after
which ``done`` reads 1, for every input: ``FIT_MAC_CYCLES = 49`` MAC edges (one tap
per cycle; the ``go`` edge itself loads tap 0) followed by the ``FIT_LATCH_CYCLES = 3``
curvature latch (edge 50: coefficient rounding, h, e; edge 51: d; edge 52: isqrt,
A-, B-, flags into the output registers, done). In the C->D chain the latch also
absorbs stage D's 2 input-capture/sort cycles (``STAGE_D_CAPTURE_CYCLES``): the latch
registers are D's operand registers and the pair arrives already sorted
(A- >= B-, i.e. D's ``A_min`` = B-, ``B_max`` = A-), so the chain is
``49 + 3 + (756 - 2) = 806`` cycles (:func:`chain_cycles`).

References
----------
.. [1] Y. Li and W. Chu, "A new non-restoring square root algorithm and its VLSI
   implementations", Proc. IEEE ICCD, 538-544, 1996.
.. [2] H. Weyl, "Das asymptotische Verteilungsgesetz der Eigenwerte linearer
   partieller Differentialgleichungen", Math. Ann. 71, 441-479, 1912.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcontact.preview.fit.golden_vec import fit_constants, fit_kernel
from gearcontact.preview.fit.pinv import ACC, COEFF, N_COEFFS, N_TAPS, BakedPinv, baked_pinv
from gearcontact.contract.qformat import (CURVATURE, STENCIL_GAP, FixedPointOverflow,
                                          round_shift, sq, uq)
from gearcontact.validation import InputRangeError

__all__ = ["FLAG_COEFF_OVERFLOW", "FLAG_D_OVERFLOW", "FLAG_CURV_OVERFLOW",
           "FLAG_NOT_ELLIPTIC", "FLAG_ANY_OVERFLOW", "FLAG_BITS", "D_FMT", "ROOT_FMT",
           "SUM_FMT", "ISQRT_REM_FMT", "FIT_MAC_CYCLES", "FIT_LATCH_CYCLES", "FIT_CYCLES",
           "STAGE_D_CAPTURE_CYCLES", "chain_cycles", "GoldenFit", "GoldenFitBatch",
           "encode_gaps", "decode_curvature", "check_gap_codes", "isqrt_nonrestoring",
           "isqrt_nonrestoring_array", "golden_fit", "golden_fit_batch", "element_constants"]

FLAG_COEFF_OVERFLOW = 1 << 0   #: a rounded coefficient c0..c5 does not fit Q(32,20)
FLAG_D_OVERFLOW = 1 << 1       #: d = (c3-c5)^2 + c4^2 does not fit Q(64,40)
FLAG_CURV_OVERFLOW = 1 << 2    #: A- or B- does not fit CURVATURE Q(32,20)
FLAG_NOT_ELLIPTIC = 1 << 3     #: B- <= 0: saddle/flat/concave, no point contact
FLAG_ANY_OVERFLOW = FLAG_COEFF_OVERFLOW | FLAG_D_OVERFLOW | FLAG_CURV_OVERFLOW
FLAG_BITS = 4                  #: width of the flags word

SUM_FMT = sq(COEFF.bits + 1, COEFF.frac)   #: h = c3 + c5 and e = c3 - c5, Q(33,20)
D_FMT = sq(64, 2 * COEFF.frac)             #: d, Q(64,40), (1/mm)^2
ROOT_FMT = uq(32, COEFF.frac)              #: r = isqrt(d), UQ(32,20), 1/mm
#: Partial remainder of the 32-step non-restoring isqrt: |R| <= 2 Q + 1 < 2^33.
ISQRT_REM_FMT = sq(ROOT_FMT.bits + 2, 0)
_ISQRT_STEPS = ROOT_FMT.bits               # result bits = half the radicand width
_COEFF_SHIFT = ACC.frac - COEFF.frac       # 41 - 20 = 21

FIT_MAC_CYCLES = N_TAPS        #: one tap per cycle through six parallel MACs
FIT_LATCH_CYCLES = 3           #: coefficient round | d | isqrt + A-, B- registers
FIT_CYCLES = FIT_MAC_CYCLES + FIT_LATCH_CYCLES   #: go edge -> done, constant (52)
STAGE_D_CAPTURE_CYCLES = 2     #: stage-D input capture/sort cycles absorbed in the chain


def chain_cycles(stage_d_cycles: int) -> int:
    """Cycles of the C->D chain for a stage-D core of ``stage_d_cycles`` (standalone).

    The fit latch doubles as stage D's 2-cycle input capture/sort, so
    ``chain = FIT_CYCLES + stage_d_cycles - STAGE_D_CAPTURE_CYCLES``
    (806 for the 756-cycle serialized stage D).
    """
    n = int(stage_d_cycles)
    if n <= STAGE_D_CAPTURE_CYCLES:
        raise InputRangeError("stage_d_cycles", stage_d_cycles,
                              f"an integer > {STAGE_D_CAPTURE_CYCLES}")
    return FIT_CYCLES + n - STAGE_D_CAPTURE_CYCLES


@dataclass(frozen=True)
class GoldenFit:
    """Output of one golden fit (codes are Python ints).

    Attributes
    ----------
    c_codes : tuple of int
        c0..c5 in COEFF Q(32,20) (c0 mm, c1/c2 1, c3..c5 1/mm); 0 on overflow.
    a_minus_code, b_minus_code : int
        A-, B- in CURVATURE Q(32,20), 1/mm (A- >= B-); 0 on overflow.
    flags : int
        Bitmask of ``FLAG_*``.
    """

    c_codes: tuple
    a_minus_code: int
    b_minus_code: int
    flags: int

    @property
    def coefficients(self) -> tuple:
        """Decoded c0 (mm), c1, c2 (1), c3, c4, c5 (1/mm)."""
        return tuple(COEFF.to_float(x) for x in self.c_codes)

    @property
    def A_minus_per_mm(self) -> float:
        """Decoded A-, 1/mm."""
        return CURVATURE.to_float(self.a_minus_code)

    @property
    def B_minus_per_mm(self) -> float:
        """Decoded B-, 1/mm."""
        return CURVATURE.to_float(self.b_minus_code)

    @property
    def overflow(self) -> bool:
        """True if any overflow flag is set (outputs invalid, read 0)."""
        return bool(self.flags & FLAG_ANY_OVERFLOW)

    @property
    def elliptic(self) -> bool:
        """True if the result is valid and B- > 0."""
        return not self.flags


@dataclass(frozen=True)
class GoldenFitBatch:
    """Vectorized golden fit output for n stencils (int64 arrays).

    Attributes
    ----------
    c_codes : numpy.ndarray, shape (n, 6)
        COEFF Q(32,20) codes of c0..c5.
    a_minus_codes, b_minus_codes : numpy.ndarray, shape (n,)
        CURVATURE Q(32,20) codes of A-, B-, 1/mm.
    flags : numpy.ndarray, shape (n,)
        ``FLAG_*`` bitmasks.
    """

    c_codes: np.ndarray
    a_minus_codes: np.ndarray
    b_minus_codes: np.ndarray
    flags: np.ndarray

    def __len__(self) -> int:
        return int(self.flags.shape[0])

    def __getitem__(self, k: int) -> GoldenFit:
        """Row ``k`` as a scalar :class:`GoldenFit`."""
        return GoldenFit(c_codes=tuple(int(x) for x in self.c_codes[k]),
                         a_minus_code=int(self.a_minus_codes[k]),
                         b_minus_code=int(self.b_minus_codes[k]), flags=int(self.flags[k]))


def encode_gaps(gaps_mm) -> np.ndarray:
    """Quantize real gaps (mm) to STENCIL_GAP Q(32,21) codes, round half up.

    Parameters
    ----------
    gaps_mm : array_like, shape (49,) or (n, 49)
        Gap samples, mm.

    Returns
    -------
    numpy.ndarray of int64, same shape.

    Raises
    ------
    gearcontact.validation.InputRangeError
        If the last axis is not 49 long.
    gearcontact.contract.qformat.FixedPointOverflow
        A sample is NaN/inf or outside +-1024 mm; the message names it, e.g.
        ``gaps_mm[12]`` or ``gaps_mm[3, 12]`` (stencil 3, sample 12).
    """
    g = np.asarray(gaps_mm, dtype=float)
    if g.ndim not in (1, 2) or g.shape[-1] != N_TAPS:
        raise InputRangeError("gaps_mm.shape", g.shape, f"(49,) or (n, {N_TAPS})")
    return STENCIL_GAP.quantize_array(g, field="gaps_mm")


def decode_curvature(code):
    """CURVATURE Q(32,20) code(s) -> 1/mm (float or float64 array)."""
    return CURVATURE.to_float(code)


def isqrt_nonrestoring(d: int) -> int:
    """floor(sqrt(d)) by the Li-Chu non-restoring algorithm, modelled bit by bit.

    One result bit per step, shift-and-add only: the partial remainder R is updated by
    ``R = 4R + pair - (4Q + 1)`` if ``R >= 0`` else ``R = 4R + pair + (4Q + 3)`` and the
    new bit is ``R >= 0`` [1]_. ``d`` is a 64-bit radicand (0 <= d < 2^64); the
    remainder is checked to stay in ``ISQRT_REM_FMT`` (the RTL register width).
    """
    d = int(d)
    if not 0 <= d < (1 << (2 * _ISQRT_STEPS)):
        raise InputRangeError("d", d, f"[0, 2^{2 * _ISQRT_STEPS})")
    q = 0
    rem = 0
    for i in range(_ISQRT_STEPS - 1, -1, -1):
        pair = (d >> (2 * i)) & 3
        if rem >= 0:
            rem = ((rem << 2) | pair) - ((q << 2) | 1)
        else:
            rem = ((rem << 2) | pair) + ((q << 2) | 3)
        ISQRT_REM_FMT.check(rem, field="isqrt remainder")
        q = (q << 1) | (1 if rem >= 0 else 0)
    return q


def isqrt_nonrestoring_array(d: np.ndarray) -> np.ndarray:
    """Vectorized :func:`isqrt_nonrestoring` over int64 radicands in [0, 2^63)."""
    d = np.asarray(d, dtype=np.int64)
    if (d < 0).any():
        raise InputRangeError("d", int(d[d < 0].flat[0]), "[0, 2^63)")
    q = np.zeros_like(d)
    rem = np.zeros_like(d)
    for i in range(_ISQRT_STEPS - 1, -1, -1):
        shifted = (rem << 2) | ((d >> (2 * i)) & 3)
        rem = np.where(rem >= 0, shifted - ((q << 2) | 1), shifted + ((q << 2) | 3))
        q = (q << 1) | (rem >= 0)
    return q


def check_gap_codes(gap_codes, ndim: int) -> np.ndarray:
    """Validate STENCIL_GAP Q(32,21) code stencils of rank ``ndim`` (1: (49,), 2: (n, 49)).

    Returns an int64 array; raises InputRangeError (shape, non-integer) or
    FixedPointOverflow naming the first code outside Q(32,21).
    """
    codes = np.asarray(gap_codes)
    if codes.ndim != ndim or codes.shape[-1] != N_TAPS:
        want = f"({N_TAPS},)" if ndim == 1 else f"(n, {N_TAPS})"
        raise InputRangeError("gap_codes.shape", codes.shape, want)
    if codes.dtype.kind == "i":
        return STENCIL_GAP.check(codes.astype(np.int64), field="gap_codes")
    out = np.empty(codes.shape, dtype=np.int64)
    for idx, x in np.ndenumerate(codes):
        name = f"gap_codes[{', '.join(map(str, idx))}]"
        if not isinstance(x, (int, np.integer)) or isinstance(x, bool):
            raise InputRangeError(name, x, f"an integer STENCIL_GAP {STENCIL_GAP} code "
                                  "(use encode_gaps for gaps in mm)")
        out[idx] = STENCIL_GAP.check(int(x), field=name)
    return out


def golden_fit(gap_codes, *, rom: BakedPinv | None = None, bitwise: bool = True) -> GoldenFit:
    """Run the fit core on one stencil of STENCIL_GAP Q(32,21) codes (exact Python ints).

    Parameters
    ----------
    gap_codes : sequence of int, length 49
        Gap codes in stencil order.
    rom : BakedPinv, keyword-only, optional
        Pseudo-inverse ROM (default: the baked hardware ROM).
    bitwise : bool, keyword-only
        True: isqrt modelled bit by bit (:func:`isqrt_nonrestoring`); False: the equal
        fast path :func:`math.isqrt`.

    Returns
    -------
    GoldenFit
    """
    rom = baked_pinv() if rom is None else rom
    g = [int(x) for x in check_gap_codes(gap_codes, 1)]
    c = []
    for row in rom.weight_codes:
        acc = ACC.check(sum(w * x for w, x in zip(row, g)), field="acc")
        c.append(round_shift(acc, _COEFF_SHIFT))
    zero = GoldenFit(c_codes=(0,) * N_COEFFS, a_minus_code=0, b_minus_code=0, flags=0)
    if not all(COEFF.fits(x) for x in c):
        return GoldenFit(zero.c_codes, 0, 0, FLAG_COEFF_OVERFLOW)
    a, b, cc = c[3], c[4], c[5]
    h = a + cc
    e = a - cc
    d = e * e + b * b
    if not D_FMT.fits(d):
        return GoldenFit(zero.c_codes, 0, 0, FLAG_D_OVERFLOW)
    r = isqrt_nonrestoring(d) if bitwise else math.isqrt(d)
    a_minus = round_shift(h + r, 1)
    b_minus = round_shift(h - r, 1)
    if not (CURVATURE.fits(a_minus) and CURVATURE.fits(b_minus)):
        return GoldenFit(zero.c_codes, 0, 0, FLAG_CURV_OVERFLOW)
    flags = FLAG_NOT_ELLIPTIC if b_minus <= 0 else 0
    return GoldenFit(c_codes=tuple(c), a_minus_code=a_minus, b_minus_code=b_minus,
                     flags=flags)


def _check_mac_bound(rom: BakedPinv) -> None:
    """The int64 MAC of the compiled kernel is exact only for ``sum_i |M_ji| < 2^31``."""
    if max(rom.weight_l1_codes) >= (1 << 31):
        raise FixedPointOverflow("sum_i |M_ji| (int64 MAC bound)", max(rom.weight_l1_codes),
                                 sq(32, 0))


def element_constants(rom: BakedPinv | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``(weight codes (6, 49), constants (9,))``, int64: what
    :func:`.golden_vec.fit_element` takes to run this model inside another compiled loop
    (default the baked hardware ROM)."""
    rom = baked_pinv() if rom is None else rom
    _check_mac_bound(rom)
    return (np.ascontiguousarray(rom.weight_codes_array, np.int64),
            fit_constants(_COEFF_SHIFT, D_FMT.max_code))


def golden_fit_batch(gap_codes, *, rom: BakedPinv | None = None) -> GoldenFitBatch:
    """Vectorized, bit-identical :func:`golden_fit` over n stencils (numpy int64).

    Parameters
    ----------
    gap_codes : array_like of int, shape (n, 49)
        STENCIL_GAP Q(32,21) codes.
    rom : BakedPinv, keyword-only, optional
        Pseudo-inverse ROM (default: the baked hardware ROM).

    Notes
    -----
    Runs the compiled kernel :func:`.golden_vec.fit_kernel` (numba, parallel over
    stencils). Its int64 MAC is exact because ``|acc_j| <= 2^31 * sum_i |M_ji| < 2^63``
    for the ROM (checked here; a ROM with larger weights raises rather than wrap).
    ``e^2 + c4^2`` is formed in uint64 after screening ``|e| > isqrt(2^63 - 1)``, so it
    cannot wrap either.
    """
    rom = baked_pinv() if rom is None else rom
    g = np.asarray(gap_codes)
    if g.dtype != np.int64 or g.ndim != 2 or g.shape[1] != N_TAPS:
        g = check_gap_codes(gap_codes, 2)   # else the kernel range-checks in its MAC pass
    _check_mac_bound(rom)
    c, a_minus, b_minus, flags = fit_kernel(g, rom.weight_codes_array,
                                            coeff_shift=_COEFF_SHIFT,
                                            d_max_code=D_FMT.max_code)
    return GoldenFitBatch(c_codes=c, a_minus_codes=a_minus, b_minus_codes=b_minus,
                          flags=flags)
