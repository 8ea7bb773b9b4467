"""The choice of the pivot M of the local synthesis of the pinion settings
(:func:`~.setting_synthesis.synthesized_machine_pair`; docs/machine_settings.md sec. 5,
"The pivot's depth" and "The bearing's room"): which of several syntheses of one side to
keep, and the further candidates' targets and pivots read from a synthesis' full TCA.

A line-contact base pinion may pivot on any flank point (every one lies on a contact
line), so the synthesis is tried about a few and the one whose full TCA puts the paint
ellipse at a flank edge at the fewest phases is kept (:func:`better_pivot`). The
candidates beyond the mean node and the working depth's centre:

* the bearing's room (:func:`room_targets`): the paint ellipse no longer than the
  contact line's room at the centred pivot (its half chord across the flank);
* the pitch centred on the pattern run (:func:`run_pivot`): the pivot moved to the
  middle of the run of the path whose paint ellipse lies on both flanks
  (:class:`~.setting_problem.PatternRun`);
* the bearing's length from the path (:func:`length_targets`): where that run is
  shorter than a pitch, the ellipse shortened so that the run, to first order, reaches
  one pitch.

A point-contact base pinion (a hypoid's generated gear) pivots on its contact path only,
so it has no working depth's centre; the room is measured at its M, and the run's pivot
is the base path's point on the pinion section of the run's middle
(docs/machine_settings.md sec. 5, "The candidate choice for a point-contact base"); the
rank and the choice are the same. A point-contact base whose best candidate still
reaches an edge with its M closer to an edge than half its ellipse has one more
candidate (:func:`room_pivot`): the pivot moved along the base's path to the nearest
point whose room holds that half-length plus the contact's depth travel over half a
pitch along the ellipse's axis (docs/machine_settings.md sec. 5, lever 5 of "The
print's drive bearing" and its margin; :mod:`.setting_room_margin`), and one with its
path at M turned towards lengthwise (:func:`turned_path_targets`, lever 6).

The results are :class:`~.setting_synthesis.SettingSynthesis` (read here by their
``met``, ``edge_phases``, ``tca_te0_pp_arcsec``, ``edges``, ``pivot``, ``run``); this
module does not import it, so that the synthesis imports the choice.
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from .mating import solve_mating_point
from .setting_problem import PIVOT_MARGIN, line_room_mm, path_points_inside
from .setting_room_margin import axis_depth_rate, depth_rate_per_rad, room_margin_mm

__all__ = ["PATH_TURN_DEG", "better_pivot", "cuttable_choice", "length_targets", "pivot_rank", "room_need_mm", "room_pivot", "room_targets",
           "run_pivot", "turned_path_targets"]

#: Shortest paint-ellipse target of the further candidates (the
#: :class:`~.synthesis_targets.SynthesisTargets` range), over the gear face width.
_RATIO_MIN = 0.1
#: A pattern run's middle this close to M's phase (pinion pitches, one step of the
#: 31-phase check) moves no pivot.
_RUN_STEP_PITCH = 1.0 / 30.0
#: Turn of lever 6's path towards lengthwise, deg (docs/machine_settings.md sec. 5,
#: "The print's drive bearing": the step of the scan that gained on the print's drive,
#: 60.7 -> 30 deg).
PATH_TURN_DEG = 30.0


def pivot_rank(r):
    """The order of the choice: targets met first, then fewer edge phases, then the
    lower TE0 p-p."""
    return (not r.met, r.edge_phases, r.tca_te0_pp_arcsec)


def _check_text(r) -> str:
    """A candidate's full-TCA check as its kept rival's ``other_pivot`` names it."""
    return (f"{r.pivot}: paint ellipse at a flank edge at {r.edge_phases} of "
            f"{len(r.edges)} phases, full TCA TE0 p-p {r.tca_te0_pp_arcsec:.2f} arcsec"
            + ("" if r.met else ", targets missed"))


def cuttable_choice(candidates: dict, *, pointed) -> dict:
    """Per side, the candidate of ``candidates`` (``{side: [results]}``) kept by
    :func:`better_pivot`, unless the pinion tooth that the kept ones of both sides cut
    together is pointed or folds: ``pointed({side: result})`` gives the refusal's text,
    "" for a cuttable tooth (the readers' own check,
    :func:`~gearcontact.geometry.settings_top_land.check_settings_top_land`). Then the
    combinations are tried in the order of the summed rank (:func:`pivot_rank`: missed
    targets, edge phases, TE0 p-p over the sides; the first given on a tie) and the
    first cuttable one is kept, each side's result naming the others and
    why its better ones were passed over; where none is cuttable, the best, as
    :func:`better_pivot` (the readers then refuse the written file, naming the tooth)."""
    sides = tuple(candidates)
    combos = sorted(itertools.product(*(range(len(candidates[s])) for s in sides)),
                    key=lambda ix: tuple(sum(v) for v in zip(*(
                        pivot_rank(candidates[s][i]) for s, i in zip(sides, ix)))))
    why = ""
    for ix in combos:
        pick = {s: candidates[s][i] for s, i in zip(sides, ix)}
        said = pointed(pick)
        if not said:
            break
        why = why or said
    else:
        return {s: better_pivot(*candidates[s]) for s in sides}
    out = {}
    for s in sides:
        kept = pick[s]
        rest = [c for c in candidates[s] if c is not kept]
        note = "; ".join(_check_text(c) for c in rest)
        if any(pivot_rank(c) < pivot_rank(kept) for c in rest):
            note += (f"; the better ones passed over: with the other side's they cut a "
                     f"pinion tooth the readers refuse ({why})")
        out[s] = dataclasses.replace(kept, other_pivot=note)
    return out


def better_pivot(*results):
    """Of syntheses of one side at several pivots, the one whose full TCA has the fewest
    phases with the paint ellipse at a flank edge (a tie: the lower TE0 p-p, then the
    first given; a result missing a target loses to one meeting them), the others'
    checks named in its ``other_pivot``, in the order given."""
    keep = min(results, key=pivot_rank)
    return dataclasses.replace(keep, other_pivot="; ".join(
        _check_text(drop) for drop in results if drop is not keep))


def _shortened(targets, length_mm: float, face_mm: float):
    """``targets`` with the paint ellipse 2a = ``length_mm`` where that is shorter than
    its own and not below :data:`_RATIO_MIN` of the face; None otherwise (never
    clipped)."""
    if not length_mm < targets.pattern_length_ratio * face_mm or \
            length_mm < _RATIO_MIN * face_mm:
        return None
    return dataclasses.replace(targets, pattern_length_ratio=length_mm / face_mm)


def room_targets(targets, *, room_mm: float, face_mm: float):
    """``targets`` (:class:`~.synthesis_targets.SynthesisTargets`) with the paint
    ellipse's length set to the contact line's room ``room_mm``
    (:func:`~.setting_problem.line_room_mm` at the centred pivot) where the target,
    ``pattern_length_ratio`` of the gear face ``face_mm``, exceeds it; None where it
    does not, or where the room is below the shortest target (:data:`_RATIO_MIN` of the
    face: the candidate is not tried)."""
    return _shortened(targets, room_mm, face_mm)


def run_pivot(result):
    """The pinion flank point (u, v), mm, of the middle of ``result``'s pattern run
    (:class:`~.setting_problem.PatternRun`), rounded to 1e-6 mm (the head comment
    names it to that digit, so that the pivot can be rebuilt from it), where ``result``
    has edge phases and the run's middle is off M's phase by more than
    :data:`_RUN_STEP_PITCH`; None otherwise (a run of length 0 has no middle)."""
    run = result.run
    if not result.edge_phases or run is None or \
            not abs(run.middle_offset_pitch) > _RUN_STEP_PITCH:
        return None
    return tuple(round(float(t), 6) for t in run.middle_uv)


def length_targets(targets, result, *, face_mm: float):
    """``targets`` (those ``result`` was synthesized to) with the paint ellipse
    shortened so that ``result``'s pattern run would reach one pitch, where ``result``
    has edge phases and its run is shorter than a pitch within a path on the flank
    longer than one: the ellipse takes ``P - R`` pitches of the path of ``P`` (the
    surface contact's run, :attr:`~.setting_problem.PatternRun.path_pitches`) to leave
    a run of ``R``; to first order in the length that share scales with it, so
    ``2a' = 2a (P - 1) / (P - R)``; a path whose ellipse is at an edge at every phase is
    a run of ``R = 0`` (docs/machine_settings.md sec. 5, lever 4 of "The candidate
    choice for a point-contact base"). None otherwise, or below :data:`_RATIO_MIN` of
    the face."""
    run = result.run
    if not result.edge_phases or run is None or not run.pitches < 1.0 < run.path_pitches:
        return None
    length = targets.pattern_length_ratio * face_mm
    return _shortened(targets, length * (run.path_pitches - 1.0)
                      / (run.path_pitches - run.pitches), face_mm)


def room_pivot(result, targets, problem, *, side: str):
    """Lever 5 of "The print's drive bearing" (docs/machine_settings.md sec. 5, with
    session 28's margin): the pinion flank point (u, v), mm (rounded to 1e-6 mm, as
    :func:`run_pivot`), of the point-contact base's contact path to which ``result``'s
    pivot moves, or None where the lever does not apply.

    It applies where ``problem`` (the :class:`~.setting_problem.SynthesisProblem`
    ``result`` was synthesized on, to ``targets``) has a point-contact base, the
    targets leave the path angle free, ``result`` has edge phases and the room at its M
    (:func:`~.setting_problem.line_room_mm` along the major axis of the base pair's own
    contact ellipse, the uncrowned base pinion) is less than half the target ellipse
    ``a`` plus the margin ``m`` (:func:`room_need_mm`); then the point is the sampled
    point of the base's path (:func:`~.setting_problem.path_points_inside`, inside the
    flank box by :data:`~.setting_problem.PIVOT_MARGIN`) nearest M in phase whose room
    (measured the same way) is at least ``a + m``; where no sampled point has it, the
    sampled point of the widest room (the nearest in phase of equal ones), where that
    room is wider than M's and holds ``a`` (the depth then leaves the contact's travel
    less than ``m``: the most it allows); None otherwise, or where ``result``'s contact
    leaves a flank within two local steps of M (no margin)."""
    if not _free_point_contact_at_edge(result, targets, problem):
        return None
    pinion, gear = problem.flank(side, np.zeros(3)), problem.gear[side]
    kin = problem.pair.kinematics()
    at_m = solve_mating_point(pinion, gear, kin, problem.start[side])
    try:
        need = room_need_mm(result, targets, problem, side=side, at_m=at_m)
    except ArithmeticError:
        return None
    room_m = line_room_mm(pinion, gear, kin, at_m)
    if not room_m < need:
        return None
    points = path_points_inside(pinion, gear, problem.pair, problem.start[side],
                                margin=PIVOT_MARGIN)
    widest, widest_room = None, room_m
    for p in sorted(points, key=lambda p: (abs(p.phi1_rad - at_m.phi1_rad), p.phi1_rad)):
        room = line_room_mm(pinion, gear, kin, p)
        if room >= need:
            return (round(float(p.u1), 6), round(float(p.v1), 6))
        if room > widest_room:
            widest, widest_room = p, room
    # none holds a + m: the widest room, where it holds a and is wider than M's
    half = 0.5 * targets.pattern_length_ratio * problem.pair.gear_face_width_mm
    if widest is None or not widest_room >= half:
        return None
    return (round(float(widest.u1), 6), round(float(widest.v1), 6))


def room_need_mm(result, targets, problem, *, side: str, at_m) -> float:
    """The room lever 5 asks of a pivot, mm: half the target ellipse,
    ``a = pattern_length_ratio x face / 2``, plus the margin
    :func:`~.setting_room_margin.room_margin_mm` of ``result``'s depth travel over half
    a pitch (its synthesized pinion's path at M, ``problem.start[side]``) along the base
    ellipse's major axis at M (``at_m``, the uncrowned base's contact there).

    Raises
    ------
    ArithmeticError
        ``result``'s contact leaves a flank within two local steps of M.
    """
    pair = problem.pair
    gear = problem.gear[side]
    margin = room_margin_mm(
        depth_rate_per_rad=depth_rate_per_rad(problem.flank(side, result.x), gear, pair,
                                              problem.start[side]),
        axis_depth_rate_per_mm=axis_depth_rate(problem.flank(side, np.zeros(3)), gear,
                                               pair.kinematics(), at_m),
        pinion_teeth=pair.pinion_teeth)
    return 0.5 * targets.pattern_length_ratio * pair.gear_face_width_mm + margin


def _free_point_contact_at_edge(result, targets, problem) -> bool:
    """Levers 5 and 6 apply: a point-contact base, the path angle free, edge phases."""
    return bool(problem.point_contact and result.edge_phases
                and targets.path_angle_deg is None)


def turned_path_targets(result, targets, problem):
    """Lever 6 of "The print's drive bearing" (docs/machine_settings.md sec. 5):
    ``targets`` (those ``result`` was synthesized to on ``problem``) with the path angle
    prescribed at ``result``'s path angle at M turned towards lengthwise (0 deg) by
    :data:`PATH_TURN_DEG`, not past it: ``sign(a) max(|a| - 30, 0)``; the contact then
    moves less across the depth over the pitch. None where lever 5's conditions do not
    hold (:func:`room_pivot`) or the path is lengthwise already (within the targets'
    angle tolerance)."""
    if not _free_point_contact_at_edge(result, targets, problem):
        return None
    angle = float(result.point.path_angle_deg)
    if not abs(angle) > targets.tol_angle_deg:
        return None
    return dataclasses.replace(targets, path_angle_deg=_turned_deg(angle))


def _turned_deg(angle: float) -> float:
    """``angle`` turned towards lengthwise by :data:`PATH_TURN_DEG`, not past it."""
    return math.copysign(max(abs(angle) - PATH_TURN_DEG, 0.0), angle)
