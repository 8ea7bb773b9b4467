"""Cycle schedule of the serialized stage D (the timing the RTL must reproduce).

A 13-state FSM drives one shared 80-bit restoring divider (:mod:`.divider`: 80 cycles
per division + 3 handshake = 83) through nine divisions in the order of docs/spec.md sec. 6
R_x, R_y, alpha, R, E_e, C_a, b, p_n2, p_max. The LUT datapath works concurrently
with the divider where its operands are ready (the POW look-up and interpolation of
k, and k^2, run while the divider computes R and E_e); the four products of the
C_a numerator and the cube-root range reduction get their own states. The schedule is
static: every input, valid or flagged, takes exactly the same number of cycles.
The ``hertz_form="exact"`` core keeps it: its second table (EEX) is read on DIV_R's
last cycle and feeds the E_e dividend loaded on DIV_EE's first cycle.

=====  ==========  ======  ===========================================================
state  name        cycles  what it does
=====  ==========  ======  ===========================================================
0      CAPTURE     1       ``go`` edge: latch A, B (CURVATURE), W (LOAD), E' registers
1      SORT        1       A_min = min(A, B), B_max = max(A, B); envelope checks -> flags
2      DIV_RX      83      R_x = 1/(2 A_min)
3      DIV_RY      83      R_y = 1/(2 B_max)
4      DIV_ALPHA   83      alpha = R_x/R_y = B_max/A_min; alpha range check -> flag
5      DIV_R       83      R = 1/(2 (A_min + B_max)); || POW ROM read + interpolation: k
6      DIV_EE      83      E6 = 6 E_e/pi = 6/pi + (3 - 6/pi)/alpha; || k^2
7      PRODUCT     4       T1 = k^2 E6 | T2 = T1 R | T3 = T2 W | (numerator shift, C_a op load)
8      DIV_CA      83      C_a = a^3 = T3/E'
9      CBRT        3       leading-one + range reduction C_a = m 8^p | CBRT ROM read |
                           interpolation and scaling a = m^(1/3) 2^p
10     DIV_B       83      b = a/k
11     DIV_PN2     83      p_n2 = 3 W/(2 pi a)
12     DIV_PMAX    83      p_max = p_n2/b; output registers, flags and ``done`` on the
                           last (write-back) cycle
=====  ==========  ======  ===========================================================

Total ``HERTZ_CYCLES = 2 + 9 x 83 + 4 + 3 = 756`` from the ``go`` edge to ``done``.

In the C->D chain the fit core's 3-cycle curvature latch delivers the pair already
sorted into D's operand registers, absorbing CAPTURE and SORT
(``STAGE_D_CAPTURE_CYCLES = 2``): ``CHAIN_CYCLES = 49 + 3 + 754 = 806``
(:func:`gearcontact.preview.fit.golden.chain_cycles`).

The fully combinational C+D variant (``COMB_CYCLES = 58``) replaces the shared divider
by array dividers and registers stage D in ``COMB_D_STAGES = 6`` pipeline stages after
the 52-cycle fit core: {R_x, R_y, alpha, R} | {E6, k} | {T1..T3} | {C_a} |
{range reduction, cube root, a} | {b, p_n2, p_max}. Each division is the same exact
floor division, so its outputs are the golden outputs bit for bit.

References
----------
docs/spec.md sec. 6 (Algorithm 3) and section 7 (paper latencies: D 756, C->D 806,
combinational C+D 58 cycles).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..fit.golden import FIT_CYCLES, STAGE_D_CAPTURE_CYCLES, chain_cycles
from .divider import DIVISION_CYCLES

__all__ = ["State", "STATES", "HERTZ_CYCLES", "CHAIN_CYCLES", "COMB_CYCLES",
           "COMB_D_STAGES", "N_DIVISIONS", "DIVISION_ORDER", "state_start_cycles"]


@dataclass(frozen=True)
class State:
    """One FSM state: index, name, cycle count and a one-line description."""

    index: int
    name: str
    cycles: int
    does: str


#: Division order on the shared divider (docs/spec.md sec. 6, Algorithm 3).
DIVISION_ORDER = ("R_x", "R_y", "alpha", "R", "E_e", "C_a", "b", "p_n2", "p_max")
N_DIVISIONS = len(DIVISION_ORDER)

STATES = (
    State(0, "CAPTURE", 1, "latch A, B, W, E'"),
    State(1, "SORT", 1, "A_min/B_max, envelope checks"),
    State(2, "DIV_RX", DIVISION_CYCLES, "R_x = 1/(2 A_min)"),
    State(3, "DIV_RY", DIVISION_CYCLES, "R_y = 1/(2 B_max)"),
    State(4, "DIV_ALPHA", DIVISION_CYCLES, "alpha = B_max/A_min, range check"),
    State(5, "DIV_R", DIVISION_CYCLES, "R = 1/(2(A_min+B_max)) || POW LUT: k"),
    State(6, "DIV_EE", DIVISION_CYCLES, "E6 = 6/pi + (3-6/pi)/alpha || k^2"),
    State(7, "PRODUCT", 4, "T1 = k^2 E6, T2 = T1 R, T3 = T2 W, C_a operand load"),
    State(8, "DIV_CA", DIVISION_CYCLES, "C_a = T3/E'"),
    State(9, "CBRT", 3, "range reduction, CBRT LUT read, interpolate + scale a"),
    State(10, "DIV_B", DIVISION_CYCLES, "b = a/k"),
    State(11, "DIV_PN2", DIVISION_CYCLES, "p_n2 = 3W/(2 pi a)"),
    State(12, "DIV_PMAX", DIVISION_CYCLES, "p_max = p_n2/b, outputs, done"),
)

HERTZ_CYCLES = sum(s.cycles for s in STATES)             #: standalone stage D: 756
CHAIN_CYCLES = chain_cycles(HERTZ_CYCLES)                 #: C->D chain: 806
COMB_D_STAGES = 6                                         #: pipeline stages, comb. D
COMB_CYCLES = FIT_CYCLES + COMB_D_STAGES                  #: combinational C+D: 58

assert len(STATES) == 13
assert sum(1 for s in STATES if s.name.startswith("DIV_")) == N_DIVISIONS
assert STATES[0].cycles + STATES[1].cycles == STAGE_D_CAPTURE_CYCLES
assert (HERTZ_CYCLES, CHAIN_CYCLES, COMB_CYCLES) == (756, 806, 58)


def state_start_cycles() -> dict[str, int]:
    """Cycle offset (from the ``go`` edge, 0-based) at which each state begins."""
    out, t = {}, 0
    for s in STATES:
        out[s.name] = t
        t += s.cycles
    return out
