"""Standard settings from the blank (issue #27 item 3): formate gear + complementary
pinion localized by a cutter-radius mismatch and a circular pinion blade.

Truths: the localized pinion keeps the blank's mean point and pressure angle (its mean
node and normal equal the conjugate pinion's: the blade point generating it keeps
position and normal, so the envelope keeps it), the circular blade departs from the
straight one by the requested amount (closed-form circle), and the lengthwise relief of
the generated pinion follows the mismatch formula (second-order, measured 0.91 / 0.97).
"""

import math

import numpy as np
import pytest

from gearcontact.geometry.basic_settings import (complementary_pinion_setups, crown_profile,
                                                 standard_setups)
from gearcontact.geometry.conjugate import nominal_pinion_box
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.generated import EnvelopeSolver, generated_pinion_flank
from gearcontact.geometry.machine import BladeSettings, blade_profile
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError

F2 = "examples/iso23509_f2_spiral_bevel.toml"


@pytest.fixture(scope="module", params=[F2, "s0003-centred"])
def pair(request):
    return load_pair(request.param)


def test_standard_pinion_keeps_mean_point_and_pressure_angle(pair):
    # mean node of each pinion flank and its normal: equal to the conjugate (complementary)
    # pinion's within 1e-9 mm / 1e-12 (both exact node solves to 1e-10; measured 4e-14)
    std = standard_setups(pair, lengthwise_crowning_um=30.0, blade_profile_crowning_um=15.0)
    cone, _ = nominal_pinion_box(pair.blank, pair.pinion_face_width_mm)
    u_m, v_m = float(cone.root_offset_mm), float(pair.blank.pitch_point_mm[0])
    for side, conj in complementary_pinion_setups(pair).items():
        a = EnvelopeSolver(conj, pair.blank, cone)
        m0 = a.solve(u_m, v_m, a.initial_guess(u_m, v_m))
        m1 = EnvelopeSolver(std["pinion", side], pair.blank, cone).solve(u_m, v_m, m0.q)
        assert np.abs(m1.x_mm - m0.x_mm).max() < 1e-9
        assert np.abs(m1.n - m0.n).max() < 1e-12
        # and the settings really changed (the test is not vacuous)
        assert std["pinion", side].settings.radial_distance_mm != pytest.approx(
            conj.settings.radial_distance_mm, abs=0.1)
        assert std["pinion", side].blade.profile_radius_mm > 0.0
    assert std["gear", "drive"].settings.ratio_of_roll == 0.0


def test_crowned_blade_departs_by_the_requested_amount():
    # circle of radius r tangent to the straight blade at l_m: normal departure at
    # +-s along the blade is r - sqrt(r^2 - s^2) (exact circle; 1e-9 mm)
    straight = BladeSettings(kind="outside", blade_angle_deg=21.0, point_radius_mm=60.0)
    l_m, r = 3.0, 400.0
    curved = crown_profile(straight, radius_mm=r, at_length_mm=l_m)
    a = math.radians(21.0)
    t = np.array([math.sin(a), math.cos(a)])       # (rho', z') of the outside blade's line
    n = np.array([math.cos(a), -math.sin(a)])      # square to it in the (rho, z) plane
    p_m = np.array([float(x) for x in blade_profile(straight, l_m)[:2]])
    ls = np.linspace(0.0, 6.0, 13)
    rho, z, _, _ = blade_profile(curved, ls)
    pts = np.stack([rho, z], axis=-1) - p_m
    s, dev = pts @ t, pts @ n
    assert np.abs(np.abs(dev) - (r - np.sqrt(r * r - s * s))).max() < 1e-9
    assert np.ptp(np.sign(dev[np.abs(dev) > 1e-12])) == 0.0   # one side of the line


def test_lengthwise_crowning_of_the_generated_pinion():
    # relief of the standard pinion against the conjugate one along the mean-height
    # line, fitted by a s^2 (s: arc length along the tooth from the mean node): a within
    # 15 % of the design c / (F2/2)^2 (second-order design formula; measured 0.91 / 0.97)
    pair = load_pair(F2)
    c = 25.0
    std = standard_setups(pair, lengthwise_crowning_um=c, blade_profile_crowning_um=0.0)
    for side, conj in complementary_pinion_setups(pair).items():
        f0, _ = generated_pinion_flank(conj, pair.blank, pinion_face_width_mm=pair.pinion_face_width_mm,
                                       n_u=30, n_v=40)
        f1, _ = generated_pinion_flank(std["pinion", side], pair.blank,
                                       pinion_face_width_mm=pair.pinion_face_width_mm, n_u=30, n_v=40)
        u_m, v_m = float(f0.cone.root_offset_mm), float(pair.blank.pitch_point_mm[0])
        vs = np.linspace(*f0.v_range, 41)
        s0, s1 = (f.evaluate(np.full_like(vs, u_m), vs) for f in (f0, f1))
        arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(s0.r, axis=0), axis=1))])
        arc -= np.interp(v_m, vs, arc)
        relief_um = -1e3 * np.einsum("ij,ij->i", s1.r - s0.r, s0.n)
        a = np.polyfit(arc, relief_um, 2)[0]
        assert a / (c / (0.5 * pair.gear_face_width_mm) ** 2) == pytest.approx(1.0, abs=0.15)


def test_crowning_out_of_range_is_refused():
    pair = load_pair(F2)
    with pytest.raises(InputRangeError, match="lengthwise_crowning_um"):
        standard_setups(pair, lengthwise_crowning_um=-1.0)
    with pytest.raises(InputRangeError, match="blade_profile_crowning_um"):
        standard_setups(pair, blade_profile_crowning_um=500.0)


def test_example_summary_sheet_is_the_standard_settings_rounded():
    # examples/machine_settings/iso23509_f2_machine.toml (provenance in its header): the standard settings
    # of the F.2 blank typed with 4 decimals (ratio of roll 6): every setting within the
    # rounding, 5e-5 (5e-7 for the ratio of roll)
    import dataclasses as dc
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    typed = load_pair(root / "examples" / "machine_settings" / "iso23509_f2_machine.toml")
    want = {(s.member, s.side): s for s in standard_setups(load_pair(F2)).values()}
    assert len(typed.machine) == 4
    for s in typed.machine:
        w = want[s.member, s.side]
        for a, b in ((s.settings, w.settings), (s.blade, w.blade)):
            for f in dc.fields(a):
                x, y = getattr(a, f.name), getattr(b, f.name)
                if isinstance(x, str) or f.name == "where":
                    assert f.name == "where" or x == y
                elif isinstance(x, tuple):
                    assert x == y
                else:
                    tol = 5e-7 if f.name == "ratio_of_roll" else 5e-5
                    assert x == pytest.approx(y, abs=tol), (s.member, s.side, f.name)
