"""A nonlinear fit in the maximum norm: minimize ``max_k |f_k(x)|`` by sequential linear
programming in a trust region (the setting fit's ``objective="minimax"``,
:mod:`.setting_fit`, docs/machine_settings.md sec. 6).

Each step solves the linear program of the linearized residual (Fletcher 1987,
sec. 14.3, the L-infinity SL1QP with a box trust region; scipy's HiGHS ``linprog``):

    minimize  t   over (dx, t)
    subject to  -t <= f_k + J_k dx <= t,   |dx_i| <= Delta s_i

in the variables' own scale ``s`` (not the Jacobian's column norms: a parameter whose
first-order effect vanishes would get an unbounded box). A step is accepted when the
true maximum falls by at least a tenth of the predicted decrease; the radius grows after
a good step at its bound and shrinks after a poor one. The maximum norm of a fit is the figure a
tolerance is written in (a flank deviation "within +-x um"); the RMS fit leaves larger
peaks where the settings cannot follow the target.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

__all__ = ["MinimaxResult", "minimize_max_abs"]


@dataclass(frozen=True)
class MinimaxResult:
    """Outcome of :func:`minimize_max_abs`.

    Attributes
    ----------
    x : ndarray
        The best point found.
    max_abs : float
        ``max |f(x)|`` there, in the residual's unit.
    iterations : int
        Linear programs solved.
    evaluations : int
        Residual evaluations (Jacobian columns included when ``jac`` counts them).
    converged : bool
        The predicted decrease fell below ``tol`` (else the iteration limit or a
        trust radius below ``tol`` ended the search).
    """

    x: np.ndarray
    max_abs: float
    iterations: int
    evaluations: int
    converged: bool


def minimize_max_abs(fun, jac, x0, *, tol: float = 1e-6, max_iter: int = 40,
                     radius: float = 1.0, x_scale=None) -> MinimaxResult:
    """Minimize ``max |fun(x)|`` from ``x0`` (module docstring).

    Parameters
    ----------
    fun : callable
        ``x -> ndarray (m,)``, the residuals.
    jac : callable
        ``x -> ndarray (m, n)``, their Jacobian.
    x0 : array_like (n,)
        Start (e.g. the least-squares solution).
    tol : float
        Stop when a step's predicted decrease of the maximum falls below it (the
        residual's unit; converged), or the trust radius below ``tol`` times 1e-6.
    max_iter : int
        Largest number of linear programs, >= 1.
    radius : float
        Initial trust radius, in units of ``x_scale``.
    x_scale : array_like (n,), optional
        Scale of each variable (default 1: the variables are scaled already).

    Returns
    -------
    MinimaxResult
    """
    x = np.asarray(x0, dtype=float).copy()
    f, jmat = np.asarray(fun(x), dtype=float), np.asarray(jac(x), dtype=float)
    evaluations = 1
    m, n = jmat.shape
    d = np.ones(n) if x_scale is None else np.asarray(x_scale, dtype=float)
    best = float(np.abs(f).max())
    delta = float(radius)
    c = np.zeros(n + 1)
    c[-1] = 1.0
    ones = np.ones((m, 1))
    converged, it = False, 0
    for it in range(1, max_iter + 1):
        a_ub = np.vstack([np.hstack([jmat, -ones]), np.hstack([-jmat, -ones])])
        b_ub = np.concatenate([-f, f])
        bounds = [(-delta * di, delta * di) for di in d] + [(0.0, None)]
        lp = linprog(c, A_ub=a_ub, b_ub=b_ub, bounds=bounds, method="highs")
        if lp.status != 0:
            break
        dx, t = lp.x[:n], float(lp.x[-1])
        predicted = best - t
        if predicted < tol:
            converged = True
            break
        f_new = np.asarray(fun(x + dx), dtype=float)
        evaluations += 1
        new = float(np.abs(f_new).max())
        ratio = (best - new) / predicted
        if ratio > 0.1:
            at_bound = np.any(np.abs(dx / d) > 0.99 * delta)
            x, f, best = x + dx, f_new, new
            jmat = np.asarray(jac(x), dtype=float)
            if ratio > 0.75 and at_bound:
                delta *= 2.0
        if ratio < 0.25:
            delta = 0.25 * float(np.max(np.abs(dx / d)))
        if delta < 1e-6 * tol:
            break
    return MinimaxResult(x=x, max_abs=best, iterations=it, evaluations=evaluations,
                         converged=converged)
