"""Can the gear generate the pinion? The check ``design`` runs before any flank work.

:func:`check_generation` runs the cheap first step of the conjugate pinion generation
(:func:`~.conjugate.pinion_active_box`: the lines the gear tip and root generate, traced
on a few lengthwise sections, no node grid) on both flanks of a pair. A limit line that
leaves more than half the gear addendum without a conjugate partner is refused there
(:class:`~.conjugate.UndercutError`), naming a gear addendum factor that avoids it,
verified by running the check again with it, or the tooth numbers when none does
(docs/geometry.md sec. 7). It also refuses teeth that are pointed anywhere along the
face, the formate gear's (:func:`check_gear_top_land`) and the conjugate pinion's
(:func:`check_pinion_top_land`, tracing the pinion tip line with exact node solves):
ISO 23509's top-land check is made at the mean section only, and the toe is narrower.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..validation import InputRangeError
from .conjugate import UndercutError, section_guesses
from .contact_path import path_contact_ratio
from .contact_ratio import check_contact_ratio
from .easeoff import EaseOff
from .flank import right_hand_twin
from .gear_generation import pair_generation
from .pair import blank_key_error
from .settings_top_land import check_settings_top_land, member_box
from .tip_land import (TIP_MARCH, TIP_STATIONS, X_AXIS, Z_AXIS, flank_mid, flank_tip_line,
                       one_tooth_turn, tip_land_mm)

__all__ = ["check_gear_top_land", "check_generation", "check_pinion_top_land",
           "gear_tip_top_lands", "pinion_tip_top_lands", "reverse_side_contact_ratio"]


def check_generation(pair, *, contact_ratio: bool = True, bearing_of=None,
                     mesh_follows: bool = False) -> dict:
    """Check that the pinion flanks of ``pair`` can be generated, before any flank work.

    A pair cut from machine settings (``pair.machine``) is checked by
    :func:`_machine_boxes` instead (settings, blade kinds, the generated pinion's active
    box). Otherwise, in order: the gear generation (:func:`~.gear_generation.gear_generation`:
    the formate gear, or the generated gear where the formate gear undercuts its pinion)
    and :func:`~.conjugate.pinion_active_box` on both sides (no node grid) -- an undercut
    of the generated gear's pinion names a gear addendum factor that avoids it, verified
    here (the limit line moves slightly with the addenda: up to ``_FIX_TRIALS`` smaller
    values are tried); when none does, the tooth numbers are named; the gear top land
    along its tip line (:func:`check_gear_top_land`); the conjugate pinion's top land
    along its tip line (:func:`check_pinion_top_land`, verified fix). Last, unless
    ``contact_ratio=False``, the contact ratio of the design side's contact path inside
    the active boxes (:func:`~.contact_ratio.check_contact_ratio`; the ISO 10300-1
    closed form for a pair cut from machine settings: a pair whose unloaded mesh may
    have a gap is refused, naming the face width, the spiral angle or the teeth).
    ``bearing_of(pair, boxes)``: the ease-off the design side will carry where the pair's
    table does not say it (:class:`~.contact_path.Bearing` or None; the commands pass the
    synthesis' predicted bearing, ``tca.predicted_bearing``, geometry being below tca);
    without it a pair without a table is checked with the synthesis' first-order bearing
    at its default targets (:func:`~.contact_path.path_contact_ratio`). The blank whose
    machine settings ``design --machine-settings`` writes is checked with
    ``contact_ratio=False``: the settings' own TCA decides there
    (``tca.settings_gap``, docs/machine_settings.md sec. 5). ``mesh_follows``: the caller
    runs the pair's TCA next (``tca.synthesis.prepare_pair``), which refuses a mesh with
    a gap, so a pair cut from settings whose predicted contact ratio is short is not
    warned (:func:`~.contact_ratio.check_contact_ratio`).

    Returns
    -------
    dict
        ``{side: {"active_box": FlankBoundary, "gear_tip_undercut_mm": float,
        "solver": MeshingSolver, "gear_flank": FormateFlank | GearSheet,
        "gear_generation": "formate" | "generated", "pair_generation":
        PairGeneration}}`` (a machine-settings pair: the first three, ``"mean_node"``,
        the pinion flank's :class:`~.generated.EnvelopeSolution` at its mean node, and
        ``"gear_box"``, the gear flank's :func:`~.settings_top_land.member_box`). Pass it to
        :func:`~.flank.build_flanks` (``checked=``) to reuse its gear flanks.

    Raises
    ------
    UndercutError
        As :func:`~.conjugate.pinion_active_box`, with a verified ``fix``.
    InputRangeError
        Pointed gear or pinion teeth (a verified fix named); a contact ratio below
        :data:`~.contact_ratio.MIN_CONTACT_RATIO` (a verified fix named).
    """
    pair = _right_hand(pair)
    if pair.machine:
        boxes = _machine_boxes(pair)
    else:
        boxes = _undercut_checked_boxes(pair)
        check_gear_top_land(pair, boxes=boxes)
        check_pinion_top_land(pair, boxes=boxes)
    if contact_ratio:
        # last, so that a pair failing a check above is named by that (a fix of its
        # own, verified with contact_ratio=False); the contact path over the active
        # boxes, no flank work; its named fix verified on the trial pair's boxes
        check_contact_ratio(pair, boxes=boxes, bearing_of=bearing_of,
                            boxes_of=lambda p: check_generation(p, contact_ratio=False),
                            mesh_follows=mesh_follows)
    return boxes


def reverse_side_contact_ratio(pair, *, boxes: dict):
    """The path contact ratio (:func:`~.contact_path.path_contact_ratio`) of the side of
    ``pair`` that is not its design side, which :func:`check_generation` does not check
    (``boxes``: its result): its own table, or the synthesis' first-order bearing at its
    default targets where it has none (``analyze`` and ``twin`` synthesize with those).
    None for a pair cut from machine settings (its path is not known before the TCA).

    Returns
    -------
    ~.contact_path.PathContactRatio or None
    """
    if pair.machine:
        return None
    other = "coast" if pair.design_side == "drive" else "drive"
    return path_contact_ratio(_right_hand(pair), boxes=boxes, side=other)


def _machine_boxes(pair) -> dict:
    """The checks of a pair cut from machine settings (:mod:`.generated`): each gear
    flank's settings and blade (formate, blade kind), each pinion flank's active box
    (blade kind, the envelope reaching the mean node, the edge / limit line, a fold at
    the tip), then the pinion's and the gear's top land along their tip lines
    (:func:`~.settings_top_land.check_settings_top_land`). Each side's gear box is kept
    (``"gear_box"``: the generated gear's hollow ease-off check reuses it,
    :func:`~.settings_check.completed_settings`)."""
    setups = {(s.member, s.side): s for s in pair.machine}
    out, gear = {}, {}
    for side in ("drive", "coast"):
        gear[side] = member_box(pair, setups["gear", side])
        got = member_box(pair, setups["pinion", side])
        out[side] = {"active_box": got["active_box"], "gear_tip_undercut_mm": 0.0,
                     "solver": got["solver"], "mean_node": got["mean_node"],
                     "gear_box": gear[side]}
    check_settings_top_land(pair, boxes=out)
    check_settings_top_land(pair, member="gear", boxes=gear)
    return out


def _right_hand(pair):
    """The right-hand twin of ``pair``: its mirror image generates alike (:mod:`.mirror`;
    machine settings mirrored, :func:`~.flank.right_hand_twin`)."""
    return right_hand_twin(pair) if pair.pinion_hand == "left" else pair


def _undercut_checked_boxes(pair) -> dict:
    """:func:`_generation_boxes`, an undercut refused with a verified gear addendum fix."""
    try:
        return _generation_boxes(pair)
    except UndercutError as err:
        if err.fix is None:
            named = _file_keys(err)
            if named is err:
                raise
            raise named from None
        first, fix = err, err.fix
    for _ in range(_FIX_TRIALS):
        try:
            _generation_boxes(dataclasses.replace(pair, gear_addendum_factor=fix))
        except UndercutError as again:
            if again.fix is None or not 0.0 < again.fix < fix:
                break
            fix = again.fix
        except InputRangeError:
            break
        else:
            tail = first.allowed[first.allowed.index(" (or no undercut)"):]
            raise _file_keys(UndercutError(first.field, first.value, f"<= {fix:.3f}{tail}",
                                           fix=fix))
    raise _file_keys(UndercutError(
        "pinion_teeth / gear_teeth", (pair.pinion_teeth, pair.gear_teeth),
        "a pair whose pinion the gear generates: no gear addendum factor avoids the "
        f"undercut ({first.allowed.split(': ', 1)[1]})"))


def _file_keys(err: UndercutError) -> UndercutError:
    """``err`` naming the blank's fields as the pair file spells them
    (``design.gear_addendum_factor``, ``teeth.pinion / teeth.gear``: the reader's mapping,
    :func:`~.pair.blank_key_error`), its ``fix`` kept; ``err`` itself where it names
    none."""
    named = blank_key_error(err)
    return err if named is err else UndercutError(named.field, named.value, named.allowed,
                                                  fix=err.fix)


#: Smaller gear addendum factors tried by :func:`check_generation` to verify its fix.
_FIX_TRIALS = 3


def _generation_boxes(pair) -> dict:
    """Per side: the pinion's active box, gear tip undercut and meshing solver, the gear
    flank that generates it and its generation (:func:`~.gear_generation.gear_generation`:
    formate, or generated where the formate gear undercuts), and the
    :class:`~.gear_generation.PairGeneration` they come from (``"pair_generation"``:
    :func:`~.flank.build_flanks` reuses it)."""
    made = pair_generation(pair)
    return {side: {"active_box": box, "gear_tip_undercut_mm": undercut, "solver": solver,
                   "gear_flank": made.gear[side], "gear_generation": made.generation,
                   "pair_generation": made}
            for side, (solver, box, undercut) in made.active.items()}


def check_gear_top_land(pair, *, boxes: dict | None = None) -> float:
    """Smallest normal top land of the gear tooth along its tip line, mm
    (:func:`gear_tip_top_lands`); refuses pointed teeth.

    Raises
    ------
    InputRangeError
        Naming ``cutter.point_width_mm`` (the width that leaves a zero top land) or,
        when no width does, ``design.gear_face_width_mm``.
    """
    frac, land = gear_tip_top_lands(pair, boxes=boxes)
    worst = int(np.argmin(land))
    if land[worst] > 0.0:
        return float(land[worst])
    where = "toe" if frac[worst] < 0.5 else "heel"
    w_max = pair.cutter.point_width_mm + float(land[worst])
    if w_max > 0.0:
        raise InputRangeError("cutter.point_width_mm", pair.cutter.point_width_mm,
                              f"< {w_max:.4g} mm (pointed gear teeth at the {where}: the "
                              f"normal top land there is {land[worst]:.4g} mm)")
    raise InputRangeError("design.gear_face_width_mm", pair.gear_face_width_mm,
                          f"a narrower face (pointed gear teeth at the {where} for any cutter "
                          f"point width: the normal top land there is {land[worst]:.4g} mm)")


def gear_tip_top_lands(pair, *, boxes: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Normal top land of the gear tooth along its tip line (the formate or generated
    gear of the pair, :func:`~.gear_generation.gear_generation`; ``boxes`` as
    :func:`pinion_tip_top_lands`'s).

    One gear tooth lies between the drive flank and the coast flank turned by 0 or +-1
    pitch about the gear axis (the turn that puts each flank behind the other's outward
    normal at mid-face, as ``structure.tooth.tooth_geometry`` chooses it).
    At ``TIP_STATIONS`` lengthwise stations of the tip line (both flanks at the same
    fraction of their lengthwise range, as the tooth shell pairs them) the top land is
    the coast point's depth behind the drive flank's tangent plane. The mean-section
    check of ISO 23509 (:func:`~.blank.gear_top_land_mm`) can pass while the toe, whose
    normal pitch is smaller and whose slot is as wide, is pointed.

    Returns
    -------
    frac : ndarray (TIP_STATIONS,)
        Fraction of the lengthwise range, 0 (toe) .. 1 (heel).
    land_mm : ndarray (TIP_STATIONS,)
        Top land, mm (negative: the flanks cross below the tip).
    """
    boxes = _generation_boxes(_right_hand(pair)) if boxes is None else boxes
    drive, coast = boxes["drive"]["gear_flank"], boxes["coast"]["gear_flank"]
    frac = np.linspace(0.0, 1.0, TIP_STATIONS)

    turn = one_tooth_turn(*flank_mid(drive), *flank_mid(coast), axis=Z_AXIS,
                          teeth=pair.gear_teeth)
    if turn is None:
        raise InputRangeError("cutter.point_width_mm", pair.cutter.point_width_mm,
                              "a gear slot narrower than the pitch (no tooth between the "
                              "drive and coast flanks at mid-face)")
    u_tip = min(drive.u_range[1], coast.u_range[1])
    return frac, tip_land_mm(*flank_tip_line(drive, frac, u_tip),
                             flank_tip_line(coast, frac, u_tip)[0], turn)


#: Cutter point widths / working depth factors tried by :func:`check_pinion_top_land`
#: to verify its fix (each trial adds the remaining first-order deficit).
_LAND_TRIALS = 3
#: Top land the named fix aims at, mm: a first-order estimate aimed at exactly zero
#: would land on either side of it.
_LAND_MARGIN_MM = 0.02


def pinion_tip_top_lands(pair, *, boxes: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Normal top land of the conjugate pinion tooth along its tip line.

    The pinion flanks exist only as envelopes of the gear flanks, so the tip line is
    traced with exact node solves (:class:`~.conjugate.MeshingSolver`, no node grid):
    at ``TIP_STATIONS`` lengthwise stations of each flank's active box (both flanks at
    the same fraction, as the tooth shell ``structure.tooth`` pairs them) the solutions
    are continued along the face at the mean radius (:func:`~.conjugate.section_guesses`),
    then along the profile to the common tip ``u = min(u_tip drive, u_tip coast)``, the
    height where the shell's tooth ends. One pinion tooth lies between the drive flank and
    the coast flank turned by 0 or +-1 pitch about the pinion axis (chosen at mid-face);
    the top land is the coast point's depth behind the drive flank's tangent plane, as
    :func:`gear_tip_top_lands` measures it for the gear, with the pair's ease-off relief
    E applied as the eased sheet applies it (:mod:`.easeoff`: same radius and axial
    position, the point turned about the axis by ``E / (n . e_psi)``, first order in E).
    An ease-off still to be synthesized is not known here and counts as zero.

    Parameters
    ----------
    pair : GearPair
    boxes : dict, optional
        :func:`check_generation`'s active boxes and solvers (computed when omitted).

    Returns
    -------
    frac, land_mm : ndarray (TIP_STATIONS,)
        As :func:`gear_tip_top_lands` (toe 0 .. heel 1; top land, mm, negative where the
        flanks cross below the tip).
    """
    pair = _right_hand(pair)
    boxes = _generation_boxes(pair) if boxes is None else boxes
    frac = np.linspace(0.0, 1.0, TIP_STATIONS)
    u_tip = min(got["active_box"].u_tip for got in boxes.values())
    mid, tip = {}, {}
    for side in ("drive", "coast"):
        solver, box = boxes[side]["solver"], boxes[side]["active_box"]
        u_m, v_m = float(solver.cone.root_offset_mm), float(pair.blank.pitch_point_mm[0])
        vs = box.v_toe + frac * (box.v_heel - box.v_toe)
        coeffs = pair.easeoff_drive if side == "drive" else pair.easeoff_coast
        relief = EaseOff.from_coefficients(coeffs, u_mean_mm=u_m, v_mean_mm=v_m
                                           ).relief_mm(u_tip, vs)
        q, _ = section_guesses(solver, vs, u_m, v_m, substeps=1)  # stations F/40 apart
        c = TIP_STATIONS // 2
        s = solver.solve(u_m, vs[c], q[c])
        mid[side] = (s.x1_mm, s.n1)
        for u in np.linspace(u_m, u_tip, TIP_MARCH + 1)[1:]:
            s = solver.solve(np.full_like(vs, u), vs, q)
            q = np.stack([s.h_mm, s.theta_rad, s.phi2_rad], axis=-1)
        # the eased sheet keeps (u, v), i.e. radius and axial position: its point is
        # turned about the axis until it meets the relieved surface r - E n (first order)
        e_psi = np.stack([np.zeros_like(vs), -s.x1_mm[:, 2], s.x1_mm[:, 1]], axis=-1)
        e_psi /= np.linalg.norm(e_psi, axis=-1, keepdims=True)
        shift = relief / np.einsum("ni,ni->n", s.n1, e_psi)
        tip[side] = (s.x1_mm - shift[:, None] * e_psi, s.n1)
    turn = one_tooth_turn(*mid["drive"], *mid["coast"], axis=X_AXIS, teeth=pair.pinion_teeth)
    if turn is None:
        raise InputRangeError("cutter.point_width_mm", pair.cutter.point_width_mm,
                              "a pinion tooth between the drive and coast flanks at mid-face "
                              "(the gear slot is wider than the pitch)")
    return frac, tip_land_mm(*tip["drive"], tip["coast"][0], turn)


def check_pinion_top_land(pair, *, boxes: dict | None = None) -> float:
    """Smallest normal top land of the conjugate pinion tooth along its tip line, mm
    (:func:`pinion_tip_top_lands`); refuses pinion teeth pointed anywhere along the face.

    ISO 23509 checks no pinion top land at all; the conjugate pinion of a formate gear is
    thinnest at the toe tip (z1/z2 = 9/32, E = 0, beta1 = 22.1 deg: -0.06 mm at the
    toe, 0.20 mm at mid-face), where the tooth shell would find its flanks crossing.

    The fix named is verified by running the checks of :func:`check_generation` again
    with it (up to ``_LAND_TRIALS`` values, each adding the remaining first-order
    deficit plus ``_LAND_MARGIN_MM``): first a wider cutter point width ``W`` (a wider
    gear slot: the pinion's normal top land grows about one for one with W, the gear's
    shrinks alike), else a smaller working depth factor (a lower pinion tip:
    the top land grows by ``dh (tan alpha_nD + tan alpha_nC)``, dh the drop of the tip).

    Raises
    ------
    InputRangeError
        Naming ``cutter.point_width_mm`` (a lower bound that works) or
        ``design.working_depth_factor`` (an upper bound that works), with the top land
        found; else ``design.gear_face_width_mm`` (a narrower face) without a value.
    """
    pair = _right_hand(pair)
    frac, land = pinion_tip_top_lands(pair, boxes=boxes)
    worst = int(np.argmin(land))
    if land[worst] > 0.0:
        return float(land[worst])
    where = (f"pointed pinion teeth at the {'toe' if frac[worst] < 0.5 else 'heel'}: the "
             f"normal top land of the conjugate pinion along its tip line is "
             f"{land[worst]:.4g} mm there")
    w = pair.cutter.point_width_mm
    fixed = _verified_fix(pair, float(land[worst]), lambda deficit, w_try: w_try + deficit,
                          w, lambda p, x: dataclasses.replace(
                              p, cutter=dataclasses.replace(p.cutter, point_width_mm=x)))
    if fixed is not None:
        raise InputRangeError("cutter.point_width_mm", w,
                              f">= {fixed[0]:.3f} mm ({where}; with {fixed[0]:.3f} mm it is "
                              f"{fixed[1]:.3g} mm)")
    b = pair.blank
    per_kd = (1.0 - pair.gear_addendum_factor) * b.mean_normal_module_mm * sum(
        np.tan(np.radians(a)) for a in (b.pressure_angle_drive_deg, b.pressure_angle_coast_deg))
    kd = pair.working_depth_factor
    fixed = _verified_fix(pair, float(land[worst]), lambda deficit, k: k - deficit / per_kd,
                          kd, lambda p, x: dataclasses.replace(p, working_depth_factor=x))
    if fixed is not None:
        raise InputRangeError("design.working_depth_factor", kd,
                              f"<= {fixed[0]:.3f} ({where}; with {fixed[0]:.3f} it is "
                              f"{fixed[1]:.3g} mm)")
    raise InputRangeError("design.gear_face_width_mm", pair.gear_face_width_mm,
                          f"a narrower face ({where}; no cutter point width or working depth "
                          "factor tried gives both members a top land)")


def _verified_fix(pair, land_mm: float, step, start: float, change):
    """``(value, smallest pinion top land)`` of the first trial value of one field that
    passes every check of :func:`check_generation`, or None (see
    :func:`check_pinion_top_land`)."""
    x, land = start, land_mm
    for _ in range(_LAND_TRIALS):
        new = step(_LAND_MARGIN_MM - land, x)
        # 3 digits, rounded away from the given value (the safe side)
        x = float((np.ceil if new > start else np.floor)(new * 1e3) / 1e3)
        if not x > 0.0:
            return None
        try:
            trial = change(pair, x)
            boxes = _generation_boxes(trial)
            check_gear_top_land(trial, boxes=boxes)
            land = float(np.min(pinion_tip_top_lands(trial, boxes=boxes)[1]))
        except InputRangeError:
            return None
        if land > 0.0:
            return x, land
    return None
