"""Involute-helicoid flanks of a cylindrical gear with micro-geometry (exact, closed form).

Body frame of a member: z along its axis (origin mid-face), the tooth under study
centred on the +x axis at z = 0. A flank is the surface ``r(u, v)`` of the
:class:`~gearcontact.geometry.surface.Surface` contract with

- ``u`` the roll length, mm: the distance along the transverse line of action from the
  base tangency point, ``u = sqrt(r^2 - r_b^2)``, equal to the radius of curvature of
  the transverse involute (root -> tip: form circle to tip circle);
- ``v`` the axial position z, mm, over the member's face width.

With ``e(ψ) = (cos ψ, sin ψ, 0)``, ``f(ψ) = (sin ψ, -cos ψ, 0)`` and
``ψ = θ0 + k v + u / r_b`` the unmodified flank facing clockwise is
``X = r_b e(ψ) + u f(ψ) + v ẑ``: the involute of the base circle unwound from the
angle ``θ0 + k v``, ``k = tan β_b / r_b`` (> 0 right hand). Its unit normal out of the
tooth is ``cos β_b f(ψ) + sin β_b ẑ``, constant along the generators (the straight
lines of the plane of action). The flank facing counter-clockwise is its mirror image
``y -> -y`` of the opposite hand. Micro-geometry removes material along ``f`` (the
transverse line of action, ISO 1328-1's direction of profile and helix deviations):
``r = X - δ(u, v) f(ψ)`` (the normal amount is ``δ cos β_b``), with

- tip relief ``C_a ((u - u_Ca)/(u_a - u_Ca))^2`` above the start roll length u_Ca,
- root relief ``C_f ((u_L - u)/(u_L - u_Nf))^2`` below the lowest point of single
  contact ``u_L = u_a - p_bt``,
- profile crowning ``C_α ((u - u_m)/(g_α/2))^2`` about the middle of the active
  profile ``u_m = (u_Nf + u_a)/2``,
- lead crowning ``C_β (2 v / b)^2`` and helix slope ``f_Hβ v / b``.

Every derivative up to second order is closed form (docs/cylindrical.md).

References
----------
ISO 21771:2007, clauses 4.3-4.4 (involute helicoid, base helix), 6 (modifications).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 14
(involute helicoids, developable; normal curvature ``cos β_b / ρ_t``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...validation import InputRangeError
from ..sampling import SurfaceArrays, point_from_arrays
from ..surface import SurfacePoint
from .iso21771 import inv
from .pair import CylindricalPair

__all__ = ["FACINGS", "ProfileLeadModification", "InvoluteFlank", "involute_flank"]

#: Flank facings: the rotation sense the flank's outward normal points to, seen from +z
#: (a member turning counter-clockwise drives with its "ccw" flanks).
FACINGS = ("cw", "ccw")


@dataclass(frozen=True)
class ProfileLeadModification:
    """Material removed ``δ(u, v) = P(u) + L(v)`` (mm) along the transverse line of
    action, the sum of the parabolic terms of the module docstring.

    Lengths in mm (roll lengths u, axial v); amounts in mm.
    """

    tip_mm: float = 0.0
    tip_start_u_mm: float = 0.0
    tip_end_u_mm: float = 1.0
    root_mm: float = 0.0
    root_end_u_mm: float = 1.0       # u_L, relief 0 above
    root_start_u_mm: float = 0.0     # u_Nf, relief root_mm there
    profile_crowning_mm: float = 0.0
    profile_middle_u_mm: float = 0.0
    profile_half_length_mm: float = 1.0
    lead_crowning_mm: float = 0.0
    slope_mm: float = 0.0
    face_width_mm: float = 1.0

    @property
    def is_zero(self) -> bool:
        return (self.tip_mm == 0.0 and self.root_mm == 0.0 and self.profile_crowning_mm == 0.0
                and self.lead_crowning_mm == 0.0 and self.slope_mm == 0.0)

    def profile(self, u):
        """P, dP/du, d2P/du2 at roll lengths ``u`` (arrays)."""
        u = np.asarray(u, dtype=float)
        p, p1, p2 = (np.zeros_like(u) for _ in range(3))
        if self.tip_mm:
            length = self.tip_end_u_mm - self.tip_start_u_mm
            s = np.maximum(u - self.tip_start_u_mm, 0.0) / length
            c = self.tip_mm
            p, p1 = p + c * s * s, p1 + 2.0 * c * s / length
            p2 = p2 + np.where(u > self.tip_start_u_mm, 2.0 * c / length ** 2, 0.0)
        if self.root_mm:
            length = self.root_end_u_mm - self.root_start_u_mm
            s = np.maximum(self.root_end_u_mm - u, 0.0) / length
            c = self.root_mm
            p, p1 = p + c * s * s, p1 - 2.0 * c * s / length
            p2 = p2 + np.where(u < self.root_end_u_mm, 2.0 * c / length ** 2, 0.0)
        if self.profile_crowning_mm:
            h = self.profile_half_length_mm
            s = (u - self.profile_middle_u_mm) / h
            c = self.profile_crowning_mm
            p, p1, p2 = p + c * s * s, p1 + 2.0 * c * s / h, p2 + 2.0 * c / h ** 2
        return p, p1, p2

    def lead(self, v):
        """L, dL/dv, d2L/dv2 at axial positions ``v`` (arrays)."""
        v = np.asarray(v, dtype=float)
        b = self.face_width_mm
        c = self.lead_crowning_mm
        lead = c * (2.0 * v / b) ** 2 + self.slope_mm * v / b
        return lead, 8.0 * c * v / b ** 2 + self.slope_mm / b, np.full_like(v, 8.0 * c / b ** 2)


@dataclass(frozen=True)
class InvoluteFlank:
    """One flank of a cylindrical gear tooth: an involute helicoid with micro-geometry.

    Parameters
    ----------
    base_radius_mm : float
        r_b, mm.
    lead_rate_rad_per_mm : float
        k = ± tan β_b / r_b of the flank facing clockwise (before the mirror), rad/mm.
    start_angle_rad : float
        θ0: the angle of the base-circle point the involute of the section z = 0
        unwinds from (before the mirror), rad.
    facing : str
        "cw" or "ccw" (:data:`FACINGS`); "ccw" is the mirror image y -> -y.
    u_range, v_range : tuple of float
        Roll-length range (form circle to tip) and axial range (face width), mm.
    modification : ProfileLeadModification
    """

    base_radius_mm: float
    lead_rate_rad_per_mm: float
    start_angle_rad: float
    facing: str
    u_range: tuple[float, float]
    v_range: tuple[float, float]
    modification: ProfileLeadModification = ProfileLeadModification()

    def evaluate(self, u, v, *, second: bool = True) -> SurfaceArrays:
        """Position, first and second derivatives and unit normal at arrays (u, v)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        rb, k = self.base_radius_mm, self.lead_rate_rad_per_mm
        psi = self.start_angle_rad + k * v + u / rb
        c, s = np.cos(psi), np.sin(psi)
        zero, one = np.zeros_like(u), np.ones_like(u)
        e = np.stack([c, s, zero], axis=-1)
        f = np.stack([s, -c, zero], axis=-1)
        z = np.stack([zero, zero, one], axis=-1)
        U, K = u[..., None], k
        # unmodified helicoid X = rb e + u f + v z (e' = -f, f' = e in ψ)
        x = rb * e + U * f + v[..., None] * z
        x_u = (U / rb) * e
        x_v = K * (U * e - rb * f) + z
        x_uu = e / rb - (U / rb ** 2) * f
        x_uv = -(U * K / rb) * f
        x_vv = -K * K * (rb * e + U * f)
        mod = self.modification
        if mod.is_zero:
            r, r_u, r_v, r_uu, r_uv, r_vv = x, x_u, x_v, x_uu, x_uv, x_vv
        else:
            p, p1, p2 = mod.profile(u)
            q, q1, q2 = mod.lead(v)
            d, du, dv = (p + q)[..., None], p1[..., None], q1[..., None]
            duu, dvv = p2[..., None], q2[..., None]
            # f_u = e / rb, f_v = k e, f_uu = -f / rb^2, f_uv = -k f / rb, f_vv = -k^2 f
            r = x - d * f
            r_u = x_u - du * f - d * e / rb
            r_v = x_v - dv * f - d * K * e
            r_uu = x_uu - duu * f - 2.0 * du * e / rb + d * f / rb ** 2
            r_uv = x_uv - dv * e / rb - du * K * e + d * K * f / rb
            r_vv = x_vv - dvv * f - 2.0 * dv * K * e + d * K * K * f
        n = np.cross(r_u, r_v)
        n = n / np.linalg.norm(n, axis=-1, keepdims=True)
        out = [r, r_u, r_v, r_uu, r_uv, r_vv, n]
        if self.facing == "ccw":
            flip = np.array([1.0, -1.0, 1.0])
            out = [a * flip for a in out]
        if not second:
            out[3:6] = [np.full_like(r, np.nan)] * 3
        return SurfaceArrays(u, v, *out)

    def point(self, u: float, v: float) -> SurfacePoint:
        """The :class:`~gearcontact.geometry.surface.SurfacePoint` at (u, v)."""
        return point_from_arrays(self.evaluate(u, v))

    def transverse_radius_of_curvature_mm(self, u):
        """ρ_t = u of the unmodified involute (mm): ``sqrt(r^2 - r_b^2)``."""
        return np.asarray(u, dtype=float)

    def analytic_curvatures(self, u):
        """Principal curvatures (1/mm, ascending) of the unmodified helicoid at roll
        length ``u``: ``(-cos β_b / u, 0)`` (convex across, straight generators)."""
        cos_bb = 1.0 / math.sqrt(1.0 + (self.lead_rate_rad_per_mm * self.base_radius_mm) ** 2)
        u = np.asarray(u, dtype=float)
        return np.stack([-cos_bb / u, np.zeros_like(u)], axis=-1)


def involute_flank(pair: CylindricalPair, member: str, facing: str) -> InvoluteFlank:
    """The ``facing`` flank of the ``member`` tooth centred on +x at z = 0.

    Parameters
    ----------
    pair : CylindricalPair
    member : str
        "pinion" or "gear".
    facing : str
        "cw" or "ccw".

    Returns
    -------
    InvoluteFlank
        ``u`` from the form circle d_Ff to the tip d_a, ``v`` over the member's face.
    """
    if member not in ("pinion", "gear"):
        raise InputRangeError("member", member, "'pinion' or 'gear'")
    if facing not in FACINGS:
        raise InputRangeError("facing", facing, f"one of {FACINGS}")
    g = pair.geometry
    z = getattr(pair, f"{member}_teeth")
    x = getattr(pair, f"profile_shift_{member}")
    rb = 0.5 * getattr(g, f"base_diameter_{member}_mm")
    alpha_n = math.radians(g.normal_pressure_angle_deg)
    alpha_t = math.radians(g.transverse_pressure_angle_deg)
    beta_b = math.radians(g.base_helix_angle_deg)
    hand = pair.hand(member)
    sign = -1.0 if hand == "left" else 1.0
    k = sign * math.tan(beta_b) / rb
    if facing == "ccw":             # the mirror image of the opposite hand
        k = -k
    # half the transverse tooth thickness angle on d: s_t / d = (π/2 + 2 x tan α_n) / z;
    # the cw flank lies at -that angle on d, where the involute's polar angle is θ0 + inv α_t
    theta0 = -(0.5 * math.pi + 2.0 * x * math.tan(alpha_n)) / z - inv(alpha_t)
    rolls = g.roll_lengths_mm(member)
    b = pair.face_width_mm(member)
    mods = getattr(pair, f"modifications_{member}")
    u_nf, u_a = rolls["active_start"], rolls["tip"]
    u_low = u_a - g.transverse_base_pitch_mm
    if mods.root_relief_um and not u_low > u_nf:
        raise InputRangeError(f"modifications.{member}.root_relief_um", mods.root_relief_um,
                              "0 for a transverse contact ratio of 1 (no double contact)")
    modification = ProfileLeadModification(
        tip_mm=mods.tip_relief_um * 1e-3, tip_start_u_mm=pair.tip_relief_start_roll_mm(member),
        tip_end_u_mm=u_a, root_mm=mods.root_relief_um * 1e-3, root_end_u_mm=u_low,
        root_start_u_mm=u_nf, profile_crowning_mm=mods.profile_crowning_um * 1e-3,
        profile_middle_u_mm=0.5 * (u_nf + u_a), profile_half_length_mm=0.5 * (u_a - u_nf),
        lead_crowning_mm=mods.lead_crowning_um * 1e-3, slope_mm=mods.helix_slope_um * 1e-3,
        face_width_mm=b)
    return InvoluteFlank(base_radius_mm=rb, lead_rate_rad_per_mm=k, start_angle_rad=theta0,
                         facing=facing, u_range=(rolls["form"], u_a),
                         v_range=(-0.5 * b, 0.5 * b), modification=modification)
