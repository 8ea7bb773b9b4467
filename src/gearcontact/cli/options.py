"""Options shared by the commands that analyse a gear pair (tca, ltca, lte, analyze),
their cheap validation (run by :func:`gearcontact.cli.main` before any work), and the
warnings users must see (stderr, one line each)."""

from __future__ import annotations

import dataclasses
import sys

from ..geometry.kinematics import ASSEMBLY_KEYS, ASSEMBLY_LIMITS
from ..geometry.pair import BEVEL, load_pair
from ..validation import InputRangeError, check_positive
from .outdir import add_out_argument, final_path

__all__ = ["add_pair_arguments", "check_pair_arguments", "check_count", "warn",
           "check_machine_settings", "check_distinct_torques",
           "case_warnings", "lte_warnings", "run_timings", "check_torque",
           "check_cylindrical_torque",
           "MAX_PHASES", "MAX_CELLS", "MAX_PAIRS", "torque_limit_nm", "torque_floor_nm",
           "rename_load_error", "load_pair_for", "record_completed_settings",
           "parse_misalignment",
           "MISALIGNMENT_HELP"]

#: Upper limit of ``--phases`` (61 is the report value; at 1001, measured on the project
#: machine: ``tca`` 5.2 s, ``lte`` 11.4 s in all; 100000 ran for minutes).
MAX_PHASES = 1001
#: Upper limit of ``--cells`` per side (the LCP grows as cells^2 log cells; measured at
#: 320: ``ltca`` 0.17 s, ``lte`` over 11 phases 20 s, so 61 phases take about 2 min).
MAX_CELLS = 320
#: Upper limit of ``--pairs`` (neighbouring pairs per side; more never reach contact).
MAX_PAIRS = 6


def check_count(field: str, value: int, lo: int, hi: int, *, note: str = "") -> int:
    """``lo <= value <= hi`` for an integer option, else :class:`InputRangeError`
    with the limits (and ``note``) in the message."""
    if isinstance(value, bool) or int(value) != value or not lo <= value <= hi:
        raise InputRangeError(field, value, f"an integer in [{lo}, {hi}]{note}")
    return int(value)


#: Help of ``--misalignment`` (sign conventions of :mod:`gearcontact.geometry.kinematics`).
MISALIGNMENT_HELP = (
    "assembly errors overriding the pair's [assembly] table, e.g. "
    "E=0.05,P=-0.02,G=0.03,alpha=0.01 (keys not given keep the table's value). E mm: "
    "offset increased (pinion axis to y = -(E0 + E)); P mm: pinion moved along its axis "
    "away from the crossing point; G mm: gear moved along its axis away from the crossing "
    "point; alpha deg: shaft angle increased. |E|, |P|, |G| <= "
    f"{ASSEMBLY_LIMITS['E_mm']:g} mm, |alpha| <= {ASSEMBLY_LIMITS['alpha_deg']:g} deg "
    "(docs/sweeps.md)")


def parse_misalignment(text: str, *, field: str = "--misalignment") -> dict[str, float]:
    """``"E=0.05,P=-0.02"`` -> ``{"E_mm": 0.05, "P_mm": -0.02}`` (fields of
    :class:`~gearcontact.geometry.kinematics.AssemblyErrors`).

    Raises
    ------
    InputRangeError
        Naming the item for an unknown or repeated key, a bad number or a value
        beyond :data:`~gearcontact.geometry.kinematics.ASSEMBLY_LIMITS`.
    """
    out: dict[str, float] = {}
    for item in str(text).split(","):
        key, eq, value = (part.strip() for part in item.partition("="))
        if not eq or key not in ASSEMBLY_KEYS:
            raise InputRangeError(field, item.strip(), "KEY=VALUE items separated by commas,"
                                  f" KEY one of {', '.join(ASSEMBLY_KEYS)}")
        name = ASSEMBLY_KEYS[key]
        if name in out:
            raise InputRangeError(field, text, f"each key at most once ({key} repeated)")
        try:
            x = float(value)
        except ValueError:
            raise InputRangeError(f"{field} {key}", value, "a number") from None
        lim = ASSEMBLY_LIMITS[name]
        unit = "deg" if name.endswith("_deg") else "mm"
        if not -lim <= x <= lim:     # also refuses NaN
            raise InputRangeError(f"{field} {key} ({unit})", x, f"[{-lim:g}, {lim:g}] {unit}")
        out[name] = x
    return out


def add_pair_arguments(p, *, torque: bool = False, cells: int | None = None,
                       phases: bool = True, misalignment: bool = False) -> None:
    """Add ``--pair --out --force --side --phases --no-figures`` (and ``--torque``,
    ``--cells``, ``--misalignment``; ``phases=False`` leaves out the mesh options
    ``--side --phases``)."""
    p.add_argument("--pair", default="s0003", help="preset name or TOML file (default s0003)")
    add_out_argument(p)
    if misalignment:
        p.add_argument("--misalignment", default=None, metavar="E=..,P=..,G=..,alpha=..",
                       help=MISALIGNMENT_HELP)
    if torque:
        p.add_argument("--torque", type=float, default=64.5,
                       help="gear torque in N·m (default 64.5); the normal load it makes "
                            "must lie in the preview envelope (1 to 131072 N)")
    if phases:
        p.add_argument("--side", default=None, choices=("drive", "coast"),
                       help="flank pair (default: the pair's design_side; s0003: coast, the "
                            "published design point; a cylindrical pair: drive, its pinion's "
                            "cw flanks, docs/cylindrical.md)")
        p.add_argument("--phases", type=int, default=61,
                       help=f"TCA mesh phases per pinion pitch, both ends included, 3 to "
                            f"{MAX_PHASES} (default 61)")
    if cells is not None:
        p.add_argument("--cells", type=int, default=cells,
                       help=f"cells per side of the tangent-plane gap field (a "
                            f"cylindrical pair: cells along the face), 16 to {MAX_CELLS} "
                            f"(default {cells})")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")


def check_pair_arguments(args, *, kinds: tuple[str, ...] = (BEVEL,)) -> None:
    """Cheap checks before the expensive stages (the library checks again); loads the
    pair (TOML errors name the file and the field) into ``args.gear_pair``; ``kinds``:
    the pair kinds the command reads (:func:`~gearcontact.geometry.pair.load_pair`). A
    pair without a design side (cylindrical) defaults ``--side`` to drive."""
    if getattr(args, "phases", None) is not None:
        check_count("--phases", args.phases, 3, MAX_PHASES)
    args.gear_pair = load_pair(args.pair, kinds=kinds)
    if getattr(args, "cells", None) is not None:    # a bevel field is square; a line's is not
        check_count("--cells", args.cells, 16, MAX_CELLS,
                    note=" per side" if args.gear_pair.kind == BEVEL else " along the face")
    given = getattr(args, "misalignment", None)
    if given is not None and args.gear_pair.kind != BEVEL:
        raise InputRangeError("--misalignment", given, "not given for a cylindrical pair (E, "
                              "P, G, alpha are hypoid mounting errors; its [assembly] table "
                              "gives f_Sigma_delta, f_Sigma_beta: docs/cylindrical.md)")
    override = parse_misalignment(given) if given is not None else {}
    if override:    # the pair's assembly errors are what TCA and every JSON use
        assembly = dataclasses.replace(args.gear_pair.assembly, **override)
        args.gear_pair = dataclasses.replace(args.gear_pair, assembly=assembly)
    if hasattr(args, "side"):
        args.side = args.side or getattr(args.gear_pair, "design_side", "drive")
    if getattr(args, "torque", None) is not None:
        if args.gear_pair.kind == BEVEL:
            check_torque("--torque (N·m)", args.torque, args.gear_pair)
        else:
            check_cylindrical_torque("--torque (N·m)", args.torque, args.gear_pair)
    check_machine_settings(args)


def check_machine_settings(args) -> None:
    """The typed machine settings of ``args.gear_pair`` against its own blank tables,
    after the cheap option checks and before any work: the check the library runs when
    it takes a pair (:func:`~gearcontact.geometry.settings_check.check_settings`,
    docs/machine_settings.md sec. 2), run here once with its warnings on stderr
    (:func:`~gearcontact.report.design_mean_point.checked_blank`) and its result handed
    to the library as ``args.settings_check`` (:func:`load_pair_for`, ``analyze``), so
    that the library does not run it again. A gross mismatch (a hand, a generating
    spiral angle) raises naming the key (exit 2); any other flank outside its tolerance
    is a warning naming the likely key, and the run goes on. Its findings, with those
    warning lines, go into run.json as ``blank_check`` (``args.input_checks``, its time
    into the run's timings as ``blank_check_s``), the pinion ease-off shapes as
    ``easeoff_shape`` (``easeoff_shape_s``, inside ``blank_check_s``). Nothing for a pair without machine
    settings or a cylindrical pair (``args.settings_check`` None)."""
    from ..report.design_mean_point import blank_check_json, easeoff_shape_json
    from .settings_slip import checked_blank_named

    got = args.settings_check = checked_blank_named(args.gear_pair)
    if got is None:
        return
    args.input_checks = {"blank_check": {**blank_check_json(got.blank),
                                         "warnings": list(got.warnings)}}
    args.input_timings_s = {"blank_check_s": got.seconds}
    if got.easeoff is not None:
        args.input_checks["easeoff_shape"] = easeoff_shape_json(got.easeoff)
        args.input_timings_s["easeoff_shape_s"] = got.easeoff.seconds


def check_distinct_torques(option: str, torques) -> None:
    """Each torque of ``option`` once, to the 6 significant digits that name its result
    files (``pressure_64.5Nm.csv``): a repeated one would be solved again and write the
    same file over the first's."""
    seen: dict[str, float] = {}
    for t in torques:
        name = f"{t:g}"
        if name in seen:
            raise InputRangeError(option, list(torques), f"each torque once, to 6 significant "
                                  f"digits ({seen[name]!r} and {t!r} both name "
                                  f"pressure_{name}Nm.csv)")
        seen[name] = t


def torque_limit_nm(pair, lever_mm: float | None = None) -> float:
    """Largest gear torque (N·m) whose normal load W = T / lever stays within the
    preview envelope (:data:`gearcontact.preview.hertz.reference.ENVELOPE`). Without
    the lever (known only after the TCA), the gear's outer pitch radius bounds it:
    every larger torque is certainly out of range."""
    from ..preview.hertz.reference import ENVELOPE

    if lever_mm is None:
        lever_mm = pair.blank.mean_pitch_radius_gear_mm + 0.5 * pair.gear_face_width_mm
    return ENVELOPE["load_n"][1] * lever_mm / 1e3


def torque_floor_nm(pair) -> float:
    """Gear torque (N·m) below which the normal load W = T / lever is certainly under the
    preview envelope's lower end: the lever is at least the gear's inner pitch radius."""
    from ..preview.hertz.reference import ENVELOPE

    lever_mm = pair.blank.mean_pitch_radius_gear_mm - 0.5 * pair.gear_face_width_mm
    return ENVELOPE["load_n"][0] * lever_mm / 1e3


def check_torque(field: str, value, pair) -> float:
    """A gear torque in [:func:`torque_floor_nm`, :func:`torque_limit_nm`] N·m for
    ``pair``."""
    from ..preview.hertz.reference import ENVELOPE

    t = check_positive(field, value)
    lo, hi = torque_floor_nm(pair), torque_limit_nm(pair)
    if not lo <= t <= hi:
        raise InputRangeError(field, value, f"[{lo:.3g}, {hi:.6g}] for pair {pair.name} (its "
                                            "normal load must stay in "
                                            f"[{ENVELOPE['load_n'][0]:g}, "
                                            f"{ENVELOPE['load_n'][1]:g}] N, the preview "
                                            "envelope)")
    return t


def check_cylindrical_torque(field: str, value, pair) -> float:
    """A gear torque in (0, T_max] N·m for a cylindrical ``pair``: its whole normal load
    W = T2 / (r_b2 cos(beta_b)) (one pair carries it at a single-contact phase) within the
    preview envelope's largest load, as a bevel pair's (:func:`check_torque`)."""
    from ..ltca.cylindrical_lte import normal_load_n
    from ..preview.hertz.reference import ENVELOPE

    t = check_positive(field, value)
    w_max = ENVELOPE["load_n"][1]
    w = normal_load_n(pair, t)
    if w > w_max:
        raise InputRangeError(field, value, f"(0, {t * w_max / w:.6g}] for pair {pair.name} "
                                            f"(its normal load T2 / (r_b2 cos beta_b) = "
                                            f"{w:.6g} N must stay <= {w_max:g} N, the "
                                            "preview envelope)")
    return t


def rename_load_error(exc: InputRangeError, torque_nm: float, pair, tca) -> InputRangeError:
    """Re-word a library ``load_n`` range error as the ``--torque`` the user gave (the
    lever comes from the TCA's mean mating point)."""
    if not str(exc.field).startswith("load_n"):
        return exc
    from ..tca.load import torque_lever_mm

    lever = torque_lever_mm(tca.mean_point.point_mm, tca.mean_point.normal)
    hi = torque_limit_nm(pair, lever)
    return InputRangeError("--torque (N·m)", torque_nm,
                           f"(0, {hi:.6g}] for this pair (normal load W = T / lever "
                           f"{lever:.4g} mm = {1e3 * torque_nm / lever:.6g} N must lie in "
                           f"{exc.allowed})")


#: LCP peak above this multiple of the preview p_max at an edge contact: an edge spike.
EDGE_SPIKE_RATIO = 1.5


def case_warnings(case, *, label: str = "") -> list[str]:
    """What a user must see about one loaded case
    (:class:`~gearcontact.ltca.pair_ltca.PairLoadCase`), one line each: contact at
    the flank edge (the LCP peak is then an edge spike of rigid teeth, not a Hertzian
    pressure) or the edge of the gap field. Run the LTCA with
    :class:`~gearcontact.halfspace.patch.ContactAtEdgeWarning` ignored: this replaces it."""
    at = label or f"{case.torque_nm:g} N·m"
    out = []
    p = case.patch
    if case.edge_contact:
        spike = p.p_peak_mpa > EDGE_SPIKE_RATIO * case.preview.p_max_mpa
        out.append(f"{at}: the loaded contact reaches the flank edge ({case.off_flank_cells}"
                   f" cells of the field lie beyond the flank); LCP peak {p.p_peak_mpa:.0f} "
                   f"MPa vs preview p_max {case.preview.p_max_mpa:.0f} MPa"
                   + (": the peak is an edge spike of rigid teeth, not a Hertzian pressure"
                      if spike else ""))
    elif p.edge_sides:
        out.append(f"{at}: the loaded contact reaches the edge of the gap field at "
                   f"{', '.join(p.edge_sides)}: enlarge the field")
    return out   # a grid too coarse is a Python warning of the solver (printed by main)


def lte_warnings(lte) -> list[str]:
    """What a user must see about a loaded TE (:class:`~gearcontact.ltca.lte.LoadedTE`),
    one line each: the phases with edge contact."""
    edge = [int(k) for k in lte.edge_contact.nonzero()[0]]
    if not edge:
        return []
    runs, start = [], edge[0]
    for a, b in zip(edge, edge[1:] + [None]):
        if b != a + 1:                      # close a run of consecutive phases
            runs.append(f"{start}" if start == a else f"{start}-{a}")
            start = b
    return [f"loaded TE at {lte.torque_nm:g} N·m: edge contact (load beyond the flank "
            f"boundary) at {len(edge)} of {len(lte.edge_contact)} phases "
            f"({', '.join(runs)})"]


def record_completed_settings(args, checked) -> None:
    """run.json's ``easeoff_shape`` (and its timings) from the settings check ``checked``
    as ``prepare_pair`` completed it (a generated gear's pinions measured on the
    generation check's gear boxes,
    :func:`~gearcontact.geometry.settings_check.completed_settings`); nothing where it is
    the argument check's own (``args.settings_check``) or None."""
    from ..report.design_mean_point import easeoff_shape_json

    if checked is None or checked is getattr(args, "settings_check", None):
        return
    args.settings_check = checked
    run = getattr(args, "run", None)
    if run is None or checked.easeoff is None:
        return
    run.input_checks["easeoff_shape"] = easeoff_shape_json(checked.easeoff)
    run.timings_s.update(blank_check_s=checked.seconds,
                         easeoff_shape_s=checked.easeoff.seconds)


def run_timings(args, **timings) -> None:
    """Record stage timings of this run for run.json (ignored outside a run)."""
    run = getattr(args, "run", None)
    if run is not None:
        run.timings_s.update(timings)


def warn(command: str, message: str) -> None:
    """A warning the user must see: one line on stderr."""
    print(f"gearcontact {command}: warning: {message}", file=sys.stderr)


def load_pair_for(args, *, mesh_follows: bool = True):
    """The pair of ``--pair`` (loaded by :func:`check_pair_arguments`) prepared by
    :func:`gearcontact.tca.synthesis.prepare_pair`, the one preparation of every command
    that takes ``--pair``: if the pair file has no ease-off table for ``args.side``
    (default the design side), the synthesized one (the note printed, the synthesis
    time into run.json; its TOML block into ``easeoff.toml`` in ``--out``, named by the
    note's line on stdout, as ``analyze`` names summary.md). A pair ``design`` refuses is
    refused there, before any flank work; the typed-settings check run by
    :func:`check_machine_settings` is not run again; a generated gear's pinion ease-off,
    measured there on the generation check's gear boxes, replaces run.json's
    ``easeoff_shape``. ``mesh_follows``: as ``prepare_pair``'s (False for a command that
    runs no TCA of the pair). The
    :class:`~gearcontact.tca.synthesis.PreparedPair` is kept as ``args.prepared_pair``."""
    from ..tca.synthesis import prepare_pair

    if getattr(args, "gear_pair", None) is None:
        check_pair_arguments(args)
    prepared = args.prepared_pair = prepare_pair(
        args.gear_pair, side=getattr(args, "side", None),
        settings_check=getattr(args, "settings_check", None), mesh_follows=mesh_follows)
    record_completed_settings(args, prepared.settings_check)
    if prepared.note:
        from ..report.design import write_easeoff_toml

        head, _, block = prepared.note.partition("\n")
        path = write_easeoff_toml(block, args.out)
        print(f"{head.rstrip(':')} (the TOML block is in {final_path(args, path)})")
    run_timings(args, **prepared.timings_s)
    return prepared.pair
