"""Ease-off: exact normal displacement, recomputed normals, coefficient semantics."""

from dataclasses import replace

import numpy as np
import pytest

from gearcontact.geometry.easeoff import EaseOff, apply_easeoff
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.pair import EaseOffCoefficients
from gearcontact.validation import InputRangeError


def _easeoff(flanks, pair, side):
    coeffs = pair.easeoff_drive if side == "drive" else pair.easeoff_coast
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    return EaseOff.from_coefficients(coeffs, u_mean_mm=u_m, v_mean_mm=v_m)


@pytest.mark.parametrize("side", SIDES)
def test_displacement_is_exactly_E_along_normal(s0003_centred, side):
    s0003, flanks = s0003_centred
    base = flanks.pinion_conjugate.side(side)
    eased = flanks.pinion.side(side)
    eo = _easeoff(flanks, s0003, side)
    assert not eo.is_zero
    rng = np.random.default_rng(3)
    u = rng.uniform(*base.u_range, 300)
    v = rng.uniform(*base.v_range, 300)
    s = base.evaluate(u, v)
    E = eo.relief_mm(u, v)
    q = s.r - E[:, None] * s.n
    # q must lie on the eased flank: locate it by axial position and radius and compare
    # the full position (spline accuracy of both sheets, ~1e-12 mm; bound 1e-9 mm)
    uu, vv, _ = eased.locate(q)
    e = eased.evaluate(uu, vv)
    assert np.linalg.norm(e.r - q, axis=-1).max() < 1e-9
    # the separation base -> eased along the base normal equals E (0.001 nm level)
    assert np.allclose(np.einsum("ij,ij->i", s.r - e.r, s.n), E, atol=1e-9, rtol=0)
    # the eased normal is recomputed from the eased sheet: to first order it is tilted
    # from the base normal by the surface gradient of E (r* = r - E n gives
    # n* = n + grad_s E + O(E kappa, |grad E|^2)); |grad E| reaches ~0.016 here and the
    # neglected terms stay below ~3e-4 (E <= 10 um, kappa <= 0.2 1/mm): bound 2e-4
    eps = 1e-6
    E_u = (eo.relief_mm(u + eps, v) - eo.relief_mm(u - eps, v)) / (2 * eps)
    E_v = (eo.relief_mm(u, v + eps) - eo.relief_mm(u, v - eps)) / (2 * eps)
    dot = lambda a, b: np.einsum("ij,ij->i", a, b)  # noqa: E731
    g11, g12, g22 = dot(s.r_u, s.r_u), dot(s.r_u, s.r_v), dot(s.r_v, s.r_v)
    det = g11 * g22 - g12 ** 2
    grad = (((g22 * E_u - g12 * E_v) / det)[:, None] * s.r_u
            + ((g11 * E_v - g12 * E_u) / det)[:, None] * s.r_v)
    c = dot(e.n, s.n)
    tilt = (e.n - c[:, None] * s.n) / c[:, None]
    assert np.linalg.norm(grad, axis=-1).max() > 1e-4  # the test is not vacuous
    assert np.linalg.norm(tilt - grad, axis=-1).max() < 2e-4
    assert np.allclose(np.einsum("ij,ij->i", e.n, e.r_u), 0, atol=1e-13)


def test_polynomial_terms():
    eo = EaseOff(profile_angle_um_per_mm=1.0, spiral_angle_um_per_mm=2.0,
                 profile_crowning_um_per_mm2=3.0, lengthwise_crowning_um_per_mm2=4.0,
                 bias_um_per_mm2=5.0, u_mean_mm=1.0, v_mean_mm=10.0)
    # eta = 2, xi = -1: 1*2 + 2*(-1) + 3*4 + 4*1 + 5*(-2) = 6 um
    assert eo.relief_mm(3.0, 9.0) == pytest.approx(6e-3, abs=1e-15)
    assert eo.relief_mm(1.0, 10.0) == 0.0


def test_lengthwise_crowning_curvature(s0003_centred):
    # pure lengthwise crowning c_LC changes the normal curvature along the face by
    # -2 c_LC (E subtracted along the outward normal), to first order in E
    flanks = s0003_centred[1]
    base = flanks.pinion_conjugate.side("drive")
    u_m, v_m = flanks.mean_contact["drive"]["pinion_uv"]
    c = 0.5  # um/mm^2 (|E| <= 22 um over the face)
    eo = EaseOff.from_coefficients(EaseOffCoefficients(lengthwise_crowning_um_per_mm2=c),
                                   u_mean_mm=u_m, v_mean_mm=v_m)
    eased = apply_easeoff(base, eo, limit_um=flanks.easeoff_limit_um)

    def kappa_v(f):
        p = f.point(u_m, v_m)
        # normal curvature along a unit tangent of the v-line, per unit length along x
        return (p.r_vv @ p.n) / (p.r_v @ p.r_v)

    dk = kappa_v(eased) - kappa_v(base)
    t = base.point(u_m, v_m).r_v
    expect = -2 * c * 1e-3 / (t @ t)  # d^2E/dv^2 = 2c, projected on the v-line
    assert dk == pytest.approx(expect, rel=2e-2)  # first-order theory: 2 % (E/curvature terms)


def test_zero_easeoff_is_conjugate(s0003_centred):
    flanks = s0003_centred[1]
    base = flanks.pinion_conjugate.side("coast")
    eo = EaseOff.from_coefficients(EaseOffCoefficients(), u_mean_mm=0.6, v_mean_mm=35.8)
    same = apply_easeoff(base, eo, limit_um=flanks.easeoff_limit_um)
    p, q = base.point(1.0, 36.0), same.point(1.0, 36.0)
    assert np.allclose(p.r, q.r, atol=0) and np.allclose(p.n, q.n, atol=0)


def test_too_large_easeoff_rejected(s0003_centred):
    flanks = s0003_centred[1]
    base = flanks.pinion_conjugate.side("drive")
    eo = EaseOff.from_coefficients(EaseOffCoefficients(lengthwise_crowning_um_per_mm2=50.0),
                                   u_mean_mm=0.6, v_mean_mm=35.8)
    with pytest.raises(InputRangeError) as err:
        apply_easeoff(base, eo, limit_um=flanks.easeoff_limit_um)
    # the message names the relief, where it occurs and the thickness-based limit
    assert "easeoff" in err.value.field and "corner" in err.value.field
    assert "tooth thickness" in str(err.value)


def test_easeoff_limit_is_a_fraction_of_the_measured_tooth_thickness(s0003_centred):
    # s_mn from the two conjugate flanks against the ISO 23509 order of magnitude: the
    # pinion of a 7-tooth hypoid is thickened above half the normal pitch pi m_mn / 2
    flanks = s0003_centred[1]
    m = flanks.blank.mean_normal_module_mm
    s_mn = flanks.pinion_normal_thickness_mm
    assert 0.5 * np.pi * m < s_mn < np.pi * m
    assert flanks.easeoff_limit_um == pytest.approx(1e3 * 0.05 * s_mn)
    with pytest.raises(InputRangeError):
        EaseOffCoefficients(bias_um_per_mm2=float("nan"))


def test_pair_easeoff_values_used(s0003_centred):
    # build_flanks used the pair's coefficients for each side
    s0003, flanks = s0003_centred
    for side in SIDES:
        eo = _easeoff(flanks, s0003, side)
        coeffs = s0003.easeoff_drive if side == "drive" else s0003.easeoff_coast
        assert eo.lengthwise_crowning_um_per_mm2 == coeffs.lengthwise_crowning_um_per_mm2
    assert replace(s0003.easeoff_drive, profile_angle_um_per_mm=0.0).is_zero is False
