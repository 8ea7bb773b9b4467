"""ISO 21771 geometry of an external cylindrical (spur or helical) involute pair.

:func:`involute_geometry` computes the reference, base, tip, root and form diameters,
the working pressure angle and centre distance from the profile shift sum, the backlash
of a larger centre distance, and the contact ratios ε_α, ε_β, ε_γ (docs/cylindrical.md).

The tip diameter is ``d_a = d + 2 m_n (h_aP* + x)`` without tip shortening; the root
diameter ``d_f = d - 2 m_n (h_fP* - x)`` (generation by the basic rack of ISO 53 with
dedendum ``h_fP* m_n`` and tip radius ``ρ_fP* m_n``). The form diameter d_Ff is the
rack's (:func:`.trochoid.generated_form`): below the undercut limit x_min the trochoid's
crossing with the involute, and the path of contact of an undercut member starts there
where the mating tip would reach lower (the rack, the limiting mate, cut that space).

References
----------
ISO 21771:2007, *Gears — Cylindrical involute gears and gear pairs — Concepts and
geometry*, clauses 4-5 (the gear) and 6 (the pair).
ISO 53:1998, *Cylindrical gears — Standard basic rack tooth profile*.
G. Niemann, H. Winter, *Maschinenelemente* Band II, 2nd ed., Springer, 1989, ch. 21
(form circle of rack generation, undercut limit).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ...validation import InputRangeError, UnusableInput
from .trochoid import generated_form, undercut_limit_profile_shift
from .undercut_mesh import mating_tip_penetration_mm

__all__ = ["InvoluteGeometry", "inv", "inv_inverse", "involute_geometry", "roll_length_mm",
           "A_W_TOLERANCE_MODULES"]


#: How far (in m_n) a given centre distance may fall short of the zero-backlash one:
#: profile shifts rounded to 4 decimals move a_w0 by up to ~1e-4 m_n.
A_W_TOLERANCE_MODULES = 1e-4


def inv(alpha_rad: float) -> float:
    """The involute function inv α = tan α − α (α in rad)."""
    return math.tan(alpha_rad) - alpha_rad


def inv_inverse(value: float) -> float:
    """α in [0, π/2) with inv α = ``value`` >= 0 (Newton, to machine precision)."""
    if not value >= 0.0:
        raise InputRangeError("inv alpha", value, "a number >= 0")
    if value == 0.0:
        return 0.0
    a = min((3.0 * value) ** (1.0 / 3.0), 1.4)     # inv a ~ a^3/3 for small a
    for _ in range(60):
        t = math.tan(a)
        step = (t - a - value) / (t * t)            # d(inv a)/da = tan^2 a
        a -= step
        a = min(max(a, 1e-12), 0.5 * math.pi - 1e-9)
        if abs(step) < 1e-16 * max(1.0, a):
            break
    return a


def roll_length_mm(diameter_mm: float, base_diameter_mm: float) -> float:
    """Roll length ``sqrt(r^2 - r_b^2)`` (mm) of the involute at ``diameter_mm``: the
    distance along the transverse line of action from the base tangency point, equal to
    the radius of curvature of the transverse involute there."""
    return math.sqrt(max(0.25 * (diameter_mm ** 2 - base_diameter_mm ** 2), 0.0))


@dataclass(frozen=True)
class InvoluteGeometry:
    """ISO 21771 geometry of an external pair (lengths mm, angles deg).

    Per-member values carry ``_pinion`` / ``_gear``; see :func:`involute_geometry`.
    """

    pinion_teeth: int
    gear_teeth: int
    normal_module_mm: float
    transverse_module_mm: float
    normal_pressure_angle_deg: float
    transverse_pressure_angle_deg: float
    helix_angle_deg: float
    base_helix_angle_deg: float
    profile_shift_pinion: float
    profile_shift_gear: float
    reference_diameter_pinion_mm: float
    reference_diameter_gear_mm: float
    base_diameter_pinion_mm: float
    base_diameter_gear_mm: float
    tip_diameter_pinion_mm: float
    tip_diameter_gear_mm: float
    root_diameter_pinion_mm: float
    root_diameter_gear_mm: float
    form_diameter_pinion_mm: float          # d_Ff: lowest point of the generated involute
    form_diameter_gear_mm: float
    undercut_pinion: bool                   # x < x_min: d_Ff is the trochoid's crossing
    undercut_gear: bool
    undercut_limit_shift_pinion: float      # x_min of ISO 21771 (trochoid.py)
    undercut_limit_shift_gear: float
    active_start_diameter_pinion_mm: float  # d_Nf: start of the active profile
    active_start_diameter_gear_mm: float
    working_pitch_diameter_pinion_mm: float
    working_pitch_diameter_gear_mm: float
    tip_thickness_normal_pinion_mm: float   # s_an, normal tooth thickness on d_a
    tip_thickness_normal_gear_mm: float
    reference_centre_distance_mm: float     # a = (d1 + d2)/2
    zero_backlash_centre_distance_mm: float  # from x1 + x2, inv α_wt
    centre_distance_mm: float               # a_w in use (given, or the zero-backlash one)
    working_pressure_angle_deg: float       # α_wt at a_w
    normal_backlash_mm: float               # j_bn of a_w beyond the zero-backlash one
    tip_clearance_pinion_mm: float          # a_w - (d_a1 + d_f2)/2
    tip_clearance_gear_mm: float
    transverse_base_pitch_mm: float         # p_bt = π m_t cos α_t
    length_of_contact_mm: float             # g_α
    face_width_mm: float                    # common face width b
    transverse_contact_ratio: float         # ε_α
    overlap_ratio: float                    # ε_β
    total_contact_ratio: float              # ε_γ

    @property
    def ratio(self) -> float:
        """Gear ratio u = z2/z1."""
        return self.gear_teeth / self.pinion_teeth

    def as_dict(self) -> dict:
        """All fields (JSON-ready)."""
        return asdict(self)

    def single_contact_tip_diameter_mm(self, member: str) -> float:
        """Diameter of the member's highest point of single tooth contact, mm: the
        transverse roll length of its active start plus one base pitch,
        ``u_Nf + p_bt`` (the tip-side end of single contact for 1 <= eps_alpha < 2;
        where a "short" tip relief starts)."""
        d_b = getattr(self, f"base_diameter_{member}_mm")
        u = (roll_length_mm(getattr(self, f"active_start_diameter_{member}_mm"), d_b)
             + self.transverse_base_pitch_mm)
        return 2.0 * math.hypot(0.5 * d_b, u)

    def roll_lengths_mm(self, member: str) -> dict[str, float]:
        """Roll lengths (mm, transverse line of action from the member's base tangency
        point) at the form circle, the start of the active profile, and the tip."""
        d_b = getattr(self, f"base_diameter_{member}_mm")
        return {key: roll_length_mm(getattr(self, f"{name}_{member}_mm"), d_b)
                for key, name in (("form", "form_diameter"),
                                  ("active_start", "active_start_diameter"),
                                  ("tip", "tip_diameter"))}


def _check_mating_tip(forms, i, *, z, x, r_b, r_a, d, a_w, alpha_n, alpha_t, m_t, x_min,
                      field) -> None:
    """Raise InputRangeError if the mate's tip cuts into undercut member ``i``'s tooth
    (:func:`.undercut_mesh.mating_tip_penetration_mm`; 1e-9 mm: a tip touching the
    involute at the start of the path is ~1e-9 inside)."""
    j = 1 - i
    s_t = m_t * (0.5 * math.pi + 2.0 * x[j] * math.tan(alpha_n))
    pen = mating_tip_penetration_mm(
        forms[i], teeth=z[i], base_radius_mm=r_b[i], tip_radius_mm=r_a[i],
        half_angle_rad=(0.5 * math.pi + 2.0 * x[i] * math.tan(alpha_n)) / z[i] + inv(alpha_t),
        mate_teeth=z[j], mate_tip_radius_mm=r_a[j],
        mate_tip_half_angle_rad=s_t / d[j] + inv(alpha_t) - inv(math.acos(r_b[j] / r_a[j])),
        centre_distance_mm=a_w)
    if pen > 1e-9:
        member, mate = ("pinion", "gear")[i], ("pinion", "gear")[j]
        raise InputRangeError(field, x[i], f"a larger value (interference: the {mate} tip "
                                           f"cuts {pen:.4f} mm into the undercut {member} "
                                           f"(z = {z[i]}, x_min = {x_min:.4f}) below its form "
                                           f"circle d_Ff = {forms[i].form_diameter_mm:.4f} mm)")


def involute_geometry(*, pinion_teeth: int, gear_teeth: int, normal_module_mm: float,
                      normal_pressure_angle_deg: float, helix_angle_deg: float,
                      profile_shift_pinion: float, profile_shift_gear: float,
                      face_width_mm: float, centre_distance_mm: float | None = None,
                      addendum_factor: float = 1.0, dedendum_factor: float = 1.25,
                      tip_radius_factor: float = 0.38,
                      tip_diameter_pinion_mm: float | None = None,
                      tip_diameter_gear_mm: float | None = None,
                      field_prefix: str = "cylindrical.") -> InvoluteGeometry:
    """ISO 21771 geometry of an external pair from its (validated) inputs.

    Parameters
    ----------
    pinion_teeth, gear_teeth : int
        z1, z2.
    normal_module_mm : float
        m_n, mm.
    normal_pressure_angle_deg, helix_angle_deg : float
        α_n and β (reference cylinder), deg.
    profile_shift_pinion, profile_shift_gear : float
        x1, x2 (in units of m_n).
    face_width_mm : float
        Common face width b, mm (for ε_β).
    centre_distance_mm : float or None
        a_w; None: the zero-backlash centre distance of x1 + x2.
    addendum_factor, dedendum_factor, tip_radius_factor : float
        h_aP*, h_fP*, ρ_fP* of the basic rack.
    tip_diameter_pinion_mm, tip_diameter_gear_mm : float or None
        The blank's tip diameter d_a, mm (a drawing's value, e.g. with tip shortening);
        None: ``d + 2 m_n (h_aP* + x)``.
    field_prefix : str
        Prefix of the field names in error messages (the TOML table).

    Returns
    -------
    InvoluteGeometry

    Raises
    ------
    InputRangeError
        A centre distance below the zero-backlash one (the teeth interfere), an undercut
        cutting the whole involute (its crossing at or above d_a), pointed teeth, a tip
        touching the mating root, a mating tip reaching below the form circle of a
        member that is not undercut or cutting into the root of one that is
        (interference), named by the field that decides it.
    UnusableInput
        A transverse contact ratio ε_α < 1 (naming an undercut that shortened the path).
    """
    z1, z2, m_n = pinion_teeth, gear_teeth, normal_module_mm
    x1, x2 = profile_shift_pinion, profile_shift_gear
    alpha_n = math.radians(normal_pressure_angle_deg)
    beta = math.radians(helix_angle_deg)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    beta_b = math.asin(math.sin(beta) * math.cos(alpha_n))
    m_t = m_n / math.cos(beta)
    d1, d2 = z1 * m_t, z2 * m_t
    db1, db2 = d1 * math.cos(alpha_t), d2 * math.cos(alpha_t)
    a_ref = 0.5 * (d1 + d2)
    da1 = d1 + 2.0 * m_n * (addendum_factor + x1) if tip_diameter_pinion_mm is None \
        else tip_diameter_pinion_mm
    da2 = d2 + 2.0 * m_n * (addendum_factor + x2) if tip_diameter_gear_mm is None \
        else tip_diameter_gear_mm
    df1 = d1 - 2.0 * m_n * (dedendum_factor - x1)
    df2 = d2 - 2.0 * m_n * (dedendum_factor - x2)
    for member, df, x in (("pinion", df1, x1), ("gear", df2, x2)):
        if df <= 0.0:
            raise InputRangeError(f"{field_prefix}profile_shift_{member}", x,
                                  f"a root diameter d_f > 0 (d_f = {df:.4f} mm)")
    forms = [generated_form(teeth=z, normal_module_mm=m_n, profile_shift=x,
                            normal_pressure_angle_deg=normal_pressure_angle_deg,
                            helix_angle_deg=helix_angle_deg, dedendum_factor=dedendum_factor,
                            tip_radius_factor=tip_radius_factor) for z, x in ((z1, x1), (z2, x2))]
    (dff1, cut1), (dff2, cut2) = ((f.form_diameter_mm, f.undercut) for f in forms)
    x_min = [undercut_limit_profile_shift(
        teeth=z, normal_pressure_angle_deg=normal_pressure_angle_deg,
        helix_angle_deg=helix_angle_deg, dedendum_factor=dedendum_factor,
        tip_radius_factor=tip_radius_factor) for z in (z1, z2)]
    for member, z, x, d_a, d_ff, cut, lim in (("pinion", z1, x1, da1, dff1, cut1, x_min[0]),
                                              ("gear", z2, x2, da2, dff2, cut2, x_min[1])):
        if cut and not d_a > d_ff:
            raise InputRangeError(f"{field_prefix}profile_shift_{member}", x,
                                  f">= {lim:.4f}, the undercut limit x_min of z = {z} "
                                  f"(undercut: the trochoid of the rack's tip cuts the "
                                  f"whole involute, crossing it at d = {d_ff:.4f} mm >= "
                                  f"d_a = {d_a:.4f} mm; a usable involute needs a larger "
                                  "profile shift)")
    for member, d_a, d_ff in (("pinion", da1, dff1), ("gear", da2, dff2)):
        if not d_a > d_ff:
            raise InputRangeError(f"{field_prefix}tip_diameter_{member}_mm", d_a,
                                  f"> {d_ff:.4f} mm (the form diameter d_Ff)")
    # ISO 21771 eq. for the working pressure angle of zero backlash
    inv_wt0 = inv(alpha_t) + 2.0 * math.tan(alpha_n) * (x1 + x2) / (z1 + z2)
    if inv_wt0 < 0.0:
        low = -inv(alpha_t) * (z1 + z2) / (2.0 * math.tan(alpha_n))
        raise InputRangeError(f"{field_prefix}profile_shift_pinion + profile_shift_gear",
                              x1 + x2, f">= {low:.4f} (a zero-backlash working pressure "
                              "angle alpha_wt >= 0)")
    alpha_wt0 = inv_inverse(inv_wt0)
    a_w0 = a_ref * math.cos(alpha_t) / math.cos(alpha_wt0)
    if centre_distance_mm is None:
        a_w, alpha_wt, j_bn = a_w0, alpha_wt0, 0.0
    else:
        a_w = centre_distance_mm
        # published shifts are rounded to 4 decimals: a_w may fall short of a_w0 by up
        # to ~1e-4 m_n (FZG C: 0.08 um), a tight mesh reported as j_bn < 0
        if a_w < a_w0 - A_W_TOLERANCE_MODULES * m_n:
            raise InputRangeError(f"{field_prefix}centre_distance_mm", a_w,
                                  f">= {a_w0 - A_W_TOLERANCE_MODULES * m_n:.6f} mm (the "
                                  f"zero-backlash centre distance of x1 + x2 = {x1 + x2:g} "
                                  f"is {a_w0:.6f} mm; closer, the teeth interfere)")
        # beyond half the tip diameters' sum the tip circles do not overlap: no mesh
        if not a_w < 0.5 * (da1 + da2):
            raise InputRangeError(f"{field_prefix}centre_distance_mm", a_w,
                                  f"< {0.5 * (da1 + da2):.6f} mm, where the tip circles "
                                  f"(d_a = {da1:.4f}, {da2:.4f} mm) meet (the zero-backlash "
                                  f"centre distance of x1 + x2 = {x1 + x2:g} is "
                                  f"{a_w0:.6f} mm)")
        alpha_wt = math.acos(min(a_ref * math.cos(alpha_t) / a_w, 1.0))
        # the profile-shift sum that would close the gap at a_w, and the base-circle arc
        # (= length along the line of action) it stands for, in the normal section
        x_sum_w = (inv(alpha_wt) - inv(alpha_t)) * (z1 + z2) / (2.0 * math.tan(alpha_n))
        j_bt = 2.0 * (x_sum_w - x1 - x2) * m_n * math.tan(alpha_n) * math.cos(alpha_t) \
            / math.cos(beta)
        j_bn = j_bt * math.cos(beta_b)
    # tip thickness: s_t = m_t (π/2 + 2 x tan α_n) on d, carried to d_a by the involute
    s_an = []
    for member, d, d_b, d_a, x in (("pinion", d1, db1, da1, x1), ("gear", d2, db2, da2, x2)):
        s_t = m_t * (0.5 * math.pi + 2.0 * x * math.tan(alpha_n))
        alpha_at = math.acos(d_b / d_a)
        s_at = d_a * (s_t / d + inv(alpha_t) - inv(alpha_at))
        beta_a = math.atan(math.tan(beta) * d_a / d)
        s_an.append(s_at * math.cos(beta_a))
        if s_an[-1] <= 0.0:
            raise InputRangeError(f"{field_prefix}profile_shift_{member}", x,
                                  f"a smaller value (pointed teeth: the normal tip thickness "
                                  f"is {s_an[-1]:.4f} mm)")
    c1 = a_w - 0.5 * (da1 + df2)
    c2 = a_w - 0.5 * (da2 + df1)
    for member, c, x in (("pinion", c1, x1), ("gear", c2, x2)):
        if c <= 0.0:
            raise InputRangeError(f"{field_prefix}profile_shift_{member}", x,
                                  f"a smaller value (the {member} tip reaches the mating root: "
                                  f"tip clearance {c:.4f} mm; tip shortening is not applied)")
    # the path of contact on the transverse line of action (ISO 21771, ε_α)
    line = a_w * math.sin(alpha_wt)
    u_a1, u_a2 = roll_length_mm(da1, db1), roll_length_mm(da2, db2)
    p_bt = math.pi * m_t * math.cos(alpha_t)
    u_nf = [line - u_a2, line - u_a1]               # roll lengths of the active start
    g_alpha = u_a1 + u_a2 - line
    dnf = []
    for i, (member, d_b, d_ff, cut, other) in enumerate((("pinion", db1, dff1, cut1, "gear"),
                                                         ("gear", db2, dff2, cut2, "pinion"))):
        u_ff = roll_length_mm(d_ff, d_b)
        if cut:     # the mate's tip must pass through the space the rack's tip cut
            _check_mating_tip(forms, i, z=(z1, z2), x=(x1, x2), r_b=(0.5 * db1, 0.5 * db2),
                              r_a=(0.5 * da1, 0.5 * da2), d=(d1, d2), a_w=a_w,
                              alpha_n=alpha_n, alpha_t=alpha_t, m_t=m_t, x_min=x_min[i],
                              field=f"{field_prefix}profile_shift_{member}")
        if u_nf[i] < u_ff - 1e-9:
            if not cut:
                raise InputRangeError(f"{field_prefix}profile_shift_{member}",
                                      x1 if member == "pinion" else x2,
                                      f"a larger value (interference: the {other} tip meets "
                                      f"the {member} {u_ff - u_nf[i]:.4f} mm below its form "
                                      f"circle d_Ff = {d_ff:.4f} mm on the line of action)")
            # undercut: the mate's tip clears the cut root, contact starts at d_Ff
            g_alpha -= u_ff - u_nf[i]
            u_nf[i] = u_ff
        dnf.append(2.0 * math.hypot(0.5 * d_b, u_nf[i]))
    eps_alpha = g_alpha / p_bt
    if eps_alpha < 1.0:
        why = "".join(f"; the {m} (z = {z}, x = {x:g}) is undercut below x_min = {lim:.4f}: "
                      f"its involute starts at d_Ff = {d_ff:.4f} mm, above the mating tip's "
                      f"reach, which shortens the path (raise its profile shift toward x_min)"
                      for m, z, x, lim, d_ff, start, reach in (
                          ("pinion", z1, x1, x_min[0], dff1, u_nf[0], line - u_a2),
                          ("gear", z2, x2, x_min[1], dff2, u_nf[1], line - u_a1))
                      if start > reach)
        raise UnusableInput(f"transverse contact ratio eps_alpha = {eps_alpha:.4f} < 1 "
                            f"(length of contact {g_alpha:.4f} mm, base pitch {p_bt:.4f} mm): "
                            f"raise the addendum factor or lower the centre distance{why}")
    eps_beta = face_width_mm * math.sin(beta) / (math.pi * m_n)
    return InvoluteGeometry(
        pinion_teeth=z1, gear_teeth=z2, normal_module_mm=m_n, transverse_module_mm=m_t,
        normal_pressure_angle_deg=normal_pressure_angle_deg,
        transverse_pressure_angle_deg=math.degrees(alpha_t), helix_angle_deg=helix_angle_deg,
        base_helix_angle_deg=math.degrees(beta_b),
        profile_shift_pinion=x1, profile_shift_gear=x2,
        reference_diameter_pinion_mm=d1, reference_diameter_gear_mm=d2,
        base_diameter_pinion_mm=db1, base_diameter_gear_mm=db2,
        tip_diameter_pinion_mm=da1, tip_diameter_gear_mm=da2,
        root_diameter_pinion_mm=df1, root_diameter_gear_mm=df2,
        form_diameter_pinion_mm=dff1, form_diameter_gear_mm=dff2,
        undercut_pinion=cut1, undercut_gear=cut2,
        undercut_limit_shift_pinion=x_min[0], undercut_limit_shift_gear=x_min[1],
        active_start_diameter_pinion_mm=dnf[0], active_start_diameter_gear_mm=dnf[1],
        working_pitch_diameter_pinion_mm=2.0 * a_w * z1 / (z1 + z2),
        working_pitch_diameter_gear_mm=2.0 * a_w * z2 / (z1 + z2),
        tip_thickness_normal_pinion_mm=s_an[0], tip_thickness_normal_gear_mm=s_an[1],
        reference_centre_distance_mm=a_ref, zero_backlash_centre_distance_mm=a_w0,
        centre_distance_mm=a_w, working_pressure_angle_deg=math.degrees(alpha_wt),
        normal_backlash_mm=j_bn, tip_clearance_pinion_mm=c1, tip_clearance_gear_mm=c2,
        transverse_base_pitch_mm=p_bt, length_of_contact_mm=g_alpha,
        face_width_mm=face_width_mm, transverse_contact_ratio=eps_alpha,
        overlap_ratio=eps_beta, total_contact_ratio=eps_alpha + eps_beta)
