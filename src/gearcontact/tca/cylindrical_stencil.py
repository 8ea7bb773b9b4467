"""The preview's inputs on the contact of a cylindrical pair: per phase and tooth pair
the 7 x 7 stage-C gap stencil, the exact curvatures, the contact-line length, lever and
opening (docs/cylindrical.md sec. 8).

At the least-gap point of each pair's contact line (:func:`~.cylindrical_cycle.
pair_contact_points`) the stencil is the gap between the posed involute flanks along
the common normal on the baked 7 x 7 grid of :mod:`gearcontact.contract.stencil`
(:func:`~.stencil.hardware_stencil`, flank frame); a window reaching beyond the flank
(the least-gap point of an unmodified line can sit at a face end, a line at the tip or
form circle) is the osculating quadric of the gap at that point, ``off_flank =
"quadric"``, the hypoid pipeline's rule. Unmodified flanks are cylinders in contact
along the line: A- = 1 / (2 R) with the normal-section relative radius ``R`` (ISO
6336-2) and B- = 0; lead crowning makes B- small and positive, an ellipse far longer
than the face, which the line core of stage D truncates to the line
(:mod:`gearcontact.preview.hertz.line`).

Contact-line length ``L``: the pair's line in the zone of action (the cycle's solved
ends), the length the line core truncates a longer ellipse to. Lever and opening as
:mod:`gearcontact.ltca.cylindrical_lte`: ``r_b2 cos(beta_b)`` about the gear axis and
``cos(beta_b) (g_j - min g)`` along the normal.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contract.stencil import STENCIL_SIZE
from ..geometry.cylindrical.flank import involute_flank
from ..geometry.cylindrical.pair import CylindricalPair
from .curvature import relative_curvature
from ..validation import InputRangeError
from .cylindrical_cycle import (CONTACT_TOLERANCE_MM, CylindricalMeshCycle, LineGaps,
                                contact_line_gaps, pair_contact_points)
from .parallel_axes import parallel_kinematics
from .stencil import hardware_stencil

__all__ = ["CylindricalStencils", "cylindrical_stencils", "contact_line_slices",
           "LINE_SLICES"]

#: Equal slices of each contact line at whose centres the ease-off along the line is
#: sampled for the twin's line law (docs/cylindrical.md sec. 10): on the EV example 16
#: and 64 give static rotations within 1 % of each other.
LINE_SLICES = 16


@dataclass(frozen=True)
class CylindricalStencils:
    """Preview inputs per tooth pair and phase of a cylindrical mesh cycle.

    Shapes (P, K) as the cycle's (``pair_offsets`` x phases); entries where ``valid`` is
    False hold zeros.

    Attributes
    ----------
    phi1_rad : ndarray (K,)
    pair_offsets : tuple of int
    valid : ndarray (P, K) of bool
        The pair has a contact line in the zone of action.
    in_contact : ndarray (P, K) of bool
        Its closed gap is within :data:`~.cylindrical_cycle.CONTACT_TOLERANCE_MM`
        (touching, unloaded).
    gaps_mm : ndarray (P, K, 49)
        Stage-C stencil in the order of :mod:`gearcontact.contract.stencil`, mm.
    on_flank : ndarray (P, K) of bool
        The whole window lay on both flanks (else it is the osculating quadric).
    A_minus_per_mm, B_minus_per_mm : ndarray (P, K)
        Exact half relative principal curvatures at the point (shape operators), 1/mm.
    line_length_mm : ndarray (P, K)
        Length of the pair's contact line in the zone of action, mm.
    opening_mm : ndarray (P, K)
        Normal separation with the gear resting on the transmitting pair, mm.
    lever_mm : float
        Lever of the normal about the gear axis, ``r_b2 cos(beta_b)``, mm.
    """

    phi1_rad: np.ndarray
    pair_offsets: tuple[int, ...]
    valid: np.ndarray
    in_contact: np.ndarray
    gaps_mm: np.ndarray
    on_flank: np.ndarray
    A_minus_per_mm: np.ndarray
    B_minus_per_mm: np.ndarray
    line_length_mm: np.ndarray
    opening_mm: np.ndarray
    lever_mm: float


def cylindrical_stencils(pair: CylindricalPair, cycle: CylindricalMeshCycle
                         ) -> CylindricalStencils:
    """Stencil, curvatures, line length and opening of every pair at every phase of
    ``cycle`` (module docstring).

    Parameters
    ----------
    pair : CylindricalPair
        The pair ``cycle`` was computed for.
    cycle : CylindricalMeshCycle
    """
    points = pair_contact_points(pair, cycle)
    kin = parallel_kinematics(pair)
    pinion = involute_flank(pair, "pinion", cycle.facing)
    gear = involute_flank(pair, "gear", cycle.facing)
    shape = cycle.gap_min_mm.shape
    valid = np.zeros(shape, bool)
    on_flank = np.zeros(shape, bool)
    gaps = np.zeros(shape + (STENCIL_SIZE,))
    a_minus, b_minus = np.zeros(shape), np.zeros(shape)
    for j, row in enumerate(points):
        for k, mp in enumerate(row):
            if mp is None:
                continue
            field = hardware_stencil(pinion, gear, kin, mp, off_flank="quadric")
            rc = relative_curvature(pinion, gear, kin, mp)
            valid[j, k] = True
            on_flank[j, k] = bool(field.on_flank.all())
            gaps[j, k] = field.gap_mm.ravel()
            a_minus[j, k], b_minus[j, k] = rc.A_minus_per_mm, rc.B_minus_per_mm
    g = pair.geometry
    cb = math.cos(math.radians(g.base_helix_angle_deg))
    ends = cycle.line_ends_mm
    length = np.where(valid, np.linalg.norm(ends[..., 1, :] - ends[..., 0, :], axis=-1), 0.0)
    # from the mesh's closing gap: a tip edge touching first leaves every line open
    closed = cycle.gap_min_mm - cycle.closing_gap_mm[None, :]
    opening = np.where(valid, cb * np.where(valid, closed, 0.0), 0.0)
    return CylindricalStencils(
        phi1_rad=cycle.phi1_rad, pair_offsets=cycle.pair_offsets, valid=valid,
        in_contact=valid & (closed <= CONTACT_TOLERANCE_MM), gaps_mm=gaps,
        on_flank=on_flank, A_minus_per_mm=a_minus, B_minus_per_mm=b_minus,
        line_length_mm=length, opening_mm=opening,
        lever_mm=0.5 * g.base_diameter_gear_mm * cb)


def contact_line_slices(pair: CylindricalPair, cycle: CylindricalMeshCycle, *,
                        slices: int = LINE_SLICES) -> LineGaps:
    """The gap along every pair's contact line at the centres of ``slices`` (an integer
    >= 2) equal slices between the line's solved ends: :func:`~.cylindrical_cycle.
    contact_line_gaps` at each line's own axial positions (``z_mm`` (P, K, slices);
    NaN where the pair has no line). The line is straight, so equal in ``z`` is equal
    along it."""
    if isinstance(slices, bool) or int(slices) != slices or slices < 2:
        raise InputRangeError("slices", slices, "an integer >= 2")
    ends = cycle.line_ends_zu_mm[..., 0]
    lo, hi = np.min(ends, axis=-1), np.max(ends, axis=-1)
    t = (np.arange(int(slices)) + 0.5) / int(slices)
    return contact_line_gaps(pair, cycle, lo[..., None] + (hi - lo)[..., None] * t)
