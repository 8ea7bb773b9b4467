"""Geometry of the hardware curvature-fit stencil (stage C) and its file format.

The datapath fits a quadratic to ``N = 49`` gap samples on a fixed 7 x 7 grid in the
local tangent frame (s, t) centred on the contact point (SPEC section 6, Algorithm 2).
The grid is a compile-time constant: its pseudo-inverse is baked into a ROM, so the
spacing below is part of the hardware contract.

Sample order (row-major, s fastest)::

    i = 7 * j + k,  s_i = (k - 3) * STENCIL_SPACING_MM,  t_i = (j - 3) * STENCIL_SPACING_MM

File format (``gap_stencil.csv``, read by ``gearcontact preview --stencil``): a CSV with
the header ``s_mm,t_mm,gap_mm`` and 49 rows in the order above; ``s_mm``/``t_mm`` must
match the baked grid to 1e-9 mm, ``gap_mm`` is the separation along the common normal
(mm, positive = open).
"""

from __future__ import annotations

import numpy as np

__all__ = ["STENCIL_SIDE", "STENCIL_SIZE", "STENCIL_SPACING_MM", "stencil_coordinates"]

STENCIL_SIDE = 7
STENCIL_SIZE = STENCIL_SIDE * STENCIL_SIDE
#: Grid spacing of the baked stencil, mm. 0.5 mm keeps the quantization error of the
#: fitted curvature below 0.1 % at A- = 1e-3 1/mm with Q(32,16) gaps (sigma_c3 ~
#: 2^-16/sqrt(12)/sqrt(588)/h^2) while the +-1.5 mm window stays inside the bearing.
STENCIL_SPACING_MM = 0.5


def stencil_coordinates(spacing_mm: float = STENCIL_SPACING_MM) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(s, t)`` of the 49 stencil samples in mm, in the documented order."""
    k = np.arange(STENCIL_SIZE) % STENCIL_SIDE
    j = np.arange(STENCIL_SIZE) // STENCIL_SIDE
    half = STENCIL_SIDE // 2
    return (k - half) * spacing_mm, (j - half) * spacing_mm
