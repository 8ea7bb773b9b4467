"""Stage A/B geometric contact-gap kernel (docs/spec.md sec. 6, Algorithm 1).

Three models that must agree:

- :mod:`.reference` -- fp64 (ideal and lane selection rules);
- :mod:`.golden` -- bit-exact fixed-point model, formats, timing model, error bound;
  :mod:`.fast` -- its vectorized (numba) twin for many points; :mod:`.precision` --
  the gap-error-versus-word-width sweep of docs/spec.md sec. 8;
- :mod:`.rtl` -- the Amaranth 0.5 core ``GapCore`` (imported on demand: it pulls in
  Amaranth); :mod:`.cores` -- its descriptors for the harness, vectors and SoC.
"""

from .fast import GapBatchCodes, GapBatchResult, gap_golden_batch, gap_golden_points
from .golden import (DEFAULT_FORMAT, IDX_SENTINEL, GapCodes, GapFormat, GapTiming,
                     GapVector, GoldenGapResult, gap_error_bound_mm, gap_golden,
                     gap_golden_codes, gap_golden_terms, gap_latency, gap_timing,
                     quantize_pass, quantize_tau2)
from .precision import PrecisionPoint, gap_precision_sweep
from .reference import GapResult, GapSampleTerms, gap_reference, gap_sample_terms

__all__ = ["GapResult", "GapSampleTerms", "gap_reference", "gap_sample_terms",
           "GapFormat", "DEFAULT_FORMAT", "GapVector", "GapCodes", "GoldenGapResult",
           "GapTiming", "IDX_SENTINEL", "quantize_pass", "quantize_tau2",
           "gap_golden_codes", "gap_golden_terms", "gap_golden", "gap_latency",
           "gap_timing", "gap_error_bound_mm", "GapBatchCodes", "gap_golden_batch", "GapBatchResult", "gap_golden_points",
           "PrecisionPoint", "gap_precision_sweep"]
