"""ISO 6336-1 Method B single-pair stiffness (gearcontact.analytic.iso6336).

Truths: the rack-rack limit of the flexibility polynomial (z_n -> infinity, x = 0) is
c'_th = 1 / C1 = 21.17 N/(mm·µm); a spur gear's virtual teeth are its teeth; more teeth
make the pair stiffer; the standard's "c' ~ 14 N/(mm·µm)" mean for solid spur gears
(ISO 6336-1:2006 clause 9.3) is met by a 20/40 pair with C_M C_B = 0.78 within 15 %;
and the hypoid s0003's virtual gears (12.7 / 1063 teeth at the mean spiral angle 34.9 deg)
give c' = 10.7 N/(mm·µm), the figure of docs/bending.md sec. 7 (rounding 0.05).
"""

import math

import pytest

from gearcontact.analytic.iso6336 import (bevel_pair_stiffness, theoretical_single_stiffness,
                                          virtual_teeth)
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError


def test_rack_limit_and_monotone_in_teeth():
    assert theoretical_single_stiffness(z_n1=1e9, z_n2=1e9) == pytest.approx(1 / 0.04723,
                                                                             rel=1e-7)
    c = [theoretical_single_stiffness(z_n1=z, z_n2=2 * z) for z in (10, 20, 40, 80)]
    assert c == sorted(c)
    # ISO's mean single stiffness of solid steel spur gears, ~14 N/(mm um)
    assert c[1] * 0.8 * 0.975 == pytest.approx(14.0, rel=0.15)


def test_virtual_teeth_of_a_spur_gear_are_its_teeth():
    assert virtual_teeth(23, pitch_angle_deg=0.0, spiral_angle_deg=0.0) == 23.0
    assert virtual_teeth(23, pitch_angle_deg=60.0, spiral_angle_deg=0.0) == \
        pytest.approx(46.0, rel=1e-12)


def test_s0003_virtual_gears_and_single_stiffness():
    pair = load_pair("s0003")
    iso = bevel_pair_stiffness(pair.blank, face_width_mm=pair.gear_face_width_mm)
    assert iso.spiral_angle_deg == pytest.approx(34.9, abs=0.05)
    assert iso.z_n1 == pytest.approx(12.7, abs=0.05)
    assert iso.z_n2 == pytest.approx(1063, abs=1)
    assert iso.c_th_n_per_mm_um == pytest.approx(16.8, abs=0.05)
    assert iso.c_n_per_mm_um == pytest.approx(10.7, abs=0.05)
    assert iso.compliance_mm_per_n == pytest.approx(
        1e-3 / (iso.c_n_per_mm_um * pair.gear_face_width_mm), rel=1e-12)
    assert math.isclose(iso.stiffness_n_per_um, iso.c_n_per_mm_um * 13.2, rel_tol=1e-12)


def test_bad_input_names_the_field():
    with pytest.raises(InputRangeError, match="z_n1"):
        theoretical_single_stiffness(z_n1=2, z_n2=40)
    with pytest.raises(InputRangeError, match="face_width_mm"):
        bevel_pair_stiffness(load_pair("s0003").blank, face_width_mm=0.0)


def test_cylindrical_pair_stiffness_worked_check():
    """The standard 20/40 spur pair (x = 0, h_fP = 1.25 m): c' = 12.7 and c_gamma_alpha =
    18.7 N/(mm·µm) (hand evaluation of ISO 6336-1 eq. 70-75 in docs/cylindrical.md sec. 7,
    to the 3 digits quoted); a helical pair's virtual teeth z / (cos^2 beta_b cos beta)."""
    from gearcontact.analytic.iso6336 import cylindrical_pair_stiffness

    s = cylindrical_pair_stiffness(pinion_teeth=20, gear_teeth=40, helix_angle_deg=0.0,
                                   base_helix_angle_deg=0.0, transverse_contact_ratio=1.635186)
    assert s.c_n_per_mm_um == pytest.approx(12.7, abs=0.05)
    assert s.c_gamma_alpha_n_per_mm_um == pytest.approx(18.7, abs=0.05)
    assert s.c_gamma_beta_n_per_mm_um == pytest.approx(0.85 * s.c_gamma_alpha_n_per_mm_um)
    h = cylindrical_pair_stiffness(pinion_teeth=23, gear_teeth=67, helix_angle_deg=25.0,
                                   base_helix_angle_deg=23.4, transverse_contact_ratio=1.4)
    f = math.cos(math.radians(23.4)) ** 2 * math.cos(math.radians(25.0))
    assert h.z_n1 == pytest.approx(23 / f, rel=1e-12) and h.z_n2 == pytest.approx(67 / f, rel=1e-12)


def test_resonance_speed_is_the_two_disc_natural_frequency():
    """n_E1 against the natural frequency of two solid steel discs coupled by a spring on
    their base circles (derived independently: J = rho pi b d^4 / 32, omega^2 = k (r_b1^2
    / J1 + r_b2^2 / J2), n = 60 omega / (2 pi z1)), for a pair whose gear mean diameter
    is exactly u times the pinion's (where the standard's u^2 form is exact): 1e-12.
    Worked numbers: 20/40 m 3 spur, d_m1 = 59.25 mm, c_gamma = 18.7 N/(mm·µm) (the
    worked check above), m_red = 9.56e-3 kg/mm, n_E1 = 21,116 rpm."""
    from gearcontact.analytic.iso6336 import reduced_mass_kg_per_mm, resonance_speed_rpm

    z1, u, b = 20, 2.0, 20.0
    dm1, db1 = 60.0 - 0.75, 60.0 * math.cos(math.radians(20.0))
    m_red = reduced_mass_kg_per_mm(mean_diameter_pinion_mm=dm1, base_diameter_pinion_mm=db1,
                                   ratio=u)
    n = resonance_speed_rpm(pinion_teeth=z1, c_gamma_n_per_mm_um=18.7,
                            reduced_mass_kg_per_mm=m_red)
    rho = 7850.0
    j1 = rho * math.pi * (b * 1e-3) * (dm1 * 1e-3) ** 4 / 32
    j2 = rho * math.pi * (b * 1e-3) * (u * dm1 * 1e-3) ** 4 / 32
    k = 18.7 * b * 1e6                                   # N/(mm µm) x mm -> N/m
    rb1, rb2 = 0.5e-3 * db1, 0.5e-3 * u * db1
    omega = math.sqrt(k * (rb1 ** 2 / j1 + rb2 ** 2 / j2))
    assert n == pytest.approx(60 * omega / (2 * math.pi * z1), rel=1e-12)
    assert m_red == pytest.approx(9.5609e-3, rel=1e-4) and n == pytest.approx(21116, rel=1e-4)
    with pytest.raises(InputRangeError, match="bore_ratio_gear"):
        reduced_mass_kg_per_mm(mean_diameter_pinion_mm=dm1, base_diameter_pinion_mm=db1,
                               ratio=u, bore_ratio_gear=1.0)
