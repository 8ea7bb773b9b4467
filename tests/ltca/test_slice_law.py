"""The slice law (gearcontact.ltca.slice_law): the loaded length of a line contact on
the ease-off along the line, shared by the twin's line law and analyze's cylindrical
preview. Truths: the exact elongated Hertz ellipse (Johnson 1985 eq. 4.39-4.41) and the
finite line's closed form (Johnson 1985 sec. 4.3)."""

import numpy as np
import pytest

from gearcontact.analytic.hertz import (exact_elliptic_hertz, line_contact_approach_mm,
                                        line_contact_terms)
from gearcontact.ltca.slice_law import equivalent_length, interference, loaded_line


def test_slice_law_against_the_elongated_hertz_ellipse():
    """The slice law (ltca.slice_law, the twin's line law and analyze's cylindrical
    preview: the loaded length where the ease-off along the line
    lies below the approach, the interference I carried by the finite line's modulus,
    ``I = 4 W / (pi E') (ln(4 L_c / b) - 3/4)``) on a lead-crowned line, the gap ``A y^2``
    along and ``B x^2`` across: a Hertz ellipse of curvature ratio B / A = 2000 (the
    EV example's lines are 1,900-2,400), whose exact solution (Johnson 1985 eq.
    4.39-4.41, analytic.hertz.exact_elliptic_hertz) is the truth. The law's approach is
    the uniform strip's energy mean, which lies 3.2-3.4 % below the half-space LCP on a
    finite cylinder (tests/analytic/test_hertz.py); here it lies 3.2 % below Hertz's
    (measured 0.968 at 256 slices over 40 mm, the limit; 0.971-0.979 with the twin's
    16 slices over a 20 mm line, the EV's 18-21 mm, where the chords of the parabola
    add interference): bound -5 % < law / Hertz - 1 < 0 at three loads (the ellipse is
    self-similar). The loaded half-length against Hertz's a: Hertz's is 0.91 x its
    interference half-length sqrt(delta / A), the law's L_c / 2 is that length at its
    own approach: bound 1.0-1.15 (measured 1.077-1.080). The peak line load W d_c / I
    (at the least gap, equivalent_length's L_eq = W / w_peak) against the ellipse's
    along its major axis, pi p0 b / 2 = 3 W / (4 a): the law's is 3 W / (2 L_c) on the
    parabola, so the same ratio inverted, bound 0.85-1.0 (measured 0.928 at 256 slices,
    0.931-0.939 at 16). On a flat line (h = 0) the law is the uniform line's closed form
    (1e-13) over the whole line, its
    peak the mean W / L (L_eq = L, 1e-13)."""
    e_prime, b_across = 229_670.0, 0.05
    a_along = b_across / 2000.0
    for n, length in ((16, 20.0), (256, 40.0)):
        y = (np.arange(n) + 0.5) / n * length - 0.5 * length
        pv = np.zeros(2 * n)
        for w in (100.0, 300.0, 700.0):     # Hertz a = 4.4, 6.3, 8.3 mm: inside the line
            pv[:n] = a_along * y ** 2
            d_c, l_c, area = loaded_line(pv, 0, n, length, w, b_across, e_prime)
            hz = exact_elliptic_hertz(a_along, b_across, w, e_prime_mpa=e_prime)
            assert -0.05 < d_c / hz.approach_mm - 1.0 < 0.0
            assert 1.0 < 0.5 * l_c / hz.a_mm < 1.15
            w_peak = w / equivalent_length(d_c, area, length)
            assert 0.85 < w_peak / (0.75 * w / hz.a_mm) < 1.0
            assert interference(pv, 0, n, length / n, d_c, False)[:2] == pytest.approx(
                (area, l_c), rel=1e-14)
            pv[:n] = 0.0
            d_c, l_c, area = loaded_line(pv, 0, n, length, w, b_across, e_prime)
            _, b = line_contact_terms(b_across, w, length, e_prime)
            assert l_c == pytest.approx(length, rel=1e-15)
            assert equivalent_length(d_c, area, length) == pytest.approx(length, rel=1e-13)
            assert d_c == pytest.approx(line_contact_approach_mm(w, length, b, e_prime),
                                        rel=1e-13)
