"""Sequential non-restoring integer square root for :class:`.rtl.FitCore`.

The Li-Chu non-restoring isqrt [1]_ of :func:`.golden.isqrt_nonrestoring`, retiring
``bits_per_cycle`` root bits per clock edge instead of all of them in one cycle. Each
retired bit is one shift-and-add step on the partial remainder ``R`` (a conditional
add/subtract of ``4Q + 1`` or ``4Q + 3``), so the longest path of an edge is
``bits_per_cycle`` such adders in series (2 x 34 bits for the fit core) instead of the
32 of the unrolled form. The steps are those of the golden model in the same order,
so the root *and* every intermediate remainder equal the golden ones; the result is
``floor(sqrt(d))`` (the integer square root is unique).

Registers (fit core sizes: 64-bit radicand, 32-bit root, 2 bits per cycle):

=========  ==========================  ==============================================
register   format                      meaning
=========  ==========================  ==============================================
``dsh``    UQ(64,0)                    radicand, shifted left 2k bits per edge (the
                                       next bit pairs at the top)
``rem``    ISQRT_REM_FMT Q(34,0)       partial remainder R, ``|R| <= 2Q + 1``
``root``   ROOT_FMT UQ(32,0) (as int)  root bits retired so far (LSB = newest); the
                                       full root after the last step
``count``  range(17)                   steps left; ``busy`` = ``count != 0``
=========  ==========================  ==============================================

Timing: the edge that samples ``start`` loads ``d`` (``rem`` = ``root`` = 0); each
of the next ``cycles`` = ``root_bits / bits_per_cycle`` edges retires
``bits_per_cycle`` bits. ``root`` is valid (and held) from the edge after which
``busy`` reads 0, until the next ``start``. A ``start`` while busy restarts.

References
----------
.. [1] Y. Li and W. Chu, "A new non-restoring square root algorithm and its VLSI
   implementations", Proc. IEEE ICCD, 538-544, 1996.
"""

from __future__ import annotations

from amaranth import Cat, Const, Module, Mux, Signal, signed, unsigned
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from gearcontact.preview.fit.golden import ISQRT_REM_FMT, ROOT_FMT
from gearcontact.validation import InputRangeError

__all__ = ["IsqrtSequential", "isqrt_steps"]


def isqrt_steps(rem, root, pairs):
    """Amaranth expressions of consecutive Li-Chu steps (combinational).

    Parameters
    ----------
    rem : Value
        Signed partial remainder R (its width is kept: the golden model proves the
        remainder fits it).
    root : Value
        Unsigned root bits so far (its width is kept; the top bits are still 0).
    pairs : sequence of Value
        2-bit radicand digits, most significant first, one per step.

    Returns
    -------
    (rem, root) : tuple of Value
        After ``len(pairs)`` steps: ``R = 4R + pair - (4Q + 1)`` if ``R >= 0`` else
        ``R = 4R + pair + (4Q + 3)``, then ``Q = 2Q + (R >= 0)``.
    """
    width, root_bits = len(rem), len(root)
    for pair in pairs:
        shifted = Cat(pair, rem).as_signed()                     # 4R + pair
        nxt = Mux(rem[-1], shifted + Cat(Const(3, 2), root),    # R < 0: + (4Q + 3)
                  shifted - Cat(Const(1, 2), root))              # R >= 0: - (4Q + 1)
        rem = nxt[:width].as_signed()                            # exact: |R| <= 2Q + 1
        root = Cat(~rem[-1], root)[:root_bits]
    return rem, root


class IsqrtSequential(wiring.Component):
    """Integer square root ``floor(sqrt(d))``, ``bits_per_cycle`` root bits per edge.

    Parameters
    ----------
    root_bits : int, keyword-only
        Root width (radicand ``2 root_bits`` bits); default ROOT_FMT.bits = 32.
    bits_per_cycle : int, keyword-only
        Root bits retired per edge (adders in series); must divide ``root_bits``.

    Notes
    -----
    Ports: ``start`` In(1); ``d`` In(unsigned(2 root_bits)) radicand (integer code,
    sampled on the ``start`` edge); ``root`` Out(unsigned(root_bits)); ``busy``
    Out(1). The remainder register is ``root_bits + 2`` bits signed
    (``ISQRT_REM_FMT`` for the fit core). Latency: :attr:`cycles` edges after the
    ``start`` edge.
    """

    def __init__(self, *, root_bits: int = ROOT_FMT.bits, bits_per_cycle: int = 2):
        if root_bits < 1 or bits_per_cycle < 1 or root_bits % bits_per_cycle:
            self._MustUse__silence = True    # never elaborated: no unused warning
            raise InputRangeError("bits_per_cycle", bits_per_cycle,
                                  f"a divisor of root_bits = {root_bits}")
        self.root_bits = root_bits
        self.bits_per_cycle = bits_per_cycle
        #: Edges after the ``start`` edge until ``root`` is valid.
        self.cycles = root_bits // bits_per_cycle
        super().__init__({"start": In(1), "d": In(unsigned(2 * root_bits)),
                          "root": Out(unsigned(root_bits)), "busy": Out(1)})

    def elaborate(self, platform):
        m = Module()
        n, k = self.root_bits, self.bits_per_cycle
        rem_bits = n + 2
        if n == ROOT_FMT.bits:
            assert rem_bits == ISQRT_REM_FMT.bits
        dsh = Signal(unsigned(2 * n))
        rem = Signal(signed(rem_bits))
        count = Signal(range(self.cycles + 1))
        pairs = [dsh[2 * n - 2 * (s + 1):2 * n - 2 * s] for s in range(k)]
        rem_next, root_next = isqrt_steps(rem, self.root, pairs)
        m.d.comb += self.busy.eq(count != 0)
        with m.If(self.start):
            m.d.sync += [dsh.eq(self.d), rem.eq(0), self.root.eq(0),
                         count.eq(self.cycles)]
        with m.Elif(count != 0):
            m.d.sync += [dsh.eq(dsh << (2 * k)), rem.eq(rem_next),
                         self.root.eq(root_next), count.eq(count - 1)]
        return m
