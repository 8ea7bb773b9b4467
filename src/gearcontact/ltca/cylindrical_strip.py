"""The strip across a cylindrical pair's contact lines in the loaded TE: its half-width
from the Hertz width of the load, widened for end-loaded lines (docs/cylindrical.md
sec. 7, "Grid and gap" and "End-loaded lines"; :mod:`.cylindrical_lte`).

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, eq. 4.43 (line-contact half-width).
"""

from __future__ import annotations

import math

import numpy as np

from ..analytic.face_load import EndLoadedLine, end_loaded_line
from ..geometry.cylindrical.pair import CylindricalPair
from ..tca.cylindrical_cycle import CylindricalMeshCycle, LineGaps
from ..validation import InputRangeError

__all__ = ["END_PEAK_MARGIN", "across_extent_mm", "end_loaded_peak_n_per_mm", "wedge_line"]

#: The strip of an end-loaded mesh is sized for this many times the closed form's peak
#: line load: the LCP's rows at a loaded face end carry 1.2-4.9 times it (the sharp
#: end's singular load, growing with refinement; spur 20/40 at 300 um, 40-640 rows), and
#: a loaded cell on the strip's border truncates the contact across.
END_PEAK_MARGIN = 2.0


def across_extent_mm(pair: CylindricalPair, cycle: CylindricalMeshCycle, load_n: float,
                      e_star: float, factor: float, lines: LineGaps | None = None) -> float:
    """Half-width of the strip: ``factor`` Hertz half-widths of the whole load on the
    shortest total line length (Johnson 1985 eq. 4.43, b = sqrt(4 w R / (pi E*))); with
    ``lines`` (the widened strip of an end-loaded mesh, module docstring) of
    :data:`END_PEAK_MARGIN` times the largest peak line load of an end-loaded line
    (:func:`end_loaded_peak_n_per_mm`) where that is more."""
    g = pair.geometry
    cb = math.cos(math.radians(g.base_helix_angle_deg))
    u_mid = 0.5 * g.centre_distance_mm * math.sin(math.radians(g.working_pressure_angle_deg))
    r = u_mid / (2.0 * cb)                       # equal roll lengths: the largest R
    w = load_n / max(float(cycle.line_length_mm.min()), 1e-3)
    if lines is not None:
        w = max(w, END_PEAK_MARGIN * end_loaded_peak_n_per_mm(lines, load_n, r, e_star, cb))
    return factor * math.sqrt(4.0 * w * r / (math.pi * e_star))


def end_loaded_peak_n_per_mm(lines: LineGaps, load_n: float, radius_mm: float,
                             e_star: float, cos_beta_b: float) -> float:
    """The largest peak line load (N/mm) of :func:`wedge_line` over the lines of
    ``lines``, each carrying the whole ``load_n`` (N) with the relative radius
    ``radius_mm`` across it; 0 where no line is end-loaded."""
    z = np.broadcast_to(lines.z_mm, lines.gap_mm.shape)
    peak = 0.0
    for j, k in zip(*np.nonzero(np.isfinite(lines.gap_mm).sum(axis=-1) >= 2)):
        on = np.isfinite(lines.gap_mm[j, k])
        y = z[j, k][on] / cos_beta_b
        res = wedge_line(y, cos_beta_b * lines.gap_mm[j, k][on],
                         float(y[-1] - y[0] + (y[1] - y[0])), load_n=load_n,
                         b_max_per_mm=0.5 / radius_mm, e_prime_mpa=2.0 * e_star)
        if res is not None and res.end_loaded:
            peak = max(peak, res.peak_line_load_n_per_mm)
    return peak


def wedge_line(y_mm: np.ndarray, gap_mm: np.ndarray, length_mm: float, *, load_n: float,
               b_max_per_mm: float, e_prime_mpa: float) -> EndLoadedLine | None:
    """The end-loaded line's closed form (:func:`~gearcontact.analytic.face_load.
    end_loaded_line`) of a line whose normal gap ``gap_mm`` (mm, at the positions
    ``y_mm`` along it, ascending) is least at one of its ends: the gap's least-squares
    slope from that end (the misalignment's wedge; crowning leaves less). None where the
    least gap lies inside the line (crowning or relief centre the load) or the slope
    leaves the line law's range (a point's contact)."""
    if gap_mm.size < 2 or int(np.argmin(gap_mm)) not in (0, gap_mm.size - 1):
        return None
    slope = abs(float(np.polyfit(y_mm, gap_mm, 1)[0]))
    try:
        return end_loaded_line(load_n=load_n, slope=slope, length_mm=length_mm,
                               b_max_per_mm=b_max_per_mm, e_prime_mpa=e_prime_mpa)
    except InputRangeError:
        return None
