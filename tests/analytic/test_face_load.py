"""The closed forms of a misaligned line contact (analytic.face_load) against independent
truths: ISO 6336-1's face load factor against the linear springs it stands for,
integrated numerically; the finite line's law on a straight gap against its own
definition through analytic.hertz and against the twin's slice law (the same law,
discretised by another code)."""

import math

import numpy as np
import pytest

from gearcontact.analytic.face_load import end_loaded_line, linear_spring_face_load
from gearcontact.analytic.hertz import line_contact_approach_mm, line_contact_terms
from gearcontact.validation import InputRangeError

#: Spur 20/40 m 3 at the pitch point, T2 = 64.5 N·m: F_n (N), 1/(2R) (1/mm), E' (MPa).
W, B_MAX, E_PRIME = 1144.0, 0.0731, 2.0 * 210000.0 / (2.0 * (1.0 - 0.3 ** 2))


def _springs(w_m, f_um, c, b=20.0, n=40_001):
    """Linear springs c (N/(mm·µm)) over the face b (mm), gap f y / b (µm), mean line
    load w_m: the approach d by bisection on the total load (60 halvings), then (peak /
    mean, loaded fraction) on n points (trapezoid rule)."""
    y = np.linspace(0.0, b, n)
    total = w_m * b

    def load(d):
        w = c * np.maximum(d - f_um * y / b, 0.0)
        return np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(y)), w

    lo, hi = 0.0, f_um + total / (c * b)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if load(mid)[0] < total else (lo, mid)
    w = load(0.5 * (lo + hi))[1]
    closed = y[w > 0.0]
    return w.max() / w_m, (closed.max() - closed.min()) / b


@pytest.mark.parametrize("f_um", [0.0, 5.0, 11.44, 30.0, 120.0])
def test_iso_face_load_factor_is_the_linear_springs(f_um):
    """K_Hbeta and b_cal / b of ISO 6336-1 (both branches, and x = 1 where they meet at
    K = 2) against the springs integrated on 40,001 points: the trapezoid's and the
    grid's error, 2e-4 relative (the loaded end lies between two points 5e-4 mm apart)."""
    w_m, c = 57.2, 20.0
    k, frac = linear_spring_face_load(mean_line_load_n_per_mm=w_m, misalignment_um=f_um,
                                      stiffness_n_per_mm_um=c)
    k_num, frac_num = _springs(w_m, f_um, c)
    assert k == pytest.approx(k_num, rel=2e-4)
    assert frac == pytest.approx(frac_num, rel=2e-4)
    if f_um == 11.44:                          # x = F c / (2 w_m) = 2.0: end-loaded
        assert k == pytest.approx(math.sqrt(2.0 * f_um * c / w_m), rel=1e-12)


def test_iso_face_load_factor_refuses_bad_input():
    with pytest.raises(InputRangeError, match="misalignment_um"):
        linear_spring_face_load(mean_line_load_n_per_mm=50.0, misalignment_um=-1.0,
                                stiffness_n_per_mm_um=20.0)
    with pytest.raises(InputRangeError, match="stiffness_n_per_mm_um"):
        linear_spring_face_load(mean_line_load_n_per_mm=50.0, misalignment_um=1.0,
                                stiffness_n_per_mm_um=0.0)


@pytest.mark.parametrize("slope_um_per_mm", [0.0, 0.05, 0.855, 5.13])
def test_end_loaded_line_is_the_finite_line_on_its_loaded_length(slope_um_per_mm):
    """The law's definition: the interference over the loaded length is L_c times the
    finite line's approach of W on L_c (analytic.hertz, Johnson 1985 sec. 4.3), d is the
    gap's closing, and the triangle's / trapezoid's area is W (1e-9: Brent's 1e-13)."""
    s, length = slope_um_per_mm * 1e-3, 19.1
    r = end_loaded_line(load_n=W, slope=s, length_mm=length, b_max_per_mm=B_MAX,
                        e_prime_mpa=E_PRIME)
    lc = r.loaded_length_mm
    _, b = line_contact_terms(B_MAX, W, lc, E_PRIME)
    area = 0.5 * s * lc * lc if r.end_loaded else length * (r.approach_mm - 0.5 * s * length)
    assert area == pytest.approx(lc * line_contact_approach_mm(W, lc, b, E_PRIME), rel=1e-9)
    if r.end_loaded:
        assert r.approach_mm == pytest.approx(s * lc, rel=1e-12)
        assert r.peak_line_load_n_per_mm == pytest.approx(2.0 * W / lc, rel=1e-12)
    # the Winkler line load W (d - s y) / I integrates to W
    y = np.linspace(0.0, lc, 100_001)
    w = r.peak_line_load_n_per_mm * (r.approach_mm - s * y) / r.approach_mm
    assert np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(y)) == pytest.approx(W, rel=1e-9)
    assert r.end_loaded == (slope_um_per_mm >= 0.855)
    assert r.hertz_pressure_mpa == pytest.approx(
        math.sqrt(r.peak_line_load_n_per_mm * E_PRIME * B_MAX / math.pi), rel=1e-12)


@pytest.mark.parametrize("slope_um_per_mm", [0.855, 1.71, 5.13])
def test_end_loaded_line_against_the_twins_slice_law(slope_um_per_mm):
    """The twin's slice law (ltca.slice_law.loaded_line, which twin.line_law runs: the
    same law on a gap sampled at slice centres, linear between them, held over the end
    half-slices) on the straight gap at 1024 slices: loaded length within half a slice
    plus 0.1 %, approach at the closed end (the flat end half-slice's s w/2 taken off)
    within 0.5 % (the discretisation; measured 2e-5 mm and -0.1 to -0.3 %)."""
    from gearcontact.ltca.slice_law import loaded_length_mm

    s, length, n = slope_um_per_mm * 1e-3, 19.1, 1024
    r = end_loaded_line(load_n=W, slope=s, length_mm=length, b_max_per_mm=B_MAX,
                        e_prime_mpa=E_PRIME)
    width = length / n
    d, lc, _ = loaded_length_mm(s * (np.arange(n) + 0.5) * width, length, W, B_MAX, E_PRIME)
    assert abs(lc - r.loaded_length_mm) <= 0.5 * width + 1e-3 * r.loaded_length_mm
    assert d - 0.5 * s * width == pytest.approx(r.approach_mm, rel=5e-3)


@pytest.mark.parametrize("slope_um_per_mm", [0.855, 1.71, 5.13])
def test_end_loaded_line_against_the_slice_law_at_16_slices(slope_um_per_mm):
    """The slice law at the twin's and the preview's 16 slices (w = L / 16) on the
    straight gap, and its peak line load W d_c / I (ltca.slice_law.equivalent_length:
    the preview's and the twin's line chain run on L_eq = W / w_peak). The end
    half-slice is held at s w / 2, so the slice law's interference lacks s w^2 / 8 of
    the wedge's (exactly, once d_c > s w / 2): with F(L) = s L^2 / 2 - lambda' W g(L)
    convex (g = 1.5 ln L + const) and F(L_c0) = 0, F(L_c) = s w^2 / 8, so 0 <= L_c -
    L_c0 <= w^2 / (8 L_c0 (1 - 3 / (4 g0))); the peaks are s L / (lambda' g(L)), so
    1 <= w_peak / (2 W / L_c0) <= L_c / L_c0 (g grows with L). Measured at 0.855 /
    1.71 / 5.13 um/mm: L_c - L_c0 = 0.0240 / 0.0370 / 0.0762 mm against the bound's
    0.0241 / 0.0372 / 0.0778 (its tangent is nearly F itself), peak +0.20 / +0.43 /
    +1.48 % within +0.28 / +0.64 / +2.6 %; the bounds carry 1e-9 for Newton's stop."""
    from gearcontact.ltca.slice_law import equivalent_length, loaded_length_mm

    s, length, n = slope_um_per_mm * 1e-3, 19.1, 16
    r = end_loaded_line(load_n=W, slope=s, length_mm=length, b_max_per_mm=B_MAX,
                        e_prime_mpa=E_PRIME)
    width = length / n
    d, lc, area = loaded_length_mm(s * (np.arange(n) + 0.5) * width, length, W, B_MAX,
                                   E_PRIME)
    l0 = r.loaded_length_mm
    _, b = line_contact_terms(B_MAX, W, l0, E_PRIME)
    g0 = math.log(4.0 * l0 / b) - 0.75
    bound = width ** 2 / (8.0 * l0 * (1.0 - 0.75 / g0))
    assert 0.0 <= lc - l0 <= bound * (1.0 + 1e-9)
    ratio = W / equivalent_length(d, area, length) / r.peak_line_load_n_per_mm
    assert 1.0 - 1e-9 <= ratio <= lc / l0 * (1.0 + 1e-9)


def test_end_loaded_line_refuses_bad_input():
    kw = dict(load_n=W, length_mm=19.1, b_max_per_mm=B_MAX, e_prime_mpa=E_PRIME)
    with pytest.raises(InputRangeError, match="slope"):
        end_loaded_line(slope=-1e-3, **kw)
    with pytest.raises(InputRangeError, match="slope"):
        end_loaded_line(slope=10.0, **kw)          # steeper than the line law's range
    with pytest.raises(InputRangeError, match="load_n"):
        end_loaded_line(slope=1e-3, **{**kw, "load_n": float("nan")})
