"""The bearing's depth against the flank's (docs/machine_settings.md sec. 5, "The
bearing's depth: room against need", session 29): how much of the pinion flank's working
depth a synthesized bearing needs over one transmitted pitch, beside how much the flank
has, to first order at the pivot M.

The synthesis centres the transmitted pitch on M (the TE0 vertex at M), so over the
pitch the contact travels along its path ``D = (2 pi / z1) |du1/dphi1|`` of the depth
coordinate ``u`` (root to tip; the rate from the candidate's local TCA at M,
:func:`~.setting_room_margin.depth_rate_per_rad`), and at every phase its paint ellipse
(semi-axes ``a``, ``b`` along the principal directions, mapped onto the flank to first
order, :func:`~.stencil.tangent_parameters`: ``du/ds``, ``du/dt``) spans ``+-h`` of depth
about the contact with

    h = sqrt((a du/ds)^2 + (b du/dt)^2)

(the largest ``u`` of ``a cos(t) du/ds + b sin(t) du/dt``). The **need** is
``N = D + 2 h``, the **room** the flank box's working depth ``W = u_tip - u_root``.
``N > W`` says, to first order, that no placement of this bearing in depth holds it
inside the flank at every phase of the pitch. With the width ``b`` held (the ellipse
shortened by the lengthwise curvature), the longest ellipse whose band fits is

    2a' = 2 sqrt(((W - D) / 2)^2 - (b du/dt)^2) / |du/ds|

(:meth:`DepthNeed.fitting_length_mm`); where that is shorter than the shortest ellipse
the targets allow (0.1 of the gear face), or does not exist (the travel and the width
alone fill the depth), no ellipse length in the targets' range holds this path's bearing
(:meth:`DepthNeed.verdict`). The gear's edges and the face (toe, heel) are not measured.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .curvature import contact_ellipse, relative_curvature
from .mating import solve_mating_point
from .setting_room_margin import depth_rate_per_rad
from .stencil import tangent_frame, tangent_parameters

__all__ = ["DepthNeed", "depth_need", "ellipse_depth_half_mm"]


def ellipse_depth_half_mm(semi_major_mm: float, semi_minor_mm: float, du_ds: float,
                          du_dt: float) -> float:
    """``h = sqrt((a du/ds)^2 + (b du/dt)^2)``, mm: the ellipse's half extent in the
    depth coordinate ``u`` (module docstring)."""
    return float(math.hypot(semi_major_mm * du_ds, semi_minor_mm * du_dt))


@dataclass(frozen=True)
class DepthNeed:
    """The bearing's depth over one pitch against the flank's (module docstring).

    Attributes
    ----------
    travel_mm : float
        ``D``: the contact's depth travel over one pitch, mm of ``u``.
    semi_major_mm, semi_minor_mm : float
        The paint ellipse's ``a`` and ``b`` at M, mm.
    du_ds, du_dt : float
        Depth per mm along its major and minor axes at M.
    room_mm : float
        ``W``: the pinion flank box's working depth, mm.
    shortest_mm : float
        The shortest ellipse the targets allow (0.1 of the gear face), mm.
    """

    travel_mm: float
    semi_major_mm: float
    semi_minor_mm: float
    du_ds: float
    du_dt: float
    room_mm: float
    shortest_mm: float

    @property
    def half_mm(self) -> float:
        """``h``: the ellipse's half extent in depth, mm."""
        return ellipse_depth_half_mm(self.semi_major_mm, self.semi_minor_mm, self.du_ds,
                                     self.du_dt)

    @property
    def need_mm(self) -> float:
        """``N = D + 2 h``, mm."""
        return self.travel_mm + 2.0 * self.half_mm

    def fitting_length_mm(self) -> float:
        """``2a'``, mm: the longest ellipse (the width ``b`` held) whose band fits the
        depth, ``2 sqrt(((W - D) / 2)^2 - (b du/dt)^2) / |du/ds|``; ``inf`` where
        ``du/ds`` is 0 (the length takes no depth) and the rest fits; 0 where none
        does."""
        left = 0.5 * (self.room_mm - self.travel_mm)
        width = abs(self.semi_minor_mm * self.du_dt)
        if not left > width:
            return 0.0
        if self.du_ds == 0.0:
            return math.inf
        return 2.0 * math.sqrt(left * left - width * width) / abs(self.du_ds)

    def verdict(self) -> str:
        """``"fits"`` (``N <= W``: edge phases are the bearing's placement, not its
        size), ``"shorter"`` (``N > W`` and an ellipse of :meth:`fitting_length_mm`, at
        least :attr:`shortest_mm`, fits) or ``"none"`` (no ellipse of at least
        :attr:`shortest_mm` fits)."""
        if not self.need_mm > self.room_mm:
            return "fits"
        return "shorter" if self.fitting_length_mm() >= self.shortest_mm else "none"

    def text(self) -> str:
        """Room against need, in words (the head comment's)."""
        words = (f"depth over a pitch: the contact travels {self.travel_mm:.2f} mm and the "
                 f"paint ellipse (2a {2.0 * self.semi_major_mm:.2f} mm) spans "
                 f"{2.0 * self.half_mm:.2f} mm, {self.need_mm:.2f} mm against the flank's "
                 f"{self.room_mm:.2f} mm")
        said = self.verdict()
        if said == "fits":
            return words + ": it fits; its edge phases are where it lies, not its size"
        if said == "shorter":
            return words + (": no placement holds it; an ellipse of "
                            f"{self.fitting_length_mm():.2f} mm would fit")
        span = 2.0 * ellipse_depth_half_mm(0.5 * self.shortest_mm, self.semi_minor_mm,
                                           self.du_ds, self.du_dt)
        return words + (f": no placement holds it, nor with any ellipse of at least "
                        f"{self.shortest_mm:.2f} mm (the targets' least), whose span "
                        f"{span:.2f} mm with the travel exceeds the depth")


def depth_need(pinion, gear, pair, start, *, shortest_mm: float) -> DepthNeed:
    """:class:`DepthNeed` of ``pinion`` and ``gear`` at the contact through ``start``
    (the pivot M): the travel from the local TCA at M
    (:func:`~.setting_room_margin.depth_rate_per_rad`), the paint ellipse
    (:func:`~.curvature.contact_ellipse`) and its axes' depth rates at M's contact.

    Raises
    ------
    ArithmeticError
        The contact leaves a flank within two local steps of M.
    """
    kin = pair.kinematics()
    rate = depth_rate_per_rad(pinion, gear, pair, start)
    mp = solve_mating_point(pinion, gear, kin, start)
    ell = contact_ellipse(relative_curvature(pinion, gear, kin, mp))
    axes = tangent_frame(pinion, gear, kin, mp, "principal")
    uv = tangent_parameters(pinion, kin.pinion_pose(mp.phi1_rad), axes, (mp.u1, mp.v1),
                            np.eye(2))
    (u0, u1), _ = pinion.u_range, pinion.v_range
    return DepthNeed(2.0 * math.pi / pair.pinion_teeth * abs(rate),
                     float(ell.semi_major_mm), float(ell.semi_minor_mm),
                     float(uv[0, 0] - mp.u1), float(uv[1, 0] - mp.u1), float(u1 - u0),
                     float(shortest_mm))
