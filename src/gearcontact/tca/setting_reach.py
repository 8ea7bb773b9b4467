"""Reach of the local setting synthesis: the corrections a target needs, predicted
before the fit (docs/machine_settings.md sec. 5, "Reach of the settings synthesis").

The local synthesis (:mod:`.setting_synthesis`) meets three conditions at the mean point
M with three pinion corrections (roll curvature, blade curvature, cutter radius). Its
targets, the parabolic TE level, the paint-ellipse length ``2a`` and the path angle, are
far from linear in the corrections: a step of a tenth of the standard crowning turns the
coast path by 174 deg on the 13/26 hypoid. They are simple functions of the second-order
form of the ease-off at M, though (Litvin & Fuentes 2004, sec. 9.2 and 21.8;
:func:`~gearcontact.geometry.contact_path.path_contact_ratio`): with
``E = x^T H x / 2`` in the tangent plane, ``l`` along the conjugate pair's contact line
(the paint ellipse's major axis) and ``m`` across it,

* the paint ellipse along ``l`` has ``(2a)^2 = 8 delta / H_ll`` (``delta`` the paint
  film);
* the path, the least ease-off on each contact line, satisfies ``l^T H p = 0``, so at
  the angle ``psi`` from ``l``: ``cot psi = -H_lm / H_ll``;
* the TE over the pitch is ``E`` along the path: its level is proportional to
  ``det H / H_ll = H_mm - H_lm^2 / H_ll``.

So the coordinates ``y = (1 / (2a)^2, cot psi / (2a)^2, s level + cot^2 psi / (2a)^2)``
are ``(H_ll, -H_lm, H_mm) / (8 delta)``, linear in ``H`` (``s = 1 / (8 delta K)``, ``K``
the level per ``det H / H_ll``: fitted, :func:`reach_model`), and ``H`` is linear in the
corrections to first order. The model linearizes ``y`` at the synthesis' start (the
standard crowning) by central differences (six local TCAs, :data:`STEP` scale steps) and
solves ``J z = y_target - y_0`` for the target's corrections: no search, no TCA at the
target. Measured (13/26 hypoid, docs/machine_settings.md): ``y`` is linear within 2 %
over the difference steps, and the corrections predicted for the targets the synthesis
met agree with the ones it found (the table there).

The span: ``J`` is 3 x 3 and of full rank (condition ~7), so every ``y`` is in the span of
the corrections' sensitivities (the projection residual is 0). A target is out of reach
only where its corrections are, by the hard limits of the settings (the roll of
:func:`~.setting_problem.roll_about`, ``1 + 2 c psi_m > 0``; a positive cutter radius),
which a path along the contact line (``psi -> 0``: an infinite ``H_lm``) always meets. A
prediction is *certain* (``design`` refuses it before the fit) only where even half the
predicted step crosses a hard limit (the largest error of the predicted corrections
measured is 31 % of the step, docs/machine_settings.md). Elsewhere the prediction is reported beside the
synthesis' result, and the synthesis starts from the predicted corrections where they miss
less than the standard crowning; a step longer than :data:`MAX_STEPS` (the range checked
against the synthesis) is no prediction either way.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 9.2
(localized contact from the ease-off), sec. 21.8 (local synthesis).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError
from .synthesis_targets import SynthesisTargets, angle_diff

__all__ = ["CERTAIN_SHARE", "MAX_STEPS", "STEP", "ReachModel", "ReachPrediction",
           "chord_step", "reach_model", "target_misses"]

#: Central-difference step of the model, in the synthesis' scale steps
#: (``setting_synthesis._SCALE``): large enough that the level's second difference
#: fixes ``s``, small enough that ``y`` stays linear (2 % measured over it).
STEP = 5.0
#: Share of the predicted step that must already cross a hard limit for a certain
#: refusal: the error of the predicted corrections measured against the synthesis is at
#: most 31 % of the step (per correction in scale steps; docs/machine_settings.md).
CERTAIN_SHARE = 0.5
#: Largest predicted step (scale steps) up to which the model was checked against the
#: synthesis (13/26 hypoid, docs/machine_settings.md sec. 5: 14 targets of 8-140 steps
#: all met; 230-3860 steps all missed); a longer step is "beyond the model's range": no
#: prediction either way.
MAX_STEPS = 150.0


@dataclass(frozen=True)
class ReachPrediction:
    """The corrections a target needs, from :meth:`ReachModel.predict`.

    Attributes
    ----------
    side : str
    path_angle_deg : float
        The target path angle, deg from the lengthwise direction (the synthesis').
    x : ndarray (3,)
        Predicted corrections (``setting_synthesis.PARAMETER_NAMES``), clipped at the
        first hard limit the step crosses.
    step_scales : float
        Largest predicted step, in the synthesis' scale steps (the model's difference step
        is :data:`STEP`).
    limit : str
        The hard limit the step crosses (``""`` none) and the share of the step at which.
    share : float
        Share of the predicted step that reaches the limit (1 when none).
    predicted : tuple of float
        (TE level arcsec, paint ellipse 2a mm, path angle deg) of the linear model at
        ``x``: the targets unless a limit clipped the step.
    residual : float
        Root sum of squares of the synthesis' normalized residual (each target's miss
        over its tolerance) predicted at ``x``: 0 where the step is free.
    """

    side: str
    path_angle_deg: float
    x: np.ndarray
    step_scales: float
    limit: str
    share: float
    predicted: tuple
    residual: float

    @property
    def reachable(self) -> bool:
        """Predicted within the targets' tolerances (residual <= 1) by a step within the
        model's checked range (:data:`MAX_STEPS`)."""
        return self.residual <= 1.0 and self.step_scales <= MAX_STEPS

    @property
    def certain(self) -> bool:
        """Out of reach even at :data:`CERTAIN_SHARE` of the predicted step."""
        return bool(self.limit) and self.share < CERTAIN_SHARE

    @property
    def verdict(self) -> str:
        """``"reachable"``, ``"beyond the model's range"`` (no prediction), ``"out of
        reach"`` (a hard limit within the step) or ``"out of reach (certain)"``."""
        if self.certain:
            return "out of reach (certain)"
        if self.limit:
            return "out of reach"
        return "reachable" if self.reachable else "beyond the model's range"

    def text(self) -> str:
        """One line for the synthesis' report."""
        lvl, length, ang = self.predicted
        why = f"; {self.limit}" if self.limit else ""
        return (f"{self.side} reach model ({self.verdict}): path {self.path_angle_deg:g} deg "
                f"needs roll "
                f"curvature {self.x[0]:+.4f}, blade curvature {self.x[1]:+.5f} /mm, cutter "
                f"radius {self.x[2]:+.3f} mm ({self.step_scales:.0f} scale steps); "
                f"predicted TE level {lvl:.2f} arcsec, ellipse {length:.3f} mm, path "
                f"{ang:.1f} deg, residual {self.residual:.2f}{why}")


def target_misses(targets: SynthesisTargets, length_mm: float, level: float,
                  length: float, angle: float | None = None) -> np.ndarray:
    """Each target's miss over its tolerance, the residual of the local synthesis: TE
    level (arcsec), paint ellipse ``length`` (mm, target ``length_mm``) and, with
    ``angle``, the path angle (deg, folded into +-90 deg; nan counts as 90 deg off)."""
    r = [(level / targets.te0_pp_arcsec - 1.0) / targets.tol_te0_rel,
         (length / length_mm - 1.0) / targets.tol_length_rel]
    if angle is not None:
        off = angle_diff(angle, targets.path_angle_deg) if np.isfinite(angle) else 90.0
        r.append(off / targets.tol_angle_deg)
    return np.asarray(r, float)


def _coordinates(level, length_mm, path_deg, line_deg, scale):
    """``y`` of the module docstring from a (signed) TE level, the ellipse length, the
    path angle and the contact line's angle (deg)."""
    a = 1.0 / length_mm ** 2
    b = a / math.tan(math.radians(path_deg - line_deg))
    return np.array([a, b, scale * level + b * b / a])


@dataclass(frozen=True)
class ReachModel:
    """The linear model of one side (:func:`reach_model`, module docstring).

    Attributes
    ----------
    side : str
    x0 : ndarray (3,)
        The synthesis' start (the standard crowning's corrections).
    scales : ndarray (3,)
        The synthesis' scale step of each correction.
    line_angle_deg : float
        Contact line direction at M (the start's paint-ellipse axis), deg.
    level_scale : float
        ``s`` of the module docstring, 1/(mm^2 arcsec).
    y0 : ndarray (3,)
    jacobian : ndarray (3, 3)
        ``dy / dz`` per scale step.
    psi_m_rad : float
        Cradle roll that generates M (the roll curvature's hard limit).
    point_radius_mm : float
        The base pinion's cutter radius: the radius correction stays above its negative
        (the cutter radius' hard limit).
    """

    side: str
    x0: np.ndarray
    scales: np.ndarray
    line_angle_deg: float
    level_scale: float
    y0: np.ndarray
    jacobian: np.ndarray
    psi_m_rad: float
    point_radius_mm: float

    @classmethod
    def from_evaluations(cls, side, x0, scales, start, plus, minus, *, psi_m_rad: float,
                         point_radius_mm: float, step: float = STEP) -> ReachModel:
        """The model from local contacts at ``x0`` (``start``) and at ``x0 +- step
        scales_i e_i`` (``plus[i]``, ``minus[i]``), each a tuple (signed TE level arcsec,
        ellipse length mm, path angle deg, ellipse angle deg). ``s`` is the least-squares
        value that makes the third coordinate's second differences vanish on all three
        axes (it is linear in ``H`` only with the right ``s``)."""
        line = float(start[3])

        def parts(c):
            y = _coordinates(c[0], c[1], c[2], line, 0.0)
            return y, float(c[0])

        y0, g0 = parts(start)
        num = den = 0.0
        for p, m in zip(plus, minus):
            (yp, gp), (ym, gm) = parts(p), parts(m)
            dg, dq = gp + gm - 2.0 * g0, yp[2] + ym[2] - 2.0 * y0[2]
            num, den = num - dg * dq, den + dg * dg
        s = num / den
        y = [_coordinates(*c[:3], line, s) for c in (start, *plus, *minus)]
        jac = np.column_stack([(y[1 + i] - y[4 + i]) / (2.0 * step) for i in range(3)])
        return cls(side, np.asarray(x0, float), np.asarray(scales, float), line, float(s),
                   y[0], jac, float(psi_m_rad), float(point_radius_mm))

    def predict(self, targets: SynthesisTargets, *, length_mm: float) -> ReachPrediction:
        """The corrections of ``targets`` (a path angle given; ``length_mm`` the ellipse
        length target) on this side, with the first hard limit the step crosses."""
        if targets.path_angle_deg is None:
            raise InputRangeError("path_angle_deg", None, "a path angle (the model of a "
                                  "free path is not built: the blade curvature is held)")
        s, line = self.level_scale, self.line_angle_deg
        y_t = _coordinates(targets.te0_pp_arcsec, length_mm, targets.path_angle_deg, line, s)
        z = np.linalg.solve(self.jacobian, y_t - self.y0)
        dx = z * self.scales
        share, limit = 1.0, ""
        c0, p = self.x0[0], self.psi_m_rad
        if p * dx[0] < 0.0:        # 1 + 2 c psi_m > 0 (roll_about)
            t = (-1.0 / (2.0 * p) - c0) / dx[0]
            if t < share:
                share, limit = t, (f"roll curvature beyond -1/(2 psi_m) = "
                                   f"{-1.0 / (2.0 * p):+.3f} (psi_m {p:.4f} rad)")
        if dx[2] < 0.0:            # the cutter radius stays positive
            t = (-self.point_radius_mm - self.x0[2]) / dx[2]
            if t < share:
                share, limit = t, (f"cutter radius change beyond -{self.point_radius_mm:.2f}"
                                   f" mm (the cutter's radius)")
        if limit:
            limit = f"{limit} at {share:.0%} of the step"
            share = max(share * 0.999, 0.0)
        y = self.y0 + self.jacobian @ (z * share)
        a, b, h = y
        length = 1.0 / math.sqrt(a) if a > 0.0 else math.inf
        angle = (math.degrees(math.atan2(a, b)) + line + 90.0) % 180.0 - 90.0 if a > 0 \
            else math.nan
        level = (h - b * b / a) / s if a > 0.0 else math.nan
        r = np.nan_to_num(target_misses(targets, length_mm, level, length, angle), nan=1e3,
                          posinf=1e3)
        return ReachPrediction(self.side, float(targets.path_angle_deg), self.x0 + dx * share,
                               float(np.abs(z).max()), limit, float(share),
                               (level, length, angle), float(math.sqrt(r @ r)))


def chord_step(model: ReachModel, prediction: ReachPrediction, x, contact, *,
               targets: SynthesisTargets, length_mm: float) -> np.ndarray:
    """Corrections one chord step from ``x``: the model's Jacobian applied to the miss
    in ``y`` measured at ``x`` (``contact``: signed TE level arcsec, ellipse length mm,
    path angle deg), clipped to the hard limits' share of the step as in
    :meth:`ReachModel.predict` (no step where the prediction was clipped)."""
    s, line = model.level_scale, model.line_angle_deg
    y_t = _coordinates(targets.te0_pp_arcsec, length_mm, targets.path_angle_deg, line, s)
    y_x = _coordinates(*contact, line, s)
    if prediction.limit or not np.all(np.isfinite(y_x)):
        return np.asarray(x, float)
    return np.asarray(x, float) + np.linalg.solve(model.jacobian, y_t - y_x) * model.scales


def reach_model(problem, side: str, *, scales, step: float = STEP) -> ReachModel:
    """:class:`ReachModel` of ``side`` of ``problem``
    (:class:`~.setting_problem.SynthesisProblem`) at the synthesis' start, the standard
    crowning: seven local TCAs at M (:meth:`~.setting_problem.SynthesisProblem.contact`);
    ``scales`` the synthesis' scale step of each correction."""
    x0, scales = problem.standard[side], np.asarray(scales, float)

    def contact(x):
        m = problem.contact(side, x)
        return (m.te_level_arcsec * math.copysign(1.0, m.te_curvature_arcsec_per_rad2),
                m.point.paint_length_mm, m.point.path_angle_deg, m.point.ellipse_angle_deg)

    start = contact(x0)
    sign = math.copysign(1.0, start[0])         # the standard crowning's parabola: +
    signed = [(sign * c[0], *c[1:]) for c in
              [start] + [contact(x0 + k * step * scales * e) for k in (1, -1)
                         for e in np.eye(3)]]
    return ReachModel.from_evaluations(
        side, x0, scales, signed[0], signed[1:4], signed[4:7], psi_m_rad=problem.means[side][2],
        point_radius_mm=problem.base[side].blade.point_radius_mm, step=step)
