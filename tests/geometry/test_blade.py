"""Toprem / Flankrem blades (geometry.blade) against closed forms.

A relief segment is the straight line through the main profile's point at the kink
depth, turned by the relief angle into the cut tooth: its normal offset from the main
(straight) profile continued past the kink is ``t tan(delta)`` at the distance ``t``
along the main profile (plane geometry), and the profile is continuous at the kink.
"""

import dataclasses
import math

import numpy as np
import pytest

from gearcontact.geometry.blade import BladeSettings, blade_profile, blade_segments, edge_round
from gearcontact.validation import InputRangeError


def _blade(kind, **kw):
    return BladeSettings(kind, 20.0, 100.0, edge_radius_mm=0.4, where="blade.pinion.drive", **kw)


@pytest.mark.parametrize("kind", ["inside", "outside"])
def test_relief_segments_leave_the_main_profile_by_t_tan_delta(kind):
    # straight main profile: every closed form is plane geometry; 1e-12 mm (rounding of
    # the quadrature-free straight segments), measured ~1e-14
    b = _blade(kind, toprem_angle_deg=3.0, toprem_depth_mm=1.5, flankrem_angle_deg=2.0,
               flankrem_depth_mm=6.0)
    main = BladeSettings(kind, 20.0, 100.0)
    a0, sig = math.radians(20.0), b.sigma
    l = np.linspace(0.0, 9.0, 91)
    rho, z, alpha, _ = blade_profile(b, l)
    # offset from the main line, positive into the slot (along the profile normal)
    off = (sig * (rho - (100.0 - sig * math.tan(a0) * z))) * math.cos(a0)
    t_top = np.maximum(1.5 - z, 0.0) / math.cos(a0)     # along the main line from the kink
    t_flank = np.maximum(z - 6.0, 0.0) / math.cos(a0)
    # the normal distance of the relief line from the main line at equal depth (t along
    # the main line): t sin(d) cos(a0) / cos(a0 -+ d) = t tan(d) (1 +- d tan(a0) + ...)
    exact = np.where(z < 1.5, -t_top * math.sin(math.radians(3.0)) * math.cos(a0)
                     / math.cos(a0 - math.radians(3.0)),
                     np.where(z > 6.0, -t_flank * math.sin(math.radians(2.0)) * math.cos(a0)
                              / math.cos(a0 + math.radians(2.0)), 0.0))
    assert np.allclose(off, exact, atol=1e-12)
    np.testing.assert_allclose(np.degrees(alpha[z < 1.5]), 17.0, atol=1e-12)
    np.testing.assert_allclose(np.degrees(alpha[(z > 1.5) & (z < 6.0)]), 20.0, atol=1e-12)
    np.testing.assert_allclose(np.degrees(alpha[z > 6.0]), 22.0, atol=1e-12)
    # continuous at each kink (the segments' own arcs meet there), 1e-12 mm
    for seg in blade_segments(b)[1:]:
        lo = np.array(blade_profile(b, seg.arc_mm - 1e-13)[:2])
        hi = np.array(blade_profile(b, seg.arc_mm)[:2])
        assert np.all(np.abs(hi - lo) < 1e-12)
    # the main segment is the blade without relief; the edge round sits on the tip segment
    assert blade_profile(main, 3.0)[0] == pytest.approx(
        float(blade_profile(b, 3.0 - blade_segments(b)[1].own_arc_mm
                            + blade_segments(b)[1].arc_mm)[0]), abs=1e-12)
    assert edge_round(b).top_angle_rad == pytest.approx(math.radians(17.0), abs=1e-14)


def test_zero_relief_is_the_smooth_blade():
    b = _blade("outside", toprem_angle_deg=0.0, toprem_depth_mm=2.0)
    assert not b.relieved and len(blade_segments(b)) == 1
    l = np.linspace(0.0, 8.0, 17)
    plain = _blade("outside")
    for x, y in zip(blade_profile(b, l), blade_profile(plain, l)):
        assert np.array_equal(x, y)


@pytest.mark.parametrize("kw, key, needle", [
    ({"toprem_angle_deg": 12.0, "toprem_depth_mm": 2.0}, "toprem_angle_deg", "[0, 10]"),
    ({"toprem_angle_deg": -1.0, "toprem_depth_mm": 2.0}, "toprem_angle_deg", "[0, 10]"),
    ({"toprem_angle_deg": 2.0}, "toprem_depth_mm", "(0, 50]"),
    ({"toprem_angle_deg": 2.0, "toprem_depth_mm": 60.0}, "toprem_depth_mm", "[0, 50]"),
    ({"toprem_angle_deg": 2.0, "toprem_depth_mm": 0.1}, "toprem_depth_mm", "edge round"),
    ({"toprem_angle_deg": 2.0, "toprem_depth_mm": 3.0, "flankrem_angle_deg": 2.0,
      "flankrem_depth_mm": 2.0}, "flankrem_depth_mm", "> toprem_depth_mm"),
    ({"flankrem_angle_deg": 9.0, "flankrem_depth_mm": 4.0, "blade_angle_deg": 40.0},
     "flankrem_angle_deg", "< 45"),
])
def test_bad_relief_named_with_value_and_range(kw, key, needle):
    args = {"blade_angle_deg": 20.0, **kw}
    with pytest.raises(InputRangeError) as err:
        BladeSettings("inside", point_radius_mm=100.0, edge_radius_mm=0.4,
                      where="blade.pinion.coast", **args)
    msg = str(err.value)
    assert f"blade.pinion.coast.{key}" in msg and needle in msg, msg


def test_toprem_angle_beyond_the_blade_angle_is_named():
    with pytest.raises(InputRangeError, match=r"toprem_angle_deg.*\[0, 5\.0000\]"):
        dataclasses.replace(_blade("inside"), blade_angle_deg=5.0, toprem_angle_deg=6.0,
                            toprem_depth_mm=2.0)


def test_toprem_depth_beyond_the_blade_is_named_by_its_own_key():
    # straight 20 deg main blade, 3 deg Toprem: the segment's reference arc is
    # depth / cos(17 deg), within the blade's 50 mm up to 50 cos(17 deg) = 47.8152 mm;
    # the error names the key typed, not the derived profile_reference_mm
    BladeSettings("outside", 20.0, 100.0, where="blade.pinion.drive",
                  toprem_angle_deg=3.0, toprem_depth_mm=47.8)
    with pytest.raises(InputRangeError, match=r"toprem_depth_mm = 47\.9.*\(0, 47\.8152\]"):
        BladeSettings("outside", 20.0, 100.0, where="blade.pinion.drive",
                      toprem_angle_deg=3.0, toprem_depth_mm=47.9)


def test_relief_keys_round_trip_through_the_pair_tables():
    from gearcontact.geometry.machine import setup_from_tables, setup_to_tables

    # a pinion is generated: its ratio of roll > 0 (a formate pinion is refused on load)
    machine = {"radial_distance_mm": 90.0, "cradle_angle_deg": 60.0,
               "machine_root_angle_deg": 20.0, "ratio_of_roll": 4.0}
    blade = {"kind": "outside", "blade_angle_deg": 20.0, "point_radius_mm": 100.0,
             "edge_radius_mm": 0.4, "toprem_angle_deg": 2.0, "toprem_depth_mm": 2.0,
             "flankrem_angle_deg": 1.5, "flankrem_depth_mm": 6.0}
    setup = setup_from_tables("pinion", "drive", machine, blade)
    assert setup.blade.relieved
    back = setup_to_tables(setup)[1]
    assert {k: back[k] for k in blade} == blade
    plain = setup_to_tables(setup_from_tables("pinion", "drive", machine, {
        k: v for k, v in blade.items() if "rem" not in k}))[1]
    assert not any("rem" in k for k in plain)      # written only when non-zero
    with pytest.raises(InputRangeError, match="blade.pinion.drive.toprem_depth_mm"):
        setup_from_tables("pinion", "drive", machine, {**blade, "toprem_depth_mm": 0.0})
