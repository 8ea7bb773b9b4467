"""Pinion flank sheets: a C2 (quintic spline) angular field over the pinion blank.

A pinion flank is stored as its angular coordinate ``psi(u, v)`` about the pinion axis
over a rectangular parameter box (both parameters in mm):

- ``v`` = axial position x along the pinion axis in the pinion body frame (toe -> heel);
- ``u`` = radial height above the root cone, ``R = R_f(v) + u`` with the root cone
  ``R_f(v) = (v - x_A1) tan(delta1) - h_f1 / cos(delta1)`` (uniform depth parallel to
  the pitch cone; x_A1 = pinion pitch apex).

so that ``r(u, v) = (v, R cos(psi), R sin(psi))``. The field psi is sampled exactly on
a dense grid (:mod:`.conjugate`, :mod:`.easeoff`) and interpolated by a quintic
tensor-product spline (scipy ``RectBivariateSpline``, kx = ky = 5, s = 0); positions,
first and second derivatives follow analytically from psi and its spline derivatives
(C4 continuous, never bilinear). With ``e_R = (0, cos psi, sin psi)``,
``e_psi = (0, -sin psi, cos psi)`` and ``t = tan(delta1) = dR/dv``:

    r_u  = e_R + R psi_u e_psi
    r_v  = x + t e_R + R psi_v e_psi
    r_uu = (2 psi_u + R psi_uu) e_psi - R psi_u^2 e_R
    r_uv = (psi_v + t psi_u + R psi_uv) e_psi - R psi_u psi_v e_R
    r_vv = (2 t psi_v + R psi_vv) e_psi - R psi_v^2 e_R

The unit normal is ``normal_sign * (r_u x r_v)/|r_u x r_v|``, the sign fixed at
construction so that n points out of the tooth.

References
----------
P. Dierckx, *Curve and Surface Fitting with Splines*, Oxford, 1993 (tensor splines).
M. P. do Carmo, *Differential Geometry of Curves and Surfaces*, 1976, sec. 3-3.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import RectBivariateSpline

from .flank import FlankBoundary
from .sampling import SurfaceArrays, point_from_arrays
from .surface import SurfacePoint

__all__ = ["PinionCone", "RadialSheet"]


@dataclass(frozen=True)
class PinionCone:
    """Pinion root cone of the sheet parameterization (lengths mm, angle rad)."""

    apex_x_mm: float
    tan_delta: float
    root_offset_mm: float  # h_f1 / cos(delta1)

    def root_radius_mm(self, v):
        """Root-cone radius R_f(v), mm."""
        return (np.asarray(v) - self.apex_x_mm) * self.tan_delta - self.root_offset_mm

    def radius_mm(self, u, v):
        """R(u, v) = R_f(v) + u, mm."""
        return self.root_radius_mm(v) + np.asarray(u)

    def parameters(self, x_mm, radius_mm):
        """(u, v) of a body-frame point given its axial position and radius, mm."""
        return np.asarray(radius_mm) - self.root_radius_mm(x_mm), np.asarray(x_mm)


@dataclass(frozen=True, eq=False)
class RadialSheet:
    """A pinion flank: spline of psi over the (u, v) box; implements ``Surface``.

    Attributes
    ----------
    side : str
        "drive" or "coast".
    cone : PinionCone
    u_nodes, v_nodes : ndarray
        Grid of the exact samples, mm.
    psi_nodes : ndarray (n_u, n_v)
        Exact angular coordinate at the nodes, rad.
    normal_sign : float
        +1 or -1 (outward orientation of r_u x r_v).
    boundary : FlankBoundary
        Active flank box (inside the node box; the nodes carry a margin).
    """

    side: str
    cone: PinionCone
    u_nodes: np.ndarray
    v_nodes: np.ndarray
    psi_nodes: np.ndarray
    normal_sign: float
    boundary: FlankBoundary

    def __post_init__(self):
        spline = RectBivariateSpline(self.u_nodes, self.v_nodes, self.psi_nodes, kx=5, ky=5, s=0)
        object.__setattr__(self, "_spline", spline)

    @property
    def u_range(self) -> tuple[float, float]:
        return (self.boundary.u_root, self.boundary.u_tip)

    @property
    def v_range(self) -> tuple[float, float]:
        return (self.boundary.v_toe, self.boundary.v_heel)

    def psi(self, u, v, du: int = 0, dv: int = 0) -> np.ndarray:
        """Spline value (or derivative) of psi at arrays (u, v), rad per mm^(du+dv)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        out = self._spline(u.ravel(), v.ravel(), dx=du, dy=dv, grid=False)
        return np.asarray(out).reshape(u.shape)

    def evaluate(self, u, v, *, second: bool = True) -> SurfaceArrays:
        """Vectorized evaluation (positions, derivatives, unit outward normal).

        ``second=False`` skips the second derivatives (returned as NaN) for speed.
        """
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        t = self.cone.tan_delta
        R = self.cone.radius_mm(u, v)[..., None]
        orders = ((0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)) if second else ((0, 0), (1, 0), (0, 1))
        p, pu, pv, *rest = (self.psi(u, v, a, b)[..., None] for a, b in orders)
        puu, puv, pvv = rest if second else (np.full_like(p, np.nan),) * 3
        zero, one = np.zeros_like(p), np.ones_like(p)
        eR = np.concatenate([zero, np.cos(p), np.sin(p)], axis=-1)
        ep = np.concatenate([zero, -np.sin(p), np.cos(p)], axis=-1)
        ex = np.concatenate([one, zero, zero], axis=-1)
        r = v[..., None] * ex + R * eR
        r_u = eR + R * pu * ep
        r_v = ex + t * eR + R * pv * ep
        r_uu = (2.0 * pu + R * puu) * ep - R * pu ** 2 * eR
        r_uv = (pv + t * pu + R * puv) * ep - R * pu * pv * eR
        r_vv = (2.0 * t * pv + R * pvv) * ep - R * pv ** 2 * eR
        c = np.cross(r_u, r_v)
        n = self.normal_sign * c / np.linalg.norm(c, axis=-1, keepdims=True)
        return SurfaceArrays(u=u, v=v, r=r, r_u=r_u, r_v=r_v, r_uu=r_uu, r_uv=r_uv, r_vv=r_vv, n=n)

    def point(self, u: float, v: float) -> SurfacePoint:
        """:class:`SurfacePoint` at (u, v) from the spline interpolant."""
        return point_from_arrays(self.evaluate(u, v))

    def locate(self, x_mm) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(u, v, psi_of_point) of body-frame points ``x_mm`` (..., 3)."""
        x = np.asarray(x_mm, dtype=float)
        u, v = self.cone.parameters(x[..., 0], np.hypot(x[..., 1], x[..., 2]))
        return u, v, np.arctan2(x[..., 2], x[..., 1])
