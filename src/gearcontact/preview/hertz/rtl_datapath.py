"""Stage-D datapath expressions shared by the serialized and the combinational cores.

Every arithmetic step of :func:`.golden.hertz_golden` appears here once, as an
Amaranth expression builder; :mod:`.rtl` (``HertzCore``, the FSM that registers them
over 756 cycles) and :mod:`gearcontact.preview.comb_rtl` (``CombCore``, six pipeline
stages) only decide *when* each one is registered. Formats, constants, envelope codes,
flags and LUT geometry are imported from :mod:`.formats` and :mod:`.luts`.

Operands are passed as a :class:`Operands` record of the registers (or comb signals)
that hold the golden intermediates of the same name.
"""

from __future__ import annotations

from dataclasses import dataclass

from amaranth import Cat, Const, Module, Mux, Signal

from ...contract.qformat import PMAX, SEMI_AXIS
from . import formats as F
from .divider import DIVIDER_BITS
from .luts import EE_DIVIDEND_SHIFT, LUT_SIZE, POW_SPEC, LutSpec

__all__ = [
    "DIVIDEND_SHIFTS",
    "DIVISIONS",
    "DIVISORS",
    "FLAG_BITS",
    "LUT_ADDR_BITS",
    "PRODUCTS",
    "SCALE_BITS",
    "Operands",
    "division",
    "e6_from_quotient",
    "envelope_flags",
    "finalize",
    "fits",
    "flags_word",
    "lut_interpolate",
    "lut_split",
    "pow_to_k",
    "product_operands",
    "product_result",
    "range_reduce",
    "round_shift",
    "round_shift_var",
    "scale_cbrt",
    "sort_pair",
]

#: Width of the stage-D flags word (highest ``FLAG_*`` bit + 1).
FLAG_BITS = max(F.FLAG_NAMES).bit_length()
#: LUT address width (256 words).
LUT_ADDR_BITS = (LUT_SIZE - 1).bit_length()
_W_BITS = (F.LOAD_MAX_CODE).bit_length()          # W inside the envelope (26 bits)

#: Dividend construction of the nine divisions, as in :func:`.golden.hertz_golden`:
#: ``(dividend register or constant, left shift)``; ``None`` marks a constant dividend
#: given by the shift alone (``1 << shift``).
DIVIDEND_SHIFTS = {
    "R_x": (None, 40), "R_y": (None, 40), "alpha": ("b_max", F.ALPHA.frac),
    "R": (None, 42), "E_e": ("N5", 0), "C_a": ("t3", F.CA.frac - F.T3.frac),
    "b": ("a_w", F.K_INT.frac), "p_n2": ("wc3", F.PN2_SHIFT),
    "p_max": ("p_n2", F.PMAX_SHIFT)}
#: Divisor register of each division.
DIVISORS = {"R_x": "a_min", "R_y": "b_max", "alpha": "a_min", "R": "a_min+b_max",
            "E_e": "alpha", "C_a": "e_prime", "b": "k", "p_n2": "a_w", "p_max": "b_w"}
DIVISIONS = tuple(DIVIDEND_SHIFTS)


@dataclass
class Operands:
    """Registers feeding divisions and products (Amaranth values; unused may be None).

    Attributes
    ----------
    a_min, b_max, w, e_prime : signed(32)
        Sorted curvatures (CURVATURE Q(32,20)), W (LOAD Q(32,8)), E' (E_PRIME Q(32,0)).
    alpha, radius, k, k2, e6, t1, t2, t3, wc3, a_w, b_w, p_n2 : unsigned
        The unsigned intermediates in their :mod:`.formats` formats, in the same
        order: ALPHA UQ(32,24), RADIUS UQ(33,23), K_INT UQ(29,24), K2 UQ(37,28),
        E6 UQ(27,25), T1 UQ(31,21), T2 UQ(39,26), T3 UQ(64,34), W C3 UQ(64,48),
        AXIS_W UQ(42,36) (a_w and b_w), PN2 UQ(47,28).
    n_ee : unsigned, optional
        ``hertz_form="exact"`` only: the EEX interpolation (units 2^-40), whose
        ``<< EE_DIVIDEND_SHIFT`` replaces the constant N5 as the E_e dividend.
    """

    a_min: object = None
    b_max: object = None
    w: object = None
    e_prime: object = None
    alpha: object = None
    radius: object = None
    k: object = None
    k2: object = None
    e6: object = None
    t1: object = None
    t2: object = None
    t3: object = None
    wc3: object = None
    a_w: object = None
    b_w: object = None
    p_n2: object = None
    n_ee: object = None


def division(name: str, ops: Operands):
    """``(dividend, divisor)`` unsigned expressions of division ``name``.

    The dividend is below 2^80 and the divisor below 2^DEN_BITS whenever the golden
    model runs (its asserts); signed registers enter as their bit patterns (a negative
    one only occurs on a flagged run, whose quotient is discarded).
    """
    reg, shift = DIVIDEND_SHIFTS[name]
    if reg is None:
        num = Const(1 << shift, DIVIDER_BITS)
    elif reg == "N5" and ops.n_ee is None:          # published form: E_e = C6 + N5/alpha
        num = Const(F.N5, DIVIDER_BITS)
    elif reg == "N5":                                # exact form: the EEX table's N(alpha)
        num = ops.n_ee.as_unsigned().shift_left(EE_DIVIDEND_SHIFT)
    else:
        num = getattr(ops, reg).as_unsigned().shift_left(shift)
    den_name = DIVISORS[name]
    if den_name == "a_min+b_max":
        den = ops.a_min.as_unsigned() + ops.b_max.as_unsigned()
    else:
        den = getattr(ops, den_name).as_unsigned()
    assert len(num) <= DIVIDER_BITS, (name, len(num))
    return num, den


def fits(value, fmt):
    """Amaranth expression: ``value`` lies in the code range of ``fmt``."""
    return (value >= fmt.min_code) & (value <= fmt.max_code)


def round_shift(value, n: int):
    """Round-half-up shift by a constant ``n >= 1`` (same as qformat.round_shift)."""
    return (value + (1 << (n - 1))).shift_right(n)


def round_shift_var(value, n_minus_1):
    """Round-half-up shift by a variable ``n = n_minus_1 + 1``:
    ``floor((floor(x / 2^(n-1)) + 1) / 2) = floor((x + 2^(n-1)) / 2^n)``."""
    return ((value >> n_minus_1) + 1).shift_right(1)


def sort_pair(a, b):
    """``(min, max)`` with the golden's tie rule (``(a, b) if a <= b else (b, a)``)."""
    le = a <= b
    return Mux(le, a, b), Mux(le, b, a)


def flags_word(bits: dict):
    """FLAG_BITS-wide word from ``{FLAG_x: 1-bit expression}``."""
    return Cat(*(bits.get(1 << i, Const(0, 1)) for i in range(FLAG_BITS)))


def envelope_flags(a_min, b_max, w, e_prime):
    """Flags of state SORT (:func:`.golden.envelope_flags`) for signed 32-bit codes."""
    ne = a_min <= 0
    return flags_word({
        F.FLAG_NOT_ELLIPTIC: ne,
        F.FLAG_CURV_RANGE: ~ne & ((a_min < F.CURV_MIN_CODE) | (b_max > F.CURV_MAX_CODE)),
        F.FLAG_LOAD_RANGE: (w < F.LOAD_MIN_CODE) | (w > F.LOAD_MAX_CODE),
        F.FLAG_E_PRIME_RANGE: (e_prime < F.E_PRIME_MIN_CODE)
        | (e_prime > F.E_PRIME_MAX_CODE)})


def lut_split(spec: LutSpec, arg):
    """``(addr, addr_next, r)`` of :func:`.luts.lut_interpolate`: segment index
    (8 bits), the next node's address, and the position inside the segment."""
    off = arg - spec.x0_code
    i = off[spec.tbits:spec.tbits + LUT_ADDR_BITS]
    return i, (i + 1)[:LUT_ADDR_BITS], off[:spec.tbits]


def lut_interpolate(spec: LutSpec, word0, word1, r):
    """``V_i T + r (V_{i+1} - V_i) + round_shift(r (T - r) Q_i, corr_shift)`` in units
    of ``2**-spec.out_frac`` (:func:`.luts.lut_interpolate`)."""
    v0, q0, v1 = word0[spec.qbits:], word0[:spec.qbits], word1[spec.qbits:]
    t_full = 1 << spec.tbits
    quad = round_shift(r * (t_full - r) * q0, spec.corr_shift)
    return v0.shift_left(spec.tbits) + r * (v1 - v0) + quad


def pow_to_k(interp):
    """K = round_shift(POW interpolation, out_frac - K_INT.frac), UQ(29,24)."""
    return round_shift(interp, POW_SPEC.out_frac - F.K_INT.frac)


#: The staged products (docs/spec.md sec. 6: "numerator products formed in stages"): operand
#: registers and the round-half-up shift applied to the exact product.
PRODUCTS = {"k2": (("k", "k"), 2 * F.K_INT.frac - F.K2.frac),
            "t1": (("k2", "e6"), F.K2.frac + F.E6.frac - F.T1.frac),
            "t2": (("t1", "radius"), F.T1.frac + F.RADIUS.frac - F.T2.frac),
            "t3": (("t2", "w"), 0),
            "wc3": (("C3", "w"), 0)}


def product_operands(step: str, ops: Operands):
    """Unsigned multiplier operands of product ``step`` (:data:`PRODUCTS`):
    K2 = rs(K K, 20), T1 = rs(K2 E6, 32), T2 = rs(T1 R, 18), T3 = T2 W, W C3."""
    def operand(name):
        if name == "C3":
            return Const(F.C3)
        if name == "w":                    # the signed LOAD register, W > 0 when used
            return ops.w[:_W_BITS]
        return getattr(ops, name)
    x, y = PRODUCTS[step][0]
    return operand(x), operand(y)


def product_result(step: str, prod):
    """Register value of product ``step`` from the exact product ``prod``."""
    shift = PRODUCTS[step][1]
    return round_shift(prod, shift) if shift else prod


def e6_from_quotient(q):
    """E6 = C6 + N5 // alpha, UQ(27,25)."""
    return F.C6 + q


# ---- cube root: range reduction and scaling -----------------------------------------
_CA_BITS = F.CA.bits


def _p_of_msb(msb: int) -> int:
    """Range-reduction exponent p for ``C_a`` with leading one at bit ``msb``."""
    return (msb - F.CA.frac) // 3


#: Right shift of ``C_a << _PAD`` that yields m, per leading-one position.
_PAD = max(0, -min(F.CA.frac + 3 * _p_of_msb(b) - F.M_RED.frac for b in range(_CA_BITS)))
_M_SHIFT = [F.CA.frac + 3 * _p_of_msb(b) - F.M_RED.frac + _PAD for b in range(_CA_BITS)]
#: Scaling shift minus one, ``CBRT_VAL.frac - AXIS_W.frac - p - 1``, per position.
_S1 = [F.CBRT_VAL.frac - F.AXIS_W.frac - _p_of_msb(b) - 1 for b in range(_CA_BITS)]
SCALE_BITS = max(_S1).bit_length()
assert min(_S1) >= 0


def range_reduce(m: Module, c_a, *, name: str):
    """Leading-one detection and range reduction ``C_a = m 8^p`` (combinational).

    Returns ``(m_red, s1)``: the mantissa m (UQ(32,29), in [1, 8) when ``C_a > 0``)
    and the scaling shift minus one (``9 - p``) for :func:`scale_cbrt`.
    """
    msb = Signal(range(_CA_BITS), name=f"{name}_msb")
    for b in range(_CA_BITS):                      # later statements win: highest one
        with m.If(c_a[b]):
            m.d.comb += msb.eq(b)
    sh = Signal(range(max(_M_SHIFT) + 1), name=f"{name}_msh")
    s1 = Signal(SCALE_BITS, name=f"{name}_s1")
    with m.Switch(msb):
        for b in range(_CA_BITS):
            with m.Case(b):
                m.d.comb += [sh.eq(_M_SHIFT[b]), s1.eq(_S1[b])]
    m_red = Signal(F.M_RED.bits, name=f"{name}_m")
    m.d.comb += m_red.eq((Cat(Const(0, _PAD), c_a) >> sh)[:F.M_RED.bits])
    return m_red, s1


def scale_cbrt(interp, s1):
    """a_w = round_shift(CBRT interpolation, 10 - p), AXIS_W UQ(42,36)."""
    return round_shift_var(interp, s1)


# ---- outputs --------------------------------------------------------------------------
def finalize(flags, ovf, *, a_w, b_w, k, r_x, r_y, alpha, p_max_q):
    """Output values and final flags (the last step of :func:`.golden.hertz_golden`).

    Parameters
    ----------
    flags : Value
        Flags recorded so far (FLAG_BITS).
    ovf : Value
        1 if R_x or R_y (already rounded) did not fit CURVATURE.
    a_w, b_w, k, r_x, r_y, alpha : Value
        Registers (r_x, r_y: the rounded quotients).
    p_max_q : Value
        The p_max quotient (before its rounding shift), full width.

    Returns
    -------
    (flags_out, outs)
        ``outs`` maps ``a, b, p_max, k, R_x, R_y, alpha`` to their output values (0 on
        a flagged run): a, b SEMI_AXIS Q(32,20); p_max PMAX Q(32,8); k K_OUT Q(32,20);
        R_x, R_y CURVATURE Q(32,20); alpha ALPHA UQ(32,24).
    """
    vals = {"a": round_shift(a_w, F.AXIS_W.frac - SEMI_AXIS.frac),
            "b": round_shift(b_w, F.AXIS_W.frac - SEMI_AXIS.frac),
            "p_max": round_shift(p_max_q, 1),
            "k": round_shift(k, F.K_INT.frac - F.K_OUT.frac)}
    fmts = {"a": SEMI_AXIS, "b": SEMI_AXIS, "p_max": PMAX, "k": F.K_OUT}
    ok = ~ovf
    for key, fmt in fmts.items():
        ok = ok & fits(vals[key], fmt)
    vals.update({"R_x": r_x, "R_y": r_y, "alpha": alpha})
    flags_out = Mux(flags != 0, flags,
                    Mux(ok, 0, Const(F.FLAG_OVERFLOW, FLAG_BITS)))
    bad = flags_out != 0
    return flags_out, {key: Mux(bad, 0, v) for key, v in vals.items()}

