"""Tests of the FitCore RTL (truth: the golden model, bit for bit; FIT_CYCLES exactly).

All comparisons are exact (integer codes and cycle counts): the RTL must be
bit-identical with :func:`golden_fit` and take exactly ``FIT_CYCLES`` = 52 edges.
"""

import numpy as np
import pytest
from amaranth import ClockDomain, Module
from amaranth.sim import Simulator

from gearcontact.preview.fit.golden import (FIT_CYCLES, FLAG_COEFF_OVERFLOW,
                                            FLAG_CURV_OVERFLOW, FLAG_D_OVERFLOW,
                                            FLAG_NOT_ELLIPTIC, encode_gaps, golden_fit)
from gearcontact.preview.fit.rtl import FitCore, convert_verilog, simulate_fit_core
from gearcontact.preview.fit.stencil import stencil_coordinates
from gearcontact.preview.qformat import GAP

S, T = stencil_coordinates()


def _field(c3, c4, c5, c0=0.0, c1=0.0, c2=0.0):
    return encode_gaps(c0 + c1 * S + c2 * T + c3 * S * S + c4 * S * T + c5 * T * T)


def _directed():
    """Corners: zero, max-magnitude, saddle, tiny curvature, every overflow path."""
    rows = {
        "zero": np.zeros(49, dtype=np.int64),
        "all_max": np.full(49, GAP.max_code),
        "all_min": np.full(49, GAP.min_code),
        "alternating": np.where(np.arange(49) % 2, GAP.max_code, GAP.min_code),
        "impulse_centre_max": np.where(np.arange(49) == 24, GAP.max_code, 0),
        "impulse_corner_min": np.where(np.arange(49) == 0, GAP.min_code, 0),
        "saddle": _field(0.1, 0.05, -0.08),
        "tiny": _field(1e-3, 0.0, 1e-3),
        "typical": _field(0.31, 0.1, 0.05, 0.01, 0.02, -0.01),
        "coeff_overflow": _field(3000.0, 0.0, 1.0),
        "d_overflow": _field(2000.0, 0.0, -2000.0),
        "curv_overflow": _field(2000.0, 2000.0, 1000.0),
    }
    return list(rows), np.array(list(rows.values()), dtype=np.int64)


def _random(n, seed):
    """Seeded random stencils: half raw codes of random magnitude, half quadratics."""
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        if k % 2:
            hi = 1 << int(rng.integers(0, 32))
            out.append(np.clip(rng.integers(-hi, hi, 49), GAP.min_code, GAP.max_code))
        else:
            c = rng.uniform(-1, 1, 3) * 10.0 ** rng.uniform(-3, 0)
            out.append(_field(*c, *rng.uniform(-0.05, 0.05, 3)))
    return np.array(out, dtype=np.int64)


def test_directed_corners_bit_exact_and_cycle_exact():
    names, codes = _directed()
    outs, cycles = simulate_fit_core(codes)
    assert cycles == [FIT_CYCLES] * len(codes)
    flags = {}
    for name, row, out in zip(names, codes, outs):
        assert out == golden_fit(row), name
        flags[name] = out.flags
    # the corners reach every flag path (otherwise the comparison proves less)
    assert flags["coeff_overflow"] == FLAG_COEFF_OVERFLOW
    assert flags["d_overflow"] == FLAG_D_OVERFLOW
    assert flags["curv_overflow"] == FLAG_CURV_OVERFLOW
    assert flags["saddle"] == flags["zero"] == FLAG_NOT_ELLIPTIC
    assert flags["typical"] == flags["tiny"] == 0


def test_random_stencils_bit_exact():
    codes = _random(120, seed=21)
    outs, cycles = simulate_fit_core(codes)
    assert cycles == [FIT_CYCLES] * len(codes)
    for row, out in zip(codes, outs):
        assert out == golden_fit(row)


@pytest.mark.slow
def test_random_stencils_bit_exact_long():
    codes = _random(3000, seed=22)
    outs, cycles = simulate_fit_core(codes)
    assert cycles == [FIT_CYCLES] * len(codes)
    for row, out in zip(codes, outs):
        assert out == golden_fit(row)


# --------------------------------------------------------------- control behaviour

def _run(bench, *, with_reset=False):
    """Run an async testbench on a fresh core (optionally with a drivable reset)."""
    dut = FitCore()
    if with_reset:
        top = Module()
        top.domains.sync = cd = ClockDomain("sync")
        top.submodules.dut = dut
        sim = Simulator(top)
    else:
        cd, sim = None, Simulator(dut)
    sim.add_clock(1e-8)

    async def testbench(ctx):
        await bench(ctx, dut, cd)

    sim.add_testbench(testbench)
    sim.run()


async def _write(ctx, dut, row):
    ctx.set(dut.wr_rst, 1)
    await ctx.tick()
    ctx.set(dut.wr_rst, 0)
    ctx.set(dut.wr_en, 1)
    for x in row:
        ctx.set(dut.wr_data, int(x))
        await ctx.tick()
    ctx.set(dut.wr_en, 0)


def _read(ctx, dut):
    return (tuple(int(ctx.get(c)) for c in dut.coeffs), int(ctx.get(dut.a_minus)),
            int(ctx.get(dut.b_minus)), int(ctx.get(dut.flags)))


def _golden_tuple(row):
    g = golden_fit(row)
    return (g.c_codes, g.a_minus_code, g.b_minus_code, g.flags)


def test_go_while_busy_is_ignored_and_writes_dropped():
    first, second = _field(0.31, 0.1, 0.05), _field(0.02, -0.01, 0.04)

    async def bench(ctx, dut, _):
        await _write(ctx, dut, first)
        assert ctx.get(dut.wr_count) == 49 and not ctx.get(dut.wr_dropped)
        ctx.set(dut.go, 1)
        await ctx.tick()
        ctx.set(dut.go, 0)
        n = 1
        while not ctx.get(dut.done):
            if n == 20:                         # go and a write while busy
                ctx.set(dut.go, 1)
                ctx.set(dut.wr_en, 1)
                ctx.set(dut.wr_data, 12345)
            elif n == 21:
                ctx.set(dut.go, 0)
                ctx.set(dut.wr_en, 0)
            assert ctx.get(dut.busy)
            await ctx.tick()
            n += 1
        assert n == FIT_CYCLES                  # not restarted, not delayed
        assert not ctx.get(dut.busy) and ctx.get(dut.done_pulse)
        assert ctx.get(dut.wr_dropped) and ctx.get(dut.wr_count) == 49
        assert _read(ctx, dut) == _golden_tuple(first)   # RAM untouched by the write
        for _ in range(10):                     # done and outputs hold while idle
            await ctx.tick()
            assert ctx.get(dut.done) and _read(ctx, dut) == _golden_tuple(first)
            assert not ctx.get(dut.done_pulse)  # one cycle only
        # second stencil: outputs keep the first result until the new done edge
        await _write(ctx, dut, second)
        assert not ctx.get(dut.wr_dropped)      # wr_rst cleared the sticky flag
        ctx.set(dut.go, 1)
        await ctx.tick()
        ctx.set(dut.go, 0)
        assert not ctx.get(dut.done)
        n = 1
        while not ctx.get(dut.done):
            assert _read(ctx, dut) == _golden_tuple(first) and not ctx.get(dut.done_pulse)
            await ctx.tick()
            n += 1
        assert n == FIT_CYCLES and _read(ctx, dut) == _golden_tuple(second)

    _run(bench)


def test_write_pointer_saturates_and_write_with_wr_rst_lands_at_zero():
    row = _field(0.2, 0.0, 0.1)

    async def bench(ctx, dut, _):
        await _write(ctx, dut, row)
        ctx.set(dut.wr_en, 1)                   # a 50th sample is dropped, no wrap
        ctx.set(dut.wr_data, 777)
        await ctx.tick()
        ctx.set(dut.wr_en, 0)
        assert ctx.get(dut.wr_count) == 49 and ctx.get(dut.wr_dropped)
        # wr_rst + wr_en together: the sample goes to address 0, pointer -> 1
        ctx.set(dut.wr_rst, 1)
        ctx.set(dut.wr_en, 1)
        ctx.set(dut.wr_data, int(row[0]) + 65536)
        await ctx.tick()
        ctx.set(dut.wr_rst, 0)
        ctx.set(dut.wr_en, 0)
        assert ctx.get(dut.wr_count) == 1 and not ctx.get(dut.wr_dropped)
        # a write in the go cycle is dropped (flagged), the run uses the RAM as it was
        ctx.set(dut.go, 1)
        ctx.set(dut.wr_en, 1)
        await ctx.tick()
        ctx.set(dut.go, 0)
        ctx.set(dut.wr_en, 0)
        assert ctx.get(dut.wr_dropped) and ctx.get(dut.wr_count) == 1
        for _ in range(FIT_CYCLES - 1):
            await ctx.tick()
        assert ctx.get(dut.done)
        expect = row.copy()
        expect[0] += 65536
        assert _read(ctx, dut) == _golden_tuple(expect)

    _run(bench)


def test_reset_mid_run_returns_to_idle_and_keeps_ram():
    row = _field(0.12, -0.03, 0.4, 0.005)

    async def bench(ctx, dut, cd):
        await _write(ctx, dut, row)
        ctx.set(dut.go, 1)
        await ctx.tick()
        ctx.set(dut.go, 0)
        for _ in range(29):
            await ctx.tick()
        assert ctx.get(dut.busy)
        ctx.set(cd.rst, 1)                      # synchronous reset mid-run
        await ctx.tick()
        ctx.set(cd.rst, 0)
        assert not ctx.get(dut.busy) and not ctx.get(dut.done)
        assert ctx.get(dut.wr_count) == 0
        assert _read(ctx, dut) == ((0,) * 6, 0, 0, 0)
        for _ in range(FIT_CYCLES + 5):         # stays idle: no spurious done
            await ctx.tick()
            assert not ctx.get(dut.done) and not ctx.get(dut.busy)
        ctx.set(dut.go, 1)                      # re-run without rewriting the RAM
        await ctx.tick()
        ctx.set(dut.go, 0)
        n = 1
        while not ctx.get(dut.done):
            await ctx.tick()
            n += 1
        assert n == FIT_CYCLES
        assert _read(ctx, dut) == _golden_tuple(row)

    _run(bench, with_reset=True)


def test_convert_verilog():
    # first call compiles the WebAssembly yosys (~4 s); the netlist must carry the
    # ports of the core and the baked ROM contents.
    text = convert_verilog()
    assert "module fit_core" in text
    for port in ("wr_data", "go", "done", "a_minus", "b_minus", "flags", "c5"):
        assert port in text
