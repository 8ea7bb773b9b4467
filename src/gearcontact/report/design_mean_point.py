"""The mean-point angles ``gearcontact design`` prints for a pair cut from machine
settings: per member and flank, the generating gear's spiral angle, pressure angle and
mean cone distance (what a summary sheet prints) beside the cut flank's on its pitch
cone, as a table (:func:`mean_point_table`) or as the ``mean_point_angles`` entry of
``design --json`` (:func:`mean_point_json`). The values are
:func:`~gearcontact.geometry.flank_angles.measure_pair_mean_points`'s; the definitions
and their sources: docs/machine_settings.md sec. 2.

The check of a pair's machine settings against its own blank tables
(:mod:`~gearcontact.geometry.settings_check`) as the command line runs it when the pair
is loaded, its warnings printed (:func:`checked_blank`): its line and its ``blank_check``
JSON entry (:func:`blank_check_text`, :func:`blank_check_json`), and the line and JSON
entry of its pinion ease-off shapes (:mod:`~gearcontact.geometry.easeoff_shape`,
:func:`easeoff_shape_text`, :func:`easeoff_shape_json`).
"""

from __future__ import annotations

import sys

from ..geometry.blank_verdict import BlankCheck
from ..geometry.easeoff_shape import EaseOffShapeCheck
from ..geometry.settings_check import SettingsCheck, check_settings
from ..geometry.flank_angles import FlankMeanPoint

__all__ = ["blank_check_json", "blank_check_text", "checked_blank", "easeoff_shape_json",
           "easeoff_shape_text", "mean_point_json", "mean_point_table"]

#: The flank's shape of each (member, side) (docs/machine_settings.md sec. 2).
_SHAPE = {("gear", "drive"): "convex", ("gear", "coast"): "concave",
          ("pinion", "drive"): "concave", ("pinion", "coast"): "convex"}
#: (label, unit, GeneratingGearAngles / MeanPointAngles attribute) of the columns; the
#: pitch cone's cone distance is the blank's mean cone distance (the point measured).
_COLUMNS = (("spiral angle", "deg", "spiral_angle_deg"),
            ("pressure angle", "deg", "pressure_angle_deg"),
            ("mean cone distance", "mm", "cone_distance_mm"))


def _values(p: FlankMeanPoint) -> dict:
    """``{"generating_gear": {...} or None, "pitch_cone": {...} or None}`` of one flank."""
    gen = None if p.generating_gear is None else {
        attr: getattr(p.generating_gear, attr) for _, _, attr in _COLUMNS}
    cone = None if p.pitch_cone is None else {
        "spiral_angle_deg": p.pitch_cone.spiral_angle_deg,
        "pressure_angle_deg": p.pitch_cone.pressure_angle_deg,
        "cone_distance_mm": p.cone_distance_mm, "hand": p.pitch_cone.hand}
    return {"generating_gear": gen, "pitch_cone": cone}


def mean_point_json(points: tuple[FlankMeanPoint, ...]) -> dict:
    """``{member: {side: {"flank": "convex" | "concave", "generating_gear": {...} | None,
    "pitch_cone": {...} | None, "missing": str}}}``: the generating gear's
    ``spiral_angle_deg``, ``pressure_angle_deg``, ``cone_distance_mm`` (None where not
    defined or not reached, ``missing`` says why) and the pitch cone's, with its hand."""
    out: dict = {}
    for p in points:
        out.setdefault(p.member, {})[p.side] = {
            "flank": _SHAPE[p.member, p.side], **_values(p), "missing": p.missing}
    return out


def mean_point_table(points: tuple[FlankMeanPoint, ...]) -> str:
    """The table ``design`` prints below the blank (module docstring), with a line per
    missing value saying why."""
    head = ("flanks at the blank's mean points, cut from the machine settings: "
            "'generating' = the generating\ngear in the cradle plane (a summary sheet's "
            "spiral and pressure angles), 'pitch cone' = the cut\nflank on its pitch cone "
            "(docs/machine_settings.md sec. 2)")
    w = 22
    top = f"{'':<{w}}" + "".join(f"{f'{label} [{unit}]':^24}" for label, unit, _ in _COLUMNS)
    sub = f"{'member flank':<{w}}" + f"{'generating':>12}{'pitch cone':>12}" * len(_COLUMNS)
    lines = [head, top, sub]
    notes = []
    for p in points:
        v = _values(p)
        row = f"{f'{p.member} {p.side} ({_SHAPE[p.member, p.side]})':<{w}}"
        for _, _, attr in _COLUMNS:
            for kind in ("generating_gear", "pitch_cone"):
                row += f"{'-' if v[kind] is None else format(v[kind][attr], '.4f'):>12}"
        lines.append(row)
        note = f"{p.member}: {p.missing}"
        if p.missing and note not in notes:
            notes.append(note)
    lines += [f"  - {n}" for n in notes]
    return "\n".join(line.rstrip() for line in lines)


def checked_blank(pair, *, measured=None, easeoff_generated: bool = False,
                  on_blank=None) -> SettingsCheck | None:
    """:func:`~gearcontact.geometry.settings_check.check_settings` of ``pair`` with its
    warnings printed on stderr, one line each, as the command line shows them, before
    the check's flank work (then ``on_blank``, as ``check_settings``'s), a hollow pinion
    flank's after it (docs/machine_settings.md sec. 2): None for a pair without
    machine settings; a gross mismatch raises
    :class:`~gearcontact.validation.InputRangeError` naming the likely key (exit 2).
    ``measured``: the pair's
    :func:`~gearcontact.geometry.flank_angles.measure_pair_mean_points` when already
    measured (``design`` prints them): the check then measures no flank again.
    ``easeoff_generated``: as :func:`~gearcontact.geometry.settings_check.check_settings`'s
    (``design`` measures a generated gear's pinion ease-off too)."""
    def first(blank: SettingsCheck) -> None:
        for line in blank.warnings:
            print(line, file=sys.stderr)
        if on_blank is not None:
            on_blank(blank)

    got = check_settings(pair, measured=measured, easeoff_generated=easeoff_generated,
                         on_blank=first)
    for line in () if got is None else got.hollow_warnings:
        print(line, file=sys.stderr)
    return got


def blank_check_text(check: BlankCheck) -> str:
    """One line: every flank agrees (with the largest difference relative to its
    tolerance), or how many do not (the warnings name them)."""
    if not check.agrees:
        bad = ", ".join(f"{f.member} {f.side}" for f in check.flanks if not f.agrees)
        return (f"machine settings against the blank: {bad} do not agree (warnings above; "
                "docs/machine_settings.md sec. 2)")
    worst = max((abs(c.measured - c.stated) / c.tolerance, f"{f.member} {f.side} {c.quantity}")
                for f in check.flanks for c in f.comparisons if c.tolerance)
    pitch = any(c.quantity == "pitch point" for f in check.flanks for c in f.comparisons)
    return ("machine settings against the blank: every flank agrees within the typed "
            "settings' rounding propagated (spiral angle, pressure angle, mean cone distance "
            "of the gear's generating gear" + (", the pitch point of its generating roll"
                                               if pitch else "")
            + "; hand and root depth of every flank; largest "
            f"difference {worst[0]:.2f} of its tolerance, {worst[1]}; "
            "docs/machine_settings.md sec. 2)")


def blank_check_json(check: BlankCheck) -> dict:
    """``{"agrees": bool, "flanks": {member: {side: {"agrees", "missing", "slip",
    "slip_also", "comparisons": [{"quantity", "unit", "measured", "stated", "tolerance",
    "within"}]}}}, "hand_slip": bool}``."""
    flanks: dict = {}
    for f in check.flanks:
        flanks.setdefault(f.member, {})[f.side] = {
            "agrees": f.agrees, "missing": f.missing, "slip": f.slip,
            "slip_also": list(f.slip_also),
            "comparisons": [{"quantity": c.quantity, "unit": c.unit, "measured": c.measured,
                             "stated": c.stated, "tolerance": c.tolerance,
                             "within": c.within} for c in f.comparisons]}
    return {"agrees": check.agrees, "hand_slip": check.hand_slip, "flanks": flanks}


def easeoff_shape_text(check: EaseOffShapeCheck) -> str:
    """One line: each pinion flank's crowning against the typed gear's conjugate pinion
    (profile / lengthwise, um, relief positive) and whether one is hollow beyond the
    bound (the warnings name it), or why a flank was not checked."""
    parts = [f"{s.side} {s.C_p_um:+.1f} / {s.C_l_um:+.1f} um"
             + (" (over the part of the box its envelope reaches)" if s.trimmed else "")
             + (" (against the gear's main blade segment)" if s.relieved_gear else "")
             + (" HOLLOW" if s.flagged else "") for s in check.flanks]
    parts += [f"{side} {why}" for side, why in check.missing.items()]
    bound = check.flanks[0].bound_um if check.flanks else None
    verdict = ("" if bound is None else
               "; hollow beyond the bound: edge contact (warnings above)"
               if any(s.flagged for s in check.flanks) else
               f"; none hollow beyond {bound:g} um")
    return ("pinion ease-off against the typed gear's conjugate pinion, crowning in profile "
            "/ lengthwise at the active box's edges (relief positive): " + ", ".join(parts)
            + verdict + " (docs/machine_settings.md sec. 2, \"The hollow ease-off warning\")")


def easeoff_shape_json(check: EaseOffShapeCheck) -> dict:
    """``{"flanks": {side: {"C_p_um", "C_l_um", "bias_um", "fit_rms_um", "bound_um",
    "hollowness", "flagged", "trimmed"[, "relieved_gear"]}}, "missing": {side: reason},
    "warnings": [line]}`` (``relieved_gear`` only where true)."""
    return {"flanks": {s.side: {"C_p_um": s.C_p_um, "C_l_um": s.C_l_um, "bias_um": s.bias_um,
                                "fit_rms_um": s.fit_rms_um, "bound_um": s.bound_um,
                                "hollowness": s.hollowness, "flagged": s.flagged,
                                "trimmed": s.trimmed,
                                **({"relieved_gear": True} if s.relieved_gear else {})}
                       for s in check.flanks},
            "missing": dict(check.missing), "warnings": list(check.warnings())}
