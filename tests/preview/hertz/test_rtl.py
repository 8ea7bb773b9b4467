"""Tests of the HertzCore RTL (truth: the golden model, bit for bit; 756 cycles exactly).

Every comparison is exact: output codes against :func:`hertz_golden`, internal
registers and divider operands against :func:`hertz_golden_trace`, state entry cycles
against :func:`.schedule.state_start_cycles`, and the go -> done edge count against
``HERTZ_CYCLES`` for every input (flagged runs included).
"""

import numpy as np
import pytest
from amaranth import Module
from amaranth.sim import Simulator

from gearcontact.preview.hertz import formats as F
from gearcontact.preview.hertz.divider import restoring_divide
from gearcontact.preview.hertz.golden import (
    HertzCodes,
    encode_e_prime,
    encode_hertz_inputs,
    hertz_golden,
    hertz_golden_trace,
)
from gearcontact.preview.hertz.rtl import (
    HertzCore,
    convert_verilog,
    read_hertz_codes,
    simulate_hertz_core,
)
from gearcontact.preview.hertz.rtl_datapath import FLAG_BITS, finalize
from gearcontact.preview.hertz.rtl_divider import DEN_BITS, SerialDivider, array_divide
from gearcontact.preview.hertz.schedule import (
    DIVISION_ORDER,
    HERTZ_CYCLES,
    STATES,
    state_start_cycles,
)
from gearcontact.contract.qformat import CURVATURE, LOAD
from gearcontact.preview.simulation import (pulse, run_testbench, run_to_done,
                                            simulate_bench)

from .conftest import E_PRIMES, accuracy_domain

STEEL = encode_e_prime(E_PRIMES["steel"])
I32_MIN, I32_MAX = CURVATURE.min_code, CURVATURE.max_code
CMIN, CMAX = F.CURV_MIN_CODE, F.CURV_MAX_CODE
WMIN, WMAX = F.LOAD_MIN_CODE, F.LOAD_MAX_CODE
EMIN, EMAX = F.E_PRIME_MIN_CODE, F.E_PRIME_MAX_CODE
ALPHA_LIMIT_A = F.ALPHA_MAX_CODE >> F.ALPHA.frac     # alpha = 128: B = 128 A


def _golden(v):
    return hertz_golden(*v[:3], e_prime_code=v[3])


def _typical(a, b, w, material="steel"):
    return encode_hertz_inputs(a, b, w, e_prime_mpa=E_PRIMES[material])


#: Directed corners: (name, (A, B, W, E') codes).
DIRECTED = [
    ("typical", _typical(0.05, 0.3, 1500.0)),
    ("typical_swapped", _typical(0.3, 0.05, 1500.0)),
    ("alpha_1", (1 << 16, 1 << 16, 1 << 20, STEEL)),
    ("alpha_1_plus_lsb", (1 << 16, (1 << 16) + 1, 1 << 20, STEEL)),
    ("alpha_128_lut_end", (1 << 12, ALPHA_LIMIT_A << 12, 1 << 20, STEEL)),
    ("alpha_128_curv_min", (CMIN, ALPHA_LIMIT_A * CMIN, WMAX, EMIN)),
    ("alpha_above_128", (1 << 12, (ALPHA_LIMIT_A << 12) + 1, 1 << 20, STEEL)),
    ("alpha_huge", (CMIN, CMAX, 1 << 20, STEEL)),
    ("curv_min_both", (CMIN, CMIN, WMAX, EMIN)),
    ("curv_max_both", (CMAX, CMAX, WMIN, EMAX)),
    ("curv_max_max_load", (CMAX, CMAX, WMAX, EMAX)),
    ("curv_min_min_load", (CMIN, CMIN, WMIN, EMAX)),
    ("curv_below_min", (CMIN - 1, 1 << 16, 1 << 20, STEEL)),
    ("curv_above_max", (1 << 16, CMAX + 1, 1 << 20, STEEL)),
    ("not_elliptic_zero", (0, 1 << 16, 1 << 20, STEEL)),
    ("not_elliptic_negative", (-(1 << 16), 1 << 16, 1 << 20, STEEL)),
    ("both_negative_all_bad", (I32_MIN, -1, I32_MIN, I32_MIN)),
    ("load_min", (1 << 16, 1 << 18, WMIN, STEEL)),
    ("load_max", (1 << 16, 1 << 18, WMAX, STEEL)),
    ("load_below", (1 << 16, 1 << 18, WMIN - 1, STEEL)),
    ("load_above", (1 << 16, 1 << 18, WMAX + 1, STEEL)),
    ("load_negative", (1 << 16, 1 << 18, -WMIN, STEEL)),
    ("e_min", (1 << 16, 1 << 18, 1 << 20, EMIN)),
    ("e_max", (1 << 16, 1 << 18, 1 << 20, EMAX)),
    ("e_below", (1 << 16, 1 << 18, 1 << 20, EMIN - 1)),
    ("e_above", (1 << 16, 1 << 18, 1 << 20, EMAX + 1)),
    ("int32_extremes", (I32_MAX, I32_MAX, I32_MAX, I32_MAX)),
    ("all_zero_go_without_data", (0, 0, 0, 0)),
]


def _check(vectors, outs, cycles, hertz_form="hamrock-brewe"):
    assert cycles == [HERTZ_CYCLES] * len(vectors)
    for v, o in zip(vectors, outs):
        assert o == hertz_golden(*v[:3], e_prime_code=v[3], hertz_form=hertz_form), v


def test_directed_corners_bit_exact_and_cycle_exact():
    vectors = [v for _, v in DIRECTED]
    outs, cycles = simulate_hertz_core(vectors)
    _check(vectors, outs, cycles)
    raised = 0
    for o in outs:
        raised |= o.flags
    # every input/alpha flag path is exercised, and valid results too
    want = F.FLAG_INPUT | F.FLAG_ALPHA_RANGE
    assert raised & want == want
    assert sum(o.valid for o in outs) >= 12
    # the flagged outputs read 0 except the sorted curvatures
    bad = outs[[n for n, _ in DIRECTED].index("both_negative_all_bad")]
    assert (bad.a_code, bad.p_max_code, bad.alpha_code) == (0, 0, 0)
    assert (bad.A_min_code, bad.B_max_code) == (I32_MIN, -1)


def _random_vectors(n, seed):
    """Accuracy-domain points over the four materials, plus raw int32 codes."""
    rng = np.random.default_rng(seed)
    a, b, w = accuracy_domain(n, seed)
    mats = sorted(E_PRIMES)
    out = []
    for i in range(n):
        out.append(_typical(a[i], b[i], w[i], mats[i % len(mats)]))
    raw = rng.integers(I32_MIN, I32_MAX, size=(max(2, n // 4), 4), endpoint=True)
    raw[::2, :2] = np.abs(raw[::2, :2]) >> rng.integers(1, 20, size=(len(raw[::2]), 2))
    out += [tuple(int(x) for x in r) for r in raw]
    return out


def test_random_vectors_bit_exact():
    vectors = _random_vectors(8, seed=20261122)
    outs, cycles = simulate_hertz_core(vectors)
    _check(vectors, outs, cycles)
    assert sum(o.valid for o in outs) >= 8


@pytest.mark.slow
@pytest.mark.parametrize("hertz_form", F.HERTZ_FORMS)
def test_random_and_corner_sweep_long(hertz_form):
    from .test_golden import CORNERS
    vectors = list(CORNERS) + _random_vectors(200, seed=7)
    outs, cycles = simulate_hertz_core(vectors, hertz_form=hertz_form)
    _check(vectors, outs, cycles, hertz_form)


def test_exact_form_corners_and_random_bit_exact():
    """HertzCore(hertz_form="exact") == hertz_golden(..., hertz_form="exact") bit for bit
    in 756 cycles on the directed corners and seeded accuracy-domain vectors (including
    alpha = 1, alpha = 128 at the end of the tables, and flagged runs)."""
    vectors = [v for _, v in DIRECTED] + _random_vectors(32, seed=20261123)
    outs, cycles = simulate_hertz_core(vectors, hertz_form="exact")
    _check(vectors, outs, cycles, "exact")
    valid = [(v, o) for v, o in zip(vectors, outs) if o.valid]
    assert len(valid) >= 20
    # the exact tables are really in use: k differs from the published form off alpha = 1
    assert sum(o.k_code != _golden(v).k_code for v, o in valid) >= 15


# ---------------------------------------------------------------------------------
# internal registers, divider operands and the state schedule vs the golden trace
# ---------------------------------------------------------------------------------
def _sim(bench, *, tag_bits=0, with_reset=False):
    simulate_bench(HertzCore(tag_bits=tag_bits), bench, with_reset=with_reset)


def _drive(ctx, dut, v):
    for port, x in zip((dut.A, dut.B, dut.W, dut.e_prime), v):
        ctx.set(port, int(x))


@pytest.mark.parametrize("v,hertz_form", [
    (_typical(0.02, 0.5, 1500.0), "hamrock-brewe"),
    (_typical(0.9, 0.0071, 20.0, "aluminium"), "hamrock-brewe"),
    (_typical(0.02, 0.5, 1500.0), "exact")])
def test_registers_divisions_and_schedule_match_golden_trace(v, hertz_form):
    codes, trace = hertz_golden_trace(*v[:3], e_prime_code=v[3], hertz_form=hertz_form)
    assert codes.valid

    async def bench(ctx, dut, cd):
        pr = dut.probes
        _drive(ctx, dut, v)
        await pulse(ctx, dut.go)
        edge, entered, divs, pending = 1, {}, [], {}
        names = {s.index: s.name for s in STATES}
        while not ctx.get(dut.done):
            # values sampled here are those the next edge (edge + 1) acts on
            st, cnt = ctx.get(pr["state"]), ctx.get(pr["cnt"])
            if cnt == 0 and names[st] not in entered:
                entered[names[st]] = edge + 1
            if ctx.get(pr["div_load"]):
                pending["num"] = ctx.get(pr["div_num"])
            if ctx.get(pr["div_start"]):
                pending["den"] = ctx.get(pr["div_den"])
            if names[st].startswith("DIV_") and cnt == STATES[st].cycles - 1:
                divs.append((pending["num"], pending["den"], ctx.get(pr["quotient"])))
            await ctx.tick()
            edge += 1
        assert edge == HERTZ_CYCLES
        # state entry edges (1-based; the go edge is edge 1 = CAPTURE)
        start = state_start_cycles()
        assert entered == {n: start[n] + 1 for n in start if n != "CAPTURE"}
        # divider operands and quotients, in the order of docs/spec.md sec. 6
        assert [d[0] for d in trace["divisions"]] == list(DIVISION_ORDER)
        assert divs == [d[1:] for d in trace["divisions"]]
        # every register holds its golden value after the run
        for name in ("A_min", "B_max", "R_x", "R_y", "alpha", "R", "K", "E6", "K2", "T1",
                     "T2", "T3", "C_a", "m", "a_w", "b_w", "p_n2"):
            assert ctx.get(pr[name]) == trace[name], name
        assert ctx.get(pr["s1"]) == 9 - trace["p"]
        assert ctx.get(pr["WC3"]) == v[2] * F.C3
        assert read_hertz_codes(ctx, dut) == codes
        if hertz_form == "exact":       # the E_e dividend is the EEX interpolation
            assert divs[DIVISION_ORDER.index("E_e")][0] == trace["N_ee"]

    simulate_bench(HertzCore(hertz_form=hertz_form), bench)


# ---------------------------------------------------------------------------------
# control behaviour
# ---------------------------------------------------------------------------------
async def _run_to_done(ctx, dut, strobe, limit=2 * HERTZ_CYCLES):
    return await run_to_done(ctx, strobe, dut.done, max_cycles=limit, what="hertz core")


def test_go_while_busy_is_ignored_and_outputs_hold_until_done():
    first, second = _typical(0.05, 0.3, 1500.0), _typical(0.4, 0.01, 80.0, "titanium")

    async def bench(ctx, dut, cd):
        _drive(ctx, dut, first)
        assert await _run_to_done(ctx, dut, dut.go) == HERTZ_CYCLES
        assert ctx.get(dut.done_pulse)
        assert read_hertz_codes(ctx, dut) == _golden(first)
        await ctx.tick()
        assert ctx.get(dut.done) and not ctx.get(dut.done_pulse)
        # second run; go / go_chain with other operands while busy are ignored
        _drive(ctx, dut, second)
        await pulse(ctx, dut.go)
        assert ctx.get(dut.busy) and not ctx.get(dut.done)
        _drive(ctx, dut, first)
        n = 1
        while not ctx.get(dut.done):
            ctx.set(dut.go, int(n in (1, 2, 300, HERTZ_CYCLES - 1)))
            ctx.set(dut.go_chain, int(n in (5, 600)))
            assert read_hertz_codes(ctx, dut) == _golden(first)   # outputs hold
            await ctx.tick()
            n += 1
        ctx.set(dut.go, 0)
        ctx.set(dut.go_chain, 0)
        assert n == HERTZ_CYCLES
        assert read_hertz_codes(ctx, dut) == _golden(second)
        for _ in range(3):                  # idle: done holds, nothing restarts
            await ctx.tick()
            assert ctx.get(dut.done) and not ctx.get(dut.busy)

    _sim(bench)


def test_go_chain_entry_takes_754_cycles_and_carries_the_tag():
    v = _typical(0.3, 0.05, 1500.0)

    async def bench(ctx, dut, cd):
        _drive(ctx, dut, v)
        ctx.set(dut.tag_in, 0b1011)
        assert await _run_to_done(ctx, dut, dut.go_chain) == HERTZ_CYCLES - 2
        assert read_hertz_codes(ctx, dut) == _golden(v)
        assert ctx.get(dut.tag) == 0b1011
        # go wins when both strobes are set: full 756-cycle run
        ctx.set(dut.tag_in, 0b0110)
        ctx.set(dut.go_chain, 1)
        assert await _run_to_done(ctx, dut, dut.go) == HERTZ_CYCLES
        ctx.set(dut.go_chain, 0)
        assert ctx.get(dut.tag) == 0b0110

    _sim(bench, tag_bits=4)


def test_reset_mid_run_returns_to_idle():
    v = _typical(0.05, 0.3, 1500.0)

    async def bench(ctx, dut, cd):
        _drive(ctx, dut, v)
        assert await _run_to_done(ctx, dut, dut.go) == HERTZ_CYCLES
        await pulse(ctx, dut.go)
        for _ in range(300):                # inside DIV_ALPHA
            await ctx.tick()
        assert ctx.get(dut.busy)
        await pulse(ctx, cd.rst)
        assert not ctx.get(dut.busy) and not ctx.get(dut.done)
        assert read_hertz_codes(ctx, dut) == HertzCodes(*(0,) * 10)
        for _ in range(HERTZ_CYCLES + 5):   # stays idle: no spurious done
            await ctx.tick()
            assert not ctx.get(dut.done) and not ctx.get(dut.busy)
        assert await _run_to_done(ctx, dut, dut.go) == HERTZ_CYCLES
        assert read_hertz_codes(ctx, dut) == _golden(v)

    _sim(bench, with_reset=True)


# ---------------------------------------------------------------------------------
# building blocks: dividers, the output/flag stage (paths unreachable in the envelope)
# ---------------------------------------------------------------------------------
def _divider_cases(seed):
    rng = np.random.default_rng(seed)
    cases = [(0, 1), (1, 1), ((1 << 80) - 1, 1), ((1 << 80) - 1, (1 << DEN_BITS) - 1),
             (12345, 0), ((1 << 79) + 7, 3), (1 << 40, F.CURV_MIN_CODE)]
    for _ in range(6):
        n = int(rng.integers(0, 1 << 62)) << int(rng.integers(0, 18))
        d = int(rng.integers(1, 1 << 40)) >> int(rng.integers(0, 38))
        cases.append((n, max(d, 1)))
    return cases


def test_serial_divider_matches_the_bit_serial_model():
    cases = _divider_cases(3)
    dut = SerialDivider()

    async def bench(ctx):
        for n, d in cases:
            ctx.set(dut.num, n)
            await pulse(ctx, dut.load)
            ctx.set(dut.den, d)
            await pulse(ctx, dut.start)
            ctx.set(dut.step, 1)
            await ctx.tick().repeat(80)
            ctx.set(dut.step, 0)
            ref = restoring_divide(n, d)
            assert ctx.get(dut.quotient) == ref.quotient, (n, d)
            if d:
                assert ctx.get(dut.remainder) == ref.remainder, (n, d)

    run_testbench(dut, bench)


def test_array_divider_matches_the_model():
    from amaranth import Signal
    m = Module()
    num, den = Signal(80), Signal(DEN_BITS)
    q = array_divide(m, num, den, name="t")
    cases = _divider_cases(4)

    async def bench(ctx):
        for n, d in cases:
            ctx.set(num, n)
            ctx.set(den, d)
            await ctx.delay(1e-9)
            assert ctx.get(q) == restoring_divide(n, d).quotient, (n, d)

    sim = Simulator(m)
    sim.add_testbench(bench)
    sim.run()


def test_output_stage_overflow_and_flag_priority():
    """FLAG_OVERFLOW / FLAG_DIV_ZERO cannot occur inside the envelope (the golden model
    proves every register bound); the output stage that would raise them is tested
    directly: overflow zeroes the outputs, an earlier flag wins over overflow."""
    from amaranth import Signal
    m = Module()
    flags, ovf, pq = Signal(FLAG_BITS), Signal(), Signal(80)
    regs = {"a_w": Signal(42), "b_w": Signal(42), "k": Signal(29), "r_x": Signal(32),
            "r_y": Signal(32), "alpha": Signal(32)}
    f_out, outs = finalize(flags, ovf, p_max_q=pq, **regs)
    f_sig = Signal(FLAG_BITS)
    o_sig = {k: Signal(64, name=f"o_{k}") for k in outs}
    m.d.comb += [f_sig.eq(f_out)] + [o_sig[k].eq(v) for k, v in outs.items()]

    async def bench(ctx):
        ctx.set(regs["a_w"], 3 << 36)
        ctx.set(regs["r_x"], 5)
        ctx.set(pq, 2 * 1000)
        await ctx.delay(1e-9)
        assert ctx.get(f_sig) == 0 and ctx.get(o_sig["p_max"]) == 1000
        assert ctx.get(o_sig["a"]) == 3 << 20 and ctx.get(o_sig["R_x"]) == 5
        ctx.set(pq, 2 * (1 << 31))                       # p_max does not fit Q(32,8)
        await ctx.delay(1e-9)
        assert ctx.get(f_sig) == F.FLAG_OVERFLOW
        assert all(ctx.get(s) == 0 for s in o_sig.values())
        ctx.set(pq, 2)
        ctx.set(ovf, 1)                                  # R_x/R_y overflow recorded
        await ctx.delay(1e-9)
        assert ctx.get(f_sig) == F.FLAG_OVERFLOW
        ctx.set(flags, F.FLAG_DIV_ZERO)                  # an earlier flag wins
        await ctx.delay(1e-9)
        assert ctx.get(f_sig) == F.FLAG_DIV_ZERO
        assert all(ctx.get(s) == 0 for s in o_sig.values())

    sim = Simulator(m)
    sim.add_testbench(bench)
    sim.run()


def test_convert_verilog_ports():
    text = convert_verilog()
    assert "module hertz_core" in text
    for port in ("A", "B", "W", "e_prime", "go", "go_chain", "busy", "done", "done_pulse",
                 "a", "b", "p_max", "k", "A_min", "B_max", "R_x", "R_y", "alpha"):
        assert f" {port};" in text, port
    assert "output [6:0] flags;" in text
    assert f"input [{LOAD.bits - 1}:0] W;" in text
