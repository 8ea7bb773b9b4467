"""Stage D in near-line contact: the truncated-ellipse (line-contact) mode, golden model.

Ordinary gear bearings are long: along the path the smaller half relative curvature
A_min falls below the published core's range (2^-11 1/mm: a reduced radius above
1 m) and the Hertz ellipse may be longer than the flank. This *line core* wraps the
published elliptic datapath (:mod:`.golden`, its 756-cycle schedule and netlist
unchanged) with one more input, the length ``L`` of the contact line on the flank
through the contact point along the ellipse's major axis, and answers in one of two
modes (``mode``):

* ``MODE_ELLIPTIC`` (0): the elliptic datapath evaluates the contact, and either the
  ellipse fits (``a <= L/2``) or it is longer but its peak pressure is still the higher
  one (below). A_min under 2^-11 1/mm is brought into the datapath's range by the exact
  Hertz similarity (``SCALE``): scaling both curvatures by ``8^n`` scales a, b by
  ``2^-n`` and p_max by ``4^n`` at the same load and ratio, so the datapath runs on
  ``(A << 3n, B << 3n)`` and its outputs are scaled back. This covers reduced radii up
  to 2^19 mm (A_min down to one code, 2^-20 1/mm; the input quantization then sets the
  accuracy, docs/hertz.md sec. 6).
* ``MODE_LINE`` (1): the flank truncates the ellipse to its contact line of length L,
  and the answer is the Hertz line contact of a cylinder of length L (Johnson 1985,
  sec. 4.3), with ``R = 1/(2 B_max)`` across the line::

      p0 = sqrt(W E* / (pi R L)) = sqrt(W E' B_max / (pi L)),  b = 2 W / (pi L p0),
      a = L/2, k = 0 (no ellipticity; the engine reports a/b)

  It is chosen when the elliptic datapath cannot evaluate the contact (ratio
  ``B_max/A_min > 128``, or ``A_min = 0``: a line already), or when the ellipse is
  longer than the flank (``a > L/2``) and the line contact's peak is the higher one.
  Both answers are lower bounds of the truncated ellipse's peak (cutting an ellipse only
  removes area; a load spread evenly along L is the least concentrated one), so the
  higher one is taken: just past ``a = L/2`` the ellipse's (the cut-off tips carry
  little load), far past it the line's. The pressure is then continuous in the load
  and curvatures where the mode changes (a plain ``a > L/2`` switch would drop it by
  up to ~20 %: ``2/3 (b_e/b_l)`` at ``a = L/2``), except where the ratio crosses 128
  with the ellipse inside the flank: there the line answer is below the ellipse's
  (the POW table's end; docs/hertz.md sec. 6, known limit).

(:func:`gearcontact.analytic.hertz.line_contact_hertz` is the fp64 truth of the line
answer, :func:`.reference.truncated_preview` the fp64 model of the mode rule.)

Operation sequence of the line core (codes; ``rs`` round-half-up shift, ``//`` the
divider, ``isqrt`` the restoring square root of :mod:`.sqrt`)::

    SORT      A_min, B_max = min(A, B), max(A, B); line-envelope checks -> flags
    SCALE     n = min(n_a, n_b): n_a smallest n in 0..3 with A_min << 3n >= 2^9
              (0 when A_min = 0 or A_min >= 2^9), n_b largest n in 0..3 with
              B_max << 3n <= 2^24
    ELLIPTIC  the published datapath on (A_min << 3n, B_max << 3n, W, E')
              -> a', b', p', k', flags'
    UNSCALE   a_e = a' << n, b_e = b' << n, p_e = rs(p', 2n), k_e = k'
    DIV_QPI   QPI  = ((W C_IPI) << 4) // L        UQ(40,24)  W/(pi L), N/mm
    PRODUCT   Y    = rs(QPI E', 21)               UQ(40,3)   W E'/(pi L), N MPa/mm
              P0SQ = Y B_max                       UQ(64,23)  p0^2, MPa^2
    SQRT      S    = isqrt(P0SQ << 9)             UQ(37,16)  p0, MPa
    DIV_BL    b_l  = (QPI << 29) // S             UQ(46,36)  b = 2 W/(pi L p0), mm
    SELECT    p_l = rs(S, 8); elliptic when flags' = 0 and (2 a_e <= L or p_e >= p_l):
              (a_e, b_e, p_e, k_e); else line: a = rs(L, 1), b = rs(b_l, 16),
              p_max = p_l, k = 0;
              S = 0 -> FLAG_DIV_ZERO; an output beyond its format (a_e, b, p_max)
              -> FLAG_OVERFLOW

=========  ============  =========================================  ==============
register   format        definition                                 bound (codes)
=========  ============  =========================================  ==============
L          Q(32,20)      LINE_LENGTH input, mm                      [2^20, 2^30]
C_IPI      UQ(31,32)     round(2^32 / pi)                           < 2^31
QPI        UQ(40,24)     W/(pi L), N/mm                             < 2^39.4
Y          UQ(40,3)      W E'/(pi L), N MPa/mm                      < 2^39.4
P0SQ       UQ(64,23)     p0^2 = W E' B_max/(pi L), MPa^2            < 2^63.4
S          UQ(37,16)     p0, MPa (floor square root)                < 2^36.2
b_l        UQ(46,36)     b, mm                                      < 2^44.2
a, b       Q(32,20)      outputs, mm (SEMI_AXIS)
p_max      Q(32,8)       output, MPa (PMAX)
mode       2 bits        MODE_ELLIPTIC / MODE_LINE
scale      2 bits        n
=========  ============  =========================================  ==============

Every product is below 2^64 and every dividend below 2^80 (QPI: W C_IPI 2^4 < 2^60;
b_l: QPI 2^29 < 2^69), the radicand below 2^73; the bounds are the envelope corners
and the model asserts them on every run.

Line-core envelope (checked in SORT; outside it the run is flagged, outputs 0):
``A_min >= 0`` (``FLAG_NOT_ELLIPTIC`` for a saddle: no contact line either),
``B_max`` in [2^-11, 16] 1/mm (``FLAG_CURV_RANGE``: the reduced radius across the line
is at most 1 m), load and E' as the published core, ``L`` in [1, 1024] mm
(:data:`FLAG_LENGTH_RANGE`, bit 7, named in :data:`LINE_FLAG_NAMES` only: the published
cores' flags word keeps its width; the host lifts a shorter line, below).

Short lines (host side, :func:`length_lift`, :func:`unlift_line`; the core and its
RTL are unchanged). A line shorter than 1 mm (an end-loaded line's equivalent length,
docs/cylindrical.md sec. 8) runs on ``(W << s, L << s)`` with the least ``s`` that
brings ``L`` to 1 mm (``s <= LIFT_MAX_SHIFT``: ``L >= 2^-8`` mm; ``W << s`` in the
load envelope). Every register of the line stage depends on ``W / L`` alone, exactly:
``QPI = floor(16 W C_IPI / L)`` is the same integer for ``(k W, k L)``, and Y, P0SQ, S,
b_l, p_max, b follow from it, so the line answer is the floorless core's bit for bit,
``a = rs(L, 1)`` restored by ``rs(a, s)``. The elliptic datapath is not invariant (its
ellipse of ``2^s W`` is ``2^(s/3)`` longer, the line ``2^s``): a lifted run that keeps
the ellipse answers ``2^s W``'s contact, so it is flagged ``length_range`` (outputs 0);
a lifted line-mode run is the unlifted decision too (``2 a_e(W) > 2^(2s/3) L`` and
``p_e(W) < 2^(-s/3) p_l``: margins of 59 % and 26 % at ``s = 1``).

Cycle schedule (the RTL's contract; data independent): CAPTURE 1, SORT + SCALE 1, the
unchanged elliptic core 756 (the line stage runs on its own divider and square-root
unit meanwhile: DIV_QPI 83 + PRODUCT 2 + SQRT 43 + DIV_BL 83 = 211 cycles), SELECT 1:
``LINE_CYCLES = 759``.

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, sec. 4.2 (Hertz
similarity), sec. 4.3 (line contact).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...validation import check_array_finite, check_finite
from ...contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS, round_shift, sq, uq
from . import formats as F
from .divider import DIVIDER_BITS, DIVISION_CYCLES, floor_divide
from .golden_vec import njit
from .golden import _check_code, hertz_golden
from .schedule import HERTZ_CYCLES
from .sqrt import SQRT_BITS, SQRT_CYCLES, floor_sqrt

__all__ = ["LINE_LENGTH", "QPI", "Y_LINE", "P0SQ", "SQRT_OUT", "B_LINE", "C_IPI",
           "LENGTH_MIN_CODE", "LENGTH_MAX_CODE", "SCALE_MAX", "MODE_ELLIPTIC", "MODE_LINE",
           "MODE_NAMES", "FLAG_LENGTH_RANGE", "LINE_FLAG_NAMES", "line_flag_names",
           "LINE_STAGE_CYCLES", "LINE_CYCLES", "LineCodes", "line_golden",
           "encode_length", "decode_line_codes", "line_envelope_flags", "scale_exponent",
           "LIFT_MAX_SHIFT", "length_lift", "unlift_line", "unlift_line_codes"]

# ---- formats (table above) -------------------------------------------------------
LINE_LENGTH = sq(32, 20)     #: contact-line length L input, mm
QPI = uq(40, 24)             #: W/(pi L), N/mm
Y_LINE = uq(40, 3)           #: W E'/(pi L), N MPa/mm
P0SQ = uq(64, 23)            #: p0^2, MPa^2
SQRT_OUT = uq(37, 16)        #: p0, MPa
B_LINE = uq(46, 36)          #: line half-width b, mm

C_IPI_FRAC = 32
C_IPI = math.floor(2.0 ** C_IPI_FRAC / math.pi + 0.5)          #: 1/pi, UQ(31,32)
QPI_SHIFT = QPI.frac + LINE_LENGTH.frac - LOAD.frac - C_IPI_FRAC   #: 4
Y_SHIFT = QPI.frac - Y_LINE.frac                                   #: 21
SQRT_SHIFT = 2 * SQRT_OUT.frac - (Y_LINE.frac + CURVATURE.frac)    #: 9
BL_SHIFT = B_LINE.frac + SQRT_OUT.frac - QPI.frac + 1              #: 29 (+1: the 2 of 2W)
assert (QPI_SHIFT, Y_SHIFT, SQRT_SHIFT, BL_SHIFT) == (4, 21, 9, 29)
assert P0SQ.frac == Y_LINE.frac + CURVATURE.frac

# ---- envelope ----------------------------------------------------------------------
LENGTH_MIN_CODE = 1 << LINE_LENGTH.frac            #: 1 mm
LENGTH_MAX_CODE = 1 << (LINE_LENGTH.frac + 10)     #: 1024 mm
SCALE_MAX = 3                                      #: curvatures scaled by up to 8^3
LIFT_MAX_SHIFT = 8                                 #: host lift of L: down to 2^-8 mm

# ---- flags: the published bits plus one (a separate map: the published cores' flag
# width, register map and the chain's flag packing stay as they are) ------------------
FLAG_LENGTH_RANGE = 1 << 7    #: contact-line length L outside [1, 1024] mm
LINE_FLAG_NAMES = {**F.FLAG_NAMES, FLAG_LENGTH_RANGE: "length_range"}


def line_flag_names(flags: int) -> tuple[str, ...]:
    """Names of the bits set in a line-core flags word (empty tuple when valid)."""
    return tuple(name for bit, name in LINE_FLAG_NAMES.items() if flags & bit)


# ---- modes and schedule ------------------------------------------------------------
MODE_ELLIPTIC = 0
MODE_LINE = 1
MODE_NAMES = {MODE_ELLIPTIC: "elliptic", MODE_LINE: "line"}
#: Cycles of the line stage on its own divider and square-root unit (inside the
#: elliptic core's 756): DIV_QPI + PRODUCT (2) + SQRT + DIV_BL.
LINE_STAGE_CYCLES = DIVISION_CYCLES + 2 + SQRT_CYCLES + DIVISION_CYCLES
#: go -> done of the line core: CAPTURE, SORT + SCALE, elliptic core, SELECT.
LINE_CYCLES = 1 + 1 + HERTZ_CYCLES + 1
assert LINE_STAGE_CYCLES == 211 <= HERTZ_CYCLES and LINE_CYCLES == 759

_PRODUCT_LIMIT = 1 << 64


@dataclass(frozen=True)
class LineCodes:
    """Output registers of one line-core run (integer codes).

    Attributes
    ----------
    a_code, b_code : int
        Semi-axes (elliptic) or half-length L/2 and half-width (line), SEMI_AXIS
        Q(32,20), mm.
    p_max_code : int
        Peak pressure, PMAX Q(32,8), MPa.
    k_code : int
        Ellipticity a/b, Q(32,20) (elliptic; 0 in line mode).
    A_min_code, B_max_code : int
        Sorted curvatures, CURVATURE Q(32,20), 1/mm.
    mode : int
        :data:`MODE_ELLIPTIC` or :data:`MODE_LINE` (0 when flagged).
    scale : int
        Similarity exponent n of SCALE (curvatures scaled by 8^n), 0..3.
    flags : int
        Bitmask of :mod:`.formats` ``FLAG_*``; 0 means valid (outputs 0 otherwise).
    """

    a_code: int
    b_code: int
    p_max_code: int
    k_code: int
    A_min_code: int
    B_max_code: int
    mode: int
    scale: int
    flags: int

    @property
    def valid(self) -> bool:
        """True when no flag is set."""
        return self.flags == 0

    @property
    def flag_names(self) -> tuple[str, ...]:
        """Names of the raised flags."""
        return line_flag_names(self.flags)

    @property
    def mode_name(self) -> str:
        """``"elliptic"``, ``"line"`` or ``"flagged"``."""
        return MODE_NAMES[self.mode] if self.valid else "flagged"


def line_envelope_flags(a_min: int, b_max: int, w: int, e_prime: int, length: int) -> int:
    """Flags raised in SORT by the line core for sorted codes, load, E' and L."""
    flags = 0
    if a_min < 0:
        flags |= F.FLAG_NOT_ELLIPTIC
    if not F.CURV_MIN_CODE <= b_max <= F.CURV_MAX_CODE:
        flags |= F.FLAG_CURV_RANGE
    if not F.LOAD_MIN_CODE <= w <= F.LOAD_MAX_CODE:
        flags |= F.FLAG_LOAD_RANGE
    if not F.E_PRIME_MIN_CODE <= e_prime <= F.E_PRIME_MAX_CODE:
        flags |= F.FLAG_E_PRIME_RANGE
    if not LENGTH_MIN_CODE <= length <= LENGTH_MAX_CODE:
        flags |= FLAG_LENGTH_RANGE
    return flags


def scale_exponent(a_min: int, b_max: int) -> int:
    """SCALE's n for sorted, in-envelope curvature codes (module docstring)."""
    n_a = 0
    if a_min > 0:
        while n_a < SCALE_MAX and (a_min << (3 * n_a)) < F.CURV_MIN_CODE:
            n_a += 1
    n_b = 0
    while n_b < SCALE_MAX and (b_max << (3 * (n_b + 1))) <= F.CURV_MAX_CODE:
        n_b += 1
    return min(n_a, n_b)


def _mul(x: int, y: int, what: str) -> int:
    p = x * y
    assert 0 <= p < _PRODUCT_LIMIT, f"product {what} = {p} exceeds 2^64"
    return p


def _div(n: int, d: int) -> tuple[int, bool]:
    assert 0 <= n < (1 << DIVIDER_BITS), "dividend exceeds the 80-bit register"
    res = floor_divide(n, d)
    return res.quotient, res.divide_by_zero


def line_golden(A_code: int, B_code: int, W_code: int, L_code: int, *, e_prime_code: int,
                hertz_form: str = F.DEFAULT_HERTZ_FORM, trace: dict | None = None
                ) -> LineCodes:
    """Run the line core on one input set (module docstring; the RTL's specification).

    Parameters
    ----------
    A_code, B_code : int
        Half relative principal curvatures, CURVATURE Q(32,20), 1/mm, any order.
    W_code : int
        Load, LOAD Q(32,8), N.
    L_code : int
        Contact-line length on the flank, :data:`LINE_LENGTH` Q(32,20), mm.
    e_prime_code : int
        E' = 2E*, Q(32,0), MPa.
    hertz_form : {"hamrock-brewe", "exact"}
        Form of the elliptic datapath (:data:`.formats.HERTZ_FORMS`).
    trace : dict, optional
        Filled with every internal register (``A_min, B_max, flags_sort, n, elliptic``
        (the :class:`~.golden.HertzCodes` of the scaled run), ``a_e, b_e, p_e, QPI, Y,
        P0SQ, S, b_l``).

    Returns
    -------
    LineCodes

    Raises
    ------
    FixedPointOverflow
        An input code that does not fit its 32-bit register.
    """
    A = _check_code(A_code, CURVATURE, "A_code")
    B = _check_code(B_code, CURVATURE, "B_code")
    W = _check_code(W_code, LOAD, "W_code")
    L = _check_code(L_code, LINE_LENGTH, "L_code")
    E = _check_code(e_prime_code, F.E_PRIME, "e_prime_code")
    tr = {} if trace is None else trace
    a_min, b_max = min(A, B), max(A, B)
    flags = line_envelope_flags(a_min, b_max, W, E, L)
    tr.update(A_min=a_min, B_max=b_max, flags_sort=flags)
    if flags:
        return LineCodes(0, 0, 0, 0, a_min, b_max, 0, 0, flags)
    # SCALE + ELLIPTIC + UNSCALE
    n = tr["n"] = scale_exponent(a_min, b_max)
    hz = tr["elliptic"] = hertz_golden(a_min << (3 * n), b_max << (3 * n), W, e_prime_code=E,
                                       hertz_form=hertz_form)
    a_e, b_e = hz.a_code << n, hz.b_code << n
    p_e = round_shift(hz.p_max_code, 2 * n)
    tr.update(a_e=a_e, b_e=b_e, p_e=p_e)
    # line stage (always computed: fixed schedule)
    qpi, _ = _div(_mul(W, C_IPI, "W C_IPI") << QPI_SHIFT, L)
    y = round_shift(_mul(qpi, E, "QPI E'"), Y_SHIFT)
    p0sq = _mul(y, b_max, "Y B_max")
    assert (p0sq << SQRT_SHIFT) < (1 << SQRT_BITS), "radicand exceeds the 80-bit register"
    s, _ = floor_sqrt(p0sq << SQRT_SHIFT)
    b_l, div_zero = _div(qpi << BL_SHIFT, s)
    tr.update(QPI=qpi, Y=y, P0SQ=p0sq, S=s, b_l=b_l)
    for name, v, fmt in (("QPI", qpi, QPI), ("Y", y, Y_LINE), ("P0SQ", p0sq, P0SQ),
                         ("S", s, SQRT_OUT)):
        assert fmt.fits(v), f"register {name} = {v} exceeds {fmt}"
    # SELECT: the higher of two lower bounds once the ellipse is longer than the flank
    p_c = round_shift(s, SQRT_OUT.frac - PMAX.frac)
    if hz.flags == 0 and (2 * a_e <= L or p_e >= p_c):
        if not SEMI_AXIS.fits(a_e):        # an ellipse beyond 2048 mm kept: no register
            return LineCodes(0, 0, 0, 0, a_min, b_max, 0, n, F.FLAG_OVERFLOW)
        return LineCodes(a_e, b_e, p_e, hz.k_code, a_min, b_max, MODE_ELLIPTIC, n, 0)
    if div_zero:
        return LineCodes(0, 0, 0, 0, a_min, b_max, 0, n, F.FLAG_DIV_ZERO)
    assert B_LINE.fits(b_l), f"register b_l = {b_l} exceeds {B_LINE}"
    a_c = round_shift(L, 1)
    b_c = round_shift(b_l, B_LINE.frac - SEMI_AXIS.frac)
    if not (SEMI_AXIS.fits(b_c) and PMAX.fits(p_c)):
        return LineCodes(0, 0, 0, 0, a_min, b_max, 0, n, F.FLAG_OVERFLOW)
    return LineCodes(a_c, b_c, p_c, 0, a_min, b_max, MODE_LINE, n, 0)


@njit(cache=True)
def length_lift(w_code, l_code):
    """The host's lift ``s`` of a line shorter than the core's 1 mm (module docstring,
    *Short lines*): the smallest ``s`` with ``L << s >= LENGTH_MIN_CODE`` when ``L`` is
    in ``[LENGTH_MIN_CODE >> LIFT_MAX_SHIFT, LENGTH_MIN_CODE)`` and ``W << s`` stays in
    the load envelope; else 0 (the core runs on ``(W, L)`` as given and flags what is
    outside). Compiled (numba): the twin calls it too."""
    s = 0
    if (LENGTH_MIN_CODE >> LIFT_MAX_SHIFT) <= l_code < LENGTH_MIN_CODE \
            and F.LOAD_MIN_CODE <= w_code:
        while (l_code << s) < LENGTH_MIN_CODE:
            s += 1
        if (w_code << s) > F.LOAD_MAX_CODE:
            s = 0
    return s


@njit(cache=True)
def unlift_line(a_code, b_code, p_code, k_code, mode, flags, s):
    """The line core's outputs ``(a, b, p_max, k, mode, flags)`` of a run on the lifted
    ``(W << s, L << s)`` (:func:`length_lift`) as those of ``(W, L)``: in line mode
    ``a = rs(a, s)`` (``rs(L, 1)`` of the unlifted ``L``; b, p_max are the same codes);
    an elliptic answer (the lift grew the ellipse by ``2^(s/3)`` only, not the line's
    ``2^s``: its decision is not ``(W, L)``'s) and a flagged run are flagged
    :data:`FLAG_LENGTH_RANGE` (with their own bits), outputs 0. ``s = 0``: unchanged."""
    if s == 0:
        return a_code, b_code, p_code, k_code, mode, flags
    if flags == 0 and mode == MODE_LINE:
        return (a_code + (1 << (s - 1))) >> s, b_code, p_code, k_code, mode, flags
    return 0, 0, 0, 0, 0, flags | FLAG_LENGTH_RANGE


def unlift_line_codes(codes: LineCodes, s: int) -> LineCodes:
    """:func:`unlift_line` on a :class:`LineCodes`."""
    a, b, p, k, mode, flags = unlift_line(codes.a_code, codes.b_code, codes.p_max_code,
                                          codes.k_code, codes.mode, codes.flags, s)
    return LineCodes(a, b, p, k, codes.A_min_code, codes.B_max_code, mode, codes.scale,
                     flags)


def decode_line_codes(codes) -> dict:
    """Physical values of a line-core result (:class:`LineCodes`, floats, or the
    :class:`.line_vec.LineCodesArray` of a batch, float64 arrays): ``a_mm, b_mm,
    p_max_mpa, k`` (the k register in elliptic mode; a/b in line mode, where the
    datapath has no k; 0 when flagged), ``A_min_per_mm, B_max_per_mm``."""
    if isinstance(codes.a_code, np.ndarray):
        def ld(code, frac):
            return np.ldexp(np.asarray(code, dtype=float), -frac)
        a, b = ld(codes.a_code, SEMI_AXIS.frac), ld(codes.b_code, SEMI_AXIS.frac)
        line = (codes.mode == MODE_LINE) & (codes.flags == 0) & (codes.b_code > 0)
        k = np.where(line, a / np.where(line, b, 1.0), ld(codes.k_code, F.K_OUT.frac))
    else:
        def ld(code, frac):
            return math.ldexp(int(code), -frac)
        a, b = ld(codes.a_code, SEMI_AXIS.frac), ld(codes.b_code, SEMI_AXIS.frac)
        k = a / b if codes.mode == MODE_LINE and codes.valid else ld(codes.k_code,
                                                                      F.K_OUT.frac)
    return {"a_mm": a, "b_mm": b, "p_max_mpa": ld(codes.p_max_code, PMAX.frac), "k": k,
            "A_min_per_mm": ld(codes.A_min_code, CURVATURE.frac),
            "B_max_per_mm": ld(codes.B_max_code, CURVATURE.frac)}


def encode_length(length_mm):
    """Contact-line length (mm) as a :data:`LINE_LENGTH` code (round half up): an int
    for a scalar, an ``int64`` array for an array.

    Raises
    ------
    InputRangeError
        Non-finite value (field ``line_length_mm``).
    FixedPointOverflow
        The value does not fit Q(32,20).
    """
    if np.ndim(length_mm):
        return LINE_LENGTH.quantize_array(check_array_finite("line_length_mm", length_mm),
                                          field="line_length_mm")
    return LINE_LENGTH.quantize(check_finite("line_length_mm", length_mm),
                                field="line_length_mm")
