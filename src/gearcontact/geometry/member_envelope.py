"""The node solver of either member's cut flank on its sheet, for the setting fit.

The setting fit (:mod:`.setting_fit`) compares a flank cut from trial settings with a
target at nodes ``(u, v)`` of the member's sheet, whose axial position and radius are
fixed, so that two flanks differ only in their angle ``psi`` about the member's axis:

- pinion: the :class:`~.sheet.PinionCone` of the blank (axial position ``v``, radius
  ``R_f(v) + u``, :func:`~.conjugate.nominal_pinion_box`); the generated envelope
  (:class:`~.generated.EnvelopeSolver`);
- generated gear (ratio of roll or helical motion): the :class:`~.sheet.GearCone` of
  the blank (``u`` above the root along the pitch-cone normal, ``v`` cone distance from
  the mean section, :func:`~.generated.gear_cone`); the same envelope;
- formate gear (no roll, no helical motion): the same cone; the flank is the blade's
  surface of revolution at zero roll (:func:`~.generated.formate_gear_flank`), so the
  node equations are the envelope's with the meshing equation ``n . dX/dpsi = 0``
  replaced by ``psi = 0`` (:class:`FormateSolver`: unknowns blade arc length and blade
  angle, the roll held at the cutting position). Unlike the cone of
  :class:`~.formate.FormateFlank` it takes any blade profile, and its ``(u, v)`` are
  the gear sheet's, the nodes of a measured gear flank.

The angular coordinate of a body point and the lever ``R (e_psi . n)`` that turns an
angle difference into a normal distance are :func:`angle_lever`'s.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.1
(envelopes), ch. 20 (formate and generated gears).
"""

from __future__ import annotations

import numpy as np

from .blank import BlankDesign
from .conjugate import nominal_pinion_box
from .generated import EnvelopeSolver, gear_cone
from .machine import MachineSetup

__all__ = ["FormateSolver", "angle_lever", "mean_node_uv", "member_cone", "member_solver"]


class FormateSolver(EnvelopeSolver):
    """Node equations of a formate gear flank on the gear sheet: the blade point at
    sheet height and radius with the roll held at 0 (module docstring); the third
    equation ``psi = 0`` takes the place of the meshing function."""

    def place(self, x_t, n_t, psi_rad):
        x, n, _ = super().place(x_t, n_t, psi_rad)
        return x, n, np.broadcast_to(np.asarray(psi_rad, dtype=float), x.shape[:-1])


def member_cone(member: str, blank: BlankDesign):
    """The sheet cone of ``member``'s flanks (module docstring)."""
    if member == "pinion":
        return nominal_pinion_box(blank, 1.0)[0]
    return gear_cone(blank)


def member_solver(setup: MachineSetup, blank: BlankDesign, cone) -> EnvelopeSolver:
    """The node solver of the flank ``setup`` cuts on ``cone``: :class:`FormateSolver`
    for a formate gear, :class:`~.generated.EnvelopeSolver` otherwise."""
    if setup.member == "gear" and setup.settings.formate:
        return FormateSolver(setup, blank, cone)
    return EnvelopeSolver(setup, blank, cone)


def mean_node_uv(member: str, blank: BlankDesign, cone) -> tuple[float, float]:
    """Sheet parameters of ``member``'s mean node (pitch cone, mean section), mm."""
    if member == "pinion":
        return float(cone.root_offset_mm), float(blank.pitch_point_mm[0])
    return float(blank.dedendum_gear_mm), 0.0


def angle_lever(member: str, r, n) -> tuple[np.ndarray, np.ndarray]:
    """``(psi, lever_um)`` of body points ``r`` (..., 3) with unit normals ``n``: the
    angle about ``member``'s axis (pinion ``x``, gear ``z``) and ``1e3 R (e_psi . n)``,
    um per rad (a flank turned by ``dpsi`` about the axis moves ``lever * dpsi`` along
    ``n``)."""
    b, c = (1, 2) if member == "pinion" else (0, 1)
    psi = np.arctan2(r[..., c], r[..., b])
    rad = np.hypot(r[..., b], r[..., c])
    e_psi = np.zeros(np.shape(psi) + (3,))
    e_psi[..., b], e_psi[..., c] = -np.sin(psi), np.cos(psi)
    return psi, 1e3 * rad * np.einsum("...i,...i->...", e_psi, n)
