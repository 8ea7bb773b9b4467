"""Compiled evaluation paths of the flanks.

Truths: scipy's FITPACK (``RectBivariateSpline.__call__``) for the B-spline values and
derivatives of every degree 1..5, inside and beyond the knot box; the numpy blade-cone
evaluation (:meth:`FormateFlank.evaluate`) for the compiled cone point; the module
formulas of :mod:`gearcontact.geometry.sheet` evaluated from FITPACK's psi
derivatives for the sheets.
"""

import numpy as np
import pytest
from scipy.interpolate import RectBivariateSpline

from gearcontact.geometry.spline_kernel import pp_coefficients, pp_derivatives

ORDERS = ((0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2))


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_spline_derivatives_equal_fitpack(k):
    x, y = np.linspace(0.0, 1.0, 15), np.linspace(0.0, 2.0, 17) ** 1.3
    z = np.sin(3.0 * x)[:, None] * np.cos(2.0 * y)[None, :] + x[:, None] * y[None, :] ** 2
    spl = RectBivariateSpline(x, y, z, kx=k, ky=k, s=0)
    tx, ty, c = spl.tck
    rng = np.random.default_rng(k)
    u = -0.3 + 1.6 * rng.random(400)           # a part beyond the knot box (clamped)
    v = -0.5 + 3.5 * rng.random(400)
    got = pp_derivatives(tx, ty, pp_coefficients(tx, ty, c, k, k), k, k, u, v, 2, False)
    for col, (a, b) in enumerate(ORDERS):
        if a >= k or b >= k:  # FITPACK evaluates derivatives below the degree only
            continue
        want = spl(np.clip(u, 0, 1), np.clip(v, y[0], y[-1]), dx=a, dy=b, grid=False)
        assert np.abs(got[:, col] - want).max() < 1e-9 * max(1.0, np.abs(want).max())


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("zero_outside", [False, True])
def test_pp_form_equals_fitpack(k, zero_outside):
    # the piecewise-polynomial form is the same spline: equal to FITPACK to rounding
    # (1e-9 relative, as the recursion it replaced; ~2e-12 observed at the degree-5
    # derivatives, where the Taylor sums cancel most), clamping rules included
    x, y = np.linspace(0.0, 1.0, 15), np.linspace(0.0, 2.0, 17) ** 1.3
    z = np.sin(3.0 * x)[:, None] * np.cos(2.0 * y)[None, :] + x[:, None] * y[None, :] ** 2
    spl = RectBivariateSpline(x, y, z, kx=k, ky=k, s=0)
    tx, ty, c = spl.tck
    rng = np.random.default_rng(10 + k)
    u = -0.3 + 1.6 * rng.random(2000)
    v = -0.5 + 3.5 * rng.random(2000)
    u[:3], v[:3] = x[[0, 7, -1]], y[[0, 5, -1]]        # knots and box corners
    got = pp_derivatives(tx, ty, pp_coefficients(tx, ty, c, k, k), k, k, u, v, 2,
                         zero_outside)
    for col, (a, b) in enumerate(ORDERS):
        if a >= k or b >= k:
            continue
        want = spl(np.clip(u, 0, 1), np.clip(v, y[0], y[-1]), dx=a, dy=b, grid=False)
        if zero_outside:
            outside = ((a > 0) & ((u < 0) | (u > 1))) | ((b > 0) & ((v < y[0]) | (v > y[-1])))
            want = np.where(outside, 0.0, want)
        assert np.abs(got[:, col] - want).max() < 1e-9 * max(1.0, np.abs(want).max())
    first = pp_derivatives(tx, ty, pp_coefficients(tx, ty, c, k, k), k, k, u, v, 1,
                           zero_outside)
    assert np.array_equal(first[:, :3], got[:, :3]) and np.isnan(first[:, 3:]).all()


def test_spline_zero_outside_has_constant_continuation():
    x = y = np.linspace(0.0, 1.0, 12)
    spl = RectBivariateSpline(x, y, np.add.outer(x ** 2, y), kx=5, ky=5, s=0)
    tx, ty, c = spl.tck
    got = pp_derivatives(tx, ty, pp_coefficients(tx, ty, c, 5, 5), 5, 5,
                         np.array([1.5, 0.5]), np.array([0.5, -1.0]), 2, True)
    assert got[0, 0] == pytest.approx(1.5) and got[1, 0] == pytest.approx(0.25)
    assert got[0, 1] == 0.0 and got[0, 3] == 0.0 and got[1, 2] == 0.0
    assert got[0, 2] == pytest.approx(1.0) and got[1, 1] == pytest.approx(1.0)


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_sheet_point_equals_fitpack_formulas(s0003_centred, side):
    flanks = s0003_centred[1]
    sheet = flanks.flank("pinion", side)
    rng = np.random.default_rng(7)
    lo = np.array([sheet.u_range[0], sheet.v_range[0]])
    hi = np.array([sheet.u_range[1], sheet.v_range[1]])
    for u, v in lo + (hi - lo) * rng.random((40, 2)):
        p, pu, pv, puu, puv, pvv = (float(sheet.psi(u, v, a, b)) for a, b in ORDERS)
        t = sheet.cone.tan_delta
        R = float(sheet.cone.radius_mm(u, v))
        eR = np.array([0.0, np.cos(p), np.sin(p)])
        ep = np.array([0.0, -np.sin(p), np.cos(p)])
        ex = np.array([1.0, 0.0, 0.0])
        want = {"r": v * ex + R * eR, "r_u": eR + R * pu * ep,
                "r_v": ex + t * eR + R * pv * ep,
                "r_uu": (2 * pu + R * puu) * ep - R * pu ** 2 * eR,
                "r_uv": (pv + t * pu + R * puv) * ep - R * pu * pv * eR,
                "r_vv": (2 * t * pv + R * pvv) * ep - R * pv ** 2 * eR}
        sp = sheet.point(u, v)
        arr = sheet.evaluate(np.array([u]), np.array([v]))
        for name, w in want.items():
            assert np.abs(getattr(sp, name) - w).max() < 1e-9
            assert np.abs(getattr(arr, name)[0] - w).max() < 1e-9
        nrm = np.cross(want["r_u"], want["r_v"])
        assert np.abs(sp.n - sheet.normal_sign * nrm / np.linalg.norm(nrm)).max() < 1e-12


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_cone_point_equals_numpy_evaluate(s0003_centred, side):
    flanks = s0003_centred[1]
    gear = flanks.flank("gear", side)
    rng = np.random.default_rng(11)
    lo = np.array([gear.u_range[0], gear.v_range[0]])
    hi = np.array([gear.u_range[1], gear.v_range[1]])
    uv = lo - 0.2 * (hi - lo) + 1.4 * (hi - lo) * rng.random((40, 2))
    ref = gear.evaluate(uv[:, 0], uv[:, 1])
    for i, (u, v) in enumerate(uv):
        sp = gear.point(u, v)
        for name in ("r", "r_u", "r_v", "r_uu", "r_uv", "r_vv", "n"):
            assert np.abs(getattr(sp, name) - getattr(ref, name)[i]).max() < 1e-12
