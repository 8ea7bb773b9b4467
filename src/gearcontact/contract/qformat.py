"""Fixed-point Q formats of the host <-> datapath data contract.

``Q(m, f)`` is an m-bit two's-complement word with f fraction bits (docs/spec.md sec. 6);
``UQ(m, f)`` its unsigned twin. Codes are Python ``int`` (arbitrary width, exact) or
numpy ``int64`` arrays where every value provably fits in 63 bits.

Rounding is round-half-up by shifting: ``(x + 2**(n-1)) >> n`` (an arithmetic shift,
so -0.5 LSB rounds to 0 and -1.5 LSB to -1). Nothing saturates or wraps silently:
:meth:`QFormat.check` raises :class:`FixedPointOverflow` naming the signal, and the
golden models turn that into a flag where the hardware has one. The host (the TCA's
phase table) encodes with these formats and the three datapath stages decode them, so
they live below both (every module imports them from here; the former
``gearcontact.preview.qformat`` is a deprecated alias).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DatapathFlagged

__all__ = ["QFormat", "FixedPointOverflow", "round_shift", "sq", "uq",
           "COORD", "NORMAL", "LOAD", "CURVATURE", "SEMI_AXIS", "PMAX", "GAP",
           "STENCIL_GAP"]


class FixedPointOverflow(DatapathFlagged):
    """A value does not fit its fixed-point format (the datapath cannot take it: exit 3
    where it escapes a command; an input file's value is checked as bad input first).

    Attributes
    ----------
    field : str
        Signal name.
    value : object
        The offending value (real number or integer code).
    fmt : QFormat
        The format it had to fit.
    """

    def __init__(self, field: str, value, fmt: "QFormat"):
        self.field = field
        self.value = value
        self.fmt = fmt
        super().__init__(
            f"{field} = {value!r} does not fit {fmt}: allowed "
            f"[{fmt.min_value:.10g}, {fmt.max_value:.10g}] "
            f"(codes [{fmt.min_code}, {fmt.max_code}])")


def round_shift(x, n: int):
    """Round-half-up arithmetic right shift of ``x`` by ``n`` bits.

    Works on Python ints (exact) and numpy integer arrays (caller guarantees that
    ``x + 2**(n-1)`` does not overflow the dtype). ``n == 0`` returns ``x``.
    """
    if n < 0:
        raise ValueError(f"shift n = {n} must be >= 0")
    if n == 0:
        return x
    return (x + (1 << (n - 1))) >> n


@dataclass(frozen=True)
class QFormat:
    """A fixed-point word format.

    Parameters
    ----------
    bits : int
        Total word width m in bits (including the sign bit when signed).
    frac : int
        Number of fraction bits f; one LSB is 2**-f.
    signed : bool
        Two's complement if True, unsigned otherwise.
    """

    bits: int
    frac: int
    signed: bool = True

    def __str__(self) -> str:
        return f"{'' if self.signed else 'U'}Q({self.bits},{self.frac})"

    @property
    def min_code(self) -> int:
        return -(1 << (self.bits - 1)) if self.signed else 0

    @property
    def max_code(self) -> int:
        return (1 << (self.bits - 1)) - 1 if self.signed else (1 << self.bits) - 1

    @property
    def lsb(self) -> float:
        """Value of one LSB (2**-f)."""
        return math.ldexp(1.0, -self.frac)

    @property
    def min_value(self) -> float:
        return math.ldexp(self.min_code, -self.frac)

    @property
    def max_value(self) -> float:
        return math.ldexp(self.max_code, -self.frac)

    def fits(self, code):
        """True where ``code`` (int or array) is representable."""
        return (code >= self.min_code) & (code <= self.max_code)

    def check(self, code, *, field: str):
        """Return ``code`` unchanged; raise :class:`FixedPointOverflow` if it does not fit."""
        if isinstance(code, np.ndarray):
            bad = ~self.fits(code)
            if bad.any():
                i = tuple(int(j) for j in np.argwhere(bad)[0])
                raise FixedPointOverflow(f"{field}[{', '.join(map(str, i))}]",
                                         int(code[i]), self)
            return code
        if not self.fits(code):
            raise FixedPointOverflow(field, int(code), self)
        return code

    def quantize(self, x: float, *, field: str) -> int:
        """Round a real number to the nearest code (half up); raise if out of range."""
        xf = float(x)
        if not math.isfinite(xf):
            raise FixedPointOverflow(field, xf, self)
        code = math.floor(math.ldexp(xf, self.frac) + 0.5)
        if not self.fits(code):
            raise FixedPointOverflow(field, xf, self)
        return int(code)

    def quantize_array(self, x, *, field: str) -> np.ndarray:
        """Vectorized :meth:`quantize` to ``int64`` (formats up to 63 bits)."""
        if self.bits > 63:
            raise ValueError(f"{self} is wider than int64")
        xa = np.asarray(x, dtype=float)
        if not np.isfinite(xa).all():
            i = tuple(int(j) for j in np.argwhere(~np.isfinite(xa))[0])
            raise FixedPointOverflow(f"{field}[{', '.join(map(str, i))}]", xa[i], self)
        scaled = np.floor(np.ldexp(xa, self.frac) + 0.5)
        bad = (scaled < self.min_code) | (scaled > self.max_code)
        if bad.any():
            i = tuple(int(j) for j in np.argwhere(bad)[0])
            raise FixedPointOverflow(f"{field}[{', '.join(map(str, i))}]", xa[i], self)
        return scaled.astype(np.int64)

    def to_float(self, code):
        """Real value of a code (float for int, float64 array for arrays)."""
        if isinstance(code, np.ndarray):
            return np.ldexp(code.astype(float), -self.frac)
        return math.ldexp(int(code), -self.frac)

    def to_bits(self, code: int) -> int:
        """The code as an unsigned ``bits``-wide bit pattern (for hex export/registers)."""
        self.check(code, field="code")
        return int(code) & ((1 << self.bits) - 1)

    def from_bits(self, pattern: int) -> int:
        """Inverse of :meth:`to_bits` (sign-extends signed formats)."""
        pattern = int(pattern) & ((1 << self.bits) - 1)
        if self.signed and pattern >> (self.bits - 1):
            pattern -= 1 << self.bits
        return pattern


def sq(bits: int, frac: int) -> QFormat:
    """Signed ``Q(bits, frac)``."""
    return QFormat(bits, frac, True)


def uq(bits: int, frac: int) -> QFormat:
    """Unsigned ``UQ(bits, frac)``."""
    return QFormat(bits, frac, False)


# The data contract of docs/spec.md sec. 6 (units in the comments).
COORD = sq(24, 16)      #: position, mm
NORMAL = sq(20, 19)     #: unit-normal / rotation-matrix component, Q1.19 (dimensionless)
LOAD = sq(32, 8)        #: contact load W, N
CURVATURE = sq(32, 20)  #: relative principal curvature A-, B-, 1/mm
SEMI_AXIS = sq(32, 20)  #: contact-ellipse semi-axes a, b, mm
PMAX = sq(32, 8)        #: peak Hertzian pressure, MPa
GAP = sq(32, 16)        #: signed gap, mm (stage A/B output)
#: Stencil gap sample, stage C input, mm. Its own format, finer than GAP: stage C's
#: degree-6 ROM (docs/spec.md sec. 6) amplifies the input rounding by its row norms
#: (||M_c3||_1 = 88.3 1/mm^2): at GAP's 2^-16 mm the rounding bound of the fitted B-
#: would be ~1600 CURVATURE codes, at 2^-21 mm it is 56. Its +-1024 mm range still holds the
#: term K s^2 at the window's edge (s = 0.6 mm: 0.36 K < 737 mm) for every curvature
#: |K| < 2048 1/mm that CURVATURE can hold, plus the offset and slopes.
#: Stage A/B and stage C are not wired together (the host writes the 49 words).
STENCIL_GAP = sq(32, 21)
