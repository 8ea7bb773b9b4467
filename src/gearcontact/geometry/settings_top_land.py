"""The top land of a member cut from machine settings, along its tip line.

The settings-pair counterpart of :func:`~.generation.check_pinion_top_land` (which
measures the conjugate pinion of a pair without settings) and of
:func:`~.generation.check_gear_top_land`: a generated flank is the envelope the settings
generate (:class:`~.generated.EnvelopeSolver`, exact node solves, no node grid); a
formate gear flank is its blade cone (:func:`~.generated.formate_gear_flank`, evaluated
on the tip line as :func:`~.generation.gear_tip_top_lands` evaluates it). At
:data:`~.tip_land.TIP_STATIONS` lengthwise stations of each generated flank's active box
(:func:`~.generated.generated_pinion_box`, :func:`~.generated.generated_gear_box`) the
node solutions are continued
from the mean node to the tip line, all stations at once (``_FAN_STEPS`` steps on the
straight lines in (u, v); the box's fold check, :func:`~.generated_box.check_tip_margin`,
has found the envelope regular up to the tip over the face); the normal top land
between the two flanks is measured as for the conjugate pinion
(:func:`~.tip_land.tip_land_mm`). A relieved blade's flank near the tip is the deepest
of its segments' smooth envelopes (each relief removes material beyond its kink,
:func:`~.blade.blade_segments`): the smallest land over the segments is taken.

A pointed tooth is refused (:func:`check_settings_top_land`): standard settings of a
narrow face get a pinion cutter radius from the standard lengthwise crowning that turns
a pinion flank into the tooth (docs/machine_settings.md sec. 5, "A fold at the tip" and "A
pointed tooth from settings").
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..validation import InputRangeError
from .blade import blade_segments
from .generated import (EnvelopeSolver, formate_gear_flank, generated_gear_box,
                        generated_pinion_box, mean_uv)
from .tip_land import (TIP_STATIONS, X_AXIS, Z_AXIS, flank_mid, flank_tip_line, one_tooth_turn,
                       tip_land_mm)

__all__ = ["check_settings_top_land", "member_box", "member_boxes", "settings_tip_top_lands"]

#: Continuation steps from the mean node to the tip line, all stations at once (each
#: station moves on the straight line to it in (u, v): steps of 1/16 of the half face
#: and of the addendum, inside Newton's convergence radius as the node grid's columns).
_FAN_STEPS = 16


def settings_tip_top_lands(pair, *, member: str = "pinion", boxes: dict | None = None
                           ) -> tuple[np.ndarray, np.ndarray]:
    """Normal top land of the ``member`` tooth cut from ``pair``'s machine settings along
    its tip line (module docstring).

    Parameters
    ----------
    pair : GearPair
        A right-hand pair with ``pair.machine`` (a left-hand pair's right-hand twin,
        :func:`~.flank.right_hand_twin`, its mirror image: the callers hold it).
    member : {"pinion", "gear"}
    boxes : dict, optional
        :func:`member_boxes` of ``member`` (``generation._machine_boxes`` keeps them);
        made when omitted.

    Returns
    -------
    frac : ndarray (TIP_STATIONS,)
        Fraction of each flank's lengthwise range, 0 (toe) .. 1 (heel).
    land_mm : ndarray (TIP_STATIONS,)
        Top land, mm (negative where the flanks cross below the tip).
    """
    if pair.pinion_hand != "right":
        raise ValueError("settings_tip_top_lands measures a right-hand pair (pass "
                         "flank.right_hand_twin(pair))")
    setups = _setups(pair, member)
    boxes = member_boxes(pair, member) if boxes is None else boxes
    frac = np.linspace(0.0, 1.0, TIP_STATIONS)
    u_tip = min(got["gear_flank"].u_range[1] if "gear_flank" in got else got["active_box"].u_tip
                for got in boxes.values())
    mid, tips = {}, {}
    for side in ("drive", "coast"):
        got = boxes[side]
        if "gear_flank" in got:      # a formate gear flank: its blade cone
            mid[side] = flank_mid(got["gear_flank"])
            tips[side] = [flank_tip_line(got["gear_flank"], frac, u_tip)]
            continue
        solver, box, mean = got["solver"], got["active_box"], got["mean_node"]
        u_m, v_m = mean_uv(solver.setup, pair.blank, solver.cone)
        vs = box.v_toe + frac * (box.v_heel - box.v_toe)
        mid[side] = (mean.x_mm, mean.n)
        segments = blade_segments(setups[side].blade)
        tips[side] = []
        for seg in segments:
            # a smooth blade's segment is the box solver's own blade (no extra solve)
            seg_solver = solver if len(segments) == 1 else EnvelopeSolver(
                dataclasses.replace(setups[side], blade=seg.blade), pair.blank, solver.cone)
            q = np.broadcast_to(seg_solver.solve(u_m, v_m, mean.q).q, vs.shape + (3,))
            # every station at once, on the straight line from the mean node to it
            for t in np.linspace(0.0, 1.0, _FAN_STEPS + 1)[1:]:
                s = seg_solver.solve(np.full_like(vs, u_m + t * (u_tip - u_m)),
                                     v_m + t * (vs - v_m), q)
                q = s.q
            tips[side].append((s.x_mm, s.n))
    axis, teeth = (X_AXIS, pair.pinion_teeth) if member == "pinion" else (Z_AXIS, pair.gear_teeth)
    turn = one_tooth_turn(*mid["drive"], *mid["coast"], axis=axis, teeth=teeth)
    if turn is None:
        raise InputRangeError(
            _field(member), tuple(setups[side].blade.point_radius_mm for side in ("drive", "coast")),
            f"a {member} tooth between the drive and coast flanks at the mean point (the "
            "settings cut a slot wider than the pitch)")
    land = np.min([tip_land_mm(rd, nd, rc, turn)
                   for rd, nd in tips["drive"] for rc, _ in tips["coast"]], axis=0)
    return frac, land


def check_settings_top_land(pair, *, member: str = "pinion", boxes: dict | None = None
                            ) -> float:
    """Smallest normal top land of the ``member`` tooth cut from ``pair``'s machine
    settings, mm (:func:`settings_tip_top_lands`); refuses a tooth pointed anywhere along
    the face (a top land <= 0, the bound of :func:`~.generation.check_pinion_top_land`
    and :func:`~.generation.check_gear_top_land`). ``pair``, ``member``, ``boxes``: as
    :func:`settings_tip_top_lands`' (a right-hand pair).

    Raises
    ------
    InputRangeError
        Naming both flanks' settings and blade point radii, where along the face
        (toe / heel, as a fraction of the face and v in mm) and the top land there; a
        pinion: the fixes measured for standard settings (a smaller lengthwise crowning,
        a wider face: docs/machine_settings.md sec. 5); a gear: a narrower slot.
    """
    boxes = member_boxes(pair, member) if boxes is None else boxes
    frac, land = settings_tip_top_lands(pair, member=member, boxes=boxes)
    worst = int(np.argmin(land))
    if land[worst] > 0.0:
        return float(land[worst])
    pointed = frac[land <= 0.0]
    got = boxes["drive"]
    v0, v1 = got["gear_flank"].v_range if "gear_flank" in got else (
        got["active_box"].v_toe, got["active_box"].v_heel)
    setups = _setups(pair, member)
    raise InputRangeError(
        f"{_field(member)} (blade point radii {setups['drive'].blade.point_radius_mm:.4g} / "
        f"{setups['coast'].blade.point_radius_mm:.4g} mm)",
        f"a pointed {member} tooth at the {'toe' if frac[worst] < 0.5 else 'heel'}: the "
        f"normal top land along the tip line is {land[worst]:.4g} mm at {frac[worst]:.3f} of "
        f"the face, v = {v0 + frac[worst] * (v1 - v0):.4f} mm (the drive flank's is v = "
        f"[{v0:.4f}, {v1:.4f}] mm) (<= 0 from {pointed[0]:.3f} to {pointed[-1]:.3f} of the "
        "face: the two flanks cross below the tip)",
        f"a {member} top land > 0 mm along the whole tip line" + _HINT[member])


#: What removes a pointed tooth: a pinion cut with standard settings (measured,
#: docs/machine_settings.md sec. 5, "A pointed tooth from settings"); a gear's slot.
_HINT = {
    "pinion": (
        ". Typed settings that do not agree with the blank cut one too (a warning "
        "above then names the flank and a likely slip, e.g. a sliding base's WITH / AWAY). "
        "Standard settings (`design --machine-settings`) of a narrow face "
        "(design.gear_face_width_mm) get such a pinion from the standard lengthwise crowning "
        "(a pinion cutter radius far from the gear's): less crowning (--lengthwise-crowning-um) "
        "or a wider face removes it; "
        'docs/machine_settings.md sec. 5, "A pointed tooth from settings"'),
    "gear": (
        " (a narrower gear slot: the gear blades' point radii closer together; the standard "
        "settings' gear is the blank's, whose top land `design` checks on the blank: "
        'cutter.point_width_mm); docs/machine_settings.md sec. 5, "A pointed tooth from '
        'settings"'),
}


def _field(member: str) -> str:
    """The settings a pointed tooth names (both flanks bound the tooth)."""
    return f"[machine.{member}.drive] / [machine.{member}.coast]"


def _setups(pair, member: str) -> dict:
    """``{side: MachineSetup}`` of ``member`` of ``pair``."""
    return {s.side: s for s in pair.machine if s.member == member}


def member_boxes(pair, member: str) -> dict:
    """The ``boxes`` of :func:`settings_tip_top_lands`: per side, :func:`member_box` of
    ``member``'s setup."""
    return {side: member_box(pair, setup) for side, setup in _setups(pair, member).items()}


def member_box(pair, setup) -> dict:
    """``{"active_box": FlankBoundary, "solver": EnvelopeSolver, "mean_node":
    EnvelopeSolution}`` of a generated flank of ``pair`` cut by ``setup``
    (:func:`~.generated.generated_pinion_box`, :func:`~.generated.generated_gear_box`,
    which check it), ``{"gear_flank": FormateFlank}`` of a formate gear flank
    (:func:`~.generated.formate_gear_flank`)."""
    if setup.member == "pinion":
        got = generated_pinion_box(setup, pair.blank,
                                   pinion_face_width_mm=pair.pinion_face_width_mm)
    elif setup.settings.formate:
        return {"gear_flank": formate_gear_flank(setup, pair.blank,
                                                 gear_face_width_mm=pair.gear_face_width_mm)}
    else:
        got = generated_gear_box(setup, pair.blank, gear_face_width_mm=pair.gear_face_width_mm)
    return dict(zip(("solver", "active_box", "mean_node"), got))
