"""``gearcontact design``: the blank (pitch-cone) data of a gear pair.

Loads a pair (built-in preset such as ``s0003`` or a TOML file) and prints its ISO 23509
Method 1 blank design as a table (after checking that the gear generates the pinion
flanks: :func:`~gearcontact.geometry.generation.check_generation`); ``--json`` prints one
JSON object instead (with at least ``pitch_angles_deg``, ``spiral_angles_deg``,
``mean_cone_distances_mm``, each ``[pinion, gear]``, ``reverse_side_contact_ratio`` and
``mean_point_angles``). For a pair cut from machine settings both also give each flank at
the blank's mean point: the generating gear's spiral angle, pressure angle and mean cone
distance (what a summary sheet prints; the gear's) beside the pitch cone's
(:mod:`~gearcontact.report.design_mean_point`, docs/machine_settings.md sec. 2).
The contact ratio of the side that is not the design side is not refused: below 1 a
one-line warning on stderr names it and what ``twin`` does with that flank
(:func:`~gearcontact.geometry.contact_ratio.reverse_side_warning`). A cylindrical pair
(``kind = "cylindrical"``) prints its ISO 21771 geometry (docs/cylindrical.md).
"""

from __future__ import annotations

import dataclasses
import json
import sys

from ..geometry.contact_path import SYNTHESIS_PATTERN_RATIO, SYNTHESIS_TE0_ARCSEC
from ..geometry.contact_ratio import reverse_side_warning
from ..geometry.flank_angles import measure_pair_mean_points
from ..geometry.formate import SIDES
from ..geometry.gear_generation import generation_of, generation_text
from ..geometry.generation import check_generation, reverse_side_contact_ratio
from ..geometry.pair import (BEVEL, CYLINDRICAL, PRESETS, load_pair,
                             without_easeoff)
from ..report.design_mean_point import (blank_check_json, blank_check_text,
                                        easeoff_shape_json, easeoff_shape_text,
                                        mean_point_json, mean_point_table)
from ..validation import InputRangeError, check_range
from .design_modes import calibrate, machine_settings, synthesize
from .design_options import (TARGET_OPTIONS, check_options, check_relieved_blades,
                             checked_flanks, kept_gear, path_angle_option,
                             path_angle_options, renamed, synthesis_targets)

#: (label, BlankDesign attribute, unit) rows of the readable table, pinion | gear pairs.
_PAIRED = (
    ("teeth", "pinion_teeth", "gear_teeth", ""),
    ("pitch angle", "pitch_angle_pinion_deg", "pitch_angle_gear_deg", "deg"),
    ("mean spiral angle", "spiral_angle_pinion_deg", "spiral_angle_gear_deg", "deg"),
    ("mean cone distance", "mean_cone_distance_pinion_mm", "mean_cone_distance_gear_mm", "mm"),
    ("mean pitch radius", "mean_pitch_radius_pinion_mm", "mean_pitch_radius_gear_mm", "mm"),
    ("offset angle (axial plane)", "offset_angle_axial_pinion_deg", "offset_angle_axial_gear_deg", "deg"),
    ("mean addendum", "addendum_pinion_mm", "addendum_gear_mm", "mm"),
    ("mean dedendum", "dedendum_pinion_mm", "dedendum_gear_mm", "mm"),
)
_SINGLE = (
    ("ratio u", "ratio", ""),
    ("hypoid offset E", "offset_mm", "mm"),
    ("offset angle in pitch plane zeta_mp", "offset_angle_pitch_plane_deg", "deg"),
    ("limit pressure angle alpha_lim", "limit_pressure_angle_deg", "deg"),
    ("limit radius rho_lim", "limit_radius_mm", "mm"),
    ("cutter radius r_c0", "cutter_radius_mm", "mm"),
    ("mean normal module m_mn", "mean_normal_module_mm", "mm"),
    ("mean working depth h_mw", "working_depth_mm", "mm"),
    ("clearance c", "clearance_mm", "mm"),
    ("pressure angle drive (gear convex)", "pressure_angle_drive_deg", "deg"),
    ("pressure angle coast (gear concave)", "pressure_angle_coast_deg", "deg"),
)


#: Targets of ``--synthesize-easeoff`` when not given.
SYNTHESIS_DEFAULTS = {"te0_arcsec": SYNTHESIS_TE0_ARCSEC,
                      "pattern_length_ratio": SYNTHESIS_PATTERN_RATIO}


def register(sub) -> None:
    p = sub.add_parser("design", help="blank / pitch-cone data of a gear pair (ISO 23509)",
                       description=__doc__.split("\n\n")[1])
    p.add_argument("--pair", required=True, metavar="PRESET|FILE.toml",
                   help=f"built-in preset ({', '.join(PRESETS)}) or a pair TOML file")
    p.add_argument("--json", action="store_true",
                   help="print the blank design as one JSON object (not with --calibrate, "
                        "--synthesize-easeoff or --machine-settings)")
    p.add_argument("--calibrate", action="store_true",
                   help="calibrate the unpublished set-up (working depth, design-side "
                        "ease-off) to the pair's published design point (TCA in the loop, "
                        "~1 min); prints the target / achieved / tolerance table")
    p.add_argument("--tip-margin", type=float, default=None, metavar="MM",
                   help="with --calibrate: pinion tip radius above the published mating "
                        "point, mm, 0.01 to 0.5 (default: the largest margin that keeps a "
                        "top land of 0.25 m_mn)")
    p.add_argument("--out", default=None, metavar="DIR",
                   help="with --calibrate: directory for calibrated.toml and "
                        "calibration.json, with --synthesize-easeoff for easeoff.toml, with "
                        "--machine-settings for machine_settings.toml (the "
                        "output-directory policy of every command, see run.json)")
    p.add_argument("--force", action="store_true",
                   help="with --out: write into it even if it holds files gearcontact did "
                        "not write")
    p.add_argument("--synthesize-easeoff", action="store_true",
                   help="local synthesis of the ease-off of both sides (TCA in the loop, "
                        "~10-30 s per side); prints the [easeoff.drive]/[easeoff.coast] TOML")
    p.add_argument("--te0-arcsec", type=float, default=None,
                   help="with --synthesize-easeoff or --local-synthesis: TE0 "
                        "peak-to-peak, arcsec (default 3)")
    p.add_argument("--pattern-length-ratio", type=float, default=None,
                   help="with --synthesize-easeoff or --local-synthesis: paint-ellipse "
                        "length over the gear face width (default 0.35; practice 1/3 to 1/2; "
                        "--local-synthesis may shorten the default to keep the bearing off "
                        "the flank edges, never a typed value)")
    p.add_argument("--path-angle-deg", type=float, default=None,
                   help="with --synthesize-easeoff or --local-synthesis: angle of the "
                        "contact path on the gear flank from the lengthwise direction on "
                        "both sides, deg (default free, bias 0); with --synthesize-easeoff "
                        "the angles the synthesis reaches on the pair are checked before "
                        "any TCA (an error names them)")
    for side in SIDES:
        p.add_argument(f"--path-angle-{side}-deg", type=float, default=None,
                       help=f"with --synthesize-easeoff or --local-synthesis: the path "
                            f"angle of the {side} side "
                            "only, deg (the sides reach different ranges; not with "
                            "--path-angle-deg)")
    p.add_argument("--machine-settings", action="store_true",
                   help="machine settings of both members (docs/machine_settings.md): the "
                        "gear of the default flanks (formate, or generated where the formate "
                        "gear undercuts); for a pair with an ease-off, the pinion settings "
                        "fitted to cut that ease-off (the residual over each flank printed, "
                        "~15 s); else the standard settings from the blank (generated "
                        "pinion with lengthwise and profile crowning; a pair file typing the "
                        "gear alone, [machine.gear.*] / [blade.gear.*] or [print.gear]: that "
                        "gear kept as typed and its standard pinion; a pair cut from machine "
                        "settings gets those of its blank unless --keep-gear, its blades' "
                        "Toprem / Flankrem kept as given; where the blank's predicted "
                        "contact ratio is below 0.85 the settings' TCA runs first, ~3 s, "
                        "and a mesh with a gap is refused); prints the pair TOML "
                        "with its [machine.*]/[blade.*] tables, written as "
                        "machine_settings.toml (and the residual map) with --out")
    p.add_argument("--keep-gear", action="store_true",
                   help="with --machine-settings on a pair file typing both members: keep "
                        "its gear exactly as typed and derive the standard pinion of that "
                        "gear (as for a gear typed alone; docs/machine_settings.md sec. 5), "
                        "instead of the blank's standard settings of both members")
    p.add_argument("--local-synthesis", action="store_true",
                   help="with --machine-settings (a right- or left-hand spiral bevel or "
                        "hypoid, formate or generated gear): the "
                        "pinion settings from local synthesis at the mean point (roll "
                        "curvature, cutter radius and, with a path angle, blade curvature "
                        "for the targets --te0-arcsec, --pattern-length-ratio and "
                        "--path-angle-*; TCA in the loop, ~1 min; docs/machine_settings.md "
                        "sec. 5) instead of the standard crowning; a path angle is first "
                        "checked by the reach model (refused, exit 2, only where it is out "
                        "of reach for certain; its prediction is written beside the result)")
    p.add_argument("--target-flank", default=None, metavar="CSV",
                   help="with --machine-settings: a measured ease-off grid (columns "
                        "side,v_mm,u_mm,easeoff_um; docs/machine_settings.md sec. 6) or "
                        "measured deviations in machine coordinates (columns "
                        "member,flank,L_mm,R_mm,deviation_um; docs/export.md: a complete "
                        "grid, or scattered points fitted at the points, their residual "
                        "per point in machine_settings_points.csv) from the nominal flank "
                        "(a pair with [machine.*] tables: the flanks its settings cut, "
                        "each measured member corrected from them); the settings that "
                        "cut it are fitted")
    p.add_argument("--fit", choices=("rms", "minimax"), default=None,
                   help="with --machine-settings on a pair with an ease-off: the objective of "
                        "the settings fit, the RMS deviation (default) or the largest one "
                        "(from the RMS fit; docs/machine_settings.md sec. 6)")
    p.add_argument("--contact-curvature", action="store_true",
                   help="with --machine-settings on a pair with an ease-off: the target "
                        "pair's TCA path found, the fit's residual kept flat there "
                        "(curvature rows) and its curvature reported with the Hertz "
                        "pressure bound it implies (docs/machine_settings.md sec. 6)")
    p.add_argument("--lengthwise-crowning-um", type=float, default=None,
                   help="with --machine-settings: pinion cutter circle departure at the "
                        "face ends, um, 0 or 1e-6 to 200 (default 25; both crowning "
                        "options 0: uncrowned settings, written with the TCA's line "
                        "contact named, which the loaded commands refuse)")
    p.add_argument("--blade-profile-crowning-um", type=float, default=None,
                   help="with --machine-settings: pinion blade profile departure at "
                        "+-h_mw/2, um, 0 or 1e-6 to 200 (default 10)")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """--calibrate needs published values and --out; design writes files only with
    --calibrate or --synthesize-easeoff --out (under the output-directory policy,
    :mod:`.outdir`). The options are checked against each other before the pair's
    generation (seconds for a generated gear): a contradiction costs nothing."""
    pair = args.gear_pair = load_pair(args.pair, kinds=(BEVEL, CYLINDRICAL),
                                      gear_alone=bool(args.machine_settings))
    if args.force and args.out is None:
        raise InputRangeError("--force", True, "given only with --out (without it the "
                                               "option has no effect)")
    if pair.kind == CYLINDRICAL:
        for option, value in (("--calibrate", args.calibrate),
                              ("--synthesize-easeoff", args.synthesize_easeoff),
                              ("--out", args.out), ("--tip-margin", args.tip_margin),
                              ("--te0-arcsec", args.te0_arcsec),
                              ("--pattern-length-ratio", args.pattern_length_ratio),
                              *path_angle_options(args).items(),
                              ("--machine-settings", args.machine_settings),
                              ("--local-synthesis", args.local_synthesis),
                              ("--keep-gear", args.keep_gear),
                              ("--target-flank", args.target_flank),
                              ("--fit", args.fit),
                              ("--contact-curvature", args.contact_curvature),
                              ("--lengthwise-crowning-um", args.lengthwise_crowning_um),
                              ("--blade-profile-crowning-um", args.blade_profile_crowning_um)):
            if value not in (None, False):
                raise InputRangeError(option, value, "not given for a cylindrical pair "
                                      "(kind = 'cylindrical': design prints its geometry)")
        args.writes_files = False
        return
    check_options(args, pair)
    check_relieved_blades(args, pair)
    # a typed gear kept (typed alone, or --keep-gear): its standard pinion is derived
    args.typed_gear = kept_gear(args, pair)
    # checked here, before its pinion is derived: the pair's own check below runs on
    # the blank's tables, not on it
    if args.typed_gear:
        from .settings_slip import checked_typed_gear

        args.typed_gear_check = checked_typed_gear(pair, args.typed_gear)
    if args.machine_settings and (pair.machine or pair.typed_gear):
        # the settings are those of the blank (the pair's own tables are replaced): its
        # default gear, formate or generated, decides the gear's settings; measured
        # gear rows are corrected from the pair's own gear (the gear they measure)
        args.machine_pair = pair
        pair = args.gear_pair = dataclasses.replace(pair, machine=(), typed_gear=())
    # typed settings against the blank tables, on the flanks measured at the blank's mean
    # points once (the table below the blank prints the same measurements)
    args.mean_points = measure_pair_mean_points(pair) if pair.machine else None
    args.blank_check = None
    if pair.machine:
        from .settings_slip import checked_blank_named

        args.blank_check = checked_blank_named(pair, measured=args.mean_points,
                                               easeoff_generated=True)
    if args.synthesize_easeoff and pair.easeoff_tables:
        # the synthesis makes both sides' tables afresh from the conjugate pinion: the
        # checks below see the bearing it will make, not the tables it replaces
        pair = args.gear_pair = without_easeoff(pair)
    if args.synthesize_easeoff or args.local_synthesis:   # the same targets and checks
        args.te0_arcsec = SYNTHESIS_DEFAULTS["te0_arcsec"] if args.te0_arcsec is None \
            else args.te0_arcsec
        # a typed length is the user's: the local synthesis keeps it (no shortened
        # candidates, docs/machine_settings.md sec. 5, "The bearing's room")
        args.pattern_length_typed = args.pattern_length_ratio is not None
        args.pattern_length_ratio = SYNTHESIS_DEFAULTS["pattern_length_ratio"] \
            if args.pattern_length_ratio is None else args.pattern_length_ratio
        args.targets = synthesis_targets(args)     # their ranges, before any TCA
    # a pair whose pinion the gear cannot generate (limit line) is refused here; its
    # contact ratio is that of the bearing the synthesis will make (its gear flanks
    # are reused)
    args.generation_check = _check_generation(args, pair)
    args.gear_generation = generation_of(args.generation_check)
    # --local-synthesis takes either default gear: a hypoid's generated gear (the crown
    # gear's pinion, point contact) or a formate gear / a spiral bevel's generated gear
    # (line contact, pivot on the blank's mean point; tca.setting_synthesis)
    if args.synthesize_easeoff:
        # the closed-form reach is the ease-off synthesis' (tca.path_reach); the settings
        # synthesis reports a target it misses in its table (exit 4)
        args.flanks = checked_flanks(pair, args, args.targets)
    if args.calibrate:
        from ..report.analyze import published_values

        if published_values(pair.name) is None:
            raise InputRangeError("--pair", args.pair, "a built-in pair with published "
                                  "values (s0003, s0003-centred) for --calibrate")
        if args.out is None:
            raise InputRangeError("--out", None, "an output directory for calibrated.toml")
        if args.tip_margin is not None:
            check_range("--tip-margin (mm)", args.tip_margin, 0.01, 0.5)
    # an --out given, even empty, goes through the output-directory policy (an empty
    # path refused there, not taken for the working directory)
    args.writes_files = bool(args.calibrate or ((args.synthesize_easeoff or args.machine_settings)
                                                and args.out is not None))


def _check_generation(args, pair) -> dict:
    """:func:`~gearcontact.geometry.generation.check_generation` of ``pair``, its
    contact path that of the bearing the synthesis will make where the design side has
    no table (:class:`~gearcontact.tca.predicted_bearing.BearingPredictor`): the targets
    of ``--synthesize-easeoff`` / ``--local-synthesis`` (the setting synthesis turns no
    short path), the default targets without them (``analyze`` synthesizes with those);
    a path angle the synthesis cannot reach names its option."""
    from ..tca.predicted_bearing import BearingPredictor
    from ..tca.synthesis_targets import SynthesisTargets

    if args.machine_settings and not args.local_synthesis:
        # standard settings: their own TCA decides the contact ratio where the blank's
        # prediction is short, before they are written (design_modes.machine_settings)
        return check_generation(pair, contact_ratio=False)
    predictor = BearingPredictor(getattr(args, "targets", None) or SynthesisTargets(),
                                 turns_short_paths=not args.local_synthesis)
    try:
        return check_generation(pair, bearing_of=predictor)
    except InputRangeError as exc:
        if exc.field != "path_angle_deg" and exc.field not in TARGET_OPTIONS:
            raise
        raise renamed(exc, path_angle_option(args, pair.design_side)) from None


def _fmt(x) -> str:
    return str(x) if isinstance(x, int) else f"{x:.4f}"


def run(args) -> int:
    pair = getattr(args, "gear_pair", None) or load_pair(args.pair, kinds=(BEVEL, CYLINDRICAL))
    if pair.kind == CYLINDRICAL:
        from ..report.design_cylindrical import cylindrical_design_text

        print(cylindrical_design_text(pair, as_json=args.json))
        return 0
    if args.machine_settings:
        return machine_settings(args, pair)
    if args.calibrate:
        return calibrate(args, pair)
    if args.synthesize_easeoff:
        return synthesize(args, pair)
    blank = pair.blank
    boxes = getattr(args, "generation_check", None) or _check_generation(args, pair)
    generation = getattr(args, "gear_generation", None) or generation_of(boxes)
    # design refuses on the design side only; the other side's gap is twin's reverse flank
    reverse = reverse_side_contact_ratio(pair, boxes=boxes)
    warning = reverse_side_warning(reverse)
    if warning:
        print(warning, file=sys.stderr)
    # a pair cut from machine settings: its flanks at the blank's mean points, the
    # generating gear's angles (a summary sheet's) beside the pitch cone's
    points = getattr(args, "mean_points", None)
    if pair.machine and points is None:
        points = measure_pair_mean_points(pair)
    settings_check = getattr(args, "blank_check", None)
    if args.json:
        out = {"pair": pair.name, **blank.as_dict(), "gear_generation": generation,
               "reverse_side_contact_ratio": None if reverse is None else {
                   "side": reverse.side, "eps_p": reverse.total, "ends": list(reverse.ends),
                   "warning": warning},
               "mean_point_angles": None if points is None else mean_point_json(points),
               "blank_check": None if settings_check is None
               else blank_check_json(settings_check.blank),
               "easeoff_shape": None if getattr(settings_check, "easeoff", None) is None
               else easeoff_shape_json(settings_check.easeoff)}
        print(json.dumps(out, indent=2))
        return 0
    print(f"pair {pair.name}: ISO 23509 Method 1 blank design "
          f"(shaft angle {pair.shaft_angle_deg:g} deg, {pair.pinion_hand}-hand pinion)")
    width = max(len(r[0]) for r in _PAIRED + _SINGLE) + 7
    print(f"{'quantity':<{width}} {'pinion':>12} {'gear':>12}")
    for label, a1, a2, unit in _PAIRED:
        name = f"{label} [{unit}]" if unit else label
        print(f"{name:<{width}} {_fmt(getattr(blank, a1)):>12} {_fmt(getattr(blank, a2)):>12}")
    for label, attr, unit in _SINGLE:
        name = f"{label} [{unit}]" if unit else label
        print(f"{name:<{width}} {_fmt(getattr(blank, attr)):>12}")
    P = ", ".join(f"{c:.4f}" for c in blank.pitch_point_mm)
    print(f"{'pitch point P (meshing frame) [mm]':<{width}} ({P})")
    print(f"gear flanks: {generation_text(generation, pair)}")
    if points is not None:
        print(mean_point_table(points))
    if settings_check is not None:
        print(blank_check_text(settings_check.blank))
        if settings_check.easeoff is not None:
            print(easeoff_shape_text(settings_check.easeoff))
    return 0
