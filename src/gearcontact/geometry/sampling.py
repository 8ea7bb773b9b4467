"""Vectorized surface evaluation, principal curvatures and flank sampling grids.

Every flank of :mod:`gearcontact.geometry` evaluates whole arrays of parameters at once
(:class:`SurfaceArrays`); :func:`sample_grid` turns that into a :class:`FlankGrid`
(positions, unit normals, principal curvatures and directions on a regular (u, v)
grid, e.g. the 16 x 22 and 120 x 150 grids of docs/spec.md sec. 3).

Curvature convention: the second fundamental form is taken w.r.t. the outward unit
normal n (out of the tooth); a principal curvature is positive where the flank bends
towards n (concave seen from the tooth space) and negative where it bends away
(convex). Principal curvatures are the eigenvalues of the shape operator
``S = I^-1 II`` (do Carmo 1976, sec. 3-3; Litvin & Fuentes 2004, ch. 7).

References
----------
M. P. do Carmo, *Differential Geometry of Curves and Surfaces*, 1976, sec. 3-3.
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 7-8.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError, check_array_finite
from .surface import SurfacePoint

__all__ = ["SurfaceArrays", "FlankGrid", "principal_curvatures", "sample_grid",
           "point_from_arrays"]


@dataclass(frozen=True)
class SurfaceArrays:
    """Surface quantities for arrays of parameters: each vector field has shape (..., 3)."""

    u: np.ndarray
    v: np.ndarray
    r: np.ndarray
    r_u: np.ndarray
    r_v: np.ndarray
    r_uu: np.ndarray
    r_uv: np.ndarray
    r_vv: np.ndarray
    n: np.ndarray


def point_from_arrays(s: SurfaceArrays) -> SurfacePoint:
    """The :class:`SurfacePoint` of a scalar evaluation."""
    return SurfacePoint(u=float(s.u), v=float(s.v), r=s.r, r_u=s.r_u, r_v=s.r_v,
                        r_uu=s.r_uu, r_uv=s.r_uv, r_vv=s.r_vv, n=s.n)


def principal_curvatures(s: SurfaceArrays) -> tuple[np.ndarray, np.ndarray]:
    """Principal curvatures (..., 2), ascending, 1/mm, and directions (..., 2, 3).

    Directions are unit tangent vectors in the body frame, ``dirs[..., k, :]`` belonging
    to ``kappa[..., k]``.
    """
    dot = lambda a, b: np.einsum("...i,...i->...", a, b)  # noqa: E731
    E, F, G = dot(s.r_u, s.r_u), dot(s.r_u, s.r_v), dot(s.r_v, s.r_v)
    L, M, N = dot(s.r_uu, s.n), dot(s.r_uv, s.n), dot(s.r_vv, s.n)
    det = E * G - F * F
    H = (E * N - 2.0 * F * M + G * L) / (2.0 * det)
    K = (L * N - M * M) / det
    disc = np.sqrt(np.maximum(H * H - K, 0.0))
    kappa = np.stack([H - disc, H + disc], axis=-1)
    # eigenvectors of S = I^-1 II in (du, dv): (II - k I) w = 0
    dirs = []
    for k in (kappa[..., 0], kappa[..., 1]):
        a, b, c = L - k * E, M - k * F, N - k * G
        # use the better-conditioned row of the singular 2x2 matrix [[a, b], [b, c]]
        use_first = np.abs(a) + np.abs(b) >= np.abs(b) + np.abs(c)
        du = np.where(use_first, -b, -c)
        dv = np.where(use_first, a, b)
        umbilic = (np.abs(du) + np.abs(dv)) == 0.0
        du = np.where(umbilic, 1.0, du)
        t = du[..., None] * s.r_u + dv[..., None] * s.r_v
        dirs.append(t / np.linalg.norm(t, axis=-1, keepdims=True))
    return kappa, np.stack(dirs, axis=-2)


@dataclass(frozen=True)
class FlankGrid:
    """A flank sampled on a regular parameter grid (index order ``[i_u, j_v]``).

    Attributes
    ----------
    u, v : ndarray (n_u,), (n_v,)
        Grid parameters (mm).
    positions_mm : ndarray (n_u, n_v, 3)
        Points in the member's body frame, mm.
    normals : ndarray (n_u, n_v, 3)
        Unit outward normals.
    curvatures_per_mm : ndarray (n_u, n_v, 2)
        Principal curvatures, ascending, 1/mm (sign convention: module docstring).
    directions : ndarray (n_u, n_v, 2, 3)
        Unit principal directions.
    """

    u: np.ndarray
    v: np.ndarray
    positions_mm: np.ndarray
    normals: np.ndarray
    curvatures_per_mm: np.ndarray
    directions: np.ndarray

    @property
    def shape(self) -> tuple[int, int]:
        """(n_u, n_v)."""
        return self.positions_mm.shape[:2]


def sample_grid(surface, n_u: int, n_v: int) -> FlankGrid:
    """Sample a flank on an ``n_u x n_v`` grid spanning its parameter box.

    ``surface`` must implement ``evaluate(u, v) -> SurfaceArrays`` (all flanks of this
    package do) or at least the :class:`~gearcontact.geometry.surface.Surface` protocol.
    """
    for name, n in (("n_u", n_u), ("n_v", n_v)):
        if int(n) != n or n < 2:
            raise InputRangeError(name, n, "an integer >= 2")
    u = np.linspace(*surface.u_range, int(n_u))
    v = np.linspace(*surface.v_range, int(n_v))
    U, V = np.meshgrid(u, v, indexing="ij")
    if hasattr(surface, "evaluate"):
        s = surface.evaluate(U, V)
    else:
        pts = [[surface.point(a, b) for b in v] for a in u]
        get = lambda name: np.array([[getattr(p, name) for p in row] for row in pts])  # noqa: E731
        s = SurfaceArrays(U, V, *(get(k) for k in ("r", "r_u", "r_v", "r_uu", "r_uv", "r_vv", "n")))
    kappa, dirs = principal_curvatures(s)
    return FlankGrid(u=u, v=v, positions_mm=check_array_finite("flank positions", s.r),
                     normals=s.n, curvatures_per_mm=kappa, directions=dirs)
