"""The edge-against-flank section (ltca.edge_section) against independent truths: the
plane Hertz section's closed form (Johnson 1985 sec. 4.3 and 5.6: the logarithmic
energy of the semi-elliptic pressure and the gap it fills) and the package's
three-dimensional half-space LCP (halfspace.lcp, Love's influence on a grid, another
solver and another kernel) on a finite strip with the line's and the edge's sections."""

import math

import numpy as np
import pytest

from gearcontact.validation import InputRangeError
from gearcontact.halfspace.grid import TangentGrid
from gearcontact.halfspace.lcp import solve_lcp
from gearcontact.ltca.edge_section import (edge_section_excess, edge_stiffness_factor,
                                           section_approach)

#: Steel on steel, E* (MPa); E' = 2 E* (Hamrock-Brewe).
E_STAR_MPA = 229670.0 / 2.0
LAMBDA = 4.0 / (math.pi * 2.0 * E_STAR_MPA)


def test_plane_hertz_section_against_the_closed_form():
    """The line's section (x^2 / 2 on both sides, unit load, the log kernel's unit
    length (lambda' w R)^(1/2)): the Hertz half-width b = 2^(1/2) there, and the approach
    at its centre the energy mean -(ln(b / 2) - 1/4) + b^2 / 8 (the semicircle's
    logarithmic energy and its mean gap). Bound 1e-4 relative: the piecewise-constant
    pressure on 200 cells over +-2.5 (measured 2.5e-6 at 400 cells)."""
    b = math.sqrt(2.0)
    want = -(math.log(b / 2.0) - 0.25) + b * b / 8.0
    assert section_approach(0.0, one_sided=False) == pytest.approx(want, rel=1e-4)


def _strip_approach(gap_of_x, x0_mm, x1_mm, *, load_per_mm, length_mm, nx, ny):
    dx = (x1_mm - x0_mm) / nx
    grid = TangentGrid.uniform(nx, ny, dx_mm=dx, dy_mm=length_mm / ny, x0_mm=x0_mm + 0.5 * dx)
    xc = x0_mm + dx * (np.arange(nx) + 0.5)
    h = np.broadcast_to(gap_of_x(xc)[None, :], (ny, nx)).copy()
    r = solve_lcp(h, grid, load_per_mm * length_mm, e_star_mpa=E_STAR_MPA, tol=1e-10,
                  warn_coarse=False)
    assert r.converged
    return float(r.delta_mm)


@pytest.mark.parametrize("chi", [0.0, 0.7])
def test_edge_excess_against_the_half_space_lcp(chi):
    """Delta(chi) against the 3D half-space LCP of a 10 mm strip (100 N/mm, R = 8 mm;
    its section uniform along it): the edge's section, gap s x + x^2 / (2 R) on x >= 0
    and no material before the edge (1 mm), against the line's Hertz section at the same
    load, their approaches' difference over lambda' w (the edge at x = 0, the line at
    its centre; the length term cancels). chi = 0: the half section cut at its centre;
    0.7: the EV example's edges beyond the lines at 400 N·m (docs/cylindrical.md sec.
    10). Bound 0.025 (in lambda' w; 0.4 % of the line's g ~ 6): the edge's pressure is
    singular at the cut (~ x^(-1/2)), so the LCP's piecewise-constant cells converge as
    dx^(1/2): 64 -> 128 cells across moved its Delta by 0.003-0.0045, leaving <= 0.015
    at 64 cells; the plane section's own 200 cells 0.005 of 1600; 10 -> 20 mm of
    length < 0.001 (measured: LCP 0.5615 / 1.0645 against 0.5511 / 1.0498)."""
    w, radius, length = 100.0, 8.0, 10.0
    ell = math.sqrt(LAMBDA * w * radius)
    slope = chi * LAMBDA * w / ell
    extent = 2.5 * ell
    kw = dict(load_per_mm=w, length_mm=length, nx=64, ny=20)
    line = _strip_approach(lambda x: x * x / (2.0 * radius), -extent, extent, **kw)
    edge = _strip_approach(lambda x: slope * x + x * x / (2.0 * radius), 0.0, extent, **kw)
    assert (edge - line) / (LAMBDA * w) == pytest.approx(edge_section_excess(chi), abs=0.025)


def test_edge_is_softer_the_steeper_it_is():
    """Delta > 0 (a cut section yields more than the whole one under the same load: its
    pressure on half the width) and grows with the slope (a narrower contact, a deeper
    logarithm); the stiffness factor g / (g + Delta) lies in (0, 1) and falls with it;
    chi outside [0, 1e3] is refused naming the field."""
    d = [edge_section_excess(c) for c in (0.0, 0.3, 1.0, 3.0)]
    assert d[0] > 0.0 and np.all(np.diff(d) > 0.0)
    kw = dict(edge_radius_mm=7.3, line_load_n_per_mm=150.0, line_length_mm=20.0,
              line_radius_mm=8.3, e_prime_mpa=2.0 * E_STAR_MPA)
    f = [edge_stiffness_factor(slope=s, **kw)[0] for s in (0.0, 0.005, 0.02)]
    assert 0.0 < f[-1] < f[1] < f[0] < 1.0
    with pytest.raises(InputRangeError, match="chi"):
        edge_section_excess(-0.1)
