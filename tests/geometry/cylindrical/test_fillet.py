"""Trochoidal root fillet of rack generation against the analytic involute flank: the
two meet at the form diameter d_Ff with one tangent; the root lies on d_f."""

import math

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.fillet import root_fillet
from gearcontact.geometry.cylindrical.flank import FACINGS, involute_flank
from gearcontact.geometry.cylindrical.pair import CylindricalPair

CASES = [  # (z1, beta, hand, x1, rho_fP*): spur, helical both hands, negative shift, sharp rack
    (20, 0.0, None, 0.0, 0.38), (23, 25.0, "right", 0.3, 0.38), (23, 25.0, "left", 0.3, 0.25),
    (31, 15.0, "right", -0.2, 0.38), (17, 0.0, None, 0.5, 0.0)]


def _pair(z1, beta, hand, x1, rho):
    return CylindricalPair(name="t", pinion_teeth=z1, gear_teeth=67, normal_module_mm=2.0,
                           pinion_face_width_mm=30.0, gear_face_width_mm=30.0,
                           helix_angle_deg=beta, pinion_hand=hand, profile_shift_pinion=x1,
                           rack_tip_radius_factor=rho)


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("facing", FACINGS)
def test_fillet_meets_involute_at_form_circle(case, facing):
    """Position (1e-9 mm) and unit tangent (1e-9) of the fillet's end equal the flank's
    at u = u_Ff, on d_Ff; the fillet's root point lies on d_f (1e-9 mm) and is the
    lowest point of the fillet; both computed by different routes (rack envelope vs the
    involute formula and ISO 21771 tooth thickness)."""
    pair = _pair(*case)
    g = pair.geometry
    flank, fillet = involute_flank(pair, "pinion", facing), root_fillet(pair, "pinion", facing)
    pts, tan = fillet.transverse(np.array(fillet.tau_range))
    s = flank.evaluate(flank.u_range[0], 0.0)
    np.testing.assert_allclose(pts[1], s.r[:2], atol=1e-9)
    assert 2 * np.linalg.norm(pts[1]) == pytest.approx(g.form_diameter_pinion_mm, abs=1e-9)
    t_flank = s.r_u[:2] / np.linalg.norm(s.r_u[:2])
    if case[4] > 0:     # a sharp rack corner (rho = 0) has no fillet tangent to compare
        np.testing.assert_allclose(tan[1] / np.linalg.norm(tan[1]), t_flank, atol=1e-9)
    assert 2 * np.linalg.norm(pts[0]) == pytest.approx(g.root_diameter_pinion_mm, abs=1e-9)
    tau = np.linspace(*fillet.tau_range, 201)
    radii = np.linalg.norm(fillet.transverse(tau)[0], axis=1)
    assert radii.min() >= 0.5 * g.root_diameter_pinion_mm - 1e-9
    assert np.all(np.diff(radii) >= -1e-12)        # rising from root to form circle


@pytest.mark.parametrize("case", CASES[:4])
def test_fillet_tangent_and_lead(case):
    """d/dτ against central differences (h 1e-6 rad: error ~1e-9 mm); a helical fillet
    turns with the lead z tan β / r like the flank above it (1e-12 rad)."""
    pair = _pair(*case)
    fillet = root_fillet(pair, "pinion", "cw")
    h = 1e-6
    for tau in np.linspace(fillet.tau_range[0] + 0.01, fillet.tau_range[1] - 0.01, 5):
        fd = (fillet.transverse(tau + h)[0] - fillet.transverse(tau - h)[0]) / (2 * h)
        np.testing.assert_allclose(fd, fillet.transverse(tau)[1], atol=1e-8)
    tau_end = fillet.tau_range[1]
    z = 9.0
    p = fillet.points(tau_end, z)
    q = involute_flank(pair, "pinion", "cw").evaluate(involute_flank(pair, "pinion", "cw").u_range[0], z)
    np.testing.assert_allclose(p, q.r, atol=1e-9)
    r = 0.5 * pair.geometry.reference_diameter_pinion_mm
    a0 = math.atan2(*fillet.points(tau_end, 0.0)[1::-1])
    turn = (1 if case[2] != "left" else -1) * z * math.tan(math.radians(case[1])) / r
    assert math.atan2(*p[1::-1]) - a0 == pytest.approx(turn, abs=1e-12)


@pytest.mark.parametrize("case", CASES[:4])
@pytest.mark.parametrize("facing", FACINGS)
def test_fillet_surface(case, facing):
    """The fillet as a Surface: closed-form derivatives against central differences
    (h 1e-5: truncation ~1e-9, rounding ~1e-11 over radii ~25 mm: atol 1e-8); at the form
    circle its position and outward unit normal equal the flank's (1e-9) at any z."""
    from gearcontact.geometry.surface import Surface

    pair = _pair(*case)
    fillet = root_fillet(pair, "pinion", facing)
    flank = involute_flank(pair, "pinion", facing)
    assert isinstance(fillet, Surface)
    for z in (-12.0, 0.0, 9.0):
        a, b = fillet.evaluate(fillet.u_range[1], z), flank.evaluate(flank.u_range[0], z)
        np.testing.assert_allclose(a.r, b.r, atol=1e-9)
        np.testing.assert_allclose(a.n, b.n, atol=1e-9)
    h = 1e-5
    for tau in np.linspace(fillet.u_range[0] + 0.01, fillet.u_range[1] - 0.01, 4):
        for z in (-10.0, 4.0):
            s = fillet.evaluate(tau, z)
            fd = lambda name, du, dv: (getattr(fillet.evaluate(tau + du, z + dv), name)  # noqa: E731
                                       - getattr(fillet.evaluate(tau - du, z - dv), name)) / (2 * h)
            np.testing.assert_allclose(fd("r", h, 0), s.r_u, atol=1e-8)
            np.testing.assert_allclose(fd("r", 0, h), s.r_v, atol=1e-8)
            np.testing.assert_allclose(fd("r_u", h, 0), s.r_uu, atol=1e-8)
            np.testing.assert_allclose(fd("r_u", 0, h), s.r_uv, atol=1e-8)
            np.testing.assert_allclose(fd("r_v", 0, h), s.r_vv, atol=1e-8)
            p = fillet.point(tau, z)
            assert abs(p.n @ p.r_u) < 1e-12 and abs(p.n @ p.r_v) < 1e-12
