"""Meshing frame, rigid-body poses and assembly errors of a crossed-axis gear pair.

Meshing frame (docs/spec.md sec. 3, docs/geometry.md sec. 1): the gear axis is ``+z`` through the
origin; the pinion axis is ``x`` through ``C1 = (0, -E, 0)`` (E = hypoid offset, mm).
The gear turns with angular velocity ``w2 = +z`` (1 rad per unit phase) and the pinion
with ``w1 = -u x`` (u = z2/z1), so that a gear rotation ``phi2`` pairs with a pinion
rotation ``phi1 = u phi2`` about ``-x``.

Left-hand pinion (``hand="left"``): the pair is the mirror image ``M = diag(1, -1, 1)``
of the right-hand pair, pinion axis through ``(0, +E, 0)``; the mirrored motion turns
both members the other way, so the rotation axes become ``w2 = -z`` and ``w1 = +u x``
and every pose is ``M R M`` of the right-hand one. A mirrored pair thus meshes at the
same phases (phi1, phi2) as its right-hand twin, with mirrored contact points.

Body frames: each member's flank is defined in its own body frame (gear: axis z,
apex-side conventions of :mod:`gearcontact.geometry.flank`; pinion: axis x, origin on
its axis at the point that coincides with C1 in the nominal assembly). A pose maps
body -> meshing frame: ``X_f = R @ X_body + t``.

Assembly errors (Gleason sign conventions, all in the meshing frame):

==========  ========  ==========================================================
symbol      unit      positive value means
==========  ========  ==========================================================
``E``       mm        offset increased: the pinion axis moves to y = -(E0 + E)
``P``       mm        pinion moved along its axis away from the crossing point (+x)
``G``       mm        gear moved along its axis away from the crossing point (+z)
``alpha``   deg       shaft angle increased: pinion axis rotated about +y through
                      the pinion's crossing point by -alpha (tilting +x towards +z)
==========  ========  ==========================================================

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., Cambridge
University Press, 2004, ch. 9 (relative velocity, equation of meshing) and ch. 15
(assembly errors of hypoid gear drives).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError, check_finite, check_positive

__all__ = ["AssemblyErrors", "MeshKinematics", "ASSEMBLY_KEYS", "ASSEMBLY_LIMITS",
           "rot_x", "rot_y", "rot_z"]

#: Short names of the assembly errors (command line, sweeps) -> AssemblyErrors fields.
ASSEMBLY_KEYS = {"E": "E_mm", "P": "P_mm", "G": "G_mm", "alpha": "alpha_deg"}
#: Largest magnitude accepted from the command line per field (mm, mm, mm, deg): ten
#: times the usual mounting tolerances of automotive hypoid sets (tens of um, minutes of
#: arc); beyond it the bearing leaves the flank of any practical set-up.
ASSEMBLY_LIMITS = {"E_mm": 1.0, "P_mm": 1.0, "G_mm": 1.0, "alpha_deg": 0.5}


def rot_x(angle_rad: float) -> np.ndarray:
    """Right-handed rotation matrix about +x by ``angle_rad``."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle_rad: float) -> np.ndarray:
    """Right-handed rotation matrix about +y by ``angle_rad``."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle_rad: float) -> np.ndarray:
    """Right-handed rotation matrix about +z by ``angle_rad``."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class AssemblyErrors:
    """Assembly (mounting) errors E, P, G, alpha; see the module table for signs.

    Parameters
    ----------
    E_mm : float
        Offset error, mm.
    P_mm : float
        Pinion axial displacement, mm.
    G_mm : float
        Gear axial displacement, mm.
    alpha_deg : float
        Shaft-angle error, degrees.
    """

    E_mm: float = 0.0
    P_mm: float = 0.0
    G_mm: float = 0.0
    alpha_deg: float = 0.0

    def __post_init__(self):
        for name in ("E_mm", "P_mm", "G_mm", "alpha_deg"):
            check_finite(f"assembly.{name}", getattr(self, name))


@dataclass(frozen=True)
class MeshKinematics:
    """Rigid-body kinematics of a crossed-axis pair with shaft angle 90 deg.

    Parameters
    ----------
    offset_mm : float
        Nominal hypoid offset E0, mm (pinion axis below the gear centre, y = -E0).
    ratio : float
        Gear ratio u = z2 / z1 (> 0).
    errors : AssemblyErrors
        Mounting errors applied to the poses (nominal: all zero).
    """

    offset_mm: float
    ratio: float
    errors: AssemblyErrors = AssemblyErrors()
    hand: str = "right"

    def __post_init__(self):
        check_finite("offset_mm", self.offset_mm)
        check_positive("ratio", self.ratio)
        if self.hand not in ("right", "left"):
            raise InputRangeError("pinion_hand", self.hand, "'right' or 'left'")

    @property
    def _side(self) -> float:
        """+1 (right-hand pinion) or -1: the mirror image y -> -y of the right-hand pair."""
        return 1.0 if self.hand == "right" else -1.0

    @property
    def pinion_centre(self) -> np.ndarray:
        """C1: the pinion's crossing point on its axis in the meshing frame, mm
        (y = -(E0 + E) for a right-hand pinion, mirrored to +(E0 + E) for a left-hand)."""
        return np.array([self.errors.P_mm, -self._side * (self.offset_mm + self.errors.E_mm), 0.0])

    @property
    def pinion_axis(self) -> np.ndarray:
        """Unit vector of the pinion axis (+x tilted by the shaft-angle error), oriented
        so that ``-ratio * pinion_axis`` is the pinion's angular velocity per unit gear
        rate (a left-hand pair, mirrored, turns the other way: -x)."""
        return self._side * (rot_y(-np.radians(self.errors.alpha_deg)) @ np.array([1.0, 0.0, 0.0]))

    @property
    def gear_axis(self) -> np.ndarray:
        """Unit vector of the gear's rotation axis (+z; -z for the mirrored left-hand pair)."""
        return np.array([0.0, 0.0, self._side])

    def gear_pose(self, phi2_rad: float) -> tuple[np.ndarray, np.ndarray]:
        """Gear body -> meshing frame after a gear rotation ``phi2`` about ``gear_axis``.

        Returns ``(R, t)`` with ``X_f = R @ X_body + t``; t carries the G error.
        """
        return rot_z(self._side * phi2_rad), np.array([0.0, 0.0, self.errors.G_mm])

    def pinion_pose(self, phi1_rad: float) -> tuple[np.ndarray, np.ndarray]:
        """Pinion body -> meshing frame after a pinion rotation ``phi1`` about -x (+x for
        a left-hand pinion: the mirror image M R M of the right-hand pose, M = diag(1, -1, 1)).

        The body frame's x axis is the pinion axis; errors move and tilt it.
        """
        tilt = rot_y(-np.radians(self.errors.alpha_deg))
        return tilt @ rot_x(-self._side * phi1_rad), self.pinion_centre

    def relative_velocity(self, x_f: np.ndarray) -> np.ndarray:
        """Nominal sliding velocity v12 = w1 x (X - C1) - w2 x X per unit gear rate.

        ``x_f`` may be (3,) or (..., 3); returns the same shape, mm/rad.
        """
        x = np.asarray(x_f, dtype=float)
        w1 = -self.ratio * self.pinion_axis
        w2 = self.gear_axis
        return np.cross(w1, x - self.pinion_centre) - np.cross(w2, x - np.array([0.0, 0.0, self.errors.G_mm]))
