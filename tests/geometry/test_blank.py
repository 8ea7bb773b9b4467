"""Blank design against ISO 23509:2016 Annex F.3 and the published s0003 pitch cones."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.blank import design_blank, gear_top_land_mm
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError


def _f3():
    # ISO 23509 Annex F.3 inputs (Table F.4): z 13/42, a = 15 mm, beta_Delta1 = 50 deg,
    # r_c0 = 63.5 mm, d_e2 = 170 mm, b2 = 30 mm. The standard's Method 1 works with the
    # gear mean pitch radius of its eq. (11)-(12): r_mpt2 = (d_e2 - b2 sin(atan(u/1.2)))/2.
    u = 42 / 13
    r2 = (170.0 - 30.0 * np.sin(np.arctan(u / 1.2))) / 2.0
    return design_blank(pinion_teeth=13, gear_teeth=42, offset_mm=15.0,
                        pinion_spiral_angle_deg=50.0, cutter_radius_mm=63.5,
                        gear_mean_pitch_radius_mm=r2, gear_addendum_factor=0.35)


def test_iso23509_f3_sample():
    b = _f3()
    # Published values are rounded to 0.001; ISO's own iteration stops at
    # |rho_mBeta/rho_lim - 1| <= 0.01 and lands on beta_m1 = 49.998 deg, which moves R_m1
    # by ~0.002 mm: tolerance 0.005 mm / 0.002 deg (exact solution vs ISO iteration).
    assert b.mean_cone_distance_pinion_mm == pytest.approx(73.519, abs=0.005)
    assert b.mean_cone_distance_gear_mm == pytest.approx(76.337, abs=0.005)
    assert b.spiral_angle_gear_deg == pytest.approx(38.609, abs=0.002)
    assert b.limit_pressure_angle_deg == pytest.approx(-2.253, abs=0.001)
    assert b.offset_angle_axial_pinion_deg == pytest.approx(10.603, abs=0.001)
    assert b.offset_angle_pitch_plane_deg == pytest.approx(11.390, abs=0.001)
    assert b.mean_normal_module_mm == pytest.approx(2.640, abs=0.001)
    # tooth proportions (ISO F.3: h_mw 5.280, h_am2 1.848, h_fm2 4.092, h_am1 3.432,
    # h_fm1 2.508, c 0.660; alpha_nD 17.747, alpha_nC 22.253), rounding tolerance 0.002
    assert b.working_depth_mm == pytest.approx(5.280, abs=0.002)
    assert b.addendum_gear_mm == pytest.approx(1.848, abs=0.002)
    assert b.dedendum_gear_mm == pytest.approx(4.092, abs=0.002)
    assert b.addendum_pinion_mm == pytest.approx(3.432, abs=0.002)
    assert b.dedendum_pinion_mm == pytest.approx(2.508, abs=0.002)
    assert b.pressure_angle_drive_deg == pytest.approx(17.747, abs=0.001)
    assert b.pressure_angle_coast_deg == pytest.approx(22.253, abs=0.001)


def test_cone_relations_hold_exactly():
    # independent re-check of the defining equations (docs/geometry.md sec. 2) at 1e-12
    b = _f3()
    d1, d2 = np.radians([b.pitch_angle_pinion_deg, b.pitch_angle_gear_deg])
    zm, eta, zmp = np.radians([b.offset_angle_axial_pinion_deg, b.offset_angle_axial_gear_deg,
                               b.offset_angle_pitch_plane_deg])
    b1, b2 = np.radians([b.spiral_angle_pinion_deg, b.spiral_angle_gear_deg])
    r1, r2 = b.mean_pitch_radius_pinion_mm, b.mean_pitch_radius_gear_mm
    assert np.cos(zm) == pytest.approx(np.sin(d1) / np.cos(d2), abs=1e-12)
    assert np.cos(eta) == pytest.approx(np.sin(d2) / np.cos(d1), abs=1e-12)
    assert np.sin(zmp) == pytest.approx(np.sin(zm) / np.cos(d1), abs=1e-12)
    assert r2 * np.sin(zm) + r1 * np.sin(eta) == pytest.approx(15.0, abs=1e-10)
    assert r2 * np.cos(b2) / (r1 * np.cos(b1)) == pytest.approx(42 / 13, abs=1e-12)
    # the pitch point is at r2 from the gear axis and r1 from the pinion axis
    P = np.array(b.pitch_point_mm)
    assert np.hypot(P[0], P[1]) == pytest.approx(r2, abs=1e-10)
    assert np.hypot(P[1] + 15.0, P[2]) == pytest.approx(r1, abs=1e-10)


def test_s0003_published_pitch_cones():
    b = load_pair("s0003-centred").blank
    # published to 0.01 deg / 0.01 mm: the rounding interval is +-0.005
    assert round(b.pitch_angle_pinion_deg, 2) == 6.07
    assert round(b.pitch_angle_gear_deg, 2) == 83.15
    assert round(b.mean_cone_distance_gear_mm, 2) == 40.68
    # docs/geometry.md sec. 2 check values (computed independently, rounded to the digits given)
    assert b.offset_angle_axial_pinion_deg == pytest.approx(27.55, abs=0.005)
    assert b.offset_angle_axial_gear_deg == pytest.approx(3.18, abs=0.005)
    assert b.offset_angle_pitch_plane_deg == pytest.approx(27.72, abs=0.005)
    assert b.mean_pitch_radius_gear_mm == pytest.approx(40.390, abs=0.0005)
    assert b.mean_pitch_radius_pinion_mm == pytest.approx(5.717, abs=0.0005)
    assert b.mean_cone_distance_pinion_mm == pytest.approx(54.06, abs=0.005)
    assert b.spiral_angle_gear_deg == pytest.approx(21.01, abs=0.005)
    assert b.limit_pressure_angle_deg == pytest.approx(-4.33, abs=0.005)
    assert b.cutter_radius_mm == pytest.approx(45.1, abs=0.05)
    assert b.mean_normal_module_mm == pytest.approx(1.08, abs=0.005)
    assert np.allclose(b.pitch_point_mm, (35.81, -18.68, 5.71), atol=0.005)


def test_standard_cutter_variant():
    # docs/geometry.md sec. 2: a 3.5 in cutter (44.45 mm), beta1 = 50 deg, gives 6.079 / 83.140 deg
    b = design_blank(pinion_teeth=7, gear_teeth=70, offset_mm=19.0, pinion_spiral_angle_deg=50.0,
                     cutter_radius_mm=44.45, gear_mean_cone_distance_mm=40.68)
    assert b.pitch_angle_pinion_deg == pytest.approx(6.079, abs=0.0005)
    assert b.pitch_angle_gear_deg == pytest.approx(83.140, abs=0.0005)


def test_spiral_bevel_limit():
    # E = 0: ISO Method 0, tan(delta1) = z1/z2 and beta1 = beta2 (ISO F.2: 14/39 -> 19.747 deg)
    b = design_blank(pinion_teeth=14, gear_teeth=39, offset_mm=0.0, pinion_spiral_angle_deg=35.0,
                     cutter_radius_mm=114.3, gear_mean_cone_distance_mm=81.273)
    assert b.pitch_angle_pinion_deg == pytest.approx(19.747, abs=0.0005)
    assert b.spiral_angle_gear_deg == pytest.approx(35.0, abs=1e-12)
    assert b.mean_normal_module_mm == pytest.approx(3.213, abs=0.001)


def test_miter_pair():
    # z2 = z1, E = 0: the 1:1 miter pair, tan(delta1) = z1/z2 = 1 -> both pitch angles
    # 45 deg, equal pitch radii (rounding only: 1e-12)
    b = design_blank(pinion_teeth=20, gear_teeth=20, offset_mm=0.0, pinion_spiral_angle_deg=35.0,
                     cutter_radius_mm=63.5, gear_mean_pitch_radius_mm=60.0)
    assert b.pitch_angle_pinion_deg == pytest.approx(45.0, abs=1e-12)
    assert b.pitch_angle_gear_deg == pytest.approx(45.0, abs=1e-12)
    assert b.mean_pitch_radius_pinion_mm == pytest.approx(60.0, abs=1e-12)


def test_pointed_gear_teeth_refused_naming_the_field():
    # Rack approximation of the mean normal section: gear top land
    # s_a2 = pi m_mn - W - k_d (1 + k_c) m_mn (tan alpha_nD + tan alpha_nC). Independent
    # truth: the k_d and W where it vanishes, from the closed form with the F.3 blank.
    from dataclasses import replace
    pair = load_pair(Path(__file__).resolve().parents[2] / "examples" / "iso23509_f3.toml")
    b = pair.blank
    t = (np.tan(np.radians(b.pressure_angle_drive_deg))
         + np.tan(np.radians(b.pressure_angle_coast_deg)))
    land = np.pi * b.mean_normal_module_mm - 1.5 - 2.0 * 1.125 * b.mean_normal_module_mm * t
    assert gear_top_land_mm(b, 1.5) == pytest.approx(land, rel=1e-12)
    w_max = 1.5 + land
    replace(pair, cutter=replace(pair.cutter, point_width_mm=w_max * (1 - 1e-6)))
    with pytest.raises(InputRangeError) as err:
        replace(pair, cutter=replace(pair.cutter, point_width_mm=w_max * (1 + 1e-6)))
    assert err.value.field == "cutter.point_width_mm" and f"< {w_max:.4g}" in err.value.allowed
    # issue 28: k_d = 50 was blamed on gear_addendum_factor; no point width helps there
    # (alpha_n does not depend on k_d, so the closed form k_max = pi / ((1 + k_c) t) holds)
    with pytest.raises(InputRangeError) as err:
        replace(pair, working_depth_factor=50.0)
    assert err.value.field == "design.working_depth_factor"
    assert f"< {np.pi / (1.125 * t):.4g}" in err.value.allowed


def test_absurd_gear_teeth_blamed_on_the_gear_teeth():
    # issue 28: 100,000 gear teeth were blamed on the spiral angle and cutter radius.
    # The error names gear_teeth and the largest tooth number with pitch cones; that
    # bound is checked against the design itself (it designs, one more does not).
    import re
    base = dict(pinion_teeth=13, offset_mm=15.0, pinion_spiral_angle_deg=50.0,
                cutter_radius_mm=63.5, gear_mean_pitch_radius_mm=70.9)
    with pytest.raises(InputRangeError) as err:
        design_blank(gear_teeth=100_000, **base)
    assert err.value.field == "gear_teeth"
    bound = int(re.match(r"<= (\d+)", err.value.allowed).group(1))
    design_blank(gear_teeth=bound, **base)
    with pytest.raises(InputRangeError):
        design_blank(gear_teeth=bound + 1, **base)


@pytest.mark.parametrize("kwargs, field", [
    (dict(pinion_teeth=3), "pinion_teeth"),
    (dict(gear_teeth=6), "gear_teeth"),
    (dict(offset_mm=30.0), "offset_mm"),
    (dict(offset_mm=-1.0), "offset_mm"),
    (dict(shaft_angle_deg=80.0), "shaft_angle_deg"),
    (dict(pinion_spiral_angle_deg=20.0), "pinion_spiral_angle_deg"),
    (dict(cutter_radius_mm=-4.0), "cutter_radius_mm"),
])
def test_impossible_designs(kwargs, field):
    base = dict(pinion_teeth=7, gear_teeth=70, offset_mm=19.0, pinion_spiral_angle_deg=48.7,
                cutter_radius_mm=45.1, gear_mean_cone_distance_mm=40.68)
    base.update(kwargs)
    with pytest.raises(InputRangeError) as err:
        design_blank(**base)
    assert field in err.value.field


def test_flat_cone_inside_a_bracket_is_no_warning():
    # found by issue 28's probe: design of 12/12, E = 0.3 r2, beta1 = 45 deg printed
    # "warning: divide by zero" - the contact-ratio fix search designs beta1 = 59.648 deg,
    # where an offset-equation root bracket holds a flat gear cone (sin(delta2) = 0 in
    # the cone distance, which that equation does not use). The blank still solves: its
    # offset equation holds to rounding (1e-10 mm)
    import warnings

    r2 = load_pair(Path(__file__).resolve().parents[2] / "examples"
                   / "iso23509_f3.toml").gear_mean_pitch_radius_mm
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        b = design_blank(pinion_teeth=12, gear_teeth=12, offset_mm=0.3 * r2,
                         pinion_spiral_angle_deg=59.6484375, cutter_radius_mm=63.5,
                         gear_mean_pitch_radius_mm=r2, gear_addendum_factor=0.35)
    zm, eta = np.radians([b.offset_angle_axial_pinion_deg, b.offset_angle_axial_gear_deg])
    assert (b.mean_pitch_radius_gear_mm * np.sin(zm) + b.mean_pitch_radius_pinion_mm
            * np.sin(eta)) == pytest.approx(0.3 * r2, abs=1e-10)


def test_no_cones_blame_survives_an_undefined_residual():
    # found by issue 28's design-space runs: z1/z2 = 5/36, E = 0.09 r2, beta1 = 22.3 deg.
    # The rho_lim = r_c0 residual is undefined (NaN) at points inside a sign-change
    # bracket of one of the spiral angles tried for the blame; brentq raised a bare
    # ValueError from design instead of the named condition
    base = load_pair(Path(__file__).resolve().parents[2] / "examples" / "iso23509_f3.toml")
    kw = dict(pinion_teeth=5, gear_teeth=36, offset_mm=0.09005790994924236
              * base.gear_mean_pitch_radius_mm, gear_face_width_mm=10.0,
              pinion_face_width_mm=10.5)
    with pytest.raises(InputRangeError) as err:
        replace(base, pinion_spiral_angle_deg=22.294710334644698, **kw)
    assert err.value.field == "pinion_spiral_angle_deg / cutter_radius_mm"
    # the named spiral angle has pitch cones with rho_lim = r_c0 (the blank designs)
    named = float(err.value.allowed.split("pinion_spiral_angle_deg = ")[1].split(",")[0])
    blank = replace(base, pinion_spiral_angle_deg=named, **kw).blank
    assert blank.spiral_angle_pinion_deg == pytest.approx(named, abs=1e-9)
