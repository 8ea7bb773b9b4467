"""Amaranth 0.5 RTL of the stage-C fit core, bit- and cycle-exact with :mod:`.golden`.

Structure (SPEC section 6, Algorithm 2; section 7 tri_core write port)::

    wr_rst / wr_en + wr_data ──► gap RAM 49 x 32 (GAP Q(32,16))
                                      │ tap k (async read)
    6 x ROM 49 x 40 (Q(40,20)) ───────┤
                                      ▼
              6 MACs  acc_j += M_jk * g_k   (ACC Q(72,36), one tap per cycle)
                                      ▼
    latch 1: c_j = round_shift(acc_j, 16) (Q(32,20)), h = c3 + c5, e = c3 - c5
    latch 2: d = e^2 + c4^2                (Q(64,40))
    latch 3: r = isqrt(d) (32-stage unrolled non-restoring, shift-and-add only),
             A- = round_shift(h + r, 1), B- = round_shift(h - r, 1), flags, done

Timing: ``FIT_CYCLES = 52`` edges from the edge that samples ``go`` (which already
multiplies tap 0) to the edge after which ``done`` reads 1, independent of the data.

Control behaviour
-----------------
* ``go`` is sampled only while idle; a ``go`` while ``busy`` is ignored (the running
  fit is neither restarted nor delayed). Accepting ``go`` clears ``done``; ``done``
  then stays 1 from the end of the run until the next accepted ``go``, and
  ``done_pulse`` is 1 for exactly the first cycle of it (the start strobe for a
  following stage D in the C->D chain: D's first compute edge is edge 53, so its 2
  capture/sort cycles are absorbed, see :mod:`.golden`). The output
  registers (``c0``..``c5``, ``a_minus``, ``b_minus``, ``flags``) change only on the
  ``done`` edge and hold until the next run completes.
* Gap writes: ``wr_rst`` sets the write pointer to 0 and clears ``wr_dropped``;
  ``wr_en`` writes ``wr_data`` at the pointer and increments it (``wr_count`` = number
  of samples written since ``wr_rst``). A write together with ``wr_rst`` lands at
  address 0. A write is *dropped* -- and the sticky ``wr_dropped`` set -- when the core
  is busy, when ``go`` is asserted in the same cycle, or when 49 samples were already
  written; the RAM never changes under a running MAC and the pointer never wraps.
* Synchronous reset (the ``sync`` domain's reset) returns the core to idle at any
  time: busy, done, accumulators, outputs, flags and the write pointer go to 0; the
  gap RAM contents are kept, so a new ``go`` re-fits the stencil already written.

All numeric ports carry codes: ``wr_data`` GAP Q(32,16) mm; ``c0`` Q(32,20) mm,
``c1``/``c2`` Q(32,20) (slopes), ``c3``..``c5``, ``a_minus``, ``b_minus`` CURVATURE
Q(32,20) 1/mm; ``flags`` the ``FLAG_*`` bitmask of :mod:`.golden`.
"""

from __future__ import annotations

from amaranth import Cat, Const, Module, Mux, Signal, signed, unsigned
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.memory import Memory
from amaranth.lib.wiring import In, Out

from gearcontact.preview.fit.golden import (D_FMT, FIT_CYCLES, FLAG_BITS,
                                            FLAG_COEFF_OVERFLOW, FLAG_CURV_OVERFLOW,
                                            FLAG_D_OVERFLOW, FLAG_NOT_ELLIPTIC,
                                            ISQRT_REM_FMT, ROOT_FMT, SUM_FMT, GoldenFit,
                                            check_gap_codes)
from gearcontact.preview.fit.pinv import (ACC, COEFF, N_COEFFS, N_TAPS, ROM_WORD_BITS,
                                          BakedPinv, baked_pinv)
from gearcontact.preview.qformat import CURVATURE, GAP
from gearcontact.preview.simulation import (read_record, run_testbench, run_to_done,
                                            write_stencil)

__all__ = ["COEFF_PORTS", "FIT_OUTPUT_PORTS", "FitCore", "convert_verilog",
           "fit_front_end_ports", "read_fit_codes", "simulate_fit_core"]

#: The coefficient output ports ``c0``..``c5``, in order.
COEFF_PORTS = tuple(f"c{j}" for j in range(N_COEFFS))
#: Output ports in :class:`.golden.GoldenFit` field order (``field -> port(s)``).
FIT_OUTPUT_PORTS = {"c_codes": COEFF_PORTS, "a_minus_code": "a_minus",
                    "b_minus_code": "b_minus", "flags": "flags"}

_COEFF_SHIFT = ACC.frac - COEFF.frac
# The flags port is Cat(cov, dov, kov, not_elliptic): it relies on this bit order.
assert (FLAG_COEFF_OVERFLOW, FLAG_D_OVERFLOW, FLAG_CURV_OVERFLOW, FLAG_NOT_ELLIPTIC) == \
    (1, 2, 4, 8)


def _fits(value, fmt):
    """Amaranth expression: ``value`` lies in the code range of ``fmt``."""
    return (value >= fmt.min_code) & (value <= fmt.max_code)


def _round_shift(value, n: int):
    """Amaranth round-half-up arithmetic shift (same as qformat.round_shift)."""
    return (value + (1 << (n - 1))) >> n


def fit_front_end_ports() -> tuple[dict, dict, dict]:
    """Port declarations of the fit front end, shared with the cores built on it.

    Returns
    -------
    (write, status, coeffs) : tuple of dict
        ``wr_rst``, ``wr_en``, ``wr_data`` (GAP Q(32,16)) inputs; ``busy``, ``done``,
        ``done_pulse``, ``wr_count``, ``wr_dropped`` outputs; ``c0``..``c5`` (COEFF
        Q(32,20)) outputs -- each in port order, as ``name -> In/Out`` dicts.
    """
    write = {"wr_rst": In(1), "wr_en": In(1), "wr_data": In(signed(GAP.bits))}
    status = {"busy": Out(1), "done": Out(1), "done_pulse": Out(1),
              "wr_count": Out(range(N_TAPS + 1)), "wr_dropped": Out(1)}
    return write, status, {p: Out(signed(COEFF.bits)) for p in COEFF_PORTS}


class FitCore(wiring.Component):
    """Stage-C curvature-fit core (49-tap baked pseudo-inverse MAC + 2x2 eigen).

    Parameters
    ----------
    rom : BakedPinv, keyword-only, optional
        Pseudo-inverse ROM to bake (default :func:`.pinv.baked_pinv`, the 0.5 mm
        hardware stencil); the golden model must be run with the same ROM.

    Notes
    -----
    Ports (all synchronous to ``sync``):

    ``wr_rst`` In(1), ``wr_en`` In(1), ``wr_data`` In(signed(32)) GAP Q(32,16);
    ``go`` In(1); ``busy`` Out(1), ``done`` Out(1), ``done_pulse`` Out(1);
    ``wr_count`` Out(range(50)),
    ``wr_dropped`` Out(1); ``c0``..``c5``, ``a_minus``, ``b_minus`` Out(signed(32))
    Q(32,20); ``flags`` Out(4).
    """

    def __init__(self, *, rom: BakedPinv | None = None):
        self._rom = baked_pinv() if rom is None else rom
        write, status, coeffs = fit_front_end_ports()
        super().__init__({**write, "go": In(1), **status,
                          "a_minus": Out(signed(CURVATURE.bits)),
                          "b_minus": Out(signed(CURVATURE.bits)), "flags": Out(FLAG_BITS),
                          **coeffs})

    @property
    def coeffs(self) -> list:
        """The six coefficient output ports ``[c0, ..., c5]``."""
        return [getattr(self, p) for p in COEFF_PORTS]

    def _isqrt(self, m: Module, d):
        """32-stage unrolled Li-Chu non-restoring isqrt of the 64-bit ``d`` (comb)."""
        rem = Const(0, signed(ISQRT_REM_FMT.bits))
        q = Const(0, 1)
        for i in range(ROOT_FMT.bits - 1, -1, -1):
            shifted = Cat(d[2 * i:2 * i + 2], rem).as_signed()     # 4 R + pair
            nxt = Signal(signed(ISQRT_REM_FMT.bits), name=f"isqrt_rem{i}")
            m.d.comb += nxt.eq(Mux(rem >= 0, shifted - Cat(Const(1, 2), q),
                                   shifted + Cat(Const(3, 2), q)))
            qn = Signal(ROOT_FMT.bits - i, name=f"isqrt_q{i}")
            m.d.comb += qn.eq(Cat(~nxt[-1], q))
            rem, q = nxt, qn
        return q

    def elaborate(self, platform):
        m = Module()

        # ---- gap RAM (49 x 32) and its write port -------------------------------
        gap_ram = Memory(shape=signed(GAP.bits), depth=N_TAPS, init=[])
        m.submodules.gap_ram = gap_ram
        wp = gap_ram.write_port()
        gap_rd = gap_ram.read_port(domain="comb")

        busy = Signal()
        ptr = Signal(range(N_TAPS + 1))
        accept = self.wr_en & ~busy & ~self.go & (self.wr_rst | (ptr < N_TAPS))
        dropped_now = self.wr_en & ~accept
        m.d.comb += [wp.addr.eq(Mux(self.wr_rst, 0, ptr)), wp.data.eq(self.wr_data),
                     wp.en.eq(accept), self.wr_count.eq(ptr), self.busy.eq(busy)]
        with m.If(self.wr_rst):
            m.d.sync += [ptr.eq(accept), self.wr_dropped.eq(dropped_now)]
        with m.Else():
            with m.If(accept):
                m.d.sync += ptr.eq(ptr + 1)
            with m.If(dropped_now):
                m.d.sync += self.wr_dropped.eq(1)

        # ---- baked ROMs and the six MACs ---------------------------------------
        tap = Signal(range(N_TAPS))
        m.d.comb += gap_rd.addr.eq(Mux(busy, tap, 0))
        accs = [Signal(signed(ACC.bits), name=f"acc{j}") for j in range(N_COEFFS)]
        prods = []
        for j in range(N_COEFFS):
            rom = Memory(shape=unsigned(ROM_WORD_BITS), depth=N_TAPS,
                         init=list(self._rom.rom_words[j]))
            m.submodules[f"rom{j}"] = rom
            rd = rom.read_port(domain="comb")
            m.d.comb += rd.addr.eq(gap_rd.addr)
            prods.append(gap_rd.data * rd.data.as_signed())      # Q(72,36)

        # ---- curvature latch registers -----------------------------------------
        c_reg = [Signal(signed(COEFF.bits), name=f"c{j}_reg") for j in range(N_COEFFS)]
        cov = Signal()                     # coefficient overflow
        dov = Signal()                     # d overflow
        h = Signal(signed(SUM_FMT.bits))   # c3 + c5, Q(33,20)
        e = Signal(signed(SUM_FMT.bits))   # c3 - c5, Q(33,20)
        d = Signal(unsigned(2 * SUM_FMT.bits))   # e^2 + c4^2, wide enough to test > max
        stage = Signal(range(4))           # 0 MAC, 1..3 latch stages

        rounded = [_round_shift(acc, _COEFF_SHIFT) for acc in accs]
        d_new = Signal(unsigned(2 * SUM_FMT.bits))   # >= 0 and < 2^66: no truncation
        m.d.comb += d_new.eq(e * e + c_reg[4] * c_reg[4])
        r = self._isqrt(m, d[:D_FMT.bits])
        a_new = _round_shift(h + r, 1)
        b_new = _round_shift(h - r, 1)

        m.d.sync += self.done_pulse.eq(0)
        with m.If(~busy):
            with m.If(self.go):
                m.d.sync += [busy.eq(1), self.done.eq(0), tap.eq(1), stage.eq(0)]
                m.d.sync += [acc.eq(p) for acc, p in zip(accs, prods)]
        with m.Elif(stage == 0):
            m.d.sync += [acc.eq(acc + p) for acc, p in zip(accs, prods)]
            m.d.sync += tap.eq(tap + 1)
            with m.If(tap == N_TAPS - 1):
                m.d.sync += stage.eq(1)
        with m.Elif(stage == 1):
            c3, c5 = rounded[3][:COEFF.bits].as_signed(), rounded[5][:COEFF.bits].as_signed()
            m.d.sync += [cr.eq(x) for cr, x in zip(c_reg, rounded)]
            m.d.sync += [cov.eq(~_all(_fits(x, COEFF) for x in rounded)),
                         h.eq(c3 + c5), e.eq(c3 - c5), stage.eq(2)]
        with m.Elif(stage == 2):
            m.d.sync += [d.eq(d_new), dov.eq(~cov & (d_new > D_FMT.max_code)), stage.eq(3)]
        with m.Else():
            kov = ~cov & ~dov & ~(_fits(a_new, CURVATURE) & _fits(b_new, CURVATURE))
            bad = cov | dov | kov
            flags = Cat(cov, dov, kov, ~bad & (b_new <= 0))     # bit order = FLAG_*
            m.d.sync += [busy.eq(0), self.done.eq(1), self.done_pulse.eq(1),
                         stage.eq(0), tap.eq(0),
                         self.flags.eq(flags),
                         self.a_minus.eq(Mux(bad, 0, a_new)),
                         self.b_minus.eq(Mux(bad, 0, b_new))]
            m.d.sync += [o.eq(Mux(bad, 0, cr)) for o, cr in zip(self.coeffs, c_reg)]
        return m


def _all(terms):
    """AND of Amaranth boolean expressions."""
    out = Const(1, 1)
    for t in terms:
        out = out & t
    return out


def convert_verilog(*, rom: BakedPinv | None = None, name: str = "fit_core") -> str:
    """Verilog of :class:`FitCore` (``strip_internal_attrs=True``)."""
    core = FitCore(rom=rom)
    return verilog.convert(core, name=name, strip_internal_attrs=True)


def read_fit_codes(ctx, dut) -> GoldenFit:
    """The output ports of a :class:`FitCore` as :class:`.golden.GoldenFit`."""
    return read_record(ctx, dut, GoldenFit, FIT_OUTPUT_PORTS)


def simulate_fit_core(stencils, *, rom: BakedPinv | None = None,
                      max_cycles: int = 4 * FIT_CYCLES) -> tuple[list, list]:
    """Simulate the core cycle-accurately on GAP code stencils.

    For each stencil: pulse ``wr_rst``, write the 49 codes, assert ``go`` for one cycle
    and count clock edges until ``done`` reads 1.

    Parameters
    ----------
    stencils : array_like of int, shape (n, 49)
        GAP Q(32,16) codes (e.g. from :func:`.golden.encode_gaps`).
    rom : BakedPinv, keyword-only, optional
        ROM to bake (default: hardware ROM).
    max_cycles : int, keyword-only
        Give up (RuntimeError) if ``done`` has not risen after this many edges.

    Returns
    -------
    (outputs, cycles)
        ``outputs``: list of :class:`.golden.GoldenFit` read from the output ports
        (directly comparable with :func:`.golden.golden_fit`); ``cycles``: edges from
        the ``go`` edge to ``done`` for each stencil (``FIT_CYCLES`` by design).
    """
    codes = check_gap_codes(stencils, 2)
    dut = FitCore(rom=rom)
    outputs, cycles = [], []

    async def bench(ctx):
        for row in codes:
            await write_stencil(ctx, dut, row)
            cycles.append(await run_to_done(ctx, dut.go, dut.done, max_cycles=max_cycles,
                                            what="fit core"))
            outputs.append(read_fit_codes(ctx, dut))

    run_testbench(dut, bench)
    return outputs, cycles
