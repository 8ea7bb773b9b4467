"""Baked pseudo-inverse of the stage-C curvature fit (design matrix, ROM contents).

Stage C (docs/spec.md sec. 6, Algorithm 2) fits the quadratic

    g(s, t) = c0 + c1 s + c2 t + c3 s^2 + c4 s t + c5 t^2

to the 49 gap samples of the 7 x 7 stencil by linear least squares. The design matrix
``A`` (columns 1, s, t, s^2, st, t^2) is a compile-time constant, so the least-squares
operator ``M = (A^T A)^-1 A^T`` (6 x 49) is formed once in double precision and baked
into a ROM; online the datapath only evaluates ``c = M g`` with six multiply-accumulate
units. This is a two-dimensional Savitzky-Golay filter [1]_ evaluated at the stencil
centre.

ROM word format
---------------
Each weight is quantized (round half up) to a ``WEIGHT`` = Q(32,20) code; the ROM word
is that code sign-extended to 40 bits (``ROM_WORD`` = Q(40,20), two's complement).
Why 40 bits: the word is the multiplier operand of the MAC, so a tap product is
``32 (GAP) + 40 (word) = 72`` bits wide and the accumulator is kept at that width
(``ACC`` = Q(72,36)). The 8 guard bits of the word are exactly the sign headroom the
49-tap sum needs on top of a full 64-bit Q(32,16) x Q(32,20) product:
``|sum| <= 49 * 2^31 * 2^31 < 2^68 < 2^71``, so the accumulator provably cannot wrap
for *any* 32-bit gap codes and *any* weights that fit Q(32,20) -- including weights of
a re-baked stencil with a finer spacing (weights grow as 1/h^2) -- and the MAC needs no
run-time overflow logic. Overflow is checked once, when the 72-bit sum is rounded into
the Q(32,20) coefficient format (see :mod:`.golden`).

Quantization error
------------------
With ``E = Mq A - I`` (``Mq`` the quantized weights) an exact quadratic with
coefficient vector ``p`` is reproduced as ``Mq A p = p + E p``; for the baked 0.5 mm
stencil ``max |E| = 6.7e-6`` (leakage of the constant term into c3, c5 and gain errors
of ~3e-6). :func:`coefficient_error_bound` turns this, the gap LSB and the output
rounding into a rigorous per-coefficient bound.

References
----------
.. [1] A. Savitzky and M. J. E. Golay, "Smoothing and differentiation of data by
   simplified least squares procedures", Anal. Chem. 36 (8), 1627-1639, 1964.
.. [2] G. H. Golub and C. F. Van Loan, *Matrix Computations*, 4th ed., Johns Hopkins,
   2013, section 5.3 (normal equations).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from gearcontact.contract.stencil import (STENCIL_SIZE, STENCIL_SPACING_MM,
                                          stencil_coordinates)
from gearcontact.contract.qformat import GAP, QFormat, sq
from gearcontact.validation import check_array_finite, check_positive, InputRangeError

__all__ = ["N_COEFFS", "N_TAPS", "WEIGHT", "ROM_WORD", "ROM_WORD_BITS", "ACC", "COEFF",
           "BakedPinv", "design_matrix", "pseudo_inverse", "bake_pseudo_inverse",
           "baked_pinv", "coefficient_error_bound"]

N_COEFFS = 6                 #: fitted coefficients c0..c5
N_TAPS = STENCIL_SIZE        #: stencil samples (49)
WEIGHT = sq(32, 20)          #: value format of a pseudo-inverse weight, 1/mm^k
ROM_WORD_BITS = 40           #: ROM word width, bits (weight sign-extended, see module doc)
ROM_WORD = sq(ROM_WORD_BITS, WEIGHT.frac)   #: Q(40,20) ROM word
#: MAC accumulator: Q(32,16) gap x Q(40,20) word -> Q(72,36), 49 taps cannot wrap.
ACC = sq(GAP.bits + ROM_WORD_BITS, GAP.frac + WEIGHT.frac)
COEFF = sq(32, 20)           #: fitted coefficient c0..c5 (c0 mm, c1/c2 1, c3..c5 1/mm)


def design_matrix(spacing_mm: float = STENCIL_SPACING_MM) -> np.ndarray:
    """Return the 49 x 6 design matrix with columns 1, s, t, s^2, st, t^2.

    Parameters
    ----------
    spacing_mm : float
        Stencil grid spacing h, mm (> 0). Rows follow the sample order of
        :mod:`gearcontact.contract.stencil`; column k has unit mm^deg(k).
    """
    h = check_positive("spacing_mm", spacing_mm)
    s, t = stencil_coordinates(h)
    return np.stack([np.ones_like(s), s, t, s * s, s * t, t * t], axis=1)


def pseudo_inverse(spacing_mm: float = STENCIL_SPACING_MM) -> np.ndarray:
    """Return ``M = (A^T A)^-1 A^T`` (6 x 49, float64) of :func:`design_matrix`.

    Row j maps the gap samples (mm) to coefficient c_j (unit mm^(1 - deg_j)). Formed
    by solving the normal equations [2]_, which are well conditioned for the 7 x 7
    stencil (cond(A^T A) ~ 40 at h = 0.5 mm).
    """
    a = design_matrix(spacing_mm)
    return np.linalg.solve(a.T @ a, a.T)


@dataclass(frozen=True)
class BakedPinv:
    """The baked ROM of the fit core (shared by the golden model and the RTL).

    Attributes
    ----------
    spacing_mm : float
        Stencil spacing the ROM was baked for, mm.
    weights : numpy.ndarray
        Double-precision pseudo-inverse, 6 x 49 (read-only).
    weight_codes : tuple of tuple of int
        ``weight_codes[j][i]`` = WEIGHT Q(32,20) code of M_ji.
    rom_words : tuple of tuple of int
        The same codes as unsigned 40-bit two's-complement patterns (ROM init).
    reproduction_error : numpy.ndarray
        ``E = Mq A - I`` (6 x 6, float64): coefficient leakage/gain error of the
        quantized weights on exact quadratics (read-only).
    """

    spacing_mm: float
    weights: np.ndarray
    weight_codes: tuple
    rom_words: tuple
    reproduction_error: np.ndarray

    @property
    def weight_codes_array(self) -> np.ndarray:
        """``weight_codes`` as a 6 x 49 int64 array."""
        return np.array(self.weight_codes, dtype=np.int64)

    @property
    def quantized_weights(self) -> np.ndarray:
        """Real value of the quantized weights Mq (6 x 49, float64, exact)."""
        return WEIGHT.to_float(self.weight_codes_array)

    @property
    def weight_l1_codes(self) -> tuple:
        """Per-row sum of |weight code| (bounds |acc| by ``2^31 * l1``)."""
        return tuple(sum(abs(w) for w in row) for row in self.weight_codes)


def bake_pseudo_inverse(*, spacing_mm: float = STENCIL_SPACING_MM) -> BakedPinv:
    """Form the pseudo-inverse in double precision and quantize it to ROM words.

    Parameters
    ----------
    spacing_mm : float
        Stencil spacing, mm (> 0). Weights scale as h^-deg, so a spacing below about
        0.002 mm would push the quadratic weights out of Q(32,20); that raises.

    Raises
    ------
    gearcontact.contract.qformat.FixedPointOverflow
        If a weight does not fit WEIGHT Q(32,20) (message names ``M[j, i]``).
    """
    m = pseudo_inverse(spacing_mm)
    codes = WEIGHT.quantize_array(m, field="M")
    words = tuple(tuple(ROM_WORD.to_bits(int(c)) for c in row) for row in codes)
    err = WEIGHT.to_float(codes) @ design_matrix(spacing_mm) - np.eye(N_COEFFS)
    m.flags.writeable = False
    err.flags.writeable = False
    return BakedPinv(spacing_mm=float(spacing_mm), weights=m,
                     weight_codes=tuple(tuple(int(c) for c in row) for row in codes),
                     rom_words=words, reproduction_error=err)


@functools.lru_cache(maxsize=1)
def baked_pinv() -> BakedPinv:
    """The ROM of the hardware stencil (``STENCIL_SPACING_MM``), computed once."""
    return bake_pseudo_inverse(spacing_mm=STENCIL_SPACING_MM)


def coefficient_error_bound(gaps_mm, *, rom: BakedPinv | None = None,
                            gap_fmt: QFormat = GAP, coeff_fmt: QFormat = COEFF) -> np.ndarray:
    """Rigorous bound on |c_golden - c_exact| for one stencil, per coefficient.

    The golden coefficient is ``round(Mq gq)`` with ``gq`` the gaps rounded to
    ``gap_fmt`` and ``Mq`` the quantized weights; the exact one is ``M g``. Hence

        |c_q - c| <= ||Mq_j||_1 * lsb_gap / 2  +  sum_i |Mq_ji - M_ji| |g_i|
                     + lsb_coeff / 2

    (gap rounding, weight rounding, coefficient rounding).

    Parameters
    ----------
    gaps_mm : array_like, shape (49,)
        Real gap samples, mm.
    rom : BakedPinv, optional
        ROM to bound (default :func:`baked_pinv`).

    Returns
    -------
    numpy.ndarray, shape (6,)
        Bound per coefficient in the coefficient's unit (c0 mm, c1/c2 1, c3..c5 1/mm).
    """
    rom = baked_pinv() if rom is None else rom
    g = check_array_finite("gaps_mm", gaps_mm)
    if g.shape != (N_TAPS,):
        raise InputRangeError("gaps_mm.shape", g.shape, f"({N_TAPS},)")
    mq = rom.quantized_weights
    return (np.abs(mq).sum(axis=1) * gap_fmt.lsb / 2
            + np.abs(mq - rom.weights) @ np.abs(g)
            + coeff_fmt.lsb / 2)
