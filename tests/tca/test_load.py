"""Torque -> normal load: statics of a force on a lever (moment = r x F)."""

import math

import numpy as np
import pytest

from gearcontact import InputRangeError
from gearcontact.tca.load import normal_load_from_torque, torque_lever_mm


def test_tangential_force_lever_is_radius():
    # force tangent to the circle of radius 40 mm about z: lever = 40 mm exactly
    assert torque_lever_mm([40.0, 0.0, 5.0], [0.0, 1.0, 0.0]) == pytest.approx(40.0, rel=1e-15)
    # 64.5 N·m on a 40 mm lever -> 1612.5 N
    assert normal_load_from_torque(64.5, [40.0, 0.0, 5.0], [0, 1, 0]) == pytest.approx(1612.5)


def test_inclined_normal_reduces_lever():
    # a normal inclined by 20 deg out of the tangent direction (pressure angle) keeps
    # only cos(20 deg) of its moment arm; an axial tilt does the same
    n = [0.0, math.cos(math.radians(20)), math.sin(math.radians(20))]
    assert torque_lever_mm([40.0, 0.0, 0.0], n) == pytest.approx(40 * math.cos(math.radians(20)))


def test_pinion_axis_lever():
    # pinion axis = x through (0, -19, 0): a point 6 mm above the axis, force along z
    lever = torque_lever_mm([30.0, -13.0, 0.0], [0.0, 0.0, 1.0],
                            axis_point_mm=[0.0, -19.0, 0.0], axis_dir=[1.0, 0.0, 0.0])
    assert lever == pytest.approx(6.0)


def test_radial_force_carries_no_torque():
    with pytest.raises(InputRangeError, match="lever"):
        torque_lever_mm([40.0, 0.0, 0.0], [1.0, 0.0, 0.0])


@pytest.mark.parametrize("torque", [0.0, -1.0, np.nan])
def test_bad_torque(torque):
    with pytest.raises(InputRangeError, match="torque_nm"):
        normal_load_from_torque(torque, [40.0, 0.0, 0.0], [0.0, 1.0, 0.0])
