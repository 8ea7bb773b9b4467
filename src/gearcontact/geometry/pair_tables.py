"""The ``[cutter]`` and ``[easeoff.*]`` tables of a pair file as typed, validated
dataclasses, and the design table's pinion face width check (the format:
:mod:`.pair`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError, check_positive, check_range
from .print_words import INCH_MM


@dataclass(frozen=True)
class CutterSpec:
    """Face-milling cutter head with one inside and one outside blade.

    Parameters
    ----------
    radius_mm : float
        Nominal cutter radius r_c0, mm: the slot centre line at the pitch plane.
    point_width_mm : float
        Blade point width W at the blade tip, mm.
    edge_radius_mm : float
        Blade tip edge radius, mm, in [0, W/2): the flank starts above the edge round.
    pressure_angle_drive_deg, pressure_angle_coast_deg : float
        Nominal design pressure angles alpha_dD, alpha_dC, degrees, in [5, 40].
    limit_pressure_angle_factor : float
        f_alim in [0, 1]: share of alpha_lim moved between the sides (ISO 23509).
    """

    radius_mm: float
    point_width_mm: float
    edge_radius_mm: float
    pressure_angle_drive_deg: float = 20.0
    pressure_angle_coast_deg: float = 20.0
    limit_pressure_angle_factor: float = 1.0

    def __post_init__(self):
        check_positive("cutter.radius_mm", self.radius_mm)
        check_positive("cutter.point_width_mm", self.point_width_mm)
        check_range("cutter.edge_radius_mm", self.edge_radius_mm, 0.0,
                    0.5 * self.point_width_mm, hi_open=True)
        check_range("cutter.pressure_angle_drive_deg", self.pressure_angle_drive_deg, 5.0, 40.0)
        check_range("cutter.pressure_angle_coast_deg", self.pressure_angle_coast_deg, 5.0, 40.0)
        check_range("cutter.limit_pressure_angle_factor", self.limit_pressure_angle_factor,
                    0.0, 1.0)


@dataclass(frozen=True)
class EaseOffCoefficients:
    """Five-term pinion ease-off ``E = c_PA eta + c_SA xi + c_PC eta^2 + c_LC xi^2 + c_TW xi eta``.

    E in um; xi (lengthwise, along the pinion axis) and eta (profile, radial) in mm from
    the mean point; see :mod:`gearcontact.geometry.easeoff`.
    """

    profile_angle_um_per_mm: float = 0.0
    spiral_angle_um_per_mm: float = 0.0
    profile_crowning_um_per_mm2: float = 0.0
    lengthwise_crowning_um_per_mm2: float = 0.0
    bias_um_per_mm2: float = 0.0

    def __post_init__(self):
        for name in self.__dataclass_fields__:
            check_range(f"easeoff.{name}", getattr(self, name), -1e3, 1e3)

    @property
    def is_zero(self) -> bool:
        """True if every coefficient is exactly zero (conjugate pinion)."""
        return all(getattr(self, n) == 0.0 for n in self.__dataclass_fields__)


def check_face_within_cone(face_mm: float, cone_mm: float, *, size_key: str,
                           size_value: float) -> None:
    """The gear face width less than the gear mean cone distance ``cone_mm`` (derived from
    the typed ``size_key = size_value``), else an :class:`InputRangeError` naming both keys
    (either may be the slip), with the unit a size typed in inches or metres would have
    needed: where the face is 0.1 to 0.5 of the converted cone distance (a plausible
    bevel blank; ISO 23509's keep the face near 0.3 of the cone distance), so that a
    face too wide for a cone distance typed right gets no unit hint."""
    if face_mm < cone_mm:
        return
    unit = next((f"; {size_key} typed in {name}? x {k:g} = {k * size_value:.4g} mm fits"
                 for name, k in (("inches", INCH_MM), ("metres", 1000.0))
                 if 0.1 * k * cone_mm <= face_mm <= 0.5 * k * cone_mm), "")
    raise InputRangeError(f"design.gear_face_width_mm / {size_key}", (face_mm, size_value),
                          f"a gear face width less than the gear mean cone distance, "
                          f"{cone_mm:.4g} mm from {size_key} = {size_value:g}{unit}")


def check_pinion_face(pinion_mm: float, gear_mm: float) -> None:
    """The pinion face width within [F2, 3 F2], the range named with the gear face width
    it comes from (and a gear face typed in inches named so: the pinion's then fits
    25.4 times it)."""
    try:
        check_range("design.pinion_face_width_mm", pinion_mm, gear_mm, 3.0 * gear_mm)
    except InputRangeError as exc:
        if not np.isfinite(pinion_mm):
            raise
        inch = (f"; design.gear_face_width_mm typed in inches? x 25.4 = {INCH_MM * gear_mm:.4g} "
                "mm fits" if INCH_MM * gear_mm <= pinion_mm <= 3.0 * INCH_MM * gear_mm else "")
        raise InputRangeError(exc.field, exc.value,
                              f"{exc.allowed} mm (from design.gear_face_width_mm = {gear_mm:g} "
                              f"to 3 times it{inch})") from None
