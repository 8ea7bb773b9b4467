"""Split partial products for :class:`.rtl.GapCore`: exact, and fewer DSP48E1 slices.

A DSP48E1 multiplies a 25-bit signed A port by an 18-bit signed B port. Yosys
(``synth_xilinx``, ``mul2dsp``) tiles a wider ``$mul`` into 25 x 18 pieces without
using the fact that our operands are narrower than a multiple of those sizes: the gap
core's stage-B products take 4 slices each (gamma n: 27 x 21 b, e^2: 27 x 27 b). Cutting
one operand at bit :data:`LO_BITS` = 17 by hand, into a signed high part and an
*unsigned* 17-bit low part (which zero-extends to 18 signed bits, the B port), leaves
partial products that fit one slice each:

* ``split_mul(a, b)`` = ``(a_hi b) << 17 + a_lo b`` -- 2 slices when ``b`` fits A (25 b);
* ``split_square(e)`` = ``a_hi^2 << 34 + (a_hi a_lo) << 18 + a_lo^2`` -- 3 slices,
  the cross term counted once (doubled by the shift).

Both are integer identities of two's complement (``a = a_hi 2^17 + a_lo`` with
``a_hi = a >> 17`` arithmetic, ``a_lo = a mod 2^17``), and every Amaranth expression
below is wide enough to hold its value, so the results equal ``a * b`` and ``e * e``
bit for bit at any width the caller truncates to. No register is added: the schedule
is unchanged; the sum of the partial products lands in the slice's post-adder (P = A B
+ C or the 17-bit-shifted PCIN cascade) or in a fabric adder.
"""

from __future__ import annotations

from amaranth.hdl import Value

__all__ = ["LO_BITS", "split_mul", "split_square"]

#: Width of the unsigned low part: 17 bits zero-extend to the 18-bit signed B port.
LO_BITS = 17


def _halves(a: Value, lo_bits: int):
    a = Value.cast(a)
    if len(a) <= lo_bits:
        raise ValueError(f"operand of {len(a)} bits needs no split at {lo_bits}")
    # hi keeps the sign (arithmetic a >> lo_bits); lo is a plain unsigned slice
    return a[lo_bits:].as_signed(), a[:lo_bits]


def split_mul(a: Value, b: Value, *, lo_bits: int = LO_BITS) -> Value:
    """``a * b`` for signed ``a`` as two partial products split at ``lo_bits``.

    Parameters
    ----------
    a : Value
        Signed operand, wider than ``lo_bits`` (gap core: gamma, Q(27,16) mm, the
        low 27 bits of Q(32,16) since ``|gamma| < 2^26``).
    b : Value
        Signed operand (gap core: a normal component, Q(21,19)); at most 25 bits so
        that each partial product fits one DSP48E1 (b on A, the part of ``a`` on B).
    lo_bits : int, keyword-only
        Split position (default 17: the low part fills the 18-bit B port unsigned).

    Returns
    -------
    Value
        Signed, ``len(a) + len(b) + 1`` bits or wider; equals ``a * b`` exactly
        (fraction bits: those of ``a`` plus those of ``b``).
    """
    hi, lo = _halves(a, lo_bits)
    return ((hi * b) << lo_bits) + lo * b


def split_square(a: Value, *, lo_bits: int = LO_BITS) -> Value:
    """``a * a`` for signed ``a`` as three partial products split at ``lo_bits``.

    Parameters
    ----------
    a : Value
        Signed operand of at most ``lo_bits + 18`` bits (gap core: the residual e_k,
        Q(27,16) mm) so that the high part fits the B port.
    lo_bits : int, keyword-only
        Split position (default 17).

    Returns
    -------
    Value
        Signed (value >= 0), ``2 len(a) + 2`` bits or wider; equals ``a * a`` exactly
        (twice the fraction bits of ``a``).
    """
    hi, lo = _halves(a, lo_bits)
    return ((hi * hi) << (2 * lo_bits)) + ((hi * lo) << (lo_bits + 1)) + lo * lo
