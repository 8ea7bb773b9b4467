"""The top land of a pinion cut from machine settings, along its tip line.

The settings-pair counterpart of :func:`~.generation.check_pinion_top_land` (which
measures the conjugate pinion of a pair without settings): the pinion flanks are the
envelopes the settings generate (:class:`~.generated.EnvelopeSolver`, exact node solves,
no node grid). At :data:`~.tip_land.TIP_STATIONS` lengthwise stations of each flank's
active box (:func:`~.generated.generated_pinion_box`) the node solutions are continued
from the mean node to the tip line, all stations at once (``_FAN_STEPS`` steps on the
straight lines in (u, v); the box's fold check, :func:`~.generated_box.check_tip_margin`,
has found the envelope regular up to the tip over the face); the normal top land
between the two flanks is measured as for the conjugate pinion
(:func:`~.tip_land.tip_land_mm`). A relieved blade's flank near the tip is the deepest
of its segments' smooth envelopes (each relief removes material beyond its kink,
:func:`~.blade.blade_segments`): the smallest land over the segments is taken.

A pointed tooth is refused (:func:`check_settings_top_land`): standard settings of a
narrow face get a pinion cutter radius from the standard lengthwise crowning that turns
a flank into the tooth (docs/machine_settings.md sec. 5, "A fold at the tip" and "A
pointed tooth from settings").
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..validation import InputRangeError
from .blade import blade_segments
from .generated import EnvelopeSolver, generated_pinion_box
from .tip_land import TIP_STATIONS, X_AXIS, one_tooth_turn, tip_land_mm

__all__ = ["check_settings_top_land", "settings_tip_top_lands"]

#: Continuation steps from the mean node to the tip line, all stations at once (each
#: station moves on the straight line to it in (u, v): steps of 1/16 of the half face
#: and of the addendum, inside Newton's convergence radius as the node grid's columns).
_FAN_STEPS = 16


def settings_tip_top_lands(pair, *, boxes: dict | None = None
                           ) -> tuple[np.ndarray, np.ndarray]:
    """Normal top land of the pinion tooth cut from ``pair``'s machine settings along
    its tip line (module docstring).

    Parameters
    ----------
    pair : GearPair
        A right-hand pair with ``pair.machine`` (a left-hand pair's right-hand twin,
        :func:`~.flank.right_hand_twin`, its mirror image: the callers hold it).
    boxes : dict, optional
        ``{side: {"active_box": FlankBoundary, "solver": EnvelopeSolver, "mean_node":
        EnvelopeSolution}}`` of the pinion flanks (``generation._machine_boxes``);
        made by :func:`~.generated.generated_pinion_box` when omitted.

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
    setups = _pinion_setups(pair)
    boxes = _pinion_boxes(pair) if boxes is None else boxes
    frac = np.linspace(0.0, 1.0, TIP_STATIONS)
    u_tip = min(got["active_box"].u_tip for got in boxes.values())
    v_m = float(pair.blank.pitch_point_mm[0])
    mid, tips = {}, {}
    for side in ("drive", "coast"):
        solver, box = boxes[side]["solver"], boxes[side]["active_box"]
        mean = boxes[side]["mean_node"]
        u_m = float(solver.cone.root_offset_mm)
        vs = box.v_toe + frac * (box.v_heel - box.v_toe)
        mid[side] = (mean.x_mm, mean.n)
        tips[side] = []
        for seg in blade_segments(setups[side].blade):
            # a smooth blade's segment is the box solver's own blade (no extra solve)
            seg_solver = solver if len(blade_segments(setups[side].blade)) == 1 else \
                EnvelopeSolver(dataclasses.replace(setups[side], blade=seg.blade),
                               pair.blank, solver.cone)
            q = np.broadcast_to(seg_solver.solve(u_m, v_m, mean.q).q, vs.shape + (3,))
            # every station at once, on the straight line from the mean node to it
            for t in np.linspace(0.0, 1.0, _FAN_STEPS + 1)[1:]:
                s = seg_solver.solve(np.full_like(vs, u_m + t * (u_tip - u_m)),
                                     v_m + t * (vs - v_m), q)
                q = s.q
            tips[side].append((s.x_mm, s.n))
    turn = one_tooth_turn(*mid["drive"], *mid["coast"], axis=X_AXIS, teeth=pair.pinion_teeth)
    if turn is None:
        raise InputRangeError(
            _FIELD, tuple(setups[side].blade.point_radius_mm for side in ("drive", "coast")),
            "a pinion tooth between the drive and coast flanks at the mean point (the "
            "settings cut a slot wider than the pitch)")
    land = np.min([tip_land_mm(rd, nd, rc, turn)
                   for rd, nd in tips["drive"] for rc, _ in tips["coast"]], axis=0)
    return frac, land


def check_settings_top_land(pair, *, boxes: dict | None = None) -> float:
    """Smallest normal top land of the pinion tooth cut from ``pair``'s machine settings,
    mm (:func:`settings_tip_top_lands`); refuses a tooth pointed anywhere along the face
    (a top land <= 0, the bound of :func:`~.generation.check_pinion_top_land`).
    ``pair``, ``boxes``: as :func:`settings_tip_top_lands`' (a right-hand pair).

    Raises
    ------
    InputRangeError
        Naming both pinion flanks' settings and blade point radii, where along the face
        (toe / heel, v in mm, as a fraction of the face) and the top land there, with
        the fixes measured for standard settings (a smaller lengthwise crowning, a wider
        face: docs/machine_settings.md sec. 5).
    """
    boxes = _pinion_boxes(pair) if boxes is None else boxes
    frac, land = settings_tip_top_lands(pair, boxes=boxes)
    worst = int(np.argmin(land))
    if land[worst] > 0.0:
        return float(land[worst])
    pointed = frac[land <= 0.0]
    box = boxes["drive"]["active_box"]
    v_txt = (f", v = {box.v_toe + frac[worst] * (box.v_heel - box.v_toe):.4f} mm (the drive "
             f"box is v = [{box.v_toe:.4f}, {box.v_heel:.4f}] mm)")
    setups = _pinion_setups(pair)
    raise InputRangeError(
        f"{_FIELD} (blade point radii {setups['drive'].blade.point_radius_mm:.4g} / "
        f"{setups['coast'].blade.point_radius_mm:.4g} mm)",
        f"a pointed pinion tooth at the {'toe' if frac[worst] < 0.5 else 'heel'}: the normal "
        f"top land along the tip line is {land[worst]:.4g} mm at {frac[worst]:.3f} of the "
        f"face{v_txt} (<= 0 from {pointed[0]:.3f} to {pointed[-1]:.3f} of the face: the "
        "two flanks cross below the tip)",
        "a pinion top land > 0 mm along the whole tip line" + _STANDARD_HINT)


#: What removes a pointed pinion tooth cut with standard settings (measured,
#: docs/machine_settings.md sec. 5, "A pointed tooth from settings").
_STANDARD_HINT = (
    ". Standard settings (`design --machine-settings`) of a narrow face "
    "(design.gear_face_width_mm) get such a pinion from the standard lengthwise crowning "
    "(a pinion cutter radius far from the gear's): less crowning (--lengthwise-crowning-um) "
    "or a wider face removes it; "
    'docs/machine_settings.md sec. 5, "A pointed tooth from settings"')


#: The settings a pointed tooth names (both flanks bound the tooth).
_FIELD = "[machine.pinion.drive] / [machine.pinion.coast]"


def _pinion_setups(pair) -> dict:
    """``{side: MachineSetup}`` of the pinion of ``pair``."""
    return {s.side: s for s in pair.machine if s.member == "pinion"}


def _pinion_boxes(pair) -> dict:
    """The ``boxes`` of :func:`settings_tip_top_lands` made by
    :func:`~.generated.generated_pinion_box` (what ``generation._machine_boxes`` keeps)."""
    out = {}
    for side, setup in _pinion_setups(pair).items():
        solver, box, mean = generated_pinion_box(
            setup, pair.blank, pinion_face_width_mm=pair.pinion_face_width_mm)
        out[side] = {"active_box": box, "solver": solver, "mean_node": mean}
    return out
