"""POW and CBRT look-up tables of stage D: contents, packing and interpolation.

Both ROMs are 256 words x 32 bits (docs/spec.md sec. 6). This module is the one place that
generates their contents; the golden models and the RTL import :func:`pow_lut` /
:func:`cbrt_lut` (never a copy).

Word layout (unsigned):  ``word = (V << QBITS) | Q``

* ``V`` — the function value at node ``i``, ``UQ(32-QBITS, VFRAC)``, round-half-up;
* ``Q`` — a non-negative curvature correction for segment ``[x_i, x_{i+1}]`` in units
  of ``2**-QFRAC``, chosen so that the interpolant is exact at the segment midpoint:
  ``Q = round(4 (f(x_mid) - (V_i + V_{i+1})/2) 2**QFRAC)`` (both functions are
  concave, so Q >= 0; asserted).

Interpolation "by shift" with ``T = 2**TBITS`` sub-steps per segment and the position
``r`` (0 <= r < T) of the argument inside segment ``i`` (the low TBITS bits of the
argument code, the segment index being the bits above)::

    y = V_i * T + r * (V_{i+1} - V_i) + round_shift(r * (T - r) * Q_i, TBITS + QFRAC - VFRAC)

in units of ``2**-(VFRAC + TBITS)`` — the chord plus the quadratic term
``t (1 - t) Q`` with ``t = r/T`` (a Newton/Bezier quadratic through both nodes and the
midpoint). Every product is below 2**57.

=====  ============================  =====  =====  =====  =====  ======  ==============
LUT    function, node x_i            VBITS  VFRAC  QBITS  QFRAC  TBITS   argument code
=====  ============================  =====  =====  =====  =====  ======  ==============
POW    k = alpha^(2/pi), 1 + i/2     22     17     10     15     23      alpha UQ(32,24)
CBRT   c = m^(1/3),      1 + i/32    24     22     8      20     24      m UQ(32,29)
=====  ============================  =====  =====  =====  =====  ======  ==============

Interpolation error (measured against fp64 ``x**exponent`` in
``tests/preview/hertz/test_luts.py``): POW at most 1.9e-4 relative (alpha ~ 1.1: the
cubic remainder ``f'''(x) h^3 t (t - 1/2)(t - 1)/6`` is odd about the midpoint, so
no symmetric quadratic term can cancel it; it decays ~alpha^-2.4 to 2.5e-6 beyond
alpha = 5); CBRT 1.8e-7 (node rounding 2^-23 plus interpolation).

References
----------
J.-M. Muller, *Elementary Functions: Algorithms and Implementation*, 3rd ed.,
Birkhaeuser, 2016, ch. 6 (table-based methods, range reduction).
B. J. Hamrock, D. E. Brewe, J. Lubrication Technol. 105 (1983) 171-177 (k = alpha^(2/pi)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..qformat import round_shift

__all__ = ["LutSpec", "POW_SPEC", "CBRT_SPEC", "LUT_SIZE", "LUT_WORD_BITS", "pow_lut",
           "cbrt_lut", "build_lut", "lut_array", "unpack_word", "lut_interpolate"]

LUT_SIZE = 256          #: words per ROM
LUT_WORD_BITS = 32      #: bits per ROM word


@dataclass(frozen=True)
class LutSpec:
    """Geometry and packing of one interpolating ROM.

    Attributes
    ----------
    name : str
        ``"pow"`` or ``"cbrt"``.
    x0 : float
        Argument of node 0 (dimensionless).
    step_log2 : int
        Node spacing ``2**step_log2`` in argument units.
    arg_frac : int
        Fraction bits of the argument code (``alpha`` UQ(32,24), ``m`` UQ(32,29)).
    vbits, vfrac : int
        Width and fraction bits of the node value V.
    qbits, qfrac : int
        Width of the correction field Q and its LSB exponent (units 2**-qfrac).
    exponent : float
        The tabulated function is ``x ** exponent``.
    """

    name: str
    x0: float
    step_log2: int
    arg_frac: int
    vbits: int
    vfrac: int
    qbits: int
    qfrac: int
    exponent: float

    @property
    def tbits(self) -> int:
        """Argument bits below the node step (sub-step resolution), ``arg_frac + step_log2``."""
        return self.arg_frac + self.step_log2

    @property
    def out_frac(self) -> int:
        """Fraction bits of the interpolated value, ``vfrac + tbits``."""
        return self.vfrac + self.tbits

    @property
    def corr_shift(self) -> int:
        """Right shift of the quadratic term, ``tbits + qfrac - vfrac``."""
        return self.tbits + self.qfrac - self.vfrac

    @property
    def x0_code(self) -> int:
        """Argument code of node 0."""
        return int(round(self.x0 * (1 << self.arg_frac)))


#: k = alpha^(2/pi) over alpha = 1 + i/2 (Hamrock & Brewe 1983), used for alpha <= 128.
POW_SPEC = LutSpec("pow", 1.0, -1, 24, 22, 17, 10, 15, 2.0 / math.pi)
#: c = m^(1/3) over m = 1 + i/32, used for m in [1, 8).
CBRT_SPEC = LutSpec("cbrt", 1.0, -5, 29, 24, 22, 8, 20, 1.0 / 3.0)


def build_lut(spec: LutSpec) -> tuple[int, ...]:
    """Generate the 256 packed ROM words of ``spec`` (see the module docstring)."""
    step = math.ldexp(1.0, spec.step_log2)

    def f(x: float) -> float:
        return x ** spec.exponent

    nodes = [spec.x0 + i * step for i in range(LUT_SIZE + 1)]
    v = [math.floor(math.ldexp(f(x), spec.vfrac) + 0.5) for x in nodes]
    words = []
    for i in range(LUT_SIZE):
        chord_mid = math.ldexp(v[i] + v[i + 1], -spec.vfrac - 1)
        q = math.floor(math.ldexp(4.0 * (f(nodes[i] + 0.5 * step) - chord_mid), spec.qfrac)
                       + 0.5)
        assert 0 <= q < (1 << spec.qbits), (spec.name, i, q)
        assert 0 <= v[i] < (1 << spec.vbits), (spec.name, i, v[i])
        words.append((v[i] << spec.qbits) | q)
    assert spec.vbits + spec.qbits == LUT_WORD_BITS
    return tuple(words)


@lru_cache(maxsize=None)
def pow_lut() -> tuple[int, ...]:
    """The POW ROM (256 x 32 bit words), k = alpha^(2/pi)."""
    return build_lut(POW_SPEC)


@lru_cache(maxsize=None)
def cbrt_lut() -> tuple[int, ...]:
    """The CBRT ROM (256 x 32 bit words), c = m^(1/3)."""
    return build_lut(CBRT_SPEC)


def lut_array(spec: LutSpec) -> np.ndarray:
    """The ROM of ``spec`` as an ``int64`` array (for vectorized models)."""
    return np.array(pow_lut() if spec.name == "pow" else cbrt_lut(), dtype=np.int64)


def unpack_word(word: int, spec: LutSpec) -> tuple[int, int]:
    """Split a ROM word into ``(V, Q)``."""
    return word >> spec.qbits, word & ((1 << spec.qbits) - 1)


def lut_interpolate(arg_code: int, spec: LutSpec, lut=None) -> int:
    """Interpolated ``f(arg)`` in units of ``2**-spec.out_frac`` (exact integers).

    Parameters
    ----------
    arg_code : int
        Argument in ``UQ(32, spec.arg_frac)``; the caller guarantees that its segment
        index ``(arg_code - x0_code) >> tbits`` lies in ``[0, 254]``.
    spec : LutSpec
        Which ROM.
    lut : sequence of int, optional
        ROM words (defaults to the baked one).

    Returns
    -------
    int
        ``V_i T + r (V_{i+1} - V_i) + round_shift(r (T - r) Q_i, corr_shift)``.
    """
    lut = (pow_lut() if spec.name == "pow" else cbrt_lut()) if lut is None else lut
    off = arg_code - spec.x0_code
    i = off >> spec.tbits
    r = off & ((1 << spec.tbits) - 1)
    if not 0 <= i < LUT_SIZE - 1:
        raise ValueError(f"{spec.name} LUT segment {i} outside [0, {LUT_SIZE - 2}]")
    v0, q0 = unpack_word(lut[i], spec)
    v1, _ = unpack_word(lut[i + 1], spec)
    t_full = 1 << spec.tbits
    return (v0 * t_full + r * (v1 - v0)
            + round_shift(r * (t_full - r) * q0, spec.corr_shift))
