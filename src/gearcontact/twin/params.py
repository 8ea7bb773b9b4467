"""Drivetrain parameters of the twin: the ``[drivetrain]`` TOML table and its defaults.

The torsional chain is motor ``J_m`` -- input shaft ``(k_1, c_1)`` -- pinion ``J_p`` --
mesh -- gear ``J_g`` -- output shaft ``(k_2, c_2)`` -- load ``J_l``. The mesh itself
(levers, openings, curvatures, unloaded TE) comes from the TCA of the pair
(:mod:`.mesh`), never from this table.

Defaults for s0003 (:func:`default_drivetrain`) and their sources:

* steel density 7850 kg/m^3 (handbook value for carbon and case-hardening steels);
* pinion: a solid steel cylinder of the mean tip radius ``r_1m + h_a1`` over the pinion
  face width (blank geometry, :class:`~gearcontact.geometry.blank.BlankDesign`) plus half
  of the input shaft (lumped-mass convention: half a shaft's inertia at each end node);
* gear: a solid steel disc of the outer radius ``r_2m + (F_2/2) sin delta_2 + h_a2`` and
  thickness ``F_2`` (blank geometry) plus half of the output shaft;
* cylindrical pairs: pinion and gear solid steel cylinders of the mean diameter
  ``(d_a + d_f) / 2`` over their face widths (ISO 6336-1:2006 clause 6.5.3's body of
  the reduced mass), plus half of their shafts;
* shafts: solid steel, input 20 mm x 150 mm, output 30 mm x 200 mm (assumed: s0003's
  shafts are not published; diameters sized for the 6.45 / 64.5 N·m torques at < 50 MPa
  shear); torsional stiffness ``k = G pi d^4 / (32 L)`` with ``G = E / (2 (1 + nu))`` of
  the pair's materials (Roark's Formulas for Stress and Strain, 8th ed., table 10.1
  case 1);
* motor rotor 5e-4 kg·m^2 (assumed: catalogue class of 2-3 kW, 3000 rpm servo motors
  for the 2 kW the pair carries at 64.5 N·m and 3000 rpm);
* load 0.05 kg·m^2 (assumed: a small test-rig absorber on the gear shaft);
* damping ratios: shafts 0.02 (steel shafts with fits, 0.01-0.05), mesh 0.05 (inside
  the 0.03-0.17 range of the gear-dynamics literature, H. N. Özgüven, D. R. Houser,
  J. Sound Vib. 121 (1988) 383-411);
* normal backlash 0.05 mm (assumed: not published for s0003; inside the usual
  0.025-0.1 mm of bevel gears of ~1 mm normal module);
* no speed controller (constant motor torque, the drive of a back-to-back or
  brake test rig); a PI speed loop is available by its bandwidth.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path

from ..validation import InputRangeError, check_positive, check_range, read_text_file

__all__ = ["DrivetrainParams", "default_drivetrain", "load_drivetrain", "check_drivetrain_file",
           "STEEL_DENSITY_KG_M3",
           "shaft_stiffness_nm_per_rad", "shaft_inertia_kgm2"]

#: Density of steel, kg/m^3 (handbook value).
STEEL_DENSITY_KG_M3 = 7850.0
_INPUT_SHAFT_MM = (20.0, 150.0)      # diameter, length (assumed, module docstring)
_OUTPUT_SHAFT_MM = (30.0, 200.0)


@dataclass(frozen=True)
class DrivetrainParams:
    """Lumped torsional drivetrain (SI units; module docstring for the defaults).

    Attributes
    ----------
    motor_inertia_kgm2, pinion_inertia_kgm2, gear_inertia_kgm2, load_inertia_kgm2 : float
        Polar moments of inertia J_m, J_p, J_g, J_l, kg·m^2 (> 0).
    input_stiffness_nm_per_rad, output_stiffness_nm_per_rad : float
        Torsional stiffness k_1 (motor-pinion) and k_2 (gear-load), N·m/rad (> 0).
    input_damping_ratio, output_damping_ratio : float
        Damping ratios of the two shafts in [0, 1): ``c = 2 zeta sqrt(k J_1 J_2 / (J_1 +
        J_2))`` of the two inertias the shaft joins, N·m·s/rad.
    mesh_damping_ratio : float
        Mesh damping ratio in [0, 1): ``c_m = 2 zeta sqrt(k_m m_e)`` along the line of
        action, with the linearised mesh stiffness at the static load and the
        equivalent mass of the two members on their levers.
    backlash_mm : float
        Normal backlash along the line of action, mm (>= 0): free play between the drive
        and the coast flank.
    speed_control_bandwidth_hz : float
        Bandwidth of the motor's PI speed controller, Hz (>= 0); 0 (default, the
        constant-torque drive of a test rig) holds the motor torque at ``T_l / u``
        (:func:`gearcontact.twin.simulate.speed_controller_gains`).
    """

    motor_inertia_kgm2: float
    pinion_inertia_kgm2: float
    gear_inertia_kgm2: float
    load_inertia_kgm2: float
    input_stiffness_nm_per_rad: float
    output_stiffness_nm_per_rad: float
    input_damping_ratio: float = 0.02
    output_damping_ratio: float = 0.02
    mesh_damping_ratio: float = 0.05
    backlash_mm: float = 0.05
    speed_control_bandwidth_hz: float = 0.0

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name.endswith("damping_ratio"):
                check_range(f"drivetrain.{f.name}", v, 0.0, 1.0, hi_open=True)
            elif f.name == "backlash_mm":
                check_range("drivetrain.backlash_mm", v, 0.0, 10.0)
            elif f.name == "speed_control_bandwidth_hz":
                check_range("drivetrain.speed_control_bandwidth_hz", v, 0.0, 1e4)
            else:
                check_positive(f"drivetrain.{f.name}", v)

    def as_dict(self) -> dict:
        """Plain dict (the keys of the ``[drivetrain]`` table)."""
        return asdict(self)

    def shaft_damping(self) -> tuple[float, float]:
        """``(c_1, c_2)``, N·m·s/rad, from the damping ratios."""
        def c(zeta, k, j1, j2):
            return 2.0 * zeta * math.sqrt(k * j1 * j2 / (j1 + j2))
        return (c(self.input_damping_ratio, self.input_stiffness_nm_per_rad,
                  self.motor_inertia_kgm2, self.pinion_inertia_kgm2),
                c(self.output_damping_ratio, self.output_stiffness_nm_per_rad,
                  self.gear_inertia_kgm2, self.load_inertia_kgm2))


def shaft_stiffness_nm_per_rad(diameter_mm: float, length_mm: float, shear_modulus_mpa: float
                               ) -> float:
    """Torsional stiffness of a solid round shaft ``G pi d^4 / (32 L)``, N·m/rad."""
    d, length = 1e-3 * diameter_mm, 1e-3 * length_mm
    return shear_modulus_mpa * 1e6 * math.pi * d ** 4 / (32.0 * length)


def shaft_inertia_kgm2(diameter_mm: float, length_mm: float) -> float:
    """Polar inertia of a solid steel cylinder ``rho pi L d^4 / 32``, kg·m^2."""
    d, length = 1e-3 * diameter_mm, 1e-3 * length_mm
    return STEEL_DENSITY_KG_M3 * math.pi * length * d ** 4 / 32.0


def _member_inertias(pair) -> tuple[float, float]:
    """Pinion and gear bodies, kg·m^2: bevel, the blank's head and disc (module
    docstring); cylindrical, solid steel cylinders of the mean diameter ``(d_a + d_f)/2``
    over each member's face width (the body of ISO 6336-1's reduced mass, clause 6.5.3)."""
    if getattr(pair, "kind", None) == "cylindrical":
        g = pair.geometry
        return (shaft_inertia_kgm2(0.5 * (g.tip_diameter_pinion_mm + g.root_diameter_pinion_mm),
                                   pair.pinion_face_width_mm),
                shaft_inertia_kgm2(0.5 * (g.tip_diameter_gear_mm + g.root_diameter_gear_mm),
                                   pair.gear_face_width_mm))
    bd = pair.blank
    r1 = bd.mean_pitch_radius_pinion_mm + bd.addendum_pinion_mm
    j_head1 = shaft_inertia_kgm2(2.0 * r1, pair.pinion_face_width_mm)
    delta2 = math.radians(bd.pitch_angle_gear_deg)
    r2 = (bd.mean_pitch_radius_gear_mm + 0.5 * pair.gear_face_width_mm * math.sin(delta2)
          + bd.addendum_gear_mm)
    return j_head1, shaft_inertia_kgm2(2.0 * r2, pair.gear_face_width_mm)


def default_drivetrain(pair) -> DrivetrainParams:
    """Defaults estimated from the pair's blank (module docstring states every source).

    Parameters
    ----------
    pair : gearcontact.geometry.pair.GearPair or CylindricalPair
    """
    m1, m2 = pair.pinion_material, pair.gear_material
    g1 = m1.youngs_modulus_mpa / (2.0 * (1.0 + m1.poisson_ratio))
    g2 = m2.youngs_modulus_mpa / (2.0 * (1.0 + m2.poisson_ratio))
    j_head1, j_disc2 = _member_inertias(pair)
    j_s1 = shaft_inertia_kgm2(*_INPUT_SHAFT_MM)
    j_s2 = shaft_inertia_kgm2(*_OUTPUT_SHAFT_MM)
    return DrivetrainParams(
        motor_inertia_kgm2=5e-4 + 0.5 * j_s1,
        pinion_inertia_kgm2=j_head1 + 0.5 * j_s1,
        gear_inertia_kgm2=j_disc2 + 0.5 * j_s2,
        load_inertia_kgm2=0.05 + 0.5 * j_s2,
        input_stiffness_nm_per_rad=shaft_stiffness_nm_per_rad(*_INPUT_SHAFT_MM, g1),
        output_stiffness_nm_per_rad=shaft_stiffness_nm_per_rad(*_OUTPUT_SHAFT_MM, g2))


def check_drivetrain_file(source) -> dict:
    """The parsed TOML document of the drivetrain file ``source``.

    Raises
    ------
    InputRangeError
        ``--drivetrain`` is not an existing, readable UTF-8 TOML file (the message names
        the file and, for a bad byte or a syntax error, where).
    """
    path = Path(source)
    if not path.is_file():
        raise InputRangeError("--drivetrain", str(source), "an existing TOML file with a "
                                                           "[drivetrain] table")
    text = read_text_file(path, field="--drivetrain", what="a TOML file")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputRangeError(f"{path.name} (TOML syntax)", str(exc), "valid TOML") from None


def load_drivetrain(source, pair) -> DrivetrainParams:
    """The ``[drivetrain]`` table of a TOML file over the defaults of ``pair``.

    Keys are the attribute names of :class:`DrivetrainParams`; missing keys keep the
    defaults of :func:`default_drivetrain`; unknown keys are an error naming the key.
    ``source`` None returns the defaults.
    """
    base = default_drivetrain(pair)
    if source is None:
        return base
    path = Path(source)
    doc = check_drivetrain_file(source)
    table = doc.get("drivetrain")
    if not isinstance(table, dict):
        raise InputRangeError("--drivetrain", path.name,
                              "a TOML file with a [drivetrain] table (this one has none; "
                              "a pair file goes to --pair)")
    known = {f.name for f in fields(DrivetrainParams)}
    for key, value in table.items():
        if key not in known:
            raise InputRangeError(f"drivetrain.{key}", value, f"a known key: {sorted(known)}")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputRangeError(f"drivetrain.{key}", value, "a number")
    return replace(base, **{k: float(v) for k, v in table.items()})
