"""fp64 reference of stage C: curvature fit of the gap stencil and principal curvatures.

The gap field around the contact point is fitted with a least-squares polynomial of
total degree 6 in s, t whose quadratic part
``c0 + c1 s + c2 t + c3 s^2 + c4 s t + c5 t^2`` the operator of :mod:`.pinv` returns
(the higher terms keep the gap's quartic and sixth-order terms out of c3..c5). The
quadratic part ``[s t] S [s t]^T`` with
``S = [[c3, c4/2], [c4/2, c5]]`` is diagonalized in closed form: with ``h = c3 + c5``
and ``r = sqrt((c3 - c5)^2 + c4^2)``,

    A- = (h + r) / 2 >= B- = (h - r) / 2,

so that ``g = A- u^2 + B- v^2`` in the principal axes (u at ``angle_deg`` from s).
A- and B- are therefore *half* the relative principal curvatures (1/mm), which is the
convention of the Hertz stage (R_x = 1/(2 A), Hamrock and Brewe [1]_; Litvin and
Fuentes [2]_ ch. 8 for the relative curvature of mating gear flanks).

A point (elliptic) contact needs B- > 0; the reference reports ``elliptic`` and leaves
raising to the caller (the preview engine refuses non-elliptic stencils).

References
----------
.. [1] B. J. Hamrock and D. E. Brewe, "Simplified solution for stresses and
   deformations", J. Lubrication Technol. 105 (2), 171-177, 1983.
.. [2] F. L. Litvin and A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed.,
   Cambridge University Press, 2004.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcontact.preview.fit.pinv import N_TAPS, baked_pinv, design_matrix, pseudo_inverse
from gearcontact.contract.stencil import STENCIL_SPACING_MM
from gearcontact.validation import InputRangeError, check_array_finite, check_positive

__all__ = ["CurvatureFit", "fit_curvatures", "fitted_coefficients", "principal_curvatures"]

#: The range of ``(c3 - c5)^2 + c4^2`` where :func:`principal_curvatures` takes its square
#: root directly (no overflow, no significant underflow; ``hypot`` outside).
_SQ_LO = 2.0 ** -900
_SQ_HI = 2.0 ** 1000


@dataclass(frozen=True)
class CurvatureFit:
    """Result of the fp64 stage-C fit.

    Attributes
    ----------
    coefficients : tuple of float
        c0 (mm), c1, c2 (dimensionless slopes), c3, c4, c5 (1/mm) of
        ``g = c0 + c1 s + c2 t + c3 s^2 + c4 s t + c5 t^2`` with s, t in mm.
    A_minus_per_mm : float
        Larger eigenvalue of ``[[c3, c4/2], [c4/2, c5]]``, 1/mm (half the larger
        relative principal curvature).
    B_minus_per_mm : float
        Smaller eigenvalue, 1/mm (``B_minus_per_mm <= A_minus_per_mm``).
    angle_deg : float
        Direction of the A- principal axis measured from the s axis towards t, deg,
        in (-90, 90].
    residual_rms_mm : float
        Root-mean-square residual of the degree-6 least-squares polynomial over the 49
        samples, mm.
    elliptic : bool
        True when ``B_minus_per_mm > 0`` (point contact; Hertz stage applicable).
    """

    coefficients: tuple
    A_minus_per_mm: float
    B_minus_per_mm: float
    angle_deg: float
    residual_rms_mm: float
    elliptic: bool


def principal_curvatures(c3: float, c4: float, c5: float) -> tuple[float, float, float]:
    """Closed-form eigen-solve of ``[[c3, c4/2], [c4/2, c5]]``.

    Parameters
    ----------
    c3, c4, c5 : float
        Quadratic coefficients, 1/mm.

    Returns
    -------
    (A_minus_per_mm, B_minus_per_mm, angle_deg)
        Eigenvalues (1/mm, descending) and the A- axis angle from s, deg.

    Notes
    -----
    The smaller-magnitude eigenvalue is taken from the determinant
    (``lambda1 * lambda2 = c3 c5 - c4^2/4``) to avoid cancellation in ``h - r``.
    ``r = sqrt((c3 - c5)^2 + c4^2)`` is formed from the squares where their sum lies in
    [2^-900, 2^1000) (neither square overflows, and one that underflows is below 2^-121
    of the sum: the correctly rounded square root of the rounded sum, within an ulp as
    ``hypot``), ``hypot`` outside: IEEE operations only on the curvatures of any gear, so
    the twin's compiled law and its C port in the FMUs give the same bits without libm.
    """
    h = c3 + c5
    d = c3 - c5
    s = d * d + c4 * c4
    r = math.sqrt(s) if _SQ_LO <= s < _SQ_HI else math.hypot(d, c4)
    a_minus = 0.5 * (h + r)
    b_minus = 0.5 * (h - r)
    det = c3 * c5 - 0.25 * c4 * c4
    if h > 0.0 and a_minus != 0.0:
        b_minus = det / a_minus
    elif h < 0.0 and b_minus != 0.0:
        a_minus = det / b_minus
    angle = 0.5 * math.degrees(math.atan2(c4, c3 - c5))
    if angle <= -90.0:
        angle += 180.0
    return a_minus, b_minus, angle


def fit_curvatures(gaps_mm, *, spacing_mm: float = STENCIL_SPACING_MM) -> CurvatureFit:
    """Fit the 7 x 7 gap stencil in fp64 and return the principal curvatures.

    Parameters
    ----------
    gaps_mm : array_like, shape (49,)
        Gap samples in the order of :mod:`gearcontact.contract.stencil`, mm (positive =
        open).
    spacing_mm : float, keyword-only
        Stencil spacing, mm (> 0; default the baked hardware spacing).

    Returns
    -------
    CurvatureFit

    Raises
    ------
    gearcontact.validation.InputRangeError
        Wrong number of samples, a NaN/inf sample (named by index) or a non-positive
        spacing.
    """
    g = check_array_finite("gaps_mm", gaps_mm)
    if g.ndim != 1 or g.shape[0] != N_TAPS:
        raise InputRangeError("gaps_mm.shape", g.shape,
                              f"exactly {N_TAPS} samples, shape ({N_TAPS},)")
    h = check_positive("spacing_mm", spacing_mm)
    m = baked_pinv().weights if h == STENCIL_SPACING_MM else pseudo_inverse(h)
    c = m @ g
    a = design_matrix(h)
    resid = g - a @ np.linalg.lstsq(a, g, rcond=None)[0]    # of the whole degree-6 fit
    a_minus, b_minus, angle = principal_curvatures(float(c[3]), float(c[4]), float(c[5]))
    return CurvatureFit(coefficients=tuple(float(x) for x in c),
                        A_minus_per_mm=a_minus, B_minus_per_mm=b_minus,
                        angle_deg=angle,
                        residual_rms_mm=float(np.sqrt(np.mean(resid * resid))),
                        elliptic=bool(b_minus > 0.0))


def fitted_coefficients(gaps_mm) -> np.ndarray:
    """fp64 stage-C coefficients c3, c4, c5 (1/mm) of stencils ``gaps_mm`` (..., 49; mm)
    at once, shape (..., 3): :func:`fit_curvatures`'s (the baked ROM's weights), for
    the preview's and the twin's tables row by row."""
    return np.asarray(gaps_mm, float) @ baked_pinv().weights[3:6].T
