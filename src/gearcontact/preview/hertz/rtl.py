"""Amaranth 0.5 RTL of the serialized stage D, bit- and cycle-exact with :mod:`.golden`.

``HertzCore`` runs the 13-state schedule of :mod:`.schedule` (756 cycles, independent
of the data) over one shared 80-bit restoring divider (:mod:`.rtl_divider`), two
256 x 32 LUT ROMs (POW, CBRT; contents from :mod:`.luts`) with two synchronous read
ports each (nodes i and i + 1), and one shared multiplier for the staged products.
Every arithmetic step is the expression of :mod:`.rtl_datapath` (shared with the
combinational core); this module only sequences them::

    state      cnt    edge action (cnt = cycle inside the state, 0-based)
    CAPTURE    -      go edge: A, B, W, E' -> capture registers
    SORT       0      A_min, B_max = sort(A, B); envelope flags
    DIV_x      0      divider: dividend <= numerator(x)       (operand load)
               1      divider: divisor <= divisor(x), rem <= 0; zero divisor ->
                      FLAG_DIV_ZERO                             (start)
               2..81  80 restoring iterations
               82     quotient write-back (alpha: range check; p_max: outputs, done)
    DIV_R      0 | 1  || POW ROM read (nodes of alpha) | K <= rs(interpolation, 16)
               82     || (hertz_form="exact") EEX read; its interpolation is the E_e
                      dividend loaded at DIV_EE cnt 0 (instead of the constant N5)
    DIV_EE     0      || K2 <= rs(K K, 20)                     (shared multiplier)
    PRODUCT    0..3   T1 = rs(K2 E6, 32) | T2 = rs(T1 R, 18) | T3 = T2 W | W C3
    CBRT       0..2   leading one + range reduction (m, p) | CBRT ROM read |
                      a_w = rs(interpolation, 10 - p)

Flags follow the golden model: the flags register keeps the first failing check
(SORT envelope, then zero divisors and the alpha range in schedule order, then the
output overflow check at the end); a flagged run still takes 756 cycles and reads 0 on
every numeric output except ``A_min``/``B_max``.

Control behaviour
-----------------
* ``go`` is sampled only while idle (``busy`` = 0); a ``go`` (or ``go_chain``) while
  busy is ignored — the running evaluation is neither restarted nor delayed, and its
  operands cannot change (they were captured on the ``go`` edge). A ``go`` with
  nothing meaningful on the inputs (e.g. all zero) simply evaluates them: the envelope
  check flags them (``not_elliptic`` ...) and the run still takes 756 cycles.
* Accepting ``go`` clears ``done``; ``done`` is set on the last edge (756 edges after
  the ``go`` edge, counting the ``go`` edge as edge 1) and stays 1 until the next
  accepted start; ``done_pulse`` is 1 for exactly the first cycle of it. The output
  registers change only on that last edge and hold until the next run completes.
* ``go_chain`` (the C->D chain entry, used by :class:`~gearcontact.preview.chain_rtl.
  ChainCore`): when the inputs are themselves registers (the fit core's curvature
  latch), capture, sort and envelope check happen on the accepting edge, which is
  also DIV_RX's operand-load cycle: the run takes ``HERTZ_CYCLES - 2 = 754`` edges.
  ``go`` wins if both are asserted.
* Synchronous reset (the ``sync`` domain's reset) returns the core to idle at any
  time: busy, done, done_pulse, every register and output go to 0 (ROMs are
  constant); the next ``go`` runs a full, correct evaluation.
"""

from __future__ import annotations

from amaranth import Cat, Module, Signal, signed, unsigned
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.memory import Memory
from amaranth.lib.wiring import In, Out

from ...contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS
from ..simulation import CycleCounter, read_record, run_testbench
from . import formats as F
from .divider import DIVIDER_BITS, DIVIDER_CYCLES, DIVIDER_HANDSHAKE_CYCLES
from .golden import HertzCodes
from .luts import CBRT_SPEC, EE_EXACT_SPEC, LUT_SIZE, LUT_WORD_BITS, POW_SPEC, POW_SPECS, rom_words
from .rtl_datapath import (
    DIVISIONS,
    FLAG_BITS,
    PRODUCTS,
    SCALE_BITS,
    Operands,
    division,
    e6_from_quotient,
    envelope_flags,
    finalize,
    fits,
    lut_interpolate,
    lut_split,
    pow_to_k,
    product_operands,
    product_result,
    range_reduce,
    round_shift,
    scale_cbrt,
    sort_pair,
)
from .rtl_divider import DEN_BITS, SerialDivider
from .schedule import DIVISION_ORDER, HERTZ_CYCLES, STATES

__all__ = [
    "FLAG_BITS",
    "OUTPUT_PORTS",
    "CycleCounter",
    "HertzCore",
    "convert_verilog",
    "read_hertz_codes",
    "simulate_hertz_core",
]

_ST = {s.name: s.index for s in STATES}
_DIV_STATE = dict(zip(DIVISION_ORDER, (s for s in STATES if s.name.startswith("DIV_"))))
_LOAD_CNT = 0                                              # operand (dividend) load
_START_CNT = 1                                             # divisor load, clear, zero test
_WB_CNT = DIVIDER_HANDSHAKE_CYCLES - 1 + DIVIDER_CYCLES    # quotient write-back (82)
_PRODUCT_ORDER = ("t1", "t2", "t3", "wc3")                  # PRODUCT cycles 0..3
assert DIVISIONS == DIVISION_ORDER
assert _WB_CNT == _DIV_STATE["R_x"].cycles - 1
assert STATES[_ST["PRODUCT"]].cycles == len(_PRODUCT_ORDER) and set(PRODUCTS) == \
    set(_PRODUCT_ORDER) | {"k2"}

#: Output ports in :class:`.golden.HertzCodes` field order (``port -> field``).
OUTPUT_PORTS = {"a": "a_code", "b": "b_code", "p_max": "p_max_code", "k": "k_code",
                "A_min": "A_min_code", "B_max": "B_max_code", "R_x": "R_x_code",
                "R_y": "R_y_code", "alpha": "alpha_code", "flags": "flags"}


class HertzCore(wiring.Component):
    """Serialized stage-D core (elliptic Hertz, Hamrock–Brewe), 756 cycles go -> done.

    Parameters
    ----------
    tag_bits : int, keyword-only
        Width of an optional side-band word captured with the operands (``tag_in``)
        and presented with the results (``tag``); 0 (default) omits both ports. The
        C->D chain carries the fit core's flags in it.
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        ROM contents (:data:`.formats.HERTZ_FORMS`). ``"exact"`` doubles the POW ROM
        to 512 words (POWX, exact k, at 0..255; EEX, the exact elliptic term N(alpha),
        at 256..511) read through the same two ports and the same interpolator: the
        EEX nodes are read on the last cycle of DIV_R and their interpolation is the
        E_e dividend loaded on DIV_EE's first cycle instead of the constant N5. Same
        756 cycles, same multipliers; bit-exact with ``hertz_golden(...,
        hertz_form="exact")``.

    Notes
    -----
    Ports (all synchronous to ``sync``; codes as in :class:`.golden.HertzCodes`):

    ==========  =====  ==============  ===============================================
    port        dir    shape           meaning (format)
    ==========  =====  ==============  ===============================================
    A, B        in     signed(32)      half relative curvatures, CURVATURE Q(32,20),
                                       1/mm, any order
    W           in     signed(32)      load, LOAD Q(32,8), N
    e_prime     in     signed(32)      E' = 2E*, E_PRIME Q(32,0), MPa
    go          in     1               start (CAPTURE on this edge); idle only
    go_chain    in     1               start with CAPTURE/SORT absorbed (754 edges)
    tag_in      in     tag_bits        side band, captured at the start (optional)
    busy        out    1               a run is in progress
    done        out    1               results valid (set on the last edge)
    done_pulse  out    1               first cycle of ``done`` only
    a, b        out    signed(32)      semi-axes, SEMI_AXIS Q(32,20), mm
    p_max       out    signed(32)      peak pressure, PMAX Q(32,8), MPa
    k           out    signed(32)      ellipticity a/b, K_OUT Q(32,20)
    A_min       out    signed(32)      min(A, B), CURVATURE Q(32,20), 1/mm
    B_max       out    signed(32)      max(A, B), CURVATURE Q(32,20), 1/mm
    R_x, R_y    out    signed(32)      principal radii, CURVATURE Q(32,20), mm
    alpha       out    unsigned(32)    R_x/R_y, ALPHA UQ(32,24)
    flags       out    7               ``FLAG_*`` of :mod:`.formats` (0 = valid)
    tag         out    tag_bits        the run's ``tag_in`` (optional)
    ==========  =====  ==============  ===============================================
    """

    def __init__(self, *, tag_bits: int = 0, hertz_form: str = F.DEFAULT_HERTZ_FORM):
        self._tag_bits = int(tag_bits)
        self._hertz_form = F.check_hertz_form(hertz_form)
        ports = {"A": In(signed(CURVATURE.bits)), "B": In(signed(CURVATURE.bits)),
                 "W": In(signed(LOAD.bits)), "e_prime": In(signed(F.E_PRIME.bits)),
                 "go": In(1), "go_chain": In(1),
                 "busy": Out(1), "done": Out(1), "done_pulse": Out(1),
                 "a": Out(signed(SEMI_AXIS.bits)), "b": Out(signed(SEMI_AXIS.bits)),
                 "p_max": Out(signed(PMAX.bits)), "k": Out(signed(F.K_OUT.bits)),
                 "A_min": Out(signed(CURVATURE.bits)), "B_max": Out(signed(CURVATURE.bits)),
                 "R_x": Out(signed(CURVATURE.bits)), "R_y": Out(signed(CURVATURE.bits)),
                 "alpha": Out(unsigned(F.ALPHA.bits)), "flags": Out(FLAG_BITS)}
        if self._tag_bits:
            ports.update(tag_in=In(self._tag_bits), tag=Out(self._tag_bits))
        super().__init__(ports)

    def elaborate(self, platform):
        m = Module()
        m.submodules.div = div = SerialDivider()

        # ---- ROMs: two synchronous read ports each (nodes i and i + 1) -------------
        exact = self._hertz_form == "exact"
        pow_words = list(rom_words(POW_SPECS[self._hertz_form]))
        if exact:                                # EEX in the upper half (address bit 8)
            pow_words += rom_words(EE_EXACT_SPEC)
        roms = {}
        for name, words in (("pow", pow_words), ("cbrt", rom_words(CBRT_SPEC))):
            rom = Memory(shape=unsigned(LUT_WORD_BITS), depth=len(words), init=list(words))
            m.submodules[f"{name}_rom"] = rom
            roms[name] = (rom.read_port(), rom.read_port())

        # ---- control and datapath registers (named after the golden intermediates) --
        busy = Signal()
        state = Signal(range(len(STATES)))
        cnt = Signal(range(_WB_CNT + 1))
        cap_a = Signal(signed(CURVATURE.bits))
        cap_b = Signal(signed(CURVATURE.bits))
        tag = Signal(max(self._tag_bits, 1))
        ops = Operands(
            a_min=Signal(signed(CURVATURE.bits), name="a_min"),
            b_max=Signal(signed(CURVATURE.bits), name="b_max"),
            w=Signal(signed(LOAD.bits), name="w"),
            e_prime=Signal(signed(F.E_PRIME.bits), name="e_prime_reg"),
            alpha=Signal(F.ALPHA.bits, name="alpha_reg"),
            radius=Signal(F.RADIUS.bits, name="radius"),
            k=Signal(F.K_INT.bits, name="k_int"), k2=Signal(F.K2.bits, name="k2"),
            e6=Signal(F.E6.bits, name="e6"), t1=Signal(F.T1.bits, name="t1"),
            t2=Signal(F.T2.bits, name="t2"), t3=Signal(F.T3.bits, name="t3"),
            wc3=Signal(F.T3.bits, name="wc3"), a_w=Signal(F.AXIS_W.bits, name="a_w"),
            b_w=Signal(F.AXIS_W.bits, name="b_w"), p_n2=Signal(F.PN2.bits, name="p_n2"))
        # POW interpolation (units 2^-40); with the exact form also the E_e dividend
        pow_interp = Signal(POW_SPEC.vbits + POW_SPEC.tbits)
        if exact:
            ops.n_ee = pow_interp
        flags = Signal(FLAG_BITS)
        ovf = Signal()                         # R_x or R_y does not fit CURVATURE
        r_x = Signal(CURVATURE.bits)
        r_y = Signal(CURVATURE.bits)
        c_a = Signal(F.CA.bits)
        m_red = Signal(F.M_RED.bits)
        s1 = Signal(SCALE_BITS)

        def in_state(name):
            return busy & (state == _ST[name])

        # ---- start: CAPTURE (go) or the chain entry (go_chain) ---------------------
        start_go = ~busy & self.go
        start_chain = ~busy & ~self.go & self.go_chain
        # (separate comb blocks below keep the simulator from re-evaluating logic
        # whose inputs did not change: only the small control block sees cnt)
        m.submodules.sort = ms = Module()
        src_a = Signal.like(cap_a)
        src_b = Signal.like(cap_b)
        src_w = Signal.like(ops.w)
        src_e = Signal.like(ops.e_prime)
        ms.d.comb += [src_a.eq(cap_a), src_b.eq(cap_b), src_w.eq(ops.w),
                      src_e.eq(ops.e_prime)]
        with ms.If(~busy):                      # chain entry: straight from the ports
            ms.d.comb += [src_a.eq(self.A), src_b.eq(self.B), src_w.eq(self.W),
                          src_e.eq(self.e_prime)]
        s_min, s_max, sort_flags = (Signal.like(cap_a), Signal.like(cap_b),
                                    Signal(FLAG_BITS))
        s_min_e, s_max_e = sort_pair(src_a, src_b)
        ms.d.comb += [s_min.eq(s_min_e), s_max.eq(s_max_e),
                      sort_flags.eq(envelope_flags(s_min, s_max, src_w, src_e))]
        sort_regs = [ops.a_min.eq(s_min), ops.b_max.eq(s_max), flags.eq(sort_flags)]

        m.d.sync += self.done_pulse.eq(0)
        with m.If(start_go | start_chain):
            m.d.sync += [busy.eq(1), self.done.eq(0), ovf.eq(0), cnt.eq(0),
                         ops.w.eq(self.W), ops.e_prime.eq(self.e_prime)]
            if self._tag_bits:
                m.d.sync += tag.eq(self.tag_in)
        with m.If(start_go):
            m.d.sync += [cap_a.eq(self.A), cap_b.eq(self.B), state.eq(_ST["SORT"]),
                         flags.eq(0)]
        with m.If(start_chain):
            m.d.sync += sort_regs + [state.eq(_ST["DIV_RX"]), cnt.eq(_LOAD_CNT + 1)]

        # ---- sequencing: cnt counts the cycles of each state ------------------------
        m.submodules.last = ml = Module()
        last = Signal.like(cnt)
        with ml.Switch(state):
            for s in STATES:
                with ml.Case(s.index):
                    ml.d.comb += last.eq(s.cycles - 1)
        with m.If(busy):
            with m.If(cnt == last):
                m.d.sync += [cnt.eq(0), state.eq(state + 1)]
            with m.Else():
                m.d.sync += cnt.eq(cnt + 1)
        with m.If(in_state("SORT")):
            m.d.sync += sort_regs

        # ---- the shared divider -----------------------------------------------------
        m.submodules.operands = mo = Module()
        is_div = Signal()
        num_st = Signal(DIVIDER_BITS)
        den = Signal(DEN_BITS)
        with mo.Switch(state):
            for name, st in _DIV_STATE.items():
                with mo.Case(st.index):
                    n_expr, d_expr = division(name, ops)
                    mo.d.comb += [is_div.eq(1), num_st.eq(n_expr), den.eq(d_expr)]
        num = Signal(DIVIDER_BITS)
        m.d.comb += num.eq(num_st)
        with m.If(start_chain):                  # DIV_RX operand load on the entry edge
            m.d.comb += num.eq(division("R_x", ops)[0])
        dividing = busy & is_div
        m.d.comb += [div.num.eq(num), div.den.eq(den),
                     div.load.eq((dividing & (cnt == _LOAD_CNT)) | start_chain),
                     div.start.eq(dividing & (cnt == _START_CNT)),
                     div.step.eq(dividing & (cnt > _START_CNT) & (cnt < _WB_CNT))]
        with m.If(div.start & (flags == 0) & (den == 0)):
            m.d.sync += flags.eq(F.FLAG_DIV_ZERO)
        q = div.quotient
        wb = {name: in_state(st.name) & (cnt == _WB_CNT) for name, st in _DIV_STATE.items()}

        radius_q = round_shift(q, 1)             # R_x, R_y = rs(2^40 // curvature, 1)
        with m.If(wb["R_x"]):
            m.d.sync += [r_x.eq(radius_q), ovf.eq(ovf | ~fits(radius_q, CURVATURE))]
        with m.If(wb["R_y"]):
            m.d.sync += [r_y.eq(radius_q), ovf.eq(ovf | ~fits(radius_q, CURVATURE))]
        with m.If(wb["alpha"]):
            m.d.sync += ops.alpha.eq(q)
            with m.If((flags == 0) & (q > F.ALPHA_MAX_CODE)):
                m.d.sync += flags.eq(F.FLAG_ALPHA_RANGE)
        with m.If(wb["R"]):
            m.d.sync += ops.radius.eq(q)
        with m.If(wb["E_e"]):
            m.d.sync += ops.e6.eq(e6_from_quotient(q))
        with m.If(wb["C_a"]):
            m.d.sync += c_a.eq(q)
        with m.If(wb["b"]):
            m.d.sync += ops.b_w.eq(q)
        with m.If(wb["p_n2"]):
            m.d.sync += ops.p_n2.eq(q)

        # ---- POW LUT || DIV_R: k ------------------------------------------------------
        # (POW, POWX and EEX share one geometry: luts.same_geometry)
        pow0, pow1 = roms["pow"]
        m.submodules.pow_addr = mp = Module()
        p_addr, p_next, p_r = lut_split(POW_SPEC, ops.alpha)
        mp.d.comb += pow_interp.eq(lut_interpolate(POW_SPEC, pow0.data, pow1.data, p_r))
        pow_en = in_state("DIV_R") & (cnt == 0)
        if exact:                 # EEX nodes on DIV_R's last cycle, dividend of DIV_EE
            ee_read = in_state("DIV_R") & (cnt == _WB_CNT)
            pow_en = pow_en | ee_read
            mp.d.comb += [pow0.addr.eq(Cat(p_addr, ee_read)),
                          pow1.addr.eq(Cat(p_next, ee_read))]
        else:
            mp.d.comb += [pow0.addr.eq(p_addr), pow1.addr.eq(p_next)]
        m.d.comb += [pow0.en.eq(pow_en), pow1.en.eq(pow0.en)]
        with m.If(in_state("DIV_R") & (cnt == 1)):
            m.d.sync += ops.k.eq(pow_to_k(pow_interp))

        # ---- the shared multiplier: K2 || DIV_EE, then PRODUCT ------------------------
        op_x = Signal(max(len(product_operands(s, ops)[0]) for s in PRODUCTS))
        op_y = Signal(max(len(product_operands(s, ops)[1]) for s in PRODUCTS))
        prod = Signal(F.T3.bits)                 # every product < 2^64 (golden asserts)
        m.d.comb += prod.eq(op_x * op_y)
        dests = {"k2": ops.k2, "t1": ops.t1, "t2": ops.t2, "t3": ops.t3, "wc3": ops.wc3}
        steps = [("k2", in_state("DIV_EE") & (cnt == 0))]
        steps += [(s, in_state("PRODUCT") & (cnt == i)) for i, s in enumerate(_PRODUCT_ORDER)]
        for step, when in steps:
            x, y = product_operands(step, ops)
            with m.If(when):
                m.d.comb += [op_x.eq(x), op_y.eq(y)]
                m.d.sync += dests[step].eq(product_result(step, prod))

        # ---- CBRT: range reduction | ROM read | interpolation + scaling ---------------
        m.submodules.range_reduce = mr = Module()
        m_new, s1_new = range_reduce(mr, c_a, name="rr")
        with m.If(in_state("CBRT") & (cnt == 0)):
            m.d.sync += [m_red.eq(m_new), s1.eq(s1_new)]
        cb0, cb1 = roms["cbrt"]
        m.submodules.cbrt_addr = mc = Module()
        c_addr, c_next, c_r = lut_split(CBRT_SPEC, m_red)
        mc.d.comb += [cb0.addr.eq(c_addr), cb1.addr.eq(c_next)]
        m.d.comb += [cb0.en.eq(in_state("CBRT") & (cnt == 1)), cb1.en.eq(cb0.en)]
        with m.If(in_state("CBRT") & (cnt == 2)):
            m.d.sync += ops.a_w.eq(scale_cbrt(lut_interpolate(CBRT_SPEC, cb0.data,
                                                              cb1.data, c_r), s1))

        # ---- last edge: outputs, flags, done --------------------------------------------
        flags_out, outs = finalize(flags, ovf, a_w=ops.a_w, b_w=ops.b_w, k=ops.k,
                                   r_x=r_x, r_y=r_y, alpha=ops.alpha, p_max_q=q)
        with m.If(wb["p_max"]):
            m.d.sync += [busy.eq(0), state.eq(0), self.done.eq(1), self.done_pulse.eq(1),
                         self.flags.eq(flags_out), self.A_min.eq(ops.a_min),
                         self.B_max.eq(ops.b_max)]
            m.d.sync += [getattr(self, port).eq(v) for port, v in outs.items()]
            if self._tag_bits:
                m.d.sync += self.tag.eq(tag)
        m.d.comb += self.busy.eq(busy)
        #: Internal registers by golden-trace name (:func:`.golden.hertz_golden_trace`),
        #: for simulation checks; set on elaboration. ``s1`` holds ``9 - p``.
        self.probes = {"A_min": ops.a_min, "B_max": ops.b_max, "flags": flags,
                       "R_x": r_x, "R_y": r_y, "alpha": ops.alpha, "R": ops.radius,
                       "K": ops.k, "E6": ops.e6, "K2": ops.k2, "T1": ops.t1, "T2": ops.t2,
                       "T3": ops.t3, "WC3": ops.wc3, "C_a": c_a, "m": m_red, "s1": s1,
                       "a_w": ops.a_w, "b_w": ops.b_w, "p_n2": ops.p_n2, "state": state,
                       "cnt": cnt, "div_load": div.load, "div_start": div.start,
                       "div_num": num, "div_den": den, "quotient": q,
                       "pow_interp": pow_interp}
        return m


def convert_verilog(*, name: str = "hertz_core", tag_bits: int = 0,
                    hertz_form: str = F.DEFAULT_HERTZ_FORM) -> str:
    """Verilog of :class:`HertzCore` (``strip_internal_attrs=True``)."""
    return verilog.convert(HertzCore(tag_bits=tag_bits, hertz_form=hertz_form), name=name,
                           strip_internal_attrs=True)


def read_hertz_codes(ctx, dut) -> HertzCodes:
    """The output ports of a :class:`HertzCore` (or a core with the same port names) as
    :class:`.golden.HertzCodes` (inside an Amaranth testbench)."""
    return read_record(ctx, dut, HertzCodes, {f: p for p, f in OUTPUT_PORTS.items()})


def _check_vectors(vectors):
    import numpy as np

    from ...contract.qformat import CURVATURE as Cv
    rows = np.asarray(vectors, dtype=object)
    if rows.ndim != 2 or rows.shape[1] != 4:
        from ...validation import InputRangeError
        raise InputRangeError("vectors.shape", rows.shape, "(n, 4): A, B, W, E' codes")
    fmts = (("A_code", Cv), ("B_code", Cv), ("W_code", LOAD), ("e_prime_code", F.E_PRIME))
    return [tuple(int(fmt.check(int(x), field=f"vectors[{i}].{f}"))
                  for x, (f, fmt) in zip(row, fmts)) for i, row in enumerate(rows)]


def simulate_hertz_core(vectors, *, max_cycles: int = 2 * HERTZ_CYCLES,
                        hertz_form: str = F.DEFAULT_HERTZ_FORM
                        ) -> tuple[list[HertzCodes], list[int]]:
    """Simulate :class:`HertzCore` cycle-accurately (Amaranth simulator).

    For each vector: drive A, B, W, E', assert ``go`` for one cycle and count clock
    edges (the ``go`` edge is edge 1) until ``done`` reads 1.

    Parameters
    ----------
    vectors : array_like of int, shape (n, 4)
        ``(A_code, B_code, W_code, e_prime_code)`` rows: CURVATURE Q(32,20), CURVATURE
        Q(32,20), LOAD Q(32,8), E_PRIME Q(32,0) (each must fit its 32-bit register).
    max_cycles : int, keyword-only
        Give up (RuntimeError) if ``done`` has not risen after this many edges.
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        ROM contents of the simulated core (:class:`HertzCore`).

    Returns
    -------
    (outputs, cycles)
        ``outputs``: list of :class:`.golden.HertzCodes` read from the ports, directly
        comparable with :func:`.golden.hertz_golden`; ``cycles``: edges from ``go`` to
        ``done`` per vector (``HERTZ_CYCLES`` = 756 by design).

    Notes
    -----
    Amaranth's Python simulator runs this core at ~15k edges/s of CPU time (~20
    evaluations/s; the bare serial divider alone: ~20k edges/s) plus ~1 s to elaborate;
    bulk sweeps belong in Verilator on :func:`convert_verilog`'s output.
    """
    rows = _check_vectors(vectors)
    dut = HertzCore(hertz_form=hertz_form)
    cc = CycleCounter(dut)
    outputs, cycles = [], []

    async def bench(ctx):
        for a, b, w, e in rows:
            for port, v in ((dut.A, a), (dut.B, b), (dut.W, w), (dut.e_prime, e)):
                ctx.set(port, v)
            t_go = await cc.start(ctx, dut.go)
            cycles.append(await cc.wait_done(ctx, dut.done, t_go, max_cycles,
                                             "hertz core"))
            outputs.append(read_hertz_codes(ctx, dut))

    run_testbench(cc.top, bench)
    return outputs, cycles
