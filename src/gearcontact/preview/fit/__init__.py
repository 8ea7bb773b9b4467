"""Stage C of the physics-direct preview: the baked curvature fit (docs/spec.md sec. 6).

Three models side by side that share the ROM of :mod:`.pinv`:

- :mod:`.reference` -- fp64 least-squares fit and closed-form 2x2 eigen-solve;
- :mod:`.golden` -- bit-exact integer model of the fixed-point core + timing model;
- :mod:`.rtl` -- Amaranth 0.5 ``FitCore`` (49-tap MAC stream, non-restoring isqrt).
"""

from gearcontact.preview.fit.golden import (FIT_CYCLES, FLAG_ANY_OVERFLOW,
                                            FLAG_COEFF_OVERFLOW, FLAG_CURV_OVERFLOW,
                                            FLAG_D_OVERFLOW, FLAG_NOT_ELLIPTIC, GoldenFit,
                                            GoldenFitBatch, chain_cycles, decode_curvature,
                                            encode_gaps, golden_fit, golden_fit_batch)
from gearcontact.preview.fit.pinv import BakedPinv, baked_pinv
from gearcontact.preview.fit.reference import CurvatureFit, fit_curvatures
from gearcontact.contract.stencil import (STENCIL_SIDE, STENCIL_SIZE,
                                          STENCIL_SPACING_MM, stencil_coordinates)

__all__ = ["FIT_CYCLES", "FLAG_ANY_OVERFLOW", "FLAG_COEFF_OVERFLOW", "FLAG_CURV_OVERFLOW",
           "FLAG_D_OVERFLOW", "FLAG_NOT_ELLIPTIC", "GoldenFit", "GoldenFitBatch",
           "chain_cycles", "decode_curvature", "encode_gaps", "golden_fit",
           "golden_fit_batch", "BakedPinv", "baked_pinv", "CurvatureFit", "fit_curvatures",
           "STENCIL_SIDE", "STENCIL_SIZE", "STENCIL_SPACING_MM", "stencil_coordinates"]
