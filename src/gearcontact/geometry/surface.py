"""The flank-surface interface shared by geometry (producers) and TCA (consumers).

A flank is a regular parametric surface ``r(u, v)`` in its member's body frame (mm).
Conventions: ``u`` runs across the tooth (root -> tip, profile direction), ``v`` along
it (toe -> heel, lengthwise direction); ``n`` is the unit normal pointing out of the
tooth material into the tooth space. Second derivatives are provided so that shape
operators (curvatures) are exact, not finite-differenced.

References
----------
M. P. do Carmo, *Differential Geometry of Curves and Surfaces*, 1976, sec. 3-3
(first and second fundamental forms, shape operator).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

__all__ = ["SurfacePoint", "Surface"]


@dataclass(frozen=True)
class SurfacePoint:
    """Position, derivatives and unit normal of a flank at one parameter pair.

    All vectors are (3,) arrays in the member's body frame; lengths in mm, derivatives
    in mm per parameter unit.
    """

    u: float
    v: float
    r: np.ndarray
    r_u: np.ndarray
    r_v: np.ndarray
    r_uu: np.ndarray
    r_uv: np.ndarray
    r_vv: np.ndarray
    n: np.ndarray

    def fundamental_forms(self) -> tuple[np.ndarray, np.ndarray]:
        """First (I) and second (II, w.r.t. ``n``) fundamental forms as 2x2 arrays."""
        first = np.array([[self.r_u @ self.r_u, self.r_u @ self.r_v],
                          [self.r_u @ self.r_v, self.r_v @ self.r_v]])
        second = np.array([[self.r_uu @ self.n, self.r_uv @ self.n],
                           [self.r_uv @ self.n, self.r_vv @ self.n]])
        return first, second


@runtime_checkable
class Surface(Protocol):
    """A flank surface: ``point(u, v)`` inside ``u_range x v_range``."""

    u_range: tuple[float, float]
    v_range: tuple[float, float]

    def point(self, u: float, v: float) -> SurfacePoint:
        """Evaluate the surface exactly (or by C2-smooth interpolation) at (u, v)."""
        ...
