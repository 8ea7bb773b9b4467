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

c3, c4, c5 are summed from the stencil's second differences about its centre
(:func:`fitted_coefficients`), not tap by tap: a gear stencil is mostly its offset and
slopes (a gap of ~0.1 mm, a curvature term of ~1e-3 mm), which the quadratic rows of the
pseudo-inverse cancel; summed tap by tap, the rounding of the large products is ~1e-16 of
``sum_i |M_ji g_i|``, up to ~1e-12 of a near-cylindrical stencil's B- (docs/export.md,
"fp64 equivalence"). The sum is in a fixed order of IEEE operations (no BLAS), which the
exported C (gearcontact.export) repeats bit for bit.

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
from functools import lru_cache

import numpy as np

from gearcontact.preview.fit.pinv import N_TAPS, baked_pinv, design_matrix, pseudo_inverse
from gearcontact.contract.stencil import STENCIL_SPACING_MM
from gearcontact.validation import InputRangeError, check_array_finite, check_positive

__all__ = ["CurvatureFit", "QuadraticWeights", "HALF", "QUADRATIC_LANES", "fit_curvatures",
           "fitted_coefficients", "pairwise_sum", "principal_curvatures", "quadratic_weights"]

#: The range of ``(c3 - c5)^2 + c4^2`` where :func:`principal_curvatures` takes its square
#: root directly (no overflow, no significant underflow; ``hypot`` outside).
_SQ_LO = 2.0 ** -900
_SQ_HI = 2.0 ** 1000

#: Taps before the stencil's centre tap (which is tap ``HALF``); the point reflection
#: (s, t) -> (-s, -t) maps tap i to ``N_TAPS - 1 - i``.
HALF = N_TAPS // 2
#: Lanes of :func:`fitted_coefficients`'s sums: lane ``l`` sums the taps
#: ``QUADRATIC_LANES * k + l`` (k = 0 .. HALF / QUADRATIC_LANES - 1), as the C code's
#: vector of four doubles does.
QUADRATIC_LANES = 4
if HALF % QUADRATIC_LANES:
    raise AssertionError("the half stencil must fill whole groups of lanes")


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


@dataclass(frozen=True)
class QuadraticWeights:
    """The quadratic rows of the baked pseudo-inverse (c3, c4, c5) about the centre tap.

    With ``i' = N_TAPS - 1 - i`` the point reflection of tap ``i < HALF`` and ``g0`` the
    centre sample, ``c_j = sum_i M_ji g_i`` is exactly
    ``sum_{i<HALF} pair_ji d_i + skew_ji e_i + total_j g0`` with the second differences
    ``d_i = (g_i - g0) + (g_i' - g0)`` and ``e_i = g_i' - g0`` (real arithmetic).

    Attributes
    ----------
    pair : numpy.ndarray, shape (3, HALF)
        ``M_ji`` for the taps ``i < HALF``, 1/mm^2.
    skew : numpy.ndarray, shape (3, HALF)
        ``M_ji' - M_ji``, the rows' departure from point symmetry (the weights are
        even under the reflection up to the pseudo-inverse's rounding, ~1e-14 of them),
        1/mm^2; exact where the two are within a factor of 2 (Sterbenz), else within
        half an ulp of the difference (~1e-30 of a weight).
    total : numpy.ndarray, shape (3,)
        ``sum_i M_ji`` over all taps, summed exactly and rounded once (``math.fsum``),
        1/mm^2 (~1e-14: zero but for that rounding).
    """

    pair: np.ndarray
    skew: np.ndarray
    total: np.ndarray


@lru_cache(maxsize=1)
def quadratic_weights() -> QuadraticWeights:
    """:class:`QuadraticWeights` of the baked pseudo-inverse (:func:`.pinv.baked_pinv`)."""
    rows = baked_pinv().weights[3:6]
    pair = rows[:, :HALF].copy()
    skew = rows[:, :HALF:-1] - pair
    total = np.array([math.fsum(row) for row in rows])
    for a in (pair, skew, total):
        a.setflags(write=False)
    return QuadraticWeights(pair=pair, skew=skew, total=total)


def pairwise_sum(terms: list, add):
    """Sum ``terms`` as a pairwise tree, adjacent terms first (``[t0, t1, t2, t3, t4]``:
    ``((t0 + t1) + (t2 + t3)) + t4``), with ``add(a, b)``: the order of the IEEE
    additions of :func:`fitted_coefficients`, and the C text of the same tree
    (gearcontact.export.c_constants)."""
    if not terms:
        raise ValueError("pairwise_sum of no terms")
    while len(terms) > 1:
        terms = [add(a, b) for a, b in zip(terms[::2], terms[1::2])] \
            + terms[len(terms) // 2 * 2:]
    return terms[0]


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
    baked = h == STENCIL_SPACING_MM
    m = baked_pinv().weights if baked else pseudo_inverse(h)
    c = m @ g
    if baked:
        c[3:6] = fitted_coefficients(g)
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
    at once, shape (..., 3): the baked ROM's weights, as :func:`fit_curvatures` applies
    them (the preview's and the twin's tables row by row).

    Notes
    -----
    ``c_j = sum_i M_ji g_i`` summed over the second differences about the centre
    (:class:`QuadraticWeights`): ``p_i = pair_ji d_i + skew_ji e_i`` in
    :data:`QUADRATIC_LANES` lanes, the groups of lanes summed by :func:`pairwise_sum`,
    then the lanes, then ``+ total_j g0``. The offset and the slopes, which the rows
    cancel, never enter a product: the rounding is ~1e-16 of
    ``sum_i |M_ji| |d_i|`` (the stencil's curvature and higher terms) instead of
    ``sum_i |M_ji g_i|`` (its offset and slopes; ~600x smaller for a near-cylindrical
    gear stencil, docs/export.md), plus the rounding of ``g_i - g0`` where it is not
    exact (it is for samples on a common grid, e.g. multiples of 2^-21 mm below 2^10 mm
    as the stencil ROM's). Elementwise IEEE operations in a fixed order: the same bits
    on every machine and in gc_fit_fp64.c (exported C).
    """
    g = np.asarray(gaps_mm, float)
    w = quadratic_weights()
    g0 = g[..., HALF:HALF + 1]
    e = g[..., :HALF:-1] - g0                       # the mirror taps N_TAPS - 1 .. HALF + 1
    d = (g[..., :HALF] - g0) + e
    p = w.pair * d[..., None, :] + w.skew * e[..., None, :]          # (..., 3, HALF)
    n = QUADRATIC_LANES
    lanes = pairwise_sum([p[..., k:k + n] for k in range(0, HALF, n)], np.add)
    return pairwise_sum([lanes[..., k] for k in range(n)], np.add) + w.total * g0
