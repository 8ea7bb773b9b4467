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

On a kinked flank (Toprem / Flankrem, :class:`~gearcontact.geometry.kinked.KinkedFlank`)
a node row lies on each kink line, so that no cell straddles the ridge
(:func:`flank_rows`; docs/bending.md sec. 10, "Kinked flanks").

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

from ..geometry.kinked import KinkedFlank, kinked_flank
from ..threads import one_blas_thread
from ..validation import InputRangeError
from .rim import rim_points, rim_segment
from .tooth import LoadPoints

__all__ = ["FeTooth", "build_fe", "fe_node_count", "flank_rows"]

#: Smallest flank cell beside a kink row, in nominal rows (2 / n_eta in eta): a kink
#: nearer the box's root or tip line is meshed this far inside it (:func:`flank_rows`).
KINK_CELL = 0.25


@dataclass(frozen=True, eq=False)
class FeTooth:
    """A factorized P2 finite-element model of one tooth (:func:`build_fe`).

    Attributes
    ----------
    body : ToothGeometry or RectangularPlate
    xi_levels, eta_levels : ndarray
        Tooth coordinates of the flank node lines (eta only on the tooth, not the rim);
        ``eta_levels`` the nominal rows, which a kinked flank moves (``flank_eta``).
    flank_eta : dict or None
        ``side -> (n_xi + 1, n_eta + 1)``: eta of each flank node (column, row) where a
        flank has kinks (:func:`flank_rows`); None: every row at ``eta_levels``.
    kink_rows : dict
        ``side -> tuple`` of the rows on that flank's kinks (empty without kinks).
    tetrahedra : ndarray (4, n_tet)
        Vertex indices of the tetrahedra (:meth:`vertex_positions_mm`).
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
    flank_eta: dict | None
    kink_rows: dict
    tetrahedra: np.ndarray
    _vertex: object      # (i_xi, j_vertical, k_zeta) -> vertex index
    _rim_levels: int
    _n_zeta: int
    _k_coast: int
    _nodal_dofs: np.ndarray
    _free: np.ndarray
    _lu: object
    _points: np.ndarray

    def node_points(self, side: str, xi, eta) -> tuple[LoadPoints, np.ndarray]:
        """Snap (xi, eta) to the nearest node line (``xi_levels``, ``eta_levels``) of
        ``side``: the load points at its node (inward flank normal; on a kinked flank
        the node of the moved row, ``flank_eta``, at a kink the normal of the piece
        the flank evaluates there) and the vertex indices."""
        xi, eta = (np.atleast_1d(np.asarray(a, float)) for a in (xi, eta))
        i = np.abs(xi[:, None] - self.xi_levels[None, :]).argmin(axis=1)
        j = np.abs(eta[:, None] - self.eta_levels[None, :]).argmin(axis=1)
        k = self._k_coast + (self._n_zeta if side == "drive" else 0)
        eta_n = self.eta_levels[j] if self.flank_eta is None else self.flank_eta[side][i, j]
        pts = self.body.points_at(side, self.xi_levels[i], eta_n)
        return pts, self._vertex[i, j + self._rim_levels, k]

    def compliance(self, points: LoadPoints, vertices: np.ndarray) -> np.ndarray:
        """G (n, n), mm/N: deflection along ``points.direction[i]`` at vertex i for a
        unit load along ``points.direction[j]`` at vertex j (:meth:`node_points`)."""
        F = np.zeros((self.n_dofs, len(vertices)))
        for col, (v, d) in enumerate(zip(vertices, points.direction)):
            F[self._nodal_dofs[:, v], col] = d
        with one_blas_thread():        # the same bits with any thread count (below)
            G = F.T @ self.displacement_mm(F)
        return 0.5 * (G + G.T)

    def displacement_mm(self, load_n: np.ndarray) -> np.ndarray:
        """Displacements (n_dofs, ...) , mm, of nodal loads ``load_n`` (n_dofs, ...), N,
        on this model's degrees of freedom (the clamped ones stay 0)."""
        u = np.zeros_like(load_n, dtype=float)
        # SuperLU's triangular solves call BLAS: on one thread, so that the result has
        # the same bits with any thread count (threaded: the FE compliance moved by
        # 1e-15 relative between 1 and 2 threads; docs/architecture.md "Determinism")
        with one_blas_thread():
            u[self._free] = self._lu.solve(np.ascontiguousarray(load_n[self._free]))
        return u

    @property
    def nodal_dofs(self) -> np.ndarray:
        """Degrees of freedom (3, n_vertices) of each vertex's x, y, z (P2 numbering)."""
        return self._nodal_dofs

    def vertices_mm(self) -> np.ndarray:
        """Body-frame positions of every mesh vertex (3, n_vertices), mm: with
        ``tetrahedra`` the mesh a P2 basis numbering this model's dofs is built on."""
        return self._points

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
             root=None, n_fillet: int = 3, n_slot: int = 2, on_kinks: bool = True) -> FeTooth:
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
    on_kinks : bool
        A node row on each kink of a kinked flank (:func:`flank_rows`); False: the
        nominal rows, the kink cut across by cells (for comparison, docs/bending.md).

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
    rows, kink_rows = flank_rows(body, xi_l, n_eta)
    if not on_kinks or not any(kink_rows.values()):
        # the nominal rows (without a kink: the mesh as it always was)
        rows, kink_rows = None, {side: () for side in kink_rows}
    if root is None:
        idx, pts, n_below, k0 = _rim_mesh(skfem, body, xi_l, eta_l, zeta_l, n_rim,
                                          rim_depth_mm, fillet_mm, rows)
    else:
        idx, pts, n_below, k0 = _fillet_mesh(skfem, body, root, xi_l, eta_l, zeta_l, n_rim,
                                             n_fillet, n_slot, rows)
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
    with one_blas_thread():        # SuperLU's supernodes call BLAS (displacement_mm)
        lu = splu(A[free][:, free].tocsc())
    vertex = np.full((n_xi + 1, int(J.max()) + 1, int(K.max()) + 1), -1, dtype=int)
    vertex[I, J, K] = np.arange(idx.p.shape[1])
    vertex[tuple(merged[1])] = merged[0]
    return FeTooth(body=body, xi_levels=xi_l, eta_levels=eta_l,
                   n_nodes=int(basis.N // 3), n_dofs=int(basis.N),
                   build_s=time.perf_counter() - t0, flank_eta=rows, kink_rows=kink_rows,
                   tetrahedra=mesh.t,
                   _vertex=vertex, _rim_levels=n_below,
                   _n_zeta=n_zeta, _k_coast=k0, _nodal_dofs=basis.nodal_dofs, _free=free,
                   _lu=lu, _points=mesh.p)


def flank_rows(body, xi_levels, n_eta: int) -> tuple[dict, dict]:
    """The flank node rows of :func:`build_fe`, with a row on each kink of a
    :class:`~gearcontact.geometry.kinked.KinkedFlank`: ``(side -> eta (n_xi + 1, n_eta
    + 1), side -> tuple of kink rows)``.

    Without a kink on the tooth's height box a flank's rows are the nominal ones,
    ``eta_j = -1 + 2 j / n_eta`` in every column. A kink gets the nominal row nearest
    its mean height (not the root or tip row): in each column that row lies on the kink
    ``u_k(v)``, solved at the column (:func:`~gearcontact.geometry.kinked.kinked_flank`
    on the columns, bisection to rounding; the flank's own kink line interpolates
    between its nodes), and the rows of a window of ``m`` rows each side of it are
    spread evenly between the kink and the window's ends (``m = 1``: only the kink's
    row moves), ``m`` grown until every cell is at least ``KINK_CELL / 2`` nominal
    rows. So the cells of each column lie each on one smooth piece (the flank between
    two rows never straddles the kink), and the rows away from the kink stay nominal.
    Where a kink leaves the box (or comes nearer its root or tip line than
    ``KINK_CELL`` rows per cell between them) its row stays that far inside, on the
    piece that holds it there.

    Raises
    ------
    InputRangeError
        ``n_eta`` too small for the kinks of a flank (a row each, between the root and
        tip rows, and cells of ``KINK_CELL / 2`` rows between them).
    """
    nominal = np.linspace(-1.0, 1.0, n_eta + 1)
    rows, kink_rows = {}, {}
    for side in ("coast", "drive"):
        eta_k = _kink_heights(body, side, xi_levels)
        rows[side], kink_rows[side] = _rows_on_kinks(eta_k, nominal, len(xi_levels), side)
    return rows, kink_rows


def _kink_heights(body, side: str, xi_levels) -> list[np.ndarray]:
    """eta of the kinks of the flank ``side`` of ``body`` at the columns ``xi_levels``
    (+-inf where a kink is out of the tooth's height box), only the kinks that lie on
    the box at a column."""
    flank = getattr(body, side, None)
    if not isinstance(flank, KinkedFlank):
        return []
    xi = np.asarray(xi_levels, float)
    v = body.flank_parameters(side, xi, np.zeros_like(xi))[1]
    # the kink at the columns themselves: kinked_flank's nodes span the flank's v box
    # evenly, as the columns do (the flank's own 41-node line interpolates, 5e-8 mm)
    solved = kinked_flank(flank.pieces, flank.names, v_scales=flank.v_scales,
                          n_nodes=len(xi))
    lo, hi = body.u_span_mm
    out = []
    for kink in solved.kinks:
        if not np.allclose(kink.v_nodes, v, rtol=0.0, atol=1e-9 * (1.0 + np.abs(v).max())):
            raise RuntimeError(f"{body.member} {side} kink nodes off the FE columns")
        eta = 2.0 * (kink.u_nodes - lo) / (hi - lo) - 1.0
        if np.any((eta > -1.0) & (eta < 1.0)):
            out.append(eta)
    return out


def _rows_on_kinks(eta_k, nominal, n_col: int, side: str) -> tuple[np.ndarray, tuple]:
    """Rows (n_col, n + 1) of one flank with a row on each kink height of ``eta_k``
    (root -> tip; :func:`flank_rows`) and the kink rows."""
    n = len(nominal) - 1
    h = 2.0 / n
    if not eta_k:
        return np.broadcast_to(nominal, (n_col, n + 1)), ()
    need = f">= {len(eta_k) + 1} (a row on each of the {side} flank's {len(eta_k)} kinks)"
    kink_rows = []
    for e in eta_k:
        mean = np.clip(e, -1.0, 1.0).mean()
        j = int(np.clip(np.rint((mean + 1.0) / h), 1, n - 1))
        j = max(j, kink_rows[-1] + 1) if kink_rows else j
        if j > n - 1:
            raise InputRangeError("n_eta", n, need)
        kink_rows.append(j)
    # a kink row keeps KINK_CELL rows per cell from the root and tip rows
    eta_k = [np.clip(e, -1.0 + j * KINK_CELL * h, 1.0 - (n - j) * KINK_CELL * h)
             for e, j in zip(eta_k, kink_rows)]
    half = [1] * len(kink_rows)
    cols = np.arange(n + 1)
    while True:
        inside = np.zeros(n + 1, bool)
        for j, m in zip(kink_rows, half):
            inside[max(j - m + 1, 1):min(j + m, n)] = True     # root and tip rows stay
        anchors = np.flatnonzero(~inside)             # nominal rows (a kink's own row
        idx = np.concatenate([anchors, kink_rows])    # is inside its window)
        order = np.argsort(idx)
        val = np.concatenate([np.broadcast_to(nominal[anchors], (n_col, len(anchors))),
                              np.stack(eta_k, axis=1)], axis=1)[:, order]
        rows = np.stack([np.interp(cols, idx[order], val[c]) for c in range(n_col)])
        short = np.flatnonzero(np.diff(rows, axis=1).min(axis=0) < 0.5 * KINK_CELL * h)
        if not len(short):
            return rows, tuple(kink_rows)
        grown = False
        for c in short:         # grow the window of the kink row nearest the short cell
            k = int(np.argmin([abs(j - c - 0.5) for j in kink_rows]))
            if kink_rows[k] - half[k] > 0 or kink_rows[k] + half[k] < n:
                half[k] += 1
                grown = True
        if not grown:
            raise InputRangeError("n_eta", n, need + f" with cells of {0.5 * KINK_CELL} "
                                  "rows between them")


def _tooth_points(body, xi_l, eta_l, zeta_l, I, j, K, rows=None) -> np.ndarray:
    """Positions (3, n) of the tooth's nodes at index (I, eta level j, zeta column K)
    (``rows``: each flank's rows, :func:`flank_rows`; None: at ``eta_l``)."""
    if rows is None:
        pc, pd = body.side_points(xi_l[I], eta_l[j])
    else:
        pc, pd = (body.flank_arrays(side, xi_l[I], rows[side][I, j])[0]
                  for side in ("coast", "drive"))
    return (pc + zeta_l[K, None] * (pd - pc)).T


def _rim_mesh(skfem, body, xi_l, eta_l, zeta_l, n_rim, rim_depth_mm, fillet_mm, rows=None):
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
                                  K[tooth], rows)
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


def _fillet_mesh(skfem, body, root, xi_l, eta_l, zeta_l, n_block, n_fillet, n_slot,
                 rows=None):
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
                                  K[tooth] - n_slot, rows)
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

