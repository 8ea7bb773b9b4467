"""Member torque <-> normal tooth load through the contact geometry.

A normal force ``W n`` acting at the mating point ``P`` produces the moment
``M = ((P - O) x W n) . e`` about a member's axis (through ``O`` along ``e``). For a
given torque ``T`` on that member the normal load is therefore ``W = T / |lever|`` with
the effective lever ``|((P - O) x n) . e|`` (mm). Friction is neglected (its moment is
second order for hypoid efficiency > 95 %).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 9.4
(force transmission at the contact point).
"""

from __future__ import annotations

import numpy as np

from ..validation import InputRangeError, check_array_finite, check_positive

__all__ = ["torque_lever_mm", "normal_load_from_torque"]


def torque_lever_mm(point_mm, normal, *, axis_point_mm=(0.0, 0.0, 0.0),
                    axis_dir=(0.0, 0.0, 1.0)) -> float:
    """Effective lever ``|((P - O) x n) . e|`` of a normal force about an axis, mm.

    Parameters
    ----------
    point_mm : array_like (3,)
        Mating point P in the meshing frame, mm.
    normal : array_like (3,)
        Common unit normal at P.
    axis_point_mm, axis_dir : array_like (3,)
        A point on the member axis (mm) and its direction (normalized here); default the
        gear axis of the meshing frame (+z through the origin).
    """
    p = check_array_finite("point_mm", point_mm)
    n = check_array_finite("normal", normal)
    e = check_array_finite("axis_dir", axis_dir)
    n = n / np.linalg.norm(n)
    e = e / np.linalg.norm(e)
    lever = abs(float(np.cross(p - np.asarray(axis_point_mm, dtype=float), n) @ e))
    if lever < 1e-9:
        raise InputRangeError("torque lever (mm)", lever,
                              "> 0 (the normal passes through the axis: no torque is carried)")
    return lever


def normal_load_from_torque(torque_nm: float, point_mm, normal, **axis) -> float:
    """Normal tooth load W (N) that carries ``torque_nm`` (N·m) on one tooth pair.

    ``axis`` as in :func:`torque_lever_mm` (default the gear axis).
    """
    t = check_positive("torque_nm (N·m)", torque_nm)
    return 1000.0 * t / torque_lever_mm(point_mm, normal, **axis)
