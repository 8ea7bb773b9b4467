"""Where the Hamrock–Brewe closed forms hold: their deviation from exact elliptic Hertz
over axis ratios 1..1000 and the curvature-ratio range within a declared tolerance.

The preview's published stage D, its fp64 reference, the twin's contact law, the C
library and the FMUs evaluate the simplified forms of Hamrock & Brewe (1983)
(:func:`.hertz.hamrock_brewe_terms`), fitted for ellipticities to about 10 and tabled
by this package over curvature ratios 1..100 (docs/hertz.md sec. 3). Beyond that they
are an extrapolation whose error grows without bound (the HB axis ratio ``alpha^(2/pi)`` against the exact ``~sqrt(alpha ln alpha)``).
This module measures that error against :func:`.hertz.exact_elliptic_hertz` and states
the range in which every output stays within :data:`HB_TOLERANCE`; a preview outside it
is a reported result (``preview.hertz.reference.law_status``; docs/hertz.md sec. 7).

Errors depend on the curvature ratio ``alpha = B_max/A_min`` only: both solutions scale
identically with load, modulus and size (docs/hertz.md sec. 3).
"""

from __future__ import annotations

import math

from ..validation import InputRangeError
from .hertz import exact_curvature_ratio, hamrock_brewe_error_table

__all__ = ["HB_TOLERANCE", "HB_RATIO_LIMIT", "HB_AXIS_RATIOS", "HB_ERROR_KEYS",
           "hamrock_brewe_worst_error", "hamrock_brewe_ratio_limit",
           "hamrock_brewe_range_table", "within_hamrock_brewe_range"]

#: Declared tolerance of the Hamrock–Brewe law against exact Hertz (relative, on each of
#: k, a, b, p_max, the approach and the contact stiffness): the smallest round figure
#: the forms meet over curvature ratios 1..100, the range the package documented them
#: for (worst 4.28 %, the stiffness at ratio 100), so that the status never fires there.
HB_TOLERANCE = 0.05

#: Largest curvature ratio ``B_max/A_min`` at which every Hamrock–Brewe output is
#: within :data:`HB_TOLERANCE` of exact Hertz: :func:`hamrock_brewe_ratio_limit` gives
#: 122.0039 (the stiffness reaches +5 %; k is then 4.2 % long, the exact axis ratio
#: 20.4), rounded down (tests/analytic/test_hertz_range.py).
HB_RATIO_LIMIT = 122.0

#: Exact axis ratios ``k = a/b`` of :func:`hamrock_brewe_range_table` (1..1000).
HB_AXIS_RATIOS = (1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 20.0, 20.4, 20.9, 25.0, 30.0, 44.0,
                  50.0, 70.0, 100.0, 150.0, 200.0, 300.0, 500.0, 700.0, 1000.0)

#: The signed error columns of :func:`.hertz.hamrock_brewe_error_table` the tolerance
#: applies to.
HB_ERROR_KEYS = ("err_k", "err_a", "err_b", "err_p_max", "err_approach", "err_stiffness")


def hamrock_brewe_worst_error(alpha: float) -> tuple[float, str]:
    """Largest relative deviation of the Hamrock–Brewe outputs from exact Hertz at one
    curvature ratio, and which output it is.

    Parameters
    ----------
    alpha : float
        Curvature ratio ``B_max/A_min >= 1``, dimensionless.

    Returns
    -------
    (float, str)
        ``max |err|`` over :data:`HB_ERROR_KEYS` (dimensionless) and its key.
    """
    row = hamrock_brewe_error_table([alpha])[0]
    key = max(HB_ERROR_KEYS, key=lambda k: abs(row[k]))
    return abs(row[key]), key


def hamrock_brewe_ratio_limit(tolerance: float = HB_TOLERANCE) -> float:
    """Curvature ratio beyond ratio 100 at which the worst Hamrock–Brewe output leaves
    ``tolerance`` (Brent's method; every error grows monotonically there).

    Parameters
    ----------
    tolerance : float
        Relative tolerance in (0.0428, 0.5): above the forms' worst error over ratios
        1..100 (so the range starts at 1), below their error at ratio 1e6.

    Returns
    -------
    float
        The ratio ``alpha`` with ``hamrock_brewe_worst_error(alpha) == tolerance``.

    Raises
    ------
    InputRangeError
        ``tolerance`` outside that interval.
    """
    from scipy.optimize import brentq   # here: scipy.optimize costs 0.3 s per process

    lo, hi = 100.0, 1e6
    tol = float(tolerance)
    if not (hamrock_brewe_worst_error(lo)[0] < tol < hamrock_brewe_worst_error(hi)[0]):
        raise InputRangeError("tolerance", tolerance, "(0.0428, 0.5): the Hamrock-Brewe "
                              "worst error at ratio 100 and at ratio 1e6")
    return brentq(lambda a: hamrock_brewe_worst_error(a)[0] - tol, lo, hi, xtol=1e-9)


def hamrock_brewe_range_table(axis_ratios=HB_AXIS_RATIOS) -> list[dict]:
    """Hamrock–Brewe against exact Hertz by exact axis ratio (docs/hertz.md sec. 7).

    Parameters
    ----------
    axis_ratios : sequence of float
        Exact ellipticities ``k = a/b >= 1``, dimensionless.

    Returns
    -------
    list of dict
        Per axis ratio: ``axis_ratio``, ``ratio`` (the curvature ratio of that exact
        ellipse, :func:`.hertz.exact_curvature_ratio`), ``hb_axis_ratio``
        (``ratio^(2/pi)``), the signed errors of :func:`.hertz.hamrock_brewe_error_table`
        and ``within_tolerance`` (every error within :data:`HB_TOLERANCE`).
    """
    rows = []
    for k in axis_ratios:
        alpha = exact_curvature_ratio(k)
        row = hamrock_brewe_error_table([alpha])[0]
        rows.append({"axis_ratio": float(k), **row,
                     "hb_axis_ratio": alpha ** (2.0 / math.pi),
                     "within_tolerance": all(abs(row[key]) <= HB_TOLERANCE
                                             for key in HB_ERROR_KEYS)})
    return rows


def within_hamrock_brewe_range(alpha: float) -> bool:
    """True when the curvature ratio ``alpha = B_max/A_min`` lies in ``[1,``
    :data:`HB_RATIO_LIMIT` ``]``, where the Hamrock–Brewe law is within
    :data:`HB_TOLERANCE` of exact Hertz (a ratio below 1 is taken as its inverse; NaN is
    outside)."""
    a = float(alpha)
    if 0.0 < a < 1.0:
        a = 1.0 / a
    return 1.0 <= a <= HB_RATIO_LIMIT
