"""geometry.generation: the gear top land along the tip line (pointed toe refused)."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.blank import gear_top_land_mm
from gearcontact.geometry.generation import check_gear_top_land, gear_tip_top_lands
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError

from design_space import design_space_pair

_EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("name", ["iso23509_f3", "hypoid_11x41_rear_axle",
                                  "iso23509_f2_spiral_bevel"])
def test_mid_face_top_land_is_the_iso_mean_top_land(name):
    pair = load_pair(_EXAMPLES / f"{name}.toml")
    frac, land = gear_tip_top_lands(pair)
    # independent truth: ISO 23509's rack approximation of the mean normal section.
    # The mid station is at mid lengthwise range (not exactly the mean cone distance)
    # and the real flanks are cones, not a rack: 10 % (measured 3-6 %).
    assert land[len(frac) // 2] == pytest.approx(
        gear_top_land_mm(pair.blank, pair.cutter.point_width_mm), rel=0.10)
    # the slot is as wide at the toe while the pitch shrinks: the toe is the thinnest
    assert land[0] == land.min() and land[-1] > land[len(frac) // 2]
    # the top land shrinks one for one with the cutter point width (normal section)
    wider = replace(pair, cutter=replace(pair.cutter,
                                         point_width_mm=pair.cutter.point_width_mm + 0.1))
    assert gear_tip_top_lands(wider)[1] == pytest.approx(land - 0.1, abs=0.02)


def test_pointed_toe_is_refused_by_design_naming_the_point_width():
    # found by tests/report/test_design_space.py: z2 = 120 with a wide face passes the
    # mean-section top-land check but its toe is pointed; analyze then failed in the
    # tooth shell (mid-surface Jacobian < 0) instead of design naming the condition
    args = dict(z1=16, ratio=7.523109466961802, offset_frac=0.2976747705510888,
                beta=25.62282030712944, face_frac=0.34689485888287486, side="drive")
    with pytest.raises(InputRangeError) as err:
        design_space_pair(**args)
    assert err.value.field == "cutter.point_width_mm"
    bound = float(err.value.allowed.split()[1])
    pair = load_pair(_EXAMPLES / "iso23509_f3.toml")
    assert 0.0 < bound < pair.cutter.point_width_mm
    # the named width (less 0.05 mm, the first-order estimate's margin) leaves a top land
    base = replace(pair, pinion_teeth=16, gear_teeth=120, offset_mm=args["offset_frac"]
                   * pair.gear_mean_pitch_radius_mm, pinion_spiral_angle_deg=args["beta"])
    face = args["face_frac"] * base.blank.mean_cone_distance_gear_mm
    base = replace(base, gear_face_width_mm=face, pinion_face_width_mm=1.05 * face)
    with pytest.raises(InputRangeError):
        check_gear_top_land(base)
    fixed = replace(base, cutter=replace(base.cutter, point_width_mm=bound - 0.05))
    assert check_gear_top_land(fixed) > 0.0
    assert np.all(gear_tip_top_lands(fixed)[1] > 0.0)
