"""fp64 reference of stage D: the elliptic Hertz preview (Hamrock–Brewe or exact).

Sorts the half relative curvatures (``A_min <= B_max``), derives
``R_x = 1/(2 A_min)``, ``R_y = 1/(2 B_max)`` and evaluates, with
``hertz_form="hamrock-brewe"`` (default), the simplified Hamrock–Brewe forms through
:func:`gearcontact.analytic.hertz.hamrock_brewe_terms` (the package's single
implementation of those formulas; docs/spec.md sec. 6, Algorithm 3), or with
``hertz_form="exact"`` the exact elliptic-integral solution
:func:`gearcontact.analytic.hertz.exact_elliptic_hertz` (what the exact tables of the
fixed-point datapath hold, :mod:`.luts`; ~50 us per call).

The scalar path uses only ``math`` and costs about 1 us per call from Python
(``benchmarks/bench_preview_reference.py``); :func:`hertz_preview_array` evaluates
numpy batches.

Operating envelope (``envelope=True``, the default): the same domain the fixed-point
datapath accepts (:mod:`.formats`): curvatures in [2^-11, 16] 1/mm, load in
[1, 2^17] N, E' in [2^12, 2^21] MPa and alpha = B_max/A_min <= 128 (POW LUT range),
so that every backend of the preview accepts exactly the same inputs. With
``envelope=False`` only positivity and finiteness are required.

Near-line contact: :func:`truncated_preview` is the fp64 model of the line core's mode
rule (:mod:`.line`): the ellipse, or the Hertz line contact of the contact line's
length where the flank truncates a longer ellipse (docs/hertz.md sec. 6).

References
----------
B. J. Hamrock, D. E. Brewe, J. Lubrication Technol. 105 (1983) 171-177.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...analytic.hertz import (exact_elliptic_hertz, hamrock_brewe_hertz_array,
                               hamrock_brewe_terms, line_contact_hertz)
from ...analytic.hertz_range import within_hamrock_brewe_range
from ...validation import (InputRangeError, check_array_finite, check_positive, check_range,
                           format_number, format_range)
from ...contract.qformat import CURVATURE, LOAD
from . import formats as F
from . import line as LN
from .golden_vec import njit

__all__ = ["HertzPreview", "hertz_preview", "hertz_preview_array", "ENVELOPE",
           "check_envelope", "LINE_ENVELOPE", "LINE_LENGTH_RANGE_MM", "LINE_LENGTH_RANGE",
           "TruncatedPreview", "truncated_preview",
           "keeps_ellipse", "line_lift", "lifted_keeps_ellipse", "law_status", "LAW_OK",
           "LAW_BEYOND_RANGE", "HertzLawRangeWarning"]

#: Operating envelope in physical units: (field, lower, upper) — shared with the golden.
ENVELOPE = {
    "curvature_per_mm": (math.ldexp(F.CURV_MIN_CODE, -CURVATURE.frac),
                         math.ldexp(F.CURV_MAX_CODE, -CURVATURE.frac)),
    "load_n": (math.ldexp(F.LOAD_MIN_CODE, -LOAD.frac), math.ldexp(F.LOAD_MAX_CODE, -LOAD.frac)),
    "e_prime_mpa": (float(F.E_PRIME_MIN_CODE), float(F.E_PRIME_MAX_CODE)),
    "alpha": (1.0, math.ldexp(F.ALPHA_MAX_CODE, -F.ALPHA.frac)),
}
#: Operating envelope of the line core (:mod:`.line`): B_max (across the line) and
#: the contact-line length L; load and E' as :data:`ENVELOPE`; A_min >= 0.
LINE_ENVELOPE = {"B_max_per_mm": ENVELOPE["curvature_per_mm"],
                 "line_length_mm": (1.0, 1024.0)}
_C_LO, _C_HI = ENVELOPE["curvature_per_mm"]
_W_LO, _W_HI = ENVELOPE["load_n"]
_E_LO, _E_HI = ENVELOPE["e_prime_mpa"]
_ALPHA_HI = ENVELOPE["alpha"][1]
_new = object.__new__
_INF = math.inf
_L_SCALE = math.ldexp(1.0, LN.LINE_LENGTH.frac)     # LINE_LENGTH codes per mm
_W_SCALE = math.ldexp(1.0, LOAD.frac)               # LOAD codes per N
#: Contact-line lengths the line path answers (mm): the core's [1, 1024] mm and, through
#: the host's lift (:func:`.line.length_lift`), down to 2^-LIFT_MAX_SHIFT mm where the
#: lifted load stays in the envelope (:data:`LINE_LENGTH_RANGE`).
LINE_LENGTH_RANGE_MM = (math.ldexp(1.0, -LN.LIFT_MAX_SHIFT), LINE_ENVELOPE["line_length_mm"][1])
#: :data:`LINE_LENGTH_RANGE_MM` in words, with the lift's load condition.
LINE_LENGTH_RANGE = (f"[1, 1024] mm, or down to 2^-{LN.LIFT_MAX_SHIFT} = "
                     f"{format_number(LINE_LENGTH_RANGE_MM[0])} mm with load_n x 2^s <= "
                     f"{_W_HI:g} N for L x 2^s >= 1 mm (the line core's host lift)")


@dataclass(frozen=True)
class HertzPreview:
    """Stage-D preview of one contact (fp64).

    Attributes
    ----------
    a_mm : float
        Major semi-axis, mm (along the A_min principal direction).
    b_mm : float
        Minor semi-axis, mm.
    k : float
        Ellipticity a/b (alpha^(2/pi) in the Hamrock–Brewe form), dimensionless.
    p_max_mpa : float
        Peak Hertzian pressure, MPa.
    alpha : float
        Radius ratio R_x/R_y = B_max/A_min >= 1.
    R_x_mm, R_y_mm : float
        Principal relative radii 1/(2 A_min), 1/(2 B_max), mm.
    approach_mm : float
        Rigid-body approach delta of the chosen form, mm (compliance 2 delta/(3 W)).
    """

    a_mm: float
    b_mm: float
    k: float
    p_max_mpa: float
    alpha: float
    R_x_mm: float
    R_y_mm: float
    approach_mm: float


def _raise_input_error(A_minus, B_minus, load_n, e_prime_mpa, envelope: bool) -> None:
    """Raise :class:`InputRangeError` for the first offending input (slow path)."""
    vals = {"A_minus": check_positive("A_minus", A_minus),
            "B_minus": check_positive("B_minus", B_minus),
            "load_n": check_positive("load_n", load_n),
            "e_prime_mpa": check_positive("e_prime_mpa", e_prime_mpa)}
    if envelope:
        for name in ("A_minus", "B_minus"):
            check_range(name, vals[name], _C_LO, _C_HI)
        check_range("load_n", vals["load_n"], _W_LO, _W_HI)
        check_range("e_prime_mpa", vals["e_prime_mpa"], _E_LO, _E_HI)
        a, b = sorted((vals["A_minus"], vals["B_minus"]))
        raise InputRangeError("alpha = B_max/A_min", b / a, f"[1, {_ALPHA_HI:g}]")
    raise InputRangeError("inputs", (A_minus, B_minus, load_n, e_prime_mpa),
                          "finite numbers > 0")     # pragma: no cover (unreachable)


def check_envelope(A_minus, B_minus, load_n, *, e_prime_mpa) -> tuple[float, float, float]:
    """Return ``(A_minus, B_minus, load_n)`` as floats if they lie in the operating
    :data:`ENVELOPE` (the domain every backend accepts); else raise
    :class:`InputRangeError` naming the first offending input and its range."""
    try:
        a, b, w, e = float(A_minus), float(B_minus), float(load_n), float(e_prime_mpa)
    except (TypeError, ValueError):
        a = b = w = e = math.nan
    lo, hi = (a, b) if a <= b else (b, a)
    if not (_C_LO <= lo and hi <= _C_HI and _W_LO <= w <= _W_HI and _E_LO <= e <= _E_HI
            and hi <= _ALPHA_HI * lo):
        _raise_input_error(A_minus, B_minus, load_n, e_prime_mpa, True)
    return a, b, w


#: :func:`law_status` of a preview whose law is within its declared tolerance of exact
#: Hertz, or that no elliptic law answered (a line-mode or flagged preview).
LAW_OK = "ok"
#: :func:`law_status` of a Hamrock–Brewe ellipse beyond the ratio where the law is within
#: :data:`gearcontact.analytic.hertz_range.HB_TOLERANCE` of exact Hertz.
LAW_BEYOND_RANGE = "beyond_hamrock_brewe_range"


class HertzLawRangeWarning(UserWarning):
    """Previews whose Hamrock–Brewe law lies beyond the ratio where it is within its
    declared tolerance of exact Hertz (:func:`law_status`): a reported result, the run
    goes on (the command line prints it as one stderr line)."""


def law_status(A_minus: float, B_minus: float, *, hertz_form: str,
               mode: str = "elliptic") -> str:
    """Whether a preview's Hertz law holds at its curvatures: :data:`LAW_BEYOND_RANGE`
    for a Hamrock–Brewe ellipse (``hertz_form="hamrock-brewe"``, ``mode="elliptic"``)
    whose ratio ``B_max/A_min`` lies beyond
    :data:`gearcontact.analytic.hertz_range.HB_RATIO_LIMIT` (122: there the forms leave
    5 % of exact Hertz, growing to +51 % in stiffness at axis ratio 1000; docs/hertz.md
    sec. 7), else :data:`LAW_OK` (the exact form, the line contact, a flagged result).
    A reported result, never an error; every backend and the twin state it alike.

    Parameters
    ----------
    A_minus, B_minus : float
        Half relative principal curvatures that entered stage D, 1/mm, any order.
    hertz_form : str
        Stage-D form of the result (:data:`.formats.HERTZ_FORMS`).
    mode : str
        What evaluated stage D (``"elliptic"``, ``"line"``, ``"flagged"``).

    Returns
    -------
    str
    """
    if mode != "elliptic" or hertz_form != F.DEFAULT_HERTZ_FORM:
        return LAW_OK
    lo, hi = (A_minus, B_minus) if A_minus <= B_minus else (B_minus, A_minus)
    if not lo > 0.0:        # no ellipse (zero curvature: the line core's case)
        return LAW_OK
    return LAW_OK if within_hamrock_brewe_range(hi / lo) else LAW_BEYOND_RANGE


def hertz_preview(A_minus: float, B_minus: float, load_n: float, *, e_prime_mpa: float,
                  envelope: bool = True,
                  hertz_form: str = F.DEFAULT_HERTZ_FORM) -> HertzPreview:
    """Stage-D preview of one contact (fp64, scalar; Hamrock–Brewe in pure ``math``).

    Parameters
    ----------
    A_minus, B_minus : float
        Half relative principal curvatures (gap ``A s^2 + B t^2``), 1/mm, any order.
    load_n : float
        Normal load W, N.
    e_prime_mpa : float
        Effective modulus E' = 2E*, MPa (steel/steel 229 670).
    envelope : bool
        Enforce the datapath's operating envelope (module docstring).
    hertz_form : {"hamrock-brewe", "exact"}
        Simplified Hamrock–Brewe forms (default) or exact elliptic Hertz.

    Returns
    -------
    HertzPreview

    Raises
    ------
    InputRangeError
        Non-positive / non-finite input, or outside the envelope (names the field),
        or an unknown ``hertz_form``.
    """
    # Hot path: one chained comparison accepts valid input (NaN fails every comparison);
    # anything else goes to _raise_input_error, which names the field.
    if A_minus <= B_minus:
        a, b = A_minus, B_minus
    else:
        a, b = B_minus, A_minus
    w = load_n
    e = e_prime_mpa
    try:
        if envelope:
            ok = (_C_LO <= a and b <= _C_HI and _W_LO <= w <= _W_HI
                  and _E_LO <= e <= _E_HI and b <= _ALPHA_HI * a)
        else:
            ok = 0.0 < a and b < _INF and 0.0 < w < _INF and 0.0 < e < _INF
    except TypeError:
        ok = False
    if not ok:
        _raise_input_error(A_minus, B_minus, load_n, e_prime_mpa, envelope)
    if hertz_form != F.DEFAULT_HERTZ_FORM:
        F.check_hertz_form(hertz_form)
        ex = exact_elliptic_hertz(a, b, w, e_prime_mpa=e)
        return HertzPreview(ex.a_mm, ex.b_mm, ex.k, ex.p_max_mpa, ex.alpha, 0.5 / a,
                            0.5 / b, ex.approach_mm)
    a_mm, b_mm, k, p_max, delta, alpha, _, _, _ = hamrock_brewe_terms(a, b, w, e)
    # Fast construction of the frozen instance: the generated __init__ calls
    # object.__setattr__ once per field (~2 us for 8 fields); filling the instance
    # dict directly yields an identical object (same fields, __eq__, __repr__).
    out = _new(HertzPreview)
    out.__dict__.update(a_mm=a_mm, b_mm=b_mm, k=k, p_max_mpa=p_max, alpha=alpha,
                        R_x_mm=0.5 / a, R_y_mm=0.5 / b, approach_mm=delta)
    return out


def hertz_preview_array(A_minus, B_minus, load_n, *, e_prime_mpa, envelope: bool = True,
                        hertz_form: str = F.DEFAULT_HERTZ_FORM) -> dict:
    """Vectorized :func:`hertz_preview` over broadcastable arrays (the exact form loops
    over :func:`~gearcontact.analytic.hertz.exact_elliptic_hertz`, ~50 us per element).

    Returns
    -------
    dict of str -> ndarray
        ``a_mm, b_mm, k, p_max_mpa, alpha, R_x_mm, R_y_mm, approach_mm``.

    Raises
    ------
    InputRangeError
        The first offending element (field and index), as in the scalar path.
    """
    F.check_hertz_form(hertz_form)
    A = check_array_finite("A_minus", A_minus)
    B = check_array_finite("B_minus", B_minus)
    W = check_array_finite("load_n", load_n)
    E = check_array_finite("e_prime_mpa", e_prime_mpa)
    if envelope:
        lo_hi = {"A_minus": (A, _C_LO, _C_HI), "B_minus": (B, _C_LO, _C_HI),
                 "load_n": (W, _W_LO, _W_HI), "e_prime_mpa": (E, _E_LO, _E_HI)}
        for name, (x, lo, hi) in lo_hi.items():
            bad = ~((x >= lo) & (x <= hi))
            if bad.any():
                idx = tuple(int(i) for i in np.argwhere(bad)[0])
                raise InputRangeError(f"{name}[{', '.join(map(str, idx))}]" if x.ndim
                                      else name, x[idx], format_range(lo, hi))
        A, B = np.broadcast_arrays(A, B)
        ratio = np.maximum(A, B) / np.minimum(A, B)
        bad = ratio > _ALPHA_HI
        if bad.any():
            idx = tuple(int(i) for i in np.argwhere(bad)[0])
            raise InputRangeError("alpha = B_max/A_min" + (f"[{idx[0]}]" if idx else ""),
                                  ratio[idx], f"[1, {_ALPHA_HI:g}]")
    if hertz_form == "exact":
        hb = _exact_array(A, B, W, E)
    else:
        hb = hamrock_brewe_hertz_array(A, B, W, e_prime_mpa=E)
    a_min = np.minimum(A, B)
    b_max = np.maximum(A, B)
    a_min, b_max = np.broadcast_arrays(a_min, b_max)
    return {"a_mm": hb["a_mm"], "b_mm": hb["b_mm"], "k": hb["k"],
            "p_max_mpa": hb["p_max_mpa"], "alpha": hb["alpha"],
            "R_x_mm": np.broadcast_to(0.5 / a_min, hb["a_mm"].shape),
            "R_y_mm": np.broadcast_to(0.5 / b_max, hb["a_mm"].shape),
            "approach_mm": hb["approach_mm"]}


def _exact_array(A, B, W, E) -> dict:
    """Exact elliptic Hertz elementwise over broadcast arrays (same keys as
    :func:`~gearcontact.analytic.hertz.hamrock_brewe_hertz_array` that are used here)."""
    A, B, W, E = np.broadcast_arrays(A, B, W, E)
    keys = ("a_mm", "b_mm", "k", "p_max_mpa", "alpha", "approach_mm")
    out = {k: np.empty(A.shape) for k in keys}
    for idx in np.ndindex(A.shape):
        ex = exact_elliptic_hertz(A[idx], B[idx], W[idx], e_prime_mpa=E[idx])
        for k in keys:
            out[k][idx] = getattr(ex, k)
    return out


@dataclass(frozen=True)
class TruncatedPreview:
    """Stage-D preview of the line core (fp64): Hertz ellipse or, when the flank
    truncates it, Hertz line contact (:mod:`.line`).

    Attributes
    ----------
    mode : str
        ``"elliptic"`` or ``"line"``.
    a_mm : float
        Major semi-axis (elliptic) or half the contact-line length L/2 (line), mm.
    b_mm : float
        Minor semi-axis (elliptic) or half-width of the line contact, mm.
    k : float
        a/b, dimensionless.
    p_max_mpa : float
        Peak pressure, MPa.
    p_ellipse_mpa : float
        Peak of the untruncated ellipse, MPa (0 where the mode rule does not evaluate
        it: ratio beyond the datapath's 128 with ``envelope=True``, or A_min = 0).
    p_line_mpa : float
        Peak of the line contact of length L, MPa.
    """

    mode: str
    a_mm: float
    b_mm: float
    k: float
    p_max_mpa: float
    p_ellipse_mpa: float
    p_line_mpa: float


@njit(cache=True)
def keeps_ellipse(a_mm: float, p_ellipse_mpa: float, p_line_mpa: float,
                  length_mm: float) -> bool:
    """The line core's SELECT on an evaluated ellipse (pure; the twin compiles it): the
    ellipse when it fits the line (``a <= L/2``) or its peak is the higher of the two
    lower bounds of the truncated ellipse's (:mod:`.line`), else the line contact
    (compiled: the twin calls it)."""
    return a_mm <= 0.5 * length_mm or p_ellipse_mpa >= p_line_mpa


@njit(cache=True)
def line_lift(load_n: float, length_mm: float) -> float:
    """``2^s`` of the line core's host lift (:func:`.line.length_lift` on the LOAD and
    LINE_LENGTH codes of ``load_n`` (N, in the load envelope) and ``length_mm`` (mm)):
    1 for a length from 1 mm up, 0 where no lift applies (the core flags the length)."""
    l_code = math.floor(length_mm * _L_SCALE + 0.5)
    if l_code >= LN.LENGTH_MIN_CODE:
        return 1.0
    s = LN.length_lift(math.floor(load_n * _W_SCALE + 0.5), l_code)
    return 2.0 ** s if s > 0 else 0.0


@njit(cache=True)
def lifted_keeps_ellipse(a_mm: float, p_ellipse_mpa: float, p_line_mpa: float,
                         length_mm: float, lift: float) -> bool:
    """:func:`keeps_ellipse` of the line core's run on the lifted ``(k W, k L)``
    (``k = lift``, :func:`line_lift`): the ellipse of ``k W`` is ``k^(1/3)`` times
    longer with a ``k^(1/3)`` times higher peak, the line's pressure is unchanged."""
    c = lift ** (1.0 / 3.0)
    return keeps_ellipse(c * a_mm, c * p_ellipse_mpa, p_line_mpa, lift * length_mm)


def truncated_preview(A_minus: float, B_minus: float, load_n: float, length_mm: float, *,
                      e_prime_mpa: float, envelope: bool = True,
                      hertz_form: str = F.DEFAULT_HERTZ_FORM) -> TruncatedPreview:
    """fp64 model of the line core's mode rule (:mod:`.line`).

    Elliptic Hertz when the ellipse fits the contact line (``a <= L/2``); past that
    the higher of the two lower bounds of the truncated ellipse's peak, the untruncated
    ellipse's and the Hertz line contact of length L
    (:func:`~gearcontact.analytic.hertz.line_contact_hertz`, R = 1/(2 B_max)); the line
    contact alone where no ellipse is evaluated.

    Parameters
    ----------
    A_minus, B_minus : float
        Half relative principal curvatures, 1/mm, any order (the smaller one may be 0).
    load_n : float
        Normal load W, N.
    length_mm : float
        Length L of the contact line on the flank through the contact point along the
        ellipse's major axis, mm.
    e_prime_mpa : float
        E' = 2E*, MPa.
    envelope : bool
        Mirror the line core's domain (default): :data:`LINE_ENVELOPE` and the load /
        E' ranges of :data:`ENVELOPE` (else InputRangeError), and no ellipse for a
        ratio ``B_max/A_min > 128`` (the datapath's POW table); a length below 1 mm
        as the host's lift (:func:`.line.length_lift`) runs it: on ``(2^s W, 2^s L)``,
        answered in line mode only (the lifted run's ellipse kept: InputRangeError).
        False: the physics alone, for host-side previews of any positive input.
    hertz_form : {"hamrock-brewe", "exact"}
        Form of the elliptic part.

    Returns
    -------
    TruncatedPreview

    Raises
    ------
    InputRangeError
        A non-finite or non-positive input (the smaller curvature may be 0), or with
        ``envelope=True`` an input outside the line core's envelope (field named).
    """
    F.check_hertz_form(hertz_form)
    a_min, b_max = sorted((check_range("A_minus", A_minus, 0.0, _INF),
                           check_range("B_minus", B_minus, 0.0, _INF)))
    b_max = check_positive("B_max = max(A_minus, B_minus)", b_max)
    w = check_positive("load_n", load_n)
    length = check_positive("line_length_mm", length_mm)
    e = check_positive("e_prime_mpa", e_prime_mpa)
    lift = 1.0
    if envelope:
        check_range("B_max = max(A_minus, B_minus)", b_max, *LINE_ENVELOPE["B_max_per_mm"])
        check_range("load_n", w, _W_LO, _W_HI)
        check_range("e_prime_mpa", e, _E_LO, _E_HI)
        lift = line_lift(w, length)
        if lift == 0.0 or length > LINE_ENVELOPE["line_length_mm"][1]:
            raise InputRangeError("line_length_mm", length, LINE_LENGTH_RANGE)
    line = line_contact_hertz(0.5 / b_max, w, length, e_prime_mpa=e)
    if a_min > 0.0 and (not envelope or b_max <= _ALPHA_HI * a_min):
        ell = hertz_preview(a_min, b_max, w, e_prime_mpa=e, envelope=False,
                            hertz_form=hertz_form)
        if lifted_keeps_ellipse(ell.a_mm, ell.p_max_mpa, line.p_max_mpa, length, lift):
            if lift > 1.0:
                raise InputRangeError(
                    "line_length_mm", length, "[1, 1024] mm where the ellipse is kept "
                    "(below 1 mm the lifted line core answers in line mode only)")
            return TruncatedPreview("elliptic", ell.a_mm, ell.b_mm, ell.k, ell.p_max_mpa,
                                    ell.p_max_mpa, line.p_max_mpa)
        p_ellipse = ell.p_max_mpa
    else:
        p_ellipse = 0.0
    return TruncatedPreview("line", line.half_length_mm, line.b_mm,
                            line.half_length_mm / line.b_mm, line.p_max_mpa, p_ellipse,
                            line.p_max_mpa)
