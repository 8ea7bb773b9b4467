"""A tooth without a rim block as a Ritz solid (docs/bending.md sec. 13, session 25).

A tooth whose rim leaves no block below its fillet (:func:`.rim_block.has_block` false)
stands within about a thickness of its rigid clamp: every load lies at 0.26-0.61 of the
root thickness above it, where the Mindlin plate of :mod:`.shell` is 1.2-1.8 times too
compliant against 3D elasticity (docs/bending.md). Here the tooth and its fillet are one
elastic solid under a Ritz basis:

- the body: below the root line the fillet of :func:`.rim.rim_points` (depth ``s`` from 0
  to the rim's clamped bottom ``depth_mm``), above it ``P_c + zeta (P_d - P_c)`` of the
  tooth's facing flank points (:meth:`~.tooth.ToothGeometry.side_points`), ``zeta`` in
  [0, 1] from the coast to the drive flank;
- the coordinates ``(xi, eta', zeta~)``: ``eta'`` the plate's own
  (:attr:`.shell.ShellModel.rim_split`: -1 at the clamp, the split at the root line, 1 at
  the tip), ``zeta~ = 2 zeta - 1``;
- the displacement ``u = sum c_ijkl P_i(xi) P_j(eta') P_k(zeta~) (1 + eta')/2 e_l`` in
  Cartesian components (Legendre degrees ``degrees``), clamped at the rim's bottom;
- the energy ``1/2 int eps^T C eps dV`` (:mod:`.ritz_solid`), the modulus that of the
  material over the tooth and raised over the fillet as the plate's is
  (:func:`.rim.rim_modulus_factor`), by Gauss quadrature on each piece;
- a unit load along d at a flank point does work on ``u . d`` there.
"""

from __future__ import annotations

import numpy as np

from .rim import rim_modulus_factor, rim_points
from .ritz_solid import (cartesian_gradients, energy_matrix, gauss_box, legendre_products,
                         map_jacobian, regular_determinant, voigt_strains)

__all__ = ["solid_stiffness", "solid_load_vectors", "solid_count", "SOLID_DEGREES",
           "SOLID_POINTS"]

#: Legendre degrees of the solid tooth along the face, over the height (clamp to tip) and
#: across the tooth (docs/bending.md sec. 13, session 25).
SOLID_DEGREES = (12, 8, 3)
#: Gauss points of its quadrature: along the face, over the height of each piece (fillet,
#: tooth), across.
SOLID_POINTS = (18, 10, 5)
#: The height coordinate's clamp: the functions vanish at the rim's bottom, eta' = -1.
_CLAMP = (None, "low", None)


def solid_count(degrees) -> int:
    """Ritz functions of the solid tooth: 3 prod(degree + 1)."""
    return 3 * int(np.prod([int(p) + 1 for p in degrees]))


def _mapping(model, piece: str):
    """``X(q)`` (n, 3), mm, of the tooth (``piece`` "tooth") or its fillet ("fillet") at
    q = (xi, eta', zeta~) (n, 3) in that piece's range of eta'."""
    body, rim, split = model.body, model.rim, model.rim_split

    def tooth(q):
        eta = 2.0 * (q[:, 1] - split) / (1.0 - split) - 1.0
        pc, pd = body.side_points(q[:, 0], eta)
        return pc + (0.5 * (q[:, 2] + 1.0))[:, None] * (pd - pc)

    def fillet(q):
        s = rim.depth_mm * (split - q[:, 1]) / (split + 1.0)
        return rim_points(body, rim, q[:, 0], s, 0.5 * (q[:, 2] + 1.0))

    return tooth if piece == "tooth" else fillet


def solid_stiffness(model) -> np.ndarray:
    """Ritz stiffness (m, m), N/mm, of the solid tooth of ``model`` (a
    :class:`~.shell.ShellModel` with ``solid_degrees``; module docstring)."""
    degrees = model.solid_degrees
    n_xi, n_eta, n_zeta = model.solid_points or SOLID_POINTS
    split = model.rim_split
    K = np.zeros((model.n_functions, model.n_functions))
    for piece, lo, hi in (("fillet", -1.0, split), ("tooth", split, 1.0)):
        q, w = gauss_box((n_xi, n_eta, n_zeta))
        q[:, 1] = 0.5 * (lo + hi) + 0.5 * (hi - lo) * q[:, 1]
        w = w * 0.5 * (hi - lo)
        J = map_jacobian(_mapping(model, piece), q)
        det = regular_determinant(J, f"solid tooth's {piece} map Jacobian")
        _, grads = legendre_products(q, degrees, clamp=_CLAMP)
        grad_x = np.einsum("bna,naj->bnj", grads, np.linalg.inv(J), optimize=True)
        strains = voigt_strains(cartesian_gradients(grad_x))
        E = model.body.material.youngs_modulus_mpa
        if piece == "fillet":
            s = model.rim.depth_mm * (split - q[:, 1]) / (split + 1.0)
            E = E * rim_modulus_factor(model.rim, s)
        K += energy_matrix(strains, w * det, E, model.body.material.poisson_ratio)
    return K


def solid_load_vectors(model, points, *, across=None) -> np.ndarray:
    """Phi (n, m): the displacement along each point's direction per Ritz coordinate of
    the solid tooth, at flank points (:class:`~.tooth.LoadPoints` on the drive flank,
    zeta~ = 1, or the coast flank, zeta~ = -1: the side of the point's offset from the
    mid-surface) or, with ``across`` (n,), at zeta~ = ``across`` below them (0: the
    mid-surface, :mod:`.near_field`)."""
    split = model.rim_split
    eta_r = split + 0.5 * (1.0 - split) * (np.asarray(points.eta, float) + 1.0)
    if across is None:
        across = np.sign(np.asarray(points.offset_mm, float))
    q = np.stack([np.asarray(points.xi, float), eta_r, across], axis=1)
    vals, _ = legendre_products(q, model.solid_degrees, clamp=_CLAMP)
    d = np.asarray(points.direction, float)
    return np.concatenate([(vals * d[:, c]).T for c in range(3)], axis=1)
