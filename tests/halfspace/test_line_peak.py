"""Incomplete-ellipse line-contact peak CP_max (gearcontact.halfspace.line_peak).

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

from gearcontact.halfspace.grid import TangentGrid
from gearcontact.halfspace.line_peak import (boundary_cells, contact_line_length_mm,
                                           inadmissible_cells,
                                         line_contact_peak, trimmed_gap)
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


# ------------------------------------------------- trimmed and re-solved (edge-cut Hertz)
def _cut_hertz(n: int, cut_mm: float):
    """Hertz gap (R = 20 mm along x, 5 mm along y, W = 2000 N, steel) on an n x n field
    of 4.8 x 2.4 mm with the flank ending at ``y = cut_mm`` (off-flank beyond: the
    separation 1 mm, as the LTCA gives cells without material)."""
    from gearcontact.halfspace.lcp import solve_lcp

    grid = TangentGrid.centered(n, n, dx_mm=4.8 / n, dy_mm=2.4 / n)
    x, y = grid.mesh()
    off = y > cut_mm
    gap = np.where(off, 1.0, x ** 2 / 40.0 + y ** 2 / 10.0)
    return grid, gap, off, solve_lcp(gap, grid, 2000.0, e_star_mpa=115_384.6,
                                     warn_coarse=False)


def test_edge_cut_hertz_trimmed_and_resolved():
    # Truths: the LCP's load constraint (sum w = W exactly) and the sharp-edge
    # singularity of a half-space pressed by a truncated punch, p ~ r^(-1/2) at the
    # edge (Johnson 1985 sec. 5.2): its cell average in the edge cell is 1/(sqrt 2 - 1)
    # = 2.41 times the next cell's, and grows as sqrt(n) under refinement.
    from gearcontact.halfspace.lcp import solve_lcp

    # the edge beyond the patch (b ~ 0.55 mm): nothing to trim, the solution stands
    grid, gap, off, raw = _cut_hertz(40, 0.9)
    assert trimmed_gap(gap, off, raw.contact_mask, 1.0) is None
    out = {}
    for n in (40, 80):
        grid, gap, off, raw = _cut_hertz(n, 0.0)          # cut along the major axis
        gap2 = trimmed_gap(gap, off, raw.contact_mask, 1.0)
        assert gap2 is not None                          # the boundary row was loaded
        res = solve_lcp(gap2, grid, 2000.0, e_star_mpa=115_384.6, warm_start=raw,
                        warn_coarse=False)
        assert raw.converged and res.converged
        row = boundary_cells(off)
        # load balance kept (1e-12: the rescaling to W), the trimmed row carries nothing
        assert res.loads_n.sum() == pytest.approx(2000.0, rel=1e-12)
        assert not res.contact_mask[row].any()
        col = n // 2
        jr = np.flatnonzero(row[:, col])[0]               # edge row of the raw solve
        pr, ps = raw.pressure_mpa[:, col], res.pressure_mpa[:, col]
        out[n] = (pr[jr], ps[jr - 1], line_contact_peak(raw.loads_n, grid, off).cp_max_mpa,
                  line_contact_peak(res.loads_n, grid, off | row).cp_max_mpa)
        # the re-solve does NOT remove the spike: it re-forms on the new boundary row
        # (the singularity belongs to the sharp edge, not to the cells). Edge / next
        # cell ratio: measured 1.90 raw, 2.03 re-solved at n = 40 (2.41 for the
        # singular part alone, the regular Hertz part lowers it); allowed > 1.6
        assert pr[jr] / pr[jr - 1] > 1.6 and ps[jr - 1] / ps[jr - 2] > 1.6
    # refinement: both cell peaks grow ~ sqrt 2 (measured 1.36 raw, 1.29 re-solved)
    assert 1.2 < out[80][0] / out[40][0] < 1.5 and 1.2 < out[80][1] / out[40][1] < 1.5
    # CP_max, the line-contact peak, is the mesh-robust measure: raw (trimmed after) and
    # re-solved agree within 6 % (measured 5.3 %, 3.0 %) and move < 10 % from 40 to 80
    # cells (measured 8.5 %, 6.2 %), while the cell peaks move 29-36 %
    for n in (40, 80):
        assert out[n][3] == pytest.approx(out[n][2], rel=0.06)
    assert out[80][2] == pytest.approx(out[40][2], rel=0.10)
    assert out[80][3] == pytest.approx(out[40][3], rel=0.10)


def test_contact_line_length_is_the_on_flank_run_through_the_centre():
    # cell centres x = -5.95 .. 5.95 mm (dx = 0.1), y = -0.5 .. 0.5 (row 10 at y = 0);
    # flank edges at s = -3 and s = +2 mm cut the centre line: 50 cells, 5.0 mm; an
    # on-flank island beyond the edge (4 < s < 5) is not part of the line
    grid = TangentGrid.uniform(120, 21, dx_mm=0.1, dy_mm=0.05, x0_mm=-5.95, y0_mm=-0.5)
    x, _ = grid.mesh()
    off = (x < -3.0) | (x > 2.0)
    off[10, (grid.x_mm > 4.0) & (grid.x_mm < 5.0)] = False
    assert contact_line_length_mm(off, grid) == pytest.approx(5.0, abs=1e-12)
    # no flank boundary inside the field: the field's width
    assert contact_line_length_mm(np.zeros_like(off), grid) == pytest.approx(12.0, abs=1e-12)
    # P0 itself off the flank (edge contact): the run nearest s = 0
    off2 = (x < 0.5) | (x > 2.0)
    assert contact_line_length_mm(off2, grid) == pytest.approx(1.5, abs=1e-12)
    assert contact_line_length_mm(np.ones_like(off), grid) is None
