"""The mean-point angles ``gearcontact design`` prints for a pair cut from machine
settings: per member and flank, the generating gear's spiral angle, pressure angle and
mean cone distance (what a summary sheet prints) beside the cut flank's on its pitch
cone, as a table (:func:`mean_point_table`) or as the ``mean_point_angles`` entry of
``design --json`` (:func:`mean_point_json`). The values are
:func:`~gearcontact.geometry.flank_angles.measure_pair_mean_points`'s; the definitions
and their sources: docs/machine_settings.md sec. 2.
"""

from __future__ import annotations

from ..geometry.flank_angles import FlankMeanPoint

__all__ = ["mean_point_json", "mean_point_table"]

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
