"""Unloaded TCA of a cylindrical (parallel-axis) pair on the crossed-axis solvers.

The mating-point and contact-line solvers of :mod:`.mating` and :mod:`.line_contact`
take any kinematics of the :class:`~gearcontact.geometry.kinematics.MeshKinematics`
interface; :class:`~gearcontact.geometry.cylindrical.kinematics.ParallelKinematics` is
that of a parallel-axis pair. Unmodified involute helicoids are conjugate: they touch
along a straight line in the plane of action, of length ``b / cos β_b`` where it
crosses the whole face, and the transmission error vanishes (ISO 21771; Litvin &
Fuentes 2004, ch. 14). :func:`cylindrical_line_contact` follows that line from the
pitch point over one pinion pitch (docs/cylindrical.md sec. 5).
"""

from __future__ import annotations

import math

from ..geometry.cylindrical.flank import FACINGS, involute_flank
from ..geometry.cylindrical.kinematics import ParallelKinematics
from ..geometry.cylindrical.pair import CylindricalPair
from ..validation import InputRangeError
from .line_contact import LineContactResult, line_contact
from .types import ContactGuess

__all__ = ["cylindrical_line_contact", "parallel_kinematics"]


def parallel_kinematics(pair: CylindricalPair) -> ParallelKinematics:
    """The meshing kinematics of ``pair`` at its centre distance a_w."""
    return ParallelKinematics(centre_distance_mm=pair.geometry.centre_distance_mm,
                              ratio=pair.ratio, gear_teeth=pair.gear_teeth)


def cylindrical_line_contact(pair: CylindricalPair, *, facing: str = "cw", phases: int = 61,
                             line_points: int = 25) -> LineContactResult:
    """Contact line at the pitch point and TE0 over one pitch of the ``facing`` flanks
    (pinion and gear flanks of that facing mesh, :mod:`~gearcontact.geometry.cylindrical.kinematics`).

    Meaningful for unmodified flanks (line contact); a modified pair has point contact.
    """
    if facing not in FACINGS:
        raise InputRangeError("facing", facing, f"one of {FACINGS}")
    g = pair.geometry
    alpha_wt = math.radians(g.working_pressure_angle_deg)
    start = ContactGuess(u1=0.5 * g.working_pitch_diameter_pinion_mm * math.sin(alpha_wt),
                         v1=0.0, u2=0.5 * g.working_pitch_diameter_gear_mm * math.sin(alpha_wt),
                         v2=0.0, phi1_rad=0.0, phi2_rad=0.0)
    return line_contact(involute_flank(pair, "pinion", facing),
                        involute_flank(pair, "gear", facing), parallel_kinematics(pair), start,
                        pinion_teeth=pair.pinion_teeth, phases=phases, line_points=line_points)
