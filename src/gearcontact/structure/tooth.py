"""One tooth of a member as a plate body: mid-surface, thickness and flank load points.

A tooth is bounded by the drive flank and the coast flank that face away from each
other (for the pinion the two flanks of :class:`~gearcontact.geometry.flank.FlankSet`
as they are; for the formate gear the coast flank of the neighbouring slot, i.e. the
coast flank turned by one pitch about the gear axis, chosen so that each flank lies
behind the other's outward normal). Both structural models of
:mod:`gearcontact.structure` (the shell Rayleigh-Ritz model and the 3D finite
elements) use the same tooth coordinates:

- ``eta`` in [-1, 1], root -> tip: affine in the flank parameter ``u`` (height above the
  root cone / root plane, mm) over the part of the height both flanks cover,
  ``[max(u_root), min(u_tip)]``;
- ``xi`` in [-1, 1], toe -> heel: affine in each flank's own lengthwise parameter ``v``
  over its own face box (pinion: axial position, the same for both flanks; gear: arc
  length along each blade circle, whose toe and heel ends lie at the same cone
  distances on both blades).

The drive point ``P_d(xi, eta)`` and the coast point ``P_c(xi, eta)`` face each other
across the tooth; the mid-surface is ``X = (P_d + P_c) / 2``, its unit normal ``m``
points from the coast to the drive side, and the thickness along ``m`` is
``t = (P_d - P_c) . m`` (mm). Everything is in the member's body frame.

References
----------
M. Kolivand, A. Kahraman, "A load distribution model for hypoid gears using ease-off
topography and shell theory", *Mechanism and Machine Theory* 44(10), 2009, 1848-1865
(tooth as a shell over the mid-surface between the flanks).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ..geometry.flank import FlankSet
from ..geometry.formate import SIDES
from ..materials import Material
from ..validation import InputRangeError, check_array_finite, check_positive

__all__ = ["MidSurfaceArrays", "LoadPoints", "PlateBody", "ToothGeometry", "RectangularPlate",
           "tooth_geometry", "local_frame", "axis_rotation"]

#: Tolerance (mm) on a flank parameter outside its own box before it is rejected.
_PARAM_TOL_MM = 1e-6


@dataclass(frozen=True)
class MidSurfaceArrays:
    """Mid-surface quantities at arrays of (xi, eta); vectors (..., 3), mm.

    ``x_xi``, ``x_eta`` are the derivatives of the position per unit xi / eta (mm),
    ``normal`` the unit normal (coast -> drive), ``thickness_mm`` the thickness along it.
    """

    position_mm: np.ndarray
    x_xi: np.ndarray
    x_eta: np.ndarray
    normal: np.ndarray
    thickness_mm: np.ndarray


@dataclass(frozen=True)
class LoadPoints:
    """Points where a unit load acts (and the deflection along it is measured).

    Attributes
    ----------
    xi, eta : ndarray (n,)
        Tooth coordinates of the mid-surface point below each point.
    direction : ndarray (n, 3)
        Unit direction of the load / measured displacement: the inward flank normal
        (-n, into the tooth) for flank points; the deflection is the displacement
        component along it, so the compliance of a point with itself is positive.
    offset_mm : ndarray (n,)
        Signed distance of the point from the mid-surface along its normal ``m``
        (+t/2 on the drive flank, -t/2 on the coast flank), mm.
    position_mm : ndarray (n, 3)
        The points in the body frame, mm.
    """

    xi: np.ndarray
    eta: np.ndarray
    direction: np.ndarray
    offset_mm: np.ndarray
    position_mm: np.ndarray

    def __len__(self) -> int:
        return len(self.xi)


def local_frame(mid: MidSurfaceArrays) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Orthonormal frame (e1, e2, m) of the mid-surface: e1 along x_xi (lengthwise),
    e2 the part of x_eta normal to it (towards the tip), m the normal (coast -> drive).

    The frame is right- or left-handed as the tooth is: the mirror image of a tooth
    (a left-hand pair, :mod:`gearcontact.geometry.mirror`) has the mirrored frame, so
    that (xi, eta) -> (x1, x2) keeps a positive Jacobian and the plate energy is the
    same (``e2 = m x e1`` would point to the root on a left-hand tooth)."""
    e1 = mid.x_xi / np.linalg.norm(mid.x_xi, axis=-1, keepdims=True)
    e2 = mid.x_eta - np.einsum("...i,...i->...", mid.x_eta, e1)[..., None] * e1
    e2 /= np.linalg.norm(e2, axis=-1, keepdims=True)
    return e1, e2, mid.normal


class PlateBody(Protocol):
    """What the shell (:mod:`.shell`) and the FE (:mod:`.fe`) need of a plate body:
    its material, mid-surface and the two faces over (xi, eta) in [-1, 1]^2 (eta = -1
    is the root), and load points on a face."""

    material: Material

    def mid_surface(self, xi, eta) -> MidSurfaceArrays:
        """Mid-surface arrays at (xi, eta)."""

    def side_points(self, xi, eta) -> tuple[np.ndarray, np.ndarray]:
        """(coast-side, drive-side) surface points (..., 3) facing each other, mm."""

    def points_at(self, side: str, xi, eta) -> LoadPoints:
        """Load points on the face of ``side`` at (xi, eta)."""


@dataclass(frozen=True, eq=False)
class RectangularPlate:
    """Flat rectangular plate clamped along one edge: the test body with closed forms.

    The plate lies in the x-y plane: ``x = xi W / 2`` across the width,
    ``y = (eta + 1) L / 2`` from the clamped root (y = 0) to the free edge (y = L);
    the thickness varies linearly from ``thickness_root_mm`` to ``thickness_tip_mm``.

    Parameters
    ----------
    length_mm, width_mm : float
        Cantilever length L (root -> free edge) and width W, mm.
    thickness_root_mm : float
        Thickness at the root, mm.
    thickness_tip_mm : float or None
        Thickness at the free edge, mm (default: uniform).
    material : Material
    """

    length_mm: float
    width_mm: float
    thickness_root_mm: float
    material: Material
    thickness_tip_mm: float | None = None

    def __post_init__(self):
        for name in ("length_mm", "width_mm", "thickness_root_mm"):
            check_positive(name, getattr(self, name))
        if self.thickness_tip_mm is not None:
            check_positive("thickness_tip_mm", self.thickness_tip_mm)

    def _thickness(self, eta):
        tip = self.thickness_root_mm if self.thickness_tip_mm is None else self.thickness_tip_mm
        t0 = self.thickness_root_mm
        return t0 + 0.5 * (np.asarray(eta) + 1.0) * (tip - t0)

    def mid_surface(self, xi, eta) -> MidSurfaceArrays:
        xi, eta = np.broadcast_arrays(np.asarray(xi, float), np.asarray(eta, float))
        pos = np.stack([0.5 * self.width_mm * xi, 0.5 * self.length_mm * (eta + 1.0),
                        np.zeros_like(xi)], axis=-1)
        one = np.ones_like(xi)[..., None]
        return MidSurfaceArrays(position_mm=pos, x_xi=one * [0.5 * self.width_mm, 0.0, 0.0],
                                x_eta=one * [0.0, 0.5 * self.length_mm, 0.0],
                                normal=one * [0.0, 0.0, 1.0], thickness_mm=self._thickness(eta))

    def side_points(self, xi, eta):
        mid = self.mid_surface(xi, eta)
        half = 0.5 * mid.thickness_mm[..., None] * mid.normal
        return mid.position_mm - half, mid.position_mm + half

    def points_at(self, side: str, xi, eta) -> LoadPoints:
        """Points on the top ("drive", z = +t/2) or bottom ("coast") face, loaded along
        the inward face normal."""
        if side not in SIDES:
            raise InputRangeError("side", side, f"one of {SIDES}")
        xi, eta = (np.atleast_1d(np.asarray(a, float)) for a in (xi, eta))
        mid = self.mid_surface(xi, eta)
        sign = 1.0 if side == "drive" else -1.0
        return LoadPoints(xi=xi, eta=eta, direction=-sign * mid.normal,
                          offset_mm=0.5 * sign * mid.thickness_mm,
                          position_mm=mid.position_mm + 0.5 * sign * mid.thickness_mm[:, None]
                          * mid.normal)

    def points(self, xi, eta) -> LoadPoints:
        """Mid-surface points loaded along -z (deflection measured along -z)."""
        xi, eta = (np.atleast_1d(np.asarray(a, float)) for a in (xi, eta))
        mid = self.mid_surface(xi, eta)
        return LoadPoints(xi=xi, eta=eta, direction=-mid.normal, offset_mm=np.zeros_like(xi),
                          position_mm=mid.position_mm)


@dataclass(frozen=True, eq=False)
class ToothGeometry:
    """One tooth of a member between its real drive and coast flanks (module docstring).

    Attributes
    ----------
    member : str
        "pinion" or "gear".
    drive, coast : Surface
        The flanks (body frame; the coast flank is used turned by ``coast_turn``).
    coast_turn : ndarray (3, 3)
        Rotation about the member axis applied to the coast flank (identity for the
        pinion, one pitch for the formate gear).
    u_span_mm : tuple
        Height box ``(u_lo, u_hi)`` common to both flanks, mm (eta = -1 .. 1).
    axis : ndarray (3,)
        Unit axis of the member in its body frame (through the origin).
    teeth : int
        Number of teeth of the member.
    material : Material
    """

    member: str
    drive: object
    coast: object
    coast_turn: np.ndarray
    u_span_mm: tuple[float, float]
    axis: np.ndarray
    teeth: int
    material: Material

    # ------------------------------------------------------------- coordinates
    def flank_parameters(self, side: str, xi, eta) -> tuple[np.ndarray, np.ndarray]:
        """Flank parameters (u, v), mm, of tooth coordinates (xi, eta) on ``side``."""
        flank = self._flank(side)
        lo, hi = self.u_span_mm
        v0, v1 = flank.v_range
        return (lo + 0.5 * (np.asarray(eta) + 1.0) * (hi - lo),
                v0 + 0.5 * (np.asarray(xi) + 1.0) * (v1 - v0))

    def tooth_coordinates(self, side: str, u, v) -> tuple[np.ndarray, np.ndarray]:
        """Tooth coordinates (xi, eta) of flank parameters (u, v) on ``side``.

        Raises InputRangeError for a point outside that flank's own parameter box; a
        point of the flank below / above the common height box (at most the difference
        of the two flanks' active roots, 0.05 mm on s0003) is taken at the box edge.
        """
        flank = self._flank(side)
        u, v = np.asarray(u, float), np.asarray(v, float)
        (ur0, ur1), (v0, v1) = flank.u_range, flank.v_range
        for name, a, lo, hi in (("u_mm", u, ur0, ur1), ("v_mm", v, v0, v1)):
            bad = (a < lo - _PARAM_TOL_MM) | (a > hi + _PARAM_TOL_MM)
            if np.any(bad):
                raise InputRangeError(f"{self.member} {side} flank {name}", a[bad].ravel()[0],
                                      f"[{lo:.4f}, {hi:.4f}] mm (the flank box)")
        lo, hi = self.u_span_mm
        eta = np.clip(2.0 * (u - lo) / (hi - lo) - 1.0, -1.0, 1.0)
        xi = np.clip(2.0 * (v - v0) / (v1 - v0) - 1.0, -1.0, 1.0)
        return xi, eta

    def _flank(self, side: str):
        if side not in SIDES:
            raise InputRangeError("side", side, f"one of {SIDES}")
        return getattr(self, side)

    # ------------------------------------------------------------- geometry
    def flank_arrays(self, side: str, xi, eta):
        """(r, r_xi, r_eta, n) of the flank of ``side`` at (xi, eta), body frame
        (coast turned into this tooth); derivatives per unit xi / eta, mm."""
        flank = self._flank(side)
        u, v = self.flank_parameters(side, xi, eta)
        s = flank.evaluate(u, v, second=False)
        du = 0.5 * (self.u_span_mm[1] - self.u_span_mm[0])
        dv = 0.5 * (flank.v_range[1] - flank.v_range[0])
        vecs = (s.r, s.r_v * dv, s.r_u * du, s.n)
        if side == "coast":
            vecs = tuple(a @ self.coast_turn.T for a in vecs)
        return vecs

    def side_points(self, xi, eta):
        return self.flank_arrays("coast", xi, eta)[0], self.flank_arrays("drive", xi, eta)[0]

    def mid_surface(self, xi, eta) -> MidSurfaceArrays:
        xi, eta = np.broadcast_arrays(np.asarray(xi, float), np.asarray(eta, float))
        rd, rd_xi, rd_eta, nd = self.flank_arrays("drive", xi, eta)
        rc, rc_xi, rc_eta, _ = self.flank_arrays("coast", xi, eta)
        x_xi, x_eta = 0.5 * (rd_xi + rc_xi), 0.5 * (rd_eta + rc_eta)
        m = np.cross(x_xi, x_eta)
        m /= np.linalg.norm(m, axis=-1, keepdims=True)
        # m points coast -> drive: along the drive flank's outward normal (not along the
        # chord, which reverses where the flanks cross and would hide a negative thickness)
        m *= np.sign(np.einsum("...i,...i->...", m, nd))[..., None]
        chord = rd - rc
        t = np.einsum("...i,...i->...", chord, m)
        t = check_array_finite(f"{self.member} tooth thickness (mm)", t)
        if np.any(t <= 0.0):
            raise InputRangeError(f"{self.member} tooth thickness (mm)", float(t.min()),
                                  "> 0 (the drive and coast flanks must not cross)")
        return MidSurfaceArrays(position_mm=0.5 * (rd + rc), x_xi=x_xi, x_eta=x_eta,
                                normal=m, thickness_mm=t)

    def flank_points(self, side: str, u, v) -> LoadPoints:
        """Load points at flank parameters (u, v) (mm) of ``side``: unit load along the
        inward flank normal, deflection measured along it."""
        u, v = (np.atleast_1d(np.asarray(a, float)) for a in (u, v))
        xi, eta = self.tooth_coordinates(side, u, v)
        return self.points_at(side, xi, eta)

    def points_at(self, side: str, xi, eta) -> LoadPoints:
        """Load points on the flank of ``side`` at tooth coordinates (xi, eta)."""
        xi, eta = (np.atleast_1d(np.asarray(a, float)) for a in (xi, eta))
        r, _, _, n = self.flank_arrays(side, xi, eta)
        mid = self.mid_surface(xi, eta)
        off = np.einsum("...i,...i->...", r - mid.position_mm, mid.normal)
        return LoadPoints(xi=xi, eta=eta, direction=-n, offset_mm=off, position_mm=r)


def axis_rotation(axis: np.ndarray, angle_rad: float) -> np.ndarray:
    """Rotation matrix about the unit ``axis`` by ``angle_rad`` (Rodrigues)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(angle_rad) * k + (1.0 - np.cos(angle_rad)) * (k @ k)


def tooth_geometry(flanks: FlankSet, member: str, *, material: Material) -> ToothGeometry:
    """The :class:`ToothGeometry` of one tooth of ``member`` ("pinion" | "gear").

    The coast flank is turned by 0 or +-1 pitch about the member axis (pinion body
    frame: axis x; gear: axis z), whichever puts the two flanks behind each other's
    outward normal at the mid-point with the smallest gap (one tooth, not a slot).
    """
    if member not in ("pinion", "gear"):
        raise InputRangeError("member", member, "'pinion' or 'gear'")
    drive, coast = flanks.flank(member, "drive"), flanks.flank(member, "coast")
    blank = flanks.blank
    axis = np.array([1.0, 0.0, 0.0]) if member == "pinion" else np.array([0.0, 0.0, 1.0])
    teeth = blank.pinion_teeth if member == "pinion" else blank.gear_teeth
    u_span = (max(drive.u_range[0], coast.u_range[0]), min(drive.u_range[1], coast.u_range[1]))
    if not u_span[1] > u_span[0]:
        raise InputRangeError(f"{member} flank heights (mm)", u_span, "an overlapping u box")
    best = None
    for k in (0, 1, -1):
        turn = axis_rotation(axis, 2.0 * np.pi * k / teeth)
        tooth = ToothGeometry(member=member, drive=drive, coast=coast, coast_turn=turn,
                              u_span_mm=u_span, axis=axis, teeth=teeth, material=material)
        rd, _, _, nd = tooth.flank_arrays("drive", 0.0, 0.0)
        rc, _, _, nc = tooth.flank_arrays("coast", 0.0, 0.0)
        gap = float(np.linalg.norm(rd - rc))
        if nd @ (rc - rd) < 0.0 and nc @ (rd - rc) < 0.0 and (best is None or gap < best[0]):
            best = (gap, tooth)
    if best is None:
        raise InputRangeError(f"{member} flanks", "drive/coast", "flanks bounding one tooth")
    return best[1]
