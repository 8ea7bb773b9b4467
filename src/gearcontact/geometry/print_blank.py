"""The blank a summary sheet's gear page prints, and the print's rounding: what the
typed-settings check states for a gear typed as ``[print.gear]`` (:mod:`.print_table`;
docs/machine_settings.md sec. 2 "Typing a print", "The check when a pair is loaded",
sec. 3).

A gear page prints, beside the settings, the blank its program designed: the gear's
spiral angle (``"26D 57M"``), its pressure angles concave / convex (the generating gear's,
``"24D 30M"`` / ``"18D 0M"``), the outer cone distance and the face width (the mean
point at ``A_o - F / 2``), the pitch angle and the hand of spiral (``"RIGHT"``). A
pair's own blank is the ISO 23509 design of its ``[design]`` table, which need not be the
print program's (the published page: 26.799 deg against the printed 26D 57M), so a gear
cut from the print is checked against what the page prints (:func:`printed_blank`),
within the print's rounding (:data:`PRINT_ROUNDING`: half a unit of each printed digit,
propagated through the settings by the check, :mod:`.blank_check`), and the pair's
blank is compared with the page once, as a note (:func:`blank_differences`).

The names a slip of a converted setting is given are the print's keys as typed
(:func:`print_key`: ``machine.gear.coast.blank_offset_mm`` ->
``print.gear.blank_offset``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from ..validation import InputRangeError, check_finite
from .machine import setup_from_tables
from .print_words import (BLADE_WORDS, INCH_MM, degrees_minutes, gear_tables_from_print,
                          pitch_apex_from_crossing_point_in)

__all__ = ["HAND_WORDS", "PRINT_BLANK_KEYS", "PRINT_ROUNDING", "SOURCE_KEYS", "PrintedBlank",
           "apex_in", "apex_rounding_in", "blank_differences", "cuts_the_printed_gear",
           "print_gear_tables", "print_key", "printed_blank", "printed_gear_setups",
           "printed_hand"]

#: Half a unit of the print's last digit (the one print read prints lengths to 0.001 in,
#: the point width to 0.0001 in, angles to the minute, the Nc/75 ratio to 6 decimals):
#: lengths in inches, angles in deg. A TOML number keeps no trailing zeros (``9.000`` is
#: read ``9.0``), so the digits are the print's, not the typed text's.
PRINT_ROUNDING = {"length_in": 0.0005, "point_width_in": 0.00005, "angle_deg": 0.5 / 60.0,
                  "ratio": 5e-7}
#: The printed blank lines the check states for the gear (all required): the gear's
#: spiral angle, its pressure angles (convex: the drive flank, concave: the coast), the
#: face width (the mean point, with ``cone_distance_in``), the hand of spiral.
PRINT_BLANK_KEYS = ("gear_spiral_angle_deg", "gear_pressure_angle_convex_deg",
                    "gear_pressure_angle_concave_deg", "face_width_in", "gear_hand")
#: The printed hand of spiral -> the hand.
HAND_WORDS = {"RIGHT": "right", "LEFT": "left"}
#: Which print key a converted key comes from (the name an error or a slip gives).
SOURCE_KEYS = {"radial_distance_mm": "radial_in", "cradle_angle_deg": "cradle_angle",
               "machine_root_angle_deg": "machine_root_angle",
               "machine_centre_to_back_mm": "machine_centre_to_back",
               "sliding_base_mm": "sliding_base", "blank_offset_mm": "blank_offset",
               "ratio_of_roll": "ratio_nc_75", "tilt_deg": "tilt_angle", "kind": "blades",
               "blade_angle_deg": "blades", "point_radius_mm": "cutter_diameter_in",
               "edge_radius_mm": "edge_radius_in"}
#: The print's blank numbers that place the MD's datum.
DATUM_LENGTHS = ("gear_crown_to_crossing_point_in", "cone_distance_in", "gear_addendum_in")
_TABLE = "print.gear"
_BLADE_OF_SIDE = {"drive": "inside", "coast": "outside"}     # docs sec. 2: IB convex


@dataclass(frozen=True)
class PrintedBlank:
    """The gear's blank as a page prints it, in mm and deg.

    Attributes
    ----------
    pitch_angle_deg, mean_cone_distance_mm : float
        The mean point: pitch angle, outer cone distance - face width / 2.
    spiral_angle_deg : float
        The gear's (generating gear's) mean spiral angle.
    pressure_angle_deg : dict
        Per side (``"drive"``: convex, ``"coast"``: concave).
    gear_hand : str
        ``"right"`` / ``"left"``.
    cutter_radius_mm : float
        The print's cutter diameter / 2.
    apex_mm : float
        The pitch apex from the crossing point towards the gear's back (the MD's datum).
    rounding : dict
        Half a unit of each printed value's last digit, propagated where a value is
        computed: ``spiral_angle_deg``, ``pressure_angle_deg``, ``pitch_angle_deg``,
        ``cone_distance_mm``, ``cutter_radius_mm``, ``apex_mm``.
    setting_rounding : dict
        ``{converted key: half unit}`` of the settings the print gives (mm, deg; 0 for
        the tilt and swivel, printed 0).
    """

    pitch_angle_deg: float
    mean_cone_distance_mm: float
    spiral_angle_deg: float
    pressure_angle_deg: dict
    gear_hand: str
    cutter_radius_mm: float
    apex_mm: float
    rounding: dict
    setting_rounding: dict


def _angle(printed: Mapping, key: str) -> float:
    return degrees_minutes(f"{_TABLE}.{key}", printed[key])


def apex_in(printed: Mapping, **lengths) -> float:
    """The print's pitch apex from the crossing point, inches
    (:func:`~.print_words.pitch_apex_from_crossing_point_in` of the printed blank;
    ``lengths``: a datum number replaced)."""
    n = {k: lengths.get(k, printed[k]) for k in DATUM_LENGTHS}
    return pitch_apex_from_crossing_point_in(
        crown_to_crossing_point_in=n["gear_crown_to_crossing_point_in"],
        outer_cone_distance_in=n["cone_distance_in"],
        pitch_angle_deg=_angle(printed, "gear_pitch_angle_deg"),
        addendum_in=n["gear_addendum_in"])


def apex_rounding_in(printed: Mapping) -> float:
    """The print's rounding of :func:`apex_in` propagated, inches: worst case, first
    order, ``t (1 + |cos d| + |sin d|) + |A_o sin d + a_o cos d| m`` (``t`` half a
    printed thousandth, ``m`` half a minute in radians)."""
    d = math.radians(_angle(printed, "gear_pitch_angle_deg"))
    t, m = PRINT_ROUNDING["length_in"], math.radians(PRINT_ROUNDING["angle_deg"])
    return (t * (1.0 + abs(math.cos(d)) + abs(math.sin(d)))
            + abs(printed["cone_distance_in"] * math.sin(d)
                  + printed["gear_addendum_in"] * math.cos(d)) * m)


def printed_hand(printed: Mapping) -> str:
    """The printed hand of spiral (``"RIGHT"``), ``"right"`` / ``"left"``; an error
    names ``print.gear.gear_hand``."""
    value = printed["gear_hand"]
    word = " ".join(value.upper().split()) if isinstance(value, str) else None
    if word not in HAND_WORDS:
        raise InputRangeError(f"{_TABLE}.gear_hand", value,
                              f"a word of {', '.join(HAND_WORDS)} (the hand of spiral as "
                              "printed)")
    return HAND_WORDS[word]


def printed_blank(printed: Mapping, *, gear_teeth: int) -> PrintedBlank:
    """The :class:`PrintedBlank` of a checked ``[print.gear]`` table (its keys:
    :mod:`.print_table`); errors name ``print.gear.<key>``."""
    a, t = PRINT_ROUNDING["angle_deg"], INCH_MM * PRINT_ROUNDING["length_in"]
    face = check_finite(f"{_TABLE}.face_width_in", printed["face_width_in"])
    cone = printed["cone_distance_in"]
    if not 0.0 < face < 2.0 * cone:
        raise InputRangeError(f"{_TABLE}.face_width_in", face,
                              f"(0, {2.0 * cone:g}) in: the mean point, cone_distance_in - "
                              "face_width_in / 2, on the pitch cone")
    apex_t = INCH_MM * apex_rounding_in(printed)
    # the point radii (D -+ W) / 2: half of each one's printed half unit
    point = 0.5 * INCH_MM * (PRINT_ROUNDING["length_in"] + PRINT_ROUNDING["point_width_in"])
    return PrintedBlank(
        pitch_angle_deg=_angle(printed, "gear_pitch_angle_deg"),
        mean_cone_distance_mm=INCH_MM * (cone - 0.5 * face),
        spiral_angle_deg=_angle(printed, "gear_spiral_angle_deg"),
        pressure_angle_deg={"drive": _angle(printed, "gear_pressure_angle_convex_deg"),
                            "coast": _angle(printed, "gear_pressure_angle_concave_deg")},
        gear_hand=printed_hand(printed),
        cutter_radius_mm=0.5 * INCH_MM * printed["cutter_diameter_in"],
        apex_mm=INCH_MM * apex_in(printed),
        # the mean cone distance A_o - F / 2: both printed to 0.001 in
        rounding={"spiral_angle_deg": a, "pressure_angle_deg": a, "pitch_angle_deg": a,
                  "cone_distance_mm": 1.5 * t, "cutter_radius_mm": 0.5 * t,
                  "apex_mm": apex_t},
        # MCTB = (MD + the apex) x 25.4: the MD's digit and the apex's chain
        setting_rounding={"radial_distance_mm": t, "cradle_angle_deg": a,
                          "machine_root_angle_deg": a, "machine_centre_to_back_mm": t + apex_t,
                          "sliding_base_mm": t, "blank_offset_mm": t,
                          "ratio_of_roll": 75.0 * PRINT_ROUNDING["ratio"] / gear_teeth,
                          "blade_angle_deg": a, "point_radius_mm": point})


def print_gear_tables(printed: Mapping, *, gear_teeth: int) -> dict:
    """``{"machine": {"gear": {side: ...}}, "blade": {"gear": {side: ...}}}``: the gear's
    tables of a checked ``[print.gear]`` table
    (:func:`~.print_words.gear_tables_from_print`); errors name ``print.gear.<key>``."""
    return gear_tables_from_print({**printed, "gear_teeth": gear_teeth}, where=_TABLE)


def printed_gear_setups(printed: Mapping, *, gear_teeth: int) -> tuple:
    """The gear's two :class:`~.machine.MachineSetup` (drive, coast) a ``[print.gear]``
    table cuts (an error on a converted value names the converted key:
    :func:`~.print_table.print_gear_setups` renames it to the print's)."""
    tables = print_gear_tables(printed, gear_teeth=gear_teeth)
    return tuple(setup_from_tables("gear", side, tables["machine"]["gear"][side],
                                   tables["blade"]["gear"][side]) for side in _BLADE_OF_SIDE)


def cuts_the_printed_gear(pair) -> bool:
    """``pair`` has a ``[print.gear]`` table and its gear set-ups are the ones the print
    cuts (a pair whose gear was changed since, a correction or standard settings, keeps
    the table but not the print's gear)."""
    printed = dict(getattr(pair, "print_gear", ()) or ())
    return bool(printed) and printed_gear_setups(printed, gear_teeth=pair.gear_teeth) == tuple(
        s for s in pair.machine or getattr(pair, "typed_gear", ()) if s.member == "gear")


def print_key(full_key: str, printed: Mapping) -> tuple[str, object] | None:
    """``(print key, value as typed)`` a converted gear key comes from
    (``machine.gear.coast.blank_offset_mm`` -> ``("print.gear.blank_offset", "UP
    0.225")``; a blade's angle: the blade of its flank, ``print.gear.blades[i]``), or
    None for another key."""
    parts = full_key.split(".")
    if len(parts) != 4 or parts[:2] not in (["machine", "gear"], ["blade", "gear"]) \
            or parts[3] not in SOURCE_KEYS:
        return None
    key = SOURCE_KEYS[parts[3]]
    value = printed.get(key)
    if key == "blades" and isinstance(value, (list, tuple)):
        word = {v: k for k, v in BLADE_WORDS.items()}[_BLADE_OF_SIDE.get(parts[2], "")]
        for i, text in enumerate(value):
            if isinstance(text, str) and text.upper().split()[:1] == [word]:
                return f"{_TABLE}.blades[{i}]", text
    return f"{_TABLE}.{key}", value


def blank_differences(printed: Mapping, blank, *, gear_teeth: int) -> list[str]:
    """Where the pair's blank (its ISO 23509 design, :class:`~.blank.BlankDesign`-like:
    ``spiral_angle_gear_deg``, ``pitch_angle_gear_deg``, ``pressure_angle_drive_deg`` /
    ``_coast_deg``, ``mean_cone_distance_gear_mm``) differs from the page's printed
    blank beyond the print's rounding: one phrase each, the pair's value beside the
    printed one (the note of :func:`~.print_table.check_print_blank`)."""
    p = printed_blank(printed, gear_teeth=gear_teeth)
    r = p.rounding
    rows = (("gear spiral angle", "deg", blank.spiral_angle_gear_deg, p.spiral_angle_deg,
             r["spiral_angle_deg"], "gear_spiral_angle_deg"),
            ("gear pitch angle", "deg", blank.pitch_angle_gear_deg, p.pitch_angle_deg,
             r["pitch_angle_deg"], "gear_pitch_angle_deg"),
            ("pressure angle drive (convex)", "deg", blank.pressure_angle_drive_deg,
             p.pressure_angle_deg["drive"], r["pressure_angle_deg"],
             "gear_pressure_angle_convex_deg"),
            ("pressure angle coast (concave)", "deg", blank.pressure_angle_coast_deg,
             p.pressure_angle_deg["coast"], r["pressure_angle_deg"],
             "gear_pressure_angle_concave_deg"),
            ("gear mean cone distance", "mm", blank.mean_cone_distance_gear_mm,
             p.mean_cone_distance_mm, r["cone_distance_mm"], "cone_distance_in, face_width_in"))
    return [f"{what} {pair_value:.4f} {unit}, printed {printed_value:.4f} "
            f"({', '.join(f'{_TABLE}.{k}' for k in keys.split(', '))}; rounding {tol:.2g})"
            for what, unit, pair_value, printed_value, tol, keys in rows
            if abs(pair_value - printed_value) > tol]
