"""Tests of the FitCore building blocks (truths: math.isqrt, exact integer dot products,
the golden model; all comparisons exact, cycle counts exact).
"""

import math

import numpy as np
import pytest

from gearcontact.preview.fit.golden import (FIT_CYCLES, encode_gaps, golden_fit,
                                            isqrt_nonrestoring)
from gearcontact.preview.fit.pinv import N_COEFFS, N_TAPS, bake_pseudo_inverse, baked_pinv
from gearcontact.preview.fit.rtl import SCHEDULE, simulate_fit_core
from gearcontact.preview.fit.rtl_isqrt import IsqrtSequential
from gearcontact.preview.fit.rtl_mac import N_PAIRS, PairMac, weight_bits
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.contract.qformat import STENCIL_GAP
from gearcontact.preview.simulation import simulate_bench
from gearcontact.validation import InputRangeError


def _isqrt_corners(bits):
    """0, 1, all-ones, powers of two, perfect squares and their neighbours."""
    top = (1 << bits) - 1
    out = {0, 1, 2, 3, top, top - 1, 1 << (bits - 1), (1 << (bits - 1)) - 1}
    out |= {1 << k for k in range(bits)}
    for q in (1, 2, 3, 255, 1 << 16, (1 << 16) - 1, (1 << 31) - 1, 1 << 31, (1 << 32) - 1,
              3037000499, 2_642_245):
        for x in (q * q - 1, q * q, q * q + 1, (q + 1) * (q + 1) - 1):
            if 0 <= x <= top:
                out.add(x)
    return sorted(out)


def _run_isqrt(values, *, root_bits=32, bits_per_cycle=2):
    """Roots and start->not-busy edge counts of the sequential isqrt."""
    dut = IsqrtSequential(root_bits=root_bits, bits_per_cycle=bits_per_cycle)
    roots, cycles = [], []

    async def bench(ctx, dut, _):
        for d in values:
            ctx.set(dut.start, 1)
            ctx.set(dut.d, int(d))
            await ctx.tick()
            ctx.set(dut.start, 0)
            ctx.set(dut.d, 0)                   # sampled on the start edge only
            n = 1
            while ctx.get(dut.busy):
                await ctx.tick()
                n += 1
            roots.append(ctx.get(dut.root))
            cycles.append(n)

    simulate_bench(dut, bench)
    return roots, cycles


def test_isqrt_64bit_corners_and_random_equal_math_isqrt():
    rng = np.random.default_rng(61)
    rand = [int(rng.integers(0, 1 << 62)) >> int(rng.integers(0, 62)) << int(rng.integers(0, 3))
            for _ in range(150)]
    values = _isqrt_corners(64) + rand
    roots, cycles = _run_isqrt(values)
    assert roots == [math.isqrt(d) for d in values]
    assert roots == [isqrt_nonrestoring(d) for d in values]   # the golden definition
    assert cycles == [1 + 16] * len(values)                   # start edge + 16 steps


@pytest.mark.parametrize("bits_per_cycle", [1, 2, 4])
def test_isqrt_8bit_radicand_exhaustive(bits_per_cycle):
    values = list(range(256))
    roots, cycles = _run_isqrt(values, root_bits=4, bits_per_cycle=bits_per_cycle)
    assert roots == [math.isqrt(d) for d in values]
    assert cycles == [1 + 4 // bits_per_cycle] * 256


def test_isqrt_rejects_a_non_divisor_step():
    with pytest.raises(InputRangeError, match="bits_per_cycle"):
        IsqrtSequential(root_bits=32, bits_per_cycle=3)


def test_isqrt_root_holds_until_next_start():
    dut = IsqrtSequential()

    async def bench(ctx, dut, _):
        ctx.set(dut.start, 1)
        ctx.set(dut.d, 10**18)
        await ctx.tick()
        ctx.set(dut.start, 0)
        for _ in range(40):
            await ctx.tick()
        assert ctx.get(dut.root) == math.isqrt(10**18) and not ctx.get(dut.busy)

    simulate_bench(dut, bench)


# ------------------------------------------------------------------ PairMac

def _run_mac(rom, stencils):
    """Write each stencil, run the MAC schedule of FitCore, read the six sums."""
    dut = PairMac(rom=rom)
    out = []

    async def bench(ctx, dut, _):
        for row in stencils:
            ctx.set(dut.wr_en, 1)
            for i, x in enumerate(row):
                ctx.set(dut.wr_addr, i)
                ctx.set(dut.wr_data, int(x))
                await ctx.tick()
            ctx.set(dut.wr_en, 0)
            # edge k: raddr presented before it is k - 1 (k <= 25); clear on edge 1;
            # accumulate on edges 3..27; fold 28, combine 29 (FitCore's SCHEDULE)
            for k in range(1, SCHEDULE["combine"] + 1):
                ctx.set(dut.raddr, k - 1 if k <= N_PAIRS else 0)
                ctx.set(dut.clear, k == 1)
                ctx.set(dut.acc_en, 3 <= k <= SCHEDULE["acc_last"])
                ctx.set(dut.fold, k == SCHEDULE["fold"])
                ctx.set(dut.combine, k == SCHEDULE["combine"])
                await ctx.tick()
            ctx.set(dut.combine, 0)
            out.append([ctx.get(s) for s in dut.sums])

    simulate_bench(dut, bench)
    return out


def _exact_sums(rom, row):
    return [sum(w * int(x) for w, x in zip(rom.weight_codes[j], row))
            for j in range(N_COEFFS)]


def _extreme_stencils(rng, n):
    rows = [np.full(N_TAPS, STENCIL_GAP.max_code), np.full(N_TAPS, STENCIL_GAP.min_code),
            np.where(np.arange(N_TAPS) % 2, STENCIL_GAP.min_code, STENCIL_GAP.max_code)]
    rows += [rng.integers(STENCIL_GAP.min_code, STENCIL_GAP.max_code + 1, N_TAPS)
             for _ in range(n)]
    return rows


def test_pair_mac_sums_are_exact_dot_products():
    rom = baked_pinv()
    assert weight_bits(rom) <= 25            # hardware ROM: one DSP A port per weight
    rows = _extreme_stencils(np.random.default_rng(62), 6)
    for row, got in zip(rows, _run_mac(rom, rows)):
        assert got == _exact_sums(rom, row)


def test_pair_mac_wide_weights_split_path_exact():
    rom = bake_pseudo_inverse(spacing_mm=0.012)  # weights x278: > 25 bits, split
    assert 25 < weight_bits(rom) <= 32
    rows = _extreme_stencils(np.random.default_rng(63), 3)
    for row, got in zip(rows, _run_mac(rom, rows)):
        assert got == _exact_sums(rom, row)


def test_fit_core_with_wide_weight_rom_bit_exact():
    rom = bake_pseudo_inverse(spacing_mm=0.012)
    rng = np.random.default_rng(64)
    s, t = stencil_coordinates(0.012)
    bowl = encode_gaps(10.0 * s * s + 1.0 * s * t + 5.0 * t * t + 0.001)
    codes = np.array([rng.integers(-(1 << b), 1 << b, N_TAPS) for b in (14, 8, 31)]
                     + [bowl, np.zeros(N_TAPS, dtype=np.int64)], dtype=np.int64)
    outs, cycles = simulate_fit_core(codes, rom=rom)
    assert cycles == [FIT_CYCLES] * len(codes)
    for row, out in zip(codes, outs):
        assert out == golden_fit(row, rom=rom)
    assert {o.flags for o in outs} >= {0, 8}     # elliptic and not: the isqrt path ran


def test_schedule_fits_fit_cycles():
    e = SCHEDULE
    assert e["acc_last"] == N_PAIRS + 2 == 27
    assert e["isqrt_last"] - e["isqrt_load"] == 16
    assert e["flags"] < e["done"] == FIT_CYCLES == 52
