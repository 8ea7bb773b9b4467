"""Determinism and latency in the report (:mod:`gearcontact.report.latency`).

Truth: the cycle formulas of the timing model written out independently -- gap pass
``L + ceil(N/L) + log2(L) + 5`` (docs/spec.md sec. 7), fit ``49 MAC + 3 latch``, Hertz
``2 + 9 x 83 + 4 + 3`` and the chain ``49 + 3 + 754`` (stage D's 2 capture edges
absorbed) -- and the ordering of the measured percentiles.
"""

import math

from gearcontact.report.latency import core_cycles, preview_inputs, scalar_latency


def test_core_cycles_follow_the_timing_formulas():
    got = core_cycles(lanes=16, n_samples=49)
    assert got == {"gap pass (L = 16, N = 49)": 16 + math.ceil(49 / 16) + 4 + 5,
                   "fit C": 49 + 3, "Hertz D": 2 + 9 * 83 + 4 + 3,
                   "chain C -> D": 49 + 3 + 754, "combinational C + D": 58,
                   # latency of the pipelined stage D at R = 4 rows per divider stage
                   # (preview.hertz.rtl_pipe; the RTL tests count it), and the chain's
                   # fit (52) plus it
                   "pipelined Hertz D (II = 1)": 90, "chain C -> D with pipelined D": 142}
    assert core_cycles(lanes=64, n_samples=4096)["gap pass (L = 64, N = 4096)"] == \
        64 + 64 + 6 + 5


def test_scalar_latency_is_ordered_and_inputs_in_domain():
    lat = scalar_latency(500, warmup=100)
    assert lat.calls == 500 and 0.0 < lat.p50_us <= lat.p99_us
    assert math.isclose(lat.jitter, lat.p99_us / lat.p50_us - 1.0)
    a, b, w = preview_inputs(1000)
    assert (a >= 1e-3).all() and (b <= 1.0).all() and (b >= a).all() and (b <= 128 * a).all()
    assert (w >= 10.0).all() and (w <= 2e4).all()
