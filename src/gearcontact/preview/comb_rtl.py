"""Amaranth 0.5 RTL of the combinational C+D preview: 58 cycles go -> done.

The fit front end of :class:`.fit.rtl.FitCore` (49 MAC edges + 3 latch edges) is
followed by stage D unrolled into :data:`.hertz.schedule.COMB_D_STAGES` = 6
registered stages of combinational logic — array dividers
(:func:`.hertz.rtl_divider.array_divide`, the same exact floor quotients as the shared
serial divider), asynchronous LUT ROMs and direct multipliers — built from the same
expressions as the serialized core (:mod:`.hertz.rtl_datapath`), so its outputs are
:func:`.chain.chain_golden`'s bit for bit::

    edge 53  S1  sort, envelope flags; R_x, R_y, alpha (range check), R    (4 dividers)
    edge 54  S2  E6 = C6 + N5 // alpha (divider); POW ROM + interpolation: K
                 (hertz_form="exact": POWX ROM for K; EEX ROM + interpolation N(alpha)
                 as the divider's dividend instead of the constant N5)
    edge 55  S3  K2, T1, T2, T3, W C3                                      (products)
    edge 56  S4  C_a = (T3 << 11) // E'                                    (divider)
    edge 57  S5  range reduction, CBRT ROM + interpolation, a_w
    edge 58  S6  b_w, p_n2, p_max (3 dividers); outputs, flags, ``done``

Only one evaluation is in flight (``go`` is refused while busy), so every stage
register holds its value until the next run and later stages read earlier ones
directly. The flags word records the first failing check in the golden model's order
(envelope, zero divisors / alpha range in division order, then output overflow).
Ports and control behaviour are those of :class:`.chain_rtl.ChainCore` (same port
list; ``done`` on edge 58 instead of 806); the logic is large (nine array dividers of
up to 80 rows) — that is the trade the synthesis study measures.
"""

from __future__ import annotations

from amaranth import Module, Mux, Signal, signed, unsigned
from amaranth.back import verilog
from amaranth.lib.memory import Memory

from .chain import ChainCodes
from .chain_rtl import ChainLikeCore, chain_flags, connect_front_end, run_chain_like
from .fit.golden import FLAG_BITS as FIT_FLAG_BITS
from .fit.pinv import BakedPinv
from .fit.rtl import FitCore
from .hertz import formats as F
from .hertz.luts import (CBRT_SPEC, EE_EXACT_SPEC, LUT_SIZE, LUT_WORD_BITS, POW_SPEC,
                         POW_SPECS, rom_words)
from .hertz import rtl_datapath as dp
from .hertz.rtl_divider import array_divide
from .hertz.schedule import COMB_CYCLES, COMB_D_STAGES
from ..contract.qformat import CURVATURE, LOAD

__all__ = ["CombCore", "convert_verilog", "simulate_comb_core"]


def _first_flag(flags, checks):
    """Golden priority: keep ``flags`` if set, else the first ``(cond, FLAG)`` that
    holds, else 0."""
    out = 0
    for cond, flag in reversed(checks):
        out = Mux(cond, flag, out)
    return Mux(flags != 0, flags, out)


class CombCore(ChainLikeCore):
    """Combinational C+D core: fit front end + 6-stage pipelined stage D (58 cycles).

    Parameters as :class:`.chain_rtl.ChainLikeCore` (``rom``, the fit's
    pseudo-inverse ROM), plus ``hertz_form`` (``"hamrock-brewe"``, the published
    default, or ``"exact"``: the exact k table and the EEX table N(alpha) of
    :mod:`.hertz.luts`, read at S2 by a second ROM pair with its own interpolator -- the
    serialized core shares one, this pipeline reads both tables in one stage; same 58
    cycles, outputs of ``chain_golden(..., hertz_form="exact")``).

    Notes
    -----
    Ports: exactly those of :class:`.chain_rtl.ChainCore` (``wr_rst``, ``wr_en``,
    ``wr_data`` STENCIL_GAP Q(32,21); ``W`` LOAD Q(32,8) and ``e_prime`` E_PRIME Q(32,0),
    captured at ``go``; ``go``; ``busy``, ``done``, ``done_pulse``, ``wr_count``,
    ``wr_dropped``; ``a``, ``b`` SEMI_AXIS Q(32,20); ``p_max`` PMAX Q(32,8); ``k``
    Q(32,20); ``a_minus``, ``b_minus``, ``R_x``, ``R_y`` CURVATURE Q(32,20); ``alpha``
    UQ(32,24); ``flags`` the 12-bit chain flags word; ``c0``..``c5`` COEFF Q(32,20)).
    ``done`` rises on edge 58 (``COMB_CYCLES``).
    """

    def __init__(self, *, rom: BakedPinv | None = None,
                 hertz_form: str = F.DEFAULT_HERTZ_FORM):
        self._hertz_form = F.check_hertz_form(hertz_form)
        super().__init__(rom=rom)

    def elaborate(self, platform):
        m = Module()
        m.submodules.fit = fit = FitCore(rom=self._rom)
        valid = [fit.done_pulse] + [Signal(name=f"v{i}") for i in range(1, COMB_D_STAGES)]
        m.d.sync += [valid[i].eq(valid[i - 1]) for i in range(1, COMB_D_STAGES)]
        busy = fit.busy
        for v in valid:
            busy = busy | v
        accept = connect_front_end(m, self, fit, busy)
        w = Signal(signed(LOAD.bits))
        e_prime = Signal(signed(F.E_PRIME.bits))
        with m.If(accept):
            m.d.sync += [w.eq(self.W), e_prime.eq(self.e_prime), self.done.eq(0)]

        # stage registers (one set: a single evaluation is in flight)
        r = dp.Operands(
            a_min=Signal(signed(CURVATURE.bits), name="a_min"),
            b_max=Signal(signed(CURVATURE.bits), name="b_max"), w=w, e_prime=e_prime,
            alpha=Signal(F.ALPHA.bits, name="alpha_reg"),
            radius=Signal(F.RADIUS.bits, name="radius"),
            k=Signal(F.K_INT.bits, name="k_int"),
            e6=Signal(F.E6.bits, name="e6"), t3=Signal(F.T3.bits, name="t3"),
            wc3=Signal(F.T3.bits, name="wc3"), a_w=Signal(F.AXIS_W.bits, name="a_w"))
        flags = Signal(dp.FLAG_BITS)
        ovf = Signal()
        r_x = Signal(CURVATURE.bits)
        r_y = Signal(CURVATURE.bits)
        c_a = Signal(F.CA.bits)
        fit_flags = Signal(FIT_FLAG_BITS)

        def rom_pair(sub, spec, words):
            rom = Memory(shape=unsigned(LUT_WORD_BITS), depth=LUT_SIZE, init=list(words))
            sub.submodules[f"{spec.name}_rom"] = rom
            return rom.read_port(domain="comb"), rom.read_port(domain="comb")

        # ---- S1: sort, envelope; R_x, R_y, alpha, R -----------------------------------
        m.submodules.s1 = s = Module()
        a_min, b_max = (Signal(signed(CURVATURE.bits), name=n)
                        for n in ("s1_min", "s1_max"))
        lo, hi = dp.sort_pair(fit.a_minus, fit.b_minus)
        s.d.comb += [a_min.eq(lo), b_max.eq(hi)]
        ops1 = dp.Operands(a_min=a_min, b_max=b_max)
        q, dens = {}, {}
        for name in ("R_x", "R_y", "alpha", "R"):
            num, dens[name] = dp.division(name, ops1)
            q[name] = array_divide(s, num, dens[name], name=f"div_{name}")
        rx_q, ry_q = dp.round_shift(q["R_x"], 1), dp.round_shift(q["R_y"], 1)
        flags1 = _first_flag(dp.envelope_flags(a_min, b_max, w, e_prime), [
            (dens["R_x"] == 0, F.FLAG_DIV_ZERO), (dens["R_y"] == 0, F.FLAG_DIV_ZERO),
            (dens["alpha"] == 0, F.FLAG_DIV_ZERO),
            (q["alpha"] > F.ALPHA_MAX_CODE, F.FLAG_ALPHA_RANGE),
            (dens["R"] == 0, F.FLAG_DIV_ZERO)])
        with m.If(valid[0]):
            m.d.sync += [r.a_min.eq(a_min), r.b_max.eq(b_max), flags.eq(flags1),
                         r_x.eq(rx_q), r_y.eq(ry_q), r.alpha.eq(q["alpha"]),
                         r.radius.eq(q["R"]), fit_flags.eq(fit.flags),
                         ovf.eq(~dp.fits(rx_q, CURVATURE) | ~dp.fits(ry_q, CURVATURE))]

        # ---- S2: E6 (divider) and K (POW ROM + interpolation) -------------------------
        m.submodules.s2 = s = Module()
        pow_spec = POW_SPECS[self._hertz_form]          # one geometry: luts.same_geometry
        pow0, pow1 = rom_pair(s, pow_spec, rom_words(pow_spec))
        p_addr, p_next, p_r = dp.lut_split(POW_SPEC, r.alpha)
        s.d.comb += [pow0.addr.eq(p_addr), pow1.addr.eq(p_next)]
        if self._hertz_form == "exact":                 # EEX: the E_e dividend N(alpha)
            ee0, ee1 = rom_pair(s, EE_EXACT_SPEC, rom_words(EE_EXACT_SPEC))
            r.n_ee = Signal(POW_SPEC.vbits + POW_SPEC.tbits, name="n_ee")
            s.d.comb += [ee0.addr.eq(p_addr), ee1.addr.eq(p_next),
                         r.n_ee.eq(dp.lut_interpolate(POW_SPEC, ee0.data, ee1.data, p_r))]
        num, den = dp.division("E_e", r)
        q_e = array_divide(s, num, den, name="div_E_e")
        with m.If(valid[1]):
            m.d.sync += [r.e6.eq(dp.e6_from_quotient(q_e)),
                         r.k.eq(dp.pow_to_k(dp.lut_interpolate(POW_SPEC, pow0.data,
                                                               pow1.data, p_r))),
                         flags.eq(_first_flag(flags, [(den == 0, F.FLAG_DIV_ZERO)]))]

        # ---- S3: the staged products --------------------------------------------------
        m.submodules.s3 = s = Module()
        p = dp.Operands(k=r.k, e6=r.e6, radius=r.radius, w=w)
        for step, fmt in (("k2", F.K2), ("t1", F.T1), ("t2", F.T2), ("t3", F.T3),
                          ("wc3", F.T3)):
            x, y = dp.product_operands(step, p)
            sig = Signal(fmt.bits, name=f"s3_{step}")
            s.d.comb += sig.eq(dp.product_result(step, x * y))
            setattr(p, step, sig)
        with m.If(valid[2]):
            m.d.sync += [r.t3.eq(p.t3), r.wc3.eq(p.wc3)]

        # ---- S4: C_a ------------------------------------------------------------------
        m.submodules.s4 = s = Module()
        num, den = dp.division("C_a", r)
        q_ca = array_divide(s, num, den, name="div_C_a")
        with m.If(valid[3]):
            m.d.sync += [c_a.eq(q_ca),
                         flags.eq(_first_flag(flags, [(den == 0, F.FLAG_DIV_ZERO)]))]

        # ---- S5: range reduction, CBRT ROM + interpolation, a_w -----------------------
        m.submodules.s5 = s = Module()
        m_red, s1 = dp.range_reduce(s, c_a, name="rr")
        cb0, cb1 = rom_pair(s, CBRT_SPEC, rom_words(CBRT_SPEC))
        c_addr, c_next, c_r = dp.lut_split(CBRT_SPEC, m_red)
        s.d.comb += [cb0.addr.eq(c_addr), cb1.addr.eq(c_next)]
        with m.If(valid[4]):
            m.d.sync += r.a_w.eq(dp.scale_cbrt(dp.lut_interpolate(CBRT_SPEC, cb0.data,
                                                                  cb1.data, c_r), s1))

        # ---- S6: b_w, p_n2, p_max; outputs --------------------------------------------
        m.submodules.s6 = s = Module()
        r6 = dp.Operands(k=r.k, a_w=r.a_w, wc3=r.wc3,
                      b_w=Signal(F.AXIS_W.bits, name="s6_b_w"),
                      p_n2=Signal(F.PN2.bits, name="s6_p_n2"))
        dens = {}
        for name, dest in (("b", r6.b_w), ("p_n2", r6.p_n2), ("p_max", None)):
            num, dens[name] = dp.division(name, r6)
            q[name] = array_divide(s, num, dens[name], name=f"div_{name}")
            if dest is not None:
                s.d.comb += dest.eq(q[name])
        flags6 = _first_flag(flags, [(dens[n] == 0, F.FLAG_DIV_ZERO)
                                     for n in ("b", "p_n2", "p_max")])
        flags_out, outs = dp.finalize(flags6, ovf, a_w=r.a_w, b_w=r6.b_w, k=r.k, r_x=r_x,
                                   r_y=r_y, alpha=r.alpha, p_max_q=q["p_max"])
        m.d.sync += self.done_pulse.eq(0)
        with m.If(valid[5]):
            m.d.sync += [self.done.eq(1), self.done_pulse.eq(1),
                         self.flags.eq(chain_flags(flags_out, fit_flags)),
                         self.a_minus.eq(r.b_max), self.b_minus.eq(r.a_min)]
            m.d.sync += [getattr(self, port).eq(v) for port, v in outs.items()]
        return m


def convert_verilog(*, rom: BakedPinv | None = None, name: str = "comb_core",
                    hertz_form: str = F.DEFAULT_HERTZ_FORM) -> str:
    """Verilog of :class:`CombCore` (``strip_internal_attrs=True``)."""
    return verilog.convert(CombCore(rom=rom, hertz_form=hertz_form), name=name,
                           strip_internal_attrs=True)


def simulate_comb_core(stencils, W_codes, *, e_prime_code: int,
                       rom: BakedPinv | None = None, max_cycles: int = 2 * COMB_CYCLES,
                       hertz_form: str = F.DEFAULT_HERTZ_FORM
                       ) -> tuple[list[ChainCodes], list[int]]:
    """Simulate :class:`CombCore` cycle-accurately; same interface and return value as
    :func:`.chain_rtl.simulate_chain_core`, with ``COMB_CYCLES`` = 58 by design (the
    returned :class:`.chain.ChainCodes` carry the measured count in ``cycles``, so
    compare with ``dataclasses.replace(chain_golden(...), cycles=COMB_CYCLES)``).

    ~10 stencils/s of CPU time in Amaranth's simulator (the cost is the once-per-run
    settling of the array dividers, not the 108 edges), plus ~2 s to elaborate."""
    return run_chain_like(CombCore(rom=rom, hertz_form=hertz_form), stencils, W_codes,
                          e_prime_code, max_cycles=max_cycles, what="comb core")
