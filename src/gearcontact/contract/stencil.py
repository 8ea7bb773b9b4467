"""Geometry of the hardware curvature-fit stencil (stage C) and its file format.

The datapath fits a quadratic to ``N = 49`` gap samples on a fixed 7 x 7 grid in the
local tangent frame (s, t) centred on the contact point (docs/spec.md sec. 6, Algorithm 2).
The grid is a compile-time constant: its pseudo-inverse is baked into a ROM, so the
spacing below is part of the hardware contract: the host's TCA samples the gap on it and
stage C fits it, so it lives below both (the former ``gearcontact.contract.stencil``
is a deprecated alias).

Sample order (row-major, s fastest)::

    i = 7 * j + k,  s_i = (k - 3) * STENCIL_SPACING_MM,  t_i = (j - 3) * STENCIL_SPACING_MM

File format (``gap_stencil.csv``, read by ``gearcontact preview --stencil``): a CSV with
the header ``s_mm,t_mm,gap_mm`` and 49 rows in the order above; ``s_mm``/``t_mm`` must
match the baked grid to 1e-9 mm, ``gap_mm`` is the separation along the common normal
(mm, positive = open).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..validation import InputRangeError, check_array_finite

__all__ = ["STENCIL_SIDE", "STENCIL_SIZE", "STENCIL_SPACING_MM", "stencil_coordinates",
           "read_stencil_csv", "write_stencil_csv"]

STENCIL_SIDE = 7
STENCIL_SIZE = STENCIL_SIDE * STENCIL_SIDE
#: Grid spacing of the baked stencil, mm. The +-0.6 mm window must stay on the flank of
#: a small-module tooth (s0003: working depth ~2.2 mm; at 0.5 mm spacing 22 of 49 samples
#: fell off the flank and the fit read B- 41 % high from higher-order gap terms), while
#: the quantization error of the fitted curvature stays small: with the degree-6 ROM and
#: STENCIL_GAP Q(32,21) samples sigma_c3 = 2^-21/sqrt(12) ||M_c3||_2 = 2^-21/sqrt(12)
#: 17.15 1/mm^2 = 2.4e-6 1/mm at h = 0.2 mm (0.13 % of s0003's B-).
STENCIL_SPACING_MM = 0.2


def stencil_coordinates(spacing_mm: float = STENCIL_SPACING_MM) -> tuple[np.ndarray, np.ndarray]:
    """Return ``(s, t)`` of the 49 stencil samples in mm, in the documented order."""
    k = np.arange(STENCIL_SIZE) % STENCIL_SIDE
    j = np.arange(STENCIL_SIZE) // STENCIL_SIDE
    half = STENCIL_SIDE // 2
    return (k - half) * spacing_mm, (j - half) * spacing_mm


def write_stencil_csv(path, gaps_mm, *, spacing_mm: float = STENCIL_SPACING_MM) -> Path:
    """Write 49 gap samples (mm, stencil order) in the documented CSV format.

    Raises
    ------
    InputRangeError
        Not exactly 49 samples, or a non-finite sample (named by index).
    """
    g = check_array_finite("gap_mm", gaps_mm).ravel()
    if g.size != STENCIL_SIZE:
        raise InputRangeError("stencil length", g.size, f"exactly {STENCIL_SIZE} samples")
    s, t = stencil_coordinates(spacing_mm)
    lines = ["s_mm,t_mm,gap_mm"] + [f"{a:.9f},{b:.9f},{c:.12e}" for a, b, c in zip(s, t, g)]
    path = Path(path)
    path.write_text("\n".join(lines) + "\n")
    return path


def read_stencil_csv(path, *, spacing_mm: float = STENCIL_SPACING_MM) -> np.ndarray:
    """Read a stencil CSV and return its 49 gaps (mm) in stencil order.

    The ``s_mm``/``t_mm`` columns must equal the baked grid to 1e-9 mm: a stencil on
    another grid would be fitted with the wrong pseudo-inverse.

    Raises
    ------
    InputRangeError
        The file is missing, not a regular file or not UTF-8 text; wrong header, wrong
        number of rows, off-grid coordinates or non-finite gaps (the file is named).
    """
    path = Path(path)
    if not path.is_file():
        raise InputRangeError("stencil file", str(path),
                              "an existing regular file (CSV s_mm,t_mm,gap_mm)")
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise InputRangeError(f"{path.name} (byte {exc.start})",
                              exc.object[exc.start:exc.start + 4], "UTF-8 text") from None
    except OSError as exc:
        raise InputRangeError("stencil file", str(path), f"a readable file ({exc.strerror})") \
            from None
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    if not lines or [h.strip() for h in lines[0].split(",")] != ["s_mm", "t_mm", "gap_mm"]:
        raise InputRangeError(f"{path.name}: header", lines[0] if lines else "",
                              "'s_mm,t_mm,gap_mm'")
    rows = lines[1:]
    if len(rows) != STENCIL_SIZE:
        raise InputRangeError(f"{path.name}: number of samples", len(rows),
                              f"exactly {STENCIL_SIZE}")
    try:
        data = np.array([[float(x) for x in r.split(",")] for r in rows])
    except ValueError as exc:
        raise InputRangeError(f"{path.name}: row", str(exc), "three numbers per row") from None
    if data.shape != (STENCIL_SIZE, 3):
        raise InputRangeError(f"{path.name}: columns", data.shape[1:], "3 (s_mm, t_mm, gap_mm)")
    bad = np.argwhere(~np.isfinite(data))      # a NaN coordinate passes every |x - s| test
    if bad.size:
        i, j = (int(k) for k in bad[0])
        raise InputRangeError(f"{path}: row {i + 1} (sample {i}), column "
                              f"{('s_mm', 't_mm', 'gap_mm')[j]}", float(data[i, j]),
                              "a finite number")
    s, t = stencil_coordinates(spacing_mm)
    off = np.flatnonzero((np.abs(data[:, 0] - s) > 1e-9) | (np.abs(data[:, 1] - t) > 1e-9))
    if off.size:
        i = int(off[0])
        raise InputRangeError(f"{path.name}: sample {i} (s_mm, t_mm)",
                              (data[i, 0], data[i, 1]), f"the baked grid point ({s[i]:g}, {t[i]:g})")
    return check_array_finite(f"{path.name}: gap_mm", data[:, 2])
