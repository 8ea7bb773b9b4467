"""Assembly errors of :mod:`gearcontact.geometry.kinematics` acting through the TCA.

Truth (rigid-body kinematics, first order): translating the pinion by ``d`` (P: along
its axis +x; E: the axis to y = -(E0 + E), i.e. ``d = (0, -E, 0)``) at a held pinion
phase must be taken up by a gear rotation that moves the gear flank by the same normal
amount, ``n . (z x X) dphi2 = n . d`` (X the mating point, n the common normal); the
tangential slide of the contact point does not enter at first order. The mating point
shift is odd in the error (first order: +P and -P move it in opposite directions).
"""

import numpy as np
import pytest

from gearcontact.geometry.kinematics import AssemblyErrors, MeshKinematics
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.mating import solve_mating_point


@pytest.fixture(scope="module")
def reference(s0003_centred):
    s0003, flanks = s0003_centred
    res, _ = analyze_pair(s0003, phases=21, flanks=flanks)
    side = s0003.design_side
    return res.mean_point, flanks.flank("pinion", side), flanks.flank("gear", side)


def _solve(pair, reference, errors):
    mp, pinion, gear = reference
    kin = MeshKinematics(offset_mm=pair.offset_mm, ratio=pair.ratio, errors=errors)
    return solve_mating_point(pinion, gear, kin, mp.as_guess(), fixed="phi1")


@pytest.mark.parametrize("key,d_mm", [("P_mm", (1.0, 0.0, 0.0)), ("E_mm", (0.0, -1.0, 0.0))])
@pytest.mark.parametrize("size_mm", [0.02, -0.02])
def test_pinion_shift_is_taken_up_by_gear_rotation(s0003_centred, reference, key, d_mm,
                                                   size_mm):
    s0003 = s0003_centred[0]
    mp = reference[0]
    moved = _solve(s0003, reference, AssemblyErrors(**{key: size_mm}))
    d = size_mm * np.array(d_mm)
    predicted = mp.normal @ d / (mp.normal @ np.cross([0.0, 0.0, 1.0], mp.point_mm))
    # measured 0.02 % (P) and 0.24 % (E) apart at 20 um: the second-order terms are
    # |d| / (relative curvature radius); 2 % leaves room for neither sign nor size to slip
    assert moved.phi2_rad - mp.phi2_rad == pytest.approx(predicted, rel=0.02)


@pytest.mark.parametrize("key", ["P_mm", "E_mm"])
def test_mating_point_shift_is_odd_in_the_error(s0003_centred, reference, key):
    s0003 = s0003_centred[0]
    mp = reference[0]
    plus = _solve(s0003, reference, AssemblyErrors(**{key: 0.01})).point_mm - mp.point_mm
    minus = _solve(s0003, reference, AssemblyErrors(**{key: -0.01})).point_mm - mp.point_mm
    assert np.linalg.norm(plus) > 1e-3          # it does move (tens of um per 10 um)
    # first order: plus = -minus up to O(e^2); 5 % of the shift bounds the curvature term
    np.testing.assert_allclose(plus, -minus, atol=0.05 * np.linalg.norm(plus))
