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
            d_c, l_c, area = loaded_line(pv, 0, n, length, w, b_across, e_prime, 0, 0.0)
            hz = exact_elliptic_hertz(a_along, b_across, w, e_prime_mpa=e_prime)
            assert -0.05 < d_c / hz.approach_mm - 1.0 < 0.0
            assert 1.0 < 0.5 * l_c / hz.a_mm < 1.15
            w_peak = w / equivalent_length(d_c, area, length)
            assert 0.85 < w_peak / (0.75 * w / hz.a_mm) < 1.0
            assert interference(pv, 0, n, length / n, d_c, False, 0, 0.0)[:2] == pytest.approx(
                (area, l_c), rel=1e-14)
            pv[:n] = 0.0
            d_c, l_c, area = loaded_line(pv, 0, n, length, w, b_across, e_prime, 0, 0.0)
            _, b = line_contact_terms(b_across, w, length, e_prime)
            assert l_c == pytest.approx(length, rel=1e-15)
            assert equivalent_length(d_c, area, length) == pytest.approx(length, rel=1e-13)
            assert d_c == pytest.approx(line_contact_approach_mm(w, length, b, e_prime),
                                        rel=1e-13)


def test_edge_slices_continue_the_line():
    """The tip edge beyond a helical line's ends (the twin's edge slices: two runs of
    ``nb`` slices after the line's ``n``, each from the line's end outwards, of their own
    width) against the same gap sampled as one line of ``n + 2 nb`` slices: a run's
    end half-slice held at its end sample and the next run's first half-slice at its
    own integrate to the linear segment between them wherever both lie below the
    approach, so at such approaches the interference, the loaded length and its
    derivative are the longer line's (1e-12), the slices' shares sum to I, and the
    slice law's state at a load whose loaded length reaches into the edge slices is
    the longer line's (1e-12; its bracket's top, the line's own, is widened there).
    Gap: a crowned line (A y^2, 20 mm, 16 slices) continued beyond both ends by a
    steeper parabola (the edge's separation growing from the line's end)."""
    e_prime, b_across, a_along = 229_670.0, 0.05, 2e-5
    n, nb, length = 16, 8, 20.0
    w = length / n
    y = (np.arange(n + 2 * nb) + 0.5 - nb) * w - 0.5 * length      # whole run, line centred
    gap = np.where(np.abs(y) < 0.5 * length, a_along * y ** 2,
                   a_along * (0.5 * length) ** 2 + 4e-4 * (np.abs(y) - 0.5 * length) ** 2)
    whole = np.zeros(2 * (n + 2 * nb))
    whole[:n + 2 * nb] = gap
    split = np.zeros_like(whole)
    split[:n] = gap[nb:nb + n]
    split[n:n + nb] = gap[:nb][::-1]             # below the line, from its end outwards
    split[n + nb:n + 2 * nb] = gap[nb + n:]
    for d in (2.2e-3, 3e-3, 5e-3):              # the junctions loaded (h there 2.0 um)
        a = interference(whole, 0, n + 2 * nb, w, d, False, 0, 0.0)
        b = interference(split, 0, n, w, d, True, nb, w)
        assert b == pytest.approx(a, rel=1e-12) and b[1] > length
        assert split[n + 2 * nb:].sum() == pytest.approx(b[0], rel=1e-12)
    total = (n + 2 * nb) * w
    for load in (3000.0, 8000.0):
        want = loaded_line(whole, 0, n + 2 * nb, total, load, b_across, e_prime, 0, 0.0)
        got = loaded_line(split, 0, n, length, load, b_across, e_prime, nb, w)
        assert got[1] > length and got == pytest.approx(want, rel=1e-12)
