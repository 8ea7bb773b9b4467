"""ISO 21771 geometry against the closed forms written out by hand, an independent
zero-backlash check of the working pressure angle, and the FZG C-type test gear."""

import math
from pathlib import Path

import pytest

from gearcontact.geometry.cylindrical.iso21771 import inv, inv_inverse, involute_geometry
from gearcontact.geometry.pair import load_pair

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
BOTH = ("bevel", "cylindrical")


def _thickness_on(d_y, *, d, d_b, m_t, x, alpha_n, alpha_t):
    """Transverse tooth thickness on diameter d_y (ISO 21771: s_t carried by inv)."""
    s_t = m_t * (0.5 * math.pi + 2.0 * x * math.tan(alpha_n))
    return d_y * (s_t / d + inv(alpha_t) - inv(math.acos(d_b / d_y)))


def test_inv_inverse_round_trip():
    # Newton to machine precision over the practical range of pressure angles
    for a in (1e-3, 0.2, math.radians(20), math.radians(35), 1.2):
        assert inv_inverse(inv(a)) == pytest.approx(a, rel=1e-13)


def test_spur_20x40_by_hand():
    """Hand values of tests/geometry/cylindrical/README.md (4 decimals: 1e-4)."""
    g = load_pair(EXAMPLES / "spur_20x40_m3.toml", kinds=BOTH).geometry
    assert g.centre_distance_mm == pytest.approx(90.0, abs=1e-12)
    assert g.base_diameter_pinion_mm == pytest.approx(2 * 28.19078, abs=2e-5)
    assert (g.tip_diameter_pinion_mm, g.root_diameter_pinion_mm) == pytest.approx((66.0, 52.5))
    assert g.length_of_contact_mm == pytest.approx(14.4819, abs=1e-4)
    assert g.transverse_contact_ratio == pytest.approx(1.6352, abs=1e-4)
    assert g.overlap_ratio == 0.0 and g.working_pressure_angle_deg == pytest.approx(20.0)


@pytest.mark.parametrize("beta, x1, x2", [(0.0, 0.0, 0.0), (25.0, 0.3, 0.1),
                                           (15.0, -0.2, 0.5), (33.0, 0.6, 0.4)])
def test_closed_forms_helical(beta, x1, x2):
    """Every quantity against the ISO 21771 closed forms (rel 1e-12: the same formulas,
    different code), and α_wt against the zero-backlash condition on the working pitch
    circles s_w1 + s_w2 = π d_w1 / z1 (independent of the inv α_wt formula; 1e-10 mm)."""
    z1, z2, m_n, an_deg, b = 23, 67, 2.0, 20.0, 30.0
    g = involute_geometry(pinion_teeth=z1, gear_teeth=z2, normal_module_mm=m_n,
                          normal_pressure_angle_deg=an_deg, helix_angle_deg=beta,
                          profile_shift_pinion=x1, profile_shift_gear=x2, face_width_mm=b)
    an, be = math.radians(an_deg), math.radians(beta)
    at = math.atan(math.tan(an) / math.cos(be))
    m_t = m_n / math.cos(be)
    d1, d2 = z1 * m_t, z2 * m_t
    db1, db2 = d1 * math.cos(at), d2 * math.cos(at)
    assert g.transverse_pressure_angle_deg == pytest.approx(math.degrees(at), rel=1e-12)
    assert g.base_helix_angle_deg == pytest.approx(
        math.degrees(math.asin(math.sin(be) * math.cos(an))), rel=1e-12, abs=1e-14)
    assert (g.reference_diameter_pinion_mm, g.base_diameter_gear_mm) == pytest.approx((d1, db2), rel=1e-12)
    da1, da2 = d1 + 2 * m_n * (1 + x1), d2 + 2 * m_n * (1 + x2)
    assert (g.tip_diameter_pinion_mm, g.tip_diameter_gear_mm) == pytest.approx((da1, da2), rel=1e-12)
    assert g.root_diameter_gear_mm == pytest.approx(d2 - 2 * m_n * (1.25 - x2), rel=1e-12)
    awt = math.radians(g.working_pressure_angle_deg)
    assert inv(awt) == pytest.approx(inv(at) + 2 * math.tan(an) * (x1 + x2) / (z1 + z2), rel=1e-12)
    a_w = g.centre_distance_mm
    assert a_w == pytest.approx(0.5 * (d1 + d2) * math.cos(at) / math.cos(awt), rel=1e-12)
    # independent: no backlash on the working pitch circles
    dw1, dw2 = 2 * a_w * z1 / (z1 + z2), 2 * a_w * z2 / (z1 + z2)
    sw1 = _thickness_on(dw1, d=d1, d_b=db1, m_t=m_t, x=x1, alpha_n=an, alpha_t=at)
    sw2 = _thickness_on(dw2, d=d2, d_b=db2, m_t=m_t, x=x2, alpha_n=an, alpha_t=at)
    assert sw1 + sw2 == pytest.approx(math.pi * dw1 / z1, abs=1e-10)
    g_a = 0.5 * (math.sqrt(da1**2 - db1**2) + math.sqrt(da2**2 - db2**2)) - a_w * math.sin(awt)
    p_bt = math.pi * m_t * math.cos(at)
    assert g.length_of_contact_mm == pytest.approx(g_a, rel=1e-12)
    assert g.transverse_contact_ratio == pytest.approx(g_a / p_bt, rel=1e-12)
    assert g.overlap_ratio == pytest.approx(b * math.sin(be) / (math.pi * m_n), rel=1e-12, abs=0)
    assert g.total_contact_ratio == pytest.approx(g_a / p_bt + g.overlap_ratio, rel=1e-12)


@pytest.mark.parametrize("beta", [0.0, 25.0])
def test_backlash_of_a_larger_centre_distance(beta):
    """j_bn -> 2 Δa sin α_wt cos β_b for small Δa (first order; Δa = 1e-4 mm, so the
    second-order term is ~1e-4 relative: rel 1e-3)."""
    kw = dict(pinion_teeth=23, gear_teeth=67, normal_module_mm=2.0,
              normal_pressure_angle_deg=20.0, helix_angle_deg=beta, profile_shift_pinion=0.3,
              profile_shift_gear=0.1, face_width_mm=30.0)
    g0 = involute_geometry(**kw)
    g = involute_geometry(**kw, centre_distance_mm=g0.centre_distance_mm + 1e-4)
    expect = 2e-4 * math.sin(math.radians(g0.working_pressure_angle_deg)) * math.cos(
        math.radians(g0.base_helix_angle_deg))
    assert g.normal_backlash_mm == pytest.approx(expect, rel=1e-3)
    assert g0.normal_backlash_mm == 0.0


def test_fzg_c_type_published():
    """FZG C-type (README): α_wt 22.44 deg and ε_α 1.44 as published (half a unit of the
    last digit); the published tip diameters are ISO 21771 tip shortening (0.005 mm)."""
    pair = load_pair(EXAMPLES / "fzg_c_type.toml", kinds=BOTH)
    g = pair.geometry
    assert g.working_pressure_angle_deg == pytest.approx(22.44, abs=0.005)
    assert g.transverse_contact_ratio == pytest.approx(1.44, abs=0.005)
    assert g.centre_distance_mm == 91.5 and abs(g.normal_backlash_mm) < 1e-4
    k_mn = 91.5 - 90.0 - (0.1817 + 0.1715) * 4.5
    for d, x, published in ((72.0, 0.1817, 82.46), (108.0, 0.1715, 118.36)):
        assert d + 2 * 4.5 * (1 + x) + 2 * k_mn == pytest.approx(published, abs=0.005)


@pytest.mark.parametrize("name", ["spur_20x40_m3", "ev_reducer_helical_23x67", "fzg_c_type"])
def test_single_contact_tip_diameter(name):
    """The highest point of single tooth contact of each member, against the lowest point
    of single contact of its mate taken from the other end of the path (the mate's tip
    roll length less one base pitch): both on one point of the line of action,
    u1 + u2 = a_w sin(alpha_wt), to 1e-9 mm; and inside the active profile."""
    g = load_pair(EXAMPLES / f"{name}.toml", kinds=BOTH).geometry
    line = g.centre_distance_mm * math.sin(math.radians(g.working_pressure_angle_deg))
    for member, mate in (("pinion", "gear"), ("gear", "pinion")):
        d = g.single_contact_tip_diameter_mm(member)
        u = math.sqrt((0.5 * d) ** 2 - (0.5 * getattr(g, f"base_diameter_{member}_mm")) ** 2)
        r_am, r_bm = (0.5 * getattr(g, f"{k}_diameter_{mate}_mm") for k in ("tip", "base"))
        u_mate = math.sqrt(r_am ** 2 - r_bm ** 2) - g.transverse_base_pitch_mm
        assert u + u_mate == pytest.approx(line, abs=1e-9)
        assert (getattr(g, f"active_start_diameter_{member}_mm") < d
                < getattr(g, f"tip_diameter_{member}_mm"))
