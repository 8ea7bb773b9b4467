"""Cylindrical (spur / helical) pair: typed, validated dataclasses and its TOML format.

A pair file with ``kind = "cylindrical"`` (:func:`gearcontact.geometry.pair.load_pair`
dispatches on ``kind``; absent is a bevel/hypoid pair). Units are in the key names;
unknown tables or keys are errors. docs/cylindrical.md describes every key.

.. code-block:: toml

    name = "spur_20x40"
    kind = "cylindrical"
    [teeth]
    pinion = 20                     # z1, integer in [5, 1000]
    gear = 40                       # z2, integer in [z1, 1000] (external pair)
    [cylindrical]
    normal_module_mm = 3.0          # m_n, (0, 100]
    normal_pressure_angle_deg = 20.0  # alpha_n, [10, 35] (default 20)
    helix_angle_deg = 0.0           # beta, [0, 45]; 0 = spur (default 0)
    pinion_hand = "right"           # helical only ("right" | "left"); gear opposite
    face_width_mm = 20.0            # or pinion_face_width_mm and gear_face_width_mm
    profile_shift_pinion = 0.0      # x1, [-1.5, 1.5] (default 0)
    profile_shift_gear = 0.0        # x2
    centre_distance_mm = 90.0       # a_w, optional: default the zero-backlash one
    addendum_factor = 1.0           # h_aP*, [0.5, 1.5] (default 1.0)
    dedendum_factor = 1.25          # h_fP*, (h_aP*, 2] (default 1.25)
    rack_tip_radius_factor = 0.38   # rho_fP*, [0, rho_max] (default 0.38)
    tip_diameter_pinion_mm = 66.0   # optional blank tip diameter (e.g. tip shortening)
    tip_diameter_gear_mm = 126.0
    [modifications.pinion]          # optional, all default 0
    tip_relief_um = 0.0             # C_a, [0, 500]; needs tip_relief_start_diameter_mm
    tip_relief_start_diameter_mm = 0.0  # d_Ca in (d_Nf, d_a)
    root_relief_um = 0.0            # C_f, [0, 500]
    profile_crowning_um = 0.0       # C_alpha, [0, 200]
    lead_crowning_um = 0.0          # C_beta, [0, 200]
    helix_slope_um = 0.0            # f_Hbeta over the face width, [-200, 200]
    [modifications.gear]
    [assembly]                      # optional mesh misalignment (ISO 1328-1 style)
    axis_inclination_um = 0.0       # f_Sigma_delta over the face width, [-500, 500]
    axis_deviation_um = 0.0         # f_Sigma_beta over the face width, [-500, 500]
    [material.pinion]               # optional; default steel 209 GPa / 0.3
    youngs_modulus_gpa = 209.0
    poisson_ratio = 0.3

Every field is checked on load: :class:`~gearcontact.validation.InputRangeError` names
the dotted key, the value and the allowed range; the ISO 21771 geometry is computed on
construction, so an impossible pair (an undercut cutting the whole involute, pointed
teeth, interference, a centre distance below the zero-backlash one) fails on load too;
an undercut member is generated (docs/cylindrical.md sec. 4).

References
----------
ISO 21771:2007, *Cylindrical involute gears and gear pairs — Concepts and geometry*.
ISO 1328-1:2013, *Cylindrical gears — ISO system of flank tolerance classification*
(profile and helix deviations, axis misalignments).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

from ...materials import STEEL, Material
from ...validation import InputRangeError, check_positive, check_range
from ..toml_tables import FLOAT, INT, MATERIAL_SCHEMA, STR, check_tables, materials_of
from .iso21771 import InvoluteGeometry, involute_geometry, roll_length_mm

__all__ = ["CylindricalPair", "MeshAlignment", "ToothModifications", "KIND",
           "parse_cylindrical_pair"]

#: The ``kind`` value of a cylindrical pair file.
KIND = "cylindrical"

#: key -> (low, high) of the modification keys, um.
_MODIFICATION_LIMITS_UM = {"tip_relief_um": (0.0, 500.0), "root_relief_um": (0.0, 500.0),
                           "profile_crowning_um": (0.0, 200.0),
                           "lead_crowning_um": (0.0, 200.0), "helix_slope_um": (-200.0, 200.0)}


@dataclass(frozen=True)
class ToothModifications:
    """Micro-geometry of one member, material removed from the involute helicoid.

    Amounts in um, measured in the transverse plane along the line of action (the
    ISO 1328-1 direction of profile and helix deviations); docs/cylindrical.md gives the
    shape of each term (:mod:`.flank`).

    Parameters
    ----------
    tip_relief_um : float
        C_a at the tip, [0, 500]; progressive (parabolic) from the start diameter.
    tip_relief_start_diameter_mm : float
        d_Ca, mm; required (> 0) when ``tip_relief_um > 0``, checked against the
        geometry by :class:`CylindricalPair`.
    root_relief_um : float
        C_f at the start of the active profile, [0, 500]; parabolic down from the lowest
        point of single contact.
    profile_crowning_um, lead_crowning_um : float
        C_alpha over the active profile, C_beta over the face width, [0, 200].
    helix_slope_um : float
        f_Hbeta over the face width, [-200, 200] (positive relieves the +z end).
    """

    tip_relief_um: float = 0.0
    tip_relief_start_diameter_mm: float = 0.0
    root_relief_um: float = 0.0
    profile_crowning_um: float = 0.0
    lead_crowning_um: float = 0.0
    helix_slope_um: float = 0.0
    member: str = "pinion"

    def __post_init__(self):
        prefix = f"modifications.{self.member}."
        for key, (lo, hi) in _MODIFICATION_LIMITS_UM.items():
            check_range(prefix + key, getattr(self, key), lo, hi)
        check_range(prefix + "tip_relief_start_diameter_mm",
                    self.tip_relief_start_diameter_mm, 0.0, 1e5)

    @property
    def is_zero(self) -> bool:
        """True if the flank is the unmodified involute helicoid."""
        return all(getattr(self, k) == 0.0 for k in _MODIFICATION_LIMITS_UM)


@dataclass(frozen=True)
class MeshAlignment:
    """Axis misalignment of the mesh over the face width (ISO 1328-1), um.

    Parameters
    ----------
    axis_inclination_um : float
        f_Sigma_delta: inclination of the gear axis in the plane of the axes, [-500, 500].
    axis_deviation_um : float
        f_Sigma_beta: deviation out of that plane, [-500, 500]. Signs and the tilt they
        make: :mod:`gearcontact.geometry.cylindrical.kinematics`.
    """

    axis_inclination_um: float = 0.0
    axis_deviation_um: float = 0.0

    def __post_init__(self):
        for key in ("axis_inclination_um", "axis_deviation_um"):
            check_range(f"assembly.{key}", getattr(self, key), -500.0, 500.0)


def max_rack_tip_radius_factor(normal_pressure_angle_deg: float, dedendum_factor: float) -> float:
    """Largest ρ_fP* whose two tip roundings fit on the basic rack's tip land:
    ``2 ρ tan(π/4 - α_n/2) <= π/2 - 2 h_fP* tan α_n`` (ISO 53 rack geometry)."""
    a = math.radians(normal_pressure_angle_deg)
    land = 0.5 * math.pi - 2.0 * dedendum_factor * math.tan(a)
    return max(land, 0.0) / (2.0 * math.tan(0.25 * math.pi - 0.5 * a))


@dataclass(frozen=True)
class CylindricalPair:
    """An external spur or helical pair (ISO 21771), its micro-geometry and mounting.

    Parameters
    ----------
    name : str
    pinion_teeth, gear_teeth : int
        z1 in [5, 1000], z2 in [z1, 1000].
    normal_module_mm : float
        m_n, mm, (0, 100].
    pinion_face_width_mm, gear_face_width_mm : float
        b1, b2, mm, (0, 1000]; the common face width is the smaller.
    normal_pressure_angle_deg : float
        α_n, [10, 35] deg.
    helix_angle_deg : float
        β, [0, 45] deg; 0 = spur.
    pinion_hand : str or None
        "right" or "left" for a helical pair (the gear has the other hand); None for spur.
    profile_shift_pinion, profile_shift_gear : float
        x1, x2, [-1.5, 1.5].
    centre_distance_mm : float or None
        a_w, mm; None: the zero-backlash centre distance of x1 + x2.
    addendum_factor, dedendum_factor, rack_tip_radius_factor : float
        h_aP* [0.5, 1.5], h_fP* (h_aP*, 2], ρ_fP* [0, fit on the rack tip land].
    tip_diameter_pinion_mm, tip_diameter_gear_mm : float or None
        Blank tip diameters, mm; None: ``d + 2 m_n (h_aP* + x)``.
    modifications_pinion, modifications_gear : ToothModifications
    assembly : MeshAlignment
    pinion_material, gear_material : Material
    """

    name: str
    pinion_teeth: int
    gear_teeth: int
    normal_module_mm: float
    pinion_face_width_mm: float
    gear_face_width_mm: float
    normal_pressure_angle_deg: float = 20.0
    helix_angle_deg: float = 0.0
    pinion_hand: str | None = None
    profile_shift_pinion: float = 0.0
    profile_shift_gear: float = 0.0
    centre_distance_mm: float | None = None
    addendum_factor: float = 1.0
    dedendum_factor: float = 1.25
    rack_tip_radius_factor: float = 0.38
    tip_diameter_pinion_mm: float | None = None
    tip_diameter_gear_mm: float | None = None
    modifications_pinion: ToothModifications = field(default_factory=ToothModifications)
    modifications_gear: ToothModifications = field(
        default_factory=lambda: ToothModifications(member="gear"))
    assembly: MeshAlignment = field(default_factory=MeshAlignment)
    pinion_material: Material = STEEL
    gear_material: Material = STEEL

    kind = KIND

    def __post_init__(self):
        c = "cylindrical."
        for key, z, lo in (("teeth.pinion", self.pinion_teeth, 5),
                           ("teeth.gear", self.gear_teeth, self.pinion_teeth)):
            if isinstance(z, bool) or not isinstance(z, int) or not lo <= z <= 1000:
                raise InputRangeError(key, z, f"an integer in [{lo}, 1000]")
        check_range(c + "normal_module_mm", self.normal_module_mm, 0.0, 100.0, lo_open=True)
        for key in ("pinion_face_width_mm", "gear_face_width_mm"):
            check_range(c + key, getattr(self, key), 0.0, 1000.0, lo_open=True)
        check_range(c + "normal_pressure_angle_deg", self.normal_pressure_angle_deg, 10.0, 35.0)
        check_range(c + "helix_angle_deg", self.helix_angle_deg, 0.0, 45.0)
        if self.helix_angle_deg > 0.0 and self.pinion_hand not in ("right", "left"):
            raise InputRangeError(c + "pinion_hand", self.pinion_hand,
                                  "'right' or 'left' (required for helix_angle_deg > 0)")
        if self.helix_angle_deg == 0.0 and self.pinion_hand is not None:
            raise InputRangeError(c + "pinion_hand", self.pinion_hand,
                                  "absent for a spur pair (helix_angle_deg = 0)")
        for key in ("profile_shift_pinion", "profile_shift_gear"):
            check_range(c + key, getattr(self, key), -1.5, 1.5)
        check_range(c + "addendum_factor", self.addendum_factor, 0.5, 1.5)
        check_range(c + "dedendum_factor", self.dedendum_factor, self.addendum_factor, 2.0,
                    lo_open=True)
        check_range(c + "rack_tip_radius_factor", self.rack_tip_radius_factor, 0.0,
                    max_rack_tip_radius_factor(self.normal_pressure_angle_deg,
                                               self.dedendum_factor))
        for key in ("centre_distance_mm", "tip_diameter_pinion_mm", "tip_diameter_gear_mm"):
            if getattr(self, key) is not None:
                check_positive(c + key, getattr(self, key))
        self.geometry           # an impossible pair fails on construction
        b = min(self.pinion_face_width_mm, self.gear_face_width_mm)
        for key in ("axis_inclination_um", "axis_deviation_um"):
            # the kinematics takes tilts up to 0.05 rad (f / b)
            check_range(f"assembly.{key}", getattr(self.assembly, key), -50.0 * b, 50.0 * b)
        for member in ("pinion", "gear"):
            self._check_modifications(member)

    @cached_property
    def geometry(self) -> InvoluteGeometry:
        """ISO 21771 geometry of this pair."""
        return involute_geometry(
            pinion_teeth=self.pinion_teeth, gear_teeth=self.gear_teeth,
            normal_module_mm=self.normal_module_mm,
            normal_pressure_angle_deg=self.normal_pressure_angle_deg,
            helix_angle_deg=self.helix_angle_deg,
            profile_shift_pinion=self.profile_shift_pinion,
            profile_shift_gear=self.profile_shift_gear,
            face_width_mm=min(self.pinion_face_width_mm, self.gear_face_width_mm),
            centre_distance_mm=self.centre_distance_mm,
            addendum_factor=self.addendum_factor, dedendum_factor=self.dedendum_factor,
            tip_radius_factor=self.rack_tip_radius_factor,
            tip_diameter_pinion_mm=self.tip_diameter_pinion_mm,
            tip_diameter_gear_mm=self.tip_diameter_gear_mm)

    def _check_modifications(self, member: str) -> None:
        """The tip-relief start diameter lies on the active profile (geometry known)."""
        mods = getattr(self, f"modifications_{member}")
        key = f"modifications.{member}.tip_relief_start_diameter_mm"
        d_ca = mods.tip_relief_start_diameter_mm
        if mods.tip_relief_um == 0.0 and d_ca == 0.0:
            return
        g = self.geometry
        lo = getattr(g, f"active_start_diameter_{member}_mm")
        hi = getattr(g, f"tip_diameter_{member}_mm")
        if mods.tip_relief_um > 0.0 and d_ca == 0.0:
            raise InputRangeError(key, d_ca, f"({lo:.4f}, {hi:.4f}) mm, the active profile "
                                             f"(required with tip_relief_um > 0)")
        if not lo < d_ca < hi:
            raise InputRangeError(key, d_ca, f"({lo:.4f}, {hi:.4f}) mm, the active profile "
                                             "from d_Nf to d_a")

    @property
    def ratio(self) -> float:
        """Gear ratio u = z2/z1."""
        return self.gear_teeth / self.pinion_teeth

    def face_width_mm(self, member: str) -> float:
        """Face width of ``member`` ("pinion" or "gear"), mm."""
        return getattr(self, f"{member}_face_width_mm")

    def hand(self, member: str) -> str | None:
        """Helix hand of ``member`` (None for spur)."""
        if self.pinion_hand is None or member == "pinion":
            return self.pinion_hand
        return "left" if self.pinion_hand == "right" else "right"

    def tip_relief_start_roll_mm(self, member: str) -> float:
        """Roll length of d_Ca (mm), or of d_a when there is no tip relief."""
        g = self.geometry
        mods = getattr(self, f"modifications_{member}")
        d = mods.tip_relief_start_diameter_mm or getattr(g, f"tip_diameter_{member}_mm")
        return roll_length_mm(d, getattr(g, f"base_diameter_{member}_mm"))


# --------------------------------------------------------------------------- TOML

_MOD_KEYS = {k: (FLOAT, False) for k in ToothModifications.__dataclass_fields__
             if k != "member"}
_SCHEMA: dict[str, dict[str, tuple[str, bool]]] = {
    "": {"name": (STR, False), "kind": (STR, True)},
    "teeth": {"pinion": (INT, True), "gear": (INT, True)},
    "cylindrical": {"normal_module_mm": (FLOAT, True),
                    "normal_pressure_angle_deg": (FLOAT, False),
                    "helix_angle_deg": (FLOAT, False), "pinion_hand": (STR, False),
                    "face_width_mm": (FLOAT, False), "pinion_face_width_mm": (FLOAT, False),
                    "gear_face_width_mm": (FLOAT, False),
                    "profile_shift_pinion": (FLOAT, False),
                    "profile_shift_gear": (FLOAT, False),
                    "centre_distance_mm": (FLOAT, False), "addendum_factor": (FLOAT, False),
                    "dedendum_factor": (FLOAT, False),
                    "rack_tip_radius_factor": (FLOAT, False),
                    "tip_diameter_pinion_mm": (FLOAT, False),
                    "tip_diameter_gear_mm": (FLOAT, False)},
    "modifications.pinion": _MOD_KEYS,
    "modifications.gear": _MOD_KEYS,
    "assembly": {k: (FLOAT, False) for k in MeshAlignment.__dataclass_fields__},
    **MATERIAL_SCHEMA,
}


def parse_cylindrical_pair(doc: dict, *, name: str = "pair") -> CylindricalPair:
    """Build a :class:`CylindricalPair` from a parsed TOML document (module docstring)."""
    s = check_tables(doc, _SCHEMA, ("teeth", "cylindrical"))
    if s[""]["kind"] != KIND:
        raise InputRangeError("kind", s[""]["kind"], f"'{KIND}'")
    cyl = dict(s["cylindrical"])
    both = "face_width_mm" in cyl
    members = ("pinion_face_width_mm" in cyl, "gear_face_width_mm" in cyl)
    if both == any(members) or (not both and not all(members)):
        raise InputRangeError("cylindrical.face_width_mm / cylindrical.pinion_face_width_mm "
                              "+ cylindrical.gear_face_width_mm", None,
                              "either face_width_mm or both member face widths")
    if both:
        b = cyl.pop("face_width_mm")
        cyl["pinion_face_width_mm"] = cyl["gear_face_width_mm"] = b
    materials = materials_of(s)
    return CylindricalPair(
        name=s[""].get("name", name),
        pinion_teeth=s["teeth"]["pinion"], gear_teeth=s["teeth"]["gear"],
        modifications_pinion=ToothModifications(**s.get("modifications.pinion", {}),
                                                 member="pinion"),
        modifications_gear=ToothModifications(**s.get("modifications.gear", {}),
                                               member="gear"),
        assembly=MeshAlignment(**s.get("assembly", {})),
        pinion_material=materials["pinion"], gear_material=materials["gear"], **cyl)
