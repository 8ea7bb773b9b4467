"""Face-milling cutter placement and blade cones of a formate (non-generated) gear.

The cutter axis ``a`` is normal to the gear pitch plane (the plane tangent to the gear
pitch cone along the generatrix through the mean point P; docs/geometry.md sec. 3, "first
version, pitch plane") and points into the gear body (towards the gear root). The
cutter centre C lies in the pitch plane at distance r_c0 from P, perpendicular to the
tooth trace, on the side that gives the gear the hand of the pair:

    t = cos(beta2) g2 + sin(beta2) s,   C = P + r_c0 (-sin(beta2) g2 + cos(beta2) s)

(g2: gear pitch generatrix through P pointing away from the apex; s = -e_t for the
left-hand gear of a right-hand pinion, e_t = z x e_r the gear's circumferential
direction), so that ``S_r^2 = L^2 + r_c0^2 - 2 L r_c0 sin(beta2)`` (Litvin & Fuentes
2004, sec. 21.3 (cradle radius) with L = R2).

Blade cones (h measured along ``a`` from the pitch plane, positive into the gear body;
``e_rho = cos(th) e1 + sin(th) e2``, e1 = (P - C)/r_c0, e2 = a x e1):

- inside blade (sigma = +1, cuts the gear convex flank):
  ``X = C + (rho_i + h tan(alpha_i)) e_rho + h a``,
  ``n = cos(alpha_i) e_rho - sin(alpha_i) a``
- outside blade (sigma = -1, cuts the gear concave flank):
  ``X = C + (rho_o - h tan(alpha_o)) e_rho + h a``,
  ``n = -cos(alpha_o) e_rho - sin(alpha_o) a``

with n the unit normal out of the gear tooth into the slot. The slot is centred on the
r_c0 circle in the pitch plane; its width there is ``W + h_f2 (tan alpha_i + tan alpha_o)``
so that the blade point width is W at the blade tip (h = h_f2, the gear root).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 21
(face-milled hypoid gears; blade cone surfaces and their normals).
ISO 23509:2016, clause 6 (cutter radius, spiral angle, limit pressure angle).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError
from .blank import BlankDesign

__all__ = ["CutterPlacement", "BladeCone", "BladeEval", "place_cutter"]


@dataclass(frozen=True, eq=False)
class CutterPlacement:
    """Cutter frame in the gear body frame (= meshing frame at phi2 = 0), mm.

    Attributes
    ----------
    centre_mm : ndarray (3,)
        Cutter centre C in the pitch plane.
    axis : ndarray (3,)
        Unit cutter axis a (normal to the pitch plane, into the gear body).
    e1, e2 : ndarray (3,)
        In-plane unit vectors: e1 from C towards the mean point P, e2 = a x e1.
    heel_sign : float
        +1 if increasing blade angle theta runs from toe to heel, else -1.
    """

    centre_mm: np.ndarray
    axis: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    heel_sign: float


@dataclass(frozen=True)
class BladeEval:
    """Blade-cone point, derivatives (w.r.t. h [mm] and theta [rad]) and normal; arrays (..., 3)."""

    x: np.ndarray
    x_h: np.ndarray
    x_t: np.ndarray
    x_tt: np.ndarray
    x_ht: np.ndarray
    n: np.ndarray
    n_t: np.ndarray
    rho: np.ndarray
    #: Normal derivative w.r.t. h; None for a cone (its normal is constant along h).
    n_h: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class BladeCone:
    """One blade's cone of revolution about the cutter axis.

    Parameters
    ----------
    placement : CutterPlacement
    radius_pitch_mm : float
        Blade radius rho_0 at the pitch plane (h = 0), mm.
    pressure_angle_deg : float
        Blade (= gear flank) pressure angle alpha, degrees.
    inside : bool
        True for the inside blade (gear convex flank), False for the outside blade.
    """

    placement: CutterPlacement
    radius_pitch_mm: float
    pressure_angle_deg: float
    inside: bool

    @property
    def sigma(self) -> float:
        """+1 for the inside blade, -1 for the outside blade."""
        return 1.0 if self.inside else -1.0

    def radius_mm(self, h_mm):
        """Cone radius rho(h) = rho_0 + sigma h tan(alpha), mm."""
        return self.radius_pitch_mm + self.sigma * np.asarray(h_mm) * np.tan(
            np.radians(self.pressure_angle_deg))

    def evaluate(self, h_mm, theta_rad) -> BladeEval:
        """Point, derivatives and unit normal of the cone at (h, theta) (broadcast arrays)."""
        pl = self.placement
        h = np.asarray(h_mm, dtype=float)[..., None]
        th = np.asarray(theta_rad, dtype=float)[..., None]
        alpha = np.radians(self.pressure_angle_deg)
        k = self.sigma * np.tan(alpha)
        e_rho = np.cos(th) * pl.e1 + np.sin(th) * pl.e2
        e_th = -np.sin(th) * pl.e1 + np.cos(th) * pl.e2
        rho = self.radius_pitch_mm + k * h
        x = pl.centre_mm + rho * e_rho + h * pl.axis
        n = self.sigma * np.cos(alpha) * e_rho - np.sin(alpha) * pl.axis
        return BladeEval(x=x, x_h=k * e_rho + pl.axis + 0.0 * th, x_t=rho * e_th,
                         x_tt=-rho * e_rho, x_ht=k * e_th + 0.0 * h,
                         n=n + 0.0 * h, n_t=self.sigma * np.cos(alpha) * e_th + 0.0 * h,
                         rho=rho[..., 0])


def place_cutter(blank: BlankDesign, *, point_width_mm: float) -> tuple[CutterPlacement,
                                                                         BladeCone, BladeCone]:
    """Place the cutter for the pair's blank and build its inside and outside blades.

    Parameters
    ----------
    blank : BlankDesign
        Pitch-cone design (mean point, spiral angle, cutter radius, pressure angles).
    point_width_mm : float
        Blade point width W at the blade tip, mm.

    Returns
    -------
    placement, inside, outside : CutterPlacement, BladeCone, BladeCone
        The inside blade cuts the gear convex (drive) flank with alpha_nD, the outside
        blade the concave (coast) flank with alpha_nC.

    Raises
    ------
    InputRangeError
        If the slot would be wider than the normal circular pitch (no gear tooth left).
    """
    P = np.array(blank.pitch_point_mm)
    d2 = np.radians(blank.pitch_angle_gear_deg)
    b2 = np.radians(blank.spiral_angle_gear_deg)
    rc0 = blank.cutter_radius_mm
    e_r = np.array([P[0], P[1], 0.0]) / np.hypot(P[0], P[1])
    z = np.array([0.0, 0.0, 1.0])
    e_t = np.cross(z, e_r)
    g2 = np.sin(d2) * e_r + np.cos(d2) * z
    a = -np.cos(d2) * e_r + np.sin(d2) * z
    s = -e_t  # left-hand gear (right-hand pinion), see module docstring
    m = -np.sin(b2) * g2 + np.cos(b2) * s
    C = P + rc0 * m
    e1 = -m
    e2 = np.cross(a, e1)
    heel = float(np.sign(e2 @ g2))
    placement = CutterPlacement(centre_mm=C, axis=a, e1=e1, e2=e2, heel_sign=heel)

    ai = np.radians(blank.pressure_angle_drive_deg)
    ao = np.radians(blank.pressure_angle_coast_deg)
    slot = point_width_mm + blank.dedendum_gear_mm * (np.tan(ai) + np.tan(ao))
    pitch_n = np.pi * blank.mean_normal_module_mm
    if not slot < pitch_n:
        raise InputRangeError("cutter.point_width_mm", point_width_mm,
                              f"< {pitch_n - slot + point_width_mm:.4f} mm (the slot at the "
                              f"pitch plane, {slot:.4f} mm, must be narrower than the normal "
                              f"circular pitch {pitch_n:.4f} mm)")
    inside = BladeCone(placement, rc0 - 0.5 * slot, blank.pressure_angle_drive_deg, True)
    outside = BladeCone(placement, rc0 + 0.5 * slot, blank.pressure_angle_coast_deg, False)
    return placement, inside, outside
