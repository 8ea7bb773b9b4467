"""The contact path of a pair's side with its relative curvature, as the setting fit's
curvature rows take it (:class:`~gearcontact.geometry.residual_curvature.PathCurvature`;
docs/machine_settings.md sec. 6, "The residual's curvature and the pressure it
bounds")."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..geometry.residual_curvature import PathCurvature
from ..validation import InputRangeError
from .analysis import analyze_pair
from .curvature import relative_curvature
from .line_contact import LineContact

__all__ = ["target_path_curvature"]


def target_path_curvature(pair, side: str, *, phases: int = 61, points: int = 25
                          ) -> PathCurvature | None:
    """The reference point P0 of ``pair``'s TCA on ``side`` (:func:`~.analysis.analyze_pair`,
    ``phases`` phases; a left-hand pair's right-hand twin, the flank the setting fit
    fits: where the loaded commands solve the single pair), then at most ``points`` of
    its surface contacts evenly spaced along the path, with the half relative curvature
    tensor there in the pinion body frame. ``None`` where the side
    is in line contact (a conjugate side: no finite relative curvature to keep).

    Raises
    ------
    InputRangeError
        ``points`` below 1 (naming it).
    """
    if int(points) != points or points < 1:
        raise InputRangeError("points", points, "an integer >= 1")
    twin = dataclasses.replace(pair, pinion_hand="right") if pair.pinion_hand == "left" else pair
    try:
        tca, flanks = analyze_pair(twin, side=side, phases=phases)
    except LineContact:
        return None
    kin = twin.kinematics()
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    surface = [m for m in tca.cycle.path.points if not m.edge and not m.edge_contact]
    if not surface:
        return None
    pick = np.unique(np.round(np.linspace(0, len(surface) - 1, min(points, len(surface)))))
    u, v, basis, tensor = [], [], [], []
    for m in [tca.mean_point] + [surface[k] for k in pick.astype(int)]:
        rc = relative_curvature(pinion, gear, kin, m)
        rot = kin.pinion_pose(m.phi1_rad)[0]
        u.append(m.u1)
        v.append(m.v1)
        basis.append(rot.T @ np.column_stack([rc.lengthwise, rc.profile]))
        tensor.append(0.5 * rc.tensor_per_mm)
    return PathCurvature(u_mm=np.array(u), v_mm=np.array(v), basis=np.array(basis),
                         tensor_per_mm=np.array(tensor))
