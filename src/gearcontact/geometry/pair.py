"""Gear-pair definition: typed, validated dataclasses and the TOML pair format.

A pair file is TOML with the tables below; every key is required unless a default is
shown. Unknown tables or keys are errors (they are usually typos). Units are part of
the key names. The built-in preset ``s0003`` (``gearcontact/data/pairs/s0003.toml``)
is a complete, commented example; ``examples/`` holds more.

.. code-block:: toml

    name = "s0003"                      # label for reports

    [teeth]
    pinion = 7                          # z1, integer >= 5
    gear = 70                           # z2, integer > z1

    [axes]
    shaft_angle_deg = 90.0              # Sigma; only 90 deg is supported
    offset_mm = 19.0                    # hypoid offset E >= 0 (pinion axis at y = -E)

    [design]                            # ISO 23509 Method 1 inputs
    pinion_hand = "right"               # spiral hand of the pinion (gear is opposite)
    gear_mean_cone_distance_mm = 40.68  # R2 ... or gear_mean_pitch_radius_mm (one of them)
    pinion_spiral_angle_deg = 48.7      # beta1, (0, 70)
    gear_face_width_mm = 12.0           # F2 along the gear pitch cone
    pinion_face_width_mm = 13.2         # b1 along the pinion pitch cone (>= F2)
    working_depth_factor = 2.0          # k_d (default 2.0)
    clearance_factor = 0.125            # k_c (default 0.125)
    gear_addendum_factor = 0.15         # c_ham (default 0.35)
    design_side = "drive"               # flank pair analysed and loaded by default
                                        # ("drive" | "coast"; default "drive")

    [cutter]                            # face-milling cutter and blades
    radius_mm = 45.1                    # r_c0 (nominal radius, slot centre line)
    point_width_mm = 0.5                # W: blade tip width
    edge_radius_mm = 0.1                # blade tip edge radius, [0, W/2)
    pressure_angle_drive_deg = 20.0     # alpha_dD (nominal, before the alpha_lim split)
    pressure_angle_coast_deg = 20.0     # alpha_dC
    limit_pressure_angle_factor = 1.0   # f_alim in [0, 1] (default 1.0)

    [easeoff.drive]                     # pinion ease-off, E in um (see easeoff.py)
    profile_angle_um_per_mm = 0.0       # c_PA: E += c_PA * eta
    spiral_angle_um_per_mm = 0.0        # c_SA: E += c_SA * xi
    profile_crowning_um_per_mm2 = 1.5   # c_PC: E += c_PC * eta^2
    lengthwise_crowning_um_per_mm2 = 0.15  # c_LC: E += c_LC * xi^2
    bias_um_per_mm2 = 0.0               # c_TW: E += c_TW * xi * eta
    [easeoff.coast]                     # same keys

    [assembly]                          # optional; all default 0 (see kinematics.py)
    E_mm = 0.0
    P_mm = 0.0
    G_mm = 0.0
    alpha_deg = 0.0

    [material.pinion]                   # optional; default steel 209 GPa / 0.3
    youngs_modulus_gpa = 209.0
    poisson_ratio = 0.3
    [material.gear]

Machine settings (optional, :mod:`.machine`; docs/machine_settings.md has the figure and
the sign table): with them all four flanks are cut from cutter and machine settings
(:mod:`.generated`) instead of today's formate gear + conjugate pinion + ease-off, so
``[easeoff.*]`` must then be absent. All eight tables are required together:

.. code-block:: toml

    [machine.gear.drive]                # also gear.coast, pinion.drive, pinion.coast
    radial_distance_mm = 48.31          # S_r
    cradle_angle_deg = -59.2            # q (signed, about the cradle axis)
    machine_root_angle_deg = 83.15      # gamma_m
    machine_centre_to_back_mm = 0.0     # X_D (default 0)
    sliding_base_mm = -1.1              # X_B (default 0)
    blank_offset_mm = 0.0               # E_m (default 0)
    ratio_of_roll = 0.0                 # R_a = work / cradle rotation; 0 = formate
    modified_roll_2c_per_rad = 0.0      # 2C (also _6d_per_rad2, _24e_per_rad3,
                                        #   _120f_per_rad4), default 0
    tilt_deg = 0.0                      # i, [0, 60]
    swivel_deg = 0.0                    # j
    helical_motion_mm_per_rad = 0.0     # V_1 (also helical_motion_mm_per_rad2)

    [blade.gear.drive]
    kind = "inside"                     # gear drive / pinion coast: inside
    blade_angle_deg = 20.0
    point_radius_mm = 43.9
    edge_radius_mm = 0.1                # default 0
    profile_radius_mm = 0.0             # 0 = straight (default)
    profile_reference_mm = 0.0          # where blade_angle_deg holds (curved blade)
    profile_cubic_per_mm2 = 0.0         # c_3, higher-order profile (default 0; also
                                        #   profile_quartic_per_mm3, c_4)
    toprem_angle_deg = 0.0              # Toprem relief at the blade tip, [0, 10] (default 0)
    toprem_depth_mm = 0.0               # its kink's depth behind the tip plane (also
                                        #   flankrem_angle_deg / flankrem_depth_mm at the top)

A summary sheet's gear page may stand for the gear's four tables: ``[print.gear]``, its
words and numbers typed verbatim (``sliding_base = "WITH 0.070"``; the keys, the
conversion and its checks: :mod:`.print_table`, docs/machine_settings.md sec. 2-3),
beside the pinion's tables; given with ``[machine.gear.*]`` / ``[blade.gear.*]`` it is
refused. The gear's tables without the pinion's are read only by ``gearcontact design
--machine-settings`` (``gear_alone``: :mod:`.typed_pinion` derives the pinion).

Every value is validated on load: a missing key, a value of the wrong TOML type or a
value outside its range raises :class:`~gearcontact.validation.InputRangeError`
naming the dotted key, the value and the expected type/range; impossible designs
(too few teeth, an offset too large for the gear, a spiral angle inconsistent with the
offset) are rejected by :func:`GearPair.blank` (ISO 23509 Method 1).

References
----------
ISO 23509:2016, *Bevel and hypoid gear geometry*, clauses 5-7.
"""

from __future__ import annotations

import dataclasses
import re
import tomllib
from dataclasses import dataclass, field
from functools import cached_property
from importlib import resources
from pathlib import Path

import numpy as np

from ..materials import STEEL, Material
from ..validation import InputRangeError, check_positive, read_text_file
from .blank import BlankDesign, design_blank, gear_top_land_mm
from .cylindrical.pair import KIND as CYLINDRICAL_KIND
from .cylindrical.pair import CylindricalPair, parse_cylindrical_pair
from .kinematics import AssemblyErrors, MeshKinematics
from .machine import (BLADE_KEYS, HELICAL_KEYS, MACHINE_KEYS, MEMBERS, MODIFIED_ROLL_KEYS,
                      setup_from_tables, setup_to_tables)
from .print_blank import cuts_the_printed_gear
from .pair_tables import (CutterSpec, EaseOffCoefficients, check_face_within_cone,
                          check_pinion_face)
from .print_table import (check_print_blank, print_gear_tables, printed_key_error,
                          printed_toml_lines, split_print)
from .toml_tables import FLOAT, INT, MATERIAL_SCHEMA, STR, check_tables, materials_of

__all__ = ["BEVEL", "CYLINDRICAL", "CutterSpec", "EaseOffCoefficients", "GearPair", "PRESETS",
           "blank_key_error", "has_easeoff", "load_pair", "parse_pair", "pair_to_toml",
           "without_easeoff"]

#: Built-in presets (resource files ``gearcontact/data/pairs/<name>.toml``): ``s0003``
#: calibrated to the published design point (tip-edge bearing on the coast flank pair,
#: docs/calibration.md) and ``s0003-centred``, the same pair with a centred drive-side
#: bearing (the Hertzian reference case).
PRESETS = ("s0003", "s0003-centred")


@dataclass(frozen=True)
class GearPair:
    """A hypoid (or spiral bevel, offset 0) pair with its cutter, ease-off and mounting.

    Parameters
    ----------
    name : str
        Label.
    pinion_teeth, gear_teeth : int
        z1 >= 5, z2 >= z1 (z2 = z1: a miter pair).
    offset_mm : float
        Hypoid offset E, mm, >= 0 (pinion axis at y = -E in the meshing frame).
    pinion_hand : str
        "right" or "left"; the gear has the opposite hand. A left-hand pair is the
        mirror image (y -> -y) of the right-hand one: pinion axis at y = +E, flanks
        reflected (:mod:`.mirror`, :func:`~.flank.build_flanks`).
    pinion_spiral_angle_deg : float
        Mean spiral angle beta1, degrees.
    gear_face_width_mm, pinion_face_width_mm : float
        Face widths along the pitch cones, mm (pinion >= gear).
    cutter : CutterSpec
    gear_mean_cone_distance_mm, gear_mean_pitch_radius_mm : float or None
        Exactly one of R2 or r2, mm.
    shaft_angle_deg : float
        90 only.
    working_depth_factor, clearance_factor, gear_addendum_factor : float
        k_d, k_c, c_ham (dimensionless, ISO 23509 clause 7).
    easeoff_drive, easeoff_coast : EaseOffCoefficients
        Pinion ease-off of the drive (pinion concave) and coast (pinion convex) flanks.
    assembly : AssemblyErrors
        Mounting errors E, P, G, alpha used by TCA (flanks are generated without them).
    pinion_material, gear_material : Material
    design_side : str
        Flank pair of the design point, "drive" (gear convex / pinion concave) or
        "coast": the side every command analyses and loads unless told otherwise.
    easeoff_tables : tuple of str
        Sides whose ease-off was given (a TOML without ``[easeoff.<side>]`` leaves the
        side out; the commands then synthesize it, :mod:`gearcontact.tca.synthesis`).
    machine : tuple of MachineSetup
        Empty, or the machine settings and blades of all four flanks
        (:mod:`.machine`): the flanks are then cut from them (:mod:`.generated`) instead
        of today's formate gear + conjugate pinion + ease-off.
    print_gear : tuple
        The ``[print.gear]`` table as typed, ``(key, value)`` items (lists as tuples),
        when the gear's settings were typed as a print (:mod:`.print_table`); empty
        otherwise. :func:`pair_to_toml` writes it back instead of the gear's tables while
        ``machine`` holds the gear it cuts.
    typed_gear : tuple of MachineSetup
        The gear's two set-ups of a file typing the gear alone (read with ``gear_alone``;
        ``machine`` empty: :func:`~.typed_pinion.typed_gear_machine_pair` cuts the pair).
    """

    name: str
    pinion_teeth: int
    gear_teeth: int
    offset_mm: float
    pinion_hand: str
    pinion_spiral_angle_deg: float
    gear_face_width_mm: float
    pinion_face_width_mm: float
    cutter: CutterSpec
    gear_mean_cone_distance_mm: float | None = None
    gear_mean_pitch_radius_mm: float | None = None
    shaft_angle_deg: float = 90.0
    working_depth_factor: float = 2.0
    clearance_factor: float = 0.125
    gear_addendum_factor: float = 0.35
    easeoff_drive: EaseOffCoefficients = field(default_factory=EaseOffCoefficients)
    easeoff_coast: EaseOffCoefficients = field(default_factory=EaseOffCoefficients)
    assembly: AssemblyErrors = field(default_factory=AssemblyErrors)
    pinion_material: Material = STEEL
    gear_material: Material = STEEL
    design_side: str = "drive"
    easeoff_tables: tuple = ("drive", "coast")
    machine: tuple = ()
    print_gear: tuple = ()
    typed_gear: tuple = ()

    #: the pair-file kind (a file without ``kind``; cylindrical pairs: ``"cylindrical"``)
    kind = "bevel"

    def __post_init__(self):
        if self.machine:
            got = sorted((s.member, s.side) for s in self.machine)
            want = sorted((m, side) for m in MEMBERS for side in ("drive", "coast"))
            if got != want:
                raise InputRangeError("[machine] / [blade]", [f"{m}.{side}" for m, side in got],
                                      "all four flanks: " + ", ".join(f"{m}.{side}" for m, side in want))
        if self.typed_gear and (self.machine or sorted(s.side for s in self.typed_gear if
                                                       s.member == "gear") != ["coast", "drive"]):
            raise InputRangeError("typed_gear", self.typed_gear, "the gear's two set-ups alone")
        if self.design_side not in ("drive", "coast"):
            raise InputRangeError("design.design_side", self.design_side, "'drive' or 'coast'")
        if self.pinion_hand not in ("right", "left"):
            raise InputRangeError("design.pinion_hand", self.pinion_hand, "'right' or 'left'")
        check_positive("design.gear_face_width_mm", self.gear_face_width_mm)
        check_pinion_face(self.pinion_face_width_mm, self.gear_face_width_mm)
        # the design itself is validated eagerly so that a bad pair fails on load
        blank = self.blank
        size = ("gear_mean_pitch_radius_mm" if self.gear_mean_cone_distance_mm is None
                else "gear_mean_cone_distance_mm")
        check_face_within_cone(self.gear_face_width_mm, blank.mean_cone_distance_gear_mm,
                               size_key=f"design.{size}", size_value=getattr(self, size))
        land = gear_top_land_mm(blank, self.cutter.point_width_mm)
        if land <= 0.0:
            # the point width that leaves a zero top land, else the working depth
            w_max = self.cutter.point_width_mm + land
            if w_max > 0.0:
                raise InputRangeError("cutter.point_width_mm", self.cutter.point_width_mm,
                                      f"< {w_max:.4g} mm (pointed gear teeth: the mean normal "
                                      f"top land is {land:.4g} mm)")
            t = (np.tan(np.radians(blank.pressure_angle_drive_deg))
                 + np.tan(np.radians(blank.pressure_angle_coast_deg)))
            k_max = np.pi / ((1.0 + self.clearance_factor) * t)
            raise InputRangeError("design.working_depth_factor", self.working_depth_factor,
                                  f"< {k_max:.4g} (pointed gear teeth: the mean normal top "
                                  f"land is {land:.4g} mm for any cutter point width)")
        if blank.dedendum_pinion_mm >= blank.mean_pitch_radius_pinion_mm:
            # h_fm1 = (c_ham + k_c) k_d m_mn must stay below the pinion pitch radius
            bound = blank.mean_pitch_radius_pinion_mm / (
                (self.gear_addendum_factor + self.clearance_factor) * blank.mean_normal_module_mm)
            raise InputRangeError("design.working_depth_factor", self.working_depth_factor,
                                  f"< {bound:.4g} (the pinion dedendum must stay below the "
                                  f"pinion mean pitch radius "
                                  f"{blank.mean_pitch_radius_pinion_mm:.4g} mm)")

    @cached_property
    def blank(self) -> BlankDesign:
        """Pitch-cone design (ISO 23509 Method 1) of this pair."""
        return design_blank(
            pinion_teeth=self.pinion_teeth, gear_teeth=self.gear_teeth,
            offset_mm=self.offset_mm, pinion_spiral_angle_deg=self.pinion_spiral_angle_deg,
            cutter_radius_mm=self.cutter.radius_mm,
            gear_mean_pitch_radius_mm=self.gear_mean_pitch_radius_mm,
            gear_mean_cone_distance_mm=self.gear_mean_cone_distance_mm,
            shaft_angle_deg=self.shaft_angle_deg,
            working_depth_factor=self.working_depth_factor,
            clearance_factor=self.clearance_factor,
            gear_addendum_factor=self.gear_addendum_factor,
            pressure_angle_drive_deg=self.cutter.pressure_angle_drive_deg,
            pressure_angle_coast_deg=self.cutter.pressure_angle_coast_deg,
            limit_pressure_angle_factor=self.cutter.limit_pressure_angle_factor)

    @property
    def ratio(self) -> float:
        """Gear ratio u = z2/z1."""
        return self.gear_teeth / self.pinion_teeth

    def kinematics(self, *, with_errors: bool = True) -> MeshKinematics:
        """Meshing kinematics; ``with_errors=False`` gives the nominal (generating) one."""
        errors = self.assembly if with_errors else AssemblyErrors()
        return MeshKinematics(offset_mm=self.offset_mm, ratio=self.ratio, errors=errors,
                              hand=self.pinion_hand)


# --------------------------------------------------------------------------- TOML

#: section -> {key: (expected type, required)}; ``""`` section = top level.
_SCHEMA: dict[str, dict[str, tuple[str, bool]]] = {
    "": {"name": (STR, False)},
    "teeth": {"pinion": (INT, True), "gear": (INT, True)},
    "axes": {"shaft_angle_deg": (FLOAT, False), "offset_mm": (FLOAT, True)},
    "design": {"pinion_hand": (STR, True), "gear_mean_cone_distance_mm": (FLOAT, False),
               "gear_mean_pitch_radius_mm": (FLOAT, False),
               "pinion_spiral_angle_deg": (FLOAT, True), "gear_face_width_mm": (FLOAT, True),
               "pinion_face_width_mm": (FLOAT, True), "working_depth_factor": (FLOAT, False),
               "clearance_factor": (FLOAT, False), "gear_addendum_factor": (FLOAT, False),
               "design_side": (STR, False)},
    "cutter": {"radius_mm": (FLOAT, True), "point_width_mm": (FLOAT, True),
               "edge_radius_mm": (FLOAT, True), "pressure_angle_drive_deg": (FLOAT, False),
               "pressure_angle_coast_deg": (FLOAT, False),
               "limit_pressure_angle_factor": (FLOAT, False)},
    "easeoff.drive": {k: (FLOAT, False) for k in EaseOffCoefficients.__dataclass_fields__},
    "easeoff.coast": {k: (FLOAT, False) for k in EaseOffCoefficients.__dataclass_fields__},
    "assembly": {k: (FLOAT, False) for k in ("E_mm", "P_mm", "G_mm", "alpha_deg")},
    **MATERIAL_SCHEMA,
}
for _m in MEMBERS:
    for _side in ("drive", "coast"):
        _SCHEMA[f"machine.{_m}.{_side}"] = {
            **{k: (FLOAT, req) for k, (_, req) in MACHINE_KEYS.items()},
            **{k: (FLOAT, False) for k in MODIFIED_ROLL_KEYS + HELICAL_KEYS}}
        _SCHEMA[f"blade.{_m}.{_side}"] = {k: (STR if k == "kind" else FLOAT, req)
                                          for k, req in BLADE_KEYS.items()}
_REQUIRED_SECTIONS = ("teeth", "axes", "design", "cutter")


def parse_pair(doc: dict, *, name: str = "pair", gear_alone: bool = False) -> GearPair:
    """Build a :class:`GearPair` from a parsed TOML document (see module docstring); a
    ``[print.gear]`` table is converted into the gear's tables first (:mod:`.print_table`)
    and they are checked as typed ones. ``gear_alone``: the gear's tables without the
    pinion's are read into ``typed_gear`` (else refused, naming the pinion's tables)."""
    doc, printed = split_print(doc)
    if printed is not None:
        teeth = check_tables(doc, _SCHEMA, _REQUIRED_SECTIONS,
                             also=("print.gear",))["teeth"]["gear"]
        converted = print_gear_tables(printed, gear_teeth=teeth)
        doc = {**doc, **{kind: {**doc.get(kind, {}), **tables}
                         for kind, tables in converted.items()}}
    s = check_tables(doc, _SCHEMA, _REQUIRED_SECTIONS, also=("print.gear",))
    design = dict(s["design"])
    if ("gear_mean_cone_distance_mm" in design) == ("gear_mean_pitch_radius_mm" in design):
        raise InputRangeError("design.gear_mean_cone_distance_mm / design.gear_mean_pitch_radius_mm",
                              None, "exactly one of the two keys")
    materials = materials_of(s)
    named = [n for n in s if n.startswith(("machine.", "blade."))]
    machine, alone = (), False
    if named:
        if any(n.startswith("easeoff.") for n in s):
            raise InputRangeError("[easeoff.*]", "given with [machine.*] / [blade.*]",
                                  "either machine settings (the flanks are cut from them) or "
                                  "an ease-off on today's conjugate pinion, not both")
        missing = [f"[{kind}.{m}.{side}]" for kind in ("machine", "blade") for m in MEMBERS
                   for side in ("drive", "coast") if f"{kind}.{m}.{side}" not in s]
        pinion_only = len(missing) == 4 and all(".pinion." in m for m in missing)
        alone = gear_alone and pinion_only
        if missing and not alone:
            raise InputRangeError(", ".join(missing), None, (
                "required with any [machine.*] / [blade.*] table (all four flanks are cut "
                "from settings)" if printed is None else "required with [print.gear]: the "
                "print cuts the gear, the pinion its own settings (a pinion page typed by "
                "docs/machine_settings.md sec. 2)") + (
                "; a gear typed alone: `gearcontact design --machine-settings` on this file "
                "derives its standard pinion (docs/machine_settings.md sec. 5)"
                if pinion_only else ""))
        try:
            machine = tuple(setup_from_tables(m, side, s[f"machine.{m}.{side}"],
                                              s[f"blade.{m}.{side}"])
                            for m in (("gear",) if alone else MEMBERS)
                            for side in ("drive", "coast"))
        except InputRangeError as exc:
            raise exc if printed is None else printed_key_error(exc, printed) from None
    typed_gear = machine if alone else ()
    machine = () if alone else machine
    try:
        pair = _pair_of_tables(s, name=name, machine=machine, typed_gear=typed_gear,
                               printed=printed, materials=materials, design=design)
    except InputRangeError as exc:      # the blank design's arguments, named as typed
        raise blank_key_error(exc) from None
    if printed is not None:
        check_print_blank(pair, printed)
    return pair


#: The blank design's argument names (:func:`~.blank.design_blank`) -> the pair file's
#: dotted keys, for its errors.
_BLANK_KEYS = {"pinion_teeth": "teeth.pinion", "gear_teeth": "teeth.gear",
               "offset_mm": "axes.offset_mm", "shaft_angle_deg": "axes.shaft_angle_deg",
               **{k: f"design.{k}" for k in (
                   "pinion_spiral_angle_deg", "working_depth_factor", "clearance_factor",
                   "gear_addendum_factor", "gear_mean_pitch_radius_mm",
                   "gear_mean_cone_distance_mm")},
               "cutter_radius_mm": "cutter.radius_mm",
               **{k: f"cutter.{k}" for k in ("pressure_angle_drive_deg",
                                             "pressure_angle_coast_deg",
                                             "limit_pressure_angle_factor")}}


def blank_key_error(exc: InputRangeError) -> InputRangeError:
    """``exc`` with a blank design argument's name (field, and in the allowed range a
    bound that is another argument: ``>= pinion_teeth = 14``) as the file's key: the
    reader's errors, and those of the checks after it that name the blank's fields
    (:func:`~.contact_ratio.check_contact_ratio`)."""
    field = " / ".join(_BLANK_KEYS.get(f, f) for f in str(exc.field).split(" / "))
    allowed = re.sub(r"(?<![.\w])(" + "|".join(_BLANK_KEYS) + r")\b",
                     lambda m: _BLANK_KEYS[m.group(1)], str(exc.allowed))
    if field == exc.field and allowed == exc.allowed:
        return exc
    return InputRangeError(field, exc.value, allowed)


def _pair_of_tables(s: dict, *, name, machine, typed_gear, printed, materials,
                    design) -> GearPair:
    """The :class:`GearPair` of the checked tables ``s`` (:func:`parse_pair`)."""
    return GearPair(
        name=s[""].get("name", name), machine=machine, typed_gear=typed_gear,
        pinion_teeth=s["teeth"]["pinion"], gear_teeth=s["teeth"]["gear"],
        offset_mm=s["axes"]["offset_mm"],
        shaft_angle_deg=s["axes"].get("shaft_angle_deg", 90.0),
        cutter=CutterSpec(**s["cutter"]),
        easeoff_drive=EaseOffCoefficients(**s.get("easeoff.drive", {})),
        easeoff_coast=EaseOffCoefficients(**s.get("easeoff.coast", {})),
        assembly=AssemblyErrors(**s.get("assembly", {})),
        pinion_material=materials["pinion"], gear_material=materials["gear"],
        easeoff_tables=(("drive", "coast") if machine or typed_gear else
                        tuple(side for side in ("drive", "coast") if f"easeoff.{side}" in s)),
        print_gear=() if printed is None else tuple(
            (k, tuple(v) if isinstance(v, list) else v) for k, v in printed.items()),
        **design)


#: ``kind`` values of the pair files; absent is a bevel/hypoid pair (:class:`GearPair`).
BEVEL, CYLINDRICAL = GearPair.kind, CYLINDRICAL_KIND
#: What each kind can be used for today (the message of a command that refuses one).
_KIND_USE = {CYLINDRICAL: "only `gearcontact design`, `tca`, `ltca`, `lte`, `analyze`, "
                          "`sweep`, `bending`, `twin`, `rtl serve`, `export flanks` and "
                          "`export fmu` read cylindrical pairs so far (docs/cylindrical.md)"}


def load_pair(source: str | Path, *, kinds: tuple[str, ...] = (BEVEL,),
              gear_alone: bool = False) -> GearPair | CylindricalPair:
    """Load a pair from a preset name (``"s0003"``) or a ``.toml`` file path.

    The file's top-level ``kind`` selects the format: absent, a bevel/hypoid
    :class:`GearPair`; ``"cylindrical"``, a
    :class:`~gearcontact.geometry.cylindrical.pair.CylindricalPair`.

    Parameters
    ----------
    source : str or Path
    kinds : tuple of str
        The kinds the caller can use (``"bevel"``, ``"cylindrical"``); a file of
        another kind is refused before it is validated.
    gear_alone : bool
        Read a gear typed without its pinion (:attr:`GearPair.typed_gear`), not refuse it.

    Raises
    ------
    InputRangeError
        If ``source`` is neither a preset nor a readable UTF-8 TOML file, for a TOML
        syntax error, a ``kind`` the caller cannot use, and for a missing, mistyped or
        out-of-range field or an impossible design; the message names the file (when
        one is involved) and the field.
    """
    text = str(source)
    if text in PRESETS:
        raw = resources.files("gearcontact").joinpath(f"data/pairs/{text}.toml").read_text()
        label, where = text, ""
    else:
        path = Path(text)
        if not path.is_file():
            raise InputRangeError("pair", text, f"a preset {PRESETS} or an existing TOML "
                                                "file (it is neither a preset nor a file)")
        raw = read_text_file(path, field="pair", what="a TOML file")
        label, where = path.stem, f"{path}: "
    try:
        doc = tomllib.loads(raw)
    except tomllib.TOMLDecodeError as exc:
        raise InputRangeError(f"{where or label + ' '}(TOML syntax)", str(exc),
                              "valid TOML") from None
    kind = doc.get("kind", BEVEL)
    try:
        if isinstance(doc.get("drivetrain"), dict):     # the twin's other file kind
            raise InputRangeError("[drivetrain]", "table", "a pair file ([teeth], [axes], "
                                  "...): this is a drivetrain file, given with "
                                  "--drivetrain (gearcontact twin, export fmu --kind "
                                  "drivetrain) beside a pair")
        if "kind" in doc and kind != CYLINDRICAL:
            raise InputRangeError("kind", kind, f"'{CYLINDRICAL}' or absent (a bevel/hypoid "
                                                "pair)")
        if kind not in kinds:
            raise InputRangeError("kind", kind, f"absent (a bevel/hypoid pair) for this "
                                                f"command: {_KIND_USE[kind]}")
        if kind == CYLINDRICAL:
            return parse_cylindrical_pair(doc, name=label)
        return parse_pair(doc, name=label, gear_alone=gear_alone)
    except InputRangeError as exc:
        if not where:
            raise
        raise InputRangeError(f"{where}{exc.field}", exc.value, exc.allowed) from None


def has_easeoff(pair: GearPair) -> bool:
    """True if ``pair`` (a bevel pair without machine tables) has a non-zero ease-off
    coefficient on either side: its analysed pinion is not the conjugate one."""
    return not pair.machine and any(
        any(dataclasses.astuple(getattr(pair, f"easeoff_{side}"))) for side in ("drive", "coast"))


def without_easeoff(pair: GearPair) -> GearPair:
    """``pair`` as its file would read without ``[easeoff.*]`` tables: both sides'
    coefficients zero and none given (``easeoff_tables`` empty), so that every command
    synthesizes them; what ``design --synthesize-easeoff`` starts from (it makes both
    tables afresh from the conjugate pinion, whatever tables the file holds)."""
    return dataclasses.replace(pair, easeoff_drive=EaseOffCoefficients(),
                               easeoff_coast=EaseOffCoefficients(), easeoff_tables=())


def pair_to_toml(pair: GearPair, *, comments: dict[str, str] | None = None) -> str:
    """The TOML text of ``pair`` (the format of the module docstring; floats at full
    precision, so ``parse_pair(tomllib.loads(pair_to_toml(p)))`` rebuilds ``p``).

    ``comments`` maps a table name (``""`` for the file head, ``"easeoff.coast"``, ...)
    to a comment block written above that table.
    """
    comments = comments or {}

    def block(name: str, items: dict) -> list[str]:
        lines = [f"# {c}" if c else "#" for c in comments.get(name, "").splitlines()]
        if name:
            lines.append(f"[{name}]")
        for key, value in items.items():
            if value is None:
                continue
            lines.append(f"{key} = " + (f'"{value}"' if isinstance(value, str) else repr(value)))
        return lines + [""]

    design = {"pinion_hand": pair.pinion_hand,
              "gear_mean_cone_distance_mm": pair.gear_mean_cone_distance_mm,
              "gear_mean_pitch_radius_mm": pair.gear_mean_pitch_radius_mm,
              "pinion_spiral_angle_deg": pair.pinion_spiral_angle_deg,
              "gear_face_width_mm": pair.gear_face_width_mm,
              "pinion_face_width_mm": pair.pinion_face_width_mm,
              "working_depth_factor": pair.working_depth_factor,
              "clearance_factor": pair.clearance_factor,
              "gear_addendum_factor": pair.gear_addendum_factor,
              "design_side": pair.design_side}
    a = pair.assembly
    out = block("", {"name": pair.name})
    out += block("teeth", {"pinion": pair.pinion_teeth, "gear": pair.gear_teeth})
    out += block("axes", {"shaft_angle_deg": pair.shaft_angle_deg, "offset_mm": pair.offset_mm})
    out += block("design", design)
    out += block("cutter", dataclasses.asdict(pair.cutter))
    for side in ("drive", "coast") if not pair.machine else ():
        c = getattr(pair, f"easeoff_{side}")
        if side not in pair.easeoff_tables and not any(dataclasses.astuple(c)):
            continue            # no table given and none set: it stays "to be synthesized"
        out += block(f"easeoff.{side}", {k: float(v) for k, v in dataclasses.asdict(c).items()})
    # a gear typed as a print is written as typed while the pair cuts the print's gear
    printed = cuts_the_printed_gear(pair)
    if printed:
        out += block("print.gear", {})[:-2] + printed_toml_lines(pair.print_gear) + [""]
    for setup in pair.machine or pair.typed_gear:
        if printed and setup.member == "gear":
            continue
        machine, blade = setup_to_tables(setup)
        out += block(f"machine.{setup.member}.{setup.side}", machine)
        out += block(f"blade.{setup.member}.{setup.side}", blade)
    out += block("assembly", {"E_mm": a.E_mm, "P_mm": a.P_mm, "G_mm": a.G_mm,
                              "alpha_deg": a.alpha_deg})
    for member in ("pinion", "gear"):
        m = getattr(pair, f"{member}_material")
        out += block(f"material.{member}", {"youngs_modulus_gpa": m.youngs_modulus_mpa / 1e3,
                                            "poisson_ratio": m.poisson_ratio})
    return "\n".join(out)
