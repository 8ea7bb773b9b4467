"""Formate gear flanks and the flank set of a pair (the geometry -> TCA contract).

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

The pinion flanks are the numerical conjugates of these (:mod:`.conjugate`) with the
pair's ease-off (:mod:`.easeoff`). :func:`build_flanks` returns all four flanks as a
:class:`FlankSet`; its layout is what TCA consumes.

Sides: ``"drive"`` = gear convex / pinion concave (the pinion pushes the gear when the
gear turns towards -z, phi2 decreasing); ``"coast"`` = gear concave / pinion convex.
Body frames and poses: :mod:`.kinematics`; at phi1 = phi2 = 0 the gear slot and the
pinion tooth are centred on the mean point P.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 21
(formate hypoid gears), ch. 6 (envelopes), ch. 9 (TCA inputs).
ISO 23509:2016 (blank data).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..validation import InputRangeError
from .blank import BlankDesign
from .cutter import BladeCone, CutterPlacement, place_cutter
from .kinematics import MeshKinematics
from .sampling import FlankGrid, SurfaceArrays, point_from_arrays, sample_grid
from .surface import SurfacePoint

__all__ = ["SIDES", "FlankBoundary", "FormateFlank", "MemberFlanks", "FlankSet",
           "build_flanks", "gear_flank"]

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

    def evaluate(self, u, v) -> SurfaceArrays:
        """Vectorized exact evaluation at arrays ``u``, ``v`` (broadcast)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        h, th = self.blade_parameters(u, v)
        b = self.blade.evaluate(h, th)
        kv = self._kv
        return SurfaceArrays(u=u, v=v, r=b.x, r_u=-b.x_h, r_v=kv * b.x_t,
                             r_uu=np.zeros_like(b.x), r_uv=-kv * b.x_ht, r_vv=kv * kv * b.x_tt,
                             n=b.n)

    def point(self, u: float, v: float) -> SurfacePoint:
        """Exact :class:`SurfacePoint` at (u, v)."""
        return point_from_arrays(self.evaluate(u, v))

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


def gear_flank(blank: BlankDesign, blade: BladeCone, *, side: str, gear_face_width_mm: float,
               edge_radius_mm: float) -> FormateFlank:
    """Build the gear flank of one blade with its boundary (see module docstring)."""
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
            raise InputRangeError("design.gear_face_width_mm", gear_face_width_mm,
                                  "a face width whose ends the cutter circle reaches") from None
    alpha = np.radians(blade.pressure_angle_deg)
    u_root = edge_radius_mm * (1.0 - np.sin(alpha))
    u_tip = blank.dedendum_gear_mm + blank.addendum_gear_mm
    return FormateFlank(side=side, blade=blade, dedendum_mm=blank.dedendum_gear_mm,
                        boundary=FlankBoundary(u_root=float(u_root), u_tip=float(u_tip),
                                               v_toe=float(ends[0]), v_heel=float(ends[1])))


@dataclass(frozen=True, eq=False)
class MemberFlanks:
    """The drive and coast flanks of one member (each a Surface in its body frame)."""

    drive: object
    coast: object

    def side(self, side: str):
        """The flank of ``side`` ("drive" or "coast")."""
        if side not in SIDES:
            raise InputRangeError("side", side, f"one of {SIDES}")
        return getattr(self, side)


@dataclass(frozen=True, eq=False)
class FlankSet:
    """All flanks of a pair: what TCA consumes.

    Attributes
    ----------
    blank : BlankDesign
    kinematics : MeshKinematics
        Nominal (generating) kinematics; TCA applies the pair's assembly errors itself
        (``pair.kinematics()``).
    cutter : CutterPlacement
    gear : MemberFlanks
        Formate gear flanks (:class:`FormateFlank`), gear body frame.
    pinion : MemberFlanks
        Pinion flanks with the pair's ease-off (:class:`~.sheet.RadialSheet`), pinion
        body frame.
    pinion_conjugate : MemberFlanks
        The exactly conjugate pinion flanks (no ease-off), for reference and tests.
    mean_contact : dict
        Per side: ``{"gear_uv": (u2, v2), "pinion_uv": (u1, v1), "phi2_rad": phi2}`` -
        the conjugate contact at the pinion's mean node, a starting guess for TCA.
    """

    blank: BlankDesign
    kinematics: MeshKinematics
    cutter: CutterPlacement
    gear: MemberFlanks
    pinion: MemberFlanks
    pinion_conjugate: MemberFlanks
    mean_contact: dict

    def flank(self, member: str, side: str):
        """Flank of ``member`` ("gear" | "pinion") and ``side`` ("drive" | "coast")."""
        if member not in ("gear", "pinion"):
            raise InputRangeError("member", member, "'gear' or 'pinion'")
        return getattr(self, member).side(side)

    def grid(self, member: str, side: str, n_u: int, n_v: int) -> FlankGrid:
        """Sample a flank on an n_u x n_v grid (16 x 22, 120 x 150, ...)."""
        return sample_grid(self.flank(member, side), n_u, n_v)


def build_flanks(pair, *, n_u: int = 120, n_v: int = 150) -> FlankSet:
    """Generate all flanks of ``pair``: formate gear, conjugate pinion, ease-off.

    Parameters
    ----------
    pair : GearPair
        The pair (blank design, cutter, ease-off coefficients).
    n_u, n_v : int
        Size of the dense exact pinion grid (profile x lengthwise) behind the quintic
        spline interpolant of the pinion flanks (default 120 x 150).

    Returns
    -------
    FlankSet

    Raises
    ------
    InputRangeError
        For impossible cutters or an undercut / limit-line violation on a pinion flank
        (:class:`~.conjugate.UndercutError`).
    """
    from .conjugate import conjugate_pinion_flank
    from .easeoff import EaseOff, apply_easeoff

    blank = pair.blank
    kin = pair.kinematics(with_errors=False)
    placement, inside, outside = place_cutter(blank, point_width_mm=pair.cutter.point_width_mm)
    gear = {side: gear_flank(blank, blade, side=side, gear_face_width_mm=pair.gear_face_width_mm,
                             edge_radius_mm=pair.cutter.edge_radius_mm)
            for side, blade in zip(SIDES, (inside, outside))}
    conj, eased, mean = {}, {}, {}
    for side in SIDES:
        conj[side], mean[side] = conjugate_pinion_flank(
            gear[side], blank=blank, kinematics=kin,
            pinion_face_width_mm=pair.pinion_face_width_mm, n_u=n_u, n_v=n_v)
        coeffs = pair.easeoff_drive if side == "drive" else pair.easeoff_coast
        eased[side] = apply_easeoff(conj[side], EaseOff.from_coefficients(
            coeffs, u_mean_mm=mean[side]["pinion_uv"][0], v_mean_mm=mean[side]["pinion_uv"][1]))
    return FlankSet(blank=blank, kinematics=kin, cutter=placement,
                    gear=MemberFlanks(**gear), pinion=MemberFlanks(**eased),
                    pinion_conjugate=MemberFlanks(**conj), mean_contact=mean)
