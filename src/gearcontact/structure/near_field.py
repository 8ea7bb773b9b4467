"""The half-space's near field of a flank pressure patch, and the solid tooth's far field.

The LTCA adds a tooth's bending compliance to the half-space compliance of its contact
(:mod:`gearcontact.halfspace`), which already holds the local indentation under the load.
A 3D model of the tooth (the Ritz solid of :mod:`.tooth_solid`, the FE of :mod:`.fe`)
holds that indentation too; what the structure layer may add is only the **far field**,
the loaded flank's deflection minus the half-space's own (docs/bending.md sec. 13,
session 26). Here for a uniform pressure of unit total force on a flank patch
(:class:`FlankPatch`, bounded by tooth coordinates), all compliances being the work per
unit load squared, ``C = f^T K^-1 f`` (the pressure-weighted mean deflection along the
inward flank normal over the patch, mm/N):

- the half-space's near field of the patch, as the flat rectangle of its arc length along
  the face and its area over that length (:func:`patch_rectangle`), on a half-space of
  the tooth's material: at the surface (:func:`halfspace_surface`, Love's closed form) and
  at a depth below each patch point (:func:`halfspace_below`, Boussinesq's point load
  integrated over the patch);
- the Ritz solid's patch compliance measured at the flank or at the mid-surface point
  below each patch point (:func:`solid_patch_compliance`);
- the far field of the solid by the combined surface-integral / FE split of Vijayakar:
  the displacement at a surface point is the solid's at a matching point below it plus the
  half-space's surface-to-matching-point difference, so the far field is the solid's
  mid-surface value minus the half-space's at the same depth (:func:`solid_far_field`);
- the same split as a point operator between flank points (:func:`solid_far_field_matrix`),
  what the LTCA adds to its half-space with
  ``ltca.tooth_bending.tooth_bending(near_field=True)`` (opt-in; as a signed factor,
  the far field being negative near the root, docs/bending.md sec. 13, session 27);
- the FE's patch compliance under the consistent load of the pressure
  (:func:`fe_patch_compliance`), the truth of the far field after the surface near field
  is taken off.

References
----------
S. M. Vijayakar, "A combined surface integral and finite element solution for a
three-dimensional contact problem", *Int. J. Numer. Meth. Engng* 31(3), 1991, 525-545.
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, eqs. 3.20 (the
Boussinesq point load) and 3.25 (Love's rectangle).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

from ..halfspace.influence import love_rectangle_displacement
from ..validation import InputRangeError
from .tooth import LoadPoints
from .tooth_solid import solid_load_vectors

__all__ = ["FlankPatch", "patch_points", "patch_rectangle", "halfspace_surface",
           "halfspace_below", "solid_patch_compliance", "solid_far_field",
           "solid_far_field_matrix", "fe_patch_compliance", "PATCH_POINTS"]

#: Gauss points (along the face, over the height) of a patch's quadrature: per unit of
#: the patch's (xi, eta) extent along the face, and over its height.
PATCH_POINTS = (48, 12)


@dataclass(frozen=True)
class FlankPatch:
    """A patch of the flank ``side`` over ``xi`` x ``eta`` (tooth coordinates, each a
    (low, high) pair in [-1, 1]) carrying a uniform pressure of unit total force."""

    side: str
    xi: tuple[float, float]
    eta: tuple[float, float]

    def __post_init__(self):
        if self.side not in ("drive", "coast"):
            raise InputRangeError("side", self.side, "'drive' or 'coast'")
        for name in ("xi", "eta"):
            lo, hi = getattr(self, name)
            if not -1.0 <= lo < hi <= 1.0:
                raise InputRangeError(f"patch {name}", (lo, hi), "-1 <= low < high <= 1")


def _gauss(lo: float, hi: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = legendre.leggauss(int(n))
    return 0.5 * (lo + hi) + 0.5 * (hi - lo) * x, 0.5 * (hi - lo) * w


def _counts(patch: FlankPatch, points) -> tuple[int, int]:
    n_xi, n_eta = PATCH_POINTS if points is None else points
    return max(4, int(np.ceil(n_xi * (patch.xi[1] - patch.xi[0]) / 2.0))), int(n_eta)


def patch_points(body, patch: FlankPatch, *, points=None) -> tuple[LoadPoints, np.ndarray]:
    """Gauss points of the patch on its flank (:meth:`~.tooth.ToothGeometry.points_at`)
    and their area weights (n,), mm^2 (``|r_xi x r_eta| dxi deta``; they sum to the
    patch's area)."""
    n_xi, n_eta = _counts(patch, points)
    (x, wx), (e, we) = _gauss(*patch.xi, n_xi), _gauss(*patch.eta, n_eta)
    X, E = (a.ravel() for a in np.meshgrid(x, e, indexing="ij"))
    _, r_xi, r_eta, _ = patch_flank(body, patch.side, X, E)
    area = np.linalg.norm(np.cross(r_xi, r_eta), axis=1) * np.outer(wx, we).ravel()
    return body.points_at(patch.side, X, E), area


def patch_flank(body, side: str, xi, eta):
    """``(r, r_xi, r_eta, n)`` of the flank ``side`` at (xi, eta): the tooth's
    (:meth:`~.tooth.ToothGeometry.flank_arrays`) or, on a body without flank arrays (a
    :class:`~.tooth.RectangularPlate`), by central differences of its face points."""
    if hasattr(body, "flank_arrays"):
        return body.flank_arrays(side, xi, eta)
    h = 1e-6
    xi, eta = np.asarray(xi, float), np.asarray(eta, float)
    pos = [body.points_at(side, xi + a, eta + b).position_mm
           for a, b in ((0, 0), (h, 0), (-h, 0), (0, h), (0, -h))]
    pts = body.points_at(side, xi, eta)
    return pos[0], (pos[1] - pos[2]) / (2 * h), (pos[3] - pos[4]) / (2 * h), -pts.direction


def patch_rectangle(body, patch: FlankPatch, *, points=None) -> tuple[float, float]:
    """(length, width), mm: the patch's arc length along the face at its middle height and
    its area over that length (the flat rectangle of the half-space's near field)."""
    n_xi, _ = _counts(patch, points)
    x, wx = _gauss(*patch.xi, n_xi)
    _, r_xi, _, _ = patch_flank(body, patch.side, x, np.full_like(x, np.mean(patch.eta)))
    length = float(np.linalg.norm(r_xi, axis=1) @ wx)
    return length, float(patch_points(body, patch, points=points)[1].sum()) / length


def halfspace_surface(length_mm: float, width_mm: float, *, youngs_modulus_mpa: float,
                      poisson_ratio: float, points: int = 64) -> float:
    """Mean surface displacement over a ``length`` x ``width`` rectangle under a uniform
    pressure of unit total force on it, one half-space of (E, nu): mm/N (Love's closed
    form at ``points`` x ``points`` Gauss receivers; its gradient is only logarithmically
    singular at the edges)."""
    e_star = youngs_modulus_mpa / (1.0 - poisson_ratio ** 2)
    (x, wx), (y, wy) = _gauss(-0.5, 0.5, points), _gauss(-0.5, 0.5, points)
    u = love_rectangle_displacement(length_mm * x[:, None], width_mm * y[None, :],
                                    0.5 * length_mm, 0.5 * width_mm, e_star_mpa=e_star,
                                    pressure_mpa=1.0 / (length_mm * width_mm))
    return float(wx @ u @ wy)


def halfspace_below(length_mm: float, width_mm: float, at_mm: np.ndarray,
                    weights: np.ndarray, *, youngs_modulus_mpa: float, poisson_ratio: float,
                    points=(96, 24)) -> float:
    """Weighted mean normal displacement at the points ``at_mm`` (n, 3) = (s, h, depth),
    mm, in the frame of the ``length`` x ``width`` rectangle (centre at 0, depth > 0
    into the body), under a uniform pressure of unit total force on the rectangle:
    Boussinesq's ``u_z = P / (4 pi G) [2 (1 - nu) / rho + z^2 / rho^3]`` (Johnson 1985,
    eq. 3.20) over ``points`` Gauss points of the source; ``weights`` (n,) sum to 1."""
    at = np.asarray(at_mm, float)
    if np.any(at[:, 2] <= 0.0):
        raise InputRangeError("depth below the patch (mm)", float(at[:, 2].min()), "> 0")
    nu = poisson_ratio
    g = youngs_modulus_mpa / (2.0 * (1.0 + nu))
    (x, wx), (y, wy) = _gauss(-0.5, 0.5, points[0]), _gauss(-0.5, 0.5, points[1])
    sx, sy = (length_mm * x)[:, None], (width_mm * y)[None, :]
    w_src = np.outer(wx, wy)                         # unit total force
    out = 0.0
    for (s, h, z), w in zip(at, weights):
        rho = np.sqrt((sx - s) ** 2 + (sy - h) ** 2 + z * z)
        out += w * float(np.sum(w_src * (2.0 * (1.0 - nu) / rho + z * z / rho ** 3)))
    return out / (4.0 * np.pi * g)


def _patch_vectors(model, patch: FlankPatch, *, points=None):
    """The patch's load vector f (m,), its mid-surface measure g (m,; None on a plate),
    its Gauss points and their weights (summing to 1)."""
    pts, area = patch_points(model.body, patch, points=points)
    w = area / area.sum()
    f = w @ model.load_vectors(pts)
    g = None
    if model.solid_degrees is not None:
        g = w @ solid_load_vectors(model, pts, across=np.zeros(len(pts)))
    return f, g, pts, w


def solid_patch_compliance(model, patch: FlankPatch, *, at: str = "mid",
                           points=None) -> float:
    """Patch compliance (mm/N) of a :class:`~.shell.ShellModel`: the pressure's work on the
    displacement along the inward flank normal taken at the flank (``at="flank"``,
    ``f^T K^-1 f``) or, on a solid tooth, at the mid-surface point below each patch point
    (``at="mid"``, the matching surface of :func:`solid_far_field`)."""
    if at not in ("flank", "mid"):
        raise InputRangeError("at", at, "'flank' or 'mid'")
    if at == "mid" and model.solid_degrees is None:
        raise InputRangeError("at", at, "'flank' (the model is no solid tooth)")
    f, g, _, _ = _patch_vectors(model, patch, points=points)
    return _work(model, f, g if at == "mid" else f)


def _work(model, f: np.ndarray, g: np.ndarray) -> float:
    """``g^T K^-1 f`` (mm/N) through the model's ``L^-T``."""
    L = model.inverse_cholesky_t
    return float((g @ L) @ (f @ L))


def _match_offsets(body, patch: FlankPatch, pts: LoadPoints, length: float,
                   width: float) -> np.ndarray:
    """(s, h, depth) (n, 3), mm, of the mid-surface point below each patch point in the
    patch's flat frame (its rectangle ``length`` x ``width``, :func:`patch_rectangle`; s
    along the face, h over the height)."""
    xc, ec = np.mean(patch.xi), np.mean(patch.eta)
    _, r_xi, r_eta, _ = patch_flank(body, patch.side, np.array([xc]), np.array([ec]))
    e_s = r_xi[0] / np.linalg.norm(r_xi[0])
    e_h = r_eta[0] - (r_eta[0] @ e_s) * e_s          # over the height, in the tangent plane
    e_h /= np.linalg.norm(e_h)
    delta = body.mid_surface(pts.xi, pts.eta).position_mm - pts.position_mm
    s = length * (pts.xi - xc) / (patch.xi[1] - patch.xi[0]) + delta @ e_s
    h = width * (pts.eta - ec) / (patch.eta[1] - patch.eta[0]) + delta @ e_h
    depth = np.einsum("ij,ij->i", delta, pts.direction)
    return np.stack([s, h, depth], axis=1)


def solid_far_field(model, patch: FlankPatch, *, points=None) -> dict:
    """The solid tooth's far field under the patch (module docstring; docs/bending.md
    sec. 13, session 26), mm/N: ``far`` = the solid's mid-surface patch compliance
    ``solid_mid`` minus the half-space's at the same points ``halfspace_mid``; also the
    solid's flank value ``solid_flank``, the half-space's surface value
    ``halfspace_surface`` (the part the LTCA supplies) and the rectangle (mm)."""
    body = model.body
    mat = body.material
    E, nu = mat.youngs_modulus_mpa, mat.poisson_ratio
    length, width = patch_rectangle(body, patch, points=points)
    if model.solid_degrees is None:
        raise InputRangeError("model", "a plate", "a solid tooth (build_shell solid_tooth)")
    f, g, pts, w = _patch_vectors(model, patch, points=points)
    below = halfspace_below(length, width, _match_offsets(body, patch, pts, length, width), w,
                            youngs_modulus_mpa=E, poisson_ratio=nu)
    mid = _work(model, f, g)
    return {"far": mid - below, "solid_mid": mid, "halfspace_mid": below,
            "solid_flank": _work(model, f, f),
            "halfspace_surface": halfspace_surface(length, width, youngs_modulus_mpa=E,
                                                   poisson_ratio=nu),
            "length_mm": length, "width_mm": width}


def solid_far_field_matrix(model, points: LoadPoints) -> np.ndarray:
    """The solid tooth's far field between flank points (n, n), mm/N: Vijayakar's split
    of :func:`solid_far_field` for unit point loads, symmetrized,
    ``G = (A + A^T) / 2 - (B + B^T) / 2`` with ``A_ij`` the solid's displacement along
    ``d_i`` at the mid-surface point below point i under a unit load along ``d_j`` at
    point j, and ``B_ij`` Boussinesq's under the same load on the half-space tangent at
    point i, at that mid-surface point's depth ``z_i`` and its distance in the tangent
    plane from point j (Johnson 1985, eq. 3.20; the tooth's material). Not positive
    semi-definite in general: near the root the far field is negative."""
    if model.solid_degrees is None:
        raise InputRangeError("model", "a plate", "a solid tooth (build_shell solid_tooth)")
    L = model.inverse_cholesky_t
    flank = model.load_vectors(points) @ L
    match = solid_load_vectors(model, points, across=np.zeros(len(points))) @ L
    A = match @ flank.T
    mat = model.body.material
    nu = mat.poisson_ratio
    g = mat.youngs_modulus_mpa / (2.0 * (1.0 + nu))
    d = np.asarray(points.direction, float)
    mid = model.body.mid_surface(points.xi, points.eta).position_mm
    z = np.einsum("ij,ij->i", mid - points.position_mm, d)
    if np.any(z <= 0.0):
        raise InputRangeError("mid-surface depth below a point (mm)", float(z.min()), "> 0")
    rel = mid[:, None, :] - points.position_mm[None, :, :]          # (i, j, 3)
    lateral = rel - np.einsum("ijk,ik->ij", rel, d)[:, :, None] * d[:, None, :]
    rho = np.sqrt(np.einsum("ijk,ijk->ij", lateral, lateral) + (z * z)[:, None])
    B = (2.0 * (1.0 - nu) / rho + (z * z)[:, None] / rho ** 3) / (4.0 * np.pi * g)
    return 0.5 * (A + A.T) - 0.5 * (B + B.T)


def fe_patch_compliance(fe, patch: FlankPatch) -> float:
    """Patch compliance (mm/N) of a factorized FE tooth (:class:`~.fe.FeTooth`): the
    consistent P2 load of the pressure on the flank facets inside the patch (whose bounds
    must lie on the mesh's node lines), ``f^T K^-1 f``.

    The P2 basis is rebuilt on the FE's own mesh (vertices and tetrahedra: the same
    degrees of freedom) and solved with its factorization."""
    import skfem

    on_lines = [np.min(np.abs(levels - b)) < 1e-9 for levels, bounds in
                ((fe.xi_levels, patch.xi), (fe.eta_levels, patch.eta)) for b in bounds]
    if not all(on_lines) or fe.flank_eta is not None:
        raise InputRangeError("patch", (patch.xi, patch.eta),
                              "bounds on the FE mesh's node lines (no kinked rows)")
    xs = fe.xi_levels[(fe.xi_levels >= patch.xi[0] - 1e-9) & (fe.xi_levels <= patch.xi[1] + 1e-9)]
    es = fe.eta_levels[(fe.eta_levels >= patch.eta[0] - 1e-9)
                       & (fe.eta_levels <= patch.eta[1] + 1e-9)]
    X, E = (a.ravel() for a in np.meshgrid(xs, es, indexing="ij"))
    _, verts = fe.node_points(patch.side, X, E)
    mesh = skfem.MeshTet(fe.vertices_mm(), fe.tetrahedra)
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementTetP2()), intorder=2)
    if basis.N != fe.n_dofs or not np.array_equal(basis.nodal_dofs, fe.nodal_dofs):
        raise RuntimeError("the rebuilt P2 basis does not number the FE's dofs alike")
    bf = mesh.boundary_facets()
    inside = np.all(np.isin(mesh.facets[:, bf], verts), axis=0)
    fb = skfem.FacetBasis(mesh, basis.elem, facets=bf[inside], intorder=4)
    area = skfem.Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(fb)

    @skfem.LinearForm
    def pressure(v, w):
        return -(v[0] * w.n[0] + v[1] * w.n[1] + v[2] * w.n[2]) / area

    f = pressure.assemble(fb)
    return float(f @ fe.displacement_mm(f))
