"""Involute-helicoid flanks: closed-form derivatives against central differences, the
involute's transverse radius of curvature sqrt(r^2 - r_b^2), the helicoid's principal
curvatures (-cos β_b / ρ_t, 0), tooth thickness, and the modification amounts."""

import math
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.flank import FACINGS, involute_flank
from gearcontact.geometry.cylindrical.pair import CylindricalPair, ToothModifications
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.sampling import principal_curvatures
from gearcontact.geometry.surface import Surface

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def _pair(beta=25.0, hand="right", **mods):
    return CylindricalPair(
        name="t", pinion_teeth=23, gear_teeth=67, normal_module_mm=2.0,
        pinion_face_width_mm=32.0, gear_face_width_mm=30.0, helix_angle_deg=beta,
        pinion_hand=hand if beta else None, profile_shift_pinion=0.3, profile_shift_gear=0.1,
        modifications_pinion=ToothModifications(**mods))


MODIFIED = dict(tip_relief_um=12.0, tip_relief_start_diameter_mm=52.0, root_relief_um=6.0,
                profile_crowning_um=3.0, lead_crowning_um=8.0, helix_slope_um=5.0)
CASES = [(0.0, "right", {}), (25.0, "right", {}), (25.0, "left", MODIFIED),
         (15.0, "right", MODIFIED)]


@pytest.mark.parametrize("beta, hand, mods", CASES)
@pytest.mark.parametrize("facing", FACINGS)
def test_derivatives_against_central_differences(beta, hand, mods, facing):
    """Central differences, step h = 1e-4 mm: truncation h^2 |r'''| / 6 < 1e-9 mm and
    rounding 1e-16 * 50 mm / h ~ 1e-10 mm, so 1e-7 is loose (r in mm, derivatives in
    mm/mm); points inside each relief zone so that the parabolas are smooth there."""
    fl = involute_flank(_pair(beta, hand, **mods), "pinion", facing)
    assert isinstance(fl, Surface)
    h = 1e-4
    lo, hi = fl.u_range
    for u in np.linspace(lo + 0.05, hi - 0.05, 7):
        for v in (-14.0, 0.3, 11.0):
            s = fl.evaluate(u, v)
            at = lambda du, dv: fl.evaluate(u + du, v + dv)  # noqa: E731
            fd = lambda name, du, dv: (getattr(at(du, dv), name)  # noqa: E731
                                       - getattr(at(-du, -dv), name)) / (2 * h)
            np.testing.assert_allclose(fd("r", h, 0), s.r_u, atol=1e-7)
            np.testing.assert_allclose(fd("r", 0, h), s.r_v, atol=1e-7)
            np.testing.assert_allclose(fd("r_u", h, 0), s.r_uu, atol=1e-7)
            np.testing.assert_allclose(fd("r_u", 0, h), s.r_uv, atol=1e-7)
            np.testing.assert_allclose(fd("r_v", h, 0), s.r_uv, atol=1e-7)
            np.testing.assert_allclose(fd("r_v", 0, h), s.r_vv, atol=1e-7)
            p = fl.point(u, v)
            assert np.linalg.norm(p.n) == pytest.approx(1.0, abs=1e-14)
            assert abs(p.n @ p.r_u) < 1e-12 and abs(p.n @ p.r_v) < 1e-12


@pytest.mark.parametrize("beta", [0.0, 25.0])
@pytest.mark.parametrize("facing", FACINGS)
def test_involute_curvature_and_base_cylinder(beta, facing):
    """Unmodified flank: the transverse section's curvature (from r_u, r_uu) is
    1 / sqrt(r^2 - r_b^2) with r from the position; the principal curvatures
    (:func:`principal_curvatures` of the closed-form forms) are (-cos β_b / ρ_t, 0);
    the normal line touches the base cylinder in projection (rel 1e-12)."""
    pair = _pair(beta)
    fl = involute_flank(pair, "pinion", facing)
    rb = 0.5 * pair.geometry.base_diameter_pinion_mm
    cos_bb = math.cos(math.radians(pair.geometry.base_helix_angle_deg))
    u = np.linspace(*fl.u_range, 9)
    v = np.linspace(-10.0, 10.0, 9)
    s = fl.evaluate(u, v)
    r = np.linalg.norm(s.r[:, :2], axis=1)
    rho_t = np.sqrt(r ** 2 - rb ** 2)
    xu, xuu = s.r_u[:, :2], s.r_uu[:, :2]
    kappa_t = np.abs(xu[:, 0] * xuu[:, 1] - xu[:, 1] * xuu[:, 0]) / np.linalg.norm(xu, axis=1) ** 3
    np.testing.assert_allclose(kappa_t, 1.0 / rho_t, rtol=1e-12)
    kappa, _ = principal_curvatures(s)
    np.testing.assert_allclose(kappa[:, 0], -cos_bb / rho_t, rtol=1e-10)
    np.testing.assert_allclose(kappa[:, 1], 0.0, atol=1e-12)
    np.testing.assert_allclose(fl.analytic_curvatures(u), kappa, rtol=1e-10, atol=1e-12)
    nxy = s.n[:, :2] / np.linalg.norm(s.n[:, :2], axis=1, keepdims=True)
    foot = s.r[:, :2] - rho_t[:, None] * nxy
    np.testing.assert_allclose(np.linalg.norm(foot, axis=1), rb, rtol=1e-12)
    # outward normal: it points to the side the flank faces
    tangent_ccw = np.stack([-s.r[:, 1], s.r[:, 0]], axis=1) / r[:, None]
    sense = np.einsum("ij,ij->i", s.n[:, :2], tangent_ccw)
    assert np.all(sense > 0) if facing == "ccw" else np.all(sense < 0)


@pytest.mark.parametrize("beta, hand", [(0.0, "right"), (25.0, "right"), (25.0, "left")])
def test_tooth_thickness_and_lead(beta, hand):
    """The two flanks are ``s_t / (d/2) = 2 (π/2 + 2 x tan α_n) / z`` apart on the
    reference circle (ISO 21771 tooth thickness), and the tooth turns by
    ``z tan β / r`` with the axial position (the lead; positive for right hand)."""
    pair = _pair(beta, hand)
    g = pair.geometry
    r = 0.5 * g.reference_diameter_pinion_mm
    u_ref = math.sqrt(r ** 2 - (0.5 * g.base_diameter_pinion_mm) ** 2)
    z = 7.0
    ang = {f: math.atan2(*involute_flank(pair, "pinion", f).evaluate(u_ref, z).r[1::-1])
           for f in FACINGS}
    expect = 2 * (0.5 * math.pi + 2 * 0.3 * math.tan(math.radians(20.0))) / 23
    assert ang["ccw"] - ang["cw"] == pytest.approx(expect, rel=1e-12)
    turn = (1 if hand == "right" else -1) * z * math.tan(math.radians(beta)) / r
    assert 0.5 * (ang["ccw"] + ang["cw"]) == pytest.approx(turn, abs=1e-13)


def test_modification_amounts():
    """Material removed along the transverse line of action (X - R) . f equals each
    term at its defining point: C_a at the tip, 0 at d_Ca; C_β at the face ends; f_Hβ
    between them; C_α at the ends of the active profile (1e-12 mm)."""
    p0 = involute_flank(_pair(25.0), "pinion", "cw")
    g = _pair(25.0).geometry
    rolls = g.roll_lengths_mm("pinion")
    u_ca = math.sqrt(27.0 ** 2 - (0.5 * g.base_diameter_pinion_mm) ** 2)

    def removed(flank, u, v):
        s0, s = p0.evaluate(u, v), flank.evaluate(u, v)
        f = s0.n / np.linalg.norm(s0.n[:2]) * np.array([1.0, 1.0, 0.0])
        return float((s0.r - s.r) @ f)

    tip = involute_flank(_pair(25.0, tip_relief_um=12.0, tip_relief_start_diameter_mm=54.0),
                         "pinion", "cw")
    assert removed(tip, rolls["tip"], 3.0) == pytest.approx(12e-3, abs=1e-12)
    assert removed(tip, u_ca, 3.0) == pytest.approx(0.0, abs=1e-12)
    lead = involute_flank(_pair(25.0, lead_crowning_um=8.0, helix_slope_um=5.0), "pinion", "cw")
    ends = [removed(lead, rolls["tip"] - 1.0, v) for v in (-16.0, 0.0, 16.0)]
    assert ends == pytest.approx([8e-3 - 2.5e-3, 0.0, 8e-3 + 2.5e-3], abs=1e-12)
    prof = involute_flank(_pair(25.0, profile_crowning_um=3.0), "pinion", "cw")
    mid = 0.5 * (rolls["active_start"] + rolls["tip"])
    assert [removed(prof, u, 0.0) for u in (rolls["active_start"], mid, rolls["tip"])] == \
        pytest.approx([3e-3, 0.0, 3e-3], abs=1e-12)


def test_ev_example_flanks_cover_the_active_profile():
    pair = load_pair(EXAMPLES / "ev_reducer_helical_23x67.toml", kinds=("cylindrical",))
    for member in ("pinion", "gear"):
        fl = involute_flank(pair, member, "ccw")
        rolls = pair.geometry.roll_lengths_mm(member)
        assert fl.u_range[0] < rolls["active_start"] < fl.u_range[1] == rolls["tip"]
        assert fl.v_range == (-0.5 * pair.face_width_mm(member), 0.5 * pair.face_width_mm(member))
