"""Rayleigh-Ritz linear elastic solid on a mapped hexahedral block.

A block is the image ``X(q)`` of the parameter cube ``q = (q_1, q_2, q_3)`` in
[-1, 1]^3 (mm). A displacement field is a linear combination of Ritz functions; its
strain energy is ``U = 1/2 int eps^T C eps dV`` (isotropic Hooke, Voigt notation with
engineering shear strains ``eps = (u1,1, u2,2, u3,3, u2,3 + u3,2, u1,3 + u3,1,
u1,2 + u2,1)``), the gradient with respect to X through the map's Jacobian
``J = dX/dq`` (central differences of the map), ``dV = |det J| dq`` and tensor
Gauss-Legendre quadrature. The polynomial basis (:func:`legendre_products`) is
``P_i(q_1) P_j(q_2) P_k(q_3)`` times a boundary factor per direction, ``(1 + q)/2``
clamping the face ``q = -1``, ``(1 - q)/2`` the face ``q = +1``, ``1 - q^2`` both,
each function times a Cartesian unit vector (:func:`cartesian_gradients`).

Used by :mod:`.rim_block` for the rim block under a tooth (docs/bending.md sec. 13);
checked against closed forms of elasticity (rigid motions, uniform strain, the clamped
bar and the Timoshenko cantilever: tests/structure/test_ritz_solid.py).

References
----------
S. P. Timoshenko, J. N. Goodier, *Theory of Elasticity*, 3rd ed., McGraw-Hill, 1970
(the uniform-strain and cantilever solutions).
K. M. Liew, Y. Xiang, S. Kitipornchai, "Research on thick plate vibration: a literature
survey", *J. Sound Vib.* 180(1), 1995, 163-176 (Ritz with polynomial bases).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.polynomial import legendre

from ..validation import InputRangeError, check_positive

__all__ = ["legendre_table", "MappedBlock", "gauss_box", "map_jacobian", "legendre_products",
           "cartesian_gradients", "voigt_strains", "hooke_matrix", "energy_matrix",
           "regular_determinant",
           "solid_stiffness", "face_load_vector"]

#: Boundary factors of :func:`legendre_products`: value and derivative in q.
_CLAMPS = {None: (lambda q: np.ones_like(q), lambda q: np.zeros_like(q)),
           "low": (lambda q: 0.5 * (1.0 + q), lambda q: np.full_like(q, 0.5)),
           "high": (lambda q: 0.5 * (1.0 - q), lambda q: np.full_like(q, -0.5)),
           "both": (lambda q: 1.0 - q * q, lambda q: -2.0 * q)}
#: Step (in q) of the central differences of the map's Jacobian.
_JACOBIAN_STEP = 1e-5


def legendre_table(x: np.ndarray, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Values and first derivatives of P_0..P_order at x: two (order+1, n) arrays."""
    # Bonnet's recurrence (n+1) P_{n+1} = (2n+1) x P_n - n P_{n-1} and
    # P'_{n+1} = P'_{n-1} + (2n+1) P_n (Abramowitz & Stegun 22.7.10, 22.8.5): the same
    # values as numpy's legval to rounding, without its per-order call overhead
    x = np.asarray(x, float)
    val, der = np.zeros((order + 1,) + x.shape), np.zeros((order + 1,) + x.shape)
    val[0] = 1.0
    if order >= 1:
        val[1], der[1] = x, 1.0
    for n in range(1, order):
        val[n + 1] = ((2 * n + 1) * x * val[n] - n * val[n - 1]) / (n + 1)
        der[n + 1] = der[n - 1] + (2 * n + 1) * val[n]
    return val, der


@dataclass(frozen=True)
class MappedBlock:
    """An isotropic elastic block ``X = mapping(q)`` (q (n, 3) in [-1, 1]^3 -> X (n, 3),
    mm), modulus ``youngs_modulus_mpa`` (N/mm^2) and ``poisson_ratio``."""

    mapping: Callable[[np.ndarray], np.ndarray]
    youngs_modulus_mpa: float
    poisson_ratio: float

    def __post_init__(self):
        check_positive("youngs_modulus_mpa", self.youngs_modulus_mpa)
        if not -1.0 < self.poisson_ratio < 0.5:
            raise InputRangeError("poisson_ratio", self.poisson_ratio, "in (-1, 0.5)")


def gauss_box(points) -> tuple[np.ndarray, np.ndarray]:
    """Tensor Gauss-Legendre rule on [-1, 1]^3 with ``points`` = (n_1, n_2, n_3) nodes:
    nodes q (n, 3) and weights (n,)."""
    rules = [legendre.leggauss(int(n)) for n in points]
    grids = np.meshgrid(*[r[0] for r in rules], indexing="ij")
    weights = np.einsum("i,j,k->ijk", *[r[1] for r in rules]).ravel()
    return np.stack([g.ravel() for g in grids], axis=1), weights


def map_jacobian(mapping, q: np.ndarray, *, step: float = _JACOBIAN_STEP) -> np.ndarray:
    """``J[n, i, a] = dX_i / dq_a`` (n, 3, 3) of ``mapping`` at q (n, 3) by central
    differences (exact for maps of degree <= 2 in each q_a, O(step^2) otherwise)."""
    q = np.asarray(q, float)
    cols = []
    for a in range(3):
        dq = np.zeros(3)
        dq[a] = step
        cols.append((mapping(q + dq) - mapping(q - dq)) / (2.0 * step))
    return np.stack(cols, axis=2)


def legendre_products(q: np.ndarray, degrees, *, clamp=(None, None, None)
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Scalar Ritz functions ``P_i(q_1) P_j(q_2) P_k(q_3) r_1 r_2 r_3`` (module
    docstring; ``clamp[a]`` one of None, "low", "high", "both"): values (nb, n) and
    gradients with respect to q (nb, n, 3), nb = prod(degrees + 1)."""
    q = np.asarray(q, float)
    tables = []
    for a in range(3):
        if clamp[a] not in _CLAMPS:
            raise InputRangeError(f"clamp[{a}]", clamp[a], "None, 'low', 'high' or 'both'")
        p, dp = legendre_table(q[:, a], int(degrees[a]))
        r, dr = (f(q[:, a]) for f in _CLAMPS[clamp[a]])
        tables.append((p * r, dp * r + p * dr))
    (v1, d1), (v2, d2), (v3, d3) = tables
    vals = np.einsum("in,jn,kn->ijkn", v1, v2, v3).reshape(-1, len(q))
    grads = np.stack([np.einsum("in,jn,kn->ijkn", d1, v2, v3).reshape(-1, len(q)),
                      np.einsum("in,jn,kn->ijkn", v1, d2, v3).reshape(-1, len(q)),
                      np.einsum("in,jn,kn->ijkn", v1, v2, d3).reshape(-1, len(q))], axis=2)
    return vals, grads


def cartesian_gradients(grad_x: np.ndarray) -> np.ndarray:
    """Displacement gradients ``du_i/dX_j`` (3 nb, n, 3, 3) of the vector functions
    ``psi e_l`` (l = 0, 1, 2; function index ``l nb + b``) from the scalar gradients
    ``grad_x`` (nb, n, 3) with respect to X."""
    nb, n, _ = grad_x.shape
    out = np.zeros((3, nb, n, 3, 3))
    for comp in range(3):
        out[comp, :, :, comp, :] = grad_x
    return out.reshape(3 * nb, n, 3, 3)


def voigt_strains(grad: np.ndarray) -> np.ndarray:
    """Engineering strains (..., 6) from displacement gradients (..., 3, 3) (module
    docstring; a rigid rotation's skew gradient gives zero)."""
    g = grad
    return np.stack([g[..., 0, 0], g[..., 1, 1], g[..., 2, 2], g[..., 1, 2] + g[..., 2, 1],
                     g[..., 0, 2] + g[..., 2, 0], g[..., 0, 1] + g[..., 1, 0]], axis=-1)


def hooke_matrix(youngs_modulus_mpa: float, poisson_ratio: float) -> np.ndarray:
    """Isotropic 3D Hooke matrix C (6, 6), N/mm^2, for the engineering strains."""
    E, nu = float(youngs_modulus_mpa), float(poisson_ratio)
    lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    mu = E / (2.0 * (1.0 + nu))
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[np.arange(3), np.arange(3)] += 2.0 * mu
    C[np.arange(3, 6), np.arange(3, 6)] = mu
    return C


def energy_matrix(strains: np.ndarray, dv: np.ndarray, modulus_mpa, poisson_ratio: float
                  ) -> np.ndarray:
    """Stiffness ``K_mn = int eps_m^T C eps_n dV`` (m, m), N/mm, from the strains of the
    m functions at the quadrature points (m, n, 6), the volume weights ``dv`` (n,), mm^3,
    and the modulus per point (scalar or (n,)); ``K = B B^T`` with B scaled by the
    Cholesky factor of C (symmetric positive semi-definite to rounding)."""
    chol = np.linalg.cholesky(hooke_matrix(1.0, poisson_ratio))
    scale = np.sqrt(np.broadcast_to(np.asarray(modulus_mpa, float), dv.shape) * dv)
    b = np.einsum("mnv,vw,n->mnw", strains, chol, scale, optimize=True)
    b = b.reshape(b.shape[0], -1)
    return b @ b.T


def solid_stiffness(block: MappedBlock, degrees, *, clamp=(None, None, None),
                    points=None) -> np.ndarray:
    """Ritz stiffness (3 nb, 3 nb), N/mm, of the block over the vector basis of
    :func:`legendre_products` (function ``l nb + b`` is ``psi_b e_l``); ``points`` the
    Gauss nodes per direction (default degree + 3 each).

    Raises
    ------
    InputRangeError
        For a degree outside 0..16 or a map whose Jacobian is not positive.
    """
    for a, p in enumerate(degrees):
        if isinstance(p, bool) or int(p) != p or not 0 <= p <= 16:
            raise InputRangeError(f"degrees[{a}]", p, "an integer in [0, 16]")
    pts = tuple(int(p) + 3 for p in degrees) if points is None else points
    q, w = gauss_box(pts)
    J = map_jacobian(block.mapping, q)
    det = regular_determinant(J, "block map Jacobian")
    _, grads = legendre_products(q, degrees, clamp=clamp)
    grad_x = np.einsum("bna,naj->bnj", grads, np.linalg.inv(J))
    strains = voigt_strains(cartesian_gradients(grad_x))
    return energy_matrix(strains, w * det, block.youngs_modulus_mpa, block.poisson_ratio)


def regular_determinant(J: np.ndarray, name: str) -> np.ndarray:
    """|det J| (n,) of a map's Jacobians (n, 3, 3), refused (naming ``name``) unless the
    determinant keeps one sign (a regular block, either orientation)."""
    det = np.linalg.det(J)
    if not (np.all(det > 0.0) or np.all(det < 0.0)):
        raise InputRangeError(name, f"det from {det.min():.3g} to {det.max():.3g}",
                              "one sign (a regular block)")
    return np.abs(det)


def face_load_vector(block: MappedBlock, degrees, *, axis: int, side: int,
                     traction: np.ndarray, clamp=(None, None, None), points=None
                     ) -> np.ndarray:
    """Work ``f_m = int psi_m . t dA`` (3 nb,), N per unit coefficient, of a uniform
    traction ``t`` (3,), N/mm^2, on the face ``q_axis = side`` (side -1 or +1), the face
    area element from the map (central differences)."""
    if side not in (-1, 1) or axis not in (0, 1, 2):
        raise InputRangeError("face", (axis, side), "axis 0..2, side -1 or +1")
    others = [a for a in range(3) if a != axis]
    pts = [int(p) + 3 for p in degrees] if points is None else list(points)
    pts[axis] = 1
    q, w = gauss_box(pts)
    q[:, axis] = float(side)
    J = map_jacobian(block.mapping, q)
    # the one-point rule's weight along ``axis`` is 2: divided out
    da = np.linalg.norm(np.cross(J[:, :, others[0]], J[:, :, others[1]]), axis=1) * w / 2.0
    vals, _ = legendre_products(q, degrees, clamp=clamp)
    return np.concatenate([vals @ (da * traction[c]) for c in range(3)])
