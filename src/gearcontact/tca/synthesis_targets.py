"""Targets of the local synthesis and their table: the conditions at the mean point
(:class:`SynthesisTargets`), the rows ``(quantity, unit, target, achieved, tolerance,
met)`` a design point gives against them (:func:`targets_rows`) and their Markdown table
(:func:`targets_table`, :class:`TargetRows`), shared by the ease-off synthesis
(:mod:`gearcontact.tca.synthesis`) and the machine-setting synthesis
(:mod:`gearcontact.tca.setting_synthesis`). The defaults and their sources:
docs/synthesis.md.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..geometry.contact_path import SYNTHESIS_PATTERN_RATIO, SYNTHESIS_TE0_ARCSEC
from ..validation import check_positive, check_range
from .design_point import DesignPoint

__all__ = ["SynthesisTargets", "TargetRows", "targets_rows", "targets_table", "angle_diff",
           "TE0_RANGE_ARCSEC", "PATTERN_RATIO_RANGE"]

#: Allowed TE0 peak-to-peak, arcsec, and pattern length ratio (2a over the face width).
TE0_RANGE_ARCSEC = (0.5, 30.0)
PATTERN_RATIO_RANGE = (0.1, 0.8)


@dataclass(frozen=True)
class SynthesisTargets:
    """Conditions of the local synthesis at the mean point (defaults and their sources:
    :mod:`gearcontact.tca.synthesis`).

    Parameters
    ----------
    te0_pp_arcsec : float
        Unloaded TE peak-to-peak over one pinion pitch, arcsec, in [0.5, 30].
    pattern_length_ratio : float
        Paint-ellipse major axis 2a over the gear face width, in [0.1, 0.8].
    path_angle_deg : float or None
        Direction of the contact path on the gear flank at the bearing centre from the
        lengthwise direction,
        deg in (-90, 90] (right-handed flank frame, as the ellipse angle of
        :class:`~gearcontact.tca.design_point.DesignPoint`); None: not prescribed
        (bias drawn weakly towards 0).
    centre_face, centre_profile : float
        Bearing centre (TE0 vertex) on the pinion flank as fractions of the face
        (0 toe, 1 heel) and of the working depth (0 root, 1 tip), in [0.02, 0.98].
    tol_centre_mm, tol_te0_rel, tol_length_rel, tol_angle_deg : float
        Tolerances (least-squares scales): centre, mm; TE0 and length, relative;
        path angle, deg.
    """

    te0_pp_arcsec: float = SYNTHESIS_TE0_ARCSEC
    pattern_length_ratio: float = SYNTHESIS_PATTERN_RATIO
    path_angle_deg: float | None = None
    centre_face: float = 0.5
    centre_profile: float = 0.5
    tol_centre_mm: float = 0.05
    tol_te0_rel: float = 0.05
    tol_length_rel: float = 0.05
    tol_angle_deg: float = 2.0

    def __post_init__(self):
        check_range("te0_pp_arcsec", self.te0_pp_arcsec, *TE0_RANGE_ARCSEC)
        check_range("pattern_length_ratio", self.pattern_length_ratio, *PATTERN_RATIO_RANGE)
        if self.path_angle_deg is not None:
            check_range("path_angle_deg", self.path_angle_deg, -89.9, 90.0)
        check_range("centre_face", self.centre_face, 0.02, 0.98)
        check_range("centre_profile", self.centre_profile, 0.02, 0.98)
        for name in ("tol_centre_mm", "tol_te0_rel", "tol_length_rel", "tol_angle_deg"):
            check_positive(name, getattr(self, name))


class TargetRows:
    """``met`` and ``table`` of a result with ``rows`` of ``(quantity, unit, target,
    achieved, tolerance, met)`` (each quantity after ``table_prefix``)."""

    rows: tuple
    table_prefix = ""

    @property
    def met(self) -> bool:
        """Every target within its tolerance."""
        return all(r[5] for r in self.rows)

    def table(self) -> str:
        """Target / achieved / tolerance as Markdown."""
        return targets_table(self.rows, prefix=self.table_prefix)


def targets_table(rows, *, prefix: str = "") -> str:
    """Rows ``(quantity, unit, target, achieved, tolerance, met)`` as a Markdown table,
    each quantity after ``prefix``."""
    lines = ["| target | aim | achieved | tolerance | met |", "|---|---:|---:|---:|---|"]
    for name, unit, aim, got, tol, ok in rows:
        lines.append(f"| {prefix}{name} ({unit}) | {aim:.4g} | {got:.4g} | {tol:.3g} | "
                     f"{'yes' if ok else 'NO'} |")
    return "\n".join(lines)


def targets_rows(dp: DesignPoint, t: SynthesisTargets, centre, length_mm: float) -> tuple:
    """``(quantity, unit, target, achieved, tolerance, met)`` of the targets ``t`` at the
    design point ``dp``: bearing centre (pinion u, v; not checked if ``centre`` is
    None), TE0 level, paint-ellipse length ``length_mm`` and, if prescribed, path angle."""
    rows = [] if centre is None else [
        ("bearing centre pinion u", "mm", centre[0], dp.pinion_uv[0], t.tol_centre_mm),
        ("bearing centre pinion v", "mm", centre[1], dp.pinion_uv[1], t.tol_centre_mm)]
    rows += [("TE0 peak-to-peak", "arcsec", t.te0_pp_arcsec, dp.te0_pp_arcsec,
             t.tol_te0_rel * t.te0_pp_arcsec),
            ("paint ellipse 2a", "mm", length_mm, dp.paint_length_mm,
             t.tol_length_rel * length_mm)]
    if t.path_angle_deg is not None:
        rows.append(("path angle from lengthwise", "deg", t.path_angle_deg,
                     dp.path_angle_deg, t.tol_angle_deg))
    return tuple((n, u, float(a), float(g), float(tol), bool(abs(g - a) <= tol))
                 for n, u, a, g, tol in rows)


def angle_diff(a: float, b: float) -> float:
    """Difference of two axis directions, deg in (-90, 90]."""
    d = (a - b + 90.0) % 180.0 - 90.0
    return float(d)
