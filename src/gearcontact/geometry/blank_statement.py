"""What a blank states for the flanks cut from machine settings: the values the typed
settings' check (:mod:`.blank_check`) compares each flank with at its mean point.

Two sources: a pair's own blank tables (ISO 23509 design, ``[cutter] radius_mm``,
``[design] pinion_hand``; :func:`stated_blank`), whose values are the design's
definitions (rounding 0), and the gear page of a ``[print.gear]`` (:func:`printed_stated_blank`,
from :func:`~.print_blank.printed_blank`), whose values carry the print's rounding.

References
----------
docs/machine_settings.md sec. 2 (the check when a pair is loaded; the printed blank).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from .print_blank import cuts_the_printed_gear, printed_blank
from .print_words import INCH_MM

__all__ = ["StatedBlank", "printed_stated_blank", "stated_blank"]


@dataclass(frozen=True)
class StatedBlank:
    """What a pair's blank tables (or a print) state for the flanks cut from settings.

    Attributes
    ----------
    pitch_angle_deg, mean_cone_distance_mm, dedendum_mm : dict
        Per member (``"gear"``, ``"pinion"``): pitch angle (deg), mean cone distance and
        mean dedendum (mm); a member absent is not checked.
    spiral_angle_gear_deg : float
        The gear's mean spiral angle ``beta_m2``, deg.
    pressure_angle_deg : dict
        Per side: the generating gear's pressure angle, deg.
    gear_hand : str
        ``"right"`` / ``"left"``.
    cutter_radius_mm : float
        Nominal cutter radius ``r_c`` of the gear's generating gear, mm.
    rounding : dict
        Half a unit of each stated value's last digit (``"spiral_angle_deg"``,
        ``"pressure_angle_deg"``, ``"cone_distance_mm"``, ``"cutter_radius_mm"``); 0 for
        a pair's blank, whose values are the design's definitions.
    setting_rounding : dict or None
        ``{key: half unit}`` of the settings when known from their source (a print's
        inches); None: each typed value's own (:func:`.typed_settings.typed_resolution`).
    hand_key, hand_value : str
        The key and value that state the hand (``design.pinion_hand``).
    mctb_datum_mm : dict
        Per member, the pitch apex's offset from the crossing point along the work axis
        towards the member's back, mm: a sheet's MD measured from the crossing point is
        typed as ``X_D = MD + datum`` (docs sec. 2), so its sign slip is ``X_D -> 2 datum
        - X_D``; tried where non-zero.
    clearance_mm : float or None
        The blank's mean clearance ``c``, mm (the dedendum less the mate's addendum): a
        root datum shallower than the stated dedendum by more than ``c`` plus its
        tolerance lies above the mate's tip, an input error
        (:data:`~.blank_verdict.GROSS_ROOT_QUANTITY`); None: no such bound.
    gear_face_width_mm : float or None
        The gear's face width, mm: a generating gear's mean cone distance off the stated
        one by more than half of it lies off the gear's face, an input error
        (:data:`~.blank_check.GROSS_CONE_FACE_FRACTION`); None: no such bound.
    printed : tuple
        The ``[print.gear]`` items ``(key, value as typed)`` when the settings checked
        against this statement were converted from a print (:func:`printed_stated_blank`):
        a slip or key found is then named by the print's key
        (:func:`~.print_blank.print_key`); empty otherwise.
    """

    pitch_angle_deg: dict
    mean_cone_distance_mm: dict
    dedendum_mm: dict
    spiral_angle_gear_deg: float
    pressure_angle_deg: dict
    gear_hand: str
    cutter_radius_mm: float
    rounding: dict = dataclasses.field(default_factory=dict)
    setting_rounding: dict | None = None
    hand_key: str = "design.pinion_hand"
    hand_value: str = ""
    mctb_datum_mm: dict = dataclasses.field(default_factory=dict)
    printed: tuple = ()
    gear_face_width_mm: float | None = None
    clearance_mm: float | None = None


def stated_blank(pair) -> StatedBlank:
    """The :class:`StatedBlank` of ``pair``'s blank tables (ISO 23509 design,
    ``[cutter] radius_mm``, ``[design] pinion_hand``)."""
    b = pair.blank
    other = {"right": "left", "left": "right"}
    return StatedBlank(
        pitch_angle_deg={"gear": b.pitch_angle_gear_deg, "pinion": b.pitch_angle_pinion_deg},
        mean_cone_distance_mm={"gear": b.mean_cone_distance_gear_mm,
                               "pinion": b.mean_cone_distance_pinion_mm},
        dedendum_mm={"gear": b.dedendum_gear_mm, "pinion": b.dedendum_pinion_mm},
        spiral_angle_gear_deg=b.spiral_angle_gear_deg,
        pressure_angle_deg={"drive": b.pressure_angle_drive_deg,
                            "coast": b.pressure_angle_coast_deg},
        gear_hand=other[pair.pinion_hand], cutter_radius_mm=pair.cutter.radius_mm,
        hand_value=pair.pinion_hand, gear_face_width_mm=pair.gear_face_width_mm,
        clearance_mm=b.clearance_mm,
        # the pitch apexes on the axes in the meshing frame, the crossing point at 0 and
        # each body on the + side (geometry.blank)
        mctb_datum_mm={"gear": b.gear_apex_z_mm, "pinion": b.pinion_apex_x_mm})


def printed_stated_blank(pair) -> StatedBlank | None:
    """What the gear page of ``pair``'s ``[print.gear]`` prints, as the statement its gear
    flanks are checked against (:func:`~.print_blank.printed_blank`): the printed mean
    point (pitch angle, outer cone distance - face width / 2), spiral angle, pressure
    angles, hand and cutter, the MD's datum by the print's chain, the stated values'
    and the settings' rounding the print's (its digits, propagated by the check as for
    typed digits); the dedendum (root datum, a model bound) the pair's blank's. None for
    a pair without ``[print.gear]``, or whose gear is not the one it cuts
    (:func:`~.print_blank.cuts_the_printed_gear`: a gear changed since, by a correction
    or standard settings, is checked as typed tables against the pair's blank)."""
    if not cuts_the_printed_gear(pair):
        return None
    printed = dict(pair.print_gear)
    base, p = stated_blank(pair), printed_blank(printed, gear_teeth=pair.gear_teeth)
    return dataclasses.replace(
        base, pitch_angle_deg={"gear": p.pitch_angle_deg},
        mean_cone_distance_mm={"gear": p.mean_cone_distance_mm},
        dedendum_mm={"gear": base.dedendum_mm["gear"]},
        spiral_angle_gear_deg=p.spiral_angle_deg, pressure_angle_deg=p.pressure_angle_deg,
        gear_hand=p.gear_hand, cutter_radius_mm=p.cutter_radius_mm,
        rounding=p.rounding,
        setting_rounding=p.setting_rounding, hand_key="print.gear.gear_hand",
        hand_value=printed["gear_hand"], mctb_datum_mm={"gear": p.apex_mm},
        printed=pair.print_gear, gear_face_width_mm=INCH_MM * printed["face_width_in"])
