"""Meshing frame and rigid-body poses of a parallel-axis (cylindrical) pair.

The same interface as the crossed-axis :class:`~gearcontact.geometry.kinematics.MeshKinematics`
(``ratio``, ``pinion_axis``, ``gear_axis``, ``pinion_pose``, ``gear_pose``,
``relative_velocity``), so that the TCA's mating-point and contact-line solvers
(:mod:`gearcontact.tca.mating`, :mod:`gearcontact.tca.line_contact`) run unchanged on
either kind of pair: the pinion turns about ``-pinion_axis`` by ``phi1``, the gear about
``gear_axis`` by ``phi2``, and ``phi1 = u phi2`` for a perfect mesh.

Meshing frame: the gear axis is +z through the origin, the pinion axis +z through
``C1 = (-a_w, 0, 0)``. Body frames are those of :mod:`.flank` (tooth centred on +x at
z = 0). At ``phi1 = phi2 = 0`` the pinion tooth is centred on the line of centres and
the gear, turned by ``π + π/z2``, offers it a tooth space centred there: with zero
backlash both flank pairs touch, at mirror-image points of their lines of action (the
pitch point ``(-r_w2, 0, 0)`` is passed half a working tooth thickness earlier or
later, :func:`gearcontact.tca.parallel_axes.pitch_point_guess`). A positive ``phi1`` turns the pinion
clockwise (seen from +z) and the gear counter-clockwise: the pinion's "cw" flanks drive
the gear's "cw" flanks.

Axis misalignment (ISO 1328-1's f_Σδ and f_Σβ over the face width b, as angles
f / b) tilts the gear axis about the mid-face point O: the inclination ``ε`` about +y
(in the plane of the axes, x-z), the deviation ``γ`` about +x (the line of centres, out
of that plane), ``T = rot_y(ε) rot_x(γ)``; the gear turns about ``T ẑ``.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 14
(parallel-axis involute helical gears).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...validation import check_positive, check_range
from ..kinematics import rot_x, rot_y, rot_z

__all__ = ["ParallelKinematics"]


@dataclass(frozen=True)
class ParallelKinematics:
    """Rigid-body kinematics of an external parallel-axis pair.

    Parameters
    ----------
    centre_distance_mm : float
        a_w, mm.
    ratio : float
        u = z2 / z1.
    gear_teeth : int
        z2 (the gear's start orientation offers a tooth space to the pinion).
    axis_inclination_rad, axis_deviation_rad : float
        ε and γ of the module docstring, rad (default 0).
    """

    centre_distance_mm: float
    ratio: float
    gear_teeth: int
    axis_inclination_rad: float = 0.0
    axis_deviation_rad: float = 0.0

    def __post_init__(self):
        check_positive("centre_distance_mm", self.centre_distance_mm)
        check_positive("ratio", self.ratio)
        for name in ("axis_inclination_rad", "axis_deviation_rad"):
            check_range(name, getattr(self, name), -0.05, 0.05)

    @property
    def _tilt(self) -> np.ndarray:
        """T: the gear axis' misalignment rotation."""
        return rot_y(self.axis_inclination_rad) @ rot_x(self.axis_deviation_rad)

    @property
    def pinion_centre(self) -> np.ndarray:
        """C1, the pinion axis' point at z = 0, mm."""
        return np.array([-self.centre_distance_mm, 0.0, 0.0])

    @property
    def pinion_axis(self) -> np.ndarray:
        """+z: the pinion turns about ``-pinion_axis`` (clockwise) by ``phi1``."""
        return np.array([0.0, 0.0, 1.0])

    @property
    def gear_axis(self) -> np.ndarray:
        """T ẑ (+z when aligned): the gear turns about it (counter-clockwise) by ``phi2``."""
        return self._tilt[:, 2].copy()

    def gear_pose(self, phi2_rad: float) -> tuple[np.ndarray, np.ndarray]:
        """Gear body -> meshing frame ``(R, t)``, ``X_f = R @ X_body + t``."""
        return (self._tilt @ rot_z(phi2_rad + math.pi + math.pi / self.gear_teeth),
                np.zeros(3))

    def pinion_pose(self, phi1_rad: float) -> tuple[np.ndarray, np.ndarray]:
        """Pinion body -> meshing frame after a turn ``phi1`` about -z through C1."""
        return rot_z(-phi1_rad), self.pinion_centre

    def relative_velocity(self, x_f: np.ndarray) -> np.ndarray:
        """Sliding velocity v12 = w1 x (X - C1) - w2 x X per unit gear rate, mm/rad."""
        x = np.asarray(x_f, dtype=float)
        w1 = -self.ratio * self.pinion_axis
        return np.cross(w1, x - self.pinion_centre) - np.cross(self.gear_axis, x)
