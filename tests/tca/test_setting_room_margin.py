"""The margin of lever 5's room (tca.setting_room_margin; docs/machine_settings.md sec. 5,
"The print's drive bearing: a margin on lever 5's room"; issue 27).

Truths, declared with the rule (before building it):
- ``room_margin_mm`` is ``(pi / z1) |du1/dphi1| / |du1/ds|`` (by hand, 1e-12 relative:
  the same three floating operations in another order), 0 for an axis along the root line;
- ``axis_depth_rate`` is the ``u`` component of the ellipse's major axis in the posed
  flank derivatives, here by Cramer's rule with cross products, ``du/ds = ((e_s x r_v).n)
  / ((r_u x r_v).n)`` (independent of the Jacobian inverse of
  ``stencil.tangent_parameters``; 1e-12 relative: both are exact 2 x 2 algebra of the
  same vectors, the subtraction of ``u1`` ~ 30 mm costing ~1e-14 of a rate ~ 1);
- ``depth_rate_per_rad`` is the five-point stencil of the contact's ``u1`` over steps of
  1/30 pitch: by hand on points solved one by one (``solve_mating_point`` at each phase,
  not the TCA's path; to 18 x 1e-10 mm / (12 h), the stencil's weights times the
  solver's tolerance, 1e-10 mm, on each point), and the derivative itself, a central
  difference at a sixteenth of
  the step (1e-4 relative: its truncation (h/16)^2 / 6 |u'''/u'| < 1e-4 for |u'''/u'| <
  300 /rad^2, the path curving over a pitch of 0.39 rad).
"""

import dataclasses
import math

import numpy as np
import pytest

from gearcontact.tca.curvature import relative_curvature
from gearcontact.tca.mating import solve_mating_point
from gearcontact.tca.setting_room_margin import (axis_depth_rate, depth_rate_per_rad,
                                                 room_margin_mm)


def test_the_margin_by_hand():
    got = room_margin_mm(depth_rate_per_rad=-0.75, axis_depth_rate_per_mm=0.42,
                         pinion_teeth=10)
    assert got == pytest.approx(0.75 * math.pi / (10 * 0.42), rel=1e-12)
    assert room_margin_mm(depth_rate_per_rad=0.75, axis_depth_rate_per_mm=-0.42,
                          pinion_teeth=10) == got
    assert room_margin_mm(depth_rate_per_rad=0.75, axis_depth_rate_per_mm=0.0,
                          pinion_teeth=10) == 0.0


@pytest.fixture(scope="module")
def at_mean(s0003_centred, s0003_drive):
    pair, flanks = s0003_centred
    return (pair, flanks.flank("pinion", "drive"), flanks.flank("gear", "drive"),
            s0003_drive.mean_point)


def test_the_axis_depth_rate_by_cramers_rule(at_mean):
    pair, pinion, gear, mp = at_mean
    kin = pair.kinematics()
    rc = relative_curvature(pinion, gear, kin, mp)
    rot = kin.pinion_pose(mp.phi1_rad)[0]
    sp = pinion.point(mp.u1, mp.v1)
    r_u, r_v, n, e_s = rot @ sp.r_u, rot @ sp.r_v, rc.normal, rc.dir_min
    by_hand = np.dot(np.cross(e_s, r_v), n) / np.dot(np.cross(r_u, r_v), n)
    assert axis_depth_rate(pinion, gear, kin, mp) == pytest.approx(by_hand, rel=1e-12)


def test_the_depth_rate_is_the_five_point_stencil_of_the_contact(at_mean):
    pair, pinion, gear, mp = at_mean
    kin = pair.kinematics()
    h = 2.0 * math.pi / pair.pinion_teeth / 30.0

    def u_at(dphi):
        return solve_mating_point(pinion, gear, kin, dataclasses.replace(
            mp.as_guess(), phi1_rad=mp.phi1_rad + dphi)).u1

    u = [u_at(k * h) for k in range(-2, 3)]
    stencil = (u[0] - 8.0 * u[1] + 8.0 * u[3] - u[4]) / (12.0 * h)
    got = depth_rate_per_rad(pinion, gear, pair, mp.as_guess())
    assert abs(got - stencil) <= 18.0 * 1e-10 / (12.0 * h)
    d = h / 16.0
    assert got == pytest.approx((u_at(d) - u_at(-d)) / (2.0 * d), rel=1e-4)
