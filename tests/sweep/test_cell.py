"""One grid point (:func:`gearcontact.sweep.cell.compute_point`): the pattern shift of
a pure E or P error against the first-order kinematics.

Truth (first order in the pinion translation ``d``: ``d = (0, -E, 0)`` for E, ``(P, 0,
0)`` for P, docs/sweeps.md), from the nominal set-up's geometry alone:

1. *Path shift.* At the contact ``r`` with gear normal ``n`` the translation is taken up
   by a gear rotation ``theta = n.d / n.(z x r)`` (tests/geometry/test_kinematics.py),
   i.e. the TE of a pair changes by ``theta(phi1)`` along its path. Each pair's TE0 is
   a parabola ``TE0''/2 (phi1 - phi_v)^2`` about its vertex, all pairs alike one pitch
   apart, so a tilt ``s = d theta / d phi1`` moves every vertex, and with them the
   crossings of neighbouring parabolas that bound the transmitting segment, by
   ``d phi1 = -s / TE0''``; the pattern moves along the path by ``(dv2/dphi1) d phi1``.
2. *Local shift at a held phase.* With the gap ``g(q) = q^T B q / 2`` (B relative
   curvature in the tangent plane, ``B = H1 - H2`` with the flanks' height curvatures
   along the gear normal) the moved pinion and the turned gear add a linear term whose
   minimum moves the contact by ``q = B^-1 [H1 d_t - theta H2 (z x r)_t + theta (n x
   z)_t]`` (Litvin & Fuentes 2004, sec. 9.4-9.5, contact-point displacement from the
   relations between the curvatures).

The sum along the gear face (v2) is compared with the sweep's pattern-centre shift,
symmetrised ``(shift(+e) - shift(-e)) / 2`` (the even second-order part cancels),
within 10 % (measured: 3 % for E, 1 % for P at 10 um); the height shift is below a
tenth of the face shift in both.
"""

import numpy as np
import pytest

from gearcontact.sweep.cell import compute_point
from gearcontact.tca.analysis import analyze_pair

from .conftest import predicted_face_shift_mm

PHASES = 61      # the vertex and the segment ends are read on the sampled phases
STEP_MM = 0.01


@pytest.fixture(scope="module")
def nominal(s0003_centred):
    pair, flanks = s0003_centred
    res, _ = analyze_pair(pair, side="drive", phases=PHASES, flanks=flanks)
    return res, compute_point(pair, flanks, {}, [64.5], side="drive", compute=("tca",),
                              phases=PHASES)


@pytest.mark.parametrize("key,direction", [("E_mm", (0.0, -1.0, 0.0)),
                                           ("P_mm", (1.0, 0.0, 0.0))])
def test_pure_e_or_p_moves_the_pattern_as_the_kinematics_predict(s0003_centred, nominal,
                                                                 key, direction):
    pair, flanks = s0003_centred
    res, base = nominal
    d = STEP_MM * np.array(direction)
    want = predicted_face_shift_mm(res, pair, flanks, d)
    got = {}
    for sign in (1, -1):
        c = compute_point(pair, flanks, {key: sign * STEP_MM}, [64.5], side="drive",
                          compute=("tca",), phases=PHASES)
        assert c["error"] == [""]
        got[sign] = (c["pattern_face_mm"][0] - base["pattern_face_mm"][0],
                     c["pattern_height_mm"][0] - base["pattern_height_mm"][0])
    face = 0.5 * (got[1][0] - got[-1][0])
    height = 0.5 * (got[1][1] - got[-1][1])
    assert abs(want) > 0.2                    # a real move: tenths of a mm per 10 um
    assert face == pytest.approx(want, rel=0.10)
    assert abs(height) < 0.1 * abs(face)
