"""Checks of ``gearcontact design``'s options against each other and the pair, before
any flank is built (a contradiction costs nothing), and the synthesis targets they set;
the error names the option the user typed."""

from __future__ import annotations

from ..geometry.formate import SIDES
from ..geometry.pair import has_easeoff
from ..validation import InputRangeError, check_range


#: The least crowning ``--lengthwise-crowning-um`` / ``--blade-profile-crowning-um``
#: take besides 0, um: the flanks' own accuracy (the pinion sheets interpolate their
#: exact nodes to ~1e-9 mm = 1e-6 um, :data:`~gearcontact.tca.line_contact.LINE_TOLERANCE_MM`'s
#: reason), below which a crowning is none on the flanks built; a subnormal one
#: overflowed the blade radius ``(h_mw/2)^2 / 2c`` to inf.
MIN_CROWNING_UM = 1e-6


def check_relieved_blades(args, pair) -> None:
    """The Toprem / Flankrem of a pair's blades, before any flank is built: kept by
    ``--machine-settings`` (``args.reliefs``: the standard settings and the settings
    fit keep each relief as given on its blade,
    :func:`~gearcontact.geometry.relief_setup.relieved_setup`),
    refused where the kink would be dropped or smoothed: ``--machine-settings
    --local-synthesis`` (the synthesized settings are solved for smooth blades).
    ``--synthesize-easeoff`` refuses every pair cut from settings (:func:`check_options`)."""
    from ..geometry.machine import relieved_blade_keys
    from ..geometry.relief_setup import blade_reliefs

    args.reliefs = blade_reliefs(pair.machine)
    kinks = relieved_blade_keys(pair.machine)
    if not args.local_synthesis or not kinks:
        return
    raise InputRangeError(*kinks[0], "0 with --machine-settings --local-synthesis: the "
                          "synthesized settings are solved for smooth blades (--machine-"
                          "settings without it keeps the relief); analyze, ltca, bending "
                          "and export flanks take the relieved pair as it is")


def check_options(args, pair) -> None:
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
    if args.synthesize_easeoff and (pair.machine or pair.typed_gear):
        raise InputRangeError("--synthesize-easeoff", True, (
            "a pair without [machine.*] / [blade.*] tables: this pair's flanks are cut "
            "from its settings, and [easeoff.*] tables are refused beside them; the "
            "pinion settings for a TE0 and bearing target come from --machine-settings "
            "--local-synthesis"))
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
            if exc.field.endswith(": header"):  # neither format's: name both
                from ..geometry.easeoff import GRID_COLUMNS
                from ..geometry.measuring_grid import MEASURED_COLUMNS

                raise InputRangeError(exc.field, exc.value, (
                    f"a header {','.join(GRID_COLUMNS)} (a measured ease-off grid) or "
                    f"{','.join(MEASURED_COLUMNS)} (deviations in machine coordinates, "
                    "docs/export.md)")) from None
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
    if getattr(args, "contact_curvature", False) and not (
            args.machine_settings and has_easeoff(pair) and args.target_flank is None):
        raise InputRangeError("--contact-curvature", True, "given only with "
                              "--machine-settings on a pair with an ease-off and no "
                              "--target-flank (the target pair's own TCA path)")
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
            if 0.0 < value < MIN_CROWNING_UM:
                raise InputRangeError(f"{option} (um)", value, (
                    f"0 (no crowning) or [{MIN_CROWNING_UM:g}, 200]: a crowning below "
                    f"{MIN_CROWNING_UM:g} um is below the flanks' own accuracy (their "
                    "interpolation, ~1e-9 mm)"))
    # an option of a mode that is not asked for would be ignored without a word
    synthesis = args.synthesize_easeoff or args.local_synthesis
    for option, value, mode in (("--tip-margin", args.tip_margin, args.calibrate),
                                ("--te0-arcsec", args.te0_arcsec, synthesis),
                                ("--pattern-length-ratio", args.pattern_length_ratio,
                                 synthesis),
                                *((o, v, synthesis)
                                  for o, v in path_angle_options(args).items()),
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
#: (the path angle's: :func:`path_angle_option`).
TARGET_OPTIONS = {"te0_pp_arcsec": "--te0-arcsec",
                   "pattern_length_ratio": "--pattern-length-ratio"}


def path_angle_options(args) -> dict:
    """The path-angle options, option -> value (None if not given)."""
    return {"--path-angle-deg": args.path_angle_deg,
            **{f"--path-angle-{side}-deg": getattr(args, f"path_angle_{side}_deg")
               for side in SIDES}}


def path_angle_option(args, side: str) -> str:
    """The option that sets the path angle of ``side``."""
    return "--path-angle-deg" if args.path_angle_deg is not None else f"--path-angle-{side}-deg"


def renamed(exc: InputRangeError, option: str | None = None) -> InputRangeError:
    """``exc`` naming the option of its field (``option`` for the path angle's)."""
    field = option if exc.field == "path_angle_deg" and option else exc.field
    return InputRangeError(TARGET_OPTIONS.get(field, field), exc.value, exc.allowed)


def synthesis_targets(args) -> dict:
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
            raise renamed(exc, path_angle_option(args, side)) from None
    return out


def checked_targets(args) -> dict:
    """The targets :func:`check` made, or made of the options (a run without it)."""
    return getattr(args, "targets", None) or synthesis_targets(args)


def checked_flanks(pair, args, targets: dict):
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
            raise renamed(exc, path_angle_option(args, side)) from None
    return flanks


def kept_gear(args, pair) -> dict | None:
    """``{side: MachineSetup}`` of the typed gear ``design --machine-settings`` keeps (a
    pair file typing the gear alone, or both members with ``--keep-gear``), else None;
    an input error (exit 2) for ``--keep-gear`` without ``--machine-settings`` or without
    a typed gear, and for a kept gear with ``--target-flank`` (a mode that fits the
    pair's own settings). ``--local-synthesis`` synthesizes the pinion of the kept gear."""
    keep = getattr(args, "keep_gear", False)
    if keep and not args.machine_settings:
        raise InputRangeError("--keep-gear", True, "given only with --machine-settings "
                              "(without it the option has no effect)")
    if keep and not (pair.machine or pair.typed_gear):
        raise InputRangeError("--keep-gear", True, f"a pair file that types the gear's "
                              f"settings ([machine.gear.*] / [blade.gear.*] or [print.gear]); "
                              f"{args.pair} types none (its standard settings: without "
                              "--keep-gear)")
    setups = pair.typed_gear or (tuple(s for s in pair.machine if s.member == "gear")
                                 if keep else ())
    if not setups:
        return None
    if args.target_flank is not None:
        raise InputRangeError("--target-flank", args.target_flank, "not given when the pair's "
                              "typed gear is kept (a gear typed alone, or --keep-gear): its "
                              "pinion is derived; the option works on the blank's own gear "
                              "or on a pair typing both members without --keep-gear")
    gear = {s.side: s for s in setups}
    if args.local_synthesis:
        from ..geometry.typed_pinion import gear_motion_keys

        moved = gear_motion_keys(gear) if len(gear) == len(SIDES) else []
        if moved:       # the roll correction takes a linear-roll base pinion only
            raise InputRangeError(*moved[0], "0 with --machine-settings --local-synthesis "
                                  "(the synthesis corrects a linear roll; the derived pinion "
                                  "of a gear cut with modified roll or helical motion is "
                                  "not one); --machine-settings without it writes that "
                                  "gear's standard pinion")
    return gear

