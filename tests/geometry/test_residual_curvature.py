"""The residual's curvature at the contact path and the pressure bound it implies
(geometry.residual_curvature; docs/machine_settings.md sec. 6, "The residual's
curvature and the pressure it bounds").

Truths:
- the bound ``1 - (1 - e)^(2/3)`` against the exact elliptic Hertz solution and the
  line-contact form of analytic.hertz (independent closed forms): never exceeded for
  perturbations of relative size ``e`` in any direction, reached for ``dK = -e K``;
- the Hessian in tangent-plane arc lengths against a function known in Cartesian
  coordinates on a plane in curvilinear coordinates (the chain rule's gradient term
  matters there);
- the fit's curvature rows against the relative error formed by hand.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from gearcontact.analytic.hertz import exact_elliptic_hertz, line_contact_terms
from gearcontact.geometry.residual_curvature import (PAINT_UM, PathCurvature,
                                                     curvature_rows, path_residual,
                                                     pressure_bound, tangent_hessian)
from gearcontact.validation import InputRangeError

E_PRIME = 2.0 * 210e3 / (2.0 * (1.0 - 0.3 ** 2))     # steel on steel, MPa


def _perturbed(K, E):
    root = np.linalg.cholesky(K)
    return np.linalg.eigvalsh(root @ (np.eye(2) + E) @ root.T)


@pytest.mark.parametrize("A, B", [(0.06067, 0.000967), (0.02, 0.01), (0.5, 0.49)])
def test_pressure_bound_against_exact_hertz(A, B):
    # s0003's P0 (A- / B- 0.0607 / 0.00097 1/mm), a moderate and a nearly circular
    # contact; 400 random symmetric E of norm e in (0, 0.5), each rotated against K.
    # The exact p0 of K' = L (I + E) L^T (its eigenvalues) stays within the bound
    # (to 1e-12: the solver's relative tolerance is 4 eps)
    rng = np.random.default_rng(7)
    K = np.diag([A, B])
    p = exact_elliptic_hertz(A, B, 2000.0, e_prime_mpa=E_PRIME).p_max_mpa
    worst = 0.0
    for _ in range(400):
        e = rng.uniform(0.0, 0.5)
        m = rng.normal(size=(2, 2))
        m = 0.5 * (m + m.T)
        E = e * m / np.abs(np.linalg.eigvalsh(m)).max()
        a2, b2 = _perturbed(K, E)
        q = exact_elliptic_hertz(a2, b2, 2000.0, e_prime_mpa=E_PRIME).p_max_mpa
        assert abs(q / p - 1.0) <= pressure_bound(e) + 1e-12
        worst = max(worst, abs(q / p - 1.0) / pressure_bound(e))
    assert worst > 0.5            # the random set comes near the bound
    # reached: dK = -e K scales the gap, p0 by (1 - e)^(2/3) (degree 2/3), 1e-12
    for e in (0.05, 0.2, 0.6):
        q = exact_elliptic_hertz((1 - e) * A, (1 - e) * B, 2000.0, e_prime_mpa=E_PRIME)
        assert 1.0 - q.p_max_mpa / p == pytest.approx(pressure_bound(e), abs=1e-12)


def test_pressure_bound_covers_the_line_contact():
    # an ellipse truncated by the flank: p0 = sqrt(W E' B_max / (pi L)), degree 1/2 in
    # B_max (analytic.hertz.line_contact_terms), inside the bound of degree 2/3
    p = line_contact_terms(0.03, 2000.0, 10.0, E_PRIME)[0]
    for e in (0.01, 0.1, 0.4, 0.9):
        for s in (-1.0, 1.0):
            q = line_contact_terms(0.03 * (1 + s * e), 2000.0, 10.0, E_PRIME)[0]
            assert abs(q / p - 1.0) <= pressure_bound(e)
    assert pressure_bound(0.0) == 0.0 and pressure_bound(1.0) == math.inf
    # the rows' scale is the TCA's paint thickness, the same number
    from gearcontact.tca.curvature import PAINT_THICKNESS_MM
    assert PAINT_UM == pytest.approx(1e3 * PAINT_THICKNESS_MM, rel=1e-15)
    with pytest.raises(InputRangeError, match="error"):
        pressure_bound(-0.1)
    with pytest.raises(InputRangeError, match="tensor_per_mm"):
        PathCurvature(np.zeros(1), np.zeros(1), np.zeros((1, 3, 2)),
                      np.array([[[1e-3, 0.0], [0.0, -1e-4]]]))


class _Plane:
    """The plane z = 0 in curvilinear coordinates ``x = u + c v^2``, ``y = v``."""

    c = 0.1

    def evaluate(self, u, v, *, second=True):
        u, v = np.asarray(u, float), np.asarray(v, float)
        z, o = np.zeros_like(u), np.ones_like(u)
        vec = lambda a, b: np.stack([a, b, z], axis=-1)  # noqa: E731
        return SimpleNamespace(r=vec(u + self.c * v ** 2, v), r_u=vec(o, z),
                               r_v=vec(2 * self.c * v, o), r_uu=vec(z, z), r_uv=vec(z, z),
                               r_vv=vec(2 * self.c * o, z), n=np.stack([z, z, o], axis=-1))


def _d(u, v, c=_Plane.c):
    """d = x^2 + 3 x y (um) and its (u, v) derivatives, x = u + c v^2, y = v."""
    x = u + c * v ** 2
    return (x ** 2 + 3 * x * v,
            np.array([2 * x + 3 * v, 4 * c * v * x + 6 * c * v ** 2 + 3 * x, 2 + 0 * u,
                      4 * c * v + 3, 4 * c * x + 8 * c ** 2 * v ** 2 + 18 * c * v]))


class _FlatPlane(_Plane):
    """The plane z = 0 in Cartesian coordinates ``x = u``, ``y = v``."""

    c = 0.0


def _path(u, v, K, angle=0.3):
    c, s = math.cos(angle), math.sin(angle)
    basis = np.array([[c, -s], [s, c], [0.0, 0.0]])
    n = len(u)
    return PathCurvature(np.asarray(u), np.asarray(v), np.repeat(basis[None], n, 0),
                         np.repeat(np.asarray(K)[None], n, 0)), basis[:2]


def test_tangent_hessian_against_cartesian_coordinates():
    # the Hessian of d = x^2 + 3 x y is [[2, 3], [3, 0]] in (x, y); in a basis turned
    # by 0.3 rad, R^T H R. The (u, v) derivatives alone (without the gradient term of
    # the curved coordinate lines) would be off by 0.2 (3 + 2 x) at v = 1
    u, v = np.array([0.3, -1.0, 2.0]), np.array([1.0, 0.5, -2.0])
    path, rot = _path(u, v, np.diag([0.05, 0.001]))
    h = tangent_hessian(_Plane(), path, _d(u, v)[1])
    want = rot.T @ np.array([[2.0, 3.0], [3.0, 0.0]]) @ rot
    assert np.abs(h - want).max() < 1e-12


def test_curvature_rows_and_path_residual_by_hand():
    # d quadratic in (x, y) = (u, v) on a 9 x 11 grid: the bicubic spline through it is exact,
    # so the rows equal PAINT_UM (E_11, sqrt 2 E_12, E_22), E = K^-1/2 (H / 2 1e-3)
    # K^-1/2, formed by hand (1e-9 relative: the spline's rounding); the plane has
    # no curvature, so e = ||E||_2 exactly (no offset term)
    us, vs = np.linspace(-1, 1, 9), np.linspace(-2, 2, 11)
    U, V = np.meshgrid(us, vs, indexing="ij")
    vals = _d(U, V, c=0.0)[0]
    K = np.array([[0.04, 0.002], [0.002, 0.001]])
    path, rot = _path(np.array([0.2, -0.5]), np.array([0.7, -1.3]), K)
    h = 1e-3 * (rot.T @ np.array([[2.0, 3.0], [3.0, 0.0]]) @ rot)
    lam, vec = np.linalg.eigh(K)
    w = vec @ np.diag(lam ** -0.5) @ vec.T
    E = w @ (0.5 * h) @ w
    rows = curvature_rows(_FlatPlane(), path, us, vs) @ vals.ravel()
    want = PAINT_UM * np.array([E[0, 0], math.sqrt(2) * E[0, 1], E[1, 1]])
    assert rows == pytest.approx(np.tile(want, 2), rel=1e-9)
    got = path_residual(_FlatPlane(), path, U, V, vals)
    assert got.error == pytest.approx(np.abs(np.linalg.eigvalsh(E)).max(), rel=1e-9)
    assert got.reference_error == got.error[0]
    assert got.deviation_um == pytest.approx(_d(path.u_mm, path.v_mm, c=0.0)[0], rel=1e-9)
