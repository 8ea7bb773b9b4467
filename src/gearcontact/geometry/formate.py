"""Formate gear flanks: the blade-cone flank of each gear side and its boundary box.

Gear (formate, non-generated): each gear flank is a copy of a blade cone
(:mod:`.cutter`): the inside blade gives the convex (drive) flank, the outside blade the
concave (coast) flank. Parameters of :class:`FormateFlank` (both in mm):

- ``u`` = height above the gear root plane along the cutter axis, root -> tip:
  ``h = h_f2 - u`` (h: depth below the pitch plane); the flank starts above the blade
  edge round, ``u >= r_e (1 - sin alpha)``, and ends at the gear tip, ``u = h_f2 + h_a2``
  (uniform depth: root and face parallel to the pitch plane);
- ``v`` = arc length along the blade circle in the pitch plane, toe -> heel, 0 at the
  mean section: ``theta = heel_sign v / rho_0``; the ends are the blade angles at which
  the pitch-plane trace reaches the cone distances ``R2 -+ F2/2`` (toe / heel).

:class:`FlankBoundary` (the named edges of any flank's parameter box) and the sides
live here, below the conjugate pinion (:mod:`.conjugate`, :mod:`.sheet`) and the flank
set that puts all four flanks together (:mod:`.flank`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 21
(formate hypoid gears).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit
from scipy.optimize import brentq

from ..validation import InputRangeError
from .blank import BlankDesign
from .cutter import BladeCone, CutterPlacement, place_cutter
from .sampling import SurfaceArrays
from .surface import SurfacePoint

__all__ = ["SIDES", "FlankBoundary", "FormateFlank", "cone_vector", "gear_flank",
           "gear_flanks"]

#: Flank sides, in the order used everywhere.
SIDES = ("drive", "coast")


@dataclass(frozen=True)
class FlankBoundary:
    """Parameter box of a flank with named edges (for edge-contact detection), mm.

    ``u``: root -> tip, ``v``: toe -> heel.
    """

    u_root: float
    u_tip: float
    v_toe: float
    v_heel: float

    def contains(self, u, v, *, tol: float = 0.0):
        """True (elementwise) where (u, v) lies inside the box (+ tol)."""
        u, v = np.asarray(u), np.asarray(v)
        return ((u >= self.u_root - tol) & (u <= self.u_tip + tol)
                & (v >= self.v_toe - tol) & (v <= self.v_heel + tol))

    def edge(self, u: float, v: float) -> str | None:
        """Name of the edge (root/tip/toe/heel) that (u, v) lies beyond, or None inside."""
        if u < self.u_root:
            return "root"
        if u > self.u_tip:
            return "tip"
        if v < self.v_toe:
            return "toe"
        if v > self.v_heel:
            return "heel"
        return None


@dataclass(frozen=True, eq=False)
class FormateFlank:
    """A gear flank = a blade cone, in the gear body frame (see module docstring).

    Implements :class:`~gearcontact.geometry.surface.Surface` exactly (no
    interpolation): position, derivatives and normal are closed-form.
    """

    side: str
    blade: BladeCone
    dedendum_mm: float
    boundary: FlankBoundary

    @property
    def u_range(self) -> tuple[float, float]:
        return (self.boundary.u_root, self.boundary.u_tip)

    @property
    def v_range(self) -> tuple[float, float]:
        return (self.boundary.v_toe, self.boundary.v_heel)

    @property
    def _kv(self) -> float:
        return self.blade.placement.heel_sign / self.blade.radius_pitch_mm

    def blade_parameters(self, u, v):
        """(h, theta): blade depth below the pitch plane (mm) and blade angle (rad)."""
        return self.dedendum_mm - np.asarray(u, dtype=float), self._kv * np.asarray(v, dtype=float)

    def surface_parameters(self, h_mm, theta_rad):
        """Inverse of :meth:`blade_parameters`: (u, v) in mm."""
        return self.dedendum_mm - np.asarray(h_mm), np.asarray(theta_rad) / self._kv

    def evaluate(self, u, v, *, second: bool = True) -> SurfaceArrays:
        """Vectorized exact evaluation at arrays ``u``, ``v`` (broadcast).

        ``second`` is accepted for symmetry with
        :meth:`~.sheet.RadialSheet.evaluate`; the closed-form second derivatives cost
        nothing extra and are always returned.
        """
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        h, th = self.blade_parameters(u, v)
        b = self.blade.evaluate(h, th)
        kv = self._kv
        return SurfaceArrays(u=u, v=v, r=b.x, r_u=-b.x_h, r_v=kv * b.x_t,
                             r_uu=np.zeros_like(b.x), r_uv=-kv * b.x_ht, r_vv=kv * kv * b.x_tt,
                             n=b.n)

    def point(self, u: float, v: float) -> SurfacePoint:
        """Exact :class:`SurfacePoint` at (u, v) (compiled, :func:`cone_vector`)."""
        out = np.empty((7, 3))
        cone_vector(self.kernel_parameters, float(u), float(v), True, out)
        return SurfacePoint(float(u), float(v), *out)

    @property
    def kernel_parameters(self) -> np.ndarray:
        """Parameter vector of :func:`cone_vector`: cutter centre, axis, e1, e2 (3 each),
        ``rho_0``, ``k = sigma tan(alpha)``, dedendum, ``k_v``, ``sigma cos(alpha)``,
        ``sin(alpha)``."""
        got = self.__dict__.get("_kernel_parameters")
        if got is None:
            blade, pl = self.blade, self.blade.placement
            alpha = np.radians(blade.pressure_angle_deg)
            got = np.concatenate([pl.centre_mm, pl.axis, pl.e1, pl.e2, [
                blade.radius_pitch_mm, blade.sigma * np.tan(alpha), self.dedendum_mm, self._kv,
                blade.sigma * np.cos(alpha), np.sin(alpha)]]).astype(float)
            object.__setattr__(self, "_kernel_parameters", got)
        return got

    def analytic_curvatures(self, u, v) -> np.ndarray:
        """Principal curvatures of the blade cone, (..., 2) ascending, 1/mm.

        A cone of half-angle alpha: 0 along the generator and ``cos(alpha)/rho`` across
        it (rho = distance from the cone axis), negative on the convex (inside-blade)
        flank w.r.t. the outward normal, positive on the concave flank.
        """
        h, _ = self.blade_parameters(u, v)
        k = self.blade.sigma * -np.cos(np.radians(self.blade.pressure_angle_deg)) / self.blade.radius_mm(h)
        z = np.zeros_like(k)
        return np.sort(np.stack([k, z], axis=-1), axis=-1)


@njit(cache=True, inline="always")
def cone_vector(par, u, v, full, out):
    """Compiled twin of :meth:`FormateFlank.evaluate` at one point: ``out`` (7, 3) =
    r, r_u, r_v, r_uu, r_uv, r_vv, n (only the first three rows unless ``full``), from
    :attr:`FormateFlank.kernel_parameters` ``par``. The blade cone
    (:meth:`~.cutter.BladeCone.evaluate`) at ``h = dedendum - u``, ``theta = k_v v``:
    ``x = C + rho e_rho + h a``, ``rho = rho_0 + k h``."""
    h = par[14] - u
    kv = par[15]
    c = np.cos(kv * v)
    s = np.sin(kv * v)
    rho = par[12] + par[13] * h
    for i in range(3):
        e_rho = c * par[6 + i] + s * par[9 + i]
        e_th = -s * par[6 + i] + c * par[9 + i]
        out[0, i] = par[i] + rho * e_rho + h * par[3 + i]
        out[1, i] = -(par[13] * e_rho + par[3 + i])
        out[2, i] = kv * rho * e_th
        if full:
            out[3, i] = 0.0
            out[4, i] = -kv * par[13] * e_th
            out[5, i] = -kv * kv * rho * e_rho
            out[6, i] = par[16] * e_rho - par[17] * par[3 + i]


def gear_flank(blank: BlankDesign, blade: BladeCone, *, side: str, gear_face_width_mm: float,
               edge_radius_mm: float, blade_key: tuple[str, float] | None = None
               ) -> FormateFlank:
    """Build the gear flank of one blade with its boundary (see module docstring).

    A cutter circle that misses a face end is refused naming ``blade_key`` (the key and
    value of a typed blade, e.g. its point radius), else ``design.gear_face_width_mm``."""
    pl = blade.placement
    apex = np.array([0.0, 0.0, blank.gear_apex_z_mm])
    R2 = blank.mean_cone_distance_gear_mm
    rho0 = blade.radius_pitch_mm

    def cone_distance(v, target):
        th = pl.heel_sign * v / rho0
        x = pl.centre_mm + rho0 * (np.cos(th) * pl.e1 + np.sin(th) * pl.e2)
        return np.linalg.norm(x - apex) - target

    span = 2.0 * gear_face_width_mm
    ends = []
    for target in (R2 - 0.5 * gear_face_width_mm, R2 + 0.5 * gear_face_width_mm):
        try:
            ends.append(brentq(cone_distance, -span, span, args=(target,), xtol=1e-13))
        except ValueError:
            if blade_key is None:
                raise InputRangeError("design.gear_face_width_mm", gear_face_width_mm,
                                      "a face width whose ends the cutter circle reaches") from None
            raise InputRangeError(*blade_key, f"a cutter circle that reaches both face ends (cone "
                                  f"distances {R2 - 0.5 * gear_face_width_mm:.3f} to "
                                  f"{R2 + 0.5 * gear_face_width_mm:.3f} mm; mm, not inches)"
                                  ) from None
    alpha = np.radians(blade.pressure_angle_deg)
    u_root = edge_radius_mm * (1.0 - np.sin(alpha))
    u_tip = blank.dedendum_gear_mm + blank.addendum_gear_mm
    return FormateFlank(side=side, blade=blade, dedendum_mm=blank.dedendum_gear_mm,
                        boundary=FlankBoundary(u_root=float(u_root), u_tip=float(u_tip),
                                               v_toe=float(ends[0]), v_heel=float(ends[1])))


def gear_flanks(pair) -> tuple[CutterPlacement, dict]:
    """The cutter placement and the formate gear flanks ``{side: FormateFlank}`` of
    ``pair`` (inside blade -> drive, outside blade -> coast)."""
    blank = pair.blank
    placement, inside, outside = place_cutter(blank, point_width_mm=pair.cutter.point_width_mm)
    return placement, {side: gear_flank(blank, blade, side=side,
                                        gear_face_width_mm=pair.gear_face_width_mm,
                                        edge_radius_mm=pair.cutter.edge_radius_mm)
                       for side, blade in zip(SIDES, (inside, outside))}

