"""Amaranth restoring dividers of stage D: the shared bit-serial unit and the array twin.

Both realize the recurrence of :func:`.divider.restoring_divide` (one quotient bit per
step, MSB first: shift the next dividend bit into the partial remainder, trial-subtract
the divisor, keep the difference when it is non-negative), built from one step
function, :func:`restoring_step`, so the serialized core and the combinational core
cannot drift apart:

* :class:`SerialDivider` — the shared 80-bit divider of the serialized core: an 80-bit
  dividend/quotient shift register (dividend bits leave at the top while quotient bits
  enter at the bottom), a divisor register and a partial-remainder register, one
  iteration per cycle; the FSM of :mod:`.rtl` drives its three handshake strobes
  (``load`` dividend, ``start`` divisor + clear, then 80 ``step`` cycles; the quotient
  is written back on the cycle after the last step: ``DIVISION_CYCLES = 83``).
* :func:`array_divide` — the unrolled (combinational) array divider of the C+D
  combinational core: one row per dividend bit.

The divisor and remainder registers are :data:`DEN_BITS` wide (the widest stage-D
divisor, the 42-bit semi-axes), not 80: the remainder of a restoring division is always
below the divisor, so nothing is lost, and the quotient is ``floor(N / D)`` for every
``0 <= N < 2**80``, ``1 <= D < 2**DEN_BITS``. A zero divisor makes every trial
subtraction succeed (quotient all ones), as in the model; the caller flags it.
"""

from __future__ import annotations

from amaranth import Cat, Module, Mux, Signal, unsigned
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from ...contract.qformat import CURVATURE
from . import formats as F
from .divider import DIVIDER_BITS

__all__ = ["DEN_BITS", "SerialDivider", "array_divide", "restoring_step"]

#: Divisor/remainder width: the widest stage-D divisor (a_w, b_w: AXIS_W, 42 bits;
#: the others are A_min, B_max (32), A_min + B_max (33), alpha (32), E' (32), K (29)).
DEN_BITS = max(F.AXIS_W.bits, CURVATURE.bits + 1, F.ALPHA.bits, F.E_PRIME.bits,
               F.K_INT.bits)


def restoring_step(rem, bit, den):
    """One restoring iteration (Amaranth expressions).

    Parameters
    ----------
    rem : Value
        Partial remainder, unsigned, ``rem < den``.
    bit : Value
        Next dividend bit (MSB first), 1 bit.
    den : Value
        Divisor, unsigned.

    Returns
    -------
    (new_rem, qbit)
        ``new_rem = t - den`` if ``t = 2 rem + bit >= den`` else ``t`` (it is below
        ``den`` and fits ``len(den)`` bits when ``den > 0``); ``qbit`` the quotient bit.
    """
    t = Cat(bit, rem)                  # 2 rem + bit, unsigned
    diff = t - den                     # signed, exact
    qbit = diff >= 0
    return Mux(qbit, diff, t), qbit


class SerialDivider(wiring.Component):
    """Shared bit-serial restoring divider (80-bit dividend/quotient).

    Ports (synchronous to ``sync``; strobes are mutually exclusive, ``load`` wins):

    ``load`` In(1): ``quotient`` register <= ``num`` (the dividend, unsigned(80));
    ``start`` In(1): divisor register <= ``den`` (unsigned(:data:`DEN_BITS`)),
    remainder <= 0; ``step`` In(1): one iteration; ``quotient`` Out(unsigned(80)): the
    shift register, ``floor(num / den)`` after 80 steps; ``remainder``
    Out(unsigned(DEN_BITS)): ``num mod den`` after 80 steps. All values are plain
    unsigned integers (the caller's Q formats pass through: the quotient has the
    dividend's minus the divisor's fraction bits).
    """

    def __init__(self):
        super().__init__({"load": In(1), "num": In(unsigned(DIVIDER_BITS)),
                          "start": In(1), "den": In(unsigned(DEN_BITS)), "step": In(1),
                          "quotient": Out(unsigned(DIVIDER_BITS)),
                          "remainder": Out(unsigned(DEN_BITS))})

    def elaborate(self, platform):
        m = Module()
        nq = self.quotient                 # dividend bits out at the top, quotient in
        rem = self.remainder
        den = Signal(DEN_BITS)
        new_rem, qbit = restoring_step(rem, nq[-1], den)
        with m.If(self.load):
            m.d.sync += nq.eq(self.num)
        with m.Elif(self.start):
            m.d.sync += [den.eq(self.den), rem.eq(0)]
        with m.Elif(self.step):
            m.d.sync += [nq.eq(Cat(qbit, nq[:-1])), rem.eq(new_rem)]
        return m


def array_divide(m: Module, num, den, *, name: str):
    """Unrolled restoring array divider: ``floor(num / den)`` (combinational).

    One row of :func:`restoring_step` per dividend bit (``len(num)`` rows, each a
    ``len(den) + 1``-bit subtractor); every row's remainder is a named comb signal.

    Parameters
    ----------
    m : Module
        Parent module; the rows go into a submodule named ``name``.
    num, den : Value
        Unsigned dividend and divisor (any widths).
    name : str
        Signal-name prefix.

    Returns
    -------
    Signal
        ``unsigned(len(num))`` quotient (all ones when ``den == 0``, as the model).
    """
    nbits, dbits = len(num), len(den)
    m.submodules[name] = sub = Module()   # own block: simulated only when its inputs move
    rem = Signal(dbits, name=f"{name}_r{nbits}")
    qbits = []
    for i in range(nbits - 1, -1, -1):
        new_rem, qbit = restoring_step(rem, num[i], den)
        nxt = Signal(dbits, name=f"{name}_r{i}")
        sub.d.comb += nxt.eq(new_rem)
        qbits.append(qbit)
        rem = nxt
    q = Signal(nbits, name=f"{name}_q")
    sub.d.comb += q.eq(Cat(*reversed(qbits)))
    return q
