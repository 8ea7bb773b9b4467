"""Baked pseudo-inverse of the stage-C curvature fit (design matrix, ROM contents).

Stage C (docs/spec.md sec. 6, Algorithm 2) reads the coefficients

    g(s, t) ~ c0 + c1 s + c2 t + c3 s^2 + c4 s t + c5 t^2 + (terms of degree 3..6)

from the 49 gap samples of the 7 x 7 stencil: the *quadratic part of the degree-6
least-squares polynomial* in s, t. The design matrix ``A`` (the 28 monomials
``s^i t^(n-i)`` of total degree n <= ``FIT_DEGREE``, first columns 1, s, t, s^2, st,
t^2) is a compile-time constant, so the operator ``M`` = rows 0..5 of ``A^+`` (6 x 49)
is formed once in double precision and baked into a ROM; online the datapath only
evaluates ``c = M g`` with six multiply-accumulate units. This is a two-dimensional
Savitzky-Golay filter [1]_ of order 6 evaluated at the stencil centre.

Why degree 6: over the +-0.6 mm window the gap of a long bearing has large quartic and
sixth-order terms (B- varies along the contact line), and a plain quadratic fit folds
them into c3..c5. Measured on two design-space pairs (tests/twin/test_mesh.py, worst
rows, A-/B- relative error against the TCA's shape operator): degree 2 (the former
ROM) 2.5 / 88 % and 3.3 / 28 %; degree 4 0.15 / 8.7 % and 0.21 / 3.8 %; degree 6
0.01 / 0.59 % and 0.00 / 0.13 %. On the symmetric grid the odd-degree columns are
orthogonal to the even ones, so degree 6 equals the even part of degree 7; dropping
some sixth-degree columns does not work (s^5 t, s^3 t^3, s t^5 couple into c4). The
price is the noise gain: ``||M_c3||_2`` = 1.03 (degree 2), 4.53 (4), 17.15 (6),
``||M_c3||_1`` = 6.0 / 26.1 / 88.3 1/mm^2 -- hence stage C's own input format
STENCIL_GAP Q(32,21) (:mod:`gearcontact.contract.qformat`), 32 x finer than GAP.

ROM word format
---------------
Each weight is quantized (round half up) to a ``WEIGHT`` = Q(32,20) code (the widest
code of the degree-6 ROM is 6.4 1/mm^2, 24 bits); the ROM word is that code
sign-extended to 40 bits (``ROM_WORD`` = Q(40,20), two's complement). Why 40 bits: the
word is the multiplier operand of the MAC, so a tap product is
``32 (STENCIL_GAP) + 40 (word) = 72`` bits wide and the accumulator is kept at that
width (``ACC`` = Q(72,41)). The 8 guard bits of the word are exactly the sign headroom
the 49-tap sum needs on top of a full 64-bit Q(32,21) x Q(32,20) product:
``|sum| <= 49 * 2^31 * 2^31 < 2^68 < 2^71``, so the accumulator provably cannot wrap
for *any* 32-bit gap codes and *any* weights that fit Q(32,20) -- including weights of
a re-baked stencil with a finer spacing (weights grow as 1/h^2) -- and the MAC needs no
run-time overflow logic. Overflow is checked once, when the 72-bit sum is rounded into
the Q(32,20) coefficient format (see :mod:`.golden`).

Quantization error
------------------
With ``E = Mq A - [I 0]`` (``Mq`` the quantized weights, 6 x 28) an exact polynomial of
degree <= 6 with coefficient vector ``p`` gives ``Mq A p = p[:6] + E p``; for the
baked 0.2 mm stencil ``max |E| = 3.8e-6`` (leakage of the constant term into c3).
:func:`coefficient_error_bound` turns this, the gap LSB and the output rounding into a
rigorous per-coefficient bound.

References
----------
.. [1] A. Savitzky and M. J. E. Golay, "Smoothing and differentiation of data by
   simplified least squares procedures", Anal. Chem. 36 (8), 1627-1639, 1964.
.. [2] G. H. Golub and C. F. Van Loan, *Matrix Computations*, 4th ed., Johns Hopkins,
   2013, section 5.3 (least squares by QR factorization).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from gearcontact.contract.stencil import (STENCIL_SIZE, STENCIL_SPACING_MM,
                                          stencil_coordinates)
from gearcontact.contract.qformat import STENCIL_GAP, QFormat, sq
from gearcontact.validation import check_array_finite, check_positive, InputRangeError

__all__ = ["FIT_DEGREE", "N_COEFFS", "N_TAPS", "WEIGHT", "ROM_WORD", "ROM_WORD_BITS", "ACC",
           "COEFF", "BakedPinv", "design_matrix", "pseudo_inverse", "bake_pseudo_inverse",
           "baked_pinv", "coefficient_error_bound"]

FIT_DEGREE = 6               #: total degree of the least-squares polynomial
N_COEFFS = 6                 #: fitted coefficients c0..c5 (its quadratic part)
N_TAPS = STENCIL_SIZE        #: stencil samples (49)
WEIGHT = sq(32, 20)          #: value format of a pseudo-inverse weight, 1/mm^k
ROM_WORD_BITS = 40           #: ROM word width, bits (weight sign-extended, see module doc)
ROM_WORD = sq(ROM_WORD_BITS, WEIGHT.frac)   #: Q(40,20) ROM word
#: MAC accumulator: Q(32,21) gap x Q(40,20) word -> Q(72,41), 49 taps cannot wrap.
ACC = sq(STENCIL_GAP.bits + ROM_WORD_BITS, STENCIL_GAP.frac + WEIGHT.frac)
COEFF = sq(32, 20)           #: fitted coefficient c0..c5 (c0 mm, c1/c2 1, c3..c5 1/mm)


def design_matrix(spacing_mm: float = STENCIL_SPACING_MM, *,
                  degree: int = FIT_DEGREE) -> np.ndarray:
    """Return the 49 x n design matrix of the monomials of total degree <= ``degree``.

    Parameters
    ----------
    spacing_mm : float
        Stencil grid spacing h, mm (> 0). Rows follow the sample order of
        :mod:`gearcontact.contract.stencil`.
    degree : int, keyword-only
        Total degree, 2..6 (from degree 7 on the design is singular: on 7 grid columns
        s^7 is a combination of 1, s, ..., s^6). Columns ``s^i t^(n-i)`` for n = 0..degree,
        i = n..0: 1, s, t, s^2, st, t^2, s^3, ...; a column of degree n has unit mm^n;
        ``n = (degree + 1)(degree + 2)/2`` columns.
    """
    h = check_positive("spacing_mm", spacing_mm)
    if isinstance(degree, bool) or not isinstance(degree, int) or not 2 <= degree <= 6:
        raise InputRangeError("degree", degree, "an integer in [2, 6]")
    s, t = stencil_coordinates(h)
    return np.stack([s ** i * t ** (n - i) for n in range(degree + 1)
                     for i in range(n, -1, -1)], axis=1)


def pseudo_inverse(spacing_mm: float = STENCIL_SPACING_MM, *,
                   degree: int = FIT_DEGREE) -> np.ndarray:
    """Return the fit operator ``M`` (6 x 49, float64): rows 0..5 of ``A^+``.

    ``A`` is :func:`design_matrix` of ``degree``; row j maps the gap samples (mm) to
    coefficient c_j (unit mm^(1 - deg_j)) of the degree-``degree`` least-squares
    polynomial. Formed by QR factorization [2]_ (cond(A) = 2.0e3 for degree 6 at
    h = 0.2 mm; the normal equations would square it).
    """
    a = design_matrix(spacing_mm, degree=degree)
    q, r = np.linalg.qr(a)
    return np.linalg.solve(r, q.T)[:N_COEFFS]


@dataclass(frozen=True)
class BakedPinv:
    """The baked ROM of the fit core (shared by the golden model and the RTL).

    Attributes
    ----------
    spacing_mm : float
        Stencil spacing the ROM was baked for, mm.
    degree : int
        Total degree of the least-squares polynomial whose quadratic part the ROM
        reads (``FIT_DEGREE`` = 6 for the hardware ROM).
    weights : numpy.ndarray
        Double-precision fit operator (:func:`pseudo_inverse`), 6 x 49 (read-only).
    weight_codes : tuple of tuple of int
        ``weight_codes[j][i]`` = WEIGHT Q(32,20) code of M_ji.
    rom_words : tuple of tuple of int
        The same codes as unsigned 40-bit two's-complement patterns (ROM init).
    reproduction_error : numpy.ndarray
        ``E = Mq A - [I 0]`` (6 x n, float64, ``A`` the design of ``degree``, n = 28
        for degree 6): leakage and gain error of the quantized weights on exact
        polynomials of that degree, per monomial (read-only).
    """

    spacing_mm: float
    degree: int
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


def bake_pseudo_inverse(*, spacing_mm: float = STENCIL_SPACING_MM,
                        degree: int = FIT_DEGREE) -> BakedPinv:
    """Form the fit operator in double precision and quantize it to ROM words.

    Parameters
    ----------
    spacing_mm : float, keyword-only
        Stencil spacing, mm (> 0). Weights scale as h^-deg, so a spacing below about
        0.011 mm would push the quadratic weights (6.4 1/mm^2 at 0.2 mm) out of
        Q(32,20); that raises.
    degree : int, keyword-only
        Total degree of the least-squares polynomial (:func:`design_matrix`); other
        than ``FIT_DEGREE`` only to compare against the hardware ROM.

    Raises
    ------
    gearcontact.contract.qformat.FixedPointOverflow
        If a weight does not fit WEIGHT Q(32,20) (message names ``M[j, i]``).
    """
    m = pseudo_inverse(spacing_mm, degree=degree)
    codes = WEIGHT.quantize_array(m, field="M")
    words = tuple(tuple(ROM_WORD.to_bits(int(c)) for c in row) for row in codes)
    a = design_matrix(spacing_mm, degree=degree)
    err = WEIGHT.to_float(codes) @ a - np.eye(N_COEFFS, a.shape[1])
    m.flags.writeable = False
    err.flags.writeable = False
    return BakedPinv(spacing_mm=float(spacing_mm), degree=int(degree), weights=m,
                     weight_codes=tuple(tuple(int(c) for c in row) for row in codes),
                     rom_words=words, reproduction_error=err)


@functools.lru_cache(maxsize=1)
def baked_pinv() -> BakedPinv:
    """The ROM of the hardware stencil (``STENCIL_SPACING_MM``), computed once."""
    return bake_pseudo_inverse(spacing_mm=STENCIL_SPACING_MM)


def coefficient_error_bound(gaps_mm, *, rom: BakedPinv | None = None,
                            gap_fmt: QFormat = STENCIL_GAP,
                            coeff_fmt: QFormat = COEFF) -> np.ndarray:
    """Rigorous bound on |c_golden - c_exact| for one stencil, per coefficient.

    The golden coefficient is ``round(Mq gq)`` with ``gq`` the gaps rounded to
    ``gap_fmt`` and ``Mq`` the quantized weights; the exact one is ``M g`` (for samples
    of a polynomial of degree <= 6, its own quadratic coefficients). Hence

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
