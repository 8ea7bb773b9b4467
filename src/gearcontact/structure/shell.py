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
  mid-surface curvature is neglected, a shallow-shell / plate approximation; with
  ``membrane=True`` it is kept as a shallow shell: in-plane fields u_1, u_2, membrane
  strain ``eps_ab = (u_a,b + u_b,a)/2 - b_ab w`` with the mid-surface's second
  fundamental form ``b_ab = m . X,ab`` (:func:`second_form`), membrane energy
  ``1/2 int eps^T A eps dA``, ``A = E t / (1 - nu^2) [...]``, and, with
  ``membrane_shear``, ``gamma_a = w,a + beta_a + b_ab u_b``; docs/bending.md sec. 12);
- Ritz basis: ``w, beta_1, beta_2 = sum_ij a_ij P_i(xi) P_j(eta') r(eta')`` with Legendre
  polynomials of degree <= ``order_face`` along the face (xi) and <= ``order`` over the
  height (a tooth is 5-10 times longer than high); ``r = (1 + eta')/2`` clamps all three
  fields at the plate's bottom ``eta' = -1``;
- root and rim (``docs/bending.md`` sec. 3): the plate continues below the root line
  through the root fillet and the rim block of :mod:`.rim` (the same geometry as the
  3D FE's), clamped at the rim's bottom; ``eta'`` runs from there (-1) over the rim and
  the tooth to the tip (1). The plate model of the fillet and the rim block (wide,
  shallow, with a twisted mid-surface) is too soft against the 3D solid: their modulus
  is raised by a factor calibrated per member against the FE (:data:`RIM_STIFFENING`).
  With ``rim_block`` the block below the fillet is a Ritz solid instead, coupled to the
  plate (:mod:`.rim_block`, docs/bending.md sec. 13). Without a rim segment the plate is clamped at the root line (the closed-form
  cantilever);
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
K. Marguerre, "Zur Theorie der gekrümmt[en] Platte grosser Formänderung", *Proc. 5th
Int. Congr. Appl. Mech.*, 1938, 93-101 (the shallow shell).
P. M. Naghdi, "The theory of shells and plates", in *Handbuch der Physik* VIa/2,
Springer, 1972, 425-640 (the shear-deformable shell's transverse shear with b_ab u_b).
R. D. Mindlin, "Influence of rotatory inertia and shear on flexural motions of
isotropic, elastic plates", *J. Appl. Mech.* 18, 1951, 31-38.
K. M. Liew, Y. Xiang, S. Kitipornchai, "Research on thick plate vibration: a literature
survey", *J. Sound Vib.* 180(1), 1995, 163-176 (Ritz with polynomial bases).
P. Sainsot, P. Velex, O. Duverger, "Contribution of gear body to tooth deflections - a
new bidimensional analytical formula", *J. Mech. Des.* 126(4), 2004, 748-752 (the
body's share of the tooth deflection).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from numpy.polynomial import legendre
from scipy.linalg import cho_factor, solve_triangular

from ..geometry.flank import FlankSet
from ..threads import one_blas_thread
from ..validation import InputRangeError
from .rim import RimSegment, rim_mid_surface, rim_modulus_factor, rim_segment, tooth_height_mm
from .rim_block import (BLOCK_ORDERS, BLOCK_RIM_STIFFENING, block_stiffness, check_block,
                        enrichment_count, has_block, NoBlockWarning)
from .ritz_solid import legendre_table
from .tooth import LoadPoints, ToothGeometry, local_frame, tooth_geometry
from .tooth_solid import SOLID_DEGREES, solid_count, solid_load_vectors, solid_stiffness

__all__ = ["ShellModel", "ComplianceOperator", "build_shell", "tooth_shell",
           "RIM_STIFFENING", "SHEAR_FACTOR", "ORDER", "ORDER_FACE"]

#: Mindlin shear correction factor kappa_s (Mindlin 1951; Reissner's 5/6).
SHEAR_FACTOR = 5.0 / 6.0



#: Factor on the modulus of the fillet and rim block of each member's plate shell
#: (module docstring; with :data:`RIM_BLOCK` the shell takes
#: :data:`~.rim_block.BLOCK_RIM_STIFFENING` instead), calibrated against the 3D FE on the teeth's real roots (P2, default mesh
#: 12 x 6 x 3 + 4 with 3 fillet layers and 2 cells across each slot bottom;
#: :mod:`.root_fillet`) of the pinions of s0003-centred, s0003 (its slot closing in a V
#: at the toe) and the ISO 23509 F.2 pair (machine-cut and conjugate) and the gears of
#: s0003-centred, s0003 and F.2, on the deflection under distributed loads (segment and
#: line loads along the face at three heights; orders 10 / 16): the one factor for both
#: members minimizing the largest |log(shell / FE)| over the eight teeth, 0.172, shell /
#: FE 0.842 .. 1.186 (docs/bending.md sec. 10; ``benchmarks/bench_rim_calibration.py``;
#: 1.45 on the seven teeth without the s0003 pinion). Against the quarter-ellipse root of
#: :mod:`.rim` the pinion needed 2.9: that root is stiffer than the real one.
RIM_STIFFENING = {"pinion": 1.49, "gear": 1.49}
#: Ritz orders of a tooth's shell (the calibration's): over the height of rim and tooth,
#: and along the face.
ORDER, ORDER_FACE = 10, 16

#: Whether a bevel tooth's shell (:func:`tooth_shell`) couples membrane and bending
#: through its mid-surface's curvature (docs/bending.md sec. 12).
MEMBRANE = False
#: Whether a bevel tooth's shell (:func:`tooth_shell`) takes its rim block below the
#: fillet as a Ritz solid (:mod:`.rim_block`, its own calibrated factor
#: :data:`~.rim_block.BLOCK_RIM_STIFFENING`; a tooth whose fillet leaves no block keeps
#: the plate at that factor, :data:`~.rim_block.BLOCK_MIN_DEPTH`): the default since
#: session 23 (docs/bending.md sec. 13, "Teeth without a block"); False: the plate
#: through the block at :data:`RIM_STIFFENING`.
RIM_BLOCK = True
#: Step of the central differences of the mid-surface's tangents in :func:`second_form`
#: (in the surface's coordinates: xi, eta in [-1, 1]; mm of height in the rim).
_CURVATURE_STEP = 1e-3

#: Gauss-Legendre points per direction of the stiffness quadrature (fixed, so that the
#: trial spaces of different orders are compared on the same integration rule); along
#: the face at least ``order_face + 6`` points.
_QUADRATURE = 20


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
    cholesky: np.ndarray
    n_functions: int
    rim: RimSegment | None = None
    membrane: bool = False
    membrane_shear: bool = True
    rim_block: bool = False
    block_orders: tuple | None = None
    block_points: tuple | None = None
    solid_degrees: tuple | None = None
    solid_points: tuple | None = None

    @property
    def n_plate(self) -> int:
        """The plate's Ritz functions (the first coordinates); with ``rim_block`` the
        block's enrichment follows them (:mod:`.rim_block`); 0 for a solid tooth
        (``solid_degrees``, :mod:`.tooth_solid`)."""
        if self.solid_degrees is not None:
            return 0
        return self.n_fields * (self.order + 1) * (self.order_face + 1)

    @property
    def n_fields(self) -> int:
        """Displacement fields of the Ritz basis: (w, beta_1, beta_2), and with the
        membrane coupling (u_1, u_2) as well."""
        return 5 if self.membrane else 3

    @cached_property
    def rim_split(self) -> float:
        """The Ritz coordinate ``eta'`` of the root line: -1 without a rim segment,
        else ``-1 + 2 D / (D + h)`` (rim depth D, tooth height h), so that ``eta'`` runs
        about evenly from the rim's clamped bottom (-1) to the tip (1)."""
        if self.rim is None:
            return -1.0
        d = self.rim.depth_mm
        return -1.0 + 2.0 * d / (d + tooth_height_mm(self.body))

    def shape_functions(self, xi, eta) -> tuple[np.ndarray, ...]:
        """Values and derivatives of the Ritz functions of (w, beta_1, beta_2) at tooth
        coordinates: ``(N, N_xi, N_eta)`` each (3, nb, n) for the three fields."""
        eta = np.atleast_1d(np.asarray(eta, float))
        scale = 0.5 * (1.0 - self.rim_split)            # d eta' / d eta
        n, n_xi, n_eta = self._functions(xi, self.rim_split + scale * (eta + 1.0))
        return n, n_xi, n_eta * scale

    def _functions(self, xi, eta_r) -> tuple[np.ndarray, ...]:
        """:meth:`shape_functions` in the Ritz coordinate ``eta'`` (-1 at the clamped
        bottom of the plate: the root line, or the rim's bottom). The fields
        (:attr:`n_fields`) share one scalar basis."""
        xi, eta = np.atleast_1d(np.asarray(xi, float)), np.atleast_1d(np.asarray(eta_r, float))
        px, dpx = legendre_table(xi, self.order_face)
        pe, dpe = legendre_table(eta, self.order)
        qe = 0.5 * (1.0 + eta) * pe
        dqe = 0.5 * (1.0 + eta) * dpe + 0.5 * pe
        n = len(xi)
        vals = (px[:, None, :] * qe[None, :, :]).reshape(-1, n)
        dxi = (dpx[:, None, :] * qe[None, :, :]).reshape(-1, n)
        deta = (px[:, None, :] * dqe[None, :, :]).reshape(-1, n)
        k = self.n_fields
        return (np.broadcast_to(vals, (k,) + vals.shape), np.broadcast_to(dxi, (k,) + dxi.shape),
                np.broadcast_to(deta, (k,) + deta.shape))

    def load_vectors(self, points: LoadPoints) -> np.ndarray:
        """Phi (n, m): deflection of each point along its direction per Ritz coordinate."""
        if self.solid_degrees is not None:
            return solid_load_vectors(self, points)
        mid = self.body.mid_surface(points.xi, points.eta)
        e1, e2, m = local_frame(mid)
        N, _, _ = self.shape_functions(points.xi, points.eta)
        d, z = points.direction, points.offset_mm
        d1, d2 = np.einsum("ni,ni->n", d, e1), np.einsum("ni,ni->n", d, e2)
        coef = [np.einsum("ni,ni->n", d, m), z * d1, z * d2]
        if self.membrane:
            coef += [d1, d2]                 # the in-plane displacements' work
        # loads act on the flanks: no work on the rim block's enrichment
        return np.concatenate([(N[f] * coef[f]).T for f in range(self.n_fields)]
                              + [np.zeros((len(d), self.n_functions - self.n_plate))], axis=1)

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
    """Ritz stiffness K (m x m), N/mm: Gauss-Legendre quadrature of the plate energy
    over the tooth and, with a rim segment, over its fillet and rim block (a rule per
    piece: the thickness has a kink where the fillet ends); with ``model.rim_block``
    the block below the fillet is the Ritz solid of :mod:`.rim_block` instead."""
    if model.solid_degrees is not None:
        return solid_stiffness(model)
    g, wg = legendre.leggauss(_QUADRATURE)
    gx, wx = legendre.leggauss(max(_QUADRATURE, model.order_face + 6))
    XI, ETA = np.meshgrid(gx, g, indexing="ij")
    xi, eta, wq = XI.ravel(), ETA.ravel(), np.outer(wx, wg).ravel()
    curv = (second_form(body.mid_surface, xi, eta) if model.membrane else None)
    K = np.zeros((model.n_functions, model.n_functions))
    p = model.n_plate
    K[:p, :p] = _plate_energy(body.mid_surface(xi, eta), *model.shape_functions(xi, eta), wq,
                              body.material, curvature=curv,
                              shear_coupling=model.membrane_shear)
    rim = model.rim
    if rim is not None:
        # depth s below the root line; the Ritz coordinate rises by (split + 1) / D per
        # mm upwards, the direction of the rim mid-surface's x_eta
        rate = (model.rim_split + 1.0) / rim.depth_mm
        pieces = ((0.0, rim.fillet_mm), (rim.fillet_mm, rim.depth_mm))
        for s0, s1 in pieces[:1] if model.rim_block else pieces:
            if s1 <= s0:
                continue
            S = 0.5 * (s0 + s1) + 0.5 * (s1 - s0) * ETA.ravel()
            n, n_xi, n_eta = model._functions(xi, model.rim_split - rate * S)
            # the rim's coordinates: (xi, height above the root line = -S)
            curv = (second_form(lambda x, up: rim_mid_surface(body, rim, x, -up), xi, -S)
                    if model.membrane else None)
            K[:p, :p] += _plate_energy(
                rim_mid_surface(body, rim, xi, S), n, n_xi, n_eta * rate,
                wq * 0.5 * (s1 - s0), body.material,
                modulus_factor=rim_modulus_factor(rim, S), curvature=curv,
                shear_coupling=model.membrane_shear)
        if model.rim_block:
            K += block_stiffness(model)
    return 0.5 * (K + K.T)


def second_form(surface, xi, eta, *, step: float = _CURVATURE_STEP) -> np.ndarray:
    """The mid-surface's second fundamental form in the local Cartesian coordinates of
    :func:`~.tooth.local_frame`: ``(b_11, b_22, b_12)`` (3, n), 1/mm, ``b = m . X,ab``.

    ``surface(xi, eta)`` gives :class:`~.tooth.MidSurfaceArrays` (``x_xi``, ``x_eta``
    per unit of its coordinates); the parametric form ``H = m . X,(xi eta)`` by central
    differences of the tangents (step ``step``), then ``b = J^-T H J^-1`` with the
    frame's ``J = [[e1 . x_xi, e1 . x_eta], [0, e2 . x_eta]]`` (the tangential parts of
    the derivatives of J drop out against the normal m).
    """
    xi, eta = np.asarray(xi, float), np.asarray(eta, float)
    mid = surface(xi, eta)
    e1, e2, m = local_frame(mid)
    xp, xm = surface(xi + step, eta), surface(xi - step, eta)
    ep, em = surface(xi, eta + step), surface(xi, eta - step)
    dot = lambda a, b: np.einsum("ni,ni->n", a, b) / (2.0 * step)   # noqa: E731
    h11 = dot(m, xp.x_xi - xm.x_xi)
    h22 = dot(m, ep.x_eta - em.x_eta)
    h12 = 0.5 * (dot(m, ep.x_xi - em.x_xi) + dot(m, xp.x_eta - xm.x_eta))
    j11 = np.einsum("ni,ni->n", e1, mid.x_xi)
    j12 = np.einsum("ni,ni->n", e1, mid.x_eta)
    j22 = np.einsum("ni,ni->n", e2, mid.x_eta)
    # J^-1 = [[1/j11, -j12/(j11 j22)], [0, 1/j22]]
    a11, a12, a22 = 1.0 / j11, -j12 / (j11 * j22), 1.0 / j22
    b11 = a11 * a11 * h11
    b12 = a11 * (a12 * h11 + a22 * h12)
    b22 = a12 * a12 * h11 + 2.0 * a12 * a22 * h12 + a22 * a22 * h22
    return np.stack([b11, b22, b12])


def _plate_energy(mid, N, Nxi, Neta, wq, material, *, modulus_factor=1.0,
                  curvature=None, shear_coupling=True) -> np.ndarray:
    """Stiffness (m x m), N/mm, of the plate energy at quadrature points of weights
    ``wq`` (per unit of the coordinates ``mid.x_xi``, ``mid.x_eta`` refer to, in which
    ``Nxi``, ``Neta`` are the derivatives); ``modulus_factor`` (scalar or per point)
    scales E (and G). With ``curvature`` (:func:`second_form` at the points) the
    fields are (w, beta_1, beta_2, u_1, u_2) and the shallow-shell membrane energy
    ``1/2 int eps^T A eps dA``, ``eps_ab = (u_a,b + u_b,a)/2 - b_ab w``, joins the
    plate's (module docstring; docs/bending.md sec. 12); with ``shear_coupling`` the
    transverse shear is ``gamma_a = w,a + beta_a + b_ab u_b`` (Naghdi), else the
    Donnell-Mushtari-Vlasov ``w,a + beta_a``."""
    e1, e2, _ = local_frame(mid)
    # J maps (d xi, d eta) -> local (dx1, dx2); gradient = J^-T (d/dxi, d/deta)
    j11 = np.einsum("ni,ni->n", e1, mid.x_xi)
    j12 = np.einsum("ni,ni->n", e1, mid.x_eta)
    j22 = np.einsum("ni,ni->n", e2, mid.x_eta)
    det = j11 * j22
    if np.any(det <= 0.0):
        raise InputRangeError("mid-surface Jacobian", float(det.min()), "> 0 (a regular surface)")
    # inverse-transpose of [[j11, j12], [0, j22]]: d/dx1 = f_xi/j11,
    # d/dx2 = (f_eta - j12/j11 f_xi)/j22
    dx1 = Nxi / j11
    dx2 = (Neta - (j12 / j11) * Nxi) / j22
    nb, nq = N.shape[1], N.shape[2]
    zero = np.zeros((nb, nq))
    extra = [] if curvature is None else [zero, zero]                 # u_1, u_2 columns
    shear_u = [[], []]
    if curvature is not None:
        b11, b22, b12 = curvature
        shear_u = ([b11 * N[3], b12 * N[4]] if shear_coupling else extra,
                   [b12 * N[3], b22 * N[4]] if shear_coupling else extra)
    # rows: kappa_11, kappa_22, kappa_12 (engineering), gamma_1, gamma_2; columns: w, b1, b2
    Bb = np.stack([np.concatenate([zero, dx1[1], zero] + extra),
                   np.concatenate([zero, zero, dx2[2]] + extra),
                   np.concatenate([zero, dx2[1], dx1[2]] + extra)])    # (3, m, nq)
    Bs = np.stack([np.concatenate([dx1[0], N[1], zero] + shear_u[0]),
                   np.concatenate([dx2[0], zero, N[2]] + shear_u[1])])  # (2, m, nq)
    E, nu = modulus_factor * material.youngs_modulus_mpa, material.poisson_ratio
    t = mid.thickness_mm
    dA = wq * det
    D = E * t ** 3 / (12.0 * (1.0 - nu * nu)) * dA
    Gs = SHEAR_FACTOR * E / (2.0 * (1.0 + nu)) * t * dA
    Db = np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1.0 - nu)]])
    K = np.einsum("amq,ab,bnq,q->mn", Bb, Db, Bb, D, optimize=True)
    K += np.einsum("amq,anq,q->mn", Bs, Bs, Gs, optimize=True)
    if curvature is not None:
        w = N[0]
        # rows: eps_11, eps_22, 2 eps_12; columns: w, b1, b2, u1, u2
        Bm = np.stack([np.concatenate([-b11 * w, zero, zero, dx1[3], zero]),
                       np.concatenate([-b22 * w, zero, zero, zero, dx2[4]]),
                       np.concatenate([-2.0 * b12 * w, zero, zero, dx2[3], dx1[4]])])
        A = E * t / (1.0 - nu * nu) * dA
        K += np.einsum("amq,ab,bnq,q->mn", Bm, Db, Bm, A, optimize=True)
    return K


def build_shell(body, *, order: int = 6, order_face: int | None = None,
                rim: RimSegment | None = None, membrane: bool = False,
                membrane_shear: bool = True, rim_block: bool = False,
                block_orders: tuple | None = BLOCK_ORDERS,
                block_points: tuple | None = None, solid_tooth: bool = False,
                solid_degrees: tuple = SOLID_DEGREES,
                solid_points: tuple | None = None) -> ShellModel:
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
    rim : RimSegment or None
        Continue the plate below the root line through the fillet and the rim block
        (:mod:`.rim`), clamped at the rim's bottom; None: the plate is clamped at the
        root line.
    membrane : bool
        Couple membrane and bending through the mid-surface's curvature (a shallow
        shell: the in-plane displacements u_1, u_2 join the fields, docs/bending.md
        sec. 12); False: the plate of sec. 2.
    membrane_shear : bool
        With ``membrane``: the curvature also in the transverse shear,
        ``gamma_a = w,a + beta_a + b_ab u_b`` (Naghdi); False: only in the membrane
        strain (Donnell-Mushtari-Vlasov).
    rim_block : bool
        The rim block below the fillet as a Ritz solid coupled to the plate
        (:mod:`.rim_block`, docs/bending.md sec. 13; needs ``rim``, not with
        ``membrane``); False: the plate continues through it. A block thinner than
        :data:`~.rim_block.BLOCK_MIN_DEPTH` of the rim's depth (none at all included)
        is no solid: the plate continues through it (:func:`~.rim_block.has_block`;
        the model's ``rim_block`` is then False).
    block_orders : tuple of 3 int or None
        With ``rim_block``: Legendre degrees (0..16) of the block's enrichment along the
        face, over its depth and across it; None: the plate's fields alone in the solid.
    block_points : tuple of 3 int or None
        With ``rim_block``: Gauss nodes of the block's quadrature
        (:func:`~.rim_block.block_stiffness`).
    solid_tooth : bool
        With ``rim_block`` on a tooth without a block: the tooth and its fillet as the
        Ritz solid of :mod:`.tooth_solid` instead of the plate (docs/bending.md sec. 13,
        session 25); no effect on a tooth with a block.
    solid_degrees, solid_points : tuple of 3 int
        The solid tooth's Legendre degrees (0..16) and Gauss points (None: its
        defaults), along the face, the height and across.

    Raises
    ------
    InputRangeError
        For an order outside 1..16, a non-positive thickness, or a stiffness that is
        not positive definite.
    """
    order, order_face = check_orders(order, order_face)
    t = body.mid_surface(*np.meshgrid(np.linspace(-1, 1, 9), np.linspace(-1, 1, 9))).thickness_mm
    if not np.all(t > 0.0):
        raise InputRangeError("thickness_mm", float(np.min(t)), "> 0 everywhere")
    for name, flag in (("membrane", membrane), ("membrane_shear", membrane_shear),
                       ("rim_block", rim_block), ("solid_tooth", solid_tooth)):
        if not isinstance(flag, bool):
            raise InputRangeError(name, flag, "True or False")
    n = (5 if membrane else 3) * (order + 1) * (order_face + 1)
    solid = False
    if rim is not None and not isinstance(rim, RimSegment):
        raise InputRangeError("rim", rim, "a RimSegment or None")
    if rim_block:
        if membrane:
            raise InputRangeError("rim_block", rim_block, "False with membrane=True")
        block_orders = check_block(rim, block_orders)
        # a block thinner than rim_block.BLOCK_MIN_DEPTH (none included) is no solid:
        # the plate continues through it, the limit of the solid as its depth -> 0
        rim_block = has_block(rim)
        if rim_block:
            n += enrichment_count(block_orders)
        elif solid_tooth:
            solid_degrees, solid = check_block(rim, solid_degrees), True
            n = solid_count(solid_degrees)
        else:
            warnings.warn(
                f"rim: no block below the fillet (depth {rim.depth_mm:g} mm, fillet "
                f"{rim.fillet_mm:g} mm); the plate continues through the rim at the "
                f"block model's factor {BLOCK_RIM_STIFFENING}, not calibrated without a "
                "block: against the 3D FE such a tooth's shell is 1.2-2.2 times too "
                "compliant: the plate's kinematics within a thickness of the rigid clamp "
                "(docs/bending.md sec. 13)", NoBlockWarning, stacklevel=2)
    model = ShellModel(body=body, order=order, order_face=order_face,
                       cholesky=np.empty((0, 0)), n_functions=n, rim=rim,
                       membrane=membrane, membrane_shear=membrane_shear, rim_block=rim_block,
                       block_orders=block_orders if rim_block else None,
                       block_points=block_points if rim_block else None,
                       solid_degrees=solid_degrees if solid else None,
                       solid_points=solid_points if solid else None)
    # BLAS on one thread: the stiffness's products and LAPACK's blocked Cholesky sum in
    # an order set by the thread count, so threaded BLAS gives other last bits on a
    # machine with other cores or OPENBLAS_NUM_THREADS (measured: the s0003 loaded TE
    # with bending moved by 1.6e-9 arcsec between 1 and 2 threads); one thread makes the
    # model, and every result built on it, the same everywhere (docs/architecture.md
    # "Determinism")
    with one_blas_thread():
        return factored(model, _stiffness(body, model), name="shell stiffness")


def check_orders(order, order_face) -> tuple[int, int]:
    """The plate's Ritz orders checked (:func:`build_shell`): ``order`` in 1..16,
    ``order_face`` in 1..24 (None: ``order``)."""
    if isinstance(order, bool) or int(order) != order or not 1 <= order <= 16:
        raise InputRangeError("order", order, "an integer in [1, 16]")
    order_face = order if order_face is None else order_face
    if isinstance(order_face, bool) or int(order_face) != order_face or not 1 <= order_face <= 24:
        raise InputRangeError("order_face", order_face, "an integer in [1, 24]")
    return int(order), int(order_face)


def factored(model: ShellModel, K: np.ndarray, *, name: str) -> ShellModel:
    """``model`` with the lower Cholesky factor of its stiffness K set; a K that is not
    positive definite is refused naming ``name``."""
    try:
        L, _ = cho_factor(K, lower=True)
    except np.linalg.LinAlgError:
        raise InputRangeError(name, "not positive definite",
                              "a regular plate (check thickness and order)") from None
    object.__setattr__(model, "cholesky", np.tril(L))
    return model


@lru_cache(maxsize=8)
def tooth_shell(flanks: FlankSet, member: str, *, material, order: int = ORDER,
                order_face: int = ORDER_FACE, rim: RimSegment | None = None,
                membrane: bool = MEMBRANE, rim_block: bool = RIM_BLOCK) -> ShellModel:
    """The shell model of one tooth of ``member``, cached per flank set and member.

    ``rim`` defaults to the member's fillet and rim segment (:func:`.rim.rim_segment`)
    with its calibrated :data:`RIM_STIFFENING` (with ``rim_block``,
    :data:`~.rim_block.BLOCK_RIM_STIFFENING`, also on a tooth whose fillet leaves no
    block for the solid: the plate continues there, :func:`build_shell`); the default orders (10 over the height
    of tooth and rim, 16 along the face) are those of the calibration (a tooth is 5-10
    times longer than high). Both flanks (drive and coast) of the tooth use the same
    model (one cache entry per pair, member and options; the flank set is hashed by
    identity).
    """
    tooth: ToothGeometry = tooth_geometry(flanks, member, material=material)
    if rim is None:
        rim = rim_segment(tooth, stiffening=BLOCK_RIM_STIFFENING if rim_block
                          else RIM_STIFFENING[member])
    return build_shell(tooth, order=order, order_face=order_face, rim=rim, membrane=membrane,
                       rim_block=rim_block)
