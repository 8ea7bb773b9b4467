"""POW, CBRT (and exact-Hertz) look-up tables of stage D: contents, packing, interpolation.

Every ROM is 256 words x 32 bits (docs/spec.md sec. 6). This module is the one place that
generates their contents; the golden models and the RTL import :func:`pow_lut` /
:func:`cbrt_lut` / :func:`rom_words` (never a copy).

Word layout (unsigned):  ``word = (V << QBITS) | Q``

* ``V`` — the function value at node ``i``, ``UQ(32-QBITS, VFRAC)``, round-half-up;
* ``Q`` — a non-negative curvature correction for segment ``[x_i, x_{i+1}]`` in units
  of ``2**-QFRAC``, chosen so that the interpolant is exact at the segment midpoint:
  ``Q = round(4 (f(x_mid) - (V_i + V_{i+1})/2) 2**QFRAC)`` (every tabulated function
  is concave, so Q >= 0; asserted, except Q = -1 from the node rounding where EEX is
  nearly linear, stored as 0).

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
POWX   exact k(alpha),   1 + i/2     22     17     10     15     23      alpha UQ(32,24)
EEX    N(alpha),         1 + i/2     22     17     10     15     23      alpha UQ(32,24)
=====  ============================  =====  =====  =====  =====  ======  ==============

POWX and EEX are the two tables of the ``hertz_form="exact"`` variant: the exact
ellipticity ``k(alpha)`` and ``N(alpha) = (6/pi) alpha (E(alpha) - 1)``, both from
:func:`gearcontact.analytic.hertz.exact_ellipticity` (complete elliptic integrals).
The datapath then forms ``E6 = 6 E/pi = C6 + N(alpha)/alpha`` on the divider exactly as
the published form does with the constant ``N5 = 3 - 6/pi`` (the published
``E_e = 1 + (pi/2 - 1)/alpha`` is ``N = N5``), so that the division by alpha, not the
table, carries the 1/alpha curvature of E: N varies only between 1.09 and 1.14 over
alpha in [1, 128], and a direct table of E6 with these nodes would err by 9e-4
(cubic remainder at alpha ~ 1) against 2e-4 for N. Both tables have POW's geometry, so
they are interpolated by the same hardware (one 512-word ROM, :mod:`.rtl`).

Interpolation error (measured against fp64 ``x**exponent`` in
``tests/preview/hertz/test_luts.py``): POW at most 1.9e-4 relative (alpha ~ 1.1: the
cubic remainder ``f'''(x) h^3 t (t - 1/2)(t - 1)/6`` is odd about the midpoint, so
no symmetric quadratic term can cancel it; it decays ~alpha^-2.4 to 2.5e-6 beyond
alpha = 5); CBRT 1.8e-7 (node rounding 2^-23 plus interpolation); POWX 1.7e-4 and
EEX 2.1e-4 relative near alpha = 1 (same cause), 2.5e-6 and 4.3e-6 beyond alpha = 5.

References
----------
J.-M. Muller, *Elementary Functions: Algorithms and Implementation*, 3rd ed.,
Birkhaeuser, 2016, ch. 6 (table-based methods, range reduction).
B. J. Hamrock, D. E. Brewe, J. Lubrication Technol. 105 (1983) 171-177 (k = alpha^(2/pi)).
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, sec. 4.2 (exact
k and E).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ...contract.qformat import round_shift
from . import formats as F

__all__ = ["LutSpec", "POW_SPEC", "CBRT_SPEC", "POW_EXACT_SPEC", "EE_EXACT_SPEC",
           "POW_SPECS", "EE_DIVIDEND_SHIFT", "LUT_SIZE", "LUT_WORD_BITS", "pow_lut",
           "cbrt_lut", "rom_words", "build_lut", "lut_array", "lut_function",
           "unpack_word", "lut_interpolate", "same_geometry"]

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
        The tabulated function is ``x ** exponent`` (``function == "power"``).
    function : str
        ``"power"``, or one of the exact-Hertz functions of the radius ratio:
        ``"hertz_k"`` (ellipticity k) or ``"hertz_n"`` (N = (6/pi) alpha (E - 1)).
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
    function: str = "power"

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
#: Exact ellipticity k(alpha) (``hertz_form="exact"``), POW's geometry.
POW_EXACT_SPEC = LutSpec("pow_exact", 1.0, -1, 24, 22, 17, 10, 15, math.nan, "hertz_k")
#: Exact N(alpha) = (6/pi) alpha (E(alpha) - 1) (``hertz_form="exact"``), POW's geometry.
EE_EXACT_SPEC = LutSpec("ee_exact", 1.0, -1, 24, 22, 17, 10, 15, math.nan, "hertz_n")
#: The k table of each Hertz form.
POW_SPECS = {"hamrock-brewe": POW_SPEC, "exact": POW_EXACT_SPEC}
#: Left shift of the EEX interpolation (units 2^-out_frac) that gives the E_e
#: dividend in N5's units 2^-(E6.frac + ALPHA.frac): E6 = C6 + (N << 9) // alpha.
EE_DIVIDEND_SHIFT = F.E6.frac + F.ALPHA.frac - EE_EXACT_SPEC.out_frac


def same_geometry(a: LutSpec, b: LutSpec) -> bool:
    """True when two tables are read and interpolated by identical hardware (same
    argument, nodes, packing and shifts; only the words differ)."""
    return ((a.x0, a.step_log2, a.arg_frac, a.vbits, a.vfrac, a.qbits, a.qfrac)
            == (b.x0, b.step_log2, b.arg_frac, b.vbits, b.vfrac, b.qbits, b.qfrac))


assert same_geometry(POW_SPEC, POW_EXACT_SPEC) and same_geometry(POW_SPEC, EE_EXACT_SPEC)
assert EE_DIVIDEND_SHIFT == 9


def lut_function(spec: LutSpec):
    """The fp64 function ``f(x)`` tabulated by ``spec`` (dimensionless)."""
    if spec.function == "power":
        return lambda x: x ** spec.exponent
    from ...analytic.hertz import exact_ellipticity
    if spec.function == "hertz_k":
        return lambda x: exact_ellipticity(x)[0]
    if spec.function == "hertz_n":
        return lambda x: 6.0 / math.pi * x * (exact_ellipticity(x)[1] - 1.0)
    raise ValueError(f"unknown LUT function {spec.function!r}")


def build_lut(spec: LutSpec) -> tuple[int, ...]:
    """Generate the 256 packed ROM words of ``spec`` (see the module docstring)."""
    step = math.ldexp(1.0, spec.step_log2)
    f = lut_function(spec)
    nodes = [spec.x0 + i * step for i in range(LUT_SIZE + 1)]
    v = [math.floor(math.ldexp(f(x), spec.vfrac) + 0.5) for x in nodes]
    words = []
    for i in range(LUT_SIZE):
        chord_mid = math.ldexp(v[i] + v[i + 1], -spec.vfrac - 1)
        q = math.floor(math.ldexp(4.0 * (f(nodes[i] + 0.5 * step) - chord_mid), spec.qfrac)
                       + 0.5)
        # N(alpha) is within the node rounding of linear around alpha ~ 12 (Q = -1 from
        # the rounded nodes there): stored as 0, an error of at most 2^-17 absolute.
        assert -1 <= q < (1 << spec.qbits), (spec.name, i, q)
        q = max(q, 0)
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


_BAKED = {s.name: s for s in (POW_SPEC, CBRT_SPEC, POW_EXACT_SPEC, EE_EXACT_SPEC)}


@lru_cache(maxsize=None)
def rom_words(spec: LutSpec) -> tuple[int, ...]:
    """The 256 ROM words of any table of this module (generated once per process;
    the exact-Hertz tables take ~0.1 s: 513 solutions of the eccentricity equation)."""
    if _BAKED.get(spec.name) is not spec:
        raise ValueError(f"{spec.name!r} is not a stage-D table")
    return pow_lut() if spec is POW_SPEC else cbrt_lut() if spec is CBRT_SPEC \
        else build_lut(spec)


def lut_array(spec: LutSpec) -> np.ndarray:
    """The ROM of ``spec`` as an ``int64`` array (for vectorized models)."""
    return np.array(rom_words(spec), dtype=np.int64)


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
    lut = rom_words(spec) if lut is None else lut
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
