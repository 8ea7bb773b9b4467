"""The Ritz solid of ``structure.ritz_solid`` against closed forms of elasticity.

Truths: a rigid motion has zero strain; a uniform strain eps stores 1/2 eps^T C eps V
(V the block's closed-form volume); a slender clamped box under an end tension is the
bar PL/(EA) and under an end shear the Timoshenko cantilever PL^3/(3EI) + PL/(k G A)
(Cowper's k = 10 (1 + nu)/(12 + 11 nu) for a rectangle; Timoshenko & Goodier 1970),
up to the clamp's Saint-Venant zone (docs/bending.md sec. 13).
"""

from __future__ import annotations

import numpy as np
import pytest

from gearcontact.structure.ritz_solid import (MappedBlock, face_load_vector, hooke_matrix,
                                              legendre_products, solid_stiffness)
from gearcontact.validation import InputRangeError

E_MPA, NU = 2.0e5, 0.3


def _twisted(q):
    """A trilinear hexahedron: skewed, tapered and twisted (q_1 q_2 q_3 terms), mm."""
    x, y, z = q[:, 0], q[:, 1], q[:, 2]
    return np.stack([3.0 * x + 0.4 * y + 0.2 * x * y * z + 5.0,
                     1.5 * y + 0.3 * x * y + 0.25 * x * z,
                     1.0 * z + 0.2 * x + 0.15 * x * y * z - 0.1 * y * z], axis=1)


def _fit(mapping, degrees, field):
    """Ritz coefficients of ``field(X)`` (n, 3) in the unclamped basis, by least squares
    at points where it is exact (residual returned)."""
    rng = np.random.default_rng(1)
    q = rng.uniform(-1.0, 1.0, (400, 3))
    vals, _ = legendre_products(q, degrees)
    A = np.kron(np.eye(3), vals.T)                          # (3 n, 3 nb), component blocks
    u = field(mapping(q))
    rhs = np.concatenate([u[:, c] for c in range(3)])
    c, *_ = np.linalg.lstsq(A, rhs, rcond=None)
    return c, float(np.max(np.abs(A @ c - rhs)))


def test_rigid_motion_of_a_twisted_block_stores_no_energy():
    """A rigid motion u = a + omega x X of the trilinear block lies in the degree-1 basis
    (the map does); its energy must vanish against the energy of a unit-size strain
    (1e-10: the Jacobian by central differences is exact for this map, only rounding
    remains)."""
    blk = MappedBlock(_twisted, E_MPA, NU)
    deg = (1, 1, 1)
    K = solid_stiffness(blk, deg)
    omega, a = np.array([0.3, -0.2, 0.5]), np.array([1.0, 2.0, -1.0])
    c, res = _fit(_twisted, deg, lambda X: a + np.cross(omega, X))
    assert res < 1e-12
    stretch, _ = _fit(_twisted, deg, lambda X: X * np.array([1e-3, 0.0, 0.0]))
    scale = np.linalg.norm(c) ** 2 / np.linalg.norm(stretch) ** 2
    assert c @ K @ c < 1e-10 * scale * (stretch @ K @ stretch)


def test_uniform_strain_of_a_skewed_block_is_the_closed_form():
    """u = eps X (eps symmetric) on an affine block X = A q + b: the Ritz energy
    1/2 c^T K c must be 1/2 eps^T C eps V with V = 8 |det A| (1e-10: both exact in the
    basis and the quadrature)."""
    A = np.array([[2.0, 0.3, 0.1], [0.2, 1.5, -0.2], [0.1, 0.4, 0.8]])
    blk = MappedBlock(lambda q: q @ A.T + np.array([1.0, -2.0, 3.0]), E_MPA, NU)
    eps = np.array([[1e-3, 2e-4, -3e-4], [2e-4, -5e-4, 1e-4], [-3e-4, 1e-4, 4e-4]])
    deg = (1, 2, 1)
    c, res = _fit(blk.mapping, deg, lambda X: X @ eps.T)
    assert res < 1e-12
    voigt = np.array([eps[0, 0], eps[1, 1], eps[2, 2], 2 * eps[1, 2], 2 * eps[0, 2],
                      2 * eps[0, 1]])
    closed = 0.5 * voigt @ hooke_matrix(E_MPA, NU) @ voigt * 8.0 * abs(np.linalg.det(A))
    ritz = 0.5 * c @ solid_stiffness(blk, deg) @ c
    assert ritz == pytest.approx(closed, rel=1e-10)


L_MM, B_MM, H_MM = 10.0, 1.0, 1.0


def _cantilever(degrees, component, points=None):
    """Mean end deflection (mm/N) of the box clamped at x = 0 under a unit end load
    along ``component`` spread evenly over the end face."""
    blk = MappedBlock(lambda q: np.stack([0.5 * L_MM * (q[:, 0] + 1.0), 0.5 * B_MM * q[:, 1],
                                          0.5 * H_MM * q[:, 2]], axis=1), E_MPA, NU)
    clamp = ("low", None, None)
    K = solid_stiffness(blk, degrees, clamp=clamp, points=points)
    t = np.zeros(3)
    t[component] = 1.0 / (B_MM * H_MM)
    f = face_load_vector(blk, degrees, axis=0, side=1, traction=t, clamp=clamp)
    return f @ np.linalg.solve(K, f)


def test_clamped_box_is_the_bar_and_the_timoshenko_cantilever():
    """L/h = 10 at degrees (6, 3, 3): within 3 % of the bar and of the Timoshenko
    cantilever (declared in docs/bending.md sec. 13 before measuring: the clamped end
    also holds the Poisson contraction and the warping, a Saint-Venant zone of about
    h, O(h / L) of the shear term and less of the bending one)."""
    area, inertia = B_MM * H_MM, B_MM * H_MM ** 3 / 12.0
    shear_mod = E_MPA / (2.0 * (1.0 + NU))
    k = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU)
    beam = L_MM ** 3 / (3.0 * E_MPA * inertia) + L_MM / (k * shear_mod * area)
    assert _cantilever((6, 3, 3), 2) == pytest.approx(beam, rel=0.03)
    assert _cantilever((6, 3, 3), 0) == pytest.approx(L_MM / (E_MPA * area), rel=0.03)


def test_compliance_never_falls_as_the_orders_rise():
    """Nested Ritz spaces on one quadrature: the end-shear compliance is non-decreasing
    in the orders (1e-12 relative: rounding of the solves)."""
    pts = (10, 6, 6)
    d = [_cantilever(deg, 2, points=pts) for deg in ((3, 1, 1), (5, 2, 2), (7, 3, 3))]
    assert d[0] <= d[1] * (1 + 1e-12) and d[1] <= d[2] * (1 + 1e-12), d


def test_bad_input_is_named():
    blk = MappedBlock(_twisted, E_MPA, NU)
    with pytest.raises(InputRangeError, match="degrees"):
        solid_stiffness(blk, (1, 17, 1))
    with pytest.raises(InputRangeError, match="poisson_ratio"):
        MappedBlock(_twisted, E_MPA, 0.5)
    with pytest.raises(InputRangeError, match="clamp"):
        legendre_products(np.zeros((1, 3)), (1, 1, 1), clamp=("top", None, None))
    with pytest.raises(InputRangeError, match="Jacobian"):
        # folded: X_1 = q_1^2, det = 2 q_1 changes sign
        solid_stiffness(MappedBlock(lambda q: np.stack([q[:, 0] ** 2, q[:, 1], q[:, 2]], 1),
                                    E_MPA, NU), (1, 1, 1))
