"""The modes of ``gearcontact design`` that write files: ``--calibrate``,
``--synthesize-easeoff`` and ``--machine-settings`` (standard settings, local synthesis,
or the settings fit of an ease-off / measured flank). Each is one library call and one
library writer; the options were checked by :mod:`.design_options`."""

from __future__ import annotations

import dataclasses
import sys

from ..errors import CheckFailed
from ..geometry.formate import SIDES
from ..geometry.pair import has_easeoff
from ..geometry.written_blade import written_pair
from ..geometry.written_roll import written_rolls
from ..validation import InputRangeError
from .design_options import checked_targets, path_angle_option, renamed
from .outdir import final_path


def calibrate(args, pair) -> int:
    from ..report.design import calibrate_to_published, write_calibration

    cal = calibrate_to_published(pair, tip_margin_mm=args.tip_margin, progress=True)
    path = write_calibration(cal, args.out)
    print(cal.table())
    print(f"design side {cal.side}; working depth factor {cal.pair.working_depth_factor:g}; "
          f"{cal.evaluations} TCA runs in {cal.seconds:.0f} s -> {final_path(args, path)}")
    return 0


def synthesize(args, pair) -> int:
    from ..geometry.flank import build_flanks
    from ..report.design import write_easeoff_toml
    from ..tca.synthesis import easeoff_toml, synthesize_pair

    targets = checked_targets(args)
    flanks = getattr(args, "flanks", None) or build_flanks(
        pair, checked=getattr(args, "generation_check", None))
    _, done = synthesize_pair(pair, targets=targets, flanks=flanks)
    for side, s in done.items():
        print(f"# {side}: {s.evaluations} TCA runs, {s.seconds:.0f} s\n" + s.table())
    text = easeoff_toml(done, pair_name=pair.name)
    print(text)
    if args.out is not None:
        print(f"-> {final_path(args, write_easeoff_toml(text, args.out))}")
    refuse_missed("ease-off synthesis", pair, done)
    return 0


def refuse_missed(what: str, pair, done: dict) -> None:
    """CheckFailed (exit 4) naming the sides of ``done`` whose targets were missed; the
    table says which, the TOML written stays."""
    missed = [side for side, s in done.items() if not s.met]
    if missed:
        why = "".join(f"; not reachable: {done[side].unreachable}" for side in missed
                      if getattr(done[side], "unreachable", None))
        raise CheckFailed(f"{what} of {pair.name}: not all targets met on the "
                          f"{' and '.join(missed)} side{'s' if len(missed) > 1 else ''} "
                          f"(see the table){why}")


def refuse_gap(args, pair, cut) -> None:
    """The settings' own TCA where the blank's predicted contact ratio is short
    (:func:`~gearcontact.tca.settings_gap.check_settings_gap`): a gap is refused (exit 2)
    before anything is written, no gap says so on stderr; every writer of machine
    settings calls it (docs/machine_settings.md sec. 5, "The settings' own TCA in
    `design`")."""
    from ..tca.settings_gap import check_settings_gap

    line = check_settings_gap(pair, cut, boxes=args.generation_check, progress=True).line()
    if line:
        print(f"gearcontact design: {line}", file=sys.stderr)


def line_contact_note(args, cut, sides) -> list[str]:
    """The settings' line contact on ``sides`` (those cut uncrowned by construction):
    the TCA the loaded commands run (:func:`~gearcontact.tca.settings_line_contact.
    settings_line_contact`); each side found is written as asked and named: its refusal
    on stderr, ``line_contact`` in run.json (B- and the message), and the returned lines
    for the file's head comment (none where none; docs/machine_settings.md sec. 4,
    "Uncrowned settings in `design`")."""
    if not sides:
        return []
    from ..geometry.basic_settings import STANDARD_CROWNING
    from ..tca.line_contact import CROWNING_ADVICE, LINE_CURVATURE_PER_MM
    from ..tca.settings_line_contact import settings_line_contact

    found = settings_line_contact(cut, sides=sides)
    for line in found.values():
        print(f"gearcontact design: warning: the settings are written uncrowned, as asked; "
              f"the loaded commands refuse that side: {line}", file=sys.stderr)
    run = getattr(args, "run", None)
    if run is not None and found:
        run.input_checks["line_contact"] = {side: {"b_minus_per_mm": line.found,
                                                   "message": str(line)}
                                            for side, line in found.items()}
    default = ("the default crowning: --lengthwise-crowning-um "
               f"{STANDARD_CROWNING['lengthwise_crowning_um']:g} --blade-profile-crowning-um "
               f"{STANDARD_CROWNING['blade_profile_crowning_um']:g}")
    return [line for side in found for line in (
        f"{side}: uncrowned: the TCA finds line contact (B- below {LINE_CURVATURE_PER_MM:g} "
        f"1/mm at its reference point); the loaded commands refuse this side ({default}).",
        CROWNING_ADVICE)]


def crowning_named(exc: InputRangeError, args) -> InputRangeError:
    """``exc`` renamed to the crowning options the user typed where it is the pinion
    check's refusal of the standard pinion (a pointed tooth; its field the derived
    ``[machine.pinion.*]`` tables, which the user never typed): the options that moved
    the pinion from the standard one (which one pointed it is not known: both shape its
    tooth), the check's verdict kept in the message; any other error, or no option
    typed, unchanged."""
    typed = {o: v for o, v in (("--lengthwise-crowning-um", args.lengthwise_crowning_um),
                               ("--blade-profile-crowning-um",
                                args.blade_profile_crowning_um)) if v is not None}
    if not typed or not exc.field.startswith("[machine.pinion."):
        return exc
    values = tuple(typed.values())
    return InputRangeError(" / ".join(typed) + " (um)", values[0] if len(values) == 1
                           else values, (
        f"a crowning whose standard pinion the readers accept; the pinion check refuses "
        f"{exc.field} = {exc.value!r}: {exc.allowed}"))


def machine_settings(args, pair) -> int:
    from ..geometry.basic_settings import standard_machine_pair
    from ..geometry.pair import pair_to_toml
    from ..geometry.typed_pinion import typed_gear_cut
    from ..report.design import write_machine_settings_toml
    from ..tca.settings_line_contact import UNCROWNED_UM

    if has_easeoff(pair) or args.target_flank is not None:
        return easeoff_settings(args, pair)

    if args.local_synthesis:
        return local_synthesis(args, pair)
    crowning = {k: v for k, v in (("lengthwise_crowning_um", args.lengthwise_crowning_um),
                                  ("blade_profile_crowning_um", args.blade_profile_crowning_um))
                if v is not None}
    reliefs = getattr(args, "reliefs", None)
    gear = getattr(args, "typed_gear", None)
    if gear:    # the typed gear as typed, the standard pinion of that gear
        source = "[print.gear]" if pair.print_gear else "[machine.gear.*] / [blade.gear.*]"
        try:
            cut, fits = typed_gear_cut(pair, gear, reliefs=reliefs, **crowning)
        except InputRangeError as exc:      # a gear off its blank: named by its slip
            from .settings_slip import slip_renamed

            named = slip_renamed(exc, getattr(args, "typed_gear_check", None),
                                 failed="the derivation of its standard pinion")
            raise (crowning_named(exc, args) if named is exc else named) from None
        head = (f"{pair.name}: the typed gear ({source}, kept as typed) and its standard "
                "pinion (gearcontact design --machine-settings;\nsigns: "
                "docs/machine_settings.md sec. 2, the pinion sec. 5); gear: typed, "
                + "/".join(sorted({"formate" if g.settings.formate else "generated"
                                   for g in gear.values()}))
                + "".join(f"\n{f.line()}" for f in fits.values()))
    else:
        # the gear of the default flanks (check: generated where the formate gear undercuts)
        generation = "formate" if args.gear_generation == "machine" else args.gear_generation
        try:
            cut = standard_machine_pair(pair, gear_generation=generation, reliefs=reliefs,
                                        **crowning)
        except InputRangeError as exc:      # a pointed pinion: named by the typed option
            raise crowning_named(exc, args) from None
        head = (f"{pair.name}: standard machine settings from the blank (gearcontact design "
                "--machine-settings;\nsigns: docs/machine_settings.md); gear: "
                f"{generation}")
    cut, notes = written_pair(cut)
    refuse_gap(args, pair, cut)
    uncrowned = all(c is not None and c < UNCROWNED_UM for c in (
        args.lengthwise_crowning_um, args.blade_profile_crowning_um))
    notes += line_contact_note(args, cut, SIDES if uncrowned else ())
    head += "".join(f"\n{n}" for n in notes)
    text = pair_to_toml(cut, comments={"": head})
    print(text)
    if args.out is not None:
        print(f"-> {final_path(args, write_machine_settings_toml(text, args.out))}")
    return 0


def local_synthesis(args, pair) -> int:
    from ..report.design import local_synthesis_toml, write_machine_settings_toml
    from ..tca.setting_synthesis import synthesized_machine_pair

    try:
        # a side without a pivot on the flank gets its standard pinion, written, exit 4
        cut, done = synthesized_machine_pair(pair, targets=checked_targets(args),
                                             gear=getattr(args, "typed_gear", None),
                                             standard_off_flank=True,
                                             bearing_room=not getattr(
                                                 args, "pattern_length_typed", False))
    except InputRangeError as exc:     # the reach model's certain refusal names the side
        side = next((s for s in SIDES if f"the {s} settings" in exc.allowed), SIDES[0])
        raise renamed(exc, path_angle_option(args, side)) from None
    cut, notes = written_pair(cut)
    refuse_gap(args, pair, cut)
    text = local_synthesis_toml(cut, done, typed=bool(getattr(args, "typed_gear", None)),
                                notes=notes)
    print(text)
    if args.out is not None:
        print(f"-> {final_path(args, write_machine_settings_toml(text, args.out))}")
    refuse_missed("setting synthesis", pair, done)
    off = [side for side in SIDES if side not in done]
    if off:
        raise CheckFailed(f"setting synthesis of {pair.name}: no pivot on the flank on the "
                          f"{' and '.join(off)} side{'s' if len(off) > 1 else ''} (the base "
                          "pinion's contact path has no point inside the flank by the "
                          "pivot's margin; its standard pinion is written, see the head "
                          "comment)")
    return 0


def grid_relief_named(exc: InputRangeError, target_flank) -> InputRangeError:
    """``exc`` of :func:`~gearcontact.geometry.easeoff.apply_easeoff` (the largest relief
    over a side beyond the ease-off limit) renamed to the ``--target-flank`` CSV's column
    where the relief is the file's grid: the library names its ease-off and advises on
    typed tables; the user typed the file (a column in nm, or in mm, is the likely slip).
    Any other error unchanged."""
    head, _, at = exc.field.partition(" relief at the ")
    side = head.removeprefix("easeoff (").removesuffix(")")
    if target_flank is None or not at or side not in SIDES:
        return exc
    where = at[at.index("("):] if "(" in at else ""
    return InputRangeError(f"{target_flank}: {side} easeoff_um {where}".strip(), exc.value,
                           exc.allowed.split(";")[0] + "; the grid's deviations in um, not "
                           "nm or mm)")


def target_paths(pair) -> dict:
    """``{side: PathCurvature}`` of the pair's TCA on each side in point contact
    (:func:`~gearcontact.tca.path_curvature.target_path_curvature`, ``design
    --contact-curvature``); a side whose TCA fails is named on stderr and fitted without
    the curvature rows."""
    from ..geometry.formate import SIDES
    from ..tca.path_curvature import target_path_curvature
    from ..validation import UnusableInput

    paths = {}
    for side in SIDES:
        try:
            path = target_path_curvature(pair, side)
        except UnusableInput as exc:
            print(f"gearcontact design: {side}: no curvature rows (the target's TCA: "
                  f"{exc})", file=sys.stderr)
            continue
        if path is not None:
            paths[side] = path
    return paths


def easeoff_settings(args, pair) -> int:
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
        cut, notes = written_pair(cut, members=tuple(c.member for c in done))
        refuse_gap(args, pair, cut)
        text = gear_correction_toml(cut, *done, notes=notes)
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
    paths = target_paths(pair) if getattr(args, "contact_curvature", False) else None
    try:
        fit = easeoff_machine_pair(pair, easeoff_grid=getattr(args, "easeoff_grid", None),
                                   objective=args.fit or "rms", where=where,
                                   reliefs=getattr(args, "reliefs", None), paths=paths)
    except InputRangeError as exc:
        raise grid_relief_named(exc, args.target_flank) from None
    if gear is not None:
        fit = dataclasses.replace(fit, pair=corrected_pair(fit.pair, gear))
    # the fit's roll of rounding written as its seed's, then the blades' (sec. 5)
    written, roll_notes = written_rolls(fit.pair, {s: r.fit for s, r in fit.sides.items()},
                                        boxes={s: r.box for s, r in fit.sides.items()})
    written, notes = written_pair(written, members=("pinion", "gear") if gear else ("pinion",))
    notes = roll_notes + notes
    fit = dataclasses.replace(fit, pair=written)
    refuse_gap(args, pair, fit.pair)
    # a side fitted to a zero ease-off is cut uncrowned: the conjugate pinion's settings
    notes += line_contact_note(args, fit.pair, tuple(
        side for side, r in fit.sides.items() if r.easeoff_max_um == 0.0))
    print(easeoff_settings_toml(fit, gear=gear, notes=notes))
    print(fit.table())
    if gear is not None:
        print(gear.table())
    if args.out is not None:
        path = write_easeoff_settings(fit, args.out, gear=gear, notes=notes)
        print(f"-> {final_path(args, path)}")
    return 0
