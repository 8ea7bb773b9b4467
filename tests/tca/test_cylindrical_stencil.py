"""The preview's inputs on a cylindrical contact (tca.cylindrical_stencil) against the
closed forms of involute gears: at the pitch point of a spur pair the relative radius
across the line is R = (r_b1 tan a_wt)(r_b2 tan a_wt)/(r_b1 tan a_wt + r_b2 tan a_wt)
(Johnson 1985 sec. 4.3 with the involute's radius of curvature, ISO 21771: the roll
length), along the unmodified line the flanks are straight (B- = 0); on a helical pair
the normal-section relative curvature is cos(beta_b)(1/u1 + 1/u2) (ISO 6336-2), and a
parabolic lead crowning C_b over the face b adds 8 C_b / b^2 along the axis."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.pair import ToothModifications
from gearcontact.geometry.pair import load_pair
from gearcontact.preview.fit.reference import fit_curvatures
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle, contact_line_gaps
from gearcontact.tca.cylindrical_stencil import cylindrical_stencils

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _pair(name, **pinion_mods):
    p = load_pair(EXAMPLES / name, kinds=("cylindrical",))
    return replace(p, modifications_pinion=ToothModifications(**pinion_mods),
                   modifications_gear=ToothModifications())


def _pitch_radius(g):
    a = math.radians(g.working_pressure_angle_deg)
    r1 = 0.5 * g.base_diameter_pinion_mm * math.tan(a)
    r2 = 0.5 * g.base_diameter_gear_mm * math.tan(a)
    return r1 * r2 / (r1 + r2)


def test_spur_pitch_point_curvature_and_line():
    p = _pair("spur_20x40_m3.toml")
    cyc = cylindrical_mesh_cycle(p, phases=21)
    st = cylindrical_stencils(p, cyc)
    j, k = cyc.pair_offsets.index(0), 10          # phase 10: the pitch point of pair 0
    # exact shape operators: 1e-12 relative (rounding of the closed-form derivatives)
    assert st.A_minus_per_mm[j, k] == pytest.approx(0.5 / _pitch_radius(p.geometry), rel=1e-12)
    assert abs(st.B_minus_per_mm[j, k]) < 1e-15
    # the line of the unmodified pair spans the face
    assert st.line_length_mm[j, k] == pytest.approx(p.geometry.face_width_mm, rel=1e-12)
    # the pitch point is in single contact (eps_alpha = 1.635), lever r_b2
    assert st.in_contact[:, k].sum() == 1 and st.opening_mm[j, k] == 0.0
    assert st.lever_mm == pytest.approx(0.5 * p.geometry.base_diameter_gear_mm, rel=1e-15)
    # the stencil (quadric where the window leaves the face) fits those curvatures to
    # the fit's rounding
    fit = fit_curvatures(st.gaps_mm[j, k])
    assert fit.A_minus_per_mm == pytest.approx(st.A_minus_per_mm[j, k], rel=1e-9)
    assert abs(fit.B_minus_per_mm) < 1e-12


def test_crowned_spur_stencil_on_the_flank():
    """Lead crowning C_b = 2 um on b = 20 mm: B- = 4 C_b / b^2 = 2e-5 1/mm (half the
    parabola's curvature 8 C_b / b^2), the contact at mid-face and the whole window on
    the flank (true gap samples); stage C reads A- and B- to 4e-7 and 9e-8 (measured;
    its degree-6 fit leaves the gap's terms of degree 8 and up: the involutes' radii
    change along the profile by +-0.6 mm in 6.8 mm; the former quadratic fit read A-
    +0.6 %): tolerances 1e-5 (B-: its 1.2 mm span along the line holds a gap change of
    7e-3 um)."""
    p = _pair("spur_20x40_m3.toml", lead_crowning_um=2.0)
    cyc = cylindrical_mesh_cycle(p, phases=21)
    st = cylindrical_stencils(p, cyc)
    j, k = cyc.pair_offsets.index(0), 10
    b = p.geometry.face_width_mm
    assert st.B_minus_per_mm[j, k] == pytest.approx(4 * 2e-3 / b ** 2, rel=1e-9)
    assert st.on_flank[j, k]
    fit = fit_curvatures(st.gaps_mm[j, k])
    assert fit.A_minus_per_mm == pytest.approx(st.A_minus_per_mm[j, k], rel=1e-5)
    assert fit.B_minus_per_mm == pytest.approx(st.B_minus_per_mm[j, k], rel=1e-5)


def test_helical_normal_section_curvature():
    """Unmodified EV helical pair: A- = cos(beta_b)(1/u1 + 1/u2)/2 with the roll lengths
    of the contact point (ISO 6336-2 normal-section radii), B- = 0, at every phase."""
    p = _pair("ev_reducer_helical_23x67.toml")
    cyc = cylindrical_mesh_cycle(p, phases=7)
    st = cylindrical_stencils(p, cyc)
    z = cyc.contact_zu_mm[..., 0]
    lg = contact_line_gaps(p, cyc, z[np.isfinite(z)])
    cb = math.cos(math.radians(p.geometry.base_helix_angle_deg))
    got, want = [], []
    n = 0
    for j, k in zip(*np.nonzero(st.valid)):
        m = int(np.flatnonzero(np.isfinite(z).ravel())
                .tolist().index(j * z.shape[1] + k))
        u1, u2 = lg.pinion_roll_mm[j, k, m], lg.gear_roll_mm[j, k, m]
        got.append(st.A_minus_per_mm[j, k])
        want.append(0.5 * cb * (1.0 / u1 + 1.0 / u2))
        # B- is the difference of two member curvatures of ~0.1 1/mm: zero to 1e-9 of A-
        assert abs(st.B_minus_per_mm[j, k]) < 1e-9 * st.A_minus_per_mm[j, k]
        n += 1
    assert n >= 14
    # 1e-8: the point solves (1e-11 mm) through the roll lengths and the shape operators
    np.testing.assert_allclose(got, want, rtol=1e-8)
