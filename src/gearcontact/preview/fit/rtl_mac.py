"""Two-tap-per-edge pipelined MAC of the fit core (gap RAM, baked ROM, six sums).

:class:`PairMac` evaluates ``acc_j = sum_i M_ji g_i`` (j = 0..5, i = 0..48) exactly,
two taps per clock edge, with one DSP-sized multiply and one adder per path:

* the gap RAM is two banks of 25 x 32 b (even taps ``2p``, odd taps ``2p + 1``), each
  one write port and one *synchronous* read port, so a pair ``p`` is read in one edge;
* the ROM is twelve 25-word banks (coefficient x even/odd) with synchronous reads at
  the same pair address (the odd bank's word 24 is 0: tap 49 does not exist, so the
  unwritten RAM word it meets adds nothing). ROM words hold the WEIGHT Q(32,20) codes
  sign-extended only to the widest code of the baked ROM (``weight_bits``, 24 b for
  the degree-6 hardware ROM) -- the same values as :attr:`.pinv.BakedPinv.rom_words`;
* each product ``g * M`` is cut into partial products that each fit one DSP48E1
  (25 x 18 signed): ``g = g_hi 2^17 + g_lo`` with ``g_lo`` the *unsigned* low 17 bits
  (fits the 18-bit B port) and ``g_hi`` the arithmetic high part; the weight is cut
  the same way at bit 24 only if it is wider than 25 bits (never for the hardware
  ROM). Partial products are registered (the DSP's M register);
* every partial product has its own accumulator per bank (``P = P + M``, the DSP's
  accumulate mode; at most 41 + 5 = 46 bits for the hardware ROM, inside the 48-bit P);
* ``fold`` adds the even and odd bank accumulators, ``combine`` adds the shifted
  folded parts into the exact Q(72,41) sums. Two's complement partial sums are exact
  identities, and every register is wide enough for its bound, so ``acc`` equals the
  golden model's exact sum bit for bit.

Timing (edges relative to the read edge of pair 0, which is the fit core's ``go``
edge): pair ``p`` is latched from RAM/ROM on edge ``1 + p`` (address presented in the
cycle before), multiplied into the M registers on edge ``2 + p`` and accumulated on
edge ``3 + p`` (``acc_en``); ``clear`` zeroes the accumulators on its edge.

========  ======================  =================================================
register  format                  meaning
========  ======================  =================================================
g_e, g_o  STENCIL_GAP Q(32,21)    RAM read registers, taps 2p, 2p+1
w_*       WEIGHT Q(w,20)          ROM read registers (w = ``weight_bits``)
m_*       Q(g'+w', 41 - shift)    partial products (g', w' = part widths)
a_*       Q(m + 5, 41 - shift)    bank accumulators (25 terms: 5 guard bits; one
                                  more over an unsigned product, split weights only)
f_*       Q(m + 6, 41 - shift)    folded (even + odd) accumulators
acc_j     ACC Q(72,41)            exact ``sum_i M_ji g_i`` (output ports ``acc0..5``)
========  ======================  =================================================
"""

from __future__ import annotations

from amaranth import Module, Signal, signed
from amaranth.lib import wiring
from amaranth.lib.memory import Memory
from amaranth.lib.wiring import In, Out

from gearcontact.preview.fit.pinv import ACC, N_COEFFS, N_TAPS, WEIGHT, BakedPinv, baked_pinv
from gearcontact.contract.qformat import STENCIL_GAP

__all__ = ["G_LO_BITS", "N_PAIRS", "W_LO_BITS", "PairMac", "weight_bits"]

#: Tap pairs read per run: taps (2p, 2p + 1), p = 0..24 (tap 49 is a zero weight).
N_PAIRS = (N_TAPS + 1) // 2
#: Unsigned low part of the gap operand: zero-extends to the DSP48E1's 18-bit B port.
G_LO_BITS = 17
#: Unsigned low part of a weight wider than the 25-bit A port (not needed for 0.5 mm).
W_LO_BITS = 24
_DSP_A_BITS = 25
_GUARD_BITS = (N_PAIRS - 1).bit_length()     # 25 accumulated terms per bank


def weight_bits(rom: BakedPinv) -> int:
    """Signed width of the widest weight code of ``rom`` (<= WEIGHT.bits)."""
    widest = max(max(w.bit_length() for w in row) for row in rom.weight_codes)
    bits = widest + 1
    assert bits <= WEIGHT.bits, "BakedPinv weights always fit WEIGHT Q(32,20)"
    return bits


def _parts(value, lo_bits: int, split: bool):
    """``[(shift, part)]`` with ``value = sum(part << shift)`` (exact)."""
    if not split:
        return [(0, value)]
    return [(0, value[:lo_bits]), (lo_bits, value[lo_bits:].as_signed())]


class PairMac(wiring.Component):
    """Gap RAM + baked ROM + six exact MACs, two taps per edge (see module doc).

    Parameters
    ----------
    rom : BakedPinv, keyword-only, optional
        Pseudo-inverse ROM (default :func:`.pinv.baked_pinv`).

    Notes
    -----
    Ports (all synchronous to ``sync``): ``wr_en`` In(1), ``wr_addr``
    In(range(49)), ``wr_data`` In(signed(32)) STENCIL_GAP Q(32,21) -- write one tap;
    ``raddr`` In(range(25)) pair to latch on the next edge; ``clear`` In(1),
    ``acc_en`` In(1), ``fold`` In(1), ``combine`` In(1) -- the edges of those steps;
    ``acc0``..``acc5`` Out(signed(72)) ACC Q(72,41), valid after the ``combine``
    edge and held until the next ``combine``.
    """

    def __init__(self, *, rom: BakedPinv | None = None):
        self._rom = baked_pinv() if rom is None else rom
        self.weight_bits = weight_bits(self._rom)
        super().__init__({
            "wr_en": In(1), "wr_addr": In(range(N_TAPS)),
            "wr_data": In(signed(STENCIL_GAP.bits)),
            "raddr": In(range(N_PAIRS)), "clear": In(1), "acc_en": In(1), "fold": In(1),
            "combine": In(1),
            **{f"acc{j}": Out(signed(ACC.bits)) for j in range(N_COEFFS)}})

    @property
    def sums(self) -> list:
        """The six output ports ``[acc0, ..., acc5]``."""
        return [getattr(self, f"acc{j}") for j in range(N_COEFFS)]

    def _bank_words(self, j: int, bank: int) -> list:
        row = self._rom.weight_codes[j]
        return [row[2 * p + bank] if 2 * p + bank < N_TAPS else 0 for p in range(N_PAIRS)]

    def elaborate(self, platform):
        m = Module()
        wb = self.weight_bits
        g_regs = []
        for bank, name in enumerate(("even", "odd")):
            ram = Memory(shape=signed(STENCIL_GAP.bits), depth=N_PAIRS, init=[])
            m.submodules[f"gap_{name}"] = ram
            wp = ram.write_port()
            rd = ram.read_port()             # synchronous: the RAM read register
            m.d.comb += [wp.addr.eq(self.wr_addr >> 1), wp.data.eq(self.wr_data),
                         wp.en.eq(self.wr_en & (self.wr_addr[0] == bank)),
                         rd.addr.eq(self.raddr)]
            g_regs.append(rd.data)

        for j, acc_out in enumerate(self.sums):
            folded = {}                      # shift -> [bank accumulators]
            for bank, g in enumerate(g_regs):
                rom = Memory(shape=signed(wb), depth=N_PAIRS, init=self._bank_words(j, bank))
                m.submodules[f"rom{j}_{'eo'[bank]}"] = rom
                rd = rom.read_port()         # synchronous ROM read (BRAM/DSP-friendly)
                m.d.comb += rd.addr.eq(self.raddr)
                for gs, gp in _parts(g, G_LO_BITS, True):
                    for ws, wp_ in _parts(rd.data, W_LO_BITS, wb > _DSP_A_BITS):
                        tag = f"{j}{'eo'[bank]}_{gs}_{ws}"
                        prod = gp * wp_
                        mreg = Signal(prod.shape(), name=f"m{tag}")
                        # 25 terms: guard bits, plus a sign bit over an unsigned
                        # product (low gap part x low weight part of a split weight)
                        acc = Signal(signed(len(prod) + _GUARD_BITS
                                            + (not prod.shape().signed)), name=f"a{tag}")
                        m.d.sync += mreg.eq(prod)
                        with m.If(self.clear):
                            m.d.sync += acc.eq(0)
                        with m.Elif(self.acc_en):
                            m.d.sync += acc.eq(acc + mreg)
                        folded.setdefault(gs + ws, []).append(acc)
            total = 0
            for shift, (a_e, a_o) in sorted(folded.items()):
                f = Signal(signed(max(len(a_e), len(a_o)) + 1), name=f"f{j}_{shift}")
                with m.If(self.fold):
                    m.d.sync += f.eq(a_e + a_o)
                total = total + (f << shift)
            with m.If(self.combine):
                m.d.sync += acc_out.eq(total)    # exact: |sum| < 2^71 (pinv)
        return m
