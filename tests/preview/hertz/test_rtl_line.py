"""RTL of the line core (:mod:`gearcontact.preview.hertz.rtl_line`) in the Amaranth simulator.

Truths: the golden model bit for bit (every output port, the mode, the scale and the
flags) on corner and seeded random vectors; on the long ellipses truncated to the flank
of tests/preview/hertz/test_line.py, Hertz line contact (Johnson 1985 sec. 4.3) within
the datapath's tolerance stated there (issue 28: "golden and RTL bit for bit"); the cycle count, 759 for every vector
(data independent); the square-root unit equals ``math.isqrt``. The simulator runs the
core at a few evaluations/s of CPU time, so the default suite runs 14 vectors + 3 with the
exact-Hertz tables (6 s on an idle machine, 20 s under load).
"""

import math

import numpy as np
import pytest

from gearcontact.preview.hertz import formats as F
from gearcontact.preview.hertz.golden import encode_hertz_inputs
from gearcontact.preview.hertz.line import (LENGTH_MAX_CODE, LINE_CYCLES, MODE_LINE,
                                            decode_line_codes, encode_length, line_golden)
from gearcontact.preview.hertz.rtl_line import SerialSqrt, simulate_line_core
from gearcontact.preview.simulation import run_testbench
from gearcontact.preview.stimulus import STEEL_E_PRIME_CODE as EP

from .conftest import E_PRIMES
from .test_line import JOHNSON_CASES, _johnson_line


def _codes(A, B, W, L):
    a, b, w, e = encode_hertz_inputs(A, B, W, e_prime_mpa=EP)
    return (a, b, w, encode_length(L), e)


#: Corners: each mode and each SCALE exponent, the mode switch either way, the line
#: core's envelope flags, an all-zero go, the extreme 32-bit codes.
CORNERS = [
    _codes(0.1, 0.02, 1000.0, 50.0),            # elliptic, n = 0 (the published core)
    _codes(0.0246, 2.3e-4, 603.0, 20.0),        # elliptic, n = 1 (R_x = 2.2 m)
    _codes(0.02, 2.0e-5, 300.0, 200.0),         # n = 2, ratio 1000 -> line
    (3, 1200, 2560, encode_length(40.0), EP),   # n = 3, ratio 400 -> line
    _codes(0.0246, 1e-7, 4825.0, 13.3),         # A_min rounds to 0: cylinder, line
    _codes(0.0246, 2.3e-4, 4825.0, 13.3),       # a > L/2, the ellipse's p still higher
    _codes(0.0246, 2.3e-4, 20000.0, 5.0),       # far past the switch: line
    (1000, 50_000, 256_000, LENGTH_MAX_CODE + 1, EP),   # length_range
    (-5, 100_000, 256_000, 1 << 24, EP),        # saddle: not_elliptic
    (0, 0, 0, 0, 0),                            # go without data
    ((1 << 31) - 1,) * 5,
    (-(1 << 31),) * 5,
]


def _random(n, seed):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        b = math.exp(rng.uniform(math.log(2e-3), math.log(4.0)))
        a = b / math.exp(rng.uniform(0.0, math.log(1e5)))
        w = math.exp(rng.uniform(math.log(5.0), math.log(1e5)))
        length = math.exp(rng.uniform(math.log(1.5), math.log(500.0)))
        out.append(_codes(a, b, w, length))
    return out


def test_rtl_equals_golden_bit_for_bit_and_759_cycles():
    # the long ellipses of test_line's Johnson cases (A- = 0.025, B- = 1e-6 1/mm) ride
    # along: one simulation for all vectors
    johnson = [_codes(0.025, 1e-6, W, L) for W, L in JOHNSON_CASES]
    vectors = CORNERS + _random(2, seed=20) + johnson
    outs, cycles = simulate_line_core(vectors)
    assert cycles == [LINE_CYCLES] * len(vectors) == [759] * len(vectors)
    # the RTL's own outputs against Hertz line contact of the flank length (Johnson 1985
    # sec. 4.3, R = 1/(2 A-) = 20 mm), the tolerance of test_line (A- and W quantized:
    # 2e-5 relative, plus one output LSB)
    for (W, L), got in zip(JOHNSON_CASES, outs[-len(johnson):]):
        p0, b0 = _johnson_line(W, 20.0, L, E_PRIMES["steel"])
        v = decode_line_codes(got)
        assert got.mode == MODE_LINE
        assert abs(v["p_max_mpa"] - p0) <= 2e-5 * p0 + 2.0 ** -8
        assert abs(v["b_mm"] - b0) <= 2e-5 * b0 + 2.0 ** -20
    modes = set()
    for v, got in zip(vectors, outs):
        want = line_golden(*v[:4], e_prime_code=v[4])
        assert got == want, v
        modes.add(want.mode_name)
    assert modes == {"elliptic", "line", "flagged"}
    assert {line_golden(*v[:4], e_prime_code=v[4]).scale for v in CORNERS} == {0, 1, 2, 3}
    flags = {line_golden(*v[:4], e_prime_code=v[4]).flags for v in CORNERS}
    assert {F.FLAG_NOT_ELLIPTIC, 1 << 7} <= flags


def test_exact_form_rtl_equals_golden():
    # the wrapped HertzCore with the exact-Hertz tables: one vector per mode and scale
    vectors = [CORNERS[0], CORNERS[1], CORNERS[2]]
    outs, cycles = simulate_line_core(vectors, hertz_form="exact")
    assert cycles == [LINE_CYCLES] * 3
    for v, got in zip(vectors, outs):
        assert got == line_golden(*v[:4], e_prime_code=v[4], hertz_form="exact"), v


@pytest.mark.slow
def test_rtl_equals_golden_random_bulk():
    vectors = _random(200, seed=21)
    outs, cycles = simulate_line_core(vectors)
    assert set(cycles) == {LINE_CYCLES}
    for v, got in zip(vectors, outs):
        assert got == line_golden(*v[:4], e_prime_code=v[4]), v


def test_serial_sqrt_unit():
    rng = np.random.default_rng(4)
    rads = [0, 1, 2, 3, (1 << 80) - 1, (1 << 72) + 12345] + \
        [int(x) << int(s) for x, s in zip(rng.integers(1, 1 << 62, 6), rng.integers(0, 18, 6))]
    dut = SerialSqrt()
    roots = []

    async def bench(ctx):
        for r in rads:
            ctx.set(dut.rad, r)
            ctx.set(dut.load, 1)
            await ctx.tick()
            ctx.set(dut.load, 0)
            ctx.set(dut.start, 1)
            await ctx.tick()
            ctx.set(dut.start, 0)
            ctx.set(dut.step, 1)
            await ctx.tick().repeat(40)
            ctx.set(dut.step, 0)
            roots.append(ctx.get(dut.root))

    run_testbench(dut, bench)
    assert roots == [math.isqrt(r) for r in rads]
