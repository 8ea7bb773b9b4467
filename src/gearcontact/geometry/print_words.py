"""The words and numbers of a Gleason-type summary sheet (print-out) mapped to the signed
mm / deg values of the ``[machine.<member>.<flank>]`` / ``[blade.<member>.<flank>]``
tables (docs/machine_settings.md sec. 2, "Typing a print": the table of print words).

A print writes a setting as a word and an unsigned number (``Sliding Base WITH 0.070``,
``Blank Offset DN 0.225``), as ``MD`` with a signed number measured from a datum that
is not the work frame's (``Mach Center to Back MD -0.240``), in degrees and minutes
(``Cradle Angle 67D 11M``), in inches, and the ratio of roll through a change-gear
ratio (``Nc/75 Decimal Ratio 0.545665``). :func:`gear_tables_from_print` turns a gear
page of a spread-blade cut into the tables, so that a sheet typed through it, the docs
table and the test data agree by construction.

What rests on a print (tests/geometry/summary_sheets/README.md: one print, the No. 16
gear page of a 10 x 41 hypoid sample; tests/geometry/test_print_words.py): WITH = +,
DN = -, the cradle angle printed without a word = +, MD the crossing point's increment,
work / cradle = Nc / z (the printed test roll), the spread blade's point radii
(D -+ W) / 2, OB / IB = outside / inside blade, tilt 0. AWAY and UP are the opposite
words of WITH and DN: never seen on a print, mapped by opposition only. Words not seen
on any print read (tilt and swivel of a tilted cutter, modified roll, helical motion,
cradle-angle words, a pinion page) are not mapped: they are refused naming the field,
and are typed by hand with docs sec. 2's table, which marks them unverified.

References
----------
docs/machine_settings.md sec. 1 (the machine frame), sec. 2 (the sign table and the
print words); tests/geometry/summary_sheets/README.md (the print and how each sign was
decided).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from ..validation import InputRangeError, check_finite, check_range

__all__ = ["BLADE_WORDS", "BLANK_OFFSET_WORDS", "INCH_MM", "SLIDING_BASE_WORDS",
           "degrees_minutes", "gear_tables_from_print", "md_value",
           "pitch_apex_from_crossing_point_in", "ratio_of_roll_from_nc75", "word_value"]

#: Millimetres per inch (a print's lengths are inches).
INCH_MM = 25.4
#: Sliding base words -> sign of ``sliding_base_mm`` (work along ``+z_m``, docs sec. 1).
#: WITH = + is the one print's (its root line lies in the cutter tip plane only so);
#: AWAY is its opposite, on no print read.
SLIDING_BASE_WORDS = {"WITH": 1.0, "AWAY": -1.0}
#: Blank offset words -> sign of ``blank_offset_mm`` (work axis along ``+y_m``). DN = -
#: is the one print's (with UP its gear's generating spiral angle would be 37.68 deg,
#: printed 26.95); UP is its opposite, on no print read.
BLANK_OFFSET_WORDS = {"UP": 1.0, "DN": -1.0}
#: Blade words -> ``kind`` (OB / IB, as the print's cutter specification names them).
BLADE_WORDS = {"OB": "outside", "IB": "inside"}
#: Which gear flank a blade kind cuts (docs sec. 2: gear drive = convex = inside).
_GEAR_SIDE = {"inside": "drive", "outside": "coast"}
#: Decimals of the typed values: lengths in mm and angles in deg to 4 (0.001 in is
#: 0.0254 mm exactly; 1e-4 deg is 1/300 of a print's minute), the ratio of roll to 6
#: (the Nc/75 ratio's own printed digits).
_DECIMALS = {"length": 4, "angle": 4, "ratio": 6}
_NUMBER = r"\d+(?:\.\d*)?|\.\d+"
_DM = re.compile(rf"^([+-]?)\s*({_NUMBER})\s*D(?:\s*({_NUMBER})\s*M)?$")
_DEG = re.compile(rf"^([+-]?\s*(?:{_NUMBER}))\s*(?:DEG)?$")
_WORD = re.compile(rf"^([A-Z]+)\s+({_NUMBER})$")
_MD = re.compile(rf"^(?:MD\s*)?([+-]?\s*(?:{_NUMBER}))$")
_BLADE = re.compile(r"^([A-Z]+)\s+(.+)$")


def _text(field: str, value) -> str:
    if not isinstance(value, str):
        raise InputRangeError(field, value, "text as printed, e.g. 'WITH 0.070'")
    return " ".join(value.upper().split())


def degrees_minutes(field: str, value) -> float:
    """An angle as printed, in decimal degrees.

    Parameters
    ----------
    field : str
        The name an error gives (``printed.cradle_angle``).
    value : str or float
        ``"26D 57M"`` (degrees and minutes, minutes in [0, 60)), ``"30 Deg"``, ``"0"``,
        either with a leading sign, or a number of degrees.

    Returns
    -------
    float
        Degrees.

    Raises
    ------
    InputRangeError
        Naming ``field``, the value and the forms allowed.
    """
    if not isinstance(value, str):
        return check_finite(field, value)
    text = _text(field, value)
    allowed = "degrees and minutes as printed ('26D 57M', minutes in [0, 60)), '30 Deg' or a number"
    m = _DM.match(text)
    if m:
        minutes = float(m.group(3) or 0.0)
        if minutes >= 60.0:
            raise InputRangeError(field, value, allowed)
        return (-1.0 if m.group(1) == "-" else 1.0) * (float(m.group(2)) + minutes / 60.0)
    m = _DEG.match(text)
    if not m:
        raise InputRangeError(field, value, allowed)
    return float(m.group(1).replace(" ", ""))


def word_value(field: str, value, words: Mapping[str, float]) -> float:
    """A setting printed as a word and an unsigned number, signed by the word.

    Parameters
    ----------
    field : str
        The name an error gives (``printed.sliding_base``).
    value : str
        ``"WITH 0.070"``: a word of ``words`` and an unsigned number (any case).
    words : mapping
        Word -> sign (:data:`SLIDING_BASE_WORDS`, :data:`BLANK_OFFSET_WORDS`).

    Returns
    -------
    float
        The signed number, in the printed unit.

    Raises
    ------
    InputRangeError
        An unknown word, a signed or missing number: naming ``field``, the value and the
        allowed words.
    """
    text = _text(field, value)
    m = _WORD.match(text)
    if not m or m.group(1) not in words:
        raise InputRangeError(field, value, f"a word of {', '.join(words)} and an unsigned "
                                            f"number (e.g. '{next(iter(words))} 0.070')")
    return words[m.group(1)] * float(m.group(2))


def md_value(field: str, value) -> float:
    """The machine centre to back as printed (``"MD -0.240"``, ``MD`` optional), signed,
    in the printed unit; an error names ``field``, the value and the form allowed."""
    if not isinstance(value, str):
        return check_finite(field, value)
    m = _MD.match(_text(field, value))
    if not m:
        raise InputRangeError(field, value, "'MD' and a signed number, e.g. 'MD -0.240'")
    return float(m.group(1).replace(" ", ""))


def pitch_apex_from_crossing_point_in(*, crown_to_crossing_point_in: float,
                                      outer_cone_distance_in: float, pitch_angle_deg: float,
                                      addendum_in: float) -> float:
    """The member's pitch apex from the crossing point along its axis, towards its back
    (+: between the crossing point and the member), inches.

    The crown (outer tip corner) lies ``A_o cos(delta) - a_o sin(delta)`` from the pitch
    apex along the axis (outer cone distance ``A_o``, pitch angle ``delta``, outer
    addendum ``a_o``), so the apex is the printed crown to crossing point less that.
    A print's MD is the crossing point's increment: ``X_D = MD + this`` (docs sec. 2).
    """
    d = math.radians(pitch_angle_deg)
    return crown_to_crossing_point_in - (outer_cone_distance_in * math.cos(d)
                                         - addendum_in * math.sin(d))


def ratio_of_roll_from_nc75(nc75: float, teeth: int) -> float:
    """Ratio of roll work / cradle from a print's "Nc/75 Decimal Ratio": ``Nc / z`` with
    ``Nc = 75 x ratio`` the generating gear's teeth and ``z`` the member's (the print's
    test roll, 30 deg of cradle for 29D 57M of work on the 10 x 41 gear, agrees to its
    minute)."""
    return 75.0 * nc75 / teeth


def _get(printed: Mapping, key: str, where: str):
    if key not in printed:
        raise InputRangeError(f"{where}.{key}", None, "required to type a gear page "
                                                      "(geometry.print_words)")
    return printed[key]


def _rounded(x: float, kind: str, rounded: bool) -> float:
    return round(x, _DECIMALS[kind]) if rounded else x


def gear_tables_from_print(printed: Mapping, *, where: str = "printed",
                           rounded: bool = True) -> dict:
    """The ``[machine.gear.*]`` / ``[blade.gear.*]`` tables of a print's gear page (a
    spread-blade cut, both flanks from one cutter and one set of settings).

    Parameters
    ----------
    printed : mapping
        The page as printed (a ``[printed]`` TOML table). Settings, text as printed or a
        number in the print's unit: ``machine_root_angle``, ``cradle_angle``,
        ``tilt_angle`` (angles; ``"69D 7M"``), ``machine_centre_to_back``
        (``"MD -0.240"``), ``sliding_base`` (``"WITH 0.070"``), ``blank_offset``
        (``"DN 0.225"``), ``blades`` (the finishing blades, ``["OB 24D 30M", "IB 18D
        0M"]``); numbers: ``radial_in``, ``ratio_nc_75``, ``gear_teeth``,
        ``cutter_diameter_in``, ``point_width_finish_in``, ``edge_radius_in``; the
        blank's MD datum: ``gear_crown_to_crossing_point_in``, ``cone_distance_in``
        (outer), ``gear_pitch_angle_deg``, ``gear_addendum_in``. Optional
        ``cradle_test_roll_deg`` with ``work_test_roll``: checked against the ratio.
        Other keys are ignored.
    where : str
        The table's name in errors (``printed.sliding_base``).
    rounded : bool
        Round as typed: mm and deg to 4 decimals, the ratio of roll to 6 (True), or not.

    Returns
    -------
    dict
        ``{"machine": {"gear": {"drive": {...}, "coast": {...}}}, "blade": {"gear":
        {...}}}``: the keys of docs sec. 3, gear drive (convex) = inside blade, coast
        (concave) = outside blade, point radii ``(D -+ W) / 2``.

    Raises
    ------
    InputRangeError
        A missing key, an unknown word or form (naming the key, the value and the
        words allowed), a tilt other than 0 (tilt and swivel words are on no print
        read), blades other than one OB and one IB, a test roll the ratio does not give.
    """
    def key(k):
        return f"{where}.{k}"

    def number(k):
        return check_finite(key(k), _get(printed, k, where))

    tilt = degrees_minutes(key("tilt_angle"), _get(printed, "tilt_angle", where))
    if tilt != 0.0:
        raise InputRangeError(key("tilt_angle"), printed["tilt_angle"],
                              "0 (a tilted cutter's tilt and swivel words are on no print "
                              "read: type tilt_deg / swivel_deg by hand, "
                              "docs/machine_settings.md sec. 2)")
    teeth = _get(printed, "gear_teeth", where)
    if isinstance(teeth, bool) or not isinstance(teeth, int) or teeth < 1:
        raise InputRangeError(key("gear_teeth"), teeth, "a positive integer")
    # printed unsigned (a decimal of the generating gear's teeth): its own range first,
    # before the test roll it would be found wrong against
    ratio = ratio_of_roll_from_nc75(check_range(key("ratio_nc_75"), number("ratio_nc_75"),
                                                0.0, math.inf, hi_open=True), teeth)
    if "work_test_roll" in printed or "cradle_test_roll_deg" in printed:
        work = degrees_minutes(key("work_test_roll"), _get(printed, "work_test_roll", where))
        cradle = degrees_minutes(key("cradle_test_roll_deg"),
                                 _get(printed, "cradle_test_roll_deg", where))
        # the test roll is printed to the minute: half a minute, and the ratio's
        # printed 6 decimals over the cradle's roll
        if abs(ratio * cradle - work) > 0.5 / 60.0 + 75.0 * 5e-7 / teeth * abs(cradle):
            raise InputRangeError(key("work_test_roll"), printed["work_test_roll"],
                                  f"{ratio * cradle:.4f} deg within half a minute: the work "
                                  f"roll for {where}.cradle_test_roll_deg = {cradle:g} at "
                                  f"work / cradle = 75 x {where}.ratio_nc_75 / "
                                  f"{where}.gear_teeth = {ratio:.6f}")
    pitch = degrees_minutes(key("gear_pitch_angle_deg"),
                            _get(printed, "gear_pitch_angle_deg", where))
    if not 0.0 < pitch < 90.0:     # a cone's half angle (the datum chain's cos and sin)
        raise InputRangeError(key("gear_pitch_angle_deg"), printed["gear_pitch_angle_deg"],
                              f"(0, 90) deg, the gear's pitch cone angle (read {pitch:.4f} deg)")
    datum = pitch_apex_from_crossing_point_in(
        crown_to_crossing_point_in=number("gear_crown_to_crossing_point_in"),
        outer_cone_distance_in=number("cone_distance_in"),
        pitch_angle_deg=pitch, addendum_in=number("gear_addendum_in"))
    md = md_value(key("machine_centre_to_back"), _get(printed, "machine_centre_to_back", where))

    def length(x_in):
        return _rounded(INCH_MM * x_in, "length", rounded)

    def angle(k):
        return _rounded(degrees_minutes(key(k), _get(printed, k, where)), "angle", rounded)

    machine = {
        "radial_distance_mm": length(number("radial_in")),
        "cradle_angle_deg": angle("cradle_angle"),
        "machine_root_angle_deg": angle("machine_root_angle"),
        "machine_centre_to_back_mm": length(md + datum),
        "sliding_base_mm": length(word_value(key("sliding_base"),
                                             _get(printed, "sliding_base", where),
                                             SLIDING_BASE_WORDS)),
        "blank_offset_mm": length(word_value(key("blank_offset"),
                                             _get(printed, "blank_offset", where),
                                             BLANK_OFFSET_WORDS)),
        "ratio_of_roll": _rounded(ratio, "ratio", rounded),
        "tilt_deg": 0.0,
        "swivel_deg": 0.0,
    }
    diameter, width = number("cutter_diameter_in"), number("point_width_finish_in")
    if diameter > 0.0:      # both point radii (D -+ W) / 2 > 0: the width names itself
        check_range(key("point_width_finish_in"), width, 0.0, diameter, hi_open=True)
    edge = number("edge_radius_in")
    blades = _get(printed, "blades", where)
    listed = list(blades) if isinstance(blades, (list, tuple)) else [blades]
    kinds = {}
    for i, text in enumerate(listed):
        field = f"{key('blades')}[{i}]"
        m = _BLADE.match(_text(field, text))
        if not m or m.group(1) not in BLADE_WORDS:
            raise InputRangeError(field, text, f"a word of {', '.join(BLADE_WORDS)} and the "
                                               f"blade angle, e.g. 'OB 24D 30M'")
        kinds[BLADE_WORDS[m.group(1)]] = degrees_minutes(field, m.group(2))
    if sorted(kinds) != ["inside", "outside"] or len(listed) != 2:
        raise InputRangeError(key("blades"), blades, "one OB and one IB blade (a spread-"
                                                     "blade gear cutter)")
    blade = {}
    for kind, blade_angle in kinds.items():
        sign = 1.0 if kind == "outside" else -1.0
        blade[_GEAR_SIDE[kind]] = {
            "kind": kind, "blade_angle_deg": _rounded(blade_angle, "angle", rounded),
            "point_radius_mm": length(0.5 * (diameter + sign * width)),
            "edge_radius_mm": length(edge)}
    return {"machine": {"gear": {"drive": dict(machine), "coast": dict(machine)}},
            "blade": {"gear": {side: blade[side] for side in ("drive", "coast")}}}
