"""The edge law below its least calibration load at a corner (:class:`gearcontact.ltca.
edge_law.EdgeCompliance`, ``low_exponent``; docs/twin.md "below the calibration, the
corner's law").

Truths:

1. Sneddon's cone (Johnson 1985 sec. 5.2, eq. 5.26): a gap ``eps r`` pressed on the
   half-space with load ``W`` closes by ``delta = sqrt(pi eps W / (2 E*))`` -- the
   approach ``~ W^(1/2)`` of a gap of degree 1; the half-space LCP reproduces it.
2. At a corner of a flank region (a wedge of 75 deg, the rest off the flank) whose gap
   rises as ``eps r + q r^2`` the LCP's local exponent ``d ln delta / d ln W`` rises
   with the load from 1/2 toward 2/3, so that the law's corner continuation below a
   calibration load ``W_lo``, ``delta(W_lo) (W / W_lo)^(1/2)``, is within ``(n_lo - 1/2)
   ln(W_lo / W)`` of the LCP: the premise of the bound declared in docs/twin.md.
3. The law: the held scale (``low_exponent`` 2/3, every edge row but a corner) is the
   calibration's interpolation clamped at its ends, and the corner's continuation is
   ``c(W_lo) (W / W_lo)^(1/2 - 2/3)``.
"""

import numpy as np
import pytest

from gearcontact.halfspace.grid import TangentGrid
from gearcontact.halfspace.lcp import solve_lcp
from gearcontact.ltca.edge_law import EdgeCompliance
from gearcontact.ltca.pair_ltca import OFF_FLANK_GAP_MM

E_STAR_MPA = 115e3      # steel on steel, about
EPS = 0.05              # the gap's slope, mm/mm (s0003 coast's corners: 0.04-0.1)


def _grid(n_x: int, n_y: int, h: float, x0: float, y0: float):
    xs, ys = x0 + (np.arange(n_x) + 0.5) * h, y0 + (np.arange(n_y) + 0.5) * h
    return np.meshgrid(xs, ys), TangentGrid.uniform(n_x, n_y, dx_mm=h, dy_mm=h,
                                                    x0_mm=float(xs[0]), y0_mm=float(ys[0]))


def test_cone_lcp_is_sneddons():
    """Truth 1: patch radius 0.5 mm on 10 cells. Tolerance 0.5 %: the collocation of the
    cone's log-singular pressure at the cell centres (measured: 0.02 %, and 0.01 % at
    20 cells)."""
    a = 0.5
    load = 0.5 * np.pi * E_STAR_MPA * EPS * a * a       # Sneddon: W = (pi/2) E* eps a^2
    (x, y), grid = _grid(32, 32, a / 10, -1.6 * a, -1.6 * a)
    res = solve_lcp(EPS * np.hypot(x, y), grid, load, e_star_mpa=E_STAR_MPA,
                    warn_coarse=False)
    assert res.converged
    assert res.delta_mm == pytest.approx(np.sqrt(np.pi * EPS * load / (2 * E_STAR_MPA)),
                                         rel=5e-3)


def test_corner_exponent_falls_toward_one_half():
    """Truth 2: 100 x 100 cells of 0.01 mm, the wedge's vertex at the origin, q = 0.1
    /mm, loads 20-320 N (patches 12-33 cells long). The local exponents are asserted
    between 1/2 - 0.02 (the wedge without curvature gives 0.483 at 10 cells across its
    patch, 0.494 at 20: discretization) and 2/3, rising with the load; the continuation
    from the two highest loads within its bound + 1 % (the same discretization over a
    factor 16 of load)."""
    (x, y), grid = _grid(100, 100, 0.01, -0.1, -0.5)
    r = np.hypot(x, y)
    wedge = np.abs(np.degrees(np.arctan2(y, x))) <= 37.5
    gap = np.where(wedge, EPS * r + 0.1 * r * r, OFF_FLANK_GAP_MM)
    loads = 20.0 * 2.0 ** np.arange(5)
    delta = []
    for w in loads:
        res = solve_lcp(gap, grid, float(w), e_star_mpa=E_STAR_MPA, warn_coarse=False)
        assert res.converged
        delta.append(res.delta_mm)
    delta = np.array(delta)
    n = np.diff(np.log(delta)) / np.diff(np.log(loads))
    assert (np.diff(n) > 0.0).all() and (n > 0.5 - 0.02).all() and (n < 2.0 / 3.0).all()
    ref = loads ** (2.0 / 3.0)          # any Hertzian reference: it cancels in delta
    law = EdgeCompliance(loads[-2:], delta[-2:], ref[-2:], 1.0, float(n[-1]),
                         low_exponent=0.5)
    n_lo = law.low_local_exponent
    assert n_lo == pytest.approx(n[-1], rel=1e-12)
    for w, d in zip(loads[:-2], delta[:-2]):
        got = float(law.scale_at(w)) * w ** (2.0 / 3.0)
        assert abs(got / d - 1.0) <= (n_lo - 0.5) * np.log(loads[-2] / w) + 0.01


def test_law_below_its_calibration():
    """Truth 3, exactly (to rounding: 1e-12)."""
    loads = np.array([100.0, 400.0, 1600.0])
    law = EdgeCompliance(loads, np.array([10.0, 20.0, 42.0]) * 1e-3,
                         np.array([1.0, 2.5, 6.3]) * 1e-3, 7.0, 0.53)
    w = np.array([10.0, 50.0, 100.0, 250.0, 3000.0])
    held = np.exp(np.interp(np.log(w), np.log(loads), np.log(law.ratio)))
    np.testing.assert_array_equal(law.scale_at(w), held)
    corner = EdgeCompliance(law.loads_n, law.approach_lcp_mm, law.approach_ref_mm,
                            law.scale, law.exponent, low_exponent=0.5)
    want = np.where(w < 100.0, 10.0 * (w / 100.0) ** (0.5 - 2.0 / 3.0), held)
    np.testing.assert_allclose(corner.scale_at(w), want, rtol=1e-12)
