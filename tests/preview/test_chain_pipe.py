"""ChainPipe (C -> D with the pipelined stage D) against the chain golden model: every
output bit for bit, go -> done = 52 + 90 = 142 edges for every stencil (flagged too)."""

import dataclasses

import numpy as np

from gearcontact.preview.chain import chain_golden
from gearcontact.preview.chain_pipe import CHAIN_PIPE_CYCLES, chain_pipe_cycles, simulate_chain_pipe
from gearcontact.preview.fit.golden import FIT_CYCLES
from gearcontact.preview.hertz.rtl_pipe import pipe_latency
from gearcontact.preview.stimulus import STEEL_E_PRIME_CODE, chain_stimulus


def test_chain_pipe_equals_golden_in_142_cycles():
    st = chain_stimulus(2, 8)
    f = st.fields
    idx = np.flatnonzero(f["e_prime"] == STEEL_E_PRIME_CODE)[:8]    # flagged ones included
    outs, cycles = simulate_chain_pipe(f["gaps"][idx], f["W"][idx],
                                       e_prime_code=STEEL_E_PRIME_CODE)
    assert cycles == [CHAIN_PIPE_CYCLES] * len(idx)
    assert CHAIN_PIPE_CYCLES == FIT_CYCLES + pipe_latency() == 142
    assert chain_pipe_cycles("exact") == 143
    flagged = 0
    for i, o in zip(idx, outs):
        g = chain_golden([int(x) for x in f["gaps"][i]], int(f["W"][i]),
                         e_prime_code=STEEL_E_PRIME_CODE)
        assert o == dataclasses.replace(g, cycles=CHAIN_PIPE_CYCLES), st.labels[i]
        flagged += g.flags != 0
    assert 0 < flagged < len(idx)
