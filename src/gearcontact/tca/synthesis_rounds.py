"""The decoupled rounds of the ease-off synthesis (:mod:`.synthesis`): re-centring a
start on its bearing-centre miss, and fixed-point rounds on the crownings.

Both evaluate through the search's ``residual(x)`` (``x`` the centre form of
:func:`~.design_point.centred_coefficients`: centre offsets, profile and lengthwise
crowning, bias; residuals centre u, v, TE0, pattern length in tolerances), so every
evaluation enters the search's ranking.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 21.8.
"""

from __future__ import annotations

import numpy as np

__all__ = ["recentred", "polish"]


def recentred(residual, x, centre, tol_mm: float, lo, hi, *, rounds: int = 2) -> None:
    """Evaluate ``x`` and move its ease-off centre (``x[0:2]``, pinion u, v offsets) by
    the bearing centre's miss, at most ``rounds`` times (the vertex follows the relief
    centre about one to one), until the centre is within ``tol_mm``; every evaluation
    enters the search's ranking through ``residual``."""
    x = np.array(x, float)
    for _ in range(rounds + 1):
        r = residual(x)
        if r[0] >= 1e3:                     # no interior contact at this start
            return
        miss = np.array([r[0], r[1]]) * tol_mm
        if np.all(np.abs(miss) <= tol_mm):
            return
        x[0:2] = np.clip(x[0:2] - miss, lo[0:2], hi[0:2])


def polish(residual, x, lo, hi, targets, *, rounds: int = 8,
            within: float = 1.0) -> None:
    """Decoupled fixed-point rounds from the best point when the least squares stalls
    short of the targets (the residuals carry the TCA's discretization noise, which
    misleads its finite-difference Jacobian: F2 spiral bevel coast stopped with the
    pattern 7 % long). Each round scales the lengthwise crowning by the TE0 miss (the
    parabolic TE level is proportional to it, Litvin & Fuentes 2004 sec. 21.8) and the
    profile crowning by the pattern-length miss to the power -2 (the paint ellipse
    half-length goes as the inverse square root of the relative curvature across the
    path at a fixed paint thickness), exponents refined by secant from the rounds'
    own results, and re-centres the ease-off (:func:`recentred`). Stops when the
    centre, TE0 and length residuals are all within ``within`` tolerances."""
    x = np.array(x, float)
    expo = {2: -2.0, 3: 1.0}                # d log(coefficient) / d log(miss)
    prev = None
    for _ in range(rounds):
        r = residual(x)
        if r[0] >= 1e3:
            return
        miss = {2: 1.0 + r[3] * targets.tol_length_rel, 3: 1.0 + r[2] * targets.tol_te0_rel}
        if np.max(np.abs(r[0:4])) <= within:
            return
        if prev is not None:                # secant on log-log, kept to a sane range
            for i in (2, 3):
                dm = np.log(miss[i]) - np.log(prev[1][i])
                dx = np.log(x[i]) - np.log(prev[0][i])
                if abs(dm) > 1e-3 and abs(dx) > 1e-6:
                    expo[i] = float(np.clip(dx / dm, 4.0 * expo[i], 0.25 * expo[i])
                                    if expo[i] < 0 else
                                    np.clip(dx / dm, 0.25 * expo[i], 4.0 * expo[i]))
        prev = (x.copy(), miss)
        for i in (2, 3):                    # log x moves by expo * (0 - log miss)
            x[i] = x[i] * miss[i] ** (-expo[i])
        x[0:2] -= np.array([r[0], r[1]]) * targets.tol_centre_mm
        x = np.clip(x, lo, hi)
