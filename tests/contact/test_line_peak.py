"""Incomplete-ellipse line-contact peak CP_max (gearcontact.contact.line_peak).

Truths (closed forms, independent of the code):

* a complete Hertz ellipse ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)``: every strip across it is a
  semi-ellipse, so CP_max = p0 (Johnson 1985, sec. 4.2);
* the Hertz line contact ``p0 sqrt(1 - y^2/b^2)`` (uniform along x): CP_max = p0;
* an ellipse cut by a flank edge along its major axis: after trimming the edge row, each
  strip is the semi-ellipse on [dy, b_s]; its load, centroid and second moment by
  quadrature (scipy.integrate.quad) give p_s; in the limit dy -> 0 the ratio
  p_s / p0 = 1 / (4 sqrt(1/4 - 16 / (9 pi^2))) = 0.9458;
* an edge spike on the trimmed row changes neither CP_max nor any strip.

Tolerances: the fields are sampled at cell centres (nodal load = p(centre) x area); the
semi-ellipse's square-root edge makes the sampled moments converge as O((dy/b)^1.5):
with 30 cells per semi-axis the measured errors are below 0.5 %, the tests allow 1 %.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from gearcontact.contact.grid import TangentGrid
from gearcontact.contact.line_peak import inadmissible_cells, line_contact_peak
from gearcontact.validation import InputRangeError

P0, A, B = 1500.0, 2.0, 0.3          # MPa, mm, mm
N = 30                                 # cells per semi-axis


def _grid(y0_mm: float, ny: int) -> TangentGrid:
    dx, dy = A / N, B / N
    return TangentGrid.uniform(2 * int(1.2 * N) + 1, ny, dx_mm=dx, dy_mm=dy,
                               x0_mm=-int(1.2 * N) * dx, y0_mm=y0_mm)


def _loads(grid: TangentGrid, *, line: bool = False) -> np.ndarray:
    x, y = grid.mesh()
    r = y ** 2 / B ** 2 if line else x ** 2 / A ** 2 + y ** 2 / B ** 2
    return P0 * np.sqrt(np.clip(1.0 - r, 0.0, None)) * grid.cell_area_mm2


def test_complete_ellipse_reads_p0():
    g = _grid(-int(1.2 * N) * B / N, 2 * int(1.2 * N) + 1)
    lp = line_contact_peak(_loads(g), g)
    assert lp.cp_max_mpa == pytest.approx(P0, rel=1e-2)
    # every strip is the centre-line Hertz pressure p0 sqrt(1 - x^2/a^2) (inner strips)
    inner = np.abs(g.x_mm) < 0.8 * A
    assert lp.strip_peak_mpa[inner] == pytest.approx(
        P0 * np.sqrt(1.0 - g.x_mm[inner] ** 2 / A ** 2), rel=1e-2)
    assert lp.trimmed_cells == 0 and lp.trimmed_load_n == 0.0


def test_line_contact_reads_p0():
    g = _grid(-int(1.2 * N) * B / N, 2 * int(1.2 * N) + 1)
    lp = line_contact_peak(_loads(g, line=True), g)
    assert np.nanmin(lp.strip_peak_mpa) == pytest.approx(P0, rel=1e-2)
    assert lp.cp_max_mpa == pytest.approx(P0, rel=1e-2)


def _strip_peak_truth(p_centre: float, b_s: float, t0: float) -> float:
    """p_s of the semi-ellipse p_centre sqrt(1 - t^2/b_s^2) on [t0, b_s] (quadrature)."""
    def p(t):
        return p_centre * np.sqrt(max(1.0 - t * t / b_s ** 2, 0.0))
    m0 = quad(p, t0, b_s)[0]
    m1 = quad(lambda t: t * p(t), t0, b_s)[0] / m0
    m2 = quad(lambda t: (t - m1) ** 2 * p(t), t0, b_s)[0] / m0
    return 2.0 * m0 / (np.pi * 2.0 * np.sqrt(m2))


def test_ellipse_cut_by_an_edge():
    """The flank boundary at t = 0 along the major axis; cells at t < 0 are off the flank
    (they carry no load), the first row at t > 0 is trimmed."""
    dy = B / N
    g = _grid(-5.5 * dy, int(1.2 * N) + 6)          # cell edges at multiples of dy
    w = _loads(g)
    off = np.broadcast_to((g.y_mm < 0.0)[:, None], w.shape).copy()
    w[off] = 0.0
    spiked = w.copy()
    edge_row = int(np.argmin(np.abs(g.y_mm - 0.5 * dy)))
    spiked[edge_row] *= 8.0                      # the rigid-edge spike of an LCP
    lp, lps = line_contact_peak(w, g, off), line_contact_peak(spiked, g, off)
    assert (inadmissible_cells(w > 0, off) == ((w > 0) & (np.abs(g.y_mm - 0.5 * dy)
                                                          < 1e-12)[:, None])).all()
    # the spike is trimmed: nothing of the peak changes, the raw cell peak does
    assert lps.cp_max_mpa == lp.cp_max_mpa
    assert lps.p_peak_cell_mpa == pytest.approx(8.0 * lp.p_peak_cell_mpa, rel=1e-12)
    assert lps.trimmed_load_n == pytest.approx(8.0 * lp.trimmed_load_n, rel=1e-12)
    # strip by strip: the quadrature truth on [dy, b_s]
    for i in (len(g.x_mm) // 2, len(g.x_mm) // 2 + N // 2):
        s = g.x_mm[i]
        b_s, p_c = B * np.sqrt(1 - s ** 2 / A ** 2), P0 * np.sqrt(1 - s ** 2 / A ** 2)
        assert lp.strip_peak_mpa[i] == pytest.approx(_strip_peak_truth(p_c, b_s, dy),
                                                      rel=1e-2)
    # the incomplete-ellipse limit 0.9458 p0 (dy/b = 1/30 leaves 1.5 % of the cut)
    limit = 1.0 / (4.0 * np.sqrt(0.25 - 16.0 / (9.0 * np.pi ** 2)))
    assert lp.cp_max_mpa == pytest.approx(limit * P0, rel=3e-2)
    assert lp.cp_max_mpa < lp.p_peak_cell_mpa * 1.01


def test_bad_input():
    g = _grid(-1.0, 10)
    w = np.zeros(g.shape)
    w[0, 0] = -1.0
    with pytest.raises(InputRangeError, match="loads_n"):
        line_contact_peak(w, g)
    with pytest.raises(InputRangeError, match="off_flank"):
        line_contact_peak(np.zeros(g.shape), g, np.zeros((2, 2), bool))
