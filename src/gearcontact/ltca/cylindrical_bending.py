"""Tooth bending blocks of a cylindrical pair's loaded TE: the shell compliance of the
pinion and gear tooth along each contact line (docs/bending.md sec. 8).

A pair's field in :mod:`.cylindrical_lte` has one row of cells per axial position ``z``
of the pinion face (the contact line) and a strip of cells across it. Its bending
compliance is that of the pinion tooth plus that of the gear tooth at the line point of
each row, ``G = G_pinion + G_gear`` (:mod:`.tooth_bending`), each the shell operator of
:func:`~gearcontact.structure.cylindrical_tooth.cylindrical_tooth_shell` at the flank
parameters (roll length, axial position) of the point: pinion ``(u1(z), z)``, gear
``(u2(z), z)`` (both members' frames are centred mid-face on parallel axes). Across the
strip (a Hertz width, tenths of a mm, against the shell's shortest wavelength of ~1 mm
along the face and a tooth height over the profile) the bending compliance is taken as
the line point's: every cell of a row shares its factor row. Rows off the line (no
contact there in this phase, never loaded) take the line's roll lengths extrapolated
linearly in ``z`` and clipped to the flank box (smooth along the field).

The shells are those of the unmodified teeth (:func:`bending_pair`): micro-geometry
removes micrometres from a tooth millimetres thick, and one model then serves a whole
Harris map.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..geometry.cylindrical.pair import CylindricalPair, MeshAlignment, ToothModifications
from ..structure.cylindrical_tooth import cylindrical_tooth_shell, loaded_side
from ..structure.shell import ORDER, ORDER_FACE
from ..validation import check_range
from .tooth_bending import ToothBending

__all__ = ["bending_pair", "cylindrical_bending", "line_bending_factor"]

#: Rows along the face where the shell operator is evaluated exactly; the factor rows of
#: the others are cubic-spline interpolated (:meth:`.tooth_bending.ToothBending.factor`):
#: the compliance varies on the Ritz scale along the face (degree 16), the rolls are
#: affine in z.
_NODES_ALONG = 24


def bending_pair(pair: CylindricalPair) -> CylindricalPair:
    """``pair`` without micro-geometry and misalignment: the teeth the shells model."""
    return replace(pair, modifications_pinion=ToothModifications(member="pinion"),
                   modifications_gear=ToothModifications(member="gear"),
                   assembly=MeshAlignment())


def cylindrical_bending(pair: CylindricalPair, *, facing: str = "cw", scale: float = 1.0,
                        order: int = ORDER, order_face: int = ORDER_FACE) -> ToothBending:
    """The :class:`~.tooth_bending.ToothBending` of a cylindrical pair meshing on
    ``facing`` (shells cached per unmodified pair; ``scale`` as there: 0 rigid)."""
    check_range("bending scale", scale, 0.0, 1e6)
    side = loaded_side(facing)
    base = bending_pair(pair)
    return ToothBending(
        pinion=cylindrical_tooth_shell(base, "pinion", order=order, order_face=order_face),
        gear=cylindrical_tooth_shell(base, "gear", order=order, order_face=order_face),
        side=side, scale=float(scale))


def _filled(roll: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Roll lengths on the line, extrapolated linearly in z to the rows off it."""
    on = np.flatnonzero(np.isfinite(roll))
    if on.size == roll.size:
        return roll
    i, j = on[0], on[-1]           # the line is affine in z (micro-geometry: nearly)
    slope = (roll[j] - roll[i]) / (z[j] - z[i]) if j > i else 0.0
    out = roll[i] + slope * (z - z[i])
    out[on] = roll[on]
    return out


def line_bending_factor(bending: ToothBending, z_mm: np.ndarray, pinion_roll_mm: np.ndarray,
                        gear_roll_mm: np.ndarray, cells_across: int) -> np.ndarray:
    """Bending factor ``F`` (N, cells_across, r) of one pair's field (module docstring):
    rows at the axial positions ``z_mm`` (N,) with the line's roll lengths (NaN off the
    line), the same row for every cell across; ``G = F F^T`` mm/N."""
    z = np.asarray(z_mm, float)
    uv1 = np.stack([_filled(pinion_roll_mm, z), z], axis=1)
    uv2 = np.stack([_filled(gear_roll_mm, z), z], axis=1)
    f = bending.factor(uv1, uv2, (len(z), 1), nodes=(_NODES_ALONG, 1))
    return np.broadcast_to(f, (len(z), int(cells_across), f.shape[2]))
