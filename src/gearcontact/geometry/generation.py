"""Can the gear generate the pinion? The check ``design`` runs before any flank work.

:func:`check_generation` runs the cheap first step of the conjugate pinion generation
(:func:`~.conjugate.pinion_active_box`: the lines the gear tip and root generate, traced
on a few lengthwise sections, no node grid) on both flanks of a pair. A limit line that
leaves more than half the gear addendum without a conjugate partner is refused there
(:class:`~.conjugate.UndercutError`), naming a gear addendum factor that avoids it,
verified by running the check again with it, or the tooth numbers when none does
(docs/geometry.md sec. 7). It also refuses a formate gear whose teeth are pointed
anywhere along the face (:func:`check_gear_top_land`): ISO 23509's top-land check is
made at the mean section only, and the toe is narrower.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..validation import InputRangeError
from .conjugate import UndercutError, pinion_active_box
from .flank import gear_flanks

__all__ = ["check_gear_top_land", "check_generation"]


def check_generation(pair) -> dict:
    """Check that the pinion flanks of ``pair`` can be generated, before any flank work.

    Runs :func:`~.conjugate.pinion_active_box` on both sides (no node grid). An
    undercut names a gear addendum factor that avoids it, verified here (the limit line
    moves slightly with the addenda: up to ``_FIX_TRIALS`` smaller values are tried);
    when none does, the tooth numbers are named.

    Returns
    -------
    dict
        ``{side: {"active_box": FlankBoundary, "gear_tip_undercut_mm": float}}``.

    Raises
    ------
    UndercutError
        As :func:`~.conjugate.pinion_active_box`, with a verified ``fix``.
    """
    if pair.pinion_hand == "left":  # its mirror image generates alike (:mod:`.mirror`)
        pair = dataclasses.replace(pair, pinion_hand="right")
    check_gear_top_land(pair)
    try:
        return _generation_boxes(pair)
    except UndercutError as err:
        if err.fix is None:
            raise
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
            raise UndercutError(first.field, first.value, f"<= {fix:.3f}{tail}", fix=fix)
    raise UndercutError("pinion_teeth / gear_teeth", (pair.pinion_teeth, pair.gear_teeth),
                        "a pair whose pinion the formate gear generates: no gear addendum "
                        f"factor avoids the undercut ({first.allowed.split(': ', 1)[1]})")


#: Smaller gear addendum factors tried by :func:`check_generation` to verify its fix.
_FIX_TRIALS = 3


def _generation_boxes(pair) -> dict:
    kin = pair.kinematics(with_errors=False)
    out = {}
    for side, gear in gear_flanks(pair)[1].items():
        _, box, undercut = pinion_active_box(gear, blank=pair.blank, kinematics=kin,
                                             pinion_face_width_mm=pair.pinion_face_width_mm)
        out[side] = {"active_box": box, "gear_tip_undercut_mm": undercut}
    return out


#: Lengthwise stations of the gear tip line checked by :func:`check_gear_top_land`.
_TIP_STATIONS = 41


def check_gear_top_land(pair) -> float:
    """Smallest normal top land of the formate gear tooth along its tip line, mm
    (:func:`gear_tip_top_lands`); refuses pointed teeth.

    Raises
    ------
    InputRangeError
        Naming ``cutter.point_width_mm`` (the width that leaves a zero top land) or,
        when no width does, ``design.gear_face_width_mm``.
    """
    frac, land = gear_tip_top_lands(pair)
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


def gear_tip_top_lands(pair) -> tuple[np.ndarray, np.ndarray]:
    """Normal top land of the formate gear tooth along its tip line.

    One gear tooth lies between the drive flank and the coast flank turned by 0 or +-1
    pitch about the gear axis (the turn that puts each flank behind the other's outward
    normal at mid-face, as ``structure.tooth.tooth_geometry`` chooses it).
    At ``_TIP_STATIONS`` lengthwise stations of the tip line (both flanks at the same
    fraction of their lengthwise range, as the tooth shell pairs them) the top land is
    the coast point's depth behind the drive flank's tangent plane. The mean-section
    check of ISO 23509 (:func:`~.blank.gear_top_land_mm`) can pass while the toe, whose
    normal pitch is smaller and whose slot is as wide, is pointed.

    Returns
    -------
    frac : ndarray (_TIP_STATIONS,)
        Fraction of the lengthwise range, 0 (toe) .. 1 (heel).
    land_mm : ndarray (_TIP_STATIONS,)
        Top land, mm (negative: the flanks cross below the tip).
    """
    _, flanks = gear_flanks(pair)
    drive, coast = flanks["drive"], flanks["coast"]
    frac = np.linspace(0.0, 1.0, _TIP_STATIONS)

    def tip_line(flank, u):
        v0, v1 = flank.v_range
        s = flank.evaluate(np.full_like(frac, u), v0 + frac * (v1 - v0), second=False)
        return s.r, s.n

    def mid(flank):
        (u0, u1), (v0, v1) = flank.u_range, flank.v_range
        s = flank.evaluate(np.array([0.5 * (u0 + u1)]), np.array([0.5 * (v0 + v1)]),
                           second=False)
        return s.r[0], s.n[0]

    z = pair.gear_teeth
    (rd, nd), (rc0, nc0) = mid(drive), mid(coast)
    best = None
    for k in (0, 1, -1):
        turn = _turn_z(2.0 * np.pi * k / z)
        rc, nc = rc0 @ turn.T, nc0 @ turn.T
        gap = float(np.linalg.norm(rd - rc))
        if nd @ (rc - rd) < 0.0 and nc @ (rd - rc) < 0.0 and (best is None or gap < best[0]):
            best = (gap, turn)
    if best is None:
        raise InputRangeError("cutter.point_width_mm", pair.cutter.point_width_mm,
                              "a gear slot narrower than the pitch (no tooth between the "
                              "drive and coast flanks at mid-face)")
    u_tip = min(drive.u_range[1], coast.u_range[1])
    rd, nd = tip_line(drive, u_tip)
    rc = tip_line(coast, u_tip)[0] @ best[1].T
    return frac, -np.einsum("ni,ni->n", rc - rd, nd)


def _turn_z(angle_rad: float) -> np.ndarray:
    """Rotation matrix about the gear axis z by ``angle_rad``."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
