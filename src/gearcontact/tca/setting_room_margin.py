"""The margin of lever 5's room (docs/machine_settings.md sec. 5, "The print's drive
bearing: a margin on lever 5's room"): how much of the paint ellipse's room along its
major axis the contact's travel across the working depth takes away over half the
transmitted pitch.

The synthesis centres the transmitted pitch on its pivot M (the TE0 vertex at M), so the
contact moves half a pitch either way along its path, and one way it moves towards the
root. To first order its depth travel is ``(pi / z1) |du1/dphi1|`` (``u1`` the pinion
flank's depth coordinate, root to tip; ``phi1`` the pinion roll), and a depth ``d``
is ``d / |du1/ds|`` along the ellipse's major axis (``s``, mm along it in the tangent
plane), so the room that travel takes away is

    m = (pi / z1) |du1/dphi1| / |du1/ds|.

``du1/dphi1`` is measured on the candidate's own path at M (its local TCA, the five-point
central difference over steps of 1/30 pitch); ``du1/ds`` by the first-order map of the
tangent plane onto the pinion flank (:func:`~.stencil.tangent_parameters`) along the
axis :func:`~.setting_problem.line_room_mm` measures (the principal direction of least
relative curvature). Where ``du1/ds`` is 0 the axis runs along the root line and no depth
travel shortens its room: ``m = 0``.
"""

from __future__ import annotations

import math

import numpy as np

from .setting_problem import local_slope, local_tca
from .stencil import tangent_frame, tangent_parameters

__all__ = ["axis_depth_rate", "depth_rate_per_rad", "room_margin_mm"]


def depth_rate_per_rad(pinion, gear, pair, start) -> float:
    """``du1/dphi1`` (pinion flank depth coordinate, mm of ``u``, per rad of pinion roll)
    of the contact path of ``pinion`` and ``gear`` through ``start`` (a contact, the
    pivot M): the five-point central difference of the local TCA's ``u1``
    (:func:`~.setting_problem.local_tca`, steps of 1/30 pitch, edges off).

    Raises
    ------
    ArithmeticError
        The contact leaves a flank within two local steps (no rate at M).
    """
    _, h, path = local_tca(pinion, gear, pair, start)
    u = np.array([p.u1 for p in path.points], dtype=float)
    if len(u) != 5 or not np.all(np.isfinite(u)) or any(p.edge for p in path.points):
        raise ArithmeticError("the contact leaves a flank within two local steps of M")
    return local_slope(u, h)


def axis_depth_rate(pinion, gear, kin, mp) -> float:
    """``du1/ds``: the pinion flank's depth coordinate ``u`` per mm along the major axis
    of the paint ellipse at the mating point ``mp`` (the ``"principal"`` frame's first
    axis, :func:`~.stencil.tangent_frame`), to first order
    (:func:`~.stencil.tangent_parameters`)."""
    axes = tangent_frame(pinion, gear, kin, mp, "principal")
    uv = tangent_parameters(pinion, kin.pinion_pose(mp.phi1_rad), axes, (mp.u1, mp.v1),
                            np.array([[1.0, 0.0]]))
    return float(uv[0, 0] - mp.u1)


def room_margin_mm(*, depth_rate_per_rad: float, axis_depth_rate_per_mm: float,
                   pinion_teeth: int) -> float:
    """``m = (pi / z1) |du1/dphi1| / |du1/ds|``, mm (module docstring): the room along
    the ellipse's major axis that the contact's depth travel over half a pitch takes
    away; 0 where ``du1/ds`` is 0 (an axis along the root line)."""
    if axis_depth_rate_per_mm == 0.0:
        return 0.0
    return math.pi / pinion_teeth * abs(depth_rate_per_rad) / abs(axis_depth_rate_per_mm)
