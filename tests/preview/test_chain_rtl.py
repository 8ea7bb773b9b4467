"""Tests of the C->D chain RTL (ChainCore, 806 cycles) and the combinational C+D core
(CombCore, 58 cycles): both bit-exact with :func:`chain_golden` (chain flags word
included) and cycle-exact for every input."""

import dataclasses

import numpy as np
import pytest
from gearcontact.materials import STEEL, Material, effective_modulus_mpa
from gearcontact.preview.chain import chain_golden
from gearcontact.preview.chain_rtl import (
    ChainCore,
    read_chain_codes,
    simulate_chain_core,
    write_stencil,
)
from gearcontact.preview.chain_rtl import convert_verilog as chain_verilog
from gearcontact.preview.comb_rtl import CombCore, simulate_comb_core
from gearcontact.preview.comb_rtl import convert_verilog as comb_verilog
from gearcontact.preview.fit import golden as fit_golden
from gearcontact.preview.fit.golden import FIT_CYCLES, encode_gaps
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.preview.hertz import formats as F
from gearcontact.preview.hertz.golden import encode_e_prime
from gearcontact.preview.hertz.schedule import CHAIN_CYCLES, COMB_CYCLES
from gearcontact.contract.qformat import LOAD, STENCIL_GAP
from gearcontact.preview.simulation import pulse, run_to_done, simulate_bench

S, T = stencil_coordinates()
E_STEEL = encode_e_prime(effective_modulus_mpa(STEEL))
E_ALU = encode_e_prime(effective_modulus_mpa(Material(70_000.0, 0.33, "aluminium")))


def _field(c3, c4, c5, c0=0.0, c1=0.0, c2=0.0):
    return encode_gaps(c0 + c1 * S + c2 * T + c3 * S * S + c4 * S * T + c5 * T * T)


def _w(newton):
    return LOAD.quantize(newton, field="W")


#: Directed stencils with their loads: (name, stencil codes, W code).
DIRECTED = [
    ("typical", _field(0.31, 0.1, 0.05, 0.01, 0.02, -0.01), _w(1500.0)),
    ("near_circular_alpha_1", _field(0.2, 0.0, 0.2), _w(800.0)),
    ("ratio_near_lut_end", _field(0.254, 0.0, 0.00201), _w(300.0)),
    ("ratio_above_128", _field(0.3, 0.0, 0.0021), _w(300.0)),
    ("tiny_curvature_range", _field(1e-3, 0.0, 1e-4), _w(100.0)),
    ("saddle_not_elliptic", _field(0.1, 0.05, -0.08), _w(1500.0)),
    ("zero_go_without_data", np.zeros(49, dtype=np.int64), _w(1500.0)),
    # samples inside STENCIL_GAP's +-1024 mm (tests/preview/fit/test_golden.py)
    ("coeff_overflow", _field(3000.0, 0.0, 1.0, -1000.0), _w(1500.0)),
    ("d_overflow", _field(1500.0, 0.0, -1500.0), _w(1500.0)),
    ("curv_overflow", _field(1900.0, 600.0, 1900.0, -1000.0), _w(1500.0)),
    ("load_min", _field(0.05, 0.01, 0.5), F.LOAD_MIN_CODE),
    ("load_max", _field(0.05, 0.01, 0.5), F.LOAD_MAX_CODE),
    ("load_zero", _field(0.05, 0.01, 0.5), 0),
]


def _golden(rows, ws, e, cycles):
    return [dataclasses.replace(chain_golden(r, w, e_prime_code=e), cycles=cycles)
            for r, w in zip(rows, ws)]


def _random(n, seed):
    """Seeded stencils: quadratic fields in the accuracy domain (A-, B- in [1e-3, 1],
    ratio <= 100, random orientation, offsets and slopes, +-0.5 um noise) and raw
    random codes; log-uniform loads in [10, 20 000] N."""
    rng = np.random.default_rng(seed)
    rows, ws = [], []
    for i in range(n):
        if i % 4 == 3:
            rows.append(rng.integers(STENCIL_GAP.min_code >> rng.integers(0, 30),
                                     STENCIL_GAP.max_code >> 8, size=49, endpoint=True))
        else:
            lo = np.exp(rng.uniform(np.log(1e-3), np.log(0.5)))
            hi = min(lo * np.exp(rng.uniform(0.0, np.log(100.0))), 1.0)
            th = rng.uniform(0.0, np.pi)
            c, s = np.cos(th), np.sin(th)
            c3, c5 = hi * c * c + lo * s * s, hi * s * s + lo * c * c
            c4 = 2.0 * (hi - lo) * c * s
            g = (c3 * S * S + c4 * S * T + c5 * T * T + rng.uniform(-0.01, 0.01)
                 + rng.uniform(-0.05, 0.05) * S + rng.uniform(-0.05, 0.05) * T
                 + rng.uniform(-5e-4, 5e-4, 49))
            rows.append(encode_gaps(g))
        ws.append(_w(float(np.exp(rng.uniform(np.log(10.0), np.log(20_000.0))))))
    return np.array(rows, dtype=np.int64), ws


def _check(outs, cycles, rows, ws, e, n_cycles):
    assert cycles == [n_cycles] * len(rows)
    assert outs == _golden(rows, ws, e, n_cycles)


@pytest.fixture(scope="module")
def directed():
    return np.array([r for _, r, _ in DIRECTED], dtype=np.int64), [w for *_, w in DIRECTED]


def test_chain_directed_bit_exact_and_806_cycles(directed):
    rows, ws = directed
    outs, cycles = simulate_chain_core(rows, ws, e_prime_code=E_STEEL)
    _check(outs, cycles, rows, ws, E_STEEL, CHAIN_CYCLES)
    flags = {n: o.flags for (n, *_), o in zip(DIRECTED, outs)}
    assert flags["typical"] == 0 and flags["ratio_near_lut_end"] == 0
    assert flags["ratio_above_128"] == F.FLAG_ALPHA_RANGE
    assert flags["tiny_curvature_range"] == F.FLAG_CURV_RANGE
    assert flags["load_zero"] == F.FLAG_LOAD_RANGE
    fit_bits = {f >> 8 for f in flags.values()}
    assert {fit_golden.FLAG_COEFF_OVERFLOW, fit_golden.FLAG_D_OVERFLOW,
            fit_golden.FLAG_CURV_OVERFLOW, fit_golden.FLAG_NOT_ELLIPTIC} <= fit_bits


def test_comb_directed_bit_exact_and_58_cycles(directed):
    rows, ws = directed
    outs, cycles = simulate_comb_core(rows, ws, e_prime_code=E_STEEL)
    _check(outs, cycles, rows, ws, E_STEEL, COMB_CYCLES)


@pytest.mark.parametrize("core", ["chain", "comb"])
def test_random_stencils_bit_exact(core):
    rows, ws = _random(6, seed={"chain": 11, "comb": 12}[core])
    sim, n = ((simulate_chain_core, CHAIN_CYCLES) if core == "chain"
              else (simulate_comb_core, COMB_CYCLES))
    outs, cycles = sim(rows, ws, e_prime_code=E_ALU)
    _check(outs, cycles, rows, ws, E_ALU, n)
    assert sum(o.flags == 0 for o in outs) >= 3


@pytest.mark.slow
@pytest.mark.parametrize("core", ["chain", "comb"])
def test_random_stencils_bit_exact_long(core):
    rows, ws = _random(100, seed=99)
    sim, n = ((simulate_chain_core, CHAIN_CYCLES) if core == "chain"
              else (simulate_comb_core, COMB_CYCLES))
    outs, cycles = sim(rows, ws, e_prime_code=E_STEEL)
    _check(outs, cycles, rows, ws, E_STEEL, n)


# ---------------------------------------------------------------------------------
# control behaviour
# ---------------------------------------------------------------------------------
def _sim(core_cls, bench, *, with_reset=False):
    async def steel_bench(ctx, dut, cd):
        ctx.set(dut.e_prime, E_STEEL)
        await bench(ctx, dut, cd)

    simulate_bench(core_cls(), steel_bench, with_reset=with_reset)


async def _go_and_wait(ctx, dut, w, limit):
    ctx.set(dut.W, w)
    return await run_to_done(ctx, dut.go, dut.done, max_cycles=limit)


def _one(row, w, cycles):
    return _golden([row], [w], E_STEEL, cycles)[0]


A_ROW, A_W = DIRECTED[0][1], DIRECTED[0][2]
B_ROW, B_W = _field(0.02, -0.01, 0.04), _w(90.0)
C_ROW, C_W = _field(0.4, 0.0, 0.01), _w(5000.0)


@pytest.mark.parametrize("core_cls,n_cycles", [(ChainCore, CHAIN_CYCLES),
                                               (CombCore, COMB_CYCLES)])
def test_go_while_busy_ignored_outputs_hold_and_writes(core_cls, n_cycles):
    async def bench(ctx, dut, cd):
        await write_stencil(ctx, dut, A_ROW)
        assert await _go_and_wait(ctx, dut, A_W, 2 * n_cycles) == n_cycles
        assert ctx.get(dut.done_pulse)
        first = read_chain_codes(ctx, dut, n_cycles)
        assert first == _one(A_ROW, A_W, n_cycles)
        await write_stencil(ctx, dut, B_ROW)
        assert not ctx.get(dut.wr_dropped)
        ctx.set(dut.W, B_W)
        await pulse(ctx, dut.go)
        ctx.set(dut.W, C_W)                      # W is captured at go: no effect
        n = 1
        while not ctx.get(dut.done):
            assert ctx.get(dut.busy)
            # go pulses in the fit phase, at the fit -> D hand-over and in stage D
            ctx.set(dut.go, int(n in (3, FIT_CYCLES, FIT_CYCLES + 1, n_cycles - 1)))
            if n == 10:                          # a write during the fit: dropped
                ctx.set(dut.wr_en, 1)
                ctx.set(dut.wr_data, 12345)
            else:
                ctx.set(dut.wr_en, 0)
            got = read_chain_codes(ctx, dut, n_cycles)
            # stage-D outputs and the flags word hold until the done edge
            assert (got.hertz, got.flags) == (first.hertz, first.flags)
            await ctx.tick()
            n += 1
        ctx.set(dut.go, 0)
        assert n == n_cycles
        assert ctx.get(dut.wr_dropped)
        assert read_chain_codes(ctx, dut, n) == _one(B_ROW, B_W, n_cycles)
        for _ in range(3):
            await ctx.tick()
            assert ctx.get(dut.done) and not ctx.get(dut.busy)

    _sim(core_cls, bench)


def test_chain_accepts_writes_while_stage_d_runs():
    async def bench(ctx, dut, cd):
        await write_stencil(ctx, dut, A_ROW)
        ctx.set(dut.W, A_W)
        await pulse(ctx, dut.go)
        for _ in range(FIT_CYCLES + 5):
            await ctx.tick()
        assert ctx.get(dut.busy)
        await write_stencil(ctx, dut, C_ROW)     # the gap RAM is free during stage D
        assert not ctx.get(dut.wr_dropped) and ctx.get(dut.wr_count) == 49
        while not ctx.get(dut.done):
            await ctx.tick()
        assert read_chain_codes(ctx, dut, CHAIN_CYCLES) == _one(A_ROW, A_W, CHAIN_CYCLES)
        assert await _go_and_wait(ctx, dut, C_W, 2 * CHAIN_CYCLES) == CHAIN_CYCLES
        assert read_chain_codes(ctx, dut, CHAIN_CYCLES) == _one(C_ROW, C_W, CHAIN_CYCLES)

    _sim(ChainCore, bench)


@pytest.mark.parametrize("core_cls,n_cycles,reset_at", [
    (ChainCore, CHAIN_CYCLES, 20), (ChainCore, CHAIN_CYCLES, 400),
    (CombCore, COMB_CYCLES, FIT_CYCLES + 3)])
def test_reset_mid_run_returns_to_idle_and_keeps_ram(core_cls, n_cycles, reset_at):
    async def bench(ctx, dut, cd):
        await write_stencil(ctx, dut, A_ROW)
        assert await _go_and_wait(ctx, dut, A_W, 2 * n_cycles) == n_cycles
        await write_stencil(ctx, dut, B_ROW)
        ctx.set(dut.W, B_W)
        await pulse(ctx, dut.go)
        for _ in range(reset_at - 1):
            await ctx.tick()
        assert ctx.get(dut.busy)
        await pulse(ctx, cd.rst)
        assert not ctx.get(dut.busy) and not ctx.get(dut.done)
        zero = read_chain_codes(ctx, dut, 0)
        assert (zero.hertz.a_code, zero.hertz.p_max_code, zero.flags) == (0, 0, 0)
        for _ in range(n_cycles + 5):            # idle: no spurious done
            await ctx.tick()
            assert not ctx.get(dut.done) and not ctx.get(dut.busy)
        # the RAM kept stencil B: a go without rewriting evaluates it
        assert await _go_and_wait(ctx, dut, B_W, 2 * n_cycles) == n_cycles
        assert read_chain_codes(ctx, dut, n_cycles) == _one(B_ROW, B_W, n_cycles)

    _sim(core_cls, bench, with_reset=True)


def test_chain_convert_verilog():
    text = chain_verilog()
    assert "module chain_core" in text
    for port in ("wr_rst", "wr_en", "W", "e_prime", "go", "busy", "done", "a", "b", "p_max",
                 "k", "a_minus", "b_minus", "alpha", "c5"):
        assert f" {port};" in text, port
    assert "output [11:0] flags;" in text


@pytest.mark.slow
def test_comb_convert_verilog():
    text = comb_verilog()
    assert "module comb_core" in text and "output [11:0] flags;" in text


@pytest.mark.parametrize("core", ["chain", "comb"])
def test_e_prime_envelope_ends(core):
    rows = np.array([A_ROW, A_ROW], dtype=np.int64)
    sim, n = ((simulate_chain_core, CHAIN_CYCLES) if core == "chain"
              else (simulate_comb_core, COMB_CYCLES))
    # chain: upper end and just beyond; comb (slower to build): lower end
    cases = ([(F.E_PRIME_MAX_CODE, 0), (F.E_PRIME_MAX_CODE + 1, F.FLAG_E_PRIME_RANGE)]
             if core == "chain" else [(F.E_PRIME_MIN_CODE, 0)])
    for e, want in cases:
        outs, cycles = sim(rows, [A_W, F.LOAD_MAX_CODE], e_prime_code=e)
        _check(outs, cycles, rows, [A_W, F.LOAD_MAX_CODE], e, n)
        assert [o.flags for o in outs] == [want, want]


@pytest.mark.parametrize("core_cls,n_cycles", [(ChainCore, CHAIN_CYCLES),
                                               (CombCore, COMB_CYCLES)])
def test_go_after_power_up_without_writes(core_cls, n_cycles):
    async def bench(ctx, dut, cd):
        assert not ctx.get(dut.done) and not ctx.get(dut.busy)
        assert await _go_and_wait(ctx, dut, A_W, 2 * n_cycles) == n_cycles
        got = read_chain_codes(ctx, dut, n_cycles)
        assert got == _one(np.zeros(49, dtype=np.int64), A_W, n_cycles)
        assert got.flag_names == ("fit_not_elliptic", "not_elliptic")

    _sim(core_cls, bench)


def test_chain_exact_form_bit_exact_and_806_cycles():
    """ChainCore(hertz_form="exact") == chain_golden(..., hertz_form="exact") bit for
    bit in 806 cycles on 8 seeded stencils; the batch golden equals the scalar one."""
    from gearcontact.preview.chain import chain_golden_batch
    rows, ws = _random(8, seed=31)
    outs, cycles = simulate_chain_core(rows, ws, e_prime_code=E_STEEL, hertz_form="exact")
    assert cycles == [CHAIN_CYCLES] * len(rows)
    want = [dataclasses.replace(chain_golden(r, w, e_prime_code=E_STEEL, hertz_form="exact"),
                                cycles=CHAIN_CYCLES) for r, w in zip(rows, ws)]
    assert outs == want
    assert sum(o.flags == 0 for o in outs) >= 4
    batch = chain_golden_batch(rows, np.array(ws), e_prime_code=E_STEEL, hertz_form="exact")
    assert [int(x) for x in batch.hertz.p_max_code] == [o.hertz.p_max_code for o in outs]
    assert [int(x) for x in batch.flags] == [o.flags for o in outs]


def test_comb_exact_form_bit_exact_and_58_cycles():
    """CombCore(hertz_form="exact") == chain_golden(..., hertz_form="exact") bit for bit
    in 58 cycles on 6 seeded stencils, and differs from the published form's k."""
    rows, ws = _random(6, seed=37)
    outs, cycles = simulate_comb_core(rows, ws, e_prime_code=E_STEEL, hertz_form="exact")
    assert cycles == [COMB_CYCLES] * len(rows)
    want = [dataclasses.replace(chain_golden(r, w, e_prime_code=E_STEEL, hertz_form="exact"),
                                cycles=COMB_CYCLES) for r, w in zip(rows, ws)]
    assert outs == want
    ok = [o for o in outs if o.flags == 0]
    assert len(ok) >= 3
    hb = [chain_golden(r, w, e_prime_code=E_STEEL) for r, w in zip(rows, ws)]
    assert any(o.hertz.k_code != h.hertz.k_code for o, h in zip(outs, hb) if o.flags == 0)
    with pytest.raises(ValueError, match="hertz_form"):
        CombCore(hertz_form="fit")
