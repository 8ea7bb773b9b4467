"""geometry.minimax_fit: the maximum-norm fit by sequential linear programming.

Truth: Chebyshev's best uniform approximation. The polynomial of degree <= 2 nearest to
x^3 on [-1, 1] in the maximum norm is (3/4) x, with error T_3(x)/4 = x^3 - (3/4) x of
maximum 1/4, reached with alternating signs at x = -1, -1/2, 1/2, 1 (Chebyshev
equioscillation: n + 1 = 4 points for 3 parameters; Powell 1981, *Approximation theory
and methods*, ch. 7). A grid holding these points has the same discrete optimum.
"""

import numpy as np
import pytest

from gearcontact.geometry.minimax_fit import minimize_max_abs

_X = np.linspace(-1.0, 1.0, 201)      # holds +-1 and +-1/2


def _residual(p):
    # nonlinear in the parameters (b = exp(beta), c = s^3) so that the linear programs
    # are linearizations, and singular at the optimum s = 0 (a column of J vanishes)
    a, beta, s = p
    return _X ** 3 - (a + np.exp(beta) * _X + s ** 3 * _X ** 2)


def _jacobian(p):
    a, beta, s = p
    return np.column_stack([-np.ones_like(_X), -np.exp(beta) * _X, -3.0 * s ** 2 * _X ** 2])


def test_chebyshev_best_approximation_of_x_cubed():
    # the maximum 1/4 to 1e-9 (measured 3e-13, 23 linear programs), the coefficients
    # a = 0, b = 3/4 to 1e-9 and c = s^3 = 0 to 1e-9 (s itself is weakly determined);
    # the error alternates at the four Chebyshev points (to 1e-9)
    r = minimize_max_abs(_residual, _jacobian, [0.3, 0.0, 0.5], tol=1e-12)
    assert r.converged
    assert r.max_abs == pytest.approx(0.25, abs=1e-9)
    a, beta, s = r.x
    assert abs(a) < 1e-9 and np.exp(beta) == pytest.approx(0.75, abs=1e-9)
    assert abs(s ** 3) < 1e-9
    f = _residual(r.x)
    at = [int(np.argmin(np.abs(_X - x))) for x in (-1.0, -0.5, 0.5, 1.0)]
    assert np.allclose(f[at], [-0.25, 0.25, -0.25, 0.25], atol=1e-9)


def test_minimax_beats_least_squares_in_the_maximum():
    # the least-squares cubic-by-quadratic fit (numpy lstsq, an independent solver) has a
    # larger maximum than 1/4 (measured 0.394 at x = +-1) and the minimax started from it
    # reaches 1/4 (to 1e-9)
    basis = np.column_stack([np.ones_like(_X), _X, _X ** 2])
    coef = np.linalg.lstsq(basis, _X ** 3, rcond=None)[0]
    lsq_max = np.abs(_X ** 3 - basis @ coef).max()
    assert lsq_max > 0.3
    r = minimize_max_abs(_residual, _jacobian, [coef[0], np.log(coef[1]), np.cbrt(coef[2])], tol=1e-12)
    assert r.max_abs == pytest.approx(0.25, abs=1e-9)
