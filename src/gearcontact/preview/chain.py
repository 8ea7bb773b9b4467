"""The C -> D chain: curvature fit of a 49-sample gap stencil, then elliptic Hertz.

One composition per representation, so that the three agree by construction of their
stages:

* :func:`chain_reference` — fp64 :func:`.fit.reference.fit_curvatures` then
  :func:`.hertz.reference.hertz_preview`;
* :func:`chain_golden` / :func:`chain_golden_batch` — the integer fit core output codes
  (A-, B- in CURVATURE Q(32,20)) feed the integer stage D unchanged, exactly as the
  datapath latches them (docs/spec.md sec. 6); cycle count :data:`CHAIN_CYCLES` = 806.

Near-line contact, the *line chain* (docs/hertz.md sec. 6): the same fit feeding the
line core of stage D (:mod:`.hertz.line`) with the contact line's length L on the flank,
so a stencil whose ellipse is longer than the flank (or whose B- is below the published
core's 2^-11 1/mm) gets the truncated-ellipse answer instead of a flag:

* :func:`chain_line_reference` — fp64 fit then :func:`.hertz.reference.truncated_preview`;
* :func:`chain_line_golden` / :func:`chain_line_golden_batch` — the fit codes into
  :func:`.hertz.line.line_golden` (:func:`.hertz.line_vec.line_golden_array`);
  :data:`CHAIN_LINE_CYCLES` = 52 + 759 = 811 (the line core's own capture is not
  absorbed: :class:`.chain_line_rtl.ChainLineCore`). The published chain (806 cycles)
  is unchanged. :func:`lifted_chain_line_golden_batch` is the host's path around it (a
  line shorter than the core's 1 mm lifted, :mod:`.hertz.line`).

Chain flags word (what the tri_core ``flags`` readback carries): bits 0..7 are stage D's
``FLAG_*`` (:mod:`.hertz.formats`; the line chain: the line core's, bit 7
``length_range`` included), bits 8..11 the fit core's ``FLAG_*``
(:mod:`.fit.golden`) shifted left by :data:`FIT_FLAG_SHIFT`. Stage D always runs on the
latched codes (as the hardware does); a fit overflow latches zeros, which stage D flags
as not elliptic (the line core: curvature range) — nothing is silently passed on. The
line chain carries only the fit's overflow bits (:data:`LINE_CHAIN_FIT_FLAGS`): its
``not_elliptic`` (B- <= 0) is the line core's to judge, B- = 0 being a line contact
(a cylinder) and B- < 0 a saddle the line core flags ``not_elliptic``. The fit resolves
B- only to the gap rounding's share of its error, :data:`LINE_B_ZERO_CODES` codes
(5.3e-5 1/mm with the degree-6 ROM and STENCIL_GAP Q(32,21) inputs),
so between the fit and the line core a B- code in ``[-LINE_B_ZERO_CODES, 0)`` is taken
as 0, a line contact (:func:`line_b_minus`; a saddle is a B- below that).
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
from .hertz.line import LINE_CYCLES, LineCodes, line_flag_names, line_golden
from .hertz.line_vec import LineCodesArray, lifted_line_golden_array, line_golden_array
from .hertz.reference import HertzPreview, TruncatedPreview, hertz_preview, truncated_preview
from .hertz.schedule import CHAIN_CYCLES
from ..contract.qformat import CURVATURE

__all__ = ["ChainReference", "ChainCodes", "ChainCodesBatch", "chain_reference",
           "chain_golden", "chain_golden_batch", "chain_flag_names", "FIT_FLAG_SHIFT",
           "CHAIN_CYCLES", "CHAIN_LINE_CYCLES", "ChainLineReference", "ChainLineCodes",
           "ChainLineCodesBatch", "chain_line_reference", "chain_line_golden",
           "chain_line_golden_batch", "lifted_chain_line_golden_batch",
           "LINE_CHAIN_FIT_FLAGS", "LINE_B_ZERO_CODES", "line_b_minus"]

#: Position of the fit core's flags in the chain flags word.
FIT_FLAG_SHIFT = 8

_FIT_FLAG_NAMES = {
    fit_golden_mod.FLAG_COEFF_OVERFLOW: "fit_coefficient_overflow",
    fit_golden_mod.FLAG_D_OVERFLOW: "fit_discriminant_overflow",
    fit_golden_mod.FLAG_CURV_OVERFLOW: "fit_curvature_overflow",
    fit_golden_mod.FLAG_NOT_ELLIPTIC: "fit_not_elliptic",
}


#: go -> done of the line chain: the fit core (52 edges to its latch), then the line
#: core from its own go (759; CAPTURE and SORT + SCALE are its own cycles).
CHAIN_LINE_CYCLES = fit_golden_mod.FIT_CYCLES + LINE_CYCLES
assert CHAIN_LINE_CYCLES == 811
#: Fit flags the line chain carries (module docstring).
LINE_CHAIN_FIT_FLAGS = fit_golden_mod.FLAG_ANY_OVERFLOW


def _b_zero_codes() -> int:
    """Resolution of the fitted B- (CURVATURE codes): the gap rounding (half a
    STENCIL_GAP LSB) through the ROM, |dB-| <= |dc3| + |dc5| + |dc4|/2 with
    |dc_j| <= ||Mq_j||_1 lsb/2 (B- = h - r, h = (c3 + c5)/2, r = |((c3 - c5)/2, c4/2)|), plus 5 codes for the
    coefficient rounding (2.5) and the fit's own rounding and floor square root (2)."""
    from .fit.pinv import baked_pinv
    from ..contract.qformat import STENCIL_GAP
    l1 = np.abs(baked_pinv().quantized_weights).sum(axis=1)
    bound = STENCIL_GAP.lsb / 2 * (l1[3] + l1[5] + l1[4] / 2)
    return int(np.ceil(bound * (1 << CURVATURE.frac))) + 5


#: B- codes in ``[-LINE_B_ZERO_CODES, 0)`` are a line contact in the line chain: 56 (the
#: degree-6 ROM's row norms 88.3 / 49.7 / 88.3 1/mm^2 at 2^-22 mm; was 119 with the
#: degree-2 ROM at GAP's 2^-17 mm).
LINE_B_ZERO_CODES = _b_zero_codes()
assert LINE_B_ZERO_CODES == 56


def line_b_minus(b_minus):
    """The fitted B- code(s) the line core takes: 0 for a code within the fit's
    resolution below zero (:data:`LINE_B_ZERO_CODES`), else unchanged (int or array)."""
    if isinstance(b_minus, np.ndarray):
        return np.where((b_minus < 0) & (b_minus >= -LINE_B_ZERO_CODES), 0, b_minus)
    return 0 if -LINE_B_ZERO_CODES <= b_minus < 0 else b_minus


def chain_flag_names(flags: int, *, line: bool = False) -> tuple[str, ...]:
    """Names of the raised bits of a chain flags word (fit names first); ``line``: the
    line chain's word (stage D's bits named by :data:`.hertz.line.LINE_FLAG_NAMES`)."""
    fit_bits = flags >> FIT_FLAG_SHIFT
    names = tuple(n for bit, n in _FIT_FLAG_NAMES.items() if fit_bits & bit)
    stage_d = line_flag_names if line else hertz_flag_names
    return names + stage_d(flags & ((1 << FIT_FLAG_SHIFT) - 1))


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
    """fp64 C -> D on one stencil (gaps in mm, order of
    :mod:`gearcontact.contract.stencil`); stage D in the Hertz form ``hertz_form``
    (:data:`.hertz.formats.HERTZ_FORMS`).

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
    """Golden C -> D on one stencil of STENCIL_GAP Q(32,21) codes and a LOAD Q(32,8) code
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


# ---------------------------------------------------------------------------------
# the line chain: fit -> line core (near-line contact)
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class ChainLineReference:
    """fp64 C -> line core: the curvature fit and the truncated preview it feeds."""

    fit: CurvatureFit
    hertz: TruncatedPreview


@dataclass(frozen=True)
class ChainLineCodes:
    """Golden C -> line core result for one stencil.

    Attributes
    ----------
    fit : gearcontact.preview.fit.golden.GoldenFit
        Fit core outputs (A-, B- in CURVATURE Q(32,20)).
    hertz : LineCodes
        Line-core outputs (a, b Q(32,20) mm; p_max Q(32,8) MPa; k Q(32,20); mode, scale).
    flags : int
        Chain flags word (module docstring); 0 means valid.
    cycles : int
        Hardware cycles from go to done (:data:`CHAIN_LINE_CYCLES`, data independent).
    """

    fit: fit_golden_mod.GoldenFit
    hertz: LineCodes
    flags: int
    cycles: int = CHAIN_LINE_CYCLES

    @property
    def flag_names(self) -> tuple[str, ...]:
        return chain_flag_names(self.flags, line=True)


@dataclass(frozen=True)
class ChainLineCodesBatch:
    """Vectorized golden C -> line core results (``int64`` arrays, one row per stencil)."""

    fit: fit_golden_mod.GoldenFitBatch
    hertz: LineCodesArray
    flags: np.ndarray


def chain_line_reference(gaps_mm, load_n: float, length_mm: float, *, e_prime_mpa: float,
                         envelope: bool = True,
                         hertz_form: str = DEFAULT_HERTZ_FORM) -> ChainLineReference:
    """fp64 C -> line core on one stencil (gaps in mm) with the contact line's length
    ``length_mm`` (mm) on the flank; ``envelope`` as for
    :func:`.hertz.reference.truncated_preview`.

    Raises
    ------
    InputRangeError
        Bad stencil, a fit that is not a point or line contact (B- < 0), or inputs
        outside the line core's envelope (with ``envelope=True``) — naming the field.
    """
    fit = fit_curvatures(gaps_mm)
    # a B- below zero within the fit's resolution is a line contact (module docstring);
    # truncated_preview names a saddle
    b_minus = fit.B_minus_per_mm
    if -LINE_B_ZERO_CODES * CURVATURE.lsb <= b_minus < 0.0:
        b_minus = 0.0
    return ChainLineReference(fit, truncated_preview(
        fit.A_minus_per_mm, b_minus, load_n, length_mm, e_prime_mpa=e_prime_mpa,
        envelope=envelope, hertz_form=hertz_form))


def chain_line_golden(gap_codes, W_code: int, L_code: int, *, e_prime_code: int,
                      hertz_form: str = DEFAULT_HERTZ_FORM) -> ChainLineCodes:
    """Golden C -> line core on one stencil of STENCIL_GAP Q(32,21) codes, a LOAD Q(32,8)
    code and a contact-line length :data:`.hertz.line.LINE_LENGTH` Q(32,20) code."""
    fit = fit_golden_mod.golden_fit(gap_codes, bitwise=False)
    lc = line_golden(fit.a_minus_code, line_b_minus(fit.b_minus_code), W_code, L_code,
                     e_prime_code=e_prime_code, hertz_form=hertz_form)
    return ChainLineCodes(fit=fit, hertz=lc, flags=lc.flags | (
        (fit.flags & LINE_CHAIN_FIT_FLAGS) << FIT_FLAG_SHIFT))


def chain_line_golden_batch(gap_codes, W_code, L_code, *, e_prime_code,
                            hertz_form: str = DEFAULT_HERTZ_FORM) -> ChainLineCodesBatch:
    """Vectorized, bit-identical :func:`chain_line_golden` over n stencils, (n, 49)."""
    return _chain_line_batch(gap_codes, W_code, L_code, e_prime_code=e_prime_code,
                             hertz_form=hertz_form, lifted=False)[0]


def lifted_chain_line_golden_batch(gap_codes, W_code, L_code, *, e_prime_code,
                                   hertz_form: str = DEFAULT_HERTZ_FORM
                                   ) -> tuple[ChainLineCodesBatch, np.ndarray]:
    """The host's line chain over n stencils: :func:`chain_line_golden_batch` with a line
    shorter than the core's 1 mm lifted (:func:`.hertz.line_vec.lifted_line_golden_array`:
    the line core on ``(W << s, L << s)``, undone), as the preview engine runs it.
    Returns the batch (stage D's outputs and flags unlifted) and the lift ``s`` of each
    stencil (``int64``)."""
    return _chain_line_batch(gap_codes, W_code, L_code, e_prime_code=e_prime_code,
                             hertz_form=hertz_form, lifted=True)


def _chain_line_batch(gap_codes, W_code, L_code, *, e_prime_code, hertz_form, lifted):
    """The fit batch, the line core on its codes (``lifted``: the host's path), the chain
    flags; ``(batch, lift or None)``."""
    fit = fit_golden_mod.golden_fit_batch(gap_codes)
    args = (fit.a_minus_codes, line_b_minus(fit.b_minus_codes), W_code, L_code)
    kw = {"e_prime_code": e_prime_code, "hertz_form": hertz_form}
    lc, lift = (lifted_line_golden_array(*args, **kw) if lifted
                else (line_golden_array(*args, **kw), None))
    return ChainLineCodesBatch(fit=fit, hertz=lc, flags=lc.flags | (
        (fit.flags.astype(np.int64) & LINE_CHAIN_FIT_FLAGS) << FIT_FLAG_SHIFT)), lift
