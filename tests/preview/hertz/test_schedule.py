"""The stage-D cycle schedule (docs/spec.md sec. 7: 756 / 806 / 58 cycles)."""

from gearcontact.preview.fit.golden import FIT_CYCLES, STAGE_D_CAPTURE_CYCLES
from gearcontact.preview.hertz.divider import DIVISION_CYCLES
from gearcontact.preview.hertz.schedule import (CHAIN_CYCLES, COMB_CYCLES, DIVISION_ORDER,
                                                HERTZ_CYCLES, STATES, state_start_cycles)


def test_paper_cycle_counts():
    assert (HERTZ_CYCLES, CHAIN_CYCLES, COMB_CYCLES) == (756, 806, 58)


def test_state_table():
    assert len(STATES) == 13 and [s.index for s in STATES] == list(range(13))
    divs = [s for s in STATES if s.name.startswith("DIV_")]
    assert len(divs) == len(DIVISION_ORDER) == 9
    assert all(s.cycles == DIVISION_CYCLES for s in divs)
    assert sum(s.cycles for s in STATES) - 9 * DIVISION_CYCLES == 9   # 1+1+4+3
    # docs/spec.md sec. 6 division order R_x, R_y, alpha, R, E_e, C_a, b, p_n2, p_max
    assert [s.name for s in divs] == ["DIV_RX", "DIV_RY", "DIV_ALPHA", "DIV_R", "DIV_EE",
                                      "DIV_CA", "DIV_B", "DIV_PN2", "DIV_PMAX"]


def test_chain_composition():
    # chain = 49 MAC + 3 latch + (756 - 2 absorbed capture/sort cycles)
    assert STATES[0].cycles + STATES[1].cycles == STAGE_D_CAPTURE_CYCLES == 2
    assert CHAIN_CYCLES == 49 + 3 + HERTZ_CYCLES - 2
    assert COMB_CYCLES == FIT_CYCLES + 6


def test_state_starts():
    starts = state_start_cycles()
    assert starts["CAPTURE"] == 0 and starts["DIV_RX"] == 2
    assert starts["DIV_PMAX"] + DIVISION_CYCLES == HERTZ_CYCLES
