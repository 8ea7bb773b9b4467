"""Can the gear generate the pinion? The check ``design`` runs before any flank work.

:func:`check_generation` runs the cheap first step of the conjugate pinion generation
(:func:`~.conjugate.pinion_active_box`: the lines the gear tip and root generate, traced
on a few lengthwise sections, no node grid) on both flanks of a pair. A limit line that
leaves more than half the gear addendum without a conjugate partner is refused there
(:class:`~.conjugate.UndercutError`), naming a gear addendum factor that avoids it,
verified by running the check again with it, or the tooth numbers when none does
(docs/geometry.md sec. 7).
"""

from __future__ import annotations

import dataclasses

from ..validation import InputRangeError
from .conjugate import UndercutError, pinion_active_box
from .flank import gear_flanks

__all__ = ["check_generation"]


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
