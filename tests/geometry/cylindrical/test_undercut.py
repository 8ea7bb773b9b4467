"""An undercut cylindrical member (gearcontact.geometry.cylindrical.trochoid: the rack
tip's trochoid trims the involute) against independent truths.

Truths:
- the ISO 21771 undercut limit x_min = h_FfP* - z sin^2(alpha_t) / (2 cos beta),
  h_FfP* = h_fP* - rho_fP* (1 - sin alpha_n) (for the ISO 53 rack A 1 - 3.24e-5: the
  textbook h_aP* = 1 but for rho_fP* = 0.38 being 0.25 / (1 - sin 20 deg) rounded), and the textbook
  theoretical z_min = 2 cos(beta) / sin^2(alpha_t) = 17.1 for 20 deg spur (Niemann /
  Winter ch. 21): z = 17 at x = 0 is (just) undercut, z = 18 is not;
- undercut exactly when x < x_min, checked on the generated boundary itself: the
  involute points the rack's tip rounding cuts away are those inside some position of
  the rounding (tests/rack_envelope.py: the min over the rack shift of the rounding's
  implicit function, from the rolling of the pitch circle alone). At x = x_min + 0.01
  no involute point from the base circle to the tip is inside (>= -1e-12 mm: the
  helper's round-off, measured ~1e-14); at x = x_min - 0.01 the points below the
  crossing are (the cut grows as (x_min - x)^3: ~1e-7 mm here, far above the
  round-off), those above it are not. The module's own flag at x_min -/+ 1e-3 (its
  resolution, 1e-14 rad, is reached at ~1e-4 below the limit for z <= 30);
- the crossing lies on both curves: the fillet's last point and the flank's first point
  coincide within 1e-9 mm (measured ~1e-14: Brent to 1e-15 rad), both facings, at three
  face positions of a helical tooth, and both lie on the rack's envelope (1e-9 mm);
- the TCA of the undercut pair: unmodified flanks have TE0 = 0 (1e-3 arcsec, as the
  other cylindrical pairs) and the mean number of pairs in the zone is eps_gamma of the
  path shortened by the undercut (within the phase step, 1 / 100: the start of the path
  moved to the form circle d_Ff);
- the mating tip clears the undercut (what lets the path start at d_Ff instead of
  refusing the pair as interference): the gear's tip arc, moved in the ideal mesh at
  a_w (both flanks closed, the pinion tooth on the line of centres at phase 0), never
  enters the pinion tooth bounded by its involute above d_Ff and its retained trochoid
  below (polar form, the trochoid's polar angle interpolated over 20001 samples):
  largest penetration < 0 on 12/40, 14/40 spur and 12/40 helical 15 deg (measured
  clearances 3.5, 0.65 and 1.5 um: the rack, whose straight flank ends at the gear's
  addendum height, is the limiting mate), while on the 20/40 pair without undercut the
  tip touches the involute where the path starts (penetration within -1e-6..1e-9 mm:
  the phase grid's resolution, measured -1.1e-9); a gear addendum of 1.2 m instead
  cuts 0.082 mm into the undercut root, and the geometry refuses the pair naming that
  depth (geometry.cylindrical.undercut_mesh, within its printed 1e-4 mm);
- careless input: an undercut cutting the whole involute names the profile shift, z
  and x_min; a path the undercut shortens below eps_alpha = 1 says so.
"""

import math

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.fillet import root_fillet
from gearcontact.geometry.cylindrical.flank import involute_flank
from gearcontact.geometry.cylindrical.pair import CylindricalPair
from gearcontact.geometry.cylindrical.trochoid import (generated_form,
                                                       undercut_limit_profile_shift)
from gearcontact.report.design_cylindrical import cylindrical_design_text
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.validation import InputRangeError, UnusableInput
from rack_envelope import envelope_gap_mm
from rack_envelope import rack as rack_of

SIDES = {"cw": "coast", "ccw": "drive"}      # facing -> the envelope helper's side


def _pair(x1=0.0, *, beta=0.0, z1=12, z2=40, x2=0.0):
    return CylindricalPair(name="undercut", pinion_teeth=z1, gear_teeth=z2,
                           normal_module_mm=3.0, pinion_face_width_mm=20.0,
                           gear_face_width_mm=20.0, helix_angle_deg=beta,
                           pinion_hand="right" if beta else None, profile_shift_pinion=x1,
                           profile_shift_gear=x2)


def _x_min(z, beta=0.0, alpha=20.0, h_fp=1.25, rho=0.38):
    return undercut_limit_profile_shift(teeth=z, normal_pressure_angle_deg=alpha,
                                        helix_angle_deg=beta, dedendum_factor=h_fp,
                                        tip_radius_factor=rho)


def test_iso_21771_limit_and_textbook_minimum_teeth():
    # rho_fP* = 0.38 is 0.25 / (1 - sin 20 deg) = 0.37995 rounded: h_FfP* = 1 - 3.24e-5
    off = 0.38 * (1.0 - math.sin(math.radians(20.0))) - 0.25
    h = 1.25 - 0.38 * (1.0 - math.sin(math.radians(20.0)))
    assert h == pytest.approx(1.0 - off, abs=1e-15) and 3.2e-5 < off < 3.3e-5
    for z in (8, 12, 17, 30):
        s2 = math.sin(math.radians(20.0)) ** 2
        assert _x_min(z) == pytest.approx(1.0 - off - z * s2 / 2.0, abs=1e-14)
    b = math.radians(15.0)
    at = math.atan(math.tan(math.radians(20.0)) / math.cos(b))
    z_min = 2.0 * h * math.cos(b) / math.sin(at) ** 2        # x_min(z_min) = 0
    assert _x_min(z_min, beta=15.0) == pytest.approx(0.0, abs=1e-12)
    assert 2.0 / math.sin(math.radians(20.0)) ** 2 == pytest.approx(17.1, abs=0.01)
    assert _pair(z1=17).geometry.undercut_pinion and not _pair(z1=18).geometry.undercut_pinion


@pytest.mark.parametrize("z, beta, alpha, h_fp, rho", [(12, 0.0, 20.0, 1.25, 0.38),
                                                       (9, 25.0, 20.0, 1.25, 0.38),
                                                       (14, 15.0, 25.0, 1.4, 0.3),
                                                       (8, 0.0, 20.0, 1.25, 0.0),
                                                       (30, 0.0, 20.0, 1.25, 0.38)])
def test_flag_flips_at_the_limit(z, beta, alpha, h_fp, rho):
    x_min = _x_min(z, beta, alpha, h_fp, rho)
    for dx, cut in ((-1e-3, True), (1e-3, False)):
        form = generated_form(teeth=z, normal_module_mm=2.0, profile_shift=x_min + dx,
                              normal_pressure_angle_deg=alpha, helix_angle_deg=beta,
                              dedendum_factor=h_fp, tip_radius_factor=rho)
        assert form.undercut is cut and (form.crossing is not None) is cut


@pytest.mark.parametrize("beta", [0.0, 15.0])
def test_the_rack_cuts_the_involute_exactly_below_x_min(beta):
    x_min = _x_min(12, beta)
    for dx in (0.01, -0.01):
        pair = _pair(x_min + dx, beta=beta)
        g = pair.geometry
        assert g.undercut_pinion is (dx < 0.0)
        assert g.undercut_limit_shift_pinion == pytest.approx(x_min, abs=1e-15)
        rack = rack_of(pair, "pinion")
        flank = involute_flank(pair, "pinion", "ccw")
        u0, u_a = flank.u_range
        # the involute from just above the base circle (extrapolated below d_Ff) to the tip
        u = np.concatenate([np.linspace(0.02 * u0, u0, 8), np.linspace(u0, u_a, 8)[1:]])
        gaps = np.array([envelope_gap_mm(rack, "drive", p)
                         for p in flank.evaluate(u, np.zeros_like(u)).r])
        if dx > 0.0:
            assert gaps.min() > -1e-12, gaps
        else:
            below, above = gaps[u < u0 * (1 - 1e-9)], gaps[u >= u0]
            assert below.max() < -1e-9 and above.min() > -1e-12, gaps


@pytest.mark.parametrize("beta", [0.0, 15.0])
@pytest.mark.parametrize("facing", ["cw", "ccw"])
def test_crossing_lies_on_both_curves(beta, facing):
    pair = _pair(0.0, beta=beta)
    assert pair.geometry.undercut_pinion
    flank, fillet = involute_flank(pair, "pinion", facing), root_fillet(pair, "pinion", facing)
    assert fillet.u_range[1] < -math.radians(20.0)        # the fillet stops short of -alpha_n
    rack = rack_of(pair, "pinion")
    v = np.array([-10.0, 0.0, 10.0])
    a = flank.evaluate(np.full(3, flank.u_range[0]), v).r
    b = fillet.evaluate(np.full(3, fillet.u_range[1]), v).r
    assert np.abs(a - b).max() < 1e-9, np.abs(a - b).max()
    assert 2.0 * np.hypot(a[1, 0], a[1, 1]) == pytest.approx(
        pair.geometry.form_diameter_pinion_mm, abs=1e-9)
    for p in np.concatenate([a, b]):
        assert abs(envelope_gap_mm(rack, SIDES[facing], p)) < 1e-9


@pytest.mark.parametrize("beta", [0.0, 15.0])
def test_tca_of_the_undercut_pair(beta):
    pair = _pair(0.0, beta=beta)
    g = pair.geometry
    # the gear tip reaches below the crossing: the path starts on the form circle
    line = g.centre_distance_mm * math.sin(math.radians(g.working_pressure_angle_deg))
    u_a2 = 0.5 * math.sqrt(g.tip_diameter_gear_mm ** 2 - g.base_diameter_gear_mm ** 2)
    u_ff1 = g.roll_lengths_mm("pinion")["form"]
    assert line - u_a2 < u_ff1
    assert g.active_start_diameter_pinion_mm == pytest.approx(g.form_diameter_pinion_mm,
                                                              rel=1e-12)
    u_a1 = g.roll_lengths_mm("pinion")["tip"]
    assert g.length_of_contact_mm == pytest.approx(u_a1 - u_ff1, rel=1e-12)
    cycle = cylindrical_mesh_cycle(pair, phases=101)
    assert cycle.te0_pp_arcsec < 1e-3
    assert np.abs(cycle.envelope_arcsec).max() < 1e-3
    assert cycle.mean_pairs_in_zone == pytest.approx(g.total_contact_ratio, abs=0.01)


def _tip_penetration_mm(pair, gear_tip_radius_mm=None):
    """Largest penetration (mm, > 0 inside) of the gear's tip arc into the pinion teeth
    over five pinion pitches of the ideal mesh (module docstring), transverse section;
    ``gear_tip_radius_mm`` replaces the gear's r_a (the pinion and a_w stay)."""
    g = pair.geometry
    z1, z2 = pair.pinion_teeth, pair.gear_teeth
    at = math.radians(g.transverse_pressure_angle_deg)
    rb1, ra1 = 0.5 * g.base_diameter_pinion_mm, 0.5 * g.tip_diameter_pinion_mm
    r_ff = 0.5 * g.form_diameter_pinion_mm

    def inv(a):
        return np.tan(a) - a
    half = 0.5 * math.pi / z1 + inv(at)                    # x1 = 0
    fillet = root_fillet(pair, "pinion", "ccw")
    pts, _ = fillet.transverse(np.linspace(*fillet.u_range, 20001))
    rad, ang = np.hypot(pts[:, 0], pts[:, 1]), np.arctan2(pts[:, 1], pts[:, 0])
    assert np.all(np.diff(rad) > 0.0)

    def boundary(r):                                      # the tooth's half angle at r
        out = np.interp(r, rad, ang)
        hi = r >= r_ff
        out[hi] = half - inv(np.arccos(rb1 / r[hi]))
        return out
    ra2, rb2 = 0.5 * g.tip_diameter_gear_mm, 0.5 * g.base_diameter_gear_mm
    ra2 = ra2 if gear_tip_radius_mm is None else gear_tip_radius_mm
    s_t2 = 0.5 * math.pi * g.transverse_module_mm           # x2 = 0
    eta_a = s_t2 / g.reference_diameter_gear_mm + inv(at) - inv(math.acos(rb2 / ra2))
    phi = np.linspace(-5.0 * math.pi / z1, 5.0 * math.pi / z1, 20001)[:, None]
    eta = np.linspace(-eta_a, eta_a, 21)[None, :]
    worst = -np.inf
    for k in range(-3, 4):          # the gear's space faces the pinion at phase 0
        a = math.pi + math.pi / z2 + 2.0 * math.pi * k / z2 + eta - phi * z1 / z2
        x, y = g.centre_distance_mm + ra2 * np.cos(a), ra2 * np.sin(a)
        px, py = np.cos(phi) * x + np.sin(phi) * y, np.cos(phi) * y - np.sin(phi) * x
        r = np.hypot(px, py)
        rel = (np.arctan2(py, px) + math.pi / z1) % (2.0 * math.pi / z1) - math.pi / z1
        m = r <= ra1
        if np.any(m):
            worst = max(worst, float(np.max((boundary(r[m]) - np.abs(rel[m])) * r[m])))
    return worst


@pytest.mark.parametrize("z1, beta, undercut", [(12, 0.0, True), (14, 0.0, True),
                                                (12, 15.0, True), (20, 0.0, False)])
def test_the_mating_tip_clears_the_undercut(z1, beta, undercut):
    pair = _pair(0.0, beta=beta, z1=z1)
    assert pair.geometry.undercut_pinion is undercut
    pen = _tip_penetration_mm(pair)
    if undercut:
        assert pen < 0.0, pen
    else:
        assert -1e-6 < pen <= 1e-9, pen


def test_a_longer_mating_tip_cutting_the_undercut_is_interference():
    # gear addendum 1.2 m (blank d_a given) on the undercut 12-tooth pinion: the brute
    # force above finds its tip 0.082 mm inside the pinion's undercut root, the geometry
    # refuses the pair naming that depth (printed to 1e-4 mm: the bound); 1.1 m clears
    r_a = 60.0 + 3.0 * 1.2
    pen = _tip_penetration_mm(_pair(0.0), gear_tip_radius_mm=r_a)
    assert pen > 0.05
    with pytest.raises(InputRangeError) as err:
        CylindricalPair(name="undercut", pinion_teeth=12, gear_teeth=40, normal_module_mm=3.0,
                        pinion_face_width_mm=20.0, gear_face_width_mm=20.0,
                        tip_diameter_gear_mm=2.0 * r_a)
    e = err.value
    assert e.field == "cylindrical.profile_shift_pinion" and "interference" in e.allowed
    got = float(e.allowed.split("cuts ")[1].split(" mm")[0])
    assert got == pytest.approx(pen, abs=1e-4), (got, pen)
    assert _tip_penetration_mm(_pair(0.0), gear_tip_radius_mm=60.0 + 3.0 * 1.1) < 0.0
    CylindricalPair(name="undercut", pinion_teeth=12, gear_teeth=40, normal_module_mm=3.0,
                    pinion_face_width_mm=20.0, gear_face_width_mm=20.0,
                    tip_diameter_gear_mm=2.0 * (60.0 + 3.0 * 1.1))


def test_design_reports_the_undercut():
    text = cylindrical_design_text(_pair(0.0))
    row = next(line for line in text.splitlines() if line.startswith("undercut (x < x_min)"))
    assert row.split()[-2:] == ["yes", "no"]
    row = next(line for line in text.splitlines() if line.startswith("undercut limit x_min"))
    assert float(row.split()[-2]) == pytest.approx(_x_min(12), abs=1e-4)


def test_careless_inputs_name_the_limit():
    with pytest.raises(InputRangeError) as err:
        _pair(-1.0, z1=5, x2=1.0)
    e = err.value
    assert e.field == "cylindrical.profile_shift_pinion" and e.value == -1.0
    assert f">= {_x_min(5):.4f}" in e.allowed and "z = 5" in e.allowed
    assert "whole involute" in e.allowed
    with pytest.raises(UnusableInput, match=r"eps_alpha = 0\.91.*pinion \(z = 8, x = 0\) is "
                                            r"undercut below x_min = 0\.5321"):
        _pair(0.0, z1=8)
    # no undercut (x_min(30) = -0.754), but a shift sum below -inv(alpha) (z1 + z2) /
    # (2 tan alpha) = -1.2285: no working pressure angle, named before any other check
    a = math.radians(20.0)
    low = -(math.tan(a) - a) * 60 / (2.0 * math.tan(a))
    with pytest.raises(InputRangeError, match=r"profile_shift_pinion \+ profile_shift_gear = "
                                              rf"-1\.4.*>= {low:.4f}"):
        _pair(-0.7, z1=30, z2=30, x2=-0.7)
