"""The host-path line stimulus (:mod:`gearcontact.preview.stimulus_lift`).

Truths: the lift's definition (docs/hertz.md sec. 6: the least s with L << s >= 1 mm for
L in [2^-8, 1) mm and W << s <= 2^17 N, else 0) evaluated by hand on the corner cases,
the generators it modifies (:func:`line_stimulus`, :func:`chain_line_stimulus`: every
other operand unchanged), and the documented share and range of the short lines.
"""

import numpy as np
import pytest

from gearcontact.preview.hertz.line import LENGTH_MIN_CODE, length_lift
from gearcontact.preview.stimulus import chain_line_stimulus, line_stimulus
from gearcontact.preview.stimulus_lift import (SHORT_LINE_EVERY, host_chain_line_stimulus,
                                               host_line_stimulus, short_line_stimulus)

N, SEED = 400, 11


@pytest.mark.parametrize("host, base", [(host_line_stimulus, line_stimulus),
                                        (host_chain_line_stimulus, chain_line_stimulus)])
def test_every_fourth_plausible_vector_gets_a_short_line(host, base):
    st, ref = host(N, SEED), base(N, SEED)
    n0, r0 = st.n_corner, ref.n_corner
    assert n0 == r0 + 5 and st.labels[:r0] == ref.labels[:r0]
    assert st.labels[n0:] == ref.labels[r0:]
    for k, v in st.fields.items():             # the core's corners first, unchanged
        assert np.array_equal(v[:r0], ref.fields[k][:r0]), k
        if k != "L":
            assert np.array_equal(v[n0:], ref.fields[k][r0:]), k
    changed = np.flatnonzero(st.fields["L"][n0:] != ref.fields["L"][r0:])
    plausible = np.flatnonzero(np.array(st.labels[n0:]) == "random")
    assert set(changed) <= set(plausible[SHORT_LINE_EVERY - 1::SHORT_LINE_EVERY])
    assert len(changed) >= len(plausible) // SHORT_LINE_EVERY - 2   # an unlikely tie
    short = st.fields["L"][n0:][plausible[SHORT_LINE_EVERY - 1::SHORT_LINE_EVERY]]
    assert short.min() >= LENGTH_MIN_CODE >> 9 and short.max() <= LENGTH_MIN_CODE


def test_lift_corners_by_the_definition():
    st = short_line_stimulus(0, SEED)
    floor = LENGTH_MIN_CODE >> 8                   # 2^-8 mm
    w_top = (1 << 17 << 8) >> 8                    # 2^17 N in Q(32,8), over 2^8
    got = [(int(st.fields["L"][i]), int(st.fields["W"][i]),
            int(length_lift(int(st.fields["W"][i]), int(st.fields["L"][i]))))
           for i in range(len(st))]
    assert got == [(floor, 100 << 8, 8), (floor - 1, 100 << 8, 0),
                   (LENGTH_MIN_CODE - 1, 100 << 8, 1), (floor, w_top, 8),
                   (floor, w_top + 1, 0)]


def test_short_lines_are_below_one_mm_and_seeded():
    a, b = short_line_stimulus(300, SEED), short_line_stimulus(300, SEED)
    assert all(np.array_equal(a.fields[k], b.fields[k]) for k in a.fields)
    length = a.fields["L"][a.n_corner:]
    assert length.min() >= LENGTH_MIN_CODE >> 9 and length.max() < LENGTH_MIN_CODE
    lifts = {int(length_lift(int(w), int(x))) for w, x in zip(a.fields["W"], a.fields["L"])}
    assert lifts == set(range(9))
