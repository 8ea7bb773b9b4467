"""Tests of HertzPipe, the initiation-interval-1 stage D (truth: the scalar golden model,
bit for bit, and the documented latency, edge for edge).

Exact comparisons only: output codes against :func:`hertz_golden` (one call per vector,
independent of the vectorized twin), acceptance on consecutive edges (II = 1), and
latency = :func:`pipe_latency` + the stall edges an evaluation saw in flight.
"""

import numpy as np
import pytest

from gearcontact.preview.hertz.golden import hertz_golden, hertz_golden_trace
from gearcontact.preview.hertz.rtl_pipe import (
    DEFAULT_ROWS_PER_STAGE,
    HertzPipe,
    division_rows,
    pipe_latency,
    simulate_hertz_pipe,
)
from gearcontact.preview.stimulus import hertz_stimulus
from gearcontact.validation import InputRangeError


def _rows(n, seed):
    st = hertz_stimulus(n, seed)
    f = st.fields
    return np.stack([f["A"], f["B"], f["W"], f["e_prime"]], axis=1)


def _golden(rows, hertz_form="hamrock-brewe"):
    return [hertz_golden(int(a), int(b), int(w), e_prime_code=int(e), hertz_form=hertz_form)
            for a, b, w, e in rows]


def test_back_to_back_is_ii1_bit_exact_and_fixed_latency():
    rows = _rows(40, 11)                       # 27 corner cases (every flag) + 40 random
    run = simulate_hertz_pipe(rows)
    assert run.outputs == _golden(rows)
    assert np.all(np.diff(run.accept_edges) == 1)          # one input per clock
    assert run.latency == [pipe_latency()] * len(rows)
    assert run.stalls == [0] * len(rows)
    assert pipe_latency() == 90


def test_random_bubbles_and_stalls_keep_order_bits_and_latency():
    rows = _rows(60, 12)
    run = simulate_hertz_pipe(rows, bubble_prob=0.3, stall_prob=0.3, seed=4)
    assert run.outputs == _golden(rows)                     # in input order, bit exact
    gaps = np.diff(run.accept_edges)
    assert (gaps > 1).any() and (gaps == 1).any()           # bubbles/stalls and bursts
    assert sum(run.stalls) > 0
    # the pipeline moves as a whole: each stalled edge delays the results in flight
    assert run.latency == [pipe_latency() + s for s in run.stalls]


def test_exact_form_bit_exact():
    rows = _rows(24, 13)
    run = simulate_hertz_pipe(rows, hertz_form="exact", stall_prob=0.2, seed=1)
    assert run.outputs == _golden(rows, "exact")
    assert run.latency == [pipe_latency(hertz_form="exact") + s for s in run.stalls]
    assert pipe_latency(hertz_form="exact") == 91


@pytest.mark.slow
@pytest.mark.parametrize("rows_per_stage, latency", [(1, 333), (7, 57)])
def test_other_stage_depths(rows_per_stage, latency):
    rows = _rows(30, 14)
    run = simulate_hertz_pipe(rows, rows_per_stage=rows_per_stage, bubble_prob=0.2,
                              stall_prob=0.2, seed=2)
    assert run.outputs == _golden(rows)
    assert pipe_latency(rows_per_stage) == latency
    assert run.latency == [latency + s for s in run.stalls]


def test_unrolled_rows_cover_every_golden_dividend():
    """The trimmed row counts (a constant dividend starts at its leading one) hold every
    dividend the golden model divides, over corners and random inputs of both forms."""
    for form in ("hamrock-brewe", "exact"):
        rows = division_rows(form)
        for a, b, w, e in _rows(300, 15):
            _, trace = hertz_golden_trace(int(a), int(b), int(w), e_prime_code=int(e),
                                          hertz_form=form)
            for name, num, _den, _q in trace["divisions"]:
                assert num < 1 << rows[name], (form, name, num)
        assert rows["p_n2"] == 80 and rows["R_x"] == 41
        assert rows["E_e"] == (50 if form == "hamrock-brewe" else 54)


def test_latency_table():
    r = division_rows()
    phases = (max(r["R_x"], r["R_y"], r["alpha"], r["R"]), r["E_e"], r["C_a"],
              max(r["b"], r["p_n2"]), r["p_max"])
    for rps in (1, DEFAULT_ROWS_PER_STAGE, 7, 16):
        assert pipe_latency(rps) == 8 + sum(-(-n // rps) for n in phases)


@pytest.mark.parametrize("bad", [0, 17, 2.0, True])
def test_bad_rows_per_stage(bad):
    with pytest.raises(InputRangeError, match="rows_per_stage"):
        HertzPipe(rows_per_stage=bad)


def test_bad_stream_probabilities():
    with pytest.raises(InputRangeError, match="stall_prob"):
        simulate_hertz_pipe(_rows(0, 1)[:1], stall_prob=1.0)
