"""GapCore RTL: bit-exact against the golden model, cycle-exact against gap_latency.

The Amaranth simulator runs ~1k cycles/s for 16 lanes, so the default suite keeps to
a dozen directed and seeded passes per lane count (a few hundred cycles in all).
"""

import gc

import numpy as np
import pytest

from gearcontact.preview.gap.golden import (
    DEFAULT_FORMAT,
    IDX_SENTINEL,
    GapVector,
    gap_golden_codes,
    gap_latency,
)
from gearcontact.preview.gap.rtl import (
    GapCore,
    convert_verilog,
    load_gap_vector,
    simulate_gap_core,
)
from gearcontact.preview.simulation import pulse, simulate_bench
from gearcontact.validation import InputRangeError

ONE = 1 << 19
C = DEFAULT_FORMAT.coord


def make(g, n, *, p=(0, 0, 0), t=(0, 0, 0), r=None, tau2=1 << 34):
    r = np.eye(3, dtype=np.int64) * ONE if r is None else np.asarray(r, np.int64)
    return GapVector(r, np.asarray(t, np.int64), np.asarray(p, np.int64),
                     np.asarray(g, np.int64), np.asarray(n, np.int64), int(tau2))


def random_vector(rng, n_samples, spread=2 << 16):
    g = rng.integers(-spread, spread, (n_samples, 3))
    nrm = rng.normal(size=(n_samples, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    q *= np.sign(np.linalg.det(q))
    return make(g, np.floor(nrm * ONE + 0.5).astype(np.int64),
                p=rng.integers(-spread, spread, 3), t=rng.integers(-spread, spread, 3),
                r=np.floor(q * ONE + 0.5).astype(np.int64), tau2=1 << 35)


def directed_vectors(n_samples):
    far = [[(20 + i) << 16, (i % 3) << 16, 0] for i in range(n_samples)]
    up = [[0, 0, ONE]] * n_samples
    vecs = []
    vecs.append(make(far, up, tau2=1))                          # gate rejects every lane
    g = [row[:] for row in far]
    g[3], g[9] = [0, 0, 700], [0, 0, -700]                      # tree tie: idx 3 wins
    vecs.append(make(g, up))
    g = [row[:] for row in far]
    g[2], g[5] = [0, 0, -(1 << 16)], [1 << 8, 0, -(3 << 16)]    # negative gaps only
    vecs.append(make(g, up))                                    # -> gamma = -1 mm at 2
    ext = [[C.min_code] * 3 if i % 2 else [C.max_code] * 3 for i in range(n_samples)]
    nx = [[ONE, -ONE, ONE] if i % 3 else [-ONE, -ONE, -ONE] for i in range(n_samples)]
    vecs.append(make(ext, nx, p=[C.max_code] * 3, tau2=(1 << 63) - 1))   # extreme codes
    vecs.append(make(ext, nx, p=[C.min_code, C.max_code, 0], tau2=(1 << 63) - 1))
    vecs.append(make(far, up, p=[127 << 16, 0, 0], t=[10 << 16, 0, 0]))   # overflow
    return vecs


def check_against_golden(vectors, lanes, **kw):
    outs, cycles = simulate_gap_core(vectors, lanes=lanes, **kw)
    variant = kw.get("variant", "published")
    for vec, out, cyc in zip(vectors, outs, cycles):
        assert out == gap_golden_codes(vec, lanes=lanes, variant=variant)   # bit for bit
        assert cyc == gap_latency(vec.n_samples, lanes)            # cycle for cycle
    return outs, cycles


def test_l16_directed_and_random_bit_and_cycle_exact():
    rng = np.random.default_rng(16)
    vecs = directed_vectors(16) + [random_vector(rng, 16) for _ in range(4)]
    outs, cycles = check_against_golden(vecs, 16)
    assert cycles == [26] * len(vecs)                   # docs/spec.md sec. 6: 26 cycles, no jitter
    assert not outs[0].valid and outs[0].min_idx == IDX_SENTINEL
    assert (outs[1].min_idx, outs[1].min_gap_code) == (3, 700)
    assert (outs[2].min_idx, outs[2].min_gap_code) == (2, -(1 << 16))
    assert outs[5].overflow and not outs[5].valid
    assert sum(o.valid for o in outs[6:]) >= 2          # random passes mostly gate in


def test_l16_partial_and_multi_beat_passes():
    rng = np.random.default_rng(17)
    vecs = [random_vector(rng, 5), random_vector(rng, 37)]
    g = [[(20 + i) << 16, 0, 0] for i in range(40)]     # lane tie: idx 4 and 20 equal
    g[4], g[20] = [0, 0, 300], [0, 0, 300]
    vecs.append(make(g, [[0, 0, ONE]] * 40))
    outs, cycles = check_against_golden(vecs, 16)
    assert cycles == [26, 28, 28]                       # K = 1, 3, 3
    assert outs[2].min_idx == 4


def test_l8_bit_and_cycle_exact():
    rng = np.random.default_rng(8)
    vecs = directed_vectors(12)[:3] + [random_vector(rng, 20), random_vector(rng, 8)]
    _, cycles = check_against_golden(vecs, 8)
    assert cycles == [gap_latency(12, 8)] * 3 + [19, 17]   # 8 + K + 3 + 5


def test_l8_plain_products_bit_and_cycle_exact():
    """The published netlist (plain gamma n, e^2 multipliers) stays exact too."""
    assert GapCore(lanes=8).split_products                      # the default is split
    rng = np.random.default_rng(80)
    vecs = directed_vectors(12)[1:5] + [random_vector(rng, 19)]
    _, cycles = check_against_golden(vecs, 8, split_products=False)
    assert cycles == [gap_latency(v.n_samples, 8) for v in vecs]


def lean_vectors(rng):
    """Saturation corners of the lean variant (residual component 2^17 codes = 2 mm)."""
    up = [[0, 0, ONE]] * 12
    g = [[(20 + i) << 16, 0, 0] for i in range(12)]
    g[0], g[1] = [-(2 << 16), 0, 0], [-(2 << 16) + 1, 0, 0]      # e = 2^17 (saturates) in
    wide = (1 << 63) - 1                                         # lane 0, 2^17 - 1 in lane 1
    vecs = [make(g, up, tau2=1 << 34), make(g, up, tau2=(1 << 34) + 1), make(g, up, tau2=wide)]
    g2 = [row[:] for row in g]
    g2[1] = [-(3 << 16), 0, 5 << 16]                             # every sample saturates
    vecs.append(make(g2, up, tau2=wide))
    vecs.append(make([[0, 0, 0]] * 12, up, tau2=wide))          # rho = 0 everywhere
    for spread in (2 << 16, 40 << 16):                          # inside / beyond 2 mm
        v = random_vector(rng, 19, spread)
        vecs.append(make(v.g_code, v.n_code, p=v.p_code, t=v.t_code, r=v.r_code, tau2=wide))
    return vecs


def test_lean_variant_bit_and_cycle_exact():
    """GapCore(variant="lean") == its golden model on saturation corners, directed and
    random passes (gates up to 2^63), at the published core's cycle counts."""
    rng = np.random.default_rng(15)
    vecs = lean_vectors(rng) + directed_vectors(12)[:5] + [random_vector(rng, 20)]
    outs, cycles = check_against_golden(vecs, 8, variant="lean")
    assert cycles == [gap_latency(v.n_samples, 8) for v in vecs]
    # gamma = 0 for both near samples (a key tie): the lowest lane holding one wins
    assert [o.min_idx for o in outs[:3]] == [1, 1, 1]
    assert [gap_golden_codes(v, lanes=8).min_idx for v in vecs[:3]] == [1, 0, 0]
    assert not outs[3].valid and outs[4].valid and outs[4].min_idx == 0
    with pytest.raises(InputRangeError, match="split_products"):
        GapCore(lanes=8, split_products=False, variant="lean")
    with pytest.raises(InputRangeError, match="variant"):
        GapCore(lanes=8, variant="narrow")


def test_go_while_busy_ignored_reset_mid_run_and_bad_n():
    rng = np.random.default_rng(3)
    vec = random_vector(rng, 16)
    want = gap_golden_codes(vec, lanes=16)
    log = {}

    async def run_pass(ctx, dut, cd, *, poke_at=None, reset_at=None):
        await pulse(ctx, dut.go)
        assert not ctx.get(dut.done)                    # accepting go clears done
        count = 1
        while not ctx.get(dut.done):
            assert not ctx.get(dut.done_pulse)
            if count == poke_at:
                ctx.set(dut.go, 1)                      # ignored: the core is busy
                ctx.set(dut.p, [0, 0, 0])               # operands were captured
            if count == reset_at:
                await pulse(ctx, cd.rst)
                return None
            await ctx.tick()
            ctx.set(dut.go, 0)
            count += 1
        # done_pulse marks done's first cycle only; done holds until the next go
        first = ctx.get(dut.done_pulse)
        await ctx.tick().repeat(3)
        held = (ctx.get(dut.done), ctx.get(dut.done_pulse), ctx.get(dut.busy))
        assert (first, held) == (1, (1, 0, 0))
        return count, (ctx.get(dut.gap), ctx.get(dut.idx), ctx.get(dut.valid))

    async def bench(ctx, dut, cd):
        assert vec.n_samples == 16
        await load_gap_vector(ctx, dut, vec)
        log["busy_poke"] = await run_pass(ctx, dut, cd, poke_at=7)
        ctx.set(dut.p, [int(x) for x in vec.p_code])
        log["reset"] = await run_pass(ctx, dut, cd, reset_at=12)
        log["after_reset"] = (ctx.get(dut.busy), ctx.get(dut.valid), ctx.get(dut.idx),
                              ctx.get(dut.done))
        log["rerun"] = await run_pass(ctx, dut, cd)
        ctx.set(dut.n_samples, 0)
        await pulse(ctx, dut.go)
        await ctx.tick()
        # refused: idle, n_error, and the last pass's done and outputs stand
        log["bad_n"] = (ctx.get(dut.busy), ctx.get(dut.n_error), ctx.get(dut.done),
                        ctx.get(dut.gap))

    simulate_bench(GapCore(lanes=16), bench, with_reset=True)
    golden = (want.min_gap_code, want.min_idx, want.valid)
    assert log["busy_poke"] == (26, golden)
    assert log["reset"] is None and log["after_reset"] == (0, 0, IDX_SENTINEL, 0)
    assert log["rerun"] == (26, golden)                 # sample banks survive reset
    assert log["bad_n"] == (0, 1, 1, want.min_gap_code)


@pytest.mark.filterwarnings("ignore:.*created but never used")
def test_core_parameter_validation():
    with pytest.raises(InputRangeError):
        GapCore(lanes=12)
    with pytest.raises(InputRangeError):
        GapCore(lanes=16, max_samples=24)
    gc.collect()                    # the half-built cores warn when collected: do it here


def test_convert_verilog_l8():
    text = convert_verilog(lanes=8)
    assert "module gap_core" in text and "tau2" in text and "w_ready" in text


@pytest.mark.slow
@pytest.mark.parametrize("lanes", [32, 64])
def test_wide_cores_bit_and_cycle_exact(lanes):
    rng = np.random.default_rng(lanes)
    vecs = directed_vectors(lanes) + [random_vector(rng, lanes),
                                      random_vector(rng, 3 * lanes + 5)]
    check_against_golden(vecs, lanes)


@pytest.mark.slow
def test_l16_random_sweep():
    rng = np.random.default_rng(1616)
    vecs = [random_vector(rng, int(n)) for n in rng.integers(1, 257, 40)]
    check_against_golden(vecs, 16)


@pytest.mark.slow
def test_convert_verilog_l64():
    assert "module gap_core" in convert_verilog(lanes=64)
