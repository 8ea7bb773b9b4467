"""The trochoid the basic rack's tip rounding generates in a gear's transverse section,
and where it undercuts the involute.

The rack (ISO 53: dedendum ``h_fP* m_n``, tip radius ``ρ_fP = ρ_fP* m_n``, its datum line
``x m_n`` out from the generating pitch circle of radius ``r = d/2``) translates by s
while the gear turns by s / r. A point of the tip rounding with normal angle τ (normal
section; an ellipse of semi-axes ρ_fP / cos β and ρ_fP in the transverse one) is in
contact when its normal passes through the pitch point (Willis):
``s(τ) = (P_y - r) N_x / N_y - P_x`` and the fillet is ``G(τ) = Rot(s / r) (P + s x̂)``
(:func:`tip_envelope`; :mod:`.fillet` makes the surface of it).

**Undercut.** The straight rack flank ends ``h_FfP = (h_fP* - ρ_fP* (1 - sin α_n)) m_n``
below the datum line. It generates the involute down to the form circle as long as its
end meets the transverse line of action on the pitch point's side of the interference
point T (the base circle's tangency point), ``h_FfP - x m_n <= r sin² α_t``, i.e.
``x >= x_min`` (:func:`undercut_limit_profile_shift`)::

    x_min = h_fP* - ρ_fP* (1 - sin α_n) - z sin² α_t / (2 cos β)

(ISO 21771:2007, the undercut limit, with the rack's h_FfP*; for the ISO 53 profile A
rack, h_fP* = 1.25, ρ_fP* = 0.38, α_n = 20°: h_FfP* = 1 - 3.2e-5 ≈ h_aP*, and the spur
pinion's ``x_min = 1 - z sin² α / 2``, z_min = 2 / sin² 20° = 17.1: Niemann / Winter
vol. II ch. 21). Below it the rounding's envelope runs into the tooth: it crosses the
involute at a roll length u* > 0 above the base circle, goes on through the tooth space
in a loop and joins the straight flank's envelope, the involute's second branch (the one
below T, in the space), at τ = -α_n. What the rack leaves is the trochoid from the root
up to the crossing and the involute from the crossing up (:func:`undercut_crossing`);
the loop and the involute below the crossing are cut away.

References
----------
ISO 21771:2007, *Cylindrical involute gears and gear pairs — Concepts and geometry*,
clauses 4-5 (the gear: form circle, undercut limit).
ISO 53:1998, *Cylindrical gears — Standard basic rack tooth profile*.
G. Niemann, H. Winter, *Maschinenelemente* Band II, 2nd ed., Springer, 1989, ch. 21
(undercut limit, z_min = 2 h_aP* cos β / sin² α_t).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 10
(undercutting of a rack-generated gear, the fillet's envelope).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import CheckFailed

__all__ = ["CUT_RESOLUTION_RAD", "GeneratedForm", "RackTip", "UndercutCrossing",
           "generated_form", "rack_tip", "tip_envelope",
           "undercut_crossing", "undercut_limit_profile_shift"]

#: Samples of the rounding's normal angle to bracket the crossing, over the arc of the
#: trochoid outside the base circle (down to a few micrometres of arc near the limit).
_TAU_SAMPLES = 4001
#: Least angle (rad) by which the trochoid must run into the tooth to be a cut: ~50 times
#: the round-off of the polar angles (arctan2, inv), 1e-13 mm on a 10 mm radius. The cut
#: grows as (x_min - x)^3: 2e-11 rad at 1e-3 below x_min (z = 12), 2e-14 at 1e-4.
CUT_RESOLUTION_RAD = 1e-14


def undercut_limit_profile_shift(*, teeth: int, normal_pressure_angle_deg: float,
                                 helix_angle_deg: float, dedendum_factor: float,
                                 tip_radius_factor: float) -> float:
    """The smallest profile shift without undercut (module docstring),
    ``x_min = h_FfP* - z sin² α_t / (2 cos β)``; undercut exactly when ``x < x_min``."""
    alpha_n = math.radians(normal_pressure_angle_deg)
    beta = math.radians(helix_angle_deg)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    h = dedendum_factor - tip_radius_factor * (1.0 - math.sin(alpha_n))     # h_FfP*
    return h - teeth * math.sin(alpha_t) ** 2 / (2.0 * math.cos(beta))


@dataclass(frozen=True)
class RackTip:
    """The rack's tip rounding in the frame of :func:`tip_envelope` (lengths mm)."""

    reference_radius_mm: float          # r = d/2, the generating pitch circle
    datum_mm: float                     # rack datum line radius r + x m_n
    tip_line_mm: float                  # rack tip line r + x m_n - h_fP = d_f / 2
    centre_x_mm: float                  # rounding centre, normal section
    centre_y_mm: float
    tip_radius_mm: float                # ρ_fP
    cos_beta: float
    space_angle_rad: float              # body-frame turn of the local frame


def rack_tip(*, teeth: int, normal_module_mm: float, profile_shift: float,
             normal_pressure_angle_deg: float, helix_angle_deg: float,
             dedendum_factor: float, tip_radius_factor: float) -> RackTip:
    """The rounding of the rack tooth filling the space beside the tooth on +x."""
    m_n = normal_module_mm
    alpha_n = math.radians(normal_pressure_angle_deg)
    beta = math.radians(helix_angle_deg)
    r = 0.5 * (teeth * (m_n / math.cos(beta)))     # d/2 = z m_t / 2 as ISO 21771
    rho = tip_radius_factor * m_n
    datum = r + profile_shift * m_n
    tip = datum - dedendum_factor * m_n
    cy = tip + rho
    # rack tooth (filling the space) centred on X = 0: right flank x = π m_n/4 -
    # (datum - y) tan α_n; the rounding's centre lies ρ inside it
    cx = 0.25 * math.pi * m_n - (datum - cy) * math.tan(alpha_n) - rho / math.cos(alpha_n)
    # local frame: the space centred on +Y, its right wall the ccw flank of the tooth at
    # angle π/2 - π/z; turned so that the tooth sits on +x
    return RackTip(reference_radius_mm=r, datum_mm=datum, tip_line_mm=tip, centre_x_mm=cx,
                   centre_y_mm=cy, tip_radius_mm=rho, cos_beta=math.cos(beta),
                   space_angle_rad=-(0.5 * math.pi - math.pi / teeth))


def tip_envelope(rack: RackTip, tau):
    """The ccw-facing transverse section of the fillet (before any mirror) at the
    rounding's normal angles ``tau`` (rad): G, dG/dτ, d2G/dτ2, each (..., 2), mm."""
    tau = np.asarray(tau, dtype=float)
    rho, cb, r = rack.tip_radius_mm, rack.cos_beta, rack.reference_radius_mm
    c, sn = np.cos(tau), np.sin(tau)
    px, py = (rack.centre_x_mm + rho * c) / cb, rack.centre_y_mm + rho * sn
    px1, py1 = -rho * sn / cb, rho * c
    px2, py2 = -rho * c / cb, -rho * sn
    cot, csc2 = c / sn, 1.0 / sn ** 2
    # rack displacement of contact: the normal through the pitch point (Willis)
    s = (py - r) * cb * cot - px
    s1 = py1 * cb * cot - (py - r) * cb * csc2 - px1
    s2 = py2 * cb * cot - 2.0 * py1 * cb * csc2 + 2.0 * (py - r) * cb * csc2 * cot - px2
    q = np.stack([px + s, py], axis=-1)
    q1 = np.stack([px1 + s1, py1], axis=-1)
    q2 = np.stack([px2 + s2, py2], axis=-1)
    phi = s / r + rack.space_angle_rad
    f1, f2 = (s1 / r)[..., None], (s2 / r)[..., None]

    def turn(a):        # Rot(phi) a
        return np.stack([np.cos(phi) * a[..., 0] - np.sin(phi) * a[..., 1],
                         np.sin(phi) * a[..., 0] + np.cos(phi) * a[..., 1]], axis=-1)

    def perp(a):        # J a = (-a_y, a_x)
        return np.stack([-a[..., 1], a[..., 0]], axis=-1)

    # G = Rot(phi) q; G' = Rot(q' + phi' J q); G'' = Rot(q'' + 2 phi' J q'
    # + phi'' J q - phi'^2 q)
    return (turn(q), turn(q1 + f1 * perp(q)),
            turn(q2 + 2.0 * f1 * perp(q1) + f2 * perp(q) - f1 * f1 * q))


@dataclass(frozen=True)
class UndercutCrossing:
    """Where the undercut trochoid crosses the involute (module docstring).

    Attributes
    ----------
    tau_rad : float
        The rounding's normal angle at the crossing: the retained fillet is
        ``[-π/2, tau_rad]``.
    roll_mm : float
        The involute's roll length there, u* > 0 (its new start), mm.
    diameter_mm : float
        The diameter of the crossing, 2 sqrt(r_b² + u*²): the form diameter d_Ff, mm.
    """

    tau_rad: float
    roll_mm: float
    diameter_mm: float


def undercut_crossing(rack: RackTip, *, base_radius_mm: float, half_angle_rad: float,
                      normal_pressure_angle_rad: float) -> UndercutCrossing | None:
    """The crossing of the (undercut) trochoid of ``rack`` with the involute whose polar
    angle on the radius R is ``half_angle_rad - inv(arccos(r_b / R))`` (the tooth's ccw
    flank, the tooth on +x), or None where the trochoid runs into the tooth by no more
    than :data:`CUT_RESOLUTION_RAD` (x within ~1e-4 of x_min: a cut below 1e-12 mm).

    The polar angle of the trochoid minus the involute's at the same radius, sampled
    over the trochoid's arc outside the base circle, is least inside the tooth; the
    crossing is its first sign change after that least value (then Brent to 1e-15 rad).
    """
    rb = base_radius_mm

    def radius(tau):
        g, _, _ = tip_envelope(rack, tau)
        return np.hypot(g[..., 0], g[..., 1])

    def gap(tau):
        g, _, _ = tip_envelope(rack, tau)
        a = np.arccos(np.minimum(rb / np.hypot(g[..., 0], g[..., 1]), 1.0))
        return np.arctan2(g[..., 1], g[..., 0]) - (half_angle_rad - (np.tan(a) - a))

    def solve(fun, lo, hi):
        from scipy.optimize import brentq   # lazy: reading a pair loads no solver
        return brentq(lambda t: float(fun(np.array([t]))[0]), lo, hi, xtol=1e-15,
                      rtol=4.0 * np.finfo(float).eps, maxiter=200)

    # near the limit the crossing lies micrometres above the base circle: sample only
    # the arc of the trochoid outside it, from where it last rises through r_b
    tau = np.linspace(-0.5 * math.pi, -normal_pressure_angle_rad, _TAU_SAMPLES)
    inside = np.nonzero(radius(tau) <= rb)[0]
    if inside.size and inside[-1] < tau.size - 1:
        j = int(inside[-1])
        lo = solve(lambda t: radius(t) - rb, tau[j], tau[j + 1])
        tau = np.linspace(lo, -normal_pressure_angle_rad, _TAU_SAMPLES)[1:]
    f = gap(tau)
    deepest = int(np.argmin(f))
    if not f[deepest] < -CUT_RESOLUTION_RAD:
        return None
    up = np.nonzero(f[deepest:] >= 0.0)[0]
    if up.size == 0:
        raise CheckFailed("the undercut trochoid does not leave the tooth again before "
                          "the rack's straight flank (no crossing with the involute)")
    i = deepest + int(up[0]) - 1
    t = solve(gap, tau[i], tau[i + 1])
    rad = float(radius(np.array([t]))[0])
    return UndercutCrossing(tau_rad=float(t), roll_mm=math.sqrt(rad * rad - rb * rb),
                            diameter_mm=2.0 * rad)


@dataclass(frozen=True)
class GeneratedForm:
    """What the rack leaves of one member's flank (module docstring).

    Attributes
    ----------
    rack : RackTip
    undercut : bool
        ``x < x_min`` (:func:`undercut_limit_profile_shift`).
    form_diameter_mm : float
        d_Ff: the lowest point of the involute, the straight flank's end or, undercut,
        the trochoid's crossing with the involute, mm.
    fillet_end_rad : float
        The rounding's normal angle where the retained fillet ends: -α_n, or the
        crossing's.
    crossing : UndercutCrossing or None
        The crossing (None without undercut, or a cut below :data:`CUT_RESOLUTION_RAD`,
        where the fillet keeps its junction with the straight flank's envelope).
    """

    rack: RackTip
    undercut: bool
    form_diameter_mm: float
    fillet_end_rad: float
    crossing: UndercutCrossing | None


def generated_form(*, teeth: int, normal_module_mm: float, profile_shift: float,
                   normal_pressure_angle_deg: float, helix_angle_deg: float,
                   dedendum_factor: float, tip_radius_factor: float) -> GeneratedForm:
    """The form circle and the fillet's end of a member generated by the basic rack.

    Without undercut the straight flank's end, ``(h_FfP* - x) m_n`` below the generating
    pitch line, touches the gear on the transverse line of action that height over
    sin α_t from the pitch point: roll length ``r sin α_t - (h_FfP* - x) m_n / sin α_t``
    (>= 0 exactly when ``x >= x_min``; Niemann / Winter ch. 21)."""
    m_n, z, x = normal_module_mm, teeth, profile_shift
    alpha_n = math.radians(normal_pressure_angle_deg)
    beta = math.radians(helix_angle_deg)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    rack = rack_tip(teeth=z, normal_module_mm=m_n, profile_shift=x,
                    normal_pressure_angle_deg=normal_pressure_angle_deg,
                    helix_angle_deg=helix_angle_deg, dedendum_factor=dedendum_factor,
                    tip_radius_factor=tip_radius_factor)
    r = rack.reference_radius_mm
    rb = r * math.cos(alpha_t)
    h = m_n * (dedendum_factor - x - tip_radius_factor * (1.0 - math.sin(alpha_n)))
    along = r * math.sin(alpha_t) - h / math.sin(alpha_t)
    junction = 2.0 * math.hypot(rb, along)
    if along >= 0.0:
        return GeneratedForm(rack, False, junction, -alpha_n, None)
    inv_t = math.tan(alpha_t) - alpha_t
    crossing = undercut_crossing(rack, base_radius_mm=rb,
                                 half_angle_rad=(0.5 * math.pi + 2.0 * x * math.tan(alpha_n))
                                 / z + inv_t, normal_pressure_angle_rad=alpha_n)
    if crossing is None:
        return GeneratedForm(rack, True, junction, -alpha_n, None)
    return GeneratedForm(rack, True, crossing.diameter_mm, crossing.tau_rad, crossing)
