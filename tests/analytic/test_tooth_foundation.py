"""Fillet-foundation compliance of Sainsot, Velex & Duverger (analytic.tooth_foundation).

Truths:
- an independent implementation of the same formula and table: ross-rotordynamics
  2.3.0, ``GearElementTVMS(n=0, material=steel, width=0.02, bore_diameter=0.035,
  module=0.002, n_teeth=62, pr_angle=0.349066)._inv_kf(beta)`` at ``beta =
  _to_tau(0.40)`` gives 1.926812630479527e-09 m/N (run once by hand: ross is a
  benchmarks-only dependency; its inputs r_f = 59.5 mm, theta_f = 0.04565848466736457
  rad, u = 3.7445332788019897 mm, alpha = 0.38255339042678177 rad, E = 211 GPa,
  r_int = 17.5 mm are typed in here); agreement to rounding (1e-12) checks the
  transcription of the coefficients;
- the formula's structure: it scales as 1 / (E b); with the load through the root
  section's middle (u_f = 0) and perpendicular to the centre line (alpha_m = 0) only P*
  is left; a load line farther from the root gives a larger compliance (L*, M* > 0 over
  the teeth of docs/bending.md sec. 11);
- bad input names the field; a tooth and body so far outside the fit that L*, M* or
  P* changes sign (the s0003 hypoid gear's thin normal-section tooth angle) is refused.
The 3D check of the formula against the FE and the shell is in
tests/structure/test_root_fillet.py (docs/bending.md sec. 11).
"""

import math

import pytest

from gearcontact.analytic.tooth_foundation import (fillet_foundation_compliance_mm_per_n,
                                                   foundation_coefficients)
from gearcontact.validation import InputRangeError

ROSS = dict(load_angle_rad=0.38255339042678177, load_height_mm=3.7445332788019897,
            root_thickness_mm=2 * 59.5 * 0.04565848466736457, root_radius_mm=59.5,
            bore_radius_mm=17.5, face_width_mm=20.0, youngs_modulus_mpa=211_000.0)


def test_against_an_independent_implementation():
    got = fillet_foundation_compliance_mm_per_n(**ROSS)
    assert got == pytest.approx(1.926812630479527e-09 * 1e3, rel=1e-12)


def test_structure_of_the_formula():
    base = fillet_foundation_compliance_mm_per_n(**ROSS)
    twice = fillet_foundation_compliance_mm_per_n(**{**ROSS, "face_width_mm": 40.0,
                                                     "youngs_modulus_mpa": 422_000.0})
    assert twice == pytest.approx(base / 4.0, rel=1e-14)
    c = foundation_coefficients(root_radius_mm=59.5, bore_radius_mm=17.5,
                                root_half_angle_rad=0.04565848466736457)
    centred = fillet_foundation_compliance_mm_per_n(**{**ROSS, "load_angle_rad": 0.0,
                                                       "load_height_mm": 0.0})
    assert centred == pytest.approx(c.p_star / (211_000.0 * 20.0), rel=1e-14)
    assert c.l_star > 0 and c.m_star > 0
    higher = fillet_foundation_compliance_mm_per_n(**{**ROSS, "load_height_mm": 5.0})
    assert higher > base
    assert c.h_f == pytest.approx(59.5 / 17.5, rel=1e-15)


@pytest.mark.parametrize("field, value", [
    ("bore_radius_mm", 59.5), ("bore_radius_mm", 0.0), ("load_height_mm", -0.1),
    ("root_thickness_mm", 0.0), ("load_angle_rad", math.pi / 2), ("face_width_mm", math.nan),
])
def test_bad_input(field, value):
    with pytest.raises(InputRangeError, match=field):
        fillet_foundation_compliance_mm_per_n(**{**ROSS, field: value})


def test_outside_the_fit_is_refused():
    # the s0003-centred gear's normal section (docs/bending.md sec. 11): P* < 0
    with pytest.raises(InputRangeError, match="root_half_angle_rad.*P\\*"):
        foundation_coefficients(root_radius_mm=287.7, bore_radius_mm=285.4,
                                root_half_angle_rad=0.0052)
