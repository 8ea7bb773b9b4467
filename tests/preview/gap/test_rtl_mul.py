"""Split partial products (preview.gap.rtl_mul) against Python integer products.

Tolerance: none -- the split forms are integer identities, so every output must equal
``a * b`` / ``a * a`` exactly. Operand widths are the gap core's stage B: gamma 27 b
(low bits of Q(32,16)), normal 21 b (Q(21,19)), residual e 27 b (Q(27,16)). Corner
values cover the most negative / positive codes, zero, +-1 and both sides of the
17-bit split (low part all ones, high part +-1 / 0) in a full cross product.
"""

import itertools

import numpy as np
import pytest
from amaranth.hdl import Module, Signal, signed
from amaranth.sim import Simulator

from gearcontact.preview.gap.rtl_mul import LO_BITS, split_mul, split_square

AW, BW = 27, 21                                  # gamma27 / e, and n


def corners(width):
    """Signed corner codes of a ``width``-bit word, with the split boundaries."""
    lo, hi, k = -(1 << (width - 1)), (1 << (width - 1)) - 1, 1 << LO_BITS
    vals = {lo, lo + 1, hi, hi - 1, 0, 1, -1, 2, -2}
    if width > LO_BITS:
        vals |= {k - 1, k, k + 1, -k + 1, -k, -k - 1, 2 * k - 1, -2 * k + 1,
                 hi - (k - 1), lo + (k - 1), (hi >> LO_BITS) << LO_BITS}
    return sorted(v for v in vals if lo <= v <= hi)


def run_pairs(pairs):
    """(a, b) -> (split_mul(a, b), split_square(a)) read back from the simulator."""
    m = Module()
    a, b = Signal(signed(AW)), Signal(signed(BW))
    pm, ps = split_mul(a, b), split_square(a)
    # widths as documented: wide enough for every product of the operands
    assert pm.shape().signed and len(pm) >= AW + BW + 1
    assert ps.shape().signed and len(ps) >= 2 * AW + 2
    o_mul, o_sq = Signal(pm.shape()), Signal(ps.shape())
    m.d.comb += [o_mul.eq(pm), o_sq.eq(ps)]
    out = []

    async def bench(ctx):
        for x, y in pairs:
            ctx.set(a, x)
            ctx.set(b, y)
            out.append((ctx.get(o_mul), ctx.get(o_sq)))

    sim = Simulator(m)
    sim.add_testbench(bench)
    sim.run()
    return out


def test_corner_cross_product_is_exact():
    pairs = list(itertools.product(corners(AW), corners(BW)))
    assert len(pairs) > 300
    for (x, y), (pm, ps) in zip(pairs, run_pairs(pairs)):
        assert pm == x * y, (x, y)
        assert ps == x * x, x


def test_random_operands_are_exact():
    rng = np.random.default_rng(6)
    xs = rng.integers(-(1 << (AW - 1)), 1 << (AW - 1), 2000)
    ys = rng.integers(-(1 << (BW - 1)), 1 << (BW - 1), 2000)
    pairs = [(int(x), int(y)) for x, y in zip(xs, ys)]
    for (x, y), (pm, ps) in zip(pairs, run_pairs(pairs)):
        assert (pm, ps) == (x * y, x * x)


def test_operand_too_narrow_to_split():
    with pytest.raises(ValueError, match="no split"):
        split_mul(Signal(signed(LO_BITS)), Signal(signed(BW)))
    with pytest.raises(ValueError, match="no split"):
        split_square(Signal(signed(8)))
