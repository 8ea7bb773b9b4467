"""3D finite elements of one tooth with its rim segment: the independent truth of the shell.

The solid is a structured mapped mesh (no CAD): a tensor grid of nodes in
(xi, eta, zeta) is mapped into the tooth (``zeta`` in [0, 1] runs straight from the
coast flank point ``P_c(xi, eta)`` to the drive flank point ``P_d(xi, eta)``, so every
surface node lies exactly on the real flanks of :mod:`.tooth`), and continued below the
root line by the rim segment of :mod:`.rim` (the shell's too) of depth ``rim_depth_mm``:

- a root fillet approximation over the height ``fillet_mm`` below the root line, where
  the sides widen on a quarter ellipse from the tooth to the slot middles (the
  rim segment spans one pitch, half a slot on each side);
- the rim block below it, whose bottom face is clamped (all displacements zero); its
  sides, the toe / heel ends, the flanks and the top land are free.

With the tooth's real root (:mod:`.root_fillet`, where its cutter is known) the sides
below the root line follow the cutter's fillets instead, the slot bottoms beside them
lie on the root cone and the rim block below spans one pitch (``root``).

Each hexahedral cell is split into six tetrahedra (``MeshTet.init_tensor``); linear
elasticity is solved with quadratic tetrahedra (P2) in scikit-fem with one sparse LU
factorization per tooth, then one back-substitution per load point. A unit load along
the inward flank normal at a flank node is a consistent nodal force for P2 (a vertex
basis function is 1 there, the others 0), so G_ij = d_i . u(node_i; load j) is
Maxwell-Betti symmetric to rounding. The point load makes the displacement at the
loaded node itself mesh dependent (the local indentation, which the half-space part of
the LTCA models); the shell is compared with it under distributed loads
(:mod:`.compliance`).

Needs the optional ``fe`` extra (``pip install 'gearcontact[fe]'``: scikit-fem).

References
----------
T. Gustafsson, G. D. McBain, "scikit-fem: A Python package for finite element
assembly", *J. Open Source Software* 5(52), 2020, 2369.
O. C. Zienkiewicz, R. L. Taylor, *The Finite Element Method*, vol. 1, 6th ed., 2005
(isoparametric solids, consistent nodal loads).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError
from .rim import rim_points, rim_segment
from .tooth import LoadPoints

__all__ = ["FeTooth", "build_fe", "fe_node_count"]


@dataclass(frozen=True, eq=False)
class FeTooth:
    """A factorized P2 finite-element model of one tooth (:func:`build_fe`).

    Attributes
    ----------
    body : ToothGeometry or RectangularPlate
    xi_levels, eta_levels : ndarray
        Tooth coordinates of the flank node lines (eta only on the tooth, not the rim).
    n_nodes, n_dofs : int
        Nodes (vertices + edge mid-nodes) and degrees of freedom of the P2 mesh.
    build_s : float
        Wall time of meshing, assembly and factorization, s.
    """

    body: object
    xi_levels: np.ndarray
    eta_levels: np.ndarray
    n_nodes: int
    n_dofs: int
    build_s: float
    _vertex: object      # (i_xi, j_vertical, k_zeta) -> vertex index
    _rim_levels: int
    _n_zeta: int
    _k_coast: int
    _nodal_dofs: np.ndarray
    _free: np.ndarray
    _lu: object
    _points: np.ndarray

    def node_points(self, side: str, xi, eta) -> tuple[LoadPoints, np.ndarray]:
        """Snap (xi, eta) to the nearest flank node of ``side``: the load points there
        (inward flank normal) and the vertex indices."""
        xi, eta = (np.atleast_1d(np.asarray(a, float)) for a in (xi, eta))
        i = np.abs(xi[:, None] - self.xi_levels[None, :]).argmin(axis=1)
        j = np.abs(eta[:, None] - self.eta_levels[None, :]).argmin(axis=1)
        k = self._k_coast + (self._n_zeta if side == "drive" else 0)
        pts = self.body.points_at(side, self.xi_levels[i], self.eta_levels[j])
        return pts, self._vertex[i, j + self._rim_levels, k]

    def compliance(self, points: LoadPoints, vertices: np.ndarray) -> np.ndarray:
        """G (n, n), mm/N: deflection along ``points.direction[i]`` at vertex i for a
        unit load along ``points.direction[j]`` at vertex j (:meth:`node_points`)."""
        F = np.zeros((self.n_dofs, len(vertices)))
        for col, (v, d) in enumerate(zip(vertices, points.direction)):
            F[self._nodal_dofs[:, v], col] = d
        U = np.zeros_like(F)
        U[self._free] = self._lu.solve(np.ascontiguousarray(F[self._free]))
        G = F.T @ U
        return 0.5 * (G + G.T)

    def vertex_positions_mm(self, vertices: np.ndarray) -> np.ndarray:
        """Body-frame positions of mesh vertices (n, 3), mm."""
        return self._points[:, vertices].T


def fe_node_count(n_xi: int, n_eta: int, n_zeta: int, n_rim: int, *, root: bool = False,
                  n_fillet: int = 3, n_slot: int = 2) -> int:
    """P2 nodes of :func:`build_fe`'s mesh (vertices + edge mid-nodes: on the split
    tensor grid, the points of the grid of half the spacing). Without ``root``:
    ``(2 n_xi + 1)(2 (n_eta + n_rim) + 1)(2 n_zeta + 1)``; with the real root the rim
    block spans the slot bottoms too (``n_zeta + 2 n_slot`` cells across) and the
    fillet zone adds ``n_fillet`` layers beside the tooth's: ``(2 n_xi + 1) [(2 n_rim
    + 1)(2 (n_zeta + 2 n_slot) + 1) + 2 (n_fillet + n_eta)(2 n_zeta + 1)]``."""
    if not root:
        return (2 * n_xi + 1) * (2 * (n_eta + n_rim) + 1) * (2 * n_zeta + 1)
    return (2 * n_xi + 1) * ((2 * n_rim + 1) * (2 * (n_zeta + 2 * n_slot) + 1)
                             + 2 * (n_fillet + n_eta) * (2 * n_zeta + 1))


def _signed_volumes(mesh) -> np.ndarray:
    """Six times the signed volume of every tetrahedron, mm^3."""
    p = mesh.p[:, mesh.t]
    return np.einsum("in,in->n", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0], axis=0),
                     p[:, 3] - p[:, 0])


def build_fe(body, *, n_xi: int = 12, n_eta: int = 6, n_zeta: int = 3, n_rim: int = 4,
             rim_depth_mm: float | None = None, fillet_mm: float | None = None,
             root=None, n_fillet: int = 3, n_slot: int = 2) -> FeTooth:
    """Mesh, assemble and factor the P2 elasticity model of a tooth (module docstring).

    Parameters
    ----------
    body : ToothGeometry or RectangularPlate
        The tooth (with ``axis`` and ``teeth`` for the rim) or, with ``n_rim = 0``, any
        plate body clamped at eta = -1.
    n_xi, n_eta, n_zeta : int
        Cells along the face, the height and the thickness (>= 1 each, n_xi, n_eta
        >= 2).
    n_rim : int
        Cell layers of the fillet + rim segment (0: clamp the tooth at its root line).
    rim_depth_mm : float or None
        Depth of the rim segment below the root line, mm (default: the tooth height).
    fillet_mm : float or None
        Height of the fillet widening, mm (default: the larger of the flank's start
        above the root cone, ``u_lo``, and 15 % of the tooth height; both defaults
        from :func:`.rim.rim_segment`).
    root : FilletRoot or None
        The real root of the tooth (:mod:`.root_fillet`): the sides follow the cutter's
        fillets over ``n_fillet`` layers down to the root cone, the slot bottoms
        beside them span ``n_slot`` cells each, and the rim block below has ``n_rim``
        layers down to ``root.depth_mm`` (``rim_depth_mm`` and ``fillet_mm`` unused).
        None: the quarter-ellipse fillet of :mod:`.rim`.
    n_fillet, n_slot : int
        Cell layers of the real fillet zone and cells across each slot bottom (>= 1;
        with ``root`` only).

    Raises
    ------
    InputRangeError
        For mesh sizes out of range, a non-positive depth, or a mesh with inverted
        cells (``FE mesh``).
    """
    try:
        import skfem
        from scipy.sparse.linalg import splu
        from skfem.models.elasticity import lame_parameters, linear_elasticity
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError("the FE model needs scikit-fem: pip install 'gearcontact[fe]'") from exc
    for name, n, lo in (("n_xi", n_xi, 2), ("n_eta", n_eta, 2), ("n_zeta", n_zeta, 1),
                        ("n_rim", n_rim, 0 if root is None else 1), ("n_fillet", n_fillet, 1),
                        ("n_slot", n_slot, 1)):
        if isinstance(n, bool) or int(n) != n or not lo <= n <= 200:
            raise InputRangeError(name, n, f"an integer in [{lo}, 200]")
    t0 = time.perf_counter()
    xi_l = np.linspace(-1.0, 1.0, n_xi + 1)
    eta_l = np.linspace(-1.0, 1.0, n_eta + 1)
    zeta_l = np.linspace(0.0, 1.0, n_zeta + 1)
    merged = np.empty((0,), int), np.empty((3, 0), int)
    if root is None:
        idx, pts, n_below, k0 = _rim_mesh(skfem, body, xi_l, eta_l, zeta_l, n_rim,
                                          rim_depth_mm, fillet_mm)
    else:
        idx, pts, n_below, k0 = _fillet_mesh(skfem, body, root, xi_l, eta_l, zeta_l, n_rim,
                                             n_fillet, n_slot)
        idx, pts, merged = _merge_coincident(skfem, idx, pts)
    I, J, K = (np.rint(idx.p[a]).astype(int) for a in range(3))
    mesh = skfem.MeshTet(pts, idx.t)
    # inverted cells: the map must keep (or flip) the orientation of every index cell
    flips = np.sign(_signed_volumes(mesh)) * np.sign(_signed_volumes(idx))
    if not (np.all(flips > 0) or np.all(flips < 0)):
        raise InputRangeError("FE mesh", f"{int(np.sum(flips != np.sign(np.median(flips))))} "
                              "inverted cells", "a mesh with positive cell volumes")
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementTetP2()), intorder=2)
    mat = body.material
    A = skfem.asm(linear_elasticity(*lame_parameters(mat.youngs_modulus_mpa, mat.poisson_ratio)),
                  basis)
    bottom = idx.facets_satisfying(lambda x: x[1] < 1e-6)   # all three vertices on J = 0
    fixed = basis.get_dofs(facets=bottom).all()
    free = np.setdiff1d(np.arange(basis.N), fixed)
    lu = splu(A[free][:, free].tocsc())
    vertex = np.full((n_xi + 1, int(J.max()) + 1, int(K.max()) + 1), -1, dtype=int)
    vertex[I, J, K] = np.arange(idx.p.shape[1])
    vertex[tuple(merged[1])] = merged[0]
    return FeTooth(body=body, xi_levels=xi_l, eta_levels=eta_l,
                   n_nodes=int(basis.N // 3), n_dofs=int(basis.N),
                   build_s=time.perf_counter() - t0, _vertex=vertex, _rim_levels=n_below,
                   _n_zeta=n_zeta, _k_coast=k0, _nodal_dofs=basis.nodal_dofs, _free=free,
                   _lu=lu, _points=mesh.p)


def _tooth_points(body, xi_l, eta_l, zeta_l, I, j, K) -> np.ndarray:
    """Positions (3, n) of the tooth's nodes at index (I, eta level j, zeta column K)."""
    pc, pd = body.side_points(xi_l[I], eta_l[j])
    return (pc + zeta_l[K, None] * (pd - pc)).T


def _rim_mesh(skfem, body, xi_l, eta_l, zeta_l, n_rim, rim_depth_mm, fillet_mm):
    """Index mesh and node positions of the tooth on the quarter-ellipse fillet and rim
    of :mod:`.rim`: ``(index mesh, points (3, n), levels below the root line, coast
    column)``."""
    n_xi, n_eta, n_zeta = len(xi_l) - 1, len(eta_l) - 1, len(zeta_l) - 1
    idx = skfem.MeshTet.init_tensor(np.arange(n_xi + 1.0), np.arange(n_rim + n_eta + 1.0),
                                    np.arange(n_zeta + 1.0))
    I, J, K = (np.rint(idx.p[a]).astype(int) for a in range(3))
    pts = np.empty((3, idx.p.shape[1]))
    tooth = J >= n_rim
    pts[:, tooth] = _tooth_points(body, xi_l, eta_l, zeta_l, I[tooth], J[tooth] - n_rim,
                                  K[tooth])
    if n_rim:
        if not hasattr(body, "teeth"):
            raise InputRangeError("n_rim", n_rim, "0 for a body without a member axis")
        rim = rim_segment(body, depth_mm=rim_depth_mm, fillet_mm=fillet_mm)
        # depth of the rim levels: graded towards the root (quadratic), the root level at 0
        s_lev = rim.depth_mm * ((n_rim - np.arange(n_rim + 1)) / n_rim) ** 2
        r = ~tooth
        pts[:, r] = rim_points(body, rim, xi_l[I[r]], s_lev[J[r]], zeta_l[K[r]]).T
    return idx, pts, n_rim, 0


def _merge_coincident(skfem, idx, pts):
    """Merge the vertices of the mapped mesh that coincide (the slot bottom's points of
    a slot closing in a V, :meth:`.root_fillet.FilletRoot.root_row`) and drop the
    tetrahedra that lose a vertex: ``(index mesh, points, (vertex, index points (3,
    n)) of the merged index points)``; the mesh unchanged where no two vertices
    coincide."""
    uniq, first, inv = np.unique(pts.T, axis=0, return_index=True, return_inverse=True)
    inv = inv.ravel()
    if len(uniq) == pts.shape[1]:
        return idx, pts, (np.empty((0,), int), np.empty((3, 0), int))
    t = inv[idx.t]
    # the tetrahedra that lose a vertex (the cells beside a closed section's slot
    # bottom, between it and an open one, become wedges)
    t = np.ascontiguousarray(t[:, np.all(np.diff(np.sort(t, axis=0), axis=0) > 0, axis=0)])
    # the merged vertex keeps the index point of its first occurrence; the others alias it
    alias = np.setdiff1d(np.arange(pts.shape[1]), first)
    rep = np.rint(idx.p[:, alias]).astype(int)
    return (skfem.MeshTet(idx.p[:, first], t), pts[:, first], (inv[alias], rep))


def _fillet_mesh(skfem, body, root, xi_l, eta_l, zeta_l, n_block, n_fillet, n_slot):
    """Index mesh and node positions of the tooth on its real root (:mod:`.root_fillet`):
    a tensor index grid across the slot bottoms, the tooth and the fillet zone, without
    the cells beside the tooth above the root row (``root`` of :func:`build_fe`); as
    :func:`_rim_mesh`."""
    n_xi, n_eta, n_zeta = len(xi_l) - 1, len(eta_l) - 1, len(zeta_l) - 1
    n_k = n_zeta + 2 * n_slot
    full = skfem.MeshTet.init_tensor(np.arange(n_xi + 1.0),
                                     np.arange(n_block + n_fillet + n_eta + 1.0),
                                     np.arange(n_k + 1.0))
    c = full.p[:, full.t].mean(axis=1)          # index centroids of the tetrahedra
    beside = (c[2] < n_slot) | (c[2] > n_slot + n_zeta)
    keep = (c[1] < n_block) | ~beside
    closed = root.closed(xi_l)
    if np.any(closed):
        # a slot bottom without width (a V, root_fillet.FilletRoot.root_row): the rim
        # cells beside the tooth between two such sections collapse to faces
        i = np.floor(c[0]).astype(int)
        keep &= ~(beside & closed[i] & closed[i + 1])
    used, t = np.unique(full.t[:, keep], return_inverse=True)
    idx = skfem.MeshTet(full.p[:, used], t.reshape(4, -1))
    I, J, K = (np.rint(idx.p[a]).astype(int) for a in range(3))
    pts = np.empty((3, idx.p.shape[1]))
    j_root = n_block + n_fillet                 # the tooth's root line
    tooth = J >= j_root
    pts[:, tooth] = _tooth_points(body, xi_l, eta_l, zeta_l, I[tooth], J[tooth] - j_root,
                                  K[tooth] - n_slot)
    # levels below the root line: the rim block graded towards the root row
    # (quadratic, as the ellipse rim), the fillet zone even in arc length
    s_frac = ((n_block - np.arange(n_block + 1)) / n_block) ** 2
    q = 1.0 - np.arange(n_fillet) / n_fillet
    below = root.mesh_points(xi_l, q, s_frac, zeta_l, n_slot)
    r = ~tooth
    pts[:, r] = below[I[r], J[r], K[r]].T
    if not np.all(np.isfinite(pts)):
        raise InputRangeError("FE mesh", "nodes outside the root", "finite node positions")
    return idx, pts, j_root, n_slot

