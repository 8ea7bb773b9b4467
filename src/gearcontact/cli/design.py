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

from ..errors import CheckFailed
from ..geometry.contact_path import SYNTHESIS_PATTERN_RATIO, SYNTHESIS_TE0_ARCSEC
from ..geometry.contact_ratio import reverse_side_warning
from ..geometry.flank_angles import measure_pair_mean_points
from ..geometry.formate import SIDES
from ..geometry.gear_generation import generation_of, generation_text
from ..geometry.generation import check_generation, reverse_side_contact_ratio
from ..geometry.pair import (BEVEL, CYLINDRICAL, PRESETS, has_easeoff, load_pair,
                             without_easeoff)
from ..report.design_mean_point import (blank_check_json, blank_check_text, checked_blank,
                                        mean_point_json, mean_point_table)
from ..validation import InputRangeError, check_range
from .outdir import final_path

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
                        "length over the gear face width (default 0.35; practice 1/3 to 1/2)")
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
                        "pinion with lengthwise and profile crowning; a pair cut from machine "
                        "settings gets those of its blank, its blades' Toprem / Flankrem "
                        "kept as given); prints the pair TOML "
                        "with its [machine.*]/[blade.*] tables, written as "
                        "machine_settings.toml (and the residual map) with --out")
    p.add_argument("--local-synthesis", action="store_true",
                   help="with --machine-settings on a hypoid whose gear is generated: the "
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
    p.add_argument("--lengthwise-crowning-um", type=float, default=None,
                   help="with --machine-settings: pinion cutter circle departure at the "
                        "face ends, um, 0 to 200 (default 25)")
    p.add_argument("--blade-profile-crowning-um", type=float, default=None,
                   help="with --machine-settings: pinion blade profile departure at "
                        "+-h_mw/2, um, 0 to 200 (default 10)")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """--calibrate needs published values and --out; design writes files only with
    --calibrate or --synthesize-easeoff --out (under the output-directory policy,
    :mod:`.outdir`). The options are checked against each other before the pair's
    generation (seconds for a generated gear): a contradiction costs nothing."""
    pair = args.gear_pair = load_pair(args.pair, kinds=(BEVEL, CYLINDRICAL))
    if args.force and args.out is None:
        raise InputRangeError("--force", True, "given only with --out (without it the "
                                               "option has no effect)")
    if pair.kind == CYLINDRICAL:
        for option, value in (("--calibrate", args.calibrate),
                              ("--synthesize-easeoff", args.synthesize_easeoff),
                              ("--out", args.out), ("--tip-margin", args.tip_margin),
                              ("--te0-arcsec", args.te0_arcsec),
                              ("--pattern-length-ratio", args.pattern_length_ratio),
                              *_path_angle_options(args).items(),
                              ("--machine-settings", args.machine_settings),
                              ("--local-synthesis", args.local_synthesis),
                              ("--target-flank", args.target_flank),
                              ("--fit", args.fit),
                              ("--lengthwise-crowning-um", args.lengthwise_crowning_um),
                              ("--blade-profile-crowning-um", args.blade_profile_crowning_um)):
            if value not in (None, False):
                raise InputRangeError(option, value, "not given for a cylindrical pair "
                                      "(kind = 'cylindrical': design prints its geometry)")
        args.writes_files = False
        return
    _check_options(args, pair)
    _check_relieved_blades(args, pair)
    if args.machine_settings and pair.machine:
        # the settings are those of the blank (the pair's own tables are replaced): its
        # default gear, formate or generated, decides the gear's settings; measured
        # gear rows are corrected from the pair's own gear (the gear they measure)
        args.machine_pair = pair
        pair = args.gear_pair = dataclasses.replace(pair, machine=())
    # typed settings against the blank tables, on the flanks measured at the blank's mean
    # points once (the table below the blank prints the same measurements)
    args.mean_points = measure_pair_mean_points(pair) if pair.machine else None
    args.blank_check = checked_blank(pair, measured=args.mean_points)
    if args.synthesize_easeoff and pair.easeoff_tables:
        # the synthesis makes both sides' tables afresh from the conjugate pinion: the
        # checks below see the bearing it will make, not the tables it replaces
        pair = args.gear_pair = without_easeoff(pair)
    if args.synthesize_easeoff or args.local_synthesis:   # the same targets and checks
        args.te0_arcsec = SYNTHESIS_DEFAULTS["te0_arcsec"] if args.te0_arcsec is None \
            else args.te0_arcsec
        args.pattern_length_ratio = SYNTHESIS_DEFAULTS["pattern_length_ratio"] \
            if args.pattern_length_ratio is None else args.pattern_length_ratio
        args.targets = _synthesis_targets(args)     # their ranges, before any TCA
    # a pair whose pinion the gear cannot generate (limit line) is refused here; its
    # contact ratio is that of the bearing the synthesis will make (its gear flanks
    # are reused)
    args.generation_check = _check_generation(args, pair)
    args.gear_generation = generation_of(args.generation_check)
    if args.local_synthesis and (args.gear_generation != "generated"
                                 or pair.offset_mm == 0.0):
        raise InputRangeError("--local-synthesis", f"pair {pair.name} (axes.offset_mm = "
                              f"{pair.offset_mm:g}, default gear {args.gear_generation})",
                              "a hypoid (axes.offset_mm != 0) whose default gear is "
                              "generated (its pinion cut by the crown gear: point contact)")
    if args.synthesize_easeoff:
        # the closed-form reach is the ease-off synthesis' (tca.path_reach); the settings
        # synthesis reports a target it misses in its table (exit 4)
        args.flanks = _check_targets(pair, args, args.targets)
    if args.calibrate:
        from ..report.analyze import published_values

        if published_values(pair.name) is None:
            raise InputRangeError("--pair", args.pair, "a built-in pair with published "
                                  "values (s0003, s0003-centred) for --calibrate")
        if args.out is None:
            raise InputRangeError("--out", None, "an output directory for calibrated.toml")
        if args.tip_margin is not None:
            check_range("--tip-margin (mm)", args.tip_margin, 0.01, 0.5)
    args.writes_files = bool(args.calibrate or ((args.synthesize_easeoff or args.machine_settings)
                                                and args.out))


def _check_relieved_blades(args, pair) -> None:
    """The Toprem / Flankrem of a pair's blades, before any flank is built: kept by
    ``--machine-settings`` (``args.reliefs``: the standard settings and the settings
    fit keep each relief as given on its blade,
    :func:`~gearcontact.geometry.relief_setup.relieved_setup`),
    refused where the kink would be dropped or smoothed: ``--machine-settings
    --local-synthesis`` (the synthesized settings are solved for smooth blades) and
    ``--synthesize-easeoff`` (an ease-off laid on the relieved pinion,
    :func:`~gearcontact.geometry.flank.with_easeoff`, is resampled across the kink)."""
    from ..geometry.machine import relieved_blade_keys
    from ..geometry.relief_setup import blade_reliefs

    args.reliefs = blade_reliefs(pair.machine)
    option = ("--machine-settings --local-synthesis" if args.local_synthesis else
              "--synthesize-easeoff" if args.synthesize_easeoff else None)
    kinks = relieved_blade_keys(pair.machine)
    if option is None or not kinks:
        return
    why = ("the synthesized settings are solved for smooth blades (--machine-settings "
           "without it keeps the relief)" if args.local_synthesis else
           "an ease-off laid on the relieved pinion would smooth its kink")
    raise InputRangeError(*kinks[0], f"0 with {option}: {why}; analyze, ltca, bending and "
                          "export flanks take the relieved pair as it is")


def _check_generation(args, pair) -> dict:
    """:func:`~gearcontact.geometry.generation.check_generation` of ``pair``, its
    contact path that of the bearing the synthesis will make where the design side has
    no table (:class:`~gearcontact.tca.predicted_bearing.BearingPredictor`): the targets
    of ``--synthesize-easeoff`` / ``--local-synthesis`` (the setting synthesis turns no
    short path), the default targets without them (``analyze`` synthesizes with those);
    a path angle the synthesis cannot reach names its option."""
    from ..tca.predicted_bearing import BearingPredictor
    from ..tca.synthesis_targets import SynthesisTargets

    if args.machine_settings and not args.local_synthesis:   # standard settings
        return check_generation(pair)
    predictor = BearingPredictor(getattr(args, "targets", None) or SynthesisTargets(),
                                 turns_short_paths=not args.local_synthesis)
    try:
        return check_generation(pair, bearing_of=predictor)
    except InputRangeError as exc:
        if exc.field != "path_angle_deg" and exc.field not in _TARGET_OPTIONS:
            raise
        raise _renamed(exc, _path_angle_option(args, pair.design_side)) from None


def _check_options(args, pair) -> None:
    """The options of a bevel pair against each other and the pair's kind (ease-off or
    not), without its flanks; reads ``--target-flank``."""
    modes = [m for m, on in (("--calibrate", args.calibrate),
                             ("--synthesize-easeoff", args.synthesize_easeoff),
                             ("--machine-settings", args.machine_settings)) if on]
    if len(modes) > 1:
        raise InputRangeError(" / ".join(modes), "all given", "one of them")
    if args.json and modes:
        raise InputRangeError("--json", True, f"not given with {modes[0]} (it prints TOML "
                                              "and tables; --json prints the blank design)")
    if args.target_flank is not None:
        if not args.machine_settings:
            raise InputRangeError("--target-flank", args.target_flank, "given only with "
                                  "--machine-settings (without it the option has no effect)")
        from ..geometry.measuring_grid import read_member_targets
        from ..geometry.point_fit import check_point_count

        try:
            args.easeoff_grid, args.gear_targets = read_member_targets(args.target_flank,
                                                                       pair=pair)
        except InputRangeError as exc:
            if exc.field != "target flank":     # a field inside the file: named as it is
                raise
            raise InputRangeError("--target-flank", exc.value, exc.allowed) from None
        check_point_count(args.easeoff_grid, where=str(args.target_flank))
        # the gear's points against its fewest settings before any flank is built (a
        # formate gear's subset; a pair's own gear tables tell its method exactly)
        from ..geometry.setting_fit import FORMATE_GEAR_PARAMETERS, default_parameters

        own = [s for s in pair.machine if s.member == "gear"]
        check_point_count(args.gear_targets, default_parameters(own[0]) if own else
                          FORMATE_GEAR_PARAMETERS, where=str(args.target_flank), member="gear")
    fitted = has_easeoff(pair) or args.target_flank is not None
    if args.fit is not None and not (args.machine_settings and fitted):
        raise InputRangeError("--fit", args.fit, "given only with --machine-settings on a pair "
                              "with an ease-off or --target-flank (the settings fit; without "
                              "it the option has no effect)")
    if args.local_synthesis and not args.machine_settings:
        raise InputRangeError("--local-synthesis", True, "given only with --machine-settings "
                              "(without it the option has no effect)")
    if args.local_synthesis and fitted:
        raise InputRangeError("--local-synthesis", True, "not given for a pair with an "
                              "ease-off or with --target-flank (--machine-settings fits the "
                              "settings that cut it; remove the [easeoff.*] tables for "
                              "synthesized settings)")
    for option, value in (("--lengthwise-crowning-um", args.lengthwise_crowning_um),
                          ("--blade-profile-crowning-um", args.blade_profile_crowning_um)):
        if value is not None and args.local_synthesis:
            raise InputRangeError(option, value, "not given with --local-synthesis (the "
                                  "synthesis sets the crowning)")
        if value is not None and not args.machine_settings:
            raise InputRangeError(option, value, "given only with --machine-settings "
                                                 "(without it the option has no effect)")
        if value is not None and fitted:
            raise InputRangeError(option, value, "not given for a pair with an ease-off or "
                                  "with --target-flank (--machine-settings fits the settings "
                                  "that cut it; remove the [easeoff.*] tables for standard "
                                  "settings)")
        if value is not None:
            check_range(f"{option} (um)", value, 0.0, 200.0)
    # an option of a mode that is not asked for would be ignored without a word
    synthesis = args.synthesize_easeoff or args.local_synthesis
    for option, value, mode in (("--tip-margin", args.tip_margin, args.calibrate),
                                ("--te0-arcsec", args.te0_arcsec, synthesis),
                                ("--pattern-length-ratio", args.pattern_length_ratio,
                                 synthesis),
                                *((o, v, synthesis)
                                  for o, v in _path_angle_options(args).items()),
                                ("--out", args.out, args.calibrate or args.synthesize_easeoff
                                 or args.machine_settings)):
        if value is not None and not mode:
            needs = ("--calibrate" if option == "--tip-margin" else
                     "--synthesize-easeoff or --machine-settings --local-synthesis"
                     if option != "--out" else
                     "--calibrate, --synthesize-easeoff or --machine-settings")
            raise InputRangeError(option, value, f"given only with {needs} (without it "
                                                 "the option has no effect)")


#: Option of each :class:`~gearcontact.tca.synthesis.SynthesisTargets` field it sets
#: (the path angle's: :func:`_path_angle_option`).
_TARGET_OPTIONS = {"te0_pp_arcsec": "--te0-arcsec",
                   "pattern_length_ratio": "--pattern-length-ratio"}


def _path_angle_options(args) -> dict:
    """The path-angle options, option -> value (None if not given)."""
    return {"--path-angle-deg": args.path_angle_deg,
            **{f"--path-angle-{side}-deg": getattr(args, f"path_angle_{side}_deg")
               for side in SIDES}}


def _path_angle_option(args, side: str) -> str:
    """The option that sets the path angle of ``side``."""
    return "--path-angle-deg" if args.path_angle_deg is not None else f"--path-angle-{side}-deg"


def _renamed(exc: InputRangeError, option: str | None = None) -> InputRangeError:
    """``exc`` naming the option of its field (``option`` for the path angle's)."""
    field = option if exc.field == "path_angle_deg" and option else exc.field
    return InputRangeError(_TARGET_OPTIONS.get(field, field), exc.value, exc.allowed)


def _synthesis_targets(args) -> dict:
    """The synthesis targets of each side (side -> SynthesisTargets) of the options; a
    target out of range names its option. ``--path-angle-deg`` sets both sides, a
    ``--path-angle-<side>-deg`` one side (the other is free); the two kinds together
    are refused (which would win is not obvious)."""
    from ..tca.synthesis import SynthesisTargets

    per_side = {side: getattr(args, f"path_angle_{side}_deg") for side in SIDES}
    if args.path_angle_deg is not None:
        given = [f"--path-angle-{s}-deg" for s, v in per_side.items() if v is not None]
        if given:
            raise InputRangeError("--path-angle-deg", args.path_angle_deg,
                                  f"not given with {' / '.join(given)} (it sets both "
                                  "sides; give one option per side instead)")
        per_side = dict.fromkeys(SIDES, args.path_angle_deg)
    out = {}
    for side, angle in per_side.items():
        try:
            out[side] = SynthesisTargets(te0_pp_arcsec=args.te0_arcsec,
                                         pattern_length_ratio=args.pattern_length_ratio,
                                         path_angle_deg=angle)
        except InputRangeError as exc:
            raise _renamed(exc, _path_angle_option(args, side)) from None
    return out


def _checked_targets(args) -> dict:
    """The targets :func:`check` made, or made of the options (a run without it)."""
    return getattr(args, "targets", None) or _synthesis_targets(args)


def _check_targets(pair, args, targets: dict):
    """The pair's flanks, after refusing a TE0 level, pattern length or path angle the
    synthesis cannot reach on its side (:func:`gearcontact.tca.path_reach.check_targets`:
    closed form, no TCA), the error naming the option that set it."""
    from ..geometry.flank import build_flanks
    from ..tca.path_reach import check_targets

    flanks = build_flanks(pair, checked=args.generation_check)
    for side, t in targets.items():
        try:
            check_targets(pair, targets=t, flanks=flanks, sides=(side,))
        except InputRangeError as exc:
            raise _renamed(exc, _path_angle_option(args, side)) from None
    return flanks


def _fmt(x) -> str:
    return str(x) if isinstance(x, int) else f"{x:.4f}"


def _calibrate(args, pair) -> int:
    from ..report.design import calibrate_to_published, write_calibration

    cal = calibrate_to_published(pair, tip_margin_mm=args.tip_margin, progress=True)
    path = write_calibration(cal, args.out)
    print(cal.table())
    print(f"design side {cal.side}; working depth factor {cal.pair.working_depth_factor:g}; "
          f"{cal.evaluations} TCA runs in {cal.seconds:.0f} s -> {final_path(args, path)}")
    return 0


def _synthesize(args, pair) -> int:
    from ..geometry.flank import build_flanks
    from ..report.design import write_easeoff_toml
    from ..tca.synthesis import easeoff_toml, synthesize_pair

    targets = _checked_targets(args)
    flanks = getattr(args, "flanks", None) or build_flanks(
        pair, checked=getattr(args, "generation_check", None))
    _, done = synthesize_pair(pair, targets=targets, flanks=flanks)
    for side, s in done.items():
        print(f"# {side}: {s.evaluations} TCA runs, {s.seconds:.0f} s\n" + s.table())
    text = easeoff_toml(done, pair_name=pair.name)
    print(text)
    if args.out is not None:
        print(f"-> {final_path(args, write_easeoff_toml(text, args.out))}")
    _refuse_missed("ease-off synthesis", pair, done)
    return 0


def _refuse_missed(what: str, pair, done: dict) -> None:
    """CheckFailed (exit 4) naming the sides of ``done`` whose targets were missed; the
    table says which, the TOML written stays."""
    missed = [side for side, s in done.items() if not s.met]
    if missed:
        why = "".join(f"; not reachable: {done[side].unreachable}" for side in missed
                      if getattr(done[side], "unreachable", None))
        raise CheckFailed(f"{what} of {pair.name}: not all targets met on the "
                          f"{' and '.join(missed)} side{'s' if len(missed) > 1 else ''} "
                          f"(see the table){why}")


def _machine_settings(args, pair) -> int:
    from ..geometry.basic_settings import standard_machine_pair
    from ..geometry.pair import pair_to_toml
    from ..report.design import write_machine_settings_toml

    if has_easeoff(pair) or args.target_flank is not None:
        return _easeoff_settings(args, pair)

    if args.local_synthesis:
        return _local_synthesis(args, pair)
    crowning = {k: v for k, v in (("lengthwise_crowning_um", args.lengthwise_crowning_um),
                                  ("blade_profile_crowning_um", args.blade_profile_crowning_um))
                if v is not None}
    # the gear of the default flanks (check: generated where the formate gear undercuts)
    generation = "formate" if args.gear_generation == "machine" else args.gear_generation
    text = pair_to_toml(standard_machine_pair(pair, gear_generation=generation,
                                              reliefs=getattr(args, "reliefs", None), **crowning),
                        comments={"": f"{pair.name}: standard machine settings from the blank "
                                      "(gearcontact design --machine-settings;\nsigns: "
                                      f"docs/machine_settings.md); gear: {generation}"})
    print(text)
    if args.out is not None:
        print(f"-> {final_path(args, write_machine_settings_toml(text, args.out))}")
    return 0


def _local_synthesis(args, pair) -> int:
    from ..report.design import local_synthesis_toml, write_machine_settings_toml
    from ..tca.setting_synthesis import synthesized_machine_pair

    try:
        cut, done = synthesized_machine_pair(pair, targets=_checked_targets(args))
    except InputRangeError as exc:     # the reach model's certain refusal names the side
        side = next((s for s in SIDES if f"the {s} settings" in exc.allowed), SIDES[0])
        raise _renamed(exc, _path_angle_option(args, side)) from None
    text = local_synthesis_toml(cut, done)
    print(text)
    if args.out is not None:
        print(f"-> {final_path(args, write_machine_settings_toml(text, args.out))}")
    _refuse_missed("setting synthesis", pair, done)
    return 0


def _easeoff_settings(args, pair) -> int:
    from ..geometry.easeoff_settings import easeoff_machine_pair
    from ..geometry.gear_correction import (corrected_pair, gear_correction, gear_seeds,
                                            machine_seeds, measured_corrections)
    from ..geometry.measuring_grid import MeasuredFlank
    from ..report.design import (easeoff_settings_toml, gear_correction_toml,
                                 write_easeoff_settings, write_gear_points,
                                 write_machine_settings_toml)

    where = str(args.target_flank or "target flank")
    gear = None
    own = getattr(args, "machine_pair", None)     # the pair as read, with its tables
    generation = "formate" if args.gear_generation == "machine" else args.gear_generation
    measured = {m: r for m, r in (("gear", getattr(args, "gear_targets", None)),
                                  ("pinion", getattr(args, "easeoff_grid", None))) if r}
    if own is not None and measured and \
            all(isinstance(m, MeasuredFlank) for m in measured.get("pinion", {}).values()):
        # a pair cut from machine settings, measured rows: each measured member
        # corrected from its own tables (the flank the user measured), the other kept
        done = list(measured_corrections(pair, measured, seeds={
            "gear": gear_seeds(own, generation), "pinion": machine_seeds(own, "pinion")},
            objective=args.fit or "rms", where=where).values())
        cut = own
        for c in done:
            cut = corrected_pair(cut, c)
        text = gear_correction_toml(cut, *done)
        print(text)
        for c in done:
            print(c.table())
        if args.out is not None:
            for c in done:
                write_gear_points(c, args.out)
            print(f"-> {final_path(args, write_machine_settings_toml(text, args.out))}")
        return 0
    if "gear" in measured:       # measured gear rows: the gear corrected
        gear = gear_correction(pair, measured["gear"], objective=args.fit or "rms",
                               seeds=gear_seeds(own or pair, generation), where=where)
    fit = easeoff_machine_pair(pair, easeoff_grid=getattr(args, "easeoff_grid", None),
                               objective=args.fit or "rms", where=where,
                               reliefs=getattr(args, "reliefs", None))
    if gear is not None:
        fit = dataclasses.replace(fit, pair=corrected_pair(fit.pair, gear))
    print(easeoff_settings_toml(fit, gear=gear))
    print(fit.table())
    if gear is not None:
        print(gear.table())
    if args.out is not None:
        print(f"-> {final_path(args, write_easeoff_settings(fit, args.out, gear=gear))}")
    return 0


def run(args) -> int:
    pair = getattr(args, "gear_pair", None) or load_pair(args.pair, kinds=(BEVEL, CYLINDRICAL))
    if pair.kind == CYLINDRICAL:
        from ..report.design_cylindrical import cylindrical_design_text

        print(cylindrical_design_text(pair, as_json=args.json))
        return 0
    if args.machine_settings:
        return _machine_settings(args, pair)
    if args.calibrate:
        return _calibrate(args, pair)
    if args.synthesize_easeoff:
        return _synthesize(args, pair)
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
               else blank_check_json(settings_check.blank)}
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
    return 0
