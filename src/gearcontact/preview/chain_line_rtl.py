"""Amaranth RTL of the line chain: FitCore -> HertzLineCore, 811 cycles go -> done.

Bit-exact with :func:`.chain.chain_line_golden` and cycle-exact with
:data:`.chain.CHAIN_LINE_CYCLES`::

    wr_rst / wr_en + wr_data ─► FitCore (gap RAM, 6 MACs, curvature latch; 52 edges)
                                   │ A-, B- registers, flags, done_pulse
    W, e_prime, L ─► (captured     ├─► HertzLineCore.go (its own CAPTURE, SORT + SCALE)
                      at go)       ▼
                 HertzLineCore (759 edges) ─► a, b, p_max, k, mode, scale, ...

Timing: edge 1 samples ``go`` (the fit's first MAC edge); the fit latch's last edge
(52) writes A-, B- and raises ``done_pulse``, which is the line core's ``go``: edge 53
captures the fitted curvatures, and the line core's SELECT edge, ``52 + 759 = 811``,
writes the results and raises ``done`` for every input, flagged or not. The published
:class:`.chain_rtl.ChainCore` (806 cycles) is a separate core, unchanged.

Between the fit and the line core a B- code in ``[-LINE_B_ZERO_CODES, 0)`` becomes 0
(:func:`.chain.line_b_minus`: within the fit's resolution, a line contact). The fit
flags travel beside the line core in a tag register (latched with the
curvatures, moved to the output on the line core's SELECT edge), so every output
changes only on the ``done`` edge; the chain flags word carries only the fit's overflow
bits (:data:`.chain.LINE_CHAIN_FIT_FLAGS`: B- <= 0 is the line core's to judge), the
``fit_flags`` port the fit's whole word. Control (``go`` while idle only, ``done`` /
``done_pulse``, gap writes, reset) as :class:`.chain_rtl.ChainCore`.

Ports: those of :class:`.chain_rtl.ChainCore` without ``R_x``, ``R_y``, ``alpha``
(``a_minus``, ``b_minus``: the fit's A-, B- of the run, held with the results), plus

==========  =====  ============  ===================================================
port        dir    shape         meaning (format)
==========  =====  ============  ===================================================
L           in     signed(32)    contact-line length, LINE_LENGTH Q(32,20), mm (at go)
A_min       out    signed(32)    the line core's sorted curvatures (B- after the zero
B_max       out    signed(32)    rule), CURVATURE Q(32,20), 1/mm
mode        out    1             0 elliptic, 1 line (:mod:`.hertz.line`)
scale       out    2             SCALE exponent n of the line core
flags       out    12            line-core flags in bits 0..7, fit overflow flags in
                                 bits 8..11
fit_flags   out    4             the fit core's flags word of the run
==========  =====  ============  ===================================================
"""

from __future__ import annotations

from amaranth import Cat, Const, Module, Mux, Signal, signed
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from .chain import (CHAIN_LINE_CYCLES, FIT_FLAG_SHIFT, LINE_B_ZERO_CODES, LINE_CHAIN_FIT_FLAGS,
                    ChainLineCodes)
from .chain_rtl import connect_front_end, run_chain_like
from .fit.golden import FLAG_BITS as FIT_FLAG_BITS
from .fit.golden import GoldenFit
from .fit.pinv import BakedPinv
from .fit.rtl import COEFF_PORTS, FitCore, fit_front_end_ports
from .hertz import formats as HF
from .hertz import line as LN
from .hertz.rtl_line import LINE_FLAG_BITS, LINE_OUTPUT_PORTS, HertzLineCore
from ..contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS
from .simulation import read_ports

__all__ = ["ChainLineCore", "convert_verilog", "simulate_chain_line_core"]

assert LINE_FLAG_BITS <= FIT_FLAG_SHIFT


class ChainLineCore(wiring.Component):
    """C -> line-core chain: stage-C fit feeding the line core of stage D (811 cycles).

    Parameters
    ----------
    rom : BakedPinv, keyword-only, optional
        Pseudo-inverse ROM of the fit (default: the hardware ROM).
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        Form of the elliptic core inside the line core.
    """

    def __init__(self, *, rom: BakedPinv | None = None,
                 hertz_form: str = HF.DEFAULT_HERTZ_FORM):
        self._rom = rom
        self._hertz_form = HF.check_hertz_form(hertz_form)
        write, status, coeffs = fit_front_end_ports()
        super().__init__({
            **write, "W": In(signed(LOAD.bits)), "e_prime": In(signed(HF.E_PRIME.bits)),
            "L": In(signed(LN.LINE_LENGTH.bits)), "go": In(1), **status,
            "a": Out(signed(SEMI_AXIS.bits)), "b": Out(signed(SEMI_AXIS.bits)),
            "p_max": Out(signed(PMAX.bits)), "k": Out(signed(HF.K_OUT.bits)),
            "a_minus": Out(signed(CURVATURE.bits)), "b_minus": Out(signed(CURVATURE.bits)),
            "A_min": Out(signed(CURVATURE.bits)), "B_max": Out(signed(CURVATURE.bits)),
            "mode": Out(1), "scale": Out(2), "flags": Out(FIT_FLAG_SHIFT + FIT_FLAG_BITS),
            "fit_flags": Out(FIT_FLAG_BITS), **coeffs})

    def elaborate(self, platform):
        m = Module()
        m.submodules.fit = fit = FitCore(rom=self._rom)
        m.submodules.line = line = HertzLineCore(hertz_form=self._hertz_form)
        busy = fit.busy | fit.done_pulse | line.busy
        accept = connect_front_end(m, self, fit, busy)
        w = Signal(signed(LOAD.bits))
        e_prime = Signal(signed(HF.E_PRIME.bits))
        length = Signal(signed(LN.LINE_LENGTH.bits))
        with m.If(accept):
            m.d.sync += [w.eq(self.W), e_prime.eq(self.e_prime), length.eq(self.L)]
        # a B- below zero within the fit's resolution is a line contact (.chain)
        b_zero = (fit.b_minus < 0) & (fit.b_minus >= -LINE_B_ZERO_CODES)
        m.d.comb += [line.A.eq(fit.a_minus), line.B.eq(Mux(b_zero, 0, fit.b_minus)),
                     line.W.eq(w),
                     line.e_prime.eq(e_prime), line.L.eq(length), line.go.eq(fit.done_pulse)]
        # the fit flags beside the line core: latched with its go, out on its SELECT edge
        tag_run = Signal(FIT_FLAG_BITS)
        tag_out = Signal(FIT_FLAG_BITS)
        fit_run = [Signal(signed(CURVATURE.bits)) for _ in range(2)]     # A-, B-
        fit_out = [Signal(signed(CURVATURE.bits)) for _ in range(2)]
        t = Signal(range(LN.LINE_CYCLES))
        with m.If(fit.done_pulse & ~line.busy):
            m.d.sync += [tag_run.eq(fit.flags), fit_run[0].eq(fit.a_minus),
                         fit_run[1].eq(fit.b_minus), t.eq(1)]
        with m.Elif(t == LN.LINE_CYCLES - 1):
            m.d.sync += [tag_out.eq(tag_run), fit_out[0].eq(fit_run[0]),
                         fit_out[1].eq(fit_run[1]), t.eq(0)]
        with m.Elif(t != 0):
            m.d.sync += t.eq(t + 1)
        m.d.comb += [self.done.eq(line.done & ~fit.busy & ~fit.done_pulse),
                     self.done_pulse.eq(line.done_pulse),
                     self.a.eq(line.a), self.b.eq(line.b), self.p_max.eq(line.p_max),
                     self.k.eq(line.k), self.a_minus.eq(fit_out[0]),
                     self.b_minus.eq(fit_out[1]), self.A_min.eq(line.A_min),
                     self.B_max.eq(line.B_max), self.mode.eq(line.mode),
                     self.scale.eq(line.scale), self.fit_flags.eq(tag_out),
                     self.flags.eq(Cat(line.flags, Const(0, FIT_FLAG_SHIFT - LINE_FLAG_BITS),
                                       tag_out & LINE_CHAIN_FIT_FLAGS))]
        return m


def convert_verilog(*, rom: BakedPinv | None = None, name: str = "chain_line_core",
                    hertz_form: str = HF.DEFAULT_HERTZ_FORM) -> str:
    """Verilog of :class:`ChainLineCore` (``strip_internal_attrs=True``)."""
    return verilog.convert(ChainLineCore(rom=rom, hertz_form=hertz_form), name=name,
                           strip_internal_attrs=True)


def _read(ctx, dut, cycles: int) -> ChainLineCodes:
    """The outputs of :class:`ChainLineCore` as :class:`.chain.ChainLineCodes`."""
    g = read_ports(ctx, dut, {p: p for p in ("a", "b", "p_max", "k", "a_minus", "b_minus",
                                             "A_min", "B_max", "mode", "scale", "flags",
                                             "fit_flags")})
    fit = GoldenFit(c_codes=read_ports(ctx, dut, {"c": COEFF_PORTS})["c"],
                    a_minus_code=g["a_minus"], b_minus_code=g["b_minus"],
                    flags=g["fit_flags"])
    lc = LN.LineCodes(g["a"], g["b"], g["p_max"], g["k"], g["A_min"], g["B_max"],
                      g["mode"], g["scale"], g["flags"] & ((1 << FIT_FLAG_SHIFT) - 1))
    assert set(LINE_OUTPUT_PORTS.values()) == set(LN.LineCodes.__dataclass_fields__)
    return ChainLineCodes(fit=fit, hertz=lc, flags=g["flags"], cycles=cycles)


def simulate_chain_line_core(stencils, W_codes, L_codes, *, e_prime_code: int,
                             rom: BakedPinv | None = None,
                             max_cycles: int = 2 * CHAIN_LINE_CYCLES,
                             hertz_form: str = HF.DEFAULT_HERTZ_FORM
                             ) -> tuple[list[ChainLineCodes], list[int]]:
    """Simulate :class:`ChainLineCore` cycle-accurately on STENCIL_GAP code stencils.

    Parameters
    ----------
    stencils : array_like of int, shape (n, 49)
        STENCIL_GAP Q(32,21) codes (:func:`.fit.golden.encode_gaps`).
    W_codes, L_codes : int or array_like of int, shape (n,)
        Loads, LOAD Q(32,8); contact-line lengths, LINE_LENGTH Q(32,20).
    e_prime_code : int, keyword-only
        E', E_PRIME Q(32,0).
    rom, max_cycles, hertz_form : keyword-only
        As :func:`.chain_rtl.simulate_chain_core`.

    Returns
    -------
    (outputs, cycles)
        :class:`.chain.ChainLineCodes` per stencil (``cycles`` set to the measured count,
        so ``outputs[i] == chain_line_golden(...)`` checks bits and cycles) and the
        counts (``CHAIN_LINE_CYCLES`` = 811 by design). A few stencils per second.
    """
    import numpy as np

    n = np.shape(stencils)[0] if np.ndim(stencils) == 2 else 1
    ls = np.broadcast_to(np.asarray(L_codes, dtype=object), (n,))
    ls = [int(LN.LINE_LENGTH.check(int(x), field=f"L_codes[{i}]")) for i, x in enumerate(ls)]
    return run_chain_like(ChainLineCore(rom=rom, hertz_form=hertz_form), stencils, W_codes,
                          e_prime_code, max_cycles=max_cycles, what="line chain core",
                          extra={"L": ls}, read=_read)
