"""Tooth bending blocks of a cylindrical pair's loaded TE: the shell compliance of the
pinion and gear tooth along each contact line (docs/bending.md sec. 9).

A pair's field in :mod:`.cylindrical_lte` has one row of cells per axial position ``z``
of the pinion face (the contact line) and a strip of cells across it. Its bending
compliance is that of the pinion tooth plus that of the gear tooth at the line point of
each row, ``G = G_pinion + G_gear`` (:mod:`.tooth_bending`), each the shell operator of
:func:`~gearcontact.structure.cylindrical_tooth.cylindrical_tooth_shell` at the flank
parameters (roll length, axial position) of the point: pinion ``(u1(z), z)``, gear
``(u2(z), z)`` (both members' frames are centred mid-face on parallel axes). Across the
strip (a Hertz width, tenths of a mm, against the shell's shortest wavelength of ~1 mm
along the face and a tooth height over the profile) the bending compliance is taken as
the line point's: every cell of a row shares its factor row. The rows are the shell
operator's exactly (no interpolation along the face: the compliance varies on the Ritz
scale, ~1-2 mm, and a spline over the rows errs by 2-14 % where the line ends); rows off
the line (no contact there in this phase: a separation of 1 mm, never loaded) carry
none.

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


def line_bending_factor(bending: ToothBending, z_mm: np.ndarray, pinion_roll_mm: np.ndarray,
                        gear_roll_mm: np.ndarray, cells_across: int) -> np.ndarray:
    """Bending factor ``F`` (N, cells_across, r) of one pair's field (module docstring):
    rows at the axial positions ``z_mm`` (N,) with the line's roll lengths (NaN off the
    line: a zero row), the same row for every cell across; ``G = F F^T`` mm/N."""
    z = np.asarray(z_mm, float)
    on = np.isfinite(pinion_roll_mm) & np.isfinite(gear_roll_mm)
    n_on = int(on.sum())
    if n_on == 0:
        return np.zeros((len(z), int(cells_across), 1))
    uv1 = np.stack([pinion_roll_mm[on], z[on]], axis=1)
    uv2 = np.stack([gear_roll_mm[on], z[on]], axis=1)
    f = bending.factor(uv1, uv2, (n_on, 1), nodes=(n_on, 1))[:, 0]
    out = np.zeros((len(z), f.shape[1]), f.dtype)
    out[on] = f
    return np.broadcast_to(out[:, None, :], (len(z), int(cells_across), f.shape[1]))
