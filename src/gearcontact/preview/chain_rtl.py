"""Amaranth 0.5 RTL of the C->D chain: FitCore -> HertzCore, 806 cycles go -> done.

Bit-exact with :func:`.chain.chain_golden` and cycle-exact with
:data:`.hertz.schedule.CHAIN_CYCLES`::

    wr_rst / wr_en + wr_data ─► FitCore (gap RAM, 6 MACs, curvature latch; 52 edges)
                                   │ A-, B- registers, flags, done_pulse
    W, e_prime ─► (captured at go) ├─► HertzCore.go_chain (CAPTURE/SORT absorbed)
                                   ▼
                 HertzCore (DIV_RX .. DIV_PMAX: 754 edges) ─► a, b, p_max, k, ...

Timing: edge 1 samples ``go`` (the fit's first MAC edge); the fit latch's last edge
(52) writes A-, B- and raises ``done_pulse``; edge 53 is stage D's accepting edge
(capture + sort + DIV_RX operand load, :class:`.hertz.rtl.HertzCore` ``go_chain``);
edge 806 writes the results and raises ``done`` — ``52 + 756 - 2 = 806`` for every
input, flagged or not.

Control behaviour
-----------------
* ``go`` is accepted only while idle (``busy`` = 0: neither the fit nor stage D is
  running); a ``go`` while busy is ignored. ``W`` and ``e_prime`` are captured on the
  accepting edge. Accepting ``go`` clears ``done``; ``done`` rises on edge 806 and
  stays 1 until the next accepted ``go``; ``done_pulse`` marks its first cycle.
* The stage-D outputs (``a``, ``b``, ``p_max``, ``k``, ``a_minus``, ``b_minus``,
  ``R_x``, ``R_y``, ``alpha``, ``flags``) change only on the ``done`` edge and hold
  until the next run completes (the fit flags travel through stage D as its side-band
  tag). The fit coefficients ``c0``..``c5`` are the fit core's own registers: they
  change on the fit's done edge (52 edges after ``go``).
* Gap writes follow :class:`.fit.rtl.FitCore`: ``wr_rst`` rewinds the pointer, each
  ``wr_en`` writes one sample; writes are dropped (sticky ``wr_dropped``) during the
  fit's 52 edges, with an accepted ``go`` and beyond 49 samples. While stage D runs the
  RAM is free, so the next stencil may be written then. A ``go`` without fresh writes
  re-evaluates the RAM contents (all zero after power-up: flagged not elliptic).
* Synchronous reset returns both cores to idle at any time (outputs 0, ``done`` 0,
  write pointer 0); the gap RAM keeps its contents.
"""

from __future__ import annotations

import numpy as np
from amaranth import Cat, Const, Module, Signal, signed, unsigned
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from .chain import FIT_FLAG_SHIFT, ChainCodes
from .fit.golden import FLAG_BITS as FIT_FLAG_BITS
from .fit.golden import GoldenFit, check_gap_codes
from .fit.pinv import BakedPinv
from .fit.rtl import COEFF_PORTS, FitCore, fit_front_end_ports
from .hertz import formats as HF
from .hertz.golden import HertzCodes
from .hertz.rtl import HertzCore
from .hertz.rtl_datapath import FLAG_BITS as HERTZ_FLAG_BITS
from .hertz.schedule import CHAIN_CYCLES
from ..contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS
from .simulation import CycleCounter, read_ports, run_testbench, write_stencil

__all__ = [
    "CHAIN_FLAG_BITS",
    "ChainCore",
    "ChainLikeCore",
    "chain_inputs",
    "chain_output_ports",
    "convert_verilog",
    "read_chain_codes",
    "simulate_chain_core",
    "write_stencil",
]

#: Width of the chain flags word: stage-D flags, pad, fit flags << FIT_FLAG_SHIFT.
CHAIN_FLAG_BITS = FIT_FLAG_SHIFT + FIT_FLAG_BITS
assert HERTZ_FLAG_BITS <= FIT_FLAG_SHIFT


def chain_output_ports() -> dict:
    """Output ports shared by :class:`ChainCore` and the combinational ``CombCore``."""
    _, status, coeffs = fit_front_end_ports()
    return {**status,
            "a": Out(signed(SEMI_AXIS.bits)), "b": Out(signed(SEMI_AXIS.bits)),
            "p_max": Out(signed(PMAX.bits)), "k": Out(signed(HF.K_OUT.bits)),
            "a_minus": Out(signed(CURVATURE.bits)), "b_minus": Out(signed(CURVATURE.bits)),
            "R_x": Out(signed(CURVATURE.bits)), "R_y": Out(signed(CURVATURE.bits)),
            "alpha": Out(unsigned(HF.ALPHA.bits)), "flags": Out(CHAIN_FLAG_BITS),
            **coeffs}


def chain_inputs() -> dict:
    """Input ports shared by :class:`ChainCore` and ``CombCore``."""
    write, _, _ = fit_front_end_ports()
    return {**write, "W": In(signed(LOAD.bits)), "e_prime": In(signed(HF.E_PRIME.bits)),
            "go": In(1)}


def chain_flags(hertz_flags, fit_flags):
    """The chain flags word ``hertz | fit << FIT_FLAG_SHIFT`` (:mod:`.chain`)."""
    return Cat(hertz_flags, Const(0, FIT_FLAG_SHIFT - len(hertz_flags)), fit_flags)


def stage_d_outputs(core, hz) -> list:
    """Assignments of a chain-like core's result ports from its stage D ``hz`` (a
    HertzCore or HertzPipe): a, b, p_max, k, the ordered curvatures, R_x, R_y, alpha and
    the chain flags (stage D's flags with the fit flags carried as its tag)."""
    return [core.a.eq(hz.a), core.b.eq(hz.b), core.p_max.eq(hz.p_max), core.k.eq(hz.k),
            core.a_minus.eq(hz.B_max), core.b_minus.eq(hz.A_min), core.R_x.eq(hz.R_x),
            core.R_y.eq(hz.R_y), core.alpha.eq(hz.alpha),
            core.flags.eq(chain_flags(hz.flags, hz.tag))]


def connect_front_end(m: Module, core, fit: FitCore, busy):
    """Write port, gated ``go`` and coefficient outputs of the fit front end.

    Returns the accepting strobe (``go & ~busy``).
    """
    accept = core.go & ~busy
    m.d.comb += [fit.wr_rst.eq(core.wr_rst), fit.wr_en.eq(core.wr_en),
                 fit.wr_data.eq(core.wr_data), fit.go.eq(accept),
                 core.wr_count.eq(fit.wr_count), core.wr_dropped.eq(fit.wr_dropped),
                 core.busy.eq(busy)]
    m.d.comb += [c.eq(fc) for c, fc in zip(core_coeffs(core), fit.coeffs)]
    return accept


def core_coeffs(core) -> list:
    """The ``c0``..``c5`` output ports of a chain-like core."""
    return [getattr(core, p) for p in COEFF_PORTS]


class ChainLikeCore(wiring.Component):
    """Base of the cores with the chain's ports (:class:`ChainCore`, ``CombCore``):
    :func:`chain_inputs` and :func:`chain_output_ports`.

    Parameters
    ----------
    rom : BakedPinv, keyword-only, optional
        Pseudo-inverse ROM of the fit (default: the hardware ROM).
    """

    def __init__(self, *, rom: BakedPinv | None = None):
        self._rom = rom
        super().__init__({**chain_inputs(), **chain_output_ports()})


class ChainCore(ChainLikeCore):
    """C->D chain core: stage-C fit feeding the serialized stage D (806 cycles).

    Parameters as :class:`ChainLikeCore` (``rom``), plus ``hertz_form``
    (keyword-only, :data:`.hertz.formats.HERTZ_FORMS`): the ROM contents of the
    embedded :class:`~.hertz.rtl.HertzCore` (same ports and cycle count).

    Notes
    -----
    Ports (all synchronous to ``sync``):

    ==========  =====  ==============  ===============================================
    port        dir    shape           meaning (format)
    ==========  =====  ==============  ===============================================
    wr_rst      in     1               rewind the gap write pointer
    wr_en       in     1               write ``wr_data`` at the pointer, advance it
    wr_data     in     signed(32)      gap sample, STENCIL_GAP Q(32,21), mm
    W           in     signed(32)      load, LOAD Q(32,8), N (captured at go)
    e_prime     in     signed(32)      E', E_PRIME Q(32,0), MPa (captured at go)
    go          in     1               start (idle only)
    busy        out    1               fit or stage D running
    done        out    1               results valid (from edge 806 to the next go)
    done_pulse  out    1               first cycle of ``done``
    wr_count    out    range(50)       samples written since ``wr_rst``
    wr_dropped  out    1               sticky: a write was dropped
    a, b        out    signed(32)      semi-axes, SEMI_AXIS Q(32,20), mm
    p_max       out    signed(32)      peak pressure, PMAX Q(32,8), MPa
    k           out    signed(32)      ellipticity, K_OUT Q(32,20)
    a_minus     out    signed(32)      fitted A- (= stage D's B_max), CURVATURE
                                       Q(32,20), 1/mm
    b_minus     out    signed(32)      fitted B- (= stage D's A_min), CURVATURE
                                       Q(32,20), 1/mm
    R_x, R_y    out    signed(32)      principal radii, CURVATURE Q(32,20), mm
    alpha       out    unsigned(32)    R_x/R_y, ALPHA UQ(32,24)
    flags       out    12              chain flags word: stage-D ``FLAG_*`` in bits
                                       0..6, fit ``FLAG_*`` in bits 8..11
    c0 .. c5    out    signed(32)      fit coefficients, COEFF Q(32,20)
    ==========  =====  ==============  ===============================================
    """

    def __init__(self, *, rom: BakedPinv | None = None,
                 hertz_form: str = HF.DEFAULT_HERTZ_FORM):
        self._hertz_form = HF.check_hertz_form(hertz_form)
        super().__init__(rom=rom)

    def elaborate(self, platform):
        m = Module()
        m.submodules.fit = fit = FitCore(rom=self._rom)
        m.submodules.hertz = hz = HertzCore(tag_bits=FIT_FLAG_BITS,
                                            hertz_form=self._hertz_form)
        busy = fit.busy | fit.done_pulse | hz.busy
        accept = connect_front_end(m, self, fit, busy)
        w = Signal(signed(LOAD.bits))
        e_prime = Signal(signed(HF.E_PRIME.bits))
        with m.If(accept):
            m.d.sync += [w.eq(self.W), e_prime.eq(self.e_prime)]
        m.d.comb += [hz.A.eq(fit.a_minus), hz.B.eq(fit.b_minus), hz.W.eq(w),
                     hz.e_prime.eq(e_prime), hz.go.eq(0), hz.go_chain.eq(fit.done_pulse),
                     hz.tag_in.eq(fit.flags)]
        m.d.comb += [self.done.eq(hz.done & ~fit.busy & ~fit.done_pulse),
                     self.done_pulse.eq(hz.done_pulse)]
        m.d.comb += stage_d_outputs(self, hz)
        return m


def convert_verilog(*, rom: BakedPinv | None = None, name: str = "chain_core",
                    hertz_form: str = HF.DEFAULT_HERTZ_FORM) -> str:
    """Verilog of :class:`ChainCore` (``strip_internal_attrs=True``)."""
    return verilog.convert(ChainCore(rom=rom, hertz_form=hertz_form), name=name,
                           strip_internal_attrs=True)


# ---------------------------------------------------------------------------------
# simulation runner (shared with the combinational core; write_stencil lives in
# :mod:`.simulation` and is re-exported here)
# ---------------------------------------------------------------------------------
def read_chain_codes(ctx, dut, cycles: int) -> ChainCodes:
    """The outputs of a chain-like core as :class:`.chain.ChainCodes` (testbench)."""
    g = read_ports(ctx, dut, {p: p for p in ("a", "b", "p_max", "k", "a_minus", "b_minus",
                                             "R_x", "R_y", "alpha", "flags")})
    fit_flags = g["flags"] >> FIT_FLAG_SHIFT
    hz_flags = g["flags"] & ((1 << FIT_FLAG_SHIFT) - 1)
    fit = GoldenFit(c_codes=read_ports(ctx, dut, {"c": COEFF_PORTS})["c"],
                    a_minus_code=g["a_minus"], b_minus_code=g["b_minus"], flags=fit_flags)
    hz = HertzCodes(g["a"], g["b"], g["p_max"], g["k"], g["b_minus"], g["a_minus"],
                    g["R_x"], g["R_y"], g["alpha"], hz_flags)
    return ChainCodes(fit=fit, hertz=hz, flags=g["flags"], cycles=cycles)


def check_chain_inputs(stencils, W_codes, e_prime_code):
    """Validated ``(codes (n, 49), W (n,), e_prime)`` for the chain runners."""
    codes = check_gap_codes(stencils, 2)
    w = np.broadcast_to(np.asarray(W_codes, dtype=object), (codes.shape[0],))
    w = [int(LOAD.check(int(x), field=f"W_codes[{i}]")) for i, x in enumerate(w)]
    e = int(HF.E_PRIME.check(int(e_prime_code), field="e_prime_code"))
    return codes, w, e


def run_chain_like(dut, stencils, W_codes, e_prime_code, *, max_cycles: int, what: str,
                   extra: dict | None = None, read=None) -> tuple[list, list[int]]:
    """Shared runner: write each stencil, pulse ``go``, wait for ``done``, read.

    ``extra``: more per-stencil inputs (port name -> checked codes, one per stencil),
    set with ``W``; ``read(ctx, dut, cycles)``: the result reader (default
    :func:`read_chain_codes`)."""
    codes, ws, e = check_chain_inputs(stencils, W_codes, e_prime_code)
    extra = extra or {}
    read = read_chain_codes if read is None else read
    cc = CycleCounter(dut)
    outputs, cycles = [], []

    async def bench(ctx):
        ctx.set(dut.e_prime, e)
        for i, (row, w) in enumerate(zip(codes, ws)):
            await write_stencil(ctx, dut, row)
            ctx.set(dut.W, w)
            for port, values in extra.items():
                ctx.set(getattr(dut, port), values[i])
            t_go = await cc.start(ctx, dut.go)
            n = await cc.wait_done(ctx, dut.done, t_go, max_cycles, what)
            cycles.append(n)
            outputs.append(read(ctx, dut, n))

    run_testbench(cc.top, bench)
    return outputs, cycles


def simulate_chain_core(stencils, W_codes, *, e_prime_code: int,
                        rom: BakedPinv | None = None, max_cycles: int = 2 * CHAIN_CYCLES,
                        hertz_form: str = HF.DEFAULT_HERTZ_FORM
                        ) -> tuple[list[ChainCodes], list[int]]:
    """Simulate :class:`ChainCore` cycle-accurately on STENCIL_GAP code stencils.

    For each stencil: pulse ``wr_rst``, write the 49 codes, drive ``W``, assert ``go``
    for one cycle and count edges (the ``go`` edge is edge 1) until ``done`` reads 1.

    Parameters
    ----------
    stencils : array_like of int, shape (n, 49)
        STENCIL_GAP Q(32,21) codes (:func:`.fit.golden.encode_gaps`).
    W_codes : int or array_like of int, shape (n,)
        Loads, LOAD Q(32,8).
    e_prime_code : int, keyword-only
        E', E_PRIME Q(32,0) (:func:`.hertz.golden.encode_e_prime`).
    rom : BakedPinv, keyword-only, optional
        Fit ROM (default: the hardware ROM).
    max_cycles : int, keyword-only
        Give up (RuntimeError) if ``done`` has not risen after this many edges.
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        Stage-D ROM contents (:class:`ChainCore`).

    Returns
    -------
    (outputs, cycles)
        ``outputs``: :class:`.chain.ChainCodes` per stencil with ``cycles`` set to the
        measured count, so ``outputs[i] == chain_golden(...)`` checks bits and cycles;
        ``cycles``: the counts (``CHAIN_CYCLES`` = 806 by design).

    Notes
    -----
    ~9k edges/s of CPU time in Amaranth's simulator (~10 stencils/s including the 50
    write edges), plus ~1.5 s to elaborate.
    """
    return run_chain_like(ChainCore(rom=rom, hertz_form=hertz_form), stencils, W_codes,
                          e_prime_code, max_cycles=max_cycles, what="chain core")
