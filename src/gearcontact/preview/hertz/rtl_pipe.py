"""Amaranth RTL of stage D with initiation interval 1: one Hertz preview per clock.

``HertzPipe`` computes exactly what :func:`.golden.hertz_golden` computes (the same
expressions of :mod:`.rtl_datapath`, the same exact floor quotients), so its outputs are
the golden outputs bit for bit; no golden variant is needed. What changes is the
schedule: the nine divisions of the shared 80-bit divider are unrolled into restoring
array dividers (:func:`.rtl_divider.restoring_step`, one row per dividend bit) cut into
pipeline stages of ``rows_per_stage`` rows, and every value an evaluation still needs
travels with it from stage to stage. A new input set is accepted on every clock::

    stage(s)                 what it registers (R = rows_per_stage)
    1                        CAPTURE: A, B, W, E' (and the tag)
    ceil(56 / R)             sort, envelope flags; R_x, R_y, alpha, R (4 dividers)
    1                        R_x/R_y rounding, alpha range; POW (and EEX) ROM +
                             interpolation: K (and the exact E_e dividend); W C3
    ceil(n_E / R)            E_e = N5 // alpha (n_E = 50 rows, 54 exact) || K2 = rs(K K)
    3                        T1 = rs(K2 E6), T2 = rs(T1 R), T3 = T2 W
    ceil(75 / R)             C_a = (T3 << 11) // E'
    2                        range reduction (m, p) | CBRT ROM + interpolation: a_w
    ceil(80 / R)             b = (a_w << 24) // K  ||  p_n2 = (W C3 << 16) // a_w
    ceil(64 / R)             p_max = (p_n2 << 17) // b_w
    1                        outputs, flags (finalize), ``out_valid``

Row counts are the dividend widths; a constant dividend (2^40, 2^42, N5) starts at its
leading one (the rows above it only shift zeros while the divisor is non-zero, and a
zero divisor is flagged). Latency (:func:`pipe_latency`): 90 edges at ``R = 4``,
``hertz_form="hamrock-brewe"`` (91 exact; 333 and 57 at R = 1 and 7), from the accepting edge (edge 1) to the
edge after which ``out_valid`` reads 1.

Flags are recorded in the golden order (envelope, then zero divisors and the alpha
range in division order, then the output overflow), as in the combinational core.

Stream interface (valid/ready, one global stall)
------------------------------------------------
* ``in_valid``/``in_ready``: an input set (``A``, ``B``, ``W``, ``e_prime``,
  ``tag_in``) is accepted on an edge where both are 1.
* ``out_valid``/``out_ready``: the output ports hold one result while ``out_valid``;
  it is consumed on an edge where both are 1. Results leave in input order.
* The pipeline advances as a whole when ``en = ~out_valid | out_ready``, and
  ``in_ready = en``. With ``out_ready`` held at 1 it accepts one input per clock
  (II = 1) and every result appears exactly :func:`pipe_latency` edges after its
  input; a cycle with ``out_valid & ~out_ready`` stalls every stage (the result is
  held, nothing is accepted) and delays the results in flight by one edge each.
  Bubbles (cycles without ``in_valid``) travel as invalid stages and are not squeezed
  out by a stall.
* Synchronous reset empties the pipeline (every valid bit 0).

Resources (Debian yosys 0.23 ``synth_xilinx -family xc7 -noiopad``, DSP mode, R = 4):
45,565 LUT, 10,351 FF + 1,446 SRL, 6,195 CARRY4, 36 DSP48E1, no BRAM, logic depth 121
cells -- against 2,650 LUT / 1,428 FF / 20 DSP48E1 / depth 44 for the serialized core
with the same tool (docs/architecture.md).

References
----------
B. Parhami, *Computer Arithmetic*, 2nd ed., Oxford University Press, 2010, sec. 13.1
and ch. 16 (restoring division, array dividers and their pipelining).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from amaranth import Cat, Const, Module, Signal, signed, unsigned
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.memory import Memory
from amaranth.lib.wiring import In, Out

from ...validation import InputRangeError
from ...contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS
from . import formats as F
from . import rtl_datapath as dp
from .luts import CBRT_SPEC, EE_DIVIDEND_SHIFT, EE_EXACT_SPEC, LUT_SIZE, LUT_WORD_BITS, POW_SPEC, POW_SPECS, rom_words
from .rtl_pipeline import Pipeline, PipelinedDivision, run_division_phase

__all__ = ["HertzPipe", "DEFAULT_ROWS_PER_STAGE", "INITIATION_INTERVAL", "pipe_latency",
           "division_rows", "convert_verilog", "simulate_hertz_pipe", "PipeRun"]

#: Divider rows (dividend bits) per pipeline stage by default.
DEFAULT_ROWS_PER_STAGE = 4
#: One input set accepted per clock.
INITIATION_INTERVAL = 1
_ROWS_RANGE = (1, 16)
#: Stages that hold no divider rows: capture, LUT/rounding, T1, T2, T3, range
#: reduction, CBRT, output.
_FIXED_STAGES = 8
#: The division phases in pipeline order; divisions of one phase run side by side.
_PHASES = (("R_x", "R_y", "alpha", "R"), ("E_e",), ("C_a",), ("b", "p_n2"), ("p_max",))
#: Width of the POW/EEX interpolation register (units 2^-40), as in the serialized core.
_INTERP_BITS = POW_SPEC.vbits + POW_SPEC.tbits


def _check_rows(rows_per_stage) -> int:
    if isinstance(rows_per_stage, bool) or not isinstance(rows_per_stage, int) \
            or not _ROWS_RANGE[0] <= rows_per_stage <= _ROWS_RANGE[1]:
        raise InputRangeError("rows_per_stage", rows_per_stage,
                              f"an integer in [{_ROWS_RANGE[0]}, {_ROWS_RANGE[1]}]")
    return rows_per_stage


def _dividend(name: str, ops: dp.Operands):
    """``(dividend, rows)`` of division ``name`` (:func:`.rtl_datapath.division`).

    The dividend is a Python int for a constant one, else ``(register, shift)`` with
    dividend = register << shift (so the shifted-in zeros never occupy pipeline
    registers); ``rows`` is the constant's leading-one position + 1, else the width
    of the shifted register.
    """
    num, _ = dp.division(name, ops)
    if isinstance(num, Const):
        return num.value, num.value.bit_length()
    reg, shift = dp.DIVIDEND_SHIFTS[name]
    if reg == "N5":                                  # the exact form's table dividend
        base, shift = ops.n_ee.as_unsigned(), EE_DIVIDEND_SHIFT
    else:
        base = getattr(ops, reg).as_unsigned()
    assert len(base) + shift == len(num), (name, len(base), shift, len(num))
    return (base, shift), len(num)


def division_rows(hertz_form: str = F.DEFAULT_HERTZ_FORM) -> dict[str, int]:
    """Rows (dividend bits) of each unrolled division, ``{name: rows}``."""
    F.check_hertz_form(hertz_form)
    ops = _format_operands(hertz_form)
    return {name: _dividend(name, ops)[1] for phase in _PHASES for name in phase}


def _format_operands(hertz_form: str) -> dp.Operands:
    """Operands of the register formats (for widths only)."""
    s = {"a_min": signed(CURVATURE.bits), "b_max": signed(CURVATURE.bits),
         "w": signed(LOAD.bits), "e_prime": signed(F.E_PRIME.bits), "alpha": F.ALPHA.bits,
         "k": F.K_INT.bits, "t3": F.T3.bits, "wc3": F.T3.bits, "a_w": F.AXIS_W.bits,
         "b_w": F.AXIS_W.bits, "p_n2": F.PN2.bits}
    ops = dp.Operands(**{k: Signal(v, name=k) for k, v in s.items()})
    if hertz_form == "exact":
        ops.n_ee = Signal(_INTERP_BITS, name="n_ee")
    return ops


def pipe_latency(rows_per_stage: int = DEFAULT_ROWS_PER_STAGE, *,
                 hertz_form: str = F.DEFAULT_HERTZ_FORM) -> int:
    """Edges from the accepting edge (edge 1) to the one after which ``out_valid`` reads
    1, without stalls (the module docstring's table)."""
    r = _check_rows(rows_per_stage)
    rows = division_rows(hertz_form)
    return _FIXED_STAGES + sum(math.ceil(max(rows[n] for n in ph) / r) for ph in _PHASES)


#: Bit of FLAG_OVERFLOW: raised only by the output stage, so the flags word travels down
#: the pipeline without it (a constant bit through every stage is only work for the
#: synthesis tool).
_OVF_BIT = F.FLAG_OVERFLOW.bit_length() - 1


def _pack_flags(word):
    """The flags word without the overflow bit (``FLAG_BITS - 1`` bits)."""
    return Cat(word[:_OVF_BIT], word[_OVF_BIT + 1:])


def _unpack_flags(packed):
    """The ``FLAG_BITS`` word of a packed one (overflow bit 0)."""
    return Cat(packed[:_OVF_BIT], Const(0, 1), packed[_OVF_BIT:])


def _first_flag(packed, checks):
    """Keep the (packed) flags if set, else the first ``(cond, FLAG)`` that holds, else
    0 (the golden model's priority); packed result."""
    from amaranth import Mux
    out = Const(0, dp.FLAG_BITS)
    for cond, flag in reversed(checks):
        assert flag != F.FLAG_OVERFLOW
        out = Mux(cond, flag, out)
    return _pack_flags(Mux(packed != 0, _unpack_flags(packed), out))


class HertzPipe(wiring.Component):
    """Stage D with initiation interval 1 (module docstring), bit-exact with
    :func:`.golden.hertz_golden`.

    Parameters
    ----------
    rows_per_stage : int, keyword-only
        Divider rows between pipeline registers, 1..16 (default 4): fewer rows, shorter
        logic paths, more stages and flip-flops.
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        Table contents (:data:`.formats.HERTZ_FORMS`); the exact form adds the EEX ROM
        (its own read-port pair) and its dividend's rows.
    tag_bits : int, keyword-only
        Width of a side-band word carried with each input set (``tag_in`` -> ``tag``);
        0 omits both ports.

    Notes
    -----
    Ports (``sync`` domain): inputs ``A``, ``B`` (CURVATURE Q(32,20), 1/mm), ``W``
    (LOAD Q(32,8), N), ``e_prime`` (E_PRIME Q(32,0), MPa), ``in_valid``, ``out_ready``,
    ``tag_in``; outputs ``in_ready``, ``out_valid`` and the result ports of
    :class:`.rtl.HertzCore` with the same shapes and meaning (``a``, ``b``, ``p_max``,
    ``k``, ``A_min``, ``B_max``, ``R_x``, ``R_y``, ``alpha``, ``flags``, ``tag``).
    """

    def __init__(self, *, rows_per_stage: int = DEFAULT_ROWS_PER_STAGE,
                 hertz_form: str = F.DEFAULT_HERTZ_FORM, tag_bits: int = 0):
        try:
            self._rows = _check_rows(rows_per_stage)
            self._hertz_form = F.check_hertz_form(hertz_form)
        except InputRangeError:
            self._MustUse__silence = True     # never built: no "created but never used"
            raise
        self._tag_bits = int(tag_bits)
        ports = {"A": In(signed(CURVATURE.bits)), "B": In(signed(CURVATURE.bits)),
                 "W": In(signed(LOAD.bits)), "e_prime": In(signed(F.E_PRIME.bits)),
                 "in_valid": In(1), "in_ready": Out(1), "out_valid": Out(1),
                 "out_ready": In(1),
                 "a": Out(signed(SEMI_AXIS.bits)), "b": Out(signed(SEMI_AXIS.bits)),
                 "p_max": Out(signed(PMAX.bits)), "k": Out(signed(F.K_OUT.bits)),
                 "A_min": Out(signed(CURVATURE.bits)), "B_max": Out(signed(CURVATURE.bits)),
                 "R_x": Out(signed(CURVATURE.bits)), "R_y": Out(signed(CURVATURE.bits)),
                 "alpha": Out(unsigned(F.ALPHA.bits)), "flags": Out(dp.FLAG_BITS)}
        if self._tag_bits:
            ports.update(tag_in=In(self._tag_bits), tag=Out(self._tag_bits))
        super().__init__(ports)

    @property
    def latency(self) -> int:
        """Edges from acceptance to ``out_valid`` without stalls (:func:`pipe_latency`)."""
        return pipe_latency(self._rows, hertz_form=self._hertz_form)

    def elaborate(self, platform):
        m = Module()
        r = self._rows
        exact = self._hertz_form == "exact"
        en = Signal()
        pipe = Pipeline(m, en)
        lv = pipe.live

        def rom_pair(spec, name):
            words = rom_words(spec)
            rom = Memory(shape=unsigned(LUT_WORD_BITS), depth=LUT_SIZE, init=list(words))
            m.submodules[f"{name}_rom"] = rom
            return rom.read_port(domain="comb"), rom.read_port(domain="comb")

        def ops(**kw) -> dp.Operands:
            # the live registers named after the golden intermediates, plus overrides
            live = {f: pipe.live.get(f) for f in dp.Operands.__dataclass_fields__}
            return dp.Operands(**{**live, **kw})

        # ---- 1: CAPTURE ---------------------------------------------------------------
        lv.update(valid=self.in_valid, a_in=self.A, b_in=self.B, w=self.W,
                  e_prime=self.e_prime)
        if self._tag_bits:
            lv["tag"] = self.tag_in
        pipe.stage()

        # ---- sort, envelope; R_x, R_y, alpha, R ------------------------------------
        lv = pipe.live
        lo, hi = dp.sort_pair(lv["a_in"], lv["b_in"])
        a_min = pipe.comb("a_min", lo, signed(CURVATURE.bits))
        b_max = pipe.comb("b_max", hi, signed(CURVATURE.bits))
        pipe.drop("a_in", "b_in")
        lv.update(a_min=a_min, b_max=b_max,
                  flags=pipe.comb("env", _pack_flags(dp.envelope_flags(
                      a_min, b_max, lv["w"], lv["e_prime"])), dp.FLAG_BITS - 1),
                  ab_sum=pipe.comb("ab_sum", a_min.as_unsigned() + b_max.as_unsigned(),
                                   CURVATURE.bits + 1))
        o = ops(a_min=a_min, b_max=b_max)
        divs = {}
        for name in _PHASES[0]:
            num, rows = _dividend(name, o)
            divs[name] = PipelinedDivision(pipe, name, num, rows, dp.DIVISORS[name].replace(
                "a_min+b_max", "ab_sum"))
        run_division_phase(pipe, list(divs.values()), r)

        # ---- rounding, alpha range, POW (EEX) interpolation, W C3 ----------------------
        lv = pipe.live
        q = {n: divs[n].quotient(pipe) for n in _PHASES[0]}
        rx = pipe.comb("R_x", dp.round_shift(q["R_x"], 1), CURVATURE.bits)
        ry = pipe.comb("R_y", dp.round_shift(q["R_y"], 1), CURVATURE.bits)
        alpha = pipe.comb("alpha", q["alpha"], F.ALPHA.bits)
        lv.update(flags=_first_flag(lv["flags"], [
            (lv["a_min"] == 0, F.FLAG_DIV_ZERO), (lv["b_max"] == 0, F.FLAG_DIV_ZERO),
            (lv["a_min"] == 0, F.FLAG_DIV_ZERO),
            (q["alpha"] > F.ALPHA_MAX_CODE, F.FLAG_ALPHA_RANGE),
            (lv["ab_sum"] == 0, F.FLAG_DIV_ZERO)]),
            ovf=~dp.fits(rx, CURVATURE) | ~dp.fits(ry, CURVATURE),
            r_x=rx, r_y=ry, alpha=alpha, radius=pipe.comb("R", q["R"], F.RADIUS.bits))
        pipe.drop("ab_sum")
        p_addr, p_next, p_r = dp.lut_split(POW_SPEC, alpha)
        pow0, pow1 = rom_pair(POW_SPECS[self._hertz_form], "pow")
        pipe.sub.d.comb += [pow0.addr.eq(p_addr), pow1.addr.eq(p_next)]
        lv["k"] = pipe.comb("K", dp.pow_to_k(dp.lut_interpolate(POW_SPEC, pow0.data,
                                                                pow1.data, p_r)), F.K_INT.bits)
        if exact:
            ee0, ee1 = rom_pair(EE_EXACT_SPEC, "eex")
            pipe.sub.d.comb += [ee0.addr.eq(p_addr), ee1.addr.eq(p_next)]
            lv["n_ee"] = pipe.comb("n_ee", dp.lut_interpolate(EE_EXACT_SPEC, ee0.data,
                                                              ee1.data, p_r), _INTERP_BITS)
        x, y = dp.product_operands("wc3", ops(w=lv["w"]))
        lv["wc3"] = pipe.comb("wc3", dp.product_result("wc3", x * y), F.T3.bits)
        pipe.stage()

        # ---- E_e || K2 -------------------------------------------------------------------
        lv = pipe.live
        num, rows = _dividend("E_e", ops(n_ee=lv.get("n_ee")))
        d_ee = PipelinedDivision(pipe, "E_e", num, rows, "alpha")
        if exact:
            pipe.drop("n_ee")
        x, y = dp.product_operands("k2", ops(k=lv["k"]))
        lv["k2"] = pipe.comb("K2", dp.product_result("k2", x * y), F.K2.bits)
        lv["flags"] = _first_flag(lv["flags"], [(lv["alpha"] == 0, F.FLAG_DIV_ZERO)])
        run_division_phase(pipe, [d_ee], r)

        # ---- T1, T2, T3 --------------------------------------------------------------------
        lv = pipe.live
        lv["e6"] = pipe.comb("E6", dp.e6_from_quotient(d_ee.quotient(pipe)), F.E6.bits)
        for step, fmt, used in (("t1", F.T1, ("k2", "e6")), ("t2", F.T2, ("radius",)),
                                ("t3", F.T3, ("w",))):
            lv = pipe.live
            o = ops(k2=lv.get("k2"), e6=lv.get("e6"), t1=lv.get("t1"), t2=lv.get("t2"),
                    radius=lv.get("radius"), w=lv.get("w"))
            x, y = dp.product_operands(step, o)
            lv[step] = pipe.comb(step.upper(), dp.product_result(step, x * y), fmt.bits)
            pipe.drop(*used, *(("t1",) if step == "t2" else ("t2",) if step == "t3" else ()))
            pipe.stage()

        # ---- C_a ---------------------------------------------------------------------------
        lv = pipe.live
        num, rows = _dividend("C_a", ops(t3=lv["t3"]))
        d_ca = PipelinedDivision(pipe, "C_a", num, rows, "e_prime")
        pipe.drop("t3")
        lv["flags"] = _first_flag(lv["flags"], [(lv["e_prime"] == 0, F.FLAG_DIV_ZERO)])
        run_division_phase(pipe, [d_ca], r)

        # ---- range reduction | CBRT ----------------------------------------------------
        lv = pipe.live
        pipe.drop("e_prime")
        m_red, s1 = dp.range_reduce(pipe.sub, d_ca.quotient(pipe)[:F.CA.bits], name="rr")
        lv.update(m_red=m_red, s1=s1)
        pipe.stage()
        lv = pipe.live
        cb0, cb1 = rom_pair(CBRT_SPEC, "cbrt")
        c_addr, c_next, c_r = dp.lut_split(CBRT_SPEC, lv["m_red"])
        pipe.sub.d.comb += [cb0.addr.eq(c_addr), cb1.addr.eq(c_next)]
        lv["a_w"] = pipe.comb("a_w", dp.scale_cbrt(dp.lut_interpolate(
            CBRT_SPEC, cb0.data, cb1.data, c_r), lv["s1"]), F.AXIS_W.bits)
        pipe.drop("m_red", "s1")
        pipe.stage()

        # ---- b || p_n2, then p_max ----------------------------------------------------
        lv = pipe.live
        o = ops(a_w=lv["a_w"], wc3=lv["wc3"])
        d_b = PipelinedDivision(pipe, "b", *_dividend("b", o), "k")
        d_pn2 = PipelinedDivision(pipe, "p_n2", *_dividend("p_n2", o), "a_w")
        pipe.drop("wc3")
        lv["flags"] = _first_flag(lv["flags"], [(lv["k"] == 0, F.FLAG_DIV_ZERO),
                                                (lv["a_w"] == 0, F.FLAG_DIV_ZERO)])
        run_division_phase(pipe, [d_b, d_pn2], r)
        lv = pipe.live
        lv["b_w"] = pipe.comb("b_w", d_b.quotient(pipe), F.AXIS_W.bits)
        p_n2 = pipe.comb("p_n2", d_pn2.quotient(pipe), F.PN2.bits)
        d_pmax = PipelinedDivision(pipe, "p_max", *_dividend("p_max", ops(p_n2=p_n2)), "b_w")
        lv["flags"] = _first_flag(lv["flags"], [(lv["b_w"] == 0, F.FLAG_DIV_ZERO)])
        run_division_phase(pipe, [d_pmax], r)

        # ---- outputs -------------------------------------------------------------------
        lv = pipe.live
        flags_out, outs = dp.finalize(_unpack_flags(lv["flags"]), lv["ovf"], a_w=lv["a_w"], b_w=lv["b_w"],
                                      k=lv["k"], r_x=lv["r_x"], r_y=lv["r_y"],
                                      alpha=lv["alpha"], p_max_q=d_pmax.quotient(pipe))
        final = {"valid": lv["valid"], "flags": flags_out, "A_min": lv["a_min"],
                 "B_max": lv["b_max"], **outs}
        if self._tag_bits:
            final["tag"] = lv["tag"]
        pipe.live = {k: pipe.comb(f"out_{k}", v, 1 if k == "valid" else getattr(self, k).shape())
                     for k, v in final.items()}
        pipe.stage()
        assert pipe.depth == self.latency, (pipe.depth, self.latency)
        out = pipe.live
        m.d.comb += [en.eq(~out["valid"] | self.out_ready), self.in_ready.eq(en),
                     self.out_valid.eq(out["valid"])]
        m.d.comb += [getattr(self, k).eq(v) for k, v in out.items() if k != "valid"]
        return m


def convert_verilog(*, name: str = "hertz_pipe", rows_per_stage: int = DEFAULT_ROWS_PER_STAGE,
                    hertz_form: str = F.DEFAULT_HERTZ_FORM, tag_bits: int = 0) -> str:
    """Verilog of :class:`HertzPipe` (``strip_internal_attrs=True``)."""
    return verilog.convert(HertzPipe(rows_per_stage=rows_per_stage, hertz_form=hertz_form,
                                     tag_bits=tag_bits),
                           name=name, strip_internal_attrs=True)


@dataclass(frozen=True)
class PipeRun:
    """Outcome of :func:`simulate_hertz_pipe`.

    Attributes
    ----------
    outputs : list of HertzCodes
        Results in the order they left the core (= input order).
    latency : list of int
        Per result: edges from its accepting edge (edge 1) to the edge after which it
        was first presented with ``out_valid``.
    stalls : list of int
        Per result: edges in that interval on which the pipeline was stalled
        (``out_valid & ~out_ready``); without back pressure ``latency == L + stalls``.
    accept_edges : list of int
        Edge index (1-based, from the first simulated edge) of each acceptance.
    edges : int
        Edges simulated.
    """

    outputs: list
    latency: list
    stalls: list
    accept_edges: list
    edges: int


def simulate_hertz_pipe(vectors, *, hertz_form: str = F.DEFAULT_HERTZ_FORM,
                        rows_per_stage: int = DEFAULT_ROWS_PER_STAGE,
                        bubble_prob: float = 0.0, stall_prob: float = 0.0, seed: int = 0,
                        max_cycles: int | None = None) -> PipeRun:
    """Stream input sets through :class:`HertzPipe` in the Amaranth simulator.

    Parameters
    ----------
    vectors : array_like of int, shape (n, 4)
        ``(A_code, B_code, W_code, e_prime_code)`` rows (as
        :func:`.rtl.simulate_hertz_core`).
    hertz_form, rows_per_stage : keyword-only
        Core parameters (:class:`HertzPipe`).
    bubble_prob : float, keyword-only
        Probability, per clock, that ``in_valid`` is held low although input is pending
        (a bubble), in [0, 1).
    stall_prob : float, keyword-only
        Probability, per clock, that ``out_ready`` is low (back pressure), in [0, 1).
    seed : int, keyword-only
        Seed of the bubble/stall pattern (``numpy.random.default_rng``).
    max_cycles : int, keyword-only
        Give up (RuntimeError) after this many edges (default: generous bound).

    Returns
    -------
    PipeRun

    Notes
    -----
    ~150 edges/s of CPU time in Amaranth's simulator (every stage switches on every
    clock) plus ~3 s to elaborate; bulk runs use Verilator (``gearcontact rtl sim
    --core hertz_pipe``).
    """
    import numpy as np

    from ..simulation import run_testbench
    from .rtl import _check_vectors, read_hertz_codes
    rows = _check_vectors(vectors)
    for field, p in (("bubble_prob", bubble_prob), ("stall_prob", stall_prob)):
        if not 0.0 <= p < 1.0:
            raise InputRangeError(field, p, "[0, 1)")
    dut = HertzPipe(rows_per_stage=rows_per_stage, hertz_form=hertz_form)
    lat = dut.latency
    limit = max_cycles if max_cycles is not None else \
        int((len(rows) + lat + 10) / ((1 - bubble_prob) * (1 - stall_prob))) * 4 + 100
    rng = np.random.default_rng(seed)
    outputs, accepts, appear, stalled_at = [], [], [], []

    async def bench(ctx):
        edge, nxt = 0, 0
        shown = False                                   # current output already timed
        while len(outputs) < len(rows):
            if edge >= limit:
                raise RuntimeError(f"hertz pipe: {len(outputs)} of {len(rows)} results "
                                   f"after {limit} edges")
            send = nxt < len(rows) and rng.random() >= bubble_prob
            if send:
                for port, v in zip((dut.A, dut.B, dut.W, dut.e_prime), rows[nxt]):
                    ctx.set(port, v)
            ctx.set(dut.in_valid, send)
            ready = rng.random() >= stall_prob
            ctx.set(dut.out_ready, ready)
            if ctx.get(dut.out_valid):
                if not shown:
                    appear.append(edge)
                    shown = True
                if ready:
                    outputs.append(read_hertz_codes(ctx, dut))
                    shown = False
            if not ctx.get(dut.in_ready):
                stalled_at.append(edge + 1)
            if send and ctx.get(dut.in_ready):
                accepts.append(edge + 1)
                nxt += 1
            await ctx.tick()
            edge += 1
        ctx.set(dut.in_valid, 0)

    run_testbench(dut, bench)
    stalled = np.array(stalled_at, dtype=np.int64)
    lats, stalls = [], []
    for a, o in zip(accepts, appear):
        lats.append(o - a + 1)
        stalls.append(int(((stalled > a) & (stalled <= o)).sum()))
    return PipeRun(outputs, lats, stalls, accepts, int(max(appear, default=0)))
