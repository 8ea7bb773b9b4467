"""The ``[print.gear]`` table of a pair file: a summary sheet's gear page typed verbatim,
its words and numbers as printed, converted on load into the gear's
``[machine.gear.*]`` / ``[blade.gear.*]`` tables (docs/machine_settings.md sec. 2,
"Typing a print", and sec. 3).

.. code-block:: toml

    [print.gear]                              # the No. 16 gear page, as printed
    machine_root_angle = "69D 7M"
    machine_centre_to_back = "MD -0.240"
    sliding_base = "WITH 0.070"
    blank_offset = "DN 0.225"
    radial_in = 4.108
    cradle_angle = "67D 11M"
    tilt_angle = "0"
    ratio_nc_75 = 0.545665                    # work / cradle = 75 x this / [teeth] gear
    cradle_test_roll_deg = 30.0               # optional, with work_test_roll: checked
    work_test_roll = "29D 57M"
    cutter_diameter_in = 9.000
    point_width_finish_in = 0.0900
    edge_radius_in = 0.040
    blades = ["OB 24D 30M", "IB 18D 0M"]
    gear_crown_to_crossing_point_in = 1.293   # the MD's datum, from the print's blank
    cone_distance_in = 4.274                  # outer
    gear_pitch_angle_deg = "74D 49M"
    gear_addendum_in = 0.064                  # outer
    gear_spiral_angle_deg = "26D 57M"         # what the check states for the gear
    gear_pressure_angle_convex_deg = "18D 0M"
    gear_pressure_angle_concave_deg = "24D 30M"
    face_width_in = 1.250                     # the mean point: cone_distance_in - F / 2
    gear_hand = "RIGHT"

The words are mapped by :func:`~.print_words.gear_tables_from_print` (the gear's tooth
number from ``[teeth]``); the tables it gives go through the same type check,
range check (:func:`~.machine.setup_from_tables`) and, when a command loads the pair,
the typed-settings check (:mod:`.blank_check`), which states for the gear the page's
printed blank and the print's rounding (:mod:`.print_blank`), and names a slip by the
print's key. An error a converted value raises names the print's key as typed
(``print.gear.radial_in``), with the converted key and value.

The MD's datum (the pitch apex from the crossing point) comes from the print's own blank
numbers, not from the pair's ISO 23509 blank: the print's MD is measured from the print
program's crossing point and apex, so the gear is cut as the print says whatever blank
design the pair's ``[design]`` gives (a hand-typed sheet and this table then agree
exactly). That datum is compared with the pair's own (:func:`check_print_blank`), and so
are the printed angles and mean cone distance: beyond the print's rounding one
:class:`PrintBlankNote` lists them, a datum beyond the gear's
whole depth (a datum number typed in mm, a digit lost) an input error. The pair's
``[cutter]`` must be the print's cutter (its nominal radius is the generating gear's
circle the check measures the spiral angle on).

The pinion has no print table (no pinion page was read, docs sec. 2): a pair with
``[print.gear]`` types ``[machine.pinion.*]`` / ``[blade.pinion.*]`` (e.g. the standard
settings ``gearcontact design --pair FILE --machine-settings`` writes from the blank).
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from ..validation import InputRangeError, format_number
from .machine import MachineKinematics
from .print_blank import (DATUM_LENGTHS, PRINT_BLANK_KEYS, PRINT_ROUNDING, SOURCE_KEYS,
                          apex_in, apex_rounding_in, blank_differences, print_gear_tables,
                          printed_blank, printed_gear_setups, printed_hand)
from .print_words import INCH_MM, md_value
from .toml_tables import PRINTED, check_tables

__all__ = ["PRINT_KEYS", "PRINT_ROUNDING", "PrintBlankNote", "PrintDatumWarning", "TABLE",
           "check_print_blank", "print_gear_setups", "print_gear_tables", "printed_key_error", "printed_toml_lines",
           "split_print"]

#: The table's name in a pair file (and in every error).
TABLE = "print.gear"
#: The keys of ``[print.gear]`` -> required (:func:`~.print_words.gear_tables_from_print`).
PRINT_KEYS = {"machine_root_angle": True, "machine_centre_to_back": True,
              "sliding_base": True, "blank_offset": True, "radial_in": True,
              "cradle_angle": True, "tilt_angle": True, "ratio_nc_75": True,
              "cradle_test_roll_deg": False, "work_test_roll": False,
              "cutter_diameter_in": True, "point_width_finish_in": True,
              "edge_radius_in": True, "blades": True,
              "gear_crown_to_crossing_point_in": True, "cone_distance_in": True,
              "gear_pitch_angle_deg": True, "gear_addendum_in": True,
              **{k: True for k in PRINT_BLANK_KEYS}}
_SIDES = ("drive", "coast")
_SCHEMA = {"": {}, TABLE: {k: (PRINTED, required) for k, required in PRINT_KEYS.items()}}


class PrintBlankNote(UserWarning):
    """The pair's blank (its ISO 23509 design) is not the page's printed blank beyond the
    print's rounding: spiral, pitch or pressure angles, mean cone distance, the MD's
    datum (:func:`check_print_blank`; one note per load, not a slip: the gear is cut and
    checked as the page prints)."""


#: The earlier name of :class:`PrintBlankNote` (it named the MD's datum only).
PrintDatumWarning = PrintBlankNote


def split_print(doc: dict) -> tuple[dict, dict | None]:
    """``(doc without [print], the checked [print.gear] table or None)``.

    Raises
    ------
    InputRangeError
        A ``[print.<member>]`` other than ``gear`` (no pinion page's words are mapped), an
        unknown or missing key of ``[print.gear]`` (naming ``print.gear.<key>``), a value
        of no printed form, or ``[print.gear]`` given with a ``[machine.gear.*]`` /
        ``[blade.gear.*]`` table.
    """
    if "print" not in doc:
        return doc, None
    table = doc["print"]
    for sub in table if isinstance(table, dict) else ():
        if sub != "gear":
            raise InputRangeError(f"print.{sub}", "table" if isinstance(table[sub], dict)
                                  else table[sub], "[print.gear] only (a spread-"
                                  "blade gear page): a pinion page's words are on no print "
                                  "read; type [machine.pinion.*] / [blade.pinion.*] "
                                  "(docs/machine_settings.md sec. 2-3)")
    printed = check_tables({"print": table}, _SCHEMA, ()).get(TABLE)
    if printed is None:
        raise InputRangeError(f"[{TABLE}]", None, "a table of the gear page's words "
                                                   "(geometry.print_table)")
    rest = {k: v for k, v in doc.items() if k != "print"}
    typed = [f"[{kind}.gear.{side}]" for kind in ("machine", "blade") for side in _SIDES
             if isinstance(rest.get(kind), dict) and isinstance(rest[kind].get("gear"), dict)
             and side in rest[kind]["gear"]]
    if typed:
        raise InputRangeError(f"[{TABLE}]", "given with " + ", ".join(typed),
                              "either the print's words (the gear's tables converted from "
                              "them on load) or the gear's typed tables, not both")
    return rest, printed


def print_gear_setups(printed: dict, *, gear_teeth: int) -> tuple:
    """The gear's two :class:`~.machine.MachineSetup` (drive, coast) a ``[print.gear]``
    table cuts (:func:`~.print_blank.printed_gear_setups`, errors renamed to the print's
    key)."""
    try:
        return printed_gear_setups(printed, gear_teeth=gear_teeth)
    except InputRangeError as exc:
        raise printed_key_error(exc, printed) from None


def printed_key_error(exc: InputRangeError, printed: dict) -> InputRangeError:
    """``exc`` (raised on a converted ``machine.gear.*`` / ``blade.gear.*`` value)
    renamed to the print's key as typed, the converted key and value kept in the text;
    another error unchanged."""
    parts = exc.field.split(".")
    if len(parts) != 4 or parts[:2] not in (["machine", "gear"], ["blade", "gear"]) \
            or parts[3] not in SOURCE_KEYS:
        return exc
    key = SOURCE_KEYS[parts[3]]
    value = exc.value if not isinstance(exc.value, float) else format_number(exc.value)
    return InputRangeError(f"{TABLE}.{key}", printed.get(key),
                           f"a value whose conversion ({exc.field} = {value}) lies in "
                           f"{exc.allowed}" + (" (the print's lengths are inches, x 25.4 "
                                               "mm: typed in mm?)" if key.endswith("_in")
                                               else ""))


def _check_cutter(pair, printed: dict) -> None:
    """The pair's ``[cutter]`` is the print's: nominal radius D/2, point width, edge
    radius, within the print's rounding plus the typed value's 4th decimal in mm."""
    rows = (("cutter_diameter_in", "radius_mm", 0.5, "length_in"),
            ("point_width_finish_in", "point_width_mm", 1.0, "point_width_in"),
            ("edge_radius_in", "edge_radius_mm", 1.0, "length_in"))
    for key, cutter_key, factor, rounding in rows:
        printed_mm = factor * INCH_MM * printed[key]
        typed = getattr(pair.cutter, cutter_key)
        tol = factor * INCH_MM * PRINT_ROUNDING[rounding] + 5e-5
        if abs(printed_mm - typed) > tol:
            hint = (" (typed in mm? the print's lengths are inches)"
                    if abs(printed_mm / INCH_MM - typed) <= tol else "")
            raise InputRangeError(
                f"{TABLE}.{key}", printed[key],
                f"the pair's cutter: cutter.{cutter_key} = {format_number(typed)} mm "
                f"{'x 2 ' if factor != 1.0 else ''}/ 25.4 = "
                f"{typed / (factor * INCH_MM):.5g} in within the print's rounding "
                f"({tol:.2g} mm){hint}; the print's cutter cuts the gear, and [cutter] "
                "is the nominal cutter the blank and the check use (docs/"
                "machine_settings.md sec. 3)")


def _root_height_mm(settings, blank) -> float:
    """Height over the cutter's tip plane (tilt 0: the cradle plane ``z_m = 0``) of the
    gear's root below its mean point, on the generatrix nearest the plane, at zero roll:
    about 0 when the blade tips cut the root there (the root datum of
    :mod:`.blank_check`, here in closed form)."""
    _, _, b, a0 = MachineKinematics(settings)._fixed
    d, r, h = (math.radians(blank.pitch_angle_gear_deg), blank.mean_cone_distance_gear_mm,
               blank.dedendum_gear_mm)
    root = np.array([r * math.sin(d) - h * math.cos(d), 0.0, r * math.cos(d) + h * math.sin(d)])
    return float((a0 + b @ root)[2])


def _generating_spiral_deg(settings, radius_mm: float) -> float | None:
    """The print's spiral angle of the settings, ``cos(beta) = |S_r sin q - E_m| / r_c``
    (docs/machine_settings.md sec. 2); None where the nominal cutter circle does not
    cross the root line."""
    c = MachineKinematics(settings).cutter_to_machine(np.zeros(3))
    off = abs(float(c[1]) - settings.blank_offset_mm)
    return math.degrees(math.acos(off / radius_mm)) if off < radius_mm else None


def _check_lengths(pair, printed: dict) -> None:
    """A print's length typed in mm (25.4 times its inches), where the settings are grossly
    off and the key's value / 25.4 puts them right: an input error naming the key.

    Grossly off: the gear's root at its mean point more than its whole depth off the
    cutter's tip plane (the sliding base, the MD), or the print's spiral angle
    (:func:`_generating_spiral_deg`) not within
    :data:`~.blank_check.GROSS_SPIRAL_DEG` of the printed one (the radial, the blank
    offset).
    Put right: the root within the typed-settings check's root datum bound
    (:data:`~.blank_check.ROOT_DATUM_FRACTION` of the dedendum) plus the print's rounding
    of the two, the spiral angle within the gross bound. Anything else is left to the
    typed-settings check (a sign word, the MD read +)."""
    # here: blank_check imports the flank solvers (scipy.optimize), which reading a pair
    # without a print must not (tests/test_package.py)
    from .blank_check import GROSS_SPIRAL_DEG, ROOT_DATUM_FRACTION

    blank, gear = pair.blank, (pair.machine or pair.typed_gear)[0].settings
    depth = blank.addendum_gear_mm + blank.dedendum_gear_mm
    datum = (ROOT_DATUM_FRACTION * blank.dedendum_gear_mm
             + 2.0 * INCH_MM * PRINT_ROUNDING["length_in"])
    md_mm = INCH_MM * md_value(f"{TABLE}.machine_centre_to_back",
                               printed["machine_centre_to_back"])
    shrink = {"sliding_base": {"sliding_base_mm": gear.sliding_base_mm / INCH_MM},
              "machine_centre_to_back": {"machine_centre_to_back_mm": (
                  gear.machine_centre_to_back_mm - md_mm * (1.0 - 1.0 / INCH_MM))},
              "radial_in": {"radial_distance_mm": gear.radial_distance_mm / INCH_MM},
              "blank_offset": {"blank_offset_mm": gear.blank_offset_mm / INCH_MM}}

    stated = printed_blank(printed, gear_teeth=pair.gear_teeth).spiral_angle_deg

    def spiral_off(st) -> float:
        beta = _generating_spiral_deg(st, pair.cutter.radius_mm)
        return math.inf if beta is None else abs(beta - stated)

    tests = ((lambda st: abs(_root_height_mm(st, blank)), depth, datum,
              ("sliding_base", "machine_centre_to_back"),
              "the gear's root at its mean point on the cutter's tip plane"),
             (spiral_off, GROSS_SPIRAL_DEG, GROSS_SPIRAL_DEG, ("radial_in", "blank_offset"),
              "the print's spiral angle, the nominal cutter circle against the root line, "
              "the printed one"))
    for off, gross, right, keys, what in tests:
        if off(gear) <= gross:
            continue
        for key in keys:
            if off(dataclasses.replace(gear, **shrink[key])) <= right:
                raise InputRangeError(f"{TABLE}.{key}", printed[key],
                                      f"a length in inches ({what}: with its number / 25.4 "
                                      "it is; typed in mm? the print's lengths are inches)")


def check_print_blank(pair, printed: dict) -> float:
    """The print's blank numbers a ``[print.gear]`` table uses against ``pair``'s blank.

    The ``[cutter]`` must be the print's cutter, and the printed hand of spiral
    (``gear_hand``) the pair's (``[design] pinion_hand`` the other): input errors naming
    the print's key otherwise. The MD's datum, the pitch apex from the crossing point by
    the print's chain (crown to crossing point, outer cone distance, pitch angle, outer
    addendum: :func:`~.print_blank.apex_in`), is compared with the pair's blank's
    (``gear_apex_z_mm``) within the print's rounding propagated
    (:func:`~.print_blank.apex_rounding_in`); beyond the gear's mean whole depth it is
    an input error naming the datum key (and a length typed in mm where the mm value
    fits). The pair's blank against the printed one (the datum, the spiral, pitch and
    pressure angles, the mean cone distance: :func:`~.print_blank.blank_differences`):
    where any differs beyond the print's rounding, one :class:`PrintBlankNote` lists
    them, the pair's values beside the printed ones (the gear is still cut about the
    print's apex and checked against the page, :mod:`.blank_check`). Then the settings'
    lengths typed in mm (:func:`_check_lengths`). ``pair`` holds the gear the print
    cuts (its first set-up).

    Returns
    -------
    float
        The datum's difference, print's - pair's, mm.
    """
    _check_cutter(pair, printed)
    other = {"right": "left", "left": "right"}
    if printed_hand(printed) != other[pair.pinion_hand]:
        raise InputRangeError(f"{TABLE}.gear_hand", printed["gear_hand"],
                              f"the gear's hand of the pair's blank, {other[pair.pinion_hand]} "
                              f"(design.pinion_hand = '{pair.pinion_hand}'): the two tables "
                              "state the hand both, and contradict each other")
    blank = pair.blank
    a_print = apex_in(printed)
    a_pair = blank.gear_apex_z_mm / INCH_MM
    diff_mm = INCH_MM * (a_print - a_pair)
    tol_mm = INCH_MM * apex_rounding_in(printed)
    depth = blank.addendum_gear_mm + blank.dedendum_gear_mm
    chain = ", ".join(f"{TABLE}.{k}" for k in (*DATUM_LENGTHS, "gear_pitch_angle_deg"))
    if abs(diff_mm) > depth:
        # a datum length typed in mm: the one whose value / 25.4 brings the apex back
        slipped = [k for k in DATUM_LENGTHS if abs(INCH_MM * (apex_in(
            printed, **{k: printed[k] / INCH_MM}) - a_pair)) <= depth]
        key = slipped[0] if slipped else DATUM_LENGTHS[0]
        hint = " (typed in mm? the print's lengths are inches)" if slipped else ""
        raise InputRangeError(
            f"{TABLE}.{key}", printed[key],
            f"a datum that puts the gear's pitch apex within its whole depth "
            f"({depth:.3f} mm) of the pair's blank's, {a_pair:.4f} in from the crossing "
            f"point: the print's chain ({chain}) gives {a_print:.4f} in{hint}")
    found = blank_differences(printed, blank, gear_teeth=pair.gear_teeth)
    if abs(diff_mm) > tol_mm:
        found.append(f"the MD's datum, the pitch apex from the crossing point, "
                     f"{a_pair:.4f} in, printed {a_print:.4f} in by the print's chain "
                     f"({chain}): {diff_mm:+.3f} mm, rounding {tol_mm:.3f} mm")
    if found:
        warnings.warn(
            f"{TABLE}: the pair's design blank is not the print's (what [design] and "
            "[cutter] give by ISO 23509 against what the page prints, beyond the print's "
            "rounding): " + "; ".join(found) + ". The gear is cut about the print's apex "
            "and its settings are checked against the page; the pair's blank places the "
            "flanks for the contact (docs/machine_settings.md sec. 3)", PrintBlankNote,
            stacklevel=3)
    _check_lengths(pair, printed)
    return diff_mm


def _toml_value(value) -> str:
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return repr(value)


def printed_toml_lines(printed) -> list[str]:
    """The ``[print.gear]`` table's lines as typed (``printed``: its ``(key, value)``
    items or a mapping), for :func:`~.pair.pair_to_toml`."""
    items = printed.items() if isinstance(printed, dict) else printed
    return [f"[{TABLE}]", *(f"{k} = {_toml_value(v)}" for k, v in items)]
