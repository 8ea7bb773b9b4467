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
from ..geometry.cylindrical.iso21771 import inv
from ..geometry.cylindrical.kinematics import ParallelKinematics
from ..geometry.cylindrical.pair import CylindricalPair
from ..validation import InputRangeError
from .line_contact import LineContactResult, line_contact
from .types import ContactGuess

__all__ = ["cylindrical_line_contact", "parallel_kinematics", "pitch_point_guess"]


def parallel_kinematics(pair: CylindricalPair, *, with_errors: bool = True
                        ) -> ParallelKinematics:
    """The meshing kinematics of ``pair`` at its centre distance a_w, with the axis
    misalignment of its ``[assembly]`` table as angles f / b over the common face width
    (``with_errors=False``: aligned)."""
    a, b = pair.assembly, pair.geometry.face_width_mm
    scale = 1e-3 / b if with_errors else 0.0            # um over b mm -> rad
    return ParallelKinematics(centre_distance_mm=pair.geometry.centre_distance_mm,
                              ratio=pair.ratio, gear_teeth=pair.gear_teeth,
                              axis_inclination_rad=a.axis_inclination_um * scale,
                              axis_deviation_rad=a.axis_deviation_um * scale)


def pitch_point_guess(pair: CylindricalPair, facing: str) -> ContactGuess:
    """The contact state of the ``facing`` flank pair at the pitch point, exact for
    unmodified flanks at zero backlash (a start for the solvers otherwise).

    At ``phi1 = 0`` the pinion tooth is centred on the line of centres, so its flank
    crosses the working pitch circle half the working tooth thickness away, at
    ``∓ s_w1 / d_w1`` with ``s_w1 = d_w1 (s_t1 / d1 + inv α_t - inv α_wt)`` (ISO 21771):
    the flank passes the pitch point after a turn ``phi1 = ∓ s_w1 / d_w1`` (cw facing:
    -), and ``phi2 = phi1 / u``, less one gear pitch ``2π / z2`` for the ccw facing (the
    gear body's tooth sits below the line of centres at ``phi2 = 0``, the one that meets
    the pinion's ccw flank above it). Roll lengths there ``r_w sin α_wt``.
    """
    g = pair.geometry
    alpha_wt = math.radians(g.working_pressure_angle_deg)
    alpha_t = math.radians(g.transverse_pressure_angle_deg)
    m_t = g.transverse_module_mm
    s_t1 = m_t * (0.5 * math.pi + 2.0 * pair.profile_shift_pinion
                  * math.tan(math.radians(g.normal_pressure_angle_deg)))
    d1, dw1 = g.reference_diameter_pinion_mm, g.working_pitch_diameter_pinion_mm
    half = (s_t1 / d1 + inv(alpha_t) - inv(alpha_wt))      # s_w1 / d_w1, rad
    phi1 = -half if facing == "cw" else half
    return ContactGuess(u1=0.5 * dw1 * math.sin(alpha_wt), v1=0.0,
                        u2=0.5 * g.working_pitch_diameter_gear_mm * math.sin(alpha_wt),
                        v2=0.0, phi1_rad=phi1, phi2_rad=phi1 / pair.ratio
                        - (0.0 if facing == "cw" else 2.0 * math.pi / pair.gear_teeth))


def cylindrical_line_contact(pair: CylindricalPair, *, facing: str = "cw", phases: int = 61,
                             line_points: int = 25) -> LineContactResult:
    """Contact line at the pitch point and TE0 over one pitch of the ``facing`` flanks
    (pinion and gear flanks of that facing mesh, :mod:`~gearcontact.geometry.cylindrical.kinematics`).

    Meaningful for unmodified flanks (line contact); a modified pair has point contact.
    """
    if facing not in FACINGS:
        raise InputRangeError("facing", facing, f"one of {FACINGS}")
    start = pitch_point_guess(pair, facing)
    return line_contact(involute_flank(pair, "pinion", facing),
                        involute_flank(pair, "gear", facing), parallel_kinematics(pair), start,
                        pinion_teeth=pair.pinion_teeth, phases=phases, line_points=line_points)
