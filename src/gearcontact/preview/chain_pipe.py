"""Amaranth RTL of the C->D chain with the pipelined stage D: 142 cycles go -> done.

:class:`ChainPipe` has the ports and the go/busy/done protocol of
:class:`.chain_rtl.ChainCore`; its stage D is :class:`.hertz.rtl_pipe.HertzPipe`
(initiation interval 1) instead of the serialized :class:`.hertz.rtl.HertzCore`::

    wr_rst / wr_en + wr_data ─► FitCore (52 edges) ─► done_pulse, A-, B-, fit flags
                                                        │ in_valid, tag_in
    W, e_prime (captured at go) ───────────────────────►├─► HertzPipe (90 edges)
                                                        ▼
                            held result (out_ready low until the next go) ─► outputs

Timing: edge 1 samples ``go``; the fit raises ``done_pulse`` after edge 52; edge 53 is
the pipe's accepting edge; its result shows with ``out_valid`` after edge
52 + 90 = 142 (:data:`CHAIN_PIPE_CYCLES`), for every input, flagged or not. Stage D
computes exactly what :func:`.chain.chain_golden` computes, so every output is the
golden one bit for bit (only the cycle count differs from ChainCore's 806).

Control behaviour (as ChainCore except where said)
--------------------------------------------------
* ``go`` is accepted only while idle (``busy``: the fit running or an evaluation in the
  pipe); ``W`` and ``e_prime`` are captured on the accepting edge.
* The result is held at the pipe's output (``out_ready`` stays low) and ``done`` =
  the pipe's ``out_valid`` stays 1 until the next accepted ``go``, whose edge consumes
  it; ``done_pulse`` marks the first cycle of ``done``. Between an accepted ``go`` and
  ``done`` the stage-D outputs are not meaningful (ChainCore holds the previous ones).
* The fit coefficients ``c0``..``c5`` are the fit core's registers (change on the fit's
  done edge). Writes and reset behave as in ChainCore.

One evaluation is in flight at a time here: the serialized fit (52 edges plus the
49-word write burst) bounds the chain's rate, so what the pipelined stage D buys in the
chain is latency (806 -> 142 edges); its one-per-clock rate serves a stream of stage-C
results (several fit cores), not this single-fit chain.
"""

from __future__ import annotations

from amaranth import Module, Signal, signed
from amaranth.back import verilog

from .chain_rtl import ChainLikeCore, connect_front_end, run_chain_like, stage_d_outputs
from .fit.golden import FIT_CYCLES
from .fit.golden import FLAG_BITS as FIT_FLAG_BITS
from .fit.pinv import BakedPinv
from .fit.rtl import FitCore
from .hertz import formats as HF
from .hertz.rtl_pipe import HertzPipe, pipe_latency
from ..contract.qformat import LOAD

__all__ = ["ChainPipe", "CHAIN_PIPE_CYCLES", "chain_pipe_cycles", "convert_verilog",
           "simulate_chain_pipe"]


def chain_pipe_cycles(hertz_form: str = HF.DEFAULT_HERTZ_FORM) -> int:
    """Edges from ``go`` (edge 1) to ``done``: the fit's 52 plus the pipe's latency."""
    return FIT_CYCLES + pipe_latency(hertz_form=hertz_form)


#: go -> done of the published form: 52 + 90 = 142.
CHAIN_PIPE_CYCLES = chain_pipe_cycles()


class ChainPipe(ChainLikeCore):
    """C->D chain with the pipelined stage D (module docstring); ports of
    :class:`.chain_rtl.ChainCore`.

    Parameters
    ----------
    rom : BakedPinv, keyword-only, optional
        Pseudo-inverse ROM of the fit (default: the hardware ROM).
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        Tables of the embedded :class:`.hertz.rtl_pipe.HertzPipe`.
    """

    def __init__(self, *, rom: BakedPinv | None = None,
                 hertz_form: str = HF.DEFAULT_HERTZ_FORM):
        self._hertz_form = HF.check_hertz_form(hertz_form)
        super().__init__(rom=rom)

    def elaborate(self, platform):
        m = Module()
        m.submodules.fit = fit = FitCore(rom=self._rom)
        m.submodules.hertz = hz = HertzPipe(tag_bits=FIT_FLAG_BITS,
                                            hertz_form=self._hertz_form)
        in_flight = Signal()                    # accepted by the pipe, not yet out
        shown = Signal()                        # done_pulse already given
        busy = fit.busy | fit.done_pulse | in_flight
        accept = connect_front_end(m, self, fit, busy)
        w = Signal(signed(LOAD.bits))
        e_prime = Signal(signed(HF.E_PRIME.bits))
        with m.If(accept):
            m.d.sync += [w.eq(self.W), e_prime.eq(self.e_prime), shown.eq(0)]
        with m.Elif(hz.out_valid):
            m.d.sync += shown.eq(1)
        with m.If(fit.done_pulse):
            m.d.sync += in_flight.eq(1)
        with m.Elif(hz.out_valid):
            m.d.sync += in_flight.eq(0)
        m.d.comb += [hz.A.eq(fit.a_minus), hz.B.eq(fit.b_minus), hz.W.eq(w),
                     hz.e_prime.eq(e_prime), hz.in_valid.eq(fit.done_pulse),
                     hz.tag_in.eq(fit.flags), hz.out_ready.eq(accept)]
        m.d.comb += [self.done.eq(hz.out_valid), self.done_pulse.eq(hz.out_valid & ~shown)]
        m.d.comb += stage_d_outputs(self, hz)
        return m


def convert_verilog(*, rom: BakedPinv | None = None, name: str = "chain_pipe",
                    hertz_form: str = HF.DEFAULT_HERTZ_FORM) -> str:
    """Verilog of :class:`ChainPipe` (``strip_internal_attrs=True``)."""
    return verilog.convert(ChainPipe(rom=rom, hertz_form=hertz_form), name=name,
                           strip_internal_attrs=True)


def simulate_chain_pipe(stencils, W_codes, *, e_prime_code: int,
                        rom: BakedPinv | None = None, max_cycles: int = 4 * CHAIN_PIPE_CYCLES,
                        hertz_form: str = HF.DEFAULT_HERTZ_FORM):
    """Simulate :class:`ChainPipe`; interface and return value of
    :func:`.chain_rtl.simulate_chain_core` (cycles = :func:`chain_pipe_cycles`)."""
    return run_chain_like(ChainPipe(rom=rom, hertz_form=hertz_form), stencils, W_codes,
                          e_prime_code, max_cycles=max_cycles, what="chain pipe")
