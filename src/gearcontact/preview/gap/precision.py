"""Fixed-point precision of the signed gap versus word widths (docs/spec.md sec. 8, item 8).

For each (coordinate fraction bits cf, normal fraction bits rf) the golden model's
per-sample signed gap is compared with the fp64 reference on the same seeded random
geometry, and the measured error is set beside the first-order bound
:func:`.golden.gap_error_bound_mm`::

    |e_g| <= sqrt(3) 2^-cf + 3 ||d||_inf 2^-(rf+1) + 2^-(cf+1)

The pose is a random signed permutation (exactly representable, so the posed point is
quantized once, as the bound assumes; see :func:`.golden.gap_error_bound_mm`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...validation import InputRangeError, check_positive
from .golden import GapFormat, gap_error_bound_mm, gap_golden_terms, quantize_pass
from .reference import gap_sample_terms

__all__ = ["PrecisionPoint", "gap_precision_sweep"]


@dataclass(frozen=True)
class PrecisionPoint:
    """Measured gap error at one word-width setting.

    Attributes
    ----------
    coord_frac, normal_frac : int
        Fraction bits cf and rf.
    max_error_mm, rms_error_mm : float
        Largest and RMS ``|gamma_golden - gamma_fp64|`` over the samples, mm.
    bound_mm : float
        First-order bound at the largest ``||d||_inf`` of the sample set, mm.
    max_bound_ratio : float
        Largest per-sample ratio error / bound(that sample's ``||d||_inf``); <= 1
        when the bound holds.
    """

    coord_frac: int
    normal_frac: int
    max_error_mm: float
    rms_error_mm: float
    bound_mm: float
    max_bound_ratio: float


def gap_precision_sweep(*, coord_fracs=range(14, 25), normal_fracs=(19,),
                        n_samples: int = 1000, spread_mm: float = 4.0,
                        seed: int = 0) -> tuple[PrecisionPoint, ...]:
    """Measure the signed-gap error of the golden model over word widths.

    Parameters
    ----------
    coord_fracs, normal_fracs : iterable of int, keyword-only
        cf values in [0, 24] and rf values in [8, 24]; every pair is measured.
    n_samples : int, keyword-only
        Random gear samples per setting (>= 1).
    spread_mm : float, keyword-only
        Samples and point are uniform in [-spread, spread]^3, mm (<= 60 so that
        p' and g stay inside the +-128 mm coordinate range).
    seed : int, keyword-only
        Seed of the geometry (one geometry shared by all settings).

    Returns
    -------
    tuple of PrecisionPoint
        One per (cf, rf), in iteration order (rf outer, cf inner).
    """
    spread = check_positive("spread_mm", spread_mm)
    if spread > 60.0:
        raise InputRangeError("spread_mm", spread_mm, "(0, 60] mm")
    if isinstance(n_samples, bool) or not isinstance(n_samples, int) or n_samples < 1:
        raise InputRangeError("n_samples", n_samples, "an integer >= 1")
    rng = np.random.default_rng(seed)
    perm = np.eye(3)[rng.permutation(3)] * rng.choice([-1.0, 1.0], 3)[:, None]
    R = perm if np.linalg.det(perm) > 0 else -perm
    p = rng.uniform(-spread, spread, 3)
    g = rng.uniform(-spread, spread, (n_samples, 3))
    n = rng.normal(size=(n_samples, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    t = np.zeros(3)
    ref = gap_sample_terms(R, t, p, g, n)
    d_inf = np.abs(ref.posed_point_mm - g).max(axis=1)
    out = []
    for rf in normal_fracs:
        for cf in coord_fracs:
            fmt = GapFormat(coord_frac=int(cf), normal_frac=int(rf))
            vec = quantize_pass(R, t, p, g, n, tau_mm=1.0, fmt=fmt)
            _, gam, _ = gap_golden_terms(vec, fmt=fmt)
            err = np.abs(fmt.gap.to_float(gam) - ref.gamma_mm)
            bound = np.array([gap_error_bound_mm(coord_frac=cf, normal_frac=rf, d_inf_mm=x)
                              for x in d_inf])
            out.append(PrecisionPoint(
                coord_frac=int(cf), normal_frac=int(rf), max_error_mm=float(err.max()),
                rms_error_mm=float(np.sqrt(np.mean(err ** 2))),
                bound_mm=gap_error_bound_mm(coord_frac=cf, normal_frac=rf,
                                            d_inf_mm=float(d_inf.max())),
                max_bound_ratio=float((err / bound).max())))
    return tuple(out)
