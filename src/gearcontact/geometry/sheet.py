"""Pinion flank sheets: a C2 (quintic spline) angular field over the pinion blank.

A pinion flank is stored as its angular coordinate ``psi(u, v)`` about the pinion axis
over a rectangular parameter box (both parameters in mm):

- ``v`` = axial position x along the pinion axis in the pinion body frame (toe -> heel);
- ``u`` = radial height above the root cone, ``R = R_f(v) + u`` with the root cone
  ``R_f(v) = (v - x_A1) tan(delta1) - h_f1 / cos(delta1)`` (uniform depth parallel to
  the pitch cone; x_A1 = pinion pitch apex).

so that ``r(u, v) = (v, R cos(psi), R sin(psi))``. The field psi is sampled exactly on
a dense grid (:mod:`.conjugate`, :mod:`.easeoff`) and interpolated by a quintic
tensor-product spline (scipy ``RectBivariateSpline``, kx = ky = 5, s = 0; evaluated
with its derivatives in one compiled pass from its piecewise-polynomial form,
:mod:`.spline_kernel`); positions, first
and second derivatives follow analytically from psi and its spline derivatives (C4
continuous, never bilinear). With ``e_R = (0, cos psi, sin psi)``,
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
from numba import njit
from scipy.interpolate import RectBivariateSpline

from .formate import FlankBoundary
from .sampling import SurfaceArrays
from .spline_kernel import pp_coefficients, pp_derivatives
from .surface import SurfacePoint

__all__ = ["GearCone", "GearSheet", "PinionCone", "RadialSheet", "sheet_vectors", "sheet_vector",
           "gear_sheet_vectors", "gear_sheet_vector"]


@njit(cache=True, inline="always")
def sheet_vector(u, v, d, apex_x, tan, root_offset, sign, full, out):
    """Position and derivatives of a sheet point from psi and its derivatives
    ``d = (psi, psi_u, psi_v, psi_uu, psi_uv, psi_vv)`` (module docstring formulas)
    into ``out`` (7, 3): r, r_u, r_v, r_uu, r_uv, r_vv, n; with ``full`` False only
    the first three rows."""
    p, pu, pv, puu, puv, pvv = d[0], d[1], d[2], d[3], d[4], d[5]
    rad = (v - apex_x) * tan - root_offset + u
    c = np.cos(p)
    s = np.sin(p)
    # e_R = (0, c, s), e_psi = (0, -s, c), x = (1, 0, 0)
    out[0, 0], out[0, 1], out[0, 2] = v, rad * c, rad * s
    a = rad * pu
    out[1, 0], out[1, 1], out[1, 2] = 0.0, c - a * s, s + a * c
    b = rad * pv
    out[2, 0], out[2, 1], out[2, 2] = 1.0, tan * c - b * s, tan * s + b * c
    if not full:
        return
    for row, ep, er in ((3, 2.0 * pu + rad * puu, -rad * pu * pu),
                        (4, pv + tan * pu + rad * puv, -rad * pu * pv),
                        (5, 2.0 * tan * pv + rad * pvv, -rad * pv * pv)):
        out[row, 0], out[row, 1], out[row, 2] = 0.0, -ep * s + er * c, ep * c + er * s
    nx = out[1, 1] * out[2, 2] - out[1, 2] * out[2, 1]
    ny = out[1, 2] * out[2, 0] - out[1, 0] * out[2, 2]
    nz = out[1, 0] * out[2, 1] - out[1, 1] * out[2, 0]
    f = sign / np.sqrt(nx * nx + ny * ny + nz * nz)
    out[6, 0], out[6, 1], out[6, 2] = f * nx, f * ny, f * nz


@njit(cache=True)
def sheet_vectors(u, v, d, apex_x, tan, root_offset, sign, full):
    """:func:`sheet_vector` for arrays: (N, 7, 3) from ``d`` (N, 6)."""
    out = np.empty((u.shape[0], 7, 3))
    for i in range(u.shape[0]):
        sheet_vector(u[i], v[i], d[i], apex_x, tan, root_offset, sign, full, out[i])
    return out


@njit(cache=True, inline="always")
def gear_sheet_vector(u, v, d, c, s, ru, rv, mcd, ded, apex_z, sign, full, o):
    """One :class:`GearSheet` point into ``o`` (7, 3): r, r_u, r_v, r_uu, r_uv, r_vv, n
    (only the first three rows unless ``full``) from psi's derivatives ``d`` (6,),
    ``c = cos psi``, ``s = sin psi`` and the cone ``(cos delta, sin delta, R2, h_f,
    z_A)``. Every component is the operation sequence of the array form (``R e_R + z
    k``, ``R_u e_R + R psi_u e_psi + z_u k``, ...: :class:`GearSheet`) written out,
    terms with a zero factor included, so the values are the same bits."""
    zu, zv = -rv, ru
    p_u, p_v = d[1], d[2]
    rad = (mcd + v) * rv + (u - ded) * ru
    h = apex_z + (mcd + v) * ru - (u - ded) * rv
    o[0, 0], o[0, 1], o[0, 2] = rad * c + h * 0.0, rad * s + h * 0.0, rad * 0.0 + h * 1.0
    for row, rz, zz, a in ((1, ru, zu, rad * p_u), (2, rv, zv, rad * p_v)):
        o[row, 0] = (rz * c + a * -s) + zz * 0.0
        o[row, 1] = (rz * s + a * c) + zz * 0.0
        o[row, 2] = (rz * 0.0 + a * 0.0) + zz * 1.0
    if not full:
        return
    for row, ep, er in ((3, 2.0 * ru * p_u + rad * d[3], rad * p_u * p_u),
                        (4, ru * p_v + rv * p_u + rad * d[4], rad * p_u * p_v),
                        (5, 2.0 * rv * p_v + rad * d[5], rad * p_v * p_v)):
        o[row, 0] = ep * -s - er * c
        o[row, 1] = ep * c - er * s
        o[row, 2] = ep * 0.0 - er * 0.0
    nx = o[1, 1] * o[2, 2] - o[1, 2] * o[2, 1]
    ny = o[1, 2] * o[2, 0] - o[1, 0] * o[2, 2]
    nz = o[1, 0] * o[2, 1] - o[1, 1] * o[2, 0]
    norm = np.sqrt(nx * nx + ny * ny + nz * nz)
    o[6, 0], o[6, 1], o[6, 2] = sign * nx / norm, sign * ny / norm, sign * nz / norm


@njit(cache=True)
def gear_sheet_vectors(u, v, d, cos_p, sin_p, cone, sign):
    """(N, 7, 3) of :class:`GearSheet` points (:func:`gear_sheet_vector`) from psi's
    derivatives ``d`` (N, 6) and ``cos psi``, ``sin psi`` (numpy's: the trigonometry
    stays numpy's); ``cone`` = ``(cos delta, sin delta, R2, h_f, z_A)``."""
    ru, rv, mcd, ded, apex_z = cone
    out = np.empty((u.shape[0], 7, 3))
    for i in range(u.shape[0]):
        gear_sheet_vector(u[i], v[i], d[i], cos_p[i], sin_p[i], ru, rv, mcd, ded, apex_z,
                          sign, True, out[i])
    return out


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

    def height_mm(self, u, v):
        """Axial position of the sheet point (u, v): ``v``, mm."""
        return np.asarray(v) + 0.0 * np.asarray(u)


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
    def pp_arrays(self) -> tuple:
        """``(tx, ty, pc, kx, ky)``: knots and piecewise-polynomial coefficients of the
        psi spline (:func:`~.spline_kernel.pp_coefficients`, built once, ~6 MB for the
        120 x 150 node grid)."""
        got = self.__dict__.get("_pp_arrays")
        if got is None:
            tx, ty, c = (np.ascontiguousarray(a, dtype=float) for a in self._spline.tck[:3])
            kx, ky = (int(k) for k in self._spline.degrees)
            got = (tx, ty, pp_coefficients(tx, ty, c, kx, ky), kx, ky)
            object.__setattr__(self, "_pp_arrays", got)
        return got

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

    def psi_derivatives(self, u, v, *, second: bool = True) -> np.ndarray:
        """psi and its partial derivatives at arrays (u, v) in one compiled pass:
        (..., 6) with ``psi, psi_u, psi_v, psi_uu, psi_uv, psi_vv`` (the last three NaN
        unless ``second``); equal to :meth:`psi` to rounding
        (:mod:`.spline_kernel`)."""
        u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
        if u.ndim or v.ndim:    # a single point (the TCA's solvers) needs no broadcast
            u, v = np.broadcast_arrays(u, v)
        tx, ty, pc, kx, ky = self.pp_arrays
        out = pp_derivatives(tx, ty, pc, kx, ky, np.ascontiguousarray(u.ravel()),
                             np.ascontiguousarray(v.ravel()), 2 if second else 1, False)
        return out.reshape(u.shape + (6,))

    def evaluate(self, u, v, *, second: bool = True) -> SurfaceArrays:
        """Vectorized evaluation (positions, derivatives, unit outward normal).

        ``second=False`` skips the second derivatives (returned as NaN) for speed.
        """
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        vec = self._vectors(u, v, second).reshape(u.shape + (7, 3))
        return SurfaceArrays(u, v, *(vec[..., i, :] for i in range(7)))

    def point(self, u: float, v: float) -> SurfacePoint:
        """:class:`SurfacePoint` at (u, v) from the spline interpolant."""
        vec = self._vectors(np.asarray(u, dtype=float), np.asarray(v, dtype=float), True)[0]
        return SurfacePoint(float(u), float(v), *vec)

    def _vectors(self, u: np.ndarray, v: np.ndarray, second: bool) -> np.ndarray:
        """(N, 7, 3): r, r_u, r_v, r_uu, r_uv, r_vv, n at the flattened (u, v)."""
        d = self.psi_derivatives(u, v, second=second).reshape(-1, 6)
        cone = self.cone
        return sheet_vectors(np.ascontiguousarray(u.ravel()), np.ascontiguousarray(v.ravel()),
                             d, cone.apex_x_mm, cone.tan_delta, cone.root_offset_mm,
                             float(self.normal_sign), True)

    def locate(self, x_mm) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(u, v, psi_of_point) of body-frame points ``x_mm`` (..., 3)."""
        x = np.asarray(x_mm, dtype=float)
        u, v = self.cone.parameters(x[..., 0], np.hypot(x[..., 1], x[..., 2]))
        return u, v, np.arctan2(x[..., 2], x[..., 1])


@dataclass(frozen=True)
class GearCone:
    """Axial-plane coordinates of a gear flank sheet (:class:`GearSheet`), gear body frame.

    A point at height ``u`` above the root (uniform depth, along the outward normal of
    the pitch cone in the axial plane) and cone distance ``R2 + v`` lies at radius and
    height ``R = (R2 + v) sin(delta) + (u - h_f) cos(delta)``,
    ``z = z_A + (R2 + v) cos(delta) - (u - h_f) sin(delta)`` (lengths mm).
    """

    apex_z_mm: float
    sin_delta: float
    cos_delta: float
    mean_cone_distance_mm: float
    dedendum_mm: float
    mean_azimuth_rad: float

    def radius_mm(self, u, v):
        """R(u, v), mm."""
        return ((self.mean_cone_distance_mm + np.asarray(v)) * self.sin_delta
                + (np.asarray(u) - self.dedendum_mm) * self.cos_delta)

    def height_mm(self, u, v):
        """z(u, v), mm."""
        return (self.apex_z_mm + (self.mean_cone_distance_mm + np.asarray(v)) * self.cos_delta
                - (np.asarray(u) - self.dedendum_mm) * self.sin_delta)

    def parameters(self, z_mm, radius_mm):
        """Inverse of (height, radius): ``(u, v)`` of the axial-plane point ``(z, R)``, mm."""
        dz = np.asarray(z_mm) - self.apex_z_mm
        rad = np.asarray(radius_mm)
        return (self.dedendum_mm + rad * self.cos_delta - dz * self.sin_delta,
                rad * self.sin_delta + dz * self.cos_delta - self.mean_cone_distance_mm)


@dataclass(frozen=True, eq=False)
class GearSheet(RadialSheet):
    """A generated gear flank: spline of the angle ``psi`` about the gear axis over the
    (u, v) box of :class:`GearCone` (``u`` root -> tip, ``v`` toe -> heel, 0 at the mean
    section); ``r = (R cos psi, R sin psi, z)``. With ``e_R = (cos psi, sin psi, 0)``,
    ``e_psi = (-sin psi, cos psi, 0)`` and the constant ``R_u = cos(delta)``,
    ``R_v = sin(delta)``, ``z_u = -sin(delta)``, ``z_v = cos(delta)``:

        r_u  = R_u e_R + R psi_u e_psi + z_u z
        r_uu = (2 R_u psi_u + R psi_uu) e_psi - R psi_u^2 e_R   (and alike for uv, vv)

    ``cone`` is a :class:`GearCone`. Evaluated with numpy (TCA takes its generic path).
    """

    def locate(self, x_mm):
        raise NotImplementedError("GearSheet.locate")

    def blade_parameters(self, u, v):
        """(h, theta) of the sheet point (u, v) as the meshing solver of the conjugate
        pinion takes it (:class:`~.gear_generation.SheetGenerator`): depth below the
        pitch cone ``h = h_f2 - u`` (mm, as a formate flank's) and ``theta = v / R2``
        (rad, ``R2`` the mean cone distance)."""
        c = self.cone
        return (c.dedendum_mm - np.asarray(u, dtype=float),
                np.asarray(v, dtype=float) / c.mean_cone_distance_mm)

    def surface_parameters(self, h_mm, theta_rad):
        """Inverse of :meth:`blade_parameters`: (u, v) in mm."""
        c = self.cone
        return c.dedendum_mm - np.asarray(h_mm), np.asarray(theta_rad) * c.mean_cone_distance_mm

    def _vectors(self, u: np.ndarray, v: np.ndarray, second: bool) -> np.ndarray:
        d = self.psi_derivatives(u, v, second=second).reshape(-1, 6)
        u, v = u.ravel(), v.ravel()
        c = self.cone
        p = d[:, 0]
        return gear_sheet_vectors(
            np.ascontiguousarray(u, dtype=float), np.ascontiguousarray(v, dtype=float),
            np.ascontiguousarray(d), np.cos(p), np.sin(p),
            (c.cos_delta, c.sin_delta, c.mean_cone_distance_mm, c.dedendum_mm, c.apex_z_mm),
            float(self.normal_sign))
