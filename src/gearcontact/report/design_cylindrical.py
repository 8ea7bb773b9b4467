"""What ``gearcontact design`` prints for a cylindrical pair: the ISO 21771 geometry.

:func:`cylindrical_design_text` is the table (pinion | gear columns, then the pair's
quantities) or, with ``as_json``, one JSON object of every
:class:`~gearcontact.geometry.cylindrical.iso21771.InvoluteGeometry` field
(docs/cylindrical.md). The per-member rows end with ISO 21771's undercut limit x_min and
whether the member is undercut (x < x_min: its form circle d_Ff is where the rack tip's
trochoid crosses the involute, :mod:`gearcontact.geometry.cylindrical.trochoid`).
"""

from __future__ import annotations

import json

__all__ = ["cylindrical_design_text"]

#: (label, InvoluteGeometry attribute stem, unit): per-member rows ``<stem>_pinion_mm``.
_MEMBER_ROWS = (
    ("reference diameter d", "reference_diameter", "mm"),
    ("base diameter d_b", "base_diameter", "mm"),
    ("tip diameter d_a", "tip_diameter", "mm"),
    ("root diameter d_f", "root_diameter", "mm"),
    ("root form diameter d_Ff", "form_diameter", "mm"),
    ("start of active profile d_Nf", "active_start_diameter", "mm"),
    ("working pitch diameter d_w", "working_pitch_diameter", "mm"),
    ("normal tip thickness s_an", "tip_thickness_normal", "mm"),
    ("tip clearance c", "tip_clearance", "mm"),
)
#: (label, attribute, unit) of the pair's quantities.
_PAIR_ROWS = (
    ("normal module m_n", "normal_module_mm", "mm"),
    ("transverse module m_t", "transverse_module_mm", "mm"),
    ("normal pressure angle alpha_n", "normal_pressure_angle_deg", "deg"),
    ("transverse pressure angle alpha_t", "transverse_pressure_angle_deg", "deg"),
    ("helix angle beta", "helix_angle_deg", "deg"),
    ("base helix angle beta_b", "base_helix_angle_deg", "deg"),
    ("reference centre distance a", "reference_centre_distance_mm", "mm"),
    ("zero-backlash centre distance", "zero_backlash_centre_distance_mm", "mm"),
    ("centre distance a_w", "centre_distance_mm", "mm"),
    ("working pressure angle alpha_wt", "working_pressure_angle_deg", "deg"),
    ("normal backlash j_bn", "normal_backlash_mm", "mm"),
    ("transverse base pitch p_bt", "transverse_base_pitch_mm", "mm"),
    ("length of path of contact g_alpha", "length_of_contact_mm", "mm"),
    ("common face width b", "face_width_mm", "mm"),
    ("transverse contact ratio eps_alpha", "transverse_contact_ratio", ""),
    ("overlap ratio eps_beta", "overlap_ratio", ""),
    ("total contact ratio eps_gamma", "total_contact_ratio", ""),
)


def _fmt(x) -> str:
    return str(x) if isinstance(x, int) else f"{x:.4f}"


def cylindrical_design_text(pair, *, as_json: bool = False) -> str:
    """The ISO 21771 geometry of ``pair`` (a
    :class:`~gearcontact.geometry.cylindrical.pair.CylindricalPair`) as printed text."""
    g = pair.geometry
    if as_json:
        return json.dumps({"pair": pair.name, "kind": pair.kind, **g.as_dict()}, indent=2)
    hand = f", {pair.pinion_hand}-hand pinion" if pair.pinion_hand else ""
    lines = [f"pair {pair.name}: ISO 21771 cylindrical gear geometry "
             f"({'helical' if g.helix_angle_deg else 'spur'}{hand})"]
    rows = [(f"{label} [{unit}]" if unit else label) for label, _, unit in
            _MEMBER_ROWS + _PAIR_ROWS]
    width = max(len(r) for r in rows + ["teeth z", "profile shift x", "undercut limit x_min"]) + 2
    lines.append(f"{'quantity':<{width}} {'pinion':>12} {'gear':>12}")
    lines.append(f"{'teeth z':<{width}} {g.pinion_teeth:>12} {g.gear_teeth:>12}")
    lines.append(f"{'profile shift x':<{width}} {_fmt(g.profile_shift_pinion):>12} "
                 f"{_fmt(g.profile_shift_gear):>12}")
    for (label, stem, unit), name in zip(_MEMBER_ROWS, rows):
        p, q = (getattr(g, f"{stem}_{m}_{unit}") for m in ("pinion", "gear"))
        lines.append(f"{name:<{width}} {_fmt(p):>12} {_fmt(q):>12}")
    for label, stem, fmt in (("undercut limit x_min", "undercut_limit_shift", _fmt),
                             ("undercut (x < x_min)", "undercut",
                              lambda c: "yes" if c else "no")):
        p, q = (fmt(getattr(g, f"{stem}_{m}")) for m in ("pinion", "gear"))
        lines.append(f"{label:<{width}} {p:>12} {q:>12}")
    for (label, attr, unit), name in zip(_PAIR_ROWS, rows[len(_MEMBER_ROWS):]):
        lines.append(f"{name:<{width}} {_fmt(float(getattr(g, attr))):>12}")
    return "\n".join(lines)
