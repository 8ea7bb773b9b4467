"""The candidate choice of the local synthesis of the pinion settings
(:func:`~.setting_synthesis.synthesized_machine_pair`; docs/machine_settings.md sec. 5,
"The pivot's depth", "The bearing's room", "The candidate choice for a point-contact
base" and "The print's drive bearing"): which further syntheses of
one side are tried after the one about the mean node, in which order, each on which
problem with which targets, and which of them is kept (the rules of each candidate:
:mod:`.setting_pivot`; the kept pair of both sides cuttable:
:func:`~.setting_pivot.cuttable_choice`).

The synthesis of one candidate is passed in (``synthesize``:
:func:`~.setting_synthesis.synthesize_settings`), so that this module does not import the
synthesis, which imports the choice.
"""

from __future__ import annotations

import dataclasses

from ..errors import CheckFailed
from ..geometry.formate import SIDES
from ..geometry.settings_top_land import check_settings_top_land
from ..validation import InputRangeError
from .setting_pivot import (cuttable_choice, length_targets, pivot_rank, room_pivot,
                            room_targets, run_pivot, turned_path_targets)
from .setting_problem import SynthesisProblem
from .types import EdgeContact

__all__ = ["pivot_candidates"]


def pivot_candidates(pair, done, targets, sides, options, bearing_room, *, node, problem,
                     synthesize):
    """``done`` (the syntheses of ``sides`` about the mean node, the problem ``node``)
    against the other pivots of a line-contact base (:mod:`.setting_pivot`;
    docs/machine_settings.md sec. 5, "The pivot's depth" and "The bearing's room"; a
    point-contact base, "The candidate choice for a point-contact base": no centre, the
    room at its M on its path, the run's pivot on its path),
    each side's best by :func:`~.setting_pivot.better_pivot`: the working depth's
    centre; with ``bearing_room``, in turn, the centre with the ellipse no longer than
    the contact line's room there (:func:`~.setting_pivot.room_targets`), the pivot
    moved to the middle of the best one's pattern run
    (:func:`~.setting_pivot.run_pivot`), and the best one's pivot with the ellipse
    shortened for a run of one pitch (:func:`~.setting_pivot.length_targets`), each
    where it applies. ``problem``: the :class:`SynthesisProblem` options;
    ``synthesize``: the synthesis of one candidate
    (:func:`~.setting_synthesis.synthesize_settings`'s signature), ``options`` passed to
    it."""
    per_side = targets if isinstance(targets, dict) else dict.fromkeys(sides, targets)
    # side -> [(result, its targets, its problem)]
    cands = {s: [(done[s], per_side[s], node)] for s in sides}
    failed = {s: [] for s in sides}     # the candidates without contact at their M

    def add(prob, tg, note=""):
        """Synthesize the sides of ``tg`` ({side: targets}) on ``prob``; a side without
        contact at its M is left out (its candidate not tried)."""
        for s, t in tg.items():
            said = note.format(length=t.pattern_length_ratio * pair.gear_face_width_mm)
            try:
                r = synthesize(pair, targets={s: t}, problem=prob, sides=(s,),
                                        **options)[s]
            except CheckFailed as exc:
                failed[s].append(f"{prob.pivot.get(s, 'a pivot off the flank')}{said}: "
                                 f"not synthesized ({exc})")
                continue
            cands[s].append((dataclasses.replace(r, pivot=r.pivot + said), t, prob))

    def best(s):
        return min(cands[s], key=lambda c: pivot_rank(c[0]))

    def moved_to(s, uv):
        """The problem with the pivot of ``s`` at the flank point ``uv`` (None for no
        point, or no contact there)."""
        try:
            return None if uv is None else SynthesisProblem(pair, **problem,
                                                            pivot_uv={s: uv})
        except (CheckFailed, EdgeContact, ArithmeticError):    # no contact there
            return None

    if node.point_contact:      # the pivot stays on the base's path: no centred one
        centred = node
        room_words = "its room along its major axis at M"
    else:
        centred = SynthesisProblem(pair, **problem, pivot_depth={
            s: per_side[s].centre_profile for s in sides})
        add(centred, per_side)
        room_words = "the contact line's room there"
    if bearing_room:
        face = pair.gear_face_width_mm
        # the bearing's room: the ellipse no longer than the contact line's room there
        # (a point contact's: along the ellipse's major axis at M)
        short = {s: room_targets(per_side[s], room_mm=centred.line_room_mm(
            s, centred.standard[s]), face_mm=face) for s in sides}
        add(centred, {s: t for s, t in short.items() if t is not None},
            f", the paint ellipse's target shortened to {room_words}, {{length:.2f}} mm")
        # the pitch centred on the best one's pattern run
        moved = {s: (run_pivot(best(s)[0]), best(s)) for s in sides}
        moved = {s: m for s, m in moved.items() if m[0] is not None}
        if moved:
            try:
                prob = SynthesisProblem(pair, **problem, pivot_uv={
                    s: uv for s, (uv, _) in moved.items()})
            except (CheckFailed, EdgeContact, ArithmeticError):    # no contact there
                prob = None
            for s, (uv, (r, t, _)) in moved.items():
                if prob is not None:
                    add(prob, {s: t}, ", the middle of the pattern run of the pivot at "
                        + r.pivot.replace("{", "{{").replace("}", "}}"))
        # the bearing's length from the path: the best one's run made a pitch long
        for s in sides:
            r, t, prob = best(s)
            t_len = length_targets(t, r, face_mm=face)
            if t_len is not None:
                add(prob, {s: t_len}, ", the paint ellipse's target shortened for a "
                    "pattern run of one pitch, {length:.2f} mm")
        # a point-contact base's pivot moved along its path to the ellipse's room and
        # its depth travel over half a pitch (lever 5 with its margin)
        for s in sides:
            r, t, prob = best(s)
            moved_prob = moved_to(s, room_pivot(r, t, prob, side=s))
            if moved_prob is not None:
                add(moved_prob, {s: t}, ", moved along the base's path to where its room "
                    "holds half the paint ellipse, {length:.2f} mm, and its depth travel "
                    "over half a pitch")
        # the best one's path at M turned towards lengthwise (a reach refusal: not tried)
        for s in sides:
            r, t, prob = best(s)
            t_turn = turned_path_targets(r, t, prob)
            try:
                if t_turn is not None:
                    add(prob, {s: t_turn}, f", its path at M turned towards lengthwise to "
                        f"{t_turn.path_angle_deg:.1f} deg")
            except InputRangeError as exc:
                failed[s].append(f"{prob.pivot[s]}, its path at M turned to "
                                 f"{t_turn.path_angle_deg:.1f} deg: not synthesized ({exc})")
    gear = {s: node.gear_setups[s] for s in SIDES}

    def pointed(pick):
        """The readers' refusal of the pinion tooth ``pick`` cuts ("" if none)."""
        pinion = {s: r.setup for s, r in pick.items()}
        if set(pinion) != set(SIDES):   # one side synthesized: its tooth not checked here
            return ""
        try:
            check_settings_top_land(dataclasses.replace(pair, machine=tuple(
                gear[s] for s in SIDES) + tuple(pinion[s] for s in SIDES)))
        except InputRangeError as exc:
            return str(exc.value)
        return ""

    out = cuttable_choice({s: [c[0] for c in cands[s]] for s in sides}, pointed=pointed)
    return {s: dataclasses.replace(r, other_pivot="; ".join(
        t for t in (r.other_pivot, *failed[s]) if t)) for s, r in out.items()}
