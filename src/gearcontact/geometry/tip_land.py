"""The top land of one tooth between its drive and coast flanks' tip lines.

Shared by the top-land checks of :mod:`.generation` (the formate or generated gear,
the conjugate pinion) and :mod:`.settings_top_land` (a pinion cut from machine
settings): one tooth lies between the drive flank and the coast flank turned by 0 or
+-1 pitch about the member axis (the turn that puts each flank behind the other's
outward normal at mid-face, as ``structure.tooth.tooth_geometry`` chooses it); at each
lengthwise station of the tip line (both flanks at the same fraction of their
lengthwise range, as the tooth shell pairs them) the normal top land is the coast
point's depth behind the drive flank's tangent plane, mm (negative: the flanks cross
below the tip).
"""

from __future__ import annotations

import numpy as np

__all__ = ["TIP_MARCH", "TIP_STATIONS", "X_AXIS", "Z_AXIS", "flank_mid", "flank_tip_line",
           "one_tooth_turn", "tip_land_mm"]

#: Lengthwise stations of a tip line checked (toe 0 .. heel 1, F/40 apart).
TIP_STATIONS = 41
#: Profile steps marching a flank's node solutions from the mean radius to its tip line
#: (continuation; each step well inside Newton's convergence radius).
TIP_MARCH = 12
#: The member axes in their body frames: pinion x, gear z.
X_AXIS, Z_AXIS = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])


def one_tooth_turn(rd, nd, rc, nc, *, axis: np.ndarray, teeth: int):
    """Rotation (3, 3) about the member ``axis`` by 0 or +-1 pitch that puts the coast
    point ``rc`` (normal ``nc``) and the drive point ``rd`` (``nd``) behind each other's
    outward normal with the smallest gap (one tooth, not a slot), or None."""
    best = None
    for k in (0, 1, -1):
        turn = _turn(axis, 2.0 * np.pi * k / teeth)
        rc_k, nc_k = rc @ turn.T, nc @ turn.T
        gap = float(np.linalg.norm(rd - rc_k))
        if nd @ (rc_k - rd) < 0.0 and nc_k @ (rd - rc_k) < 0.0 and (best is None or gap < best[0]):
            best = (gap, turn)
    return None if best is None else best[1]


def tip_land_mm(rd, nd, rc, turn: np.ndarray) -> np.ndarray:
    """Normal top land, mm, at tip-line stations: drive points ``rd`` and outward normals
    ``nd`` (n, 3), coast points ``rc`` (n, 3) before the turn ``turn``
    (:func:`one_tooth_turn`); negative where the flanks cross below the tip."""
    return -np.einsum("ni,ni->n", rc @ turn.T - rd, nd)


def flank_tip_line(flank, frac: np.ndarray, u_tip: float):
    """Points and unit normals (n, 3) of a flank sheet (``evaluate``, ``u_range``,
    ``v_range``: a formate or spline flank) at height ``u_tip`` and the fractions
    ``frac`` of its lengthwise range."""
    v0, v1 = flank.v_range
    s = flank.evaluate(np.full_like(frac, u_tip), v0 + frac * (v1 - v0), second=False)
    return s.r, s.n


def flank_mid(flank):
    """Point and unit normal (3,) of a flank sheet at the middle of its ranges."""
    (u0, u1), (v0, v1) = flank.u_range, flank.v_range
    s = flank.evaluate(np.array([0.5 * (u0 + u1)]), np.array([0.5 * (v0 + v1)]), second=False)
    return s.r[0], s.n[0]


def _turn(axis: np.ndarray, angle_rad: float) -> np.ndarray:
    """Rotation matrix about the unit ``axis`` by ``angle_rad`` (Rodrigues)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(angle_rad) * k + (1.0 - np.cos(angle_rad)) * (k @ k)
