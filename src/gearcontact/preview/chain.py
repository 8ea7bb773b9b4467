"""The C -> D chain: curvature fit of a 49-sample gap stencil, then elliptic Hertz.

One composition per representation, so that the three agree by construction of their
stages:

* :func:`chain_reference` — fp64 :func:`.fit.reference.fit_curvatures` then
  :func:`.hertz.reference.hertz_preview`;
* :func:`chain_golden` / :func:`chain_golden_batch` — the integer fit core output codes
  (A-, B- in CURVATURE Q(32,20)) feed the integer stage D unchanged, exactly as the
  datapath latches them (docs/spec.md sec. 6); cycle count :data:`CHAIN_CYCLES` = 806.

Chain flags word (what the tri_core ``flags`` readback carries): bits 0..7 are stage D's
``FLAG_*`` (:mod:`.hertz.formats`), bits 8..11 the fit core's ``FLAG_*``
(:mod:`.fit.golden`) shifted left by :data:`FIT_FLAG_SHIFT`. Stage D always runs on the
latched codes (as the hardware does); a fit overflow latches zeros, which stage D flags
as not elliptic — nothing is silently passed on.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .fit import golden as fit_golden_mod
from .fit.reference import CurvatureFit, fit_curvatures
from .hertz.formats import DEFAULT_HERTZ_FORM
from .hertz.formats import flag_names as hertz_flag_names
from .hertz.golden import HertzCodes, hertz_golden
from .hertz.golden_vec import HertzCodesArray, hertz_golden_array
from .hertz.reference import HertzPreview, hertz_preview
from .hertz.schedule import CHAIN_CYCLES

__all__ = ["ChainReference", "ChainCodes", "ChainCodesBatch", "chain_reference",
           "chain_golden", "chain_golden_batch", "chain_flag_names", "FIT_FLAG_SHIFT",
           "CHAIN_CYCLES"]

#: Position of the fit core's flags in the chain flags word.
FIT_FLAG_SHIFT = 8

_FIT_FLAG_NAMES = {
    fit_golden_mod.FLAG_COEFF_OVERFLOW: "fit_coefficient_overflow",
    fit_golden_mod.FLAG_D_OVERFLOW: "fit_discriminant_overflow",
    fit_golden_mod.FLAG_CURV_OVERFLOW: "fit_curvature_overflow",
    fit_golden_mod.FLAG_NOT_ELLIPTIC: "fit_not_elliptic",
}


def chain_flag_names(flags: int) -> tuple[str, ...]:
    """Names of the raised bits of a chain flags word (fit names first)."""
    fit_bits = flags >> FIT_FLAG_SHIFT
    names = tuple(n for bit, n in _FIT_FLAG_NAMES.items() if fit_bits & bit)
    return names + hertz_flag_names(flags & ((1 << FIT_FLAG_SHIFT) - 1))


@dataclass(frozen=True)
class ChainReference:
    """fp64 C -> D result: the curvature fit and the Hertz preview it feeds."""

    fit: CurvatureFit
    hertz: HertzPreview


@dataclass(frozen=True)
class ChainCodes:
    """Golden C -> D result for one stencil.

    Attributes
    ----------
    fit : gearcontact.preview.fit.golden.GoldenFit
        Fit core outputs (A-, B- in CURVATURE Q(32,20)).
    hertz : HertzCodes
        Stage-D outputs (a, b Q(32,20) mm; p_max Q(32,8) MPa; k Q(32,20)).
    flags : int
        Chain flags word (module docstring); 0 means valid.
    cycles : int
        Hardware cycles from go to done (:data:`CHAIN_CYCLES`, data independent).
    """

    fit: fit_golden_mod.GoldenFit
    hertz: HertzCodes
    flags: int
    cycles: int = CHAIN_CYCLES

    @property
    def flag_names(self) -> tuple[str, ...]:
        return chain_flag_names(self.flags)


@dataclass(frozen=True)
class ChainCodesBatch:
    """Vectorized golden C -> D results (``int64`` arrays, one row per stencil)."""

    fit: fit_golden_mod.GoldenFitBatch
    hertz: HertzCodesArray
    flags: np.ndarray


def chain_reference(gaps_mm, load_n: float, *, e_prime_mpa: float,
                    hertz_form: str = DEFAULT_HERTZ_FORM) -> ChainReference:
    """fp64 C -> D on one stencil (gaps in mm, order of :mod:`.fit.stencil`); stage D in
    the Hertz form ``hertz_form`` (:data:`.hertz.formats.HERTZ_FORMS`).

    Raises
    ------
    InputRangeError
        Bad stencil (length, NaN), a non-elliptic fit (B- <= 0) or Hertz inputs outside
        the envelope — each naming the field.
    """
    from ..validation import InputRangeError

    fit = fit_curvatures(gaps_mm)
    if not fit.elliptic:
        raise InputRangeError("fitted B_minus (1/mm)", fit.B_minus_per_mm,
                              "> 0 (the stencil is not an elliptic point contact)")
    return ChainReference(fit, hertz_preview(fit.A_minus_per_mm, fit.B_minus_per_mm,
                                             load_n, e_prime_mpa=e_prime_mpa,
                                             hertz_form=hertz_form))


def chain_golden(gap_codes, W_code: int, *, e_prime_code: int,
                 hertz_form: str = DEFAULT_HERTZ_FORM) -> ChainCodes:
    """Golden C -> D on one stencil of GAP Q(32,16) codes and a LOAD Q(32,8) code
    (stage D in the Hertz form ``hertz_form``)."""
    fit = fit_golden_mod.golden_fit(gap_codes, bitwise=False)
    hz = hertz_golden(fit.a_minus_code, fit.b_minus_code, W_code, e_prime_code=e_prime_code,
                      hertz_form=hertz_form)
    return ChainCodes(fit=fit, hertz=hz, flags=hz.flags | (fit.flags << FIT_FLAG_SHIFT))


def chain_golden_batch(gap_codes, W_code, *, e_prime_code,
                       hertz_form: str = DEFAULT_HERTZ_FORM) -> ChainCodesBatch:
    """Vectorized, bit-identical :func:`chain_golden` over n stencils, shape (n, 49)."""
    fit = fit_golden_mod.golden_fit_batch(gap_codes)
    hz = hertz_golden_array(fit.a_minus_codes, fit.b_minus_codes, W_code,
                            e_prime_code=e_prime_code, hertz_form=hertz_form)
    return ChainCodesBatch(fit=fit, hertz=hz,
                           flags=hz.flags | (fit.flags.astype(np.int64) << FIT_FLAG_SHIFT))


