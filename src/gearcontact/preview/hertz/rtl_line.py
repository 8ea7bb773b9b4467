"""Amaranth RTL of the line core (:mod:`.line`), bit- and cycle-exact with its golden model.

``HertzLineCore`` instantiates the published :class:`.rtl.HertzCore` unchanged (its
netlist and 756 cycles) on the SCALEd curvatures and runs the line stage meanwhile on its
own :class:`.rtl_divider.SerialDivider`, a :class:`SerialSqrt` (the restoring square root
of :mod:`.sqrt`) and one multiplier. One counter ``t`` (edges since ``go``) sequences
everything, so the schedule is static, ``LINE_CYCLES = 759`` for every input::

    t (cycle)   action on the edge that ends it
    0 (idle)    go: capture A, B, W, E', L                               (edge 1)
    1           SORT + SCALE: A_min, B_max, line flags, n, A << 3n, B << 3n
                || divider: dividend (W C_IPI) << 4
    2           HertzCore go (captures the scaled operands; done at t = 757)
                || divider: divisor L, clear
    3 .. 82     80 divider iterations
    83          QPI <= quotient
    84 | 85     Y <= rs(QPI E', 21) | P0SQ <= Y B_max (one multiplier)
    86 | 87     square root: radicand P0SQ << 9 | clear
    88 .. 127   40 square-root iterations
    128         S <= root
    129 | 130   divider: dividend QPI << 29 | divisor S, clear
    131 .. 210  80 divider iterations
    211         b_l <= quotient
    758         SELECT (HertzCore done since t = 758): outputs, mode, flags, done
                                                                          (edge 759)

Control as :class:`.rtl.HertzCore`: ``go`` is sampled only while idle; ``done`` is set on
the last edge and holds until the next accepted ``go``, ``done_pulse`` marks its first
cycle; a synchronous reset returns the core to idle.
"""

from __future__ import annotations

from amaranth import Cat, Const, Module, Mux, Signal, signed, unsigned
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from ...contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS
from ..simulation import CycleCounter, read_record, run_testbench
from . import formats as F
from . import line as LN
from .divider import DIVIDER_BITS
from .rtl import HertzCore
from .rtl_datapath import round_shift
from .rtl_divider import SerialDivider
from .sqrt import SQRT_BITS, SQRT_ITERATIONS

__all__ = ["SerialSqrt", "HertzLineCore", "LINE_OUTPUT_PORTS", "LINE_FLAG_BITS",
           "convert_verilog", "simulate_line_core"]

#: Output ports in :class:`.line.LineCodes` field order (``port -> field``).
LINE_OUTPUT_PORTS = {"a": "a_code", "b": "b_code", "p_max": "p_max_code", "k": "k_code",
                     "A_min": "A_min_code", "B_max": "B_max_code", "mode": "mode",
                     "scale": "scale", "flags": "flags"}
LINE_FLAG_BITS = max(LN.LINE_FLAG_NAMES).bit_length()     #: 8: the published 7 + length
_ROOT_BITS = SQRT_ITERATIONS                                # 40
_REM_BITS = _ROOT_BITS + 2                                  # remainder <= 2 root < 2^41

# ---- the schedule (cycle t; the action happens on the edge that ends it) -----------
T_SORT = 1
T_INNER_GO = 2
T_QPI_LOAD, T_QPI_START = 1, 2
T_QPI_WB = T_QPI_START + 80 + 1                             # 83
T_Y, T_P0SQ = T_QPI_WB + 1, T_QPI_WB + 2                    # 84, 85
T_SQ_LOAD, T_SQ_START = T_P0SQ + 1, T_P0SQ + 2              # 86, 87
T_SQ_WB = T_SQ_START + _ROOT_BITS + 1                       # 128
T_BL_LOAD, T_BL_START = T_SQ_WB + 1, T_SQ_WB + 2            # 129, 130
T_BL_WB = T_BL_START + 80 + 1                               # 211
T_SELECT = LN.LINE_CYCLES - 1                               # 758
assert T_BL_WB - T_QPI_LOAD + 1 == LN.LINE_STAGE_CYCLES
assert T_INNER_GO + 756 == T_SELECT     # HertzCore: go on edge 3, done after edge 758


class SerialSqrt(wiring.Component):
    """Bit-serial restoring square root (80-bit radicand, 40 iterations).

    Ports: ``load`` In(1): radicand register <= ``rad`` (unsigned(80)); ``start``
    In(1): remainder, root <= 0; ``step`` In(1): one iteration (:func:`.sqrt.
    restoring_sqrt`); ``root`` Out(unsigned(40)): ``floor(sqrt(rad))`` after 40 steps.
    """

    def __init__(self):
        super().__init__({"load": In(1), "rad": In(unsigned(SQRT_BITS)), "start": In(1),
                          "step": In(1), "root": Out(unsigned(_ROOT_BITS))})

    def elaborate(self, platform):
        m = Module()
        rad = Signal(SQRT_BITS)
        rem = Signal(_REM_BITS)
        root = self.root
        shifted = Cat(rad[-2:], rem)                        # 4 rem + next two bits
        trial = shifted - Cat(Const(1, 2), root)            # - (4 root + 1)
        keep = trial >= 0
        with m.If(self.load):
            m.d.sync += rad.eq(self.rad)
        with m.Elif(self.start):
            m.d.sync += [rem.eq(0), root.eq(0)]
        with m.Elif(self.step):
            m.d.sync += [rad.eq(rad << 2), rem.eq(Mux(keep, trial, shifted)),
                         root.eq(Cat(keep, root[:-1]))]
        return m


class HertzLineCore(wiring.Component):
    """Line core of stage D (:mod:`.line`): 759 cycles go -> done, any input.

    Parameters
    ----------
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        Form of the wrapped elliptic core.

    Notes
    -----
    ==========  =====  ============  ===================================================
    port        dir    shape         meaning (format)
    ==========  =====  ============  ===================================================
    A, B        in     signed(32)    half relative curvatures, CURVATURE Q(32,20), 1/mm
    W           in     signed(32)    load, LOAD Q(32,8), N
    e_prime     in     signed(32)    E' = 2E*, Q(32,0), MPa
    L           in     signed(32)    contact-line length, LINE_LENGTH Q(32,20), mm
    go          in     1             start (idle only)
    busy        out    1             running; ``done``, ``done_pulse`` as :class:`.rtl.HertzCore`
    a, b        out    signed(32)    semi-axes / L/2 and half-width, Q(32,20), mm
    p_max       out    signed(32)    peak pressure, Q(32,8), MPa
    k           out    signed(32)    ellipticity (elliptic mode; 0 in line mode)
    A_min       out    signed(32)    min(A, B), Q(32,20), 1/mm
    B_max       out    signed(32)    max(A, B), Q(32,20), 1/mm
    mode        out    1             0 elliptic, 1 line
    scale       out    2             SCALE exponent n
    flags       out    8             line-core flags (:data:`.line.LINE_FLAG_NAMES`)
    ==========  =====  ============  ===================================================
    """

    def __init__(self, *, hertz_form: str = F.DEFAULT_HERTZ_FORM):
        self._hertz_form = F.check_hertz_form(hertz_form)
        s32 = signed(32)
        super().__init__({
            "A": In(s32), "B": In(s32), "W": In(signed(LOAD.bits)),
            "e_prime": In(signed(F.E_PRIME.bits)), "L": In(signed(LN.LINE_LENGTH.bits)),
            "go": In(1), "busy": Out(1), "done": Out(1), "done_pulse": Out(1),
            "a": Out(signed(SEMI_AXIS.bits)), "b": Out(signed(SEMI_AXIS.bits)),
            "p_max": Out(signed(PMAX.bits)), "k": Out(signed(F.K_OUT.bits)),
            "A_min": Out(signed(CURVATURE.bits)), "B_max": Out(signed(CURVATURE.bits)),
            "mode": Out(1), "scale": Out(2), "flags": Out(LINE_FLAG_BITS)})

    def elaborate(self, platform):
        m = Module()
        m.submodules.ellipse = hz = HertzCore(hertz_form=self._hertz_form)
        m.submodules.div = div = SerialDivider()
        m.submodules.sqrt = sq = SerialSqrt()

        busy = Signal()
        t = Signal(range(LN.LINE_CYCLES))
        cap_a, cap_b = Signal(signed(32)), Signal(signed(32))
        w, e_p, length = Signal(signed(32)), Signal(signed(32)), Signal(signed(32))
        a_min, b_max = Signal(signed(32)), Signal(signed(32))
        flags = Signal(LINE_FLAG_BITS)
        n = Signal(2)
        sa, sb = Signal(signed(32)), Signal(signed(32))
        qpi = Signal(LN.QPI.bits)
        y = Signal(LN.Y_LINE.bits)
        p0sq = Signal(LN.P0SQ.bits)
        s_root = Signal(LN.SQRT_OUT.bits)
        b_l = Signal(DIVIDER_BITS)

        def at(k):
            return busy & (t == k)

        # ---- start and the counter -----------------------------------------------------
        start = ~busy & self.go
        m.d.sync += self.done_pulse.eq(0)
        with m.If(start):
            m.d.sync += [busy.eq(1), t.eq(1), self.done.eq(0), cap_a.eq(self.A),
                         cap_b.eq(self.B), w.eq(self.W), e_p.eq(self.e_prime),
                         length.eq(self.L)]
        with m.Elif(busy):
            m.d.sync += t.eq(t + 1)

        # ---- SORT + SCALE --------------------------------------------------------------
        le = cap_a <= cap_b
        s_min, s_max = Mux(le, cap_a, cap_b), Mux(le, cap_b, cap_a)
        sort_flags = Cat(
            s_min < 0,                                                     # not_elliptic
            (s_max < F.CURV_MIN_CODE) | (s_max > F.CURV_MAX_CODE),         # curvature
            (w < F.LOAD_MIN_CODE) | (w > F.LOAD_MAX_CODE),                 # load
            (e_p < F.E_PRIME_MIN_CODE) | (e_p > F.E_PRIME_MAX_CODE),       # E'
            0, 0, 0,                                                       # alpha, ovf, /0
            (length < LN.LENGTH_MIN_CODE) | (length > LN.LENGTH_MAX_CODE))  # length
        # n_a: smallest n with A_min << 3n >= 2^9 (0 for A_min <= 0 or >= 2^9);
        # n_b: largest n <= 3 with B_max << 3n <= 2^24
        n_a = Mux((s_min <= 0) | (s_min >= F.CURV_MIN_CODE), 0,
                  Mux(s_min >= F.CURV_MIN_CODE >> 3, 1, Mux(s_min >= F.CURV_MIN_CODE >> 6, 2, 3)))
        n_b = Mux(s_max <= F.CURV_MAX_CODE >> 9, 3,
                  Mux(s_max <= F.CURV_MAX_CODE >> 6, 2, Mux(s_max <= F.CURV_MAX_CODE >> 3, 1, 0)))
        n_new = Mux(n_a < n_b, n_a, n_b)
        with m.If(at(T_SORT)):
            m.d.sync += [a_min.eq(s_min), b_max.eq(s_max), flags.eq(sort_flags),
                         n.eq(n_new), sa.eq(s_min << (3 * n_new)[:4]),
                         sb.eq(s_max << (3 * n_new)[:4])]
        m.d.comb += [hz.A.eq(sa), hz.B.eq(sb), hz.W.eq(w), hz.e_prime.eq(e_p),
                     hz.go.eq(at(T_INNER_GO))]

        # ---- line stage: divider, multiplier, square root ------------------------------
        w_u = w.as_unsigned()
        num = Mux(t == T_QPI_LOAD, (w_u * LN.C_IPI) << LN.QPI_SHIFT,
                  qpi << LN.BL_SHIFT)
        m.d.comb += [div.num.eq(num), div.den.eq(Mux(t == T_QPI_START, length.as_unsigned(),
                                                     s_root)),
                     div.load.eq(at(T_QPI_LOAD) | at(T_BL_LOAD)),
                     div.start.eq(at(T_QPI_START) | at(T_BL_START)),
                     div.step.eq(busy & (((t > T_QPI_START) & (t < T_QPI_WB))
                                         | ((t > T_BL_START) & (t < T_BL_WB))))]
        with m.If(at(T_QPI_WB)):
            m.d.sync += qpi.eq(div.quotient)
        with m.If(at(T_BL_WB)):
            m.d.sync += b_l.eq(div.quotient)
        op_x = Mux(t == T_Y, qpi, y)
        op_y = Mux(t == T_Y, e_p.as_unsigned(), b_max.as_unsigned())
        prod = Signal(LN.QPI.bits + 32)
        m.d.comb += prod.eq(op_x * op_y)
        with m.If(at(T_Y)):
            m.d.sync += y.eq(round_shift(prod, LN.Y_SHIFT))
        with m.If(at(T_P0SQ)):
            m.d.sync += p0sq.eq(prod)
        m.d.comb += [sq.rad.eq(p0sq << LN.SQRT_SHIFT), sq.load.eq(at(T_SQ_LOAD)),
                     sq.start.eq(at(T_SQ_START)),
                     sq.step.eq(busy & (t > T_SQ_START) & (t < T_SQ_WB))]
        with m.If(at(T_SQ_WB)):
            m.d.sync += s_root.eq(sq.root)

        # ---- SELECT ---------------------------------------------------------------------
        a_e = Signal(SEMI_AXIS.bits + 4)
        b_e = Signal(SEMI_AXIS.bits + 4)
        p_e = Signal(PMAX.bits)
        m.d.comb += [a_e.eq(hz.a.as_unsigned() << n), b_e.eq(hz.b.as_unsigned() << n),
                     p_e.eq(Mux(n == 0, hz.p_max.as_unsigned(),
                                ((hz.p_max.as_unsigned() >> (2 * n - 1)[:3]) + 1) >> 1))]
        p_l = round_shift(s_root, LN.SQRT_OUT.frac - PMAX.frac)
        b_c = round_shift(b_l, LN.B_LINE.frac - SEMI_AXIS.frac)
        elliptic = (hz.flags == 0) & (((a_e << 1) <= length.as_unsigned()) | (p_e >= p_l))
        a_fits = a_e <= SEMI_AXIS.max_code
        line_fits = (b_c <= SEMI_AXIS.max_code) & (p_l <= PMAX.max_code)
        zero = [self.a.eq(0), self.b.eq(0), self.p_max.eq(0), self.k.eq(0), self.mode.eq(0)]
        with m.If(at(T_SELECT)):
            m.d.sync += [busy.eq(0), t.eq(0), self.done.eq(1), self.done_pulse.eq(1),
                         self.A_min.eq(a_min), self.B_max.eq(b_max), self.scale.eq(n)]
            with m.If(flags != 0):
                m.d.sync += zero + [self.flags.eq(flags), self.scale.eq(0)]
            with m.Elif(elliptic & a_fits):
                m.d.sync += [self.a.eq(a_e), self.b.eq(b_e), self.p_max.eq(p_e),
                             self.k.eq(hz.k), self.mode.eq(LN.MODE_ELLIPTIC),
                             self.flags.eq(0)]
            with m.Elif(elliptic):
                m.d.sync += zero + [self.flags.eq(F.FLAG_OVERFLOW)]
            with m.Elif(s_root == 0):
                m.d.sync += zero + [self.flags.eq(F.FLAG_DIV_ZERO)]
            with m.Elif(~line_fits):
                m.d.sync += zero + [self.flags.eq(F.FLAG_OVERFLOW)]
            with m.Else():
                m.d.sync += [self.a.eq(round_shift(length.as_unsigned(), 1)),
                             self.b.eq(b_c), self.p_max.eq(p_l), self.k.eq(0),
                             self.mode.eq(LN.MODE_LINE), self.flags.eq(0)]
        m.d.comb += self.busy.eq(busy)
        self.probes = {"t": t, "n": n, "QPI": qpi, "Y": y, "P0SQ": p0sq, "S": s_root,
                       "b_l": b_l, "a_e": a_e, "p_e": p_e, "hz_flags": hz.flags,
                       "hz_done": hz.done}
        return m


def convert_verilog(*, name: str = "hertz_line_core",
                    hertz_form: str = F.DEFAULT_HERTZ_FORM) -> str:
    """Verilog of :class:`HertzLineCore` (``strip_internal_attrs=True``)."""
    return verilog.convert(HertzLineCore(hertz_form=hertz_form), name=name,
                           strip_internal_attrs=True)


def simulate_line_core(vectors, *, max_cycles: int = 2 * LN.LINE_CYCLES,
                       hertz_form: str = F.DEFAULT_HERTZ_FORM
                       ) -> tuple[list[LN.LineCodes], list[int]]:
    """Simulate :class:`HertzLineCore` cycle-accurately (Amaranth simulator).

    Parameters
    ----------
    vectors : sequence of (A, B, W, L, e_prime) int codes
        CURVATURE, CURVATURE Q(32,20), LOAD Q(32,8), LINE_LENGTH Q(32,20), E' Q(32,0).
    max_cycles : int, keyword-only
        Give up (RuntimeError) after this many edges without ``done``.
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        Form of the wrapped elliptic core.

    Returns
    -------
    (outputs, cycles)
        :class:`.line.LineCodes` read from the ports (comparable with
        :func:`.line.line_golden`) and the edges from ``go`` to ``done`` per vector
        (``LINE_CYCLES`` = 759 by design). A few evaluations per second of CPU time.
    """
    dut = HertzLineCore(hertz_form=hertz_form)
    cc = CycleCounter(dut)
    outputs, cycles = [], []

    async def bench(ctx):
        for a, b, w, length, e in vectors:
            for port, v in ((dut.A, a), (dut.B, b), (dut.W, w), (dut.L, length),
                            (dut.e_prime, e)):
                ctx.set(port, int(v))
            t_go = await cc.start(ctx, dut.go)
            cycles.append(await cc.wait_done(ctx, dut.done, t_go, max_cycles, "line core"))
            outputs.append(read_record(ctx, dut, LN.LineCodes,
                                       {f: p for p, f in LINE_OUTPUT_PORTS.items()}))

    run_testbench(cc.top, bench)
    return outputs, cycles
