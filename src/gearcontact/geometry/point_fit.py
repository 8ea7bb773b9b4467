"""Machine settings fitted at scattered measured points of a flank (pinion or gear).

A measuring room's output is a set of points, not a grid: missing points, irregular
positions, a few hundred of them (docs/export.md "The measuring grid"). Each measured
point is the nominal point at its (L, R) moved by its deviation along the nominal
normal (:func:`~.measuring_grid.measured_points`), located on its member's sheet at
``(u_k, v_k)`` with angular coordinate ``psi_k`` (a gear's points:
:mod:`.gear_correction`). The settings are fitted at those
points, not at an interpolated flank:

    min_x  sum_k d_k(x)^2,   d_k = lever_k (psi_gen(u_k, v_k; x) - psi_k)

with the generated flank solved at the points themselves (:class:`PointProblem`, the
residual of :class:`~.setting_fit.FitProblem`; ``lever_k = R (e_psi . n)`` with the
nominal normal, so ``d_k`` is the normal distance of the measured point from the
generated flank, positive = material left, to first order in ``d_k`` itself, not in
the deviation). ``--fit minimax`` minimizes ``max |d_k|`` from there.

Before the fit the points must determine the settings: at least as many points as
settings (:func:`check_point_count`, before any flank is built), and a sensitivity
matrix at the seed of full rank (:func:`check_observable`: column-normalized, its
smallest singular value relative to the largest at least :data:`RANK_TOLERANCE`;
points on one or two profile lines, on one lengthwise line or in a small patch leave
combinations of settings that move no point, named with the settings they involve).

References
----------
G. H. Golub, C. F. Van Loan, *Matrix Computations*, 4th ed., 2013, sec. 5.5 (rank
deficiency, the numerical null space from the SVD).
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.interpolate import RegularGridInterpolator

from ..validation import InputRangeError
from .measuring_grid import MeasuredFlank, MeasuredPoints
from .setting_fit import (DEFAULT_PARAMETERS, FitProblem, SettingFit, checked_options,
                          solve_fit)

__all__ = ["RANK_TOLERANCE", "PointProblem", "check_observable", "check_point_count",
           "fit_points", "point_deviation_um", "point_problem"]

#: Smallest singular value of the column-normalized sensitivity matrix at the seed,
#: relative to the largest, that the fit accepts: a combination of settings that moves
#: the points 1e4 times less than the strongest is not determined by them. Measured on
#: s0003 coast (default settings): 2.2e-3 at 60 scattered points, 2.5e-3 on a 9 x 11
#: grid, 3.7e-4 at 8 scattered points; ~1e-6 on two profile lines, 1e-5 - 3e-5 in a
#: 0.5 x 2 mm patch, ~2e-9 / 2e-8 on one profile / lengthwise line
#: (tests/geometry/test_point_fit.py).
RANK_TOLERANCE = 1e-4
#: A setting whose unit vector projects onto the numerical null space by more than
#: this is named as unobservable.
_NULL_SHARE = 0.3


class PointProblem(FitProblem):
    """The fit's residual at measured points (module docstring): the nodes are the
    points' sheet parameters; the envelope's guesses come from a 9 x 11 continuation
    grid over the nominal box, interpolated (bilinear) at the points."""

    def __init__(self, seed, blank, points: MeasuredPoints, names, *, n_u: int = 9,
                 n_v: int = 11):
        solver, mean = self._start(seed, blank, names)
        self.U, self.V = np.asarray(points.u_mm), np.asarray(points.v_mm)
        b = points.box
        self._grid = (np.linspace(b.u_root, b.u_tip, n_u), np.linspace(b.v_toe, b.v_heel, n_v))
        self.q = self._restart(solver, mean.q).q
        self.psi_t, self.lever_um = np.asarray(points.psi_rad), np.asarray(points.lever_um)

    def _restart(self, solver, q_mean):
        grid = super()._restart(solver, q_mean)
        at = np.column_stack([self.U, self.V])
        guess = np.stack([RegularGridInterpolator(self._grid, grid.q[..., k], bounds_error=False,
                                                  fill_value=None)(at) for k in range(3)], -1)
        return solver.solve(self.U, self.V, guess)


def check_point_count(grids: dict, parameters=DEFAULT_PARAMETERS, *,
                      where: str = "target flank", member: str = "pinion") -> None:
    """Refuse, before any flank is built, a measured flank (:class:`MeasuredFlank` or
    :class:`MeasuredPoints` values of ``grids``, flanks of ``member``) with fewer
    points than fitted settings."""
    names = tuple(parameters)
    for side, data in grids.items():
        if isinstance(data, (MeasuredFlank, MeasuredPoints)) and len(data.L_mm) < len(names):
            raise InputRangeError(f"{where}: {member} {side} points", len(data.L_mm),
                                  f"at least {len(names)}, one per fitted setting "
                                  f"({', '.join(names)})")


def check_observable(jac: np.ndarray, names, *, where: str) -> float:
    """Refuse points that leave the fit rank-deficient: the sensitivity matrix ``jac``
    (points x settings) column-normalized, its singular values relative to the largest
    below :data:`RANK_TOLERANCE` span combinations of settings that move no point; the
    message names the settings with more than 30 % of their unit vector in them.
    Returns the smallest relative singular value."""
    norm = np.linalg.norm(jac, axis=0)
    if not np.all(norm > 0.0):      # a setting that moves no point at all
        dead = [n for n, x in zip(names, norm) if not x > 0.0]
        _refuse_unobservable(where, dead, 0.0)
    _, s, vt = np.linalg.svd(jac / norm, full_matrices=False)
    rel = s / s[0]
    null = vt[rel < RANK_TOLERANCE]
    if len(null):
        share = np.linalg.norm(null, axis=0)
        order = np.argsort(-share)
        _refuse_unobservable(where, [names[i] for i in order if share[i] > _NULL_SHARE],
                             float(rel[-1]))
    return float(rel[-1])


def _refuse_unobservable(where: str, names, rel: float):
    raise InputRangeError(f"{where}: points", f"rank-deficient (settings not observable at "
                          f"these points: {', '.join(names)}; smallest relative singular "
                          f"value {rel:.1e})", f"points spread over the flank's profile "
                          f"and length (relative singular value >= {RANK_TOLERANCE:g}), "
                          "or fewer settings")


def point_problem(seed, blank, points: MeasuredPoints, *, parameters=DEFAULT_PARAMETERS,
                  tolerance_um: float = 1e-6, objective: str = "rms",
                  where: str = "target flank") -> PointProblem:
    """The :class:`PointProblem` of ``points`` from ``seed`` after the checks of the
    options (:func:`~.setting_fit.checked_options`), refused if the points cannot
    determine the ``parameters`` (:func:`check_point_count`, :func:`check_observable`
    on the seed's sensitivity: 1 + len(parameters) flank evaluations at the points);
    its ``setup_seconds`` the time this took."""
    names = checked_options(seed, parameters, tolerance_um=tolerance_um, objective=objective)
    check_point_count({points.side: points}, names, where=where)
    started = time.perf_counter()
    prob = PointProblem(seed, blank, points, names)
    check_observable(prob.jacobian(np.zeros(len(names))), names,
                     where=f"{where}: {points.member} {points.side}")
    prob.setup_seconds = time.perf_counter() - started
    return prob


def fit_points(seed, blank, points: MeasuredPoints, *, parameters=DEFAULT_PARAMETERS,
               tolerance_um: float = 1e-6, objective: str = "rms",
               where: str = "target flank") -> SettingFit:
    """Fit the ``parameters`` of the pinion set-up ``seed`` so that its generated flank
    passes through the measured ``points`` (module docstring).

    Parameters
    ----------
    seed : MachineSetup
        As :func:`~.setting_fit.fit_pinion_setup`.
    blank : BlankDesign
    points : MeasuredPoints
        Same side as ``seed``, right-hand body frame.
    parameters, tolerance_um, objective
        As :func:`~.setting_fit.fit_pinion_setup`.
    where : str
        Names the file in messages.

    Returns
    -------
    SettingFit
        ``fit_rms_um`` / ``fit_max_um`` at the points.

    Raises
    ------
    InputRangeError
        The checks of :func:`~.setting_fit.fit_pinion_setup`, or points that cannot
        determine the settings (:func:`point_problem`), before the fit.
    """
    prob = point_problem(seed, blank, points, parameters=parameters,
                         tolerance_um=tolerance_um, objective=objective, where=where)
    return solve_fit(prob, tolerance_um=tolerance_um, objective=objective,
                     started=time.perf_counter() - prob.setup_seconds)


def point_deviation_um(flank, points: MeasuredPoints) -> np.ndarray:
    """Normal deviation (um) of ``flank`` (a pinion sheet on the points' cone) from each
    measured point: ``lever_k (psi_flank(u_k, v_k) - psi_k)``, positive = material
    left (the residual of the cut flank, or the distance from the conjugate pinion)."""
    d = (flank.psi(points.u_mm, points.v_mm) - points.psi_rad + math.pi) % (2 * math.pi) - math.pi
    return d * points.lever_um
