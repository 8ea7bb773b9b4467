"""ISO 6336-1 Method B single-pair tooth stiffness: an independent order of magnitude
for the mesh compliance of the loaded-contact models (docs/bending.md sec. 7).

The theoretical single stiffness of a pair of solid spur gears with the ISO 53 basic
rack is the inverse of the flexibility polynomial (ISO 6336-1:2006, eq. 70 and
table 8)::

    q' = C1 + C2 / z_n1 + C3 / z_n2 + C4 x1 + C5 x1 / z_n1 + C6 x2 + C7 x2 / z_n2
         + C8 x1^2 + C9 x2^2                       (mm µm / N)
    c'_th = 1 / q'                                   (N / (mm µm))

and the single stiffness of the real pair is ``c' = c'_th C_M C_R C_B cos(beta)``
(eq. 71), with C_M = 0.8 (measured against theory), C_R = 1 (solid blanks) and the
basic-rack factor ``C_B = [1 + 0.5 (1.2 - h_fP / m_n)] [1 - 0.02 (20 deg - alpha_n)]``
(eq. 73). A bevel or hypoid pair enters through its virtual cylindrical gears,
``z_n = z / (cos(delta) cos^3(beta_m))`` (ISO 10300-1), at the mean spiral angle; a
cylindrical pair through ``z_n = z / (cos^2(beta_b) cos(beta))`` with the mesh stiffness
``c_gamma_alpha = c' (0.75 eps_alpha + 0.25)`` and ``c_gamma_beta = 0.85 c_gamma_alpha``
(eq. 74-75).
Multiplied by the face width this is the stiffness of a contact line over the whole
face: contact flattening, tooth bending and foundation together. A localized bearing
loads only part of the face, so its pair compliance must lie *above* this value.

The resonance speed of the pinion (clause 6.5.3, the reference speed of the dynamic
factor K_v) follows from the mesh stiffness and the reduced mass of the pair per unit
face width on the line of action, for solid or bored blanks of mean diameter
``d_m = (d_a + d_f) / 2``::

    m_red = (pi/8) (d_m1/d_b1)^2 d_m1^2 / (1/((1 - q1^4) rho1) + 1/((1 - q2^4) rho2 u^2))
    n_E1  = 30 000 / (pi z1) sqrt(c_gamma_alpha / m_red)        (rpm; N/(mm µm), kg/mm)

(:func:`reduced_mass_kg_per_mm`, :func:`resonance_speed_rpm`; the gear's ``m*`` taken
as ``u^2`` times the pinion's geometric factor, the standard's form).

References
----------
ISO 6336-1:2006, *Calculation of load capacity of spur and helical gears — Part 1*,
clause 9 (Method B), eq. (70)–(73), table 8; clause 6.5.3 (resonance running speed). ISO 10300-1:2014, *Calculation of load
capacity of bevel gears*, virtual cylindrical gears.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..validation import check_positive, check_range

__all__ = ["FLEXIBILITY_COEFFICIENTS", "IsoPairStiffness", "IsoMeshStiffness",
           "theoretical_single_stiffness", "virtual_teeth", "bevel_pair_stiffness",
           "cylindrical_pair_stiffness", "reduced_mass_kg_per_mm", "resonance_speed_rpm"]

#: C1..C9 of ISO 6336-1:2006 table 8 (mm µm / N; x dimensionless).
FLEXIBILITY_COEFFICIENTS = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193,
                            -0.24188, 0.00529, 0.00182)


def theoretical_single_stiffness(*, z_n1: float, z_n2: float, x1: float = 0.0,
                                 x2: float = 0.0) -> float:
    """c'_th = 1 / q' of ISO 6336-1 eq. (70), N/(mm·µm).

    Parameters
    ----------
    z_n1, z_n2 : float, keyword-only
        Virtual (normal-section) numbers of teeth of pinion and wheel (>= 5; the
        standard's fit covers external gears).
    x1, x2 : float, keyword-only
        Profile shift coefficients, in [-0.5, 2] (the range of table 8's fit).
    """
    check_range("z_n1", z_n1, 5.0, 1e9)
    check_range("z_n2", z_n2, 5.0, 1e9)
    check_range("x1", x1, -0.5, 2.0)
    check_range("x2", x2, -0.5, 2.0)
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = FLEXIBILITY_COEFFICIENTS
    q = (c1 + c2 / z_n1 + c3 / z_n2 + c4 * x1 + c5 * x1 / z_n1 + c6 * x2 + c7 * x2 / z_n2
         + c8 * x1 ** 2 + c9 * x2 ** 2)
    return 1.0 / q


def virtual_teeth(teeth: int, *, pitch_angle_deg: float, spiral_angle_deg: float) -> float:
    """Virtual number of teeth of a bevel member, ``z / (cos(delta) cos^3(beta_m))``."""
    check_range("pitch_angle_deg", pitch_angle_deg, 0.0, 89.9)
    check_range("spiral_angle_deg", spiral_angle_deg, 0.0, 60.0)
    return teeth / (math.cos(math.radians(pitch_angle_deg))
                    * math.cos(math.radians(spiral_angle_deg)) ** 3)


@dataclass(frozen=True)
class IsoPairStiffness:
    """ISO 6336-1 Method B single-pair stiffness of a bevel / hypoid pair.

    Attributes
    ----------
    z_n1, z_n2 : float
        Virtual numbers of teeth.
    spiral_angle_deg : float
        Mean spiral angle used (mean of pinion and gear for a hypoid), degrees.
    c_th_n_per_mm_um : float
        Theoretical single stiffness c'_th, N/(mm·µm).
    c_n_per_mm_um : float
        Single stiffness c' = c'_th C_M C_R C_B cos(beta), N/(mm·µm).
    face_width_mm : float
        Face width b, mm.
    stiffness_n_per_um : float
        Pair stiffness c' b, N/µm.
    compliance_mm_per_n : float
        Pair compliance 1 / (c' b), mm/N.
    """

    z_n1: float
    z_n2: float
    spiral_angle_deg: float
    c_th_n_per_mm_um: float
    c_n_per_mm_um: float
    face_width_mm: float
    stiffness_n_per_um: float
    compliance_mm_per_n: float


def _c_b(dedendum_per_module: float, rack_pressure_angle_deg: float) -> float:
    """Basic-rack factor C_B of eq. (73)."""
    return ((1.0 + 0.5 * (1.2 - dedendum_per_module))
            * (1.0 - 0.02 * (20.0 - rack_pressure_angle_deg)))


def bevel_pair_stiffness(blank, *, face_width_mm: float, c_m: float = 0.8, c_r: float = 1.0,
                         dedendum_per_module: float = 1.25,
                         rack_pressure_angle_deg: float = 20.0) -> IsoPairStiffness:
    """Method B single-pair stiffness of a bevel or hypoid pair from its blank.

    Parameters
    ----------
    blank : gearcontact.geometry.blank.BlankDesign
        Teeth, pitch angles and spiral angles (the mean of pinion and gear spiral
        angles is the virtual gears' helix angle).
    face_width_mm : float, keyword-only
        Face width b, mm (> 0): the gear's, the narrower member of a bevel pair.
    c_m, c_r : float, keyword-only
        Correction factor (0.8, theory vs measurement) and gear-blank factor (1, solid).
    dedendum_per_module, rack_pressure_angle_deg : float, keyword-only
        Basic rack h_fP / m_n and alpha_n, degrees, of the factor C_B (eq. 73).
    """
    b = check_positive("face_width_mm", face_width_mm)
    beta = 0.5 * (blank.spiral_angle_pinion_deg + blank.spiral_angle_gear_deg)
    z1 = virtual_teeth(blank.pinion_teeth, pitch_angle_deg=blank.pitch_angle_pinion_deg,
                       spiral_angle_deg=beta)
    z2 = virtual_teeth(blank.gear_teeth, pitch_angle_deg=blank.pitch_angle_gear_deg,
                       spiral_angle_deg=beta)
    c_th = theoretical_single_stiffness(z_n1=z1, z_n2=z2)
    c_b = ((1.0 + 0.5 * (1.2 - dedendum_per_module))
           * (1.0 - 0.02 * (20.0 - rack_pressure_angle_deg)))
    c = c_th * c_m * c_r * c_b * math.cos(math.radians(beta))
    k = c * b
    return IsoPairStiffness(z_n1=z1, z_n2=z2, spiral_angle_deg=beta, c_th_n_per_mm_um=c_th,
                            c_n_per_mm_um=c, face_width_mm=b, stiffness_n_per_um=k,
                            compliance_mm_per_n=1e-3 / k)


@dataclass(frozen=True)
class IsoMeshStiffness:
    """ISO 6336-1 Method B stiffness of a cylindrical pair, N/(mm·µm) per mm of face.

    Attributes
    ----------
    z_n1, z_n2 : float
        Virtual numbers of teeth ``z / (cos^2(beta_b) cos(beta))``.
    c_th_n_per_mm_um, c_n_per_mm_um : float
        c'_th and the single stiffness c' = c'_th C_M C_R C_B cos(beta).
    c_gamma_alpha_n_per_mm_um, c_gamma_beta_n_per_mm_um : float
        Mesh stiffness c' (0.75 eps_alpha + 0.25) and 0.85 times it.
    """

    z_n1: float
    z_n2: float
    c_th_n_per_mm_um: float
    c_n_per_mm_um: float
    c_gamma_alpha_n_per_mm_um: float
    c_gamma_beta_n_per_mm_um: float


def cylindrical_pair_stiffness(*, pinion_teeth: int, gear_teeth: int, helix_angle_deg: float,
                               base_helix_angle_deg: float, transverse_contact_ratio: float,
                               profile_shift_pinion: float = 0.0,
                               profile_shift_gear: float = 0.0, c_m: float = 0.8,
                               c_r: float = 1.0, dedendum_per_module: float = 1.25,
                               rack_pressure_angle_deg: float = 20.0) -> IsoMeshStiffness:
    """Method B single and mesh stiffness of a spur or helical pair (eq. 70-75).

    Parameters
    ----------
    pinion_teeth, gear_teeth : int, keyword-only
    helix_angle_deg, base_helix_angle_deg : float, keyword-only
        beta and beta_b, degrees, [0, 45].
    transverse_contact_ratio : float, keyword-only
        eps_alpha (>= 1; the standard's c_gamma holds from 1.2).
    profile_shift_pinion, profile_shift_gear : float, keyword-only
    c_m, c_r, dedendum_per_module, rack_pressure_angle_deg
        As :func:`bevel_pair_stiffness`.
    """
    check_range("helix_angle_deg", helix_angle_deg, 0.0, 45.0)
    check_range("base_helix_angle_deg", base_helix_angle_deg, 0.0, 45.0)
    check_range("transverse_contact_ratio", transverse_contact_ratio, 1.0, 10.0)
    beta, beta_b = math.radians(helix_angle_deg), math.radians(base_helix_angle_deg)
    f = math.cos(beta_b) ** 2 * math.cos(beta)
    z1, z2 = pinion_teeth / f, gear_teeth / f
    c_th = theoretical_single_stiffness(z_n1=z1, z_n2=z2, x1=profile_shift_pinion,
                                        x2=profile_shift_gear)
    c = c_th * c_m * c_r * _c_b(dedendum_per_module, rack_pressure_angle_deg) * math.cos(beta)
    c_ga = c * (0.75 * transverse_contact_ratio + 0.25)
    return IsoMeshStiffness(z_n1=z1, z_n2=z2, c_th_n_per_mm_um=c_th, c_n_per_mm_um=c,
                            c_gamma_alpha_n_per_mm_um=c_ga, c_gamma_beta_n_per_mm_um=0.85 * c_ga)


#: Density of steel in the standard's units, kg/mm^3.
STEEL_DENSITY_KG_PER_MM3 = 7.85e-6


def reduced_mass_kg_per_mm(*, mean_diameter_pinion_mm: float, base_diameter_pinion_mm: float,
                           ratio: float, density_pinion_kg_per_mm3: float = STEEL_DENSITY_KG_PER_MM3,
                           density_gear_kg_per_mm3: float = STEEL_DENSITY_KG_PER_MM3,
                           bore_ratio_pinion: float = 0.0, bore_ratio_gear: float = 0.0) -> float:
    """Reduced mass of the pair per unit face width on the line of action, kg/mm (ISO
    6336-1:2006 clause 6.5.3; module docstring).

    Parameters
    ----------
    mean_diameter_pinion_mm, base_diameter_pinion_mm : float, keyword-only
        ``d_m1 = (d_a1 + d_f1) / 2`` and ``d_b1``, mm.
    ratio : float, keyword-only
        ``u = z2 / z1`` (>= 1).
    density_pinion_kg_per_mm3, density_gear_kg_per_mm3 : float, keyword-only
    bore_ratio_pinion, bore_ratio_gear : float, keyword-only
        ``q = d_i / d_m`` in [0, 1) (0: solid).
    """
    dm = check_positive("mean_diameter_pinion_mm", mean_diameter_pinion_mm)
    db = check_positive("base_diameter_pinion_mm", base_diameter_pinion_mm)
    u = check_range("ratio", ratio, 1.0, 1e3)
    rho1 = check_positive("density_pinion_kg_per_mm3", density_pinion_kg_per_mm3)
    rho2 = check_positive("density_gear_kg_per_mm3", density_gear_kg_per_mm3)
    q1 = check_range("bore_ratio_pinion", bore_ratio_pinion, 0.0, 1.0, hi_open=True)
    q2 = check_range("bore_ratio_gear", bore_ratio_gear, 0.0, 1.0, hi_open=True)
    return (math.pi / 8.0) * (dm / db) ** 2 * dm ** 2 / (
        1.0 / ((1.0 - q1 ** 4) * rho1) + 1.0 / ((1.0 - q2 ** 4) * rho2 * u ** 2))


def resonance_speed_rpm(*, pinion_teeth: int, c_gamma_n_per_mm_um: float,
                        reduced_mass_kg_per_mm: float) -> float:
    """Resonance speed of the pinion ``n_E1 = 30 000 / (pi z1) sqrt(c_gamma / m_red)``,
    rpm (ISO 6336-1:2006 clause 6.5.3): the pinion speed whose mesh frequency equals
    the natural frequency of the two members on the mesh stiffness ``c_gamma``
    (N/(mm·µm)) with the reduced mass ``m_red`` (kg/mm)."""
    z1 = check_range("pinion_teeth", pinion_teeth, 1, 10_000)
    c = check_positive("c_gamma_n_per_mm_um", c_gamma_n_per_mm_um)
    m = check_positive("reduced_mass_kg_per_mm", reduced_mass_kg_per_mm)
    return 30_000.0 / (math.pi * z1) * math.sqrt(c / m)
