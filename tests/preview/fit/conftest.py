"""Shared generators for the stage-C tests: exact quadratic gap fields (the truth)."""

import numpy as np
import pytest

from gearcontact.contract.stencil import STENCIL_SPACING_MM, stencil_coordinates


def quadratic_field(a_minus, b_minus, angle_deg, c0=0.0, c1=0.0, c2=0.0,
                    spacing_mm=STENCIL_SPACING_MM):
    """Exact gap field ``c0 + c1 s + c2 t + A u^2 + B v^2``, u at angle_deg from s.

    Returns (gaps_mm (49,), (c3, c4, c5)): the quadratic coefficients follow from
    rotating diag(A, B): c3 = A cos^2 + B sin^2, c4 = 2 (A - B) sin cos,
    c5 = A sin^2 + B cos^2.
    """
    s, t = stencil_coordinates(spacing_mm)
    th = np.radians(angle_deg)
    co, si = np.cos(th), np.sin(th)
    c3 = a_minus * co * co + b_minus * si * si
    c4 = 2.0 * (a_minus - b_minus) * si * co
    c5 = a_minus * si * si + b_minus * co * co
    g = c0 + c1 * s + c2 * t + c3 * s * s + c4 * s * t + c5 * t * t
    return g, (c3, c4, c5)


def random_quadratics(n, seed, *, lo=1e-3, hi=1.0, offset_mm=0.05, slope=0.05):
    """n seeded random elliptic fields: A-, B- log-uniform in [lo, hi], A- >= B-.

    Yields (gaps_mm, A, B, angle_deg, (c3, c4, c5)).
    """
    rng = np.random.default_rng(seed)
    for _ in range(n):
        x, y = np.exp(rng.uniform(np.log(lo), np.log(hi), size=2))
        a, b = max(x, y), min(x, y)
        ang = rng.uniform(-90.0, 90.0)
        c0, c1, c2 = rng.uniform(-offset_mm, offset_mm), *rng.uniform(-slope, slope, 2)
        g, c = quadratic_field(a, b, ang, c0, c1, c2)
        yield g, a, b, ang, c


@pytest.fixture
def quadratic():
    return quadratic_field


@pytest.fixture
def quadratics():
    return random_quadratics
