"""Tooth bending compliance: Mindlin-Reissner plate Rayleigh-Ritz over the tooth mid-surface.

Each tooth (:mod:`.tooth`) is a shear-deformable plate of variable thickness t(xi, eta)
over its mid-surface (the derivation is in ``docs/bending.md``):

- kinematics: a point at distance z from the mid-surface along its normal m moves by
  ``u = w m + z (beta_1 e_1 + beta_2 e_2)`` (e_1 lengthwise, e_2 towards the tip);
- energy: ``U = 1/2 int [kappa^T D_b kappa + gamma^T D_s gamma] dA`` with
  ``kappa = (beta_1,1, beta_2,2, beta_1,2 + beta_2,1)``, ``gamma_a = w,a + beta_a``,
  ``D_b = E t^3 / (12 (1 - nu^2)) [[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu)/2]]``,
  ``D_s = kappa_s G t I`` (kappa_s = 5/6); derivatives with respect to the local
  Cartesian coordinates of the tangent plane, ``dA`` the true area element (the metric
  of the real mid-surface; the coupling of membrane and bending through the
  mid-surface curvature is neglected, a shallow-shell / plate approximation);
- Ritz basis: ``w, beta_1, beta_2 = sum_ij a_ij P_i(xi) P_j(eta) r(eta)`` with Legendre
  polynomials of degree <= ``order_face`` along the face (xi) and <= ``order`` over the
  height (eta) (a tooth is 5-10 times longer than high); ``r = (1 + eta)/2`` makes beta_1
  vanish at the root eta = -1, and w and beta_2 too when the root is clamped
  (``RootFoundation(0, 0)``);
- root / rim flexibility (a foundation along the root line, Weber 1949, O'Donnell 1963,
  Sainsot et al. 2004): with a non-zero coefficient, beta_2 (the root rotation) and w
  (the root translation) are free at the root and restrained by springs per unit root
  length, ``U_root = 1/2 int (k_r beta_2^2 + k_w w^2) dl`` with
  ``k_r = E t_root^2 / (c_r (1 - nu^2))`` (N/rad) and ``k_w = E / (c_w (1 - nu^2))``
  (N/mm^2): the foundation rotation ``theta = c_r (1 - nu^2) M / (E t^2)`` and
  translation ``w = c_w (1 - nu^2) q / E`` of a root moment M / force q per unit length.
  The coefficients are calibrated against 3D finite elements of the tooth with its rim
  segment (:mod:`.fe`, ``docs/bending.md``);
- a unit load along the unit direction d at a flank point (offset z from the
  mid-surface) does work on ``delta = (d.m) w + z ((d.e_1) beta_1 + (d.e_2) beta_2)``,
  i.e. ``delta = phi^T a``; with the stiffness K (Gauss-Legendre quadrature) the
  compliance between points i, j is ``G_ij = phi_i^T K^-1 phi_j`` (Maxwell-Betti
  symmetric, positive semi-definite, rank <= number of Ritz functions). It is kept
  low-rank as ``G = B B^T``, ``B = Phi L^-T`` (K = L L^T), so ``G w`` costs O(n m).

The Ritz trial spaces of increasing order are nested, so the compliance grows
monotonically with the order towards the plate solution (Ritz is an upper bound on the
stiffness).

References
----------
M. Kolivand, A. Kahraman, "A load distribution model for hypoid gears using ease-off
topography and shell theory", *Mechanism and Machine Theory* 44(10), 2009, 1848-1865.
R. D. Mindlin, "Influence of rotatory inertia and shear on flexural motions of
isotropic, elastic plates", *J. Appl. Mech.* 18, 1951, 31-38.
K. M. Liew, Y. Xiang, S. Kitipornchai, "Research on thick plate vibration: a literature
survey", *J. Sound Vib.* 180(1), 1995, 163-176 (Ritz with polynomial bases).
A. E. O'Donnell, "Stress and deflection in built-in beams", *J. Eng. Ind.* 85, 1963;
C. Weber, "The deformation of loaded gears and the effect on their load-carrying
capacity", DSIR report 3, 1949 (root / foundation rotation).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from numpy.polynomial import legendre
from scipy.linalg import cho_factor, solve_triangular

from ..geometry.flank import FlankSet
from ..threads import one_blas_thread
from ..validation import InputRangeError, check_range
from .tooth import LoadPoints, ToothGeometry, local_frame, tooth_geometry

__all__ = ["ShellModel", "ComplianceOperator", "RootFoundation", "build_shell",
           "tooth_shell", "ROOT_FOUNDATION", "SHEAR_FACTOR", "CLAMPED"]

#: Mindlin shear correction factor kappa_s (Mindlin 1951; Reissner's 5/6).
SHEAR_FACTOR = 5.0 / 6.0



@dataclass(frozen=True)
class RootFoundation:
    """Root / rim foundation coefficients (dimensionless, module docstring).

    Parameters
    ----------
    rotation : float
        c_r >= 0 of the root rotation spring (0: rotation clamped).
    translation : float
        c_w >= 0 of the root translation spring (0: translation clamped).
    """

    rotation: float
    translation: float

    def __post_init__(self):
        check_range("root_foundation.rotation", self.rotation, 0.0, 1e3)
        check_range("root_foundation.translation", self.translation, 0.0, 1e3)


#: A clamped root (the closed-form cantilever plate).
CLAMPED = RootFoundation(0.0, 0.0)

#: Calibrated root / rim coefficients per member: the grid search of ``docs/bending.md``
#: against 3D FE (P2, 20 x 8 x 4 cells + 6 rim layers) of the s0003 teeth with their rim
#: segments, on the deflection under distributed loads (segment and line loads along
#: the face at three heights; shell orders 6 / 16): shell/FE 0.76..1.20 (pinion),
#: 0.79..1.09 (gear).
ROOT_FOUNDATION = {"pinion": RootFoundation(3.0, 1.0), "gear": RootFoundation(10.0, 2.0)}

#: Gauss-Legendre points per direction of the stiffness quadrature (fixed, so that the
#: trial spaces of different orders are compared on the same integration rule); along
#: the face at least ``order_face + 6`` points.
_QUADRATURE = 20


def _legendre_table(x: np.ndarray, order: int) -> tuple[np.ndarray, np.ndarray]:
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
class ComplianceOperator:
    """Low-rank compliance ``G = B B^T`` between a set of points, mm/N.

    ``G[i, j]`` is the deflection along direction i at point i for a unit load along
    direction j at point j (:class:`~.tooth.LoadPoints`).

    Attributes
    ----------
    factor : ndarray (n, m)
        B = Phi L^-T (mm/N)^(1/2).
    points : LoadPoints
    """

    factor: np.ndarray
    points: LoadPoints

    @property
    def shape(self) -> tuple[int, int]:
        n = self.factor.shape[0]
        return (n, n)

    def apply(self, load_n: np.ndarray) -> np.ndarray:
        """Deflections (mm) under loads ``load_n`` (N) at the points: ``B (B^T f)``."""
        return self.factor @ (self.factor.T @ np.asarray(load_n, float))

    def matrix(self) -> np.ndarray:
        """Dense G (n, n), mm/N."""
        return self.factor @ self.factor.T

    def diagonal(self) -> np.ndarray:
        """Self-compliances G_ii (n,), mm/N."""
        return np.einsum("ij,ij->i", self.factor, self.factor)


@dataclass(frozen=True, eq=False)
class ShellModel:
    """Rayleigh-Ritz Mindlin plate model of one tooth (module docstring).

    Build with :func:`build_shell`. ``cholesky`` is the lower Cholesky factor of the
    stiffness K (N/mm, in Ritz coordinates).
    """

    body: object
    order: int
    order_face: int
    foundation: RootFoundation
    cholesky: np.ndarray
    n_functions: int

    def shape_functions(self, xi, eta) -> tuple[np.ndarray, ...]:
        """Values and derivatives of the Ritz functions of (w, beta_1, beta_2):
        ``(N, N_xi, N_eta)`` each (3, nb, n) for the three fields."""
        xi, eta = np.atleast_1d(np.asarray(xi, float)), np.atleast_1d(np.asarray(eta, float))
        px, dpx = _legendre_table(xi, self.order_face)
        pe, dpe = _legendre_table(eta, self.order)
        r, dr = 0.5 * (1.0 + eta), 0.5 * np.ones_like(eta)
        fd = self.foundation
        vals, dxi, deta = [], [], []
        for clamped in (fd.translation == 0.0, True, fd.rotation == 0.0):
            qe = pe * r if clamped else pe
            dqe = dpe * r + pe * dr if clamped else dpe
            vals.append((px[:, None, :] * qe[None, :, :]).reshape(-1, len(xi)))
            dxi.append((dpx[:, None, :] * qe[None, :, :]).reshape(-1, len(xi)))
            deta.append((px[:, None, :] * dqe[None, :, :]).reshape(-1, len(xi)))
        return np.array(vals), np.array(dxi), np.array(deta)

    def load_vectors(self, points: LoadPoints) -> np.ndarray:
        """Phi (n, m): deflection of each point along its direction per Ritz coordinate."""
        mid = self.body.mid_surface(points.xi, points.eta)
        e1, e2, m = local_frame(mid)
        N, _, _ = self.shape_functions(points.xi, points.eta)
        d, z = points.direction, points.offset_mm
        coef = np.stack([np.einsum("ni,ni->n", d, m), z * np.einsum("ni,ni->n", d, e1),
                         z * np.einsum("ni,ni->n", d, e2)])          # (3, n)
        return np.concatenate([(N[f] * coef[f]).T for f in range(3)], axis=1)

    @cached_property
    def inverse_cholesky_t(self) -> np.ndarray:
        """``L^-T`` (m x m), (N/mm)^(-1/2): made once per model, so that a factor
        ``B = Phi L^-T`` is one matrix product (BLAS on one thread: threaded BLAS of
        these sizes spins on a busy machine)."""
        with one_blas_thread():
            out = solve_triangular(self.cholesky, np.eye(self.n_functions), lower=True,
                                   check_finite=False).T
        out.setflags(write=False)
        return out

    def compliance(self, points: LoadPoints) -> ComplianceOperator:
        """:class:`ComplianceOperator` between ``points`` (mm/N)."""
        phi = self.load_vectors(points)
        with one_blas_thread():
            factor = phi @ self.inverse_cholesky_t
        return ComplianceOperator(factor=factor, points=points)

    def cross_compliance(self, at: LoadPoints, loads: LoadPoints) -> np.ndarray:
        """G[i, j]: deflection at ``at[i]`` for a unit load at ``loads[j]``, mm/N."""
        return self.compliance(at).factor @ self.compliance(loads).factor.T


def _stiffness(body, model: ShellModel) -> np.ndarray:
    """Ritz stiffness K (m x m), N/mm: Gauss-Legendre quadrature of the plate energy."""
    g, wg = legendre.leggauss(_QUADRATURE)
    gx, wx = legendre.leggauss(max(_QUADRATURE, model.order_face + 6))
    XI, ETA = np.meshgrid(gx, g, indexing="ij")
    xi, eta, wq = XI.ravel(), ETA.ravel(), np.outer(wx, wg).ravel()
    mid = body.mid_surface(xi, eta)
    e1, e2, _ = local_frame(mid)
    # J maps (d xi, d eta) -> local (dx1, dx2); gradient = J^-T (d/dxi, d/deta)
    j11 = np.einsum("ni,ni->n", e1, mid.x_xi)
    j12 = np.einsum("ni,ni->n", e1, mid.x_eta)
    j22 = np.einsum("ni,ni->n", e2, mid.x_eta)
    det = j11 * j22
    if np.any(det <= 0.0):
        raise InputRangeError("mid-surface Jacobian", float(det.min()), "> 0 (a regular surface)")
    N, Nxi, Neta = model.shape_functions(xi, eta)
    # inverse-transpose of [[j11, j12], [0, j22]]: d/dx1 = f_xi/j11,
    # d/dx2 = (f_eta - j12/j11 f_xi)/j22
    dx1 = Nxi / j11
    dx2 = (Neta - (j12 / j11) * Nxi) / j22
    nb, nq = N.shape[1], len(xi)
    zero = np.zeros((nb, nq))
    # rows: kappa_11, kappa_22, kappa_12 (engineering), gamma_1, gamma_2; columns: w, b1, b2
    Bb = np.stack([np.concatenate([zero, dx1[1], zero]),
                   np.concatenate([zero, zero, dx2[2]]),
                   np.concatenate([zero, dx2[1], dx1[2]])])            # (3, m, nq)
    Bs = np.stack([np.concatenate([dx1[0], N[1], zero]),
                   np.concatenate([dx2[0], zero, N[2]])])              # (2, m, nq)
    mat = body.material
    E, nu = mat.youngs_modulus_mpa, mat.poisson_ratio
    t = mid.thickness_mm
    dA = wq * det
    D = E * t ** 3 / (12.0 * (1.0 - nu * nu)) * dA
    Gs = SHEAR_FACTOR * E / (2.0 * (1.0 + nu)) * t * dA
    Db = np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1.0 - nu)]])
    K = np.einsum("amq,ab,bnq,q->mn", Bb, Db, Bb, D, optimize=True)
    K += np.einsum("amq,anq,q->mn", Bs, Bs, Gs, optimize=True)
    fd = model.foundation
    mr = body.mid_surface(gx, -np.ones_like(gx))
    dl = wx * np.linalg.norm(mr.x_xi, axis=-1)
    Nr, _, _ = model.shape_functions(gx, -np.ones_like(gx))
    z0 = np.zeros_like(Nr[0])
    springs = ((fd.rotation, mr.thickness_mm ** 2, np.concatenate([z0, z0, Nr[2]])),
               (fd.translation, 1.0, np.concatenate([Nr[0], z0, z0])))
    for coef, t2, row in springs:
        if coef > 0.0:
            k = E * t2 / (coef * (1.0 - nu * nu)) * dl
            K += np.einsum("mq,nq,q->mn", row, row, k)
    return 0.5 * (K + K.T)


def build_shell(body, *, order: int = 6, order_face: int | None = None,
                foundation: RootFoundation = CLAMPED) -> ShellModel:
    """Assemble and factor the Ritz stiffness of a plate body.

    Parameters
    ----------
    body : ToothGeometry or RectangularPlate
        The plate (mid-surface, thickness, material).
    order : int
        Legendre degree over the height (eta), 1..16.
    order_face : int or None
        Legendre degree along the face (xi), 1..24 (default ``order``);
        3 (order + 1)(order_face + 1) Ritz functions.
    foundation : RootFoundation
        Root / rim foundation coefficients (default clamped).

    Raises
    ------
    InputRangeError
        For an order outside 1..16, a non-positive thickness, or a stiffness that is
        not positive definite.
    """
    if isinstance(order, bool) or int(order) != order or not 1 <= order <= 16:
        raise InputRangeError("order", order, "an integer in [1, 16]")
    order_face = order if order_face is None else order_face
    if isinstance(order_face, bool) or int(order_face) != order_face or not 1 <= order_face <= 24:
        raise InputRangeError("order_face", order_face, "an integer in [1, 24]")
    t = body.mid_surface(*np.meshgrid(np.linspace(-1, 1, 9), np.linspace(-1, 1, 9))).thickness_mm
    if not np.all(t > 0.0):
        raise InputRangeError("thickness_mm", float(np.min(t)), "> 0 everywhere")
    n = 3 * (int(order) + 1) * (int(order_face) + 1)
    if not isinstance(foundation, RootFoundation):
        raise InputRangeError("foundation", foundation, "a RootFoundation")
    model = ShellModel(body=body, order=int(order), order_face=int(order_face),
                       foundation=foundation,
                       cholesky=np.empty((0, 0)), n_functions=n)
    K = _stiffness(body, model)
    try:
        L, _ = cho_factor(K, lower=True)
    except np.linalg.LinAlgError:
        raise InputRangeError("shell stiffness", "not positive definite",
                              "a regular plate (check thickness and order)") from None
    object.__setattr__(model, "cholesky", np.tril(L))
    return model


@lru_cache(maxsize=8)
def tooth_shell(flanks: FlankSet, member: str, *, material, order: int = 6,
                order_face: int = 16, foundation: RootFoundation | None = None
                ) -> ShellModel:
    """The shell model of one tooth of ``member``, cached per flank set and member.

    ``foundation`` defaults to the calibrated :data:`ROOT_FOUNDATION` of the member;
    the default orders (6 over the height, 16 along the face) are those of the
    calibration (a tooth is 5-10 times longer than high).
    Both flanks (drive and coast) of the tooth use the same model (one cache entry per
    pair, member and options; the flank set is hashed by identity).
    """
    tooth: ToothGeometry = tooth_geometry(flanks, member, material=material)
    return build_shell(tooth, order=order, order_face=order_face,
                       foundation=ROOT_FOUNDATION[member] if foundation is None else foundation)
