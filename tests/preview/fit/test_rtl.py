"""Tests of the FitCore RTL (truth: the golden model, bit for bit; FIT_CYCLES exactly).

All comparisons are exact (integer codes and cycle counts): the RTL must be
bit-identical with :func:`golden_fit` and take exactly ``FIT_CYCLES`` = 52 edges.
"""

import numpy as np
import pytest

from gearcontact.preview.fit.golden import (FIT_CYCLES, FLAG_COEFF_OVERFLOW,
                                            FLAG_CURV_OVERFLOW, FLAG_D_OVERFLOW,
                                            FLAG_NOT_ELLIPTIC, GoldenFit, encode_gaps,
                                            golden_fit)
from gearcontact.preview.fit.rtl import (FitCore, convert_verilog, read_fit_codes,
                                        simulate_fit_core)
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.contract.qformat import STENCIL_GAP
from gearcontact.preview.simulation import (pulse, run_to_done, simulate_bench,
                                            write_stencil)

S, T = stencil_coordinates()


def _field(c3, c4, c5, c0=0.0, c1=0.0, c2=0.0):
    return encode_gaps(c0 + c1 * S + c2 * T + c3 * S * S + c4 * S * T + c5 * T * T)


def _directed():
    """Corners: zero, max-magnitude, saddle, tiny curvature, every overflow path."""
    rows = {
        "zero": np.zeros(49, dtype=np.int64),
        "all_max": np.full(49, STENCIL_GAP.max_code),
        "all_min": np.full(49, STENCIL_GAP.min_code),
        "alternating": np.where(np.arange(49) % 2, STENCIL_GAP.max_code, STENCIL_GAP.min_code),
        "impulse_centre_max": np.where(np.arange(49) == 24, STENCIL_GAP.max_code, 0),
        "impulse_corner_min": np.where(np.arange(49) == 0, STENCIL_GAP.min_code, 0),
        "saddle": _field(0.1, 0.05, -0.08),
        "tiny": _field(1e-3, 0.0, 1e-3),
        "typical": _field(0.31, 0.1, 0.05, 0.01, 0.02, -0.01),
        # samples inside STENCIL_GAP's +-1024 mm (test_golden.py's overflow fields)
        "coeff_overflow": _field(3000.0, 0.0, 1.0, -1000.0),
        "d_overflow": _field(1500.0, 0.0, -1500.0),
        "curv_overflow": _field(1900.0, 600.0, 1900.0, -1000.0),
    }
    return list(rows), np.array(list(rows.values()), dtype=np.int64)


def _random(n, seed):
    """Seeded random stencils: half raw codes of random magnitude, half quadratics."""
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        if k % 2:
            hi = 1 << int(rng.integers(0, 32))
            out.append(np.clip(rng.integers(-hi, hi, 49), STENCIL_GAP.min_code,
                               STENCIL_GAP.max_code))
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


def _check_random(n, seed):
    codes = _random(n, seed=seed)
    outs, cycles = simulate_fit_core(codes)
    assert cycles == [FIT_CYCLES] * len(codes)
    for row, out in zip(codes, outs):
        assert out == golden_fit(row)


def test_random_stencils_bit_exact():
    _check_random(120, seed=21)


@pytest.mark.slow
def test_random_stencils_bit_exact_long():
    _check_random(3000, seed=22)


# --------------------------------------------------------------- control behaviour

def _run(bench, *, with_reset=False):
    """Run ``bench(ctx, dut, cd)`` on a fresh core (optionally with a drivable reset)."""
    simulate_bench(FitCore(), bench, with_reset=with_reset)


def test_go_while_busy_is_ignored_and_writes_dropped():
    first, second = _field(0.31, 0.1, 0.05), _field(0.02, -0.01, 0.04)

    async def bench(ctx, dut, _):
        await write_stencil(ctx, dut, first)
        assert ctx.get(dut.wr_count) == 49 and not ctx.get(dut.wr_dropped)
        await pulse(ctx, dut.go)
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
        assert read_fit_codes(ctx, dut) == golden_fit(first)   # RAM untouched by the write
        for _ in range(10):                     # done and outputs hold while idle
            await ctx.tick()
            assert ctx.get(dut.done) and read_fit_codes(ctx, dut) == golden_fit(first)
            assert not ctx.get(dut.done_pulse)  # one cycle only
        # second stencil: outputs keep the first result until the new done edge
        await write_stencil(ctx, dut, second)
        assert not ctx.get(dut.wr_dropped)      # wr_rst cleared the sticky flag
        await pulse(ctx, dut.go)
        assert not ctx.get(dut.done)
        n = 1
        while not ctx.get(dut.done):
            assert read_fit_codes(ctx, dut) == golden_fit(first)
            assert not ctx.get(dut.done_pulse)
            await ctx.tick()
            n += 1
        assert n == FIT_CYCLES and read_fit_codes(ctx, dut) == golden_fit(second)

    _run(bench)


def test_write_pointer_saturates_and_write_with_wr_rst_lands_at_zero():
    row = _field(0.2, 0.0, 0.1)

    async def bench(ctx, dut, _):
        await write_stencil(ctx, dut, row)
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
        assert read_fit_codes(ctx, dut) == golden_fit(expect)

    _run(bench)


def test_reset_mid_run_returns_to_idle_and_keeps_ram():
    row = _field(0.12, -0.03, 0.4, 0.005)

    async def bench(ctx, dut, cd):
        await write_stencil(ctx, dut, row)
        await pulse(ctx, dut.go)
        for _ in range(29):
            await ctx.tick()
        assert ctx.get(dut.busy)
        await pulse(ctx, cd.rst)                # synchronous reset mid-run
        assert not ctx.get(dut.busy) and not ctx.get(dut.done)
        assert ctx.get(dut.wr_count) == 0
        assert read_fit_codes(ctx, dut) == GoldenFit((0,) * 6, 0, 0, 0)
        for _ in range(FIT_CYCLES + 5):         # stays idle: no spurious done
            await ctx.tick()
            assert not ctx.get(dut.done) and not ctx.get(dut.busy)
        # re-run without rewriting the RAM
        n = await run_to_done(ctx, dut.go, dut.done, max_cycles=4 * FIT_CYCLES)
        assert n == FIT_CYCLES
        assert read_fit_codes(ctx, dut) == golden_fit(row)

    _run(bench, with_reset=True)


def test_convert_verilog():
    # first call compiles the WebAssembly yosys (~4 s); the netlist must carry the
    # ports of the core and the baked ROM contents.
    text = convert_verilog()
    assert "module fit_core" in text
    for port in ("wr_data", "go", "done", "a_minus", "b_minus", "flags", "c5"):
        assert port in text
