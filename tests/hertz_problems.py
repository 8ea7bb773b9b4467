"""Hertzian test problems for the half-space contact solvers (truth: gearcontact.analytic.hertz).

The gap ``h = A x^2 + B y^2`` (A <= B, half the relative principal curvatures) between
steel bodies has the exact elliptical Hertz solution of
:func:`gearcontact.analytic.hertz.exact_elliptic_hertz` (Johnson 1985, sec. 4.2), with
the major semi-axis ``a`` along x. Grids are centred (a cell centre at the pressure
peak) with ``n`` cells per semi-axis in each direction (``dx = a/n``, ``dy = b/n``), so
every curvature ratio has the same ~pi n^2 contact cells. The ``make_hertz`` fixture
(tests/conftest.py) caches them for the halfspace and ltca tests.
"""

from dataclasses import dataclass

import numpy as np

from gearcontact.analytic.hertz import HertzContact, exact_elliptic_hertz
from gearcontact.halfspace.grid import TangentGrid
from gearcontact.materials import STEEL, reduced_modulus_mpa

E_STAR_MPA = reduced_modulus_mpa(STEEL, STEEL)
#: Half relative curvature along x (R = 20 mm relative radius), 1/mm.
A_PER_MM = 1.0 / 40.0
LOAD_N = 1000.0


@dataclass(frozen=True)
class HertzProblem:
    grid: TangentGrid
    gap_mm: np.ndarray
    hertz: HertzContact
    ratio: float
    cells_per_semi_axis: int


def hertz_problem(ratio: float, n: int, extent: float = 1.3, *,
                  load_n: float = LOAD_N) -> HertzProblem:
    """Paraboloid gap with curvature ratio ``B/A = ratio`` on a grid of +-extent semi-axes."""
    b_coef = ratio * A_PER_MM
    hz = exact_elliptic_hertz(A_PER_MM, b_coef, load_n, e_prime_mpa=2.0 * E_STAR_MPA)
    half = int(np.ceil(extent * n))
    grid = TangentGrid.centered(2 * half + 1, 2 * half + 1, dx_mm=hz.a_mm / n,
                                dy_mm=hz.b_mm / n)
    X, Y = grid.mesh()
    return HertzProblem(grid, A_PER_MM * X ** 2 + b_coef * Y ** 2, hz, ratio, n)
