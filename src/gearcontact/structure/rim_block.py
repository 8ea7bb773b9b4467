"""The rim block below a tooth's fillet as a Ritz solid, coupled to the tooth's plate.

The plate of :mod:`.shell` covers the tooth and its fillet (down to ``fillet_mm``
below the root line, :mod:`.rim`). Below the fillet, down to the rim's clamped bottom
at ``depth_mm``, the plate's energy is replaced by the 3D elastic energy
(:mod:`.ritz_solid`) of the block itself, the body of :func:`.rim.rim_points`
(``xi`` along the face, depth ``s``, ``zeta`` across the one-pitch section), under the
displacement field (docs/bending.md sec. 13)

``u = w m + z (beta_1 e_1 + beta_2 e_2) + sum c_ijk P_i(xi) P_j(s~) P_k(zeta~) (1 - s~^2) e_l``:

- the plate's own Ritz fields (w, beta_1, beta_2) carried into the block with Mindlin's
  kinematics, ``z = (zeta - 1/2) t`` the distance across the section (t the rim
  mid-surface's thickness), the frame (e_1, e_2, m) of :func:`.rim.rim_mid_surface`
  turning with xi and s (its derivatives and the thickness's kept: central differences);
- a solid enrichment in Cartesian components (Legendre in xi, in the block's depth
  ``s~`` and across it ``zeta~ = 2 zeta - 1``, both in [-1, 1]), vanishing at the block's
  top (where the fillet's plate meets it: the coupling is exact, that section stays
  plane) and at its clamped bottom (where the plate's fields vanish too).

The energy is ``1/2 int eps^T C eps dV`` with the isotropic 3D Hooke matrix, the
modulus raised by the rim factor as the plate's rim was (:func:`.rim.rim_modulus_factor`,
flat at ``stiffening`` below the fillet). The enrichment only adds Ritz functions, so
the compliance never falls as its orders rise (nested spaces, one quadrature). Loads
act on the tooth's flanks, where only the plate's fields live. The shell takes the
block with ``build_shell(..., rim_block=True)`` (:mod:`.shell`). A block thinner than
:data:`BLOCK_MIN_DEPTH` of the rim's depth (a fillet reaching the rim's bottom
included) is no solid: the plate continues through it, the solid's own limit as the
block's depth goes to 0 (its stiffness is O(that depth)).
"""

from __future__ import annotations

import numpy as np

from ..validation import InputRangeError
from .rim import RimSegment, rim_mid_surface, rim_modulus_factor, rim_points
from .ritz_solid import (cartesian_gradients, energy_matrix, gauss_box, legendre_products,
                         map_jacobian, regular_determinant, voigt_strains)
from .tooth import local_frame

__all__ = ["block_stiffness", "check_block", "enrichment_count", "has_block", "BLOCK_ORDERS",
           "BLOCK_RIM_STIFFENING", "BLOCK_MIN_DEPTH", "NoBlockWarning"]


class NoBlockWarning(UserWarning):
    """A shell asked for its rim block has none (:func:`has_block` false): the plate
    continues through the rim at :data:`BLOCK_RIM_STIFFENING`, a factor not calibrated
    on such a tooth (docs/bending.md sec. 13, "Teeth without a block")."""

#: Legendre degrees of the block's enrichment (along the face, over the block's depth,
#: across the section; docs/bending.md sec. 13).
BLOCK_ORDERS = (8, 3, 3)
#: The rim factor of the shell with the block (:func:`~.shell.tooth_shell` with
#: ``rim_block``), calibrated as :data:`~.shell.RIM_STIFFENING` is (docs/bending.md
#: sec. 10's procedure on the eight teeth's real roots, the grid 1.0 .. 1.49): the
#: smallest worst |log(shell / FE)|, 0.136, shell / FE 0.880 .. 1.145 (sec. 13).
BLOCK_RIM_STIFFENING = 1.175
#: The thinnest block taken as a solid, as a fraction of the rim's depth: a block of
#: depth ``depth_mm - fillet_mm`` below ``BLOCK_MIN_DEPTH * depth_mm`` (none at all
#: included) is no solid, the plate continues through it (:func:`has_block`). The
#: block's stiffness is O(its depth), so the compliance is continuous as the depth goes
#: to 0 and the jump at this limit is O(the limit); the limit keeps the enrichment's
#: stiffness (~ 1 / depth) within 1e3 of a full block's (docs/bending.md sec. 13,
#: "Teeth without a block"). The factor is not calibrated on such a tooth: against
#: the 3D FE, the shell without a block is softer than the calibration's band, and
#: no factor brings it inside (docs/bending.md sec. 13, session 24): the surplus is the
#: plate's kinematics within a thickness of the rigid clamp, which no shear correction
#: of a first-order plate (kappa_s <= 1) removes; the Ritz solid of :mod:`.tooth_solid`
#: does, in the FE's convention, but not in the LTCA's (session 25).
BLOCK_MIN_DEPTH = 1e-3
#: Step of the central differences of the rim frame and thickness: in xi, and in mm of
#: depth.
_FRAME_STEP = 1e-3


def _frame_fields(body, rim: RimSegment, xi, s):
    """Frame vectors (m, e_1, e_2) (3, n, 3), thickness (n,) of the rim mid-surface at
    (xi, depth s) and their derivatives along xi and s (central differences)."""
    def at(x, d):
        mid = rim_mid_surface(body, rim, x, d)
        e1, e2, m = local_frame(mid)
        return np.stack([m, e1, e2]), mid.thickness_mm

    f, t = at(xi, s)
    h = _FRAME_STEP
    fp, tp = at(xi + h, s)
    fm, tm = at(xi - h, s)
    f_xi, t_xi = (fp - fm) / (2 * h), (tp - tm) / (2 * h)
    fp, tp = at(xi, s + h)
    fm, tm = at(xi, s - h)
    f_s, t_s = (fp - fm) / (2 * h), (tp - tm) / (2 * h)
    return f, f_xi, f_s, t, t_xi, t_s


def _plate_gradients(model, xi2, s2, n_zeta: int, zeta):
    """d u / d(xi, s, zeta) (m_plate, n, 3 components, 3 parameters) of the plate's Ritz
    functions carried into the block (module docstring) at the points of the (xi, s)
    grid ``xi2, s2`` (n2,) repeated over ``zeta`` (n_zeta values in [0, 1])."""
    body, rim = model.body, model.rim
    rate = (model.rim_split + 1.0) / rim.depth_mm
    N, N_xi, N_eta = (a[0] for a in model._functions(xi2, model.rim_split - rate * s2))
    N_s = -rate * N_eta
    f, f_xi, f_s, t, t_xi, t_s = _frame_fields(body, rim, xi2, s2)
    rep = lambda a, axis: np.repeat(a, n_zeta, axis=axis)          # noqa: E731
    N, N_xi, N_s = rep(N, 1), rep(N_xi, 1), rep(N_s, 1)
    f, f_xi, f_s = rep(f, 1), rep(f_xi, 1), rep(f_s, 1)
    t, t_xi, t_s = rep(t, 0), rep(t_xi, 0), rep(t_s, 0)
    c = np.tile(np.asarray(zeta, float) - 0.5, len(xi2))             # z / t
    nb, n = N.shape
    out = np.zeros((3, nb, n, 3, 3))
    # w: u = N m
    out[0, :, :, :, 0] = N_xi[..., None] * f[0] + N[..., None] * f_xi[0]
    out[0, :, :, :, 1] = N_s[..., None] * f[0] + N[..., None] * f_s[0]
    for k in (1, 2):                                                 # beta_k: u = z N e_k
        z, z_xi, z_s = c * t, c * t_xi, c * t_s
        out[k, :, :, :, 0] = ((z_xi * N + z * N_xi)[..., None] * f[k]
                              + (z * N)[..., None] * f_xi[k])
        out[k, :, :, :, 1] = ((z_s * N + z * N_s)[..., None] * f[k]
                              + (z * N)[..., None] * f_s[k])
        out[k, :, :, :, 2] = (t * N)[..., None] * f[k]
    return out.reshape(3 * nb, n, 3, 3)


def block_stiffness(model) -> np.ndarray:
    """Ritz stiffness (m, m), N/mm, of the solid rim block below the fillet over all the
    functions of ``model`` (a :class:`~.shell.ShellModel` with ``rim_block``: the plate's
    carried in, then the enrichment's of ``model.block_orders``); the Gauss nodes along
    (xi, depth, across) ``model.block_points`` (default ``(max(20, order_face + 6),
    12, 6)``)."""
    body, rim = model.body, model.rim
    pts = model.block_points or (max(20, model.order_face + 6), 12, 6)
    q, w = gauss_box(pts)
    top, depth = rim.fillet_mm, rim.depth_mm
    half = 0.5 * (depth - top)

    def mapping(qq):
        return rim_points(body, rim, qq[:, 0], top + half * (qq[:, 1] + 1.0),
                          0.5 * (qq[:, 2] + 1.0))

    J = map_jacobian(mapping, q)
    det = regular_determinant(J, "rim block map Jacobian")
    jinv = np.linalg.inv(J)                                  # [n, a, j] = dq_a / dX_j
    n2 = pts[0] * pts[1]
    xi2 = q[::pts[2], 0]
    s2 = top + half * (q[::pts[2], 1] + 1.0)
    zeta = 0.5 * (q[:pts[2], 2] + 1.0)
    assert len(xi2) == n2
    # parameters (xi, s, zeta) -> the map's (q_1, q_2, q_3): ds/dq_2 = half, dzeta/dq_3 = 1/2
    dpar = _plate_gradients(model, xi2, s2, pts[2], zeta) * np.array([1.0, half, 0.5])
    g_plate = np.einsum("mnia,naj->mnij", dpar, jinv, optimize=True)
    strains = [voigt_strains(g_plate)]
    if model.block_orders is not None:
        _, grads = legendre_products(q, model.block_orders, clamp=(None, "both", None))
        grad_x = np.einsum("bna,naj->bnj", grads, jinv)
        strains.append(voigt_strains(cartesian_gradients(grad_x)))
    E = body.material.youngs_modulus_mpa * rim_modulus_factor(rim, top + half * (q[:, 1] + 1))
    return energy_matrix(np.concatenate(strains), w * det, E,
                         body.material.poisson_ratio)


def has_block(rim: RimSegment) -> bool:
    """Whether the rim has a block below its fillet deep enough for the solid: depth
    ``depth_mm - fillet_mm >= BLOCK_MIN_DEPTH * depth_mm`` (:data:`BLOCK_MIN_DEPTH`;
    thinner, the plate continues through it)."""
    return rim.depth_mm - rim.fillet_mm >= BLOCK_MIN_DEPTH * rim.depth_mm


def check_block(rim, block_orders) -> tuple | None:
    """The block's options checked (:func:`~.shell.build_shell` with ``rim_block``): a
    rim segment (with or without a block below its fillet: :func:`has_block`),
    ``block_orders`` three degrees in 0..16 or None (the plate's fields alone in the
    solid); returns the degrees as ints."""
    if not isinstance(rim, RimSegment):
        raise InputRangeError("rim", rim, "a RimSegment (the block lies below its fillet)")
    if block_orders is None:
        return None
    if (not isinstance(block_orders, (tuple, list)) or len(block_orders) != 3
            or any(isinstance(p, bool) or int(p) != p or not 0 <= p <= 16
                   for p in block_orders)):
        raise InputRangeError("block_orders", block_orders, "three integers in [0, 16] or None")
    return tuple(int(p) for p in block_orders)


def enrichment_count(block_orders) -> int:
    """Ritz functions of the enrichment: 3 prod(degree + 1), 0 for None."""
    return 0 if block_orders is None else 3 * int(np.prod([p + 1 for p in block_orders]))
