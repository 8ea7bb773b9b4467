"""Bit-exact integer golden model of the serialized stage D (elliptic Hertz).

The model computes exactly what the datapath computes (docs/spec.md sec. 6, Algorithm 3),
operation by operation, with Python integers: no floating point. Register formats,
constants and the operating envelope are tabulated in :mod:`.formats`, the ROMs in
:mod:`.luts`, the divider in :mod:`.divider` and the cycle schedule in :mod:`.schedule`.

Operation sequence (codes; ``rs`` = round-half-up shift, ``//`` = the divider)::

    SORT      A_min, B_max = min(A, B), max(A, B); envelope checks -> flags
    DIV_RX    R_x   = rs(2^40 // A_min, 1)                         Q(32,20)
    DIV_RY    R_y   = rs(2^40 // B_max, 1)                         Q(32,20)
    DIV_ALPHA alpha = (B_max << 24) // A_min     ; > 2^31 -> FLAG_ALPHA_RANGE
    DIV_R     R     = 2^42 // (A_min + B_max)    || K = rs(POW(alpha), 16)
    DIV_EE    E6    = C6 + N5 // alpha           || K2 = rs(K K, 20)
              (hertz_form="exact": K = rs(POWX(alpha), 16) and
               E6 = C6 + (EEX(alpha) << 9) // alpha, tables of :mod:`.luts`)
    PRODUCT   T1 = rs(K2 E6, 32); T2 = rs(T1 R, 18); T3 = T2 W
    DIV_CA    C_a   = (T3 << 11) // E'
    CBRT      p = floor((msb(C_a) - 45)/3); m = C_a >> (16 + 3p) (<< if negative)
              a_w = rs(CBRT(m), 10 - p)
    DIV_B     b_w   = (a_w << 24) // K
    DIV_PN2   p_n2  = (W C3 << 16) // a_w
    DIV_PMAX  p_max = rs((p_n2 << 17) // b_w, 1)
    outputs   a = rs(a_w, 16), b = rs(b_w, 16), k = rs(K, 4); overflow -> FLAG_OVERFLOW

Flag semantics (what the RTL implements): the flags register only records the first
check stage that fails (SORT, then DIV_ALPHA, then the divider zero test and the
output checks); once any flag is set the schedule still runs to completion (fixed
latency) but every numeric output except the sorted curvature registers reads 0.

Accuracy against the fp64 reference of the same formulas (:mod:`.reference`),
measured on 200 000 seeded points per material of the accuracy domain A-, B- in
[1e-3, 1] 1/mm, alpha <= 127.5, W in [10, 20 000] N, for steel/steel, aluminium,
titanium and steel/cast iron (``tests/preview/hertz/test_golden.py`` asserts it on
25 000 points per material); maximum relative errors:

=========  ===========================  =================  =======================
output     datapath only (reference     same, alpha > 5    end to end (reference
           at the decoded input codes)                     at the real inputs)
=========  ===========================  =================  =======================
k          1.9e-4 (rms 6e-5)            2.7e-6             6.8e-4
a          1.4e-4 (rms 4e-5)            7.8e-6             3.6e-4
b          7.7e-5 (rms 2e-5)            3.3e-5             3.3e-4
p_max      1.25e-4 (rms 2e-5)           3.9e-5             3.4e-4
=========  ===========================  =================  =======================

The datapath error is dominated by the POW interpolation near alpha = 1 (cubic
remainder, :mod:`.luts`) and, beyond alpha = 5, by the half-LSB rounding of the
output registers (small b, p_max); the end-to-end figure adds the CURVATURE input
quantization (+-2^-21 1/mm, i.e. 4.8e-4 relative at A- = 1e-3). All are at least
7x inside the requirement of 0.5 % (docs/spec.md sec. 6). The ``hertz_form="exact"``
variant is measured against exact Hertz instead (the package docstring's table: end to end
at most 5.4e-4).

References
----------
B. J. Hamrock, D. E. Brewe, J. Lubrication Technol. 105 (1983) 171-177.
J.-M. Muller, *Elementary Functions*, 3rd ed., 2016 (table methods, range reduction).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...validation import check_array_finite, check_finite
from ...contract.qformat import CURVATURE, LOAD, PMAX, SEMI_AXIS, round_shift
from . import formats as F
from .divider import DIVIDER_BITS, floor_divide, restoring_divide
from .luts import CBRT_SPEC, EE_DIVIDEND_SHIFT, EE_EXACT_SPEC, POW_SPECS, lut_interpolate

__all__ = ["HertzCodes", "HertzGoldenValues", "hertz_golden", "hertz_golden_trace",
           "envelope_flags",
           "encode_hertz_inputs", "encode_e_prime", "decode_hertz_codes"]

_PRODUCT_LIMIT = 1 << 64        # every product is below this (docs/spec.md sec. 6: 2^66)


@dataclass(frozen=True)
class HertzCodes:
    """Output registers of one stage-D run (integer codes).

    Attributes
    ----------
    a_code, b_code : int
        Semi-axes, SEMI_AXIS Q(32,20), mm.
    p_max_code : int
        Peak pressure, PMAX Q(32,8), MPa.
    k_code : int
        Ellipticity a/b, Q(32,20), dimensionless.
    A_min_code, B_max_code : int
        Sorted curvatures, CURVATURE Q(32,20), 1/mm (always the latched inputs).
    R_x_code, R_y_code : int
        Principal relative radii, Q(32,20), mm.
    alpha_code : int
        Radius ratio R_x/R_y, UQ(32,24).
    flags : int
        Bitmask of :mod:`.formats` ``FLAG_*``; 0 means valid.
    """

    a_code: int
    b_code: int
    p_max_code: int
    k_code: int
    A_min_code: int
    B_max_code: int
    R_x_code: int
    R_y_code: int
    alpha_code: int
    flags: int

    @property
    def valid(self) -> bool:
        """True when no flag is set."""
        return self.flags == 0

    @property
    def flag_names(self) -> tuple[str, ...]:
        """Names of the raised flags."""
        return F.flag_names(self.flags)


@dataclass(frozen=True)
class HertzGoldenValues:
    """Decoded golden outputs in physical units (floats or float64 arrays).

    Attributes
    ----------
    a_mm, b_mm : float
        Semi-axes, mm.
    k : float
        Ellipticity a/b.
    p_max_mpa : float
        Peak pressure, MPa.
    alpha : float
        R_x/R_y.
    R_x_mm, R_y_mm : float
        Principal relative radii, mm.
    A_min_per_mm, B_max_per_mm : float
        Sorted half relative curvatures, 1/mm.
    flags : int
        Flags word(s); outputs are 0 where flags != 0.
    """

    a_mm: object
    b_mm: object
    k: object
    p_max_mpa: object
    alpha: object
    R_x_mm: object
    R_y_mm: object
    A_min_per_mm: object
    B_max_per_mm: object
    flags: object

    @property
    def valid(self):
        """True (elementwise) where no flag is set."""
        return self.flags == 0


def _check_code(code, fmt, field: str) -> int:
    if isinstance(code, bool) or not isinstance(code, (int, np.integer)):
        raise TypeError(f"{field} must be an integer code, got {type(code).__name__}")
    return int(fmt.check(int(code), field=field))


def envelope_flags(a_min: int, b_max: int, w: int, e_prime: int) -> int:
    """Flags raised in state SORT for sorted curvature codes, load and E' codes."""
    flags = 0
    if a_min <= 0:
        flags |= F.FLAG_NOT_ELLIPTIC
    elif a_min < F.CURV_MIN_CODE or b_max > F.CURV_MAX_CODE:
        flags |= F.FLAG_CURV_RANGE
    if not F.LOAD_MIN_CODE <= w <= F.LOAD_MAX_CODE:
        flags |= F.FLAG_LOAD_RANGE
    if not F.E_PRIME_MIN_CODE <= e_prime <= F.E_PRIME_MAX_CODE:
        flags |= F.FLAG_E_PRIME_RANGE
    return flags


def _mul(x: int, y: int, what: str) -> int:
    p = x * y
    assert 0 <= p < _PRODUCT_LIMIT, f"product {what} = {p} exceeds 2^64"
    return p


def _flagged(a_min: int, b_max: int, flags: int) -> HertzCodes:
    return HertzCodes(0, 0, 0, 0, a_min, b_max, 0, 0, 0, flags)


def hertz_golden(A_code: int, B_code: int, W_code: int, *, e_prime_code: int,
                 bit_serial: bool = False,
                 hertz_form: str = F.DEFAULT_HERTZ_FORM) -> HertzCodes:
    """Run the stage-D datapath on one input set (bit-exact with the RTL).

    Parameters
    ----------
    A_code, B_code : int
        Half relative principal curvatures, CURVATURE Q(32,20), 1/mm, any order.
    W_code : int
        Contact load, LOAD Q(32,8), N.
    e_prime_code : int
        Effective modulus E' = 2E*, :data:`.formats.E_PRIME` Q(32,0), MPa
        (:func:`encode_e_prime`).
    bit_serial : bool
        Run every division through the 80-iteration restoring model instead of the
        floor-division fast path (identical results, ~100x slower).
    hertz_form : {"hamrock-brewe", "exact"}
        Contents of the k and E_e terms (:data:`.formats.HERTZ_FORMS`): the published
        simplified forms (default) or the exact elliptic solution in the same tables.

    Returns
    -------
    HertzCodes

    Raises
    ------
    FixedPointOverflow
        An input code does not fit its 32-bit register (the caller's error; values
        that fit but lie outside the operating envelope are flagged instead).
    InputRangeError
        Unknown ``hertz_form``.
    """
    return _run(A_code, B_code, W_code, e_prime_code, bit_serial, None,
                F.check_hertz_form(hertz_form))


def hertz_golden_trace(A_code: int, B_code: int, W_code: int, *, e_prime_code: int,
                       hertz_form: str = F.DEFAULT_HERTZ_FORM) -> tuple[HertzCodes, dict]:
    """:func:`hertz_golden` plus every internal register, for stage-by-stage RTL checks.

    Returns
    -------
    codes : HertzCodes
    trace : dict
        Register name -> integer code, in datapath order (``A_min, B_max, flags_sort,
        R_x, R_y, alpha, R, K, E6, K2, T1, T2, T3, C_a, p, m, cbrt, a_w, b_w, p_n2,
        p_max``; formats in :mod:`.formats`; ``N_ee``, the shifted EEX interpolation,
        with ``hertz_form="exact"``), plus ``"divisions"``: the list of
        ``(name, dividend, divisor, quotient)`` in divider order. A flagged run stops
        recording where the datapath's results stop mattering.
    """
    trace: dict = {"divisions": []}
    codes = _run(A_code, B_code, W_code, e_prime_code, False, trace,
                 F.check_hertz_form(hertz_form))
    return codes, trace


def _run(A_code, B_code, W_code, e_prime_code, bit_serial: bool, trace,
         hertz_form: str) -> HertzCodes:
    """The datapath (module docstring); ``trace`` (dict or None) records registers."""
    A = _check_code(A_code, CURVATURE, "A_code")
    B = _check_code(B_code, CURVATURE, "B_code")
    W = _check_code(W_code, LOAD, "W_code")
    E = _check_code(e_prime_code, F.E_PRIME, "e_prime_code")
    div = restoring_divide if bit_serial else floor_divide

    def divide(name: str, n: int, d: int) -> int:
        assert 0 <= n < (1 << DIVIDER_BITS), "dividend exceeds the 80-bit register"
        res = div(n, d)
        if trace is not None:
            trace["divisions"].append((name, n, d, res.quotient))
        if res.divide_by_zero:
            raise _DivZero
        return res.quotient

    def reg(name: str, value: int, fmt=None) -> int:
        assert fmt is None or fmt.fits(value), f"register {name} = {value} exceeds {fmt}"
        if trace is not None:
            trace[name] = value
        return value

    # SORT
    a_min, b_max = reg("A_min", min(A, B)), reg("B_max", max(A, B))
    flags = reg("flags_sort", envelope_flags(a_min, b_max, W, E))
    if flags:
        return _flagged(a_min, b_max, flags)
    try:
        # DIV_RX, DIV_RY
        r_x = reg("R_x", round_shift(divide("R_x", 1 << 40, a_min), 1))
        r_y = reg("R_y", round_shift(divide("R_y", 1 << 40, b_max), 1))
        # DIV_ALPHA
        alpha = reg("alpha", divide("alpha", b_max << F.ALPHA.frac, a_min))
        if alpha > F.ALPHA_MAX_CODE:
            return _flagged(a_min, b_max, F.FLAG_ALPHA_RANGE)
        # DIV_R || POW
        radius = reg("R", divide("R", 1 << 42, a_min + b_max), F.RADIUS)
        pow_spec = POW_SPECS[hertz_form]
        k_int = reg("K", round_shift(lut_interpolate(alpha, pow_spec),
                                     pow_spec.out_frac - F.K_INT.frac), F.K_INT)
        # DIV_EE || k^2 (exact form: the dividend is the EEX interpolation, not N5)
        if hertz_form == "exact":
            n_ee = reg("N_ee", lut_interpolate(alpha, EE_EXACT_SPEC) << EE_DIVIDEND_SHIFT)
        else:
            n_ee = F.N5
        e6 = reg("E6", F.C6 + divide("E_e", n_ee, alpha), F.E6)
        k2 = reg("K2", round_shift(_mul(k_int, k_int, "K K"),
                                   2 * F.K_INT.frac - F.K2.frac), F.K2)
        # PRODUCT
        t1 = reg("T1", round_shift(_mul(k2, e6, "K2 E6"),
                                   F.K2.frac + F.E6.frac - F.T1.frac), F.T1)
        t2 = reg("T2", round_shift(_mul(t1, radius, "T1 R"),
                                   F.T1.frac + F.RADIUS.frac - F.T2.frac), F.T2)
        t3 = reg("T3", _mul(t2, W, "T2 W"), F.T3)
        # DIV_CA
        c_a = reg("C_a", divide("C_a", t3 << (F.CA.frac - F.T3.frac), E), F.CA)
        # CBRT: range reduction C_a = m 8^p, m in [1, 8)
        p = reg("p", (c_a.bit_length() - 1 - F.CA.frac) // 3)
        sh = F.CA.frac + 3 * p - F.M_RED.frac
        m = reg("m", c_a >> sh if sh >= 0 else c_a << -sh, F.M_RED)
        assert (1 << F.M_RED.frac) <= m < (8 << F.M_RED.frac), "range reduction"
        cbrt = reg("cbrt", lut_interpolate(m, CBRT_SPEC), F.CBRT_VAL)
        a_w = reg("a_w", round_shift(cbrt, F.CBRT_VAL.frac - F.AXIS_W.frac - p), F.AXIS_W)
        # DIV_B, DIV_PN2, DIV_PMAX
        b_w = reg("b_w", divide("b", a_w << F.K_INT.frac, k_int), F.AXIS_W)
        pn2 = reg("p_n2", divide("p_n2", _mul(W, F.C3, "W C3") << F.PN2_SHIFT, a_w), F.PN2)
        p_max = reg("p_max", round_shift(divide("p_max", pn2 << F.PMAX_SHIFT, b_w), 1))
    except _DivZero:
        return _flagged(a_min, b_max, F.FLAG_DIV_ZERO)
    a_code = round_shift(a_w, F.AXIS_W.frac - SEMI_AXIS.frac)
    b_code = round_shift(b_w, F.AXIS_W.frac - SEMI_AXIS.frac)
    k_code = round_shift(k_int, F.K_INT.frac - F.K_OUT.frac)
    outs = ((a_code, SEMI_AXIS), (b_code, SEMI_AXIS), (p_max, PMAX), (k_code, F.K_OUT),
            (r_x, CURVATURE), (r_y, CURVATURE))
    if not all(fmt.fits(v) for v, fmt in outs):
        return _flagged(a_min, b_max, F.FLAG_OVERFLOW)
    return HertzCodes(a_code, b_code, p_max, k_code, a_min, b_max, r_x, r_y, alpha, 0)


class _DivZero(Exception):
    """Internal: the divider saw a zero divisor (turned into FLAG_DIV_ZERO)."""


# ---------------------------------------------------------------------------------
# encode / decode
# ---------------------------------------------------------------------------------
def encode_e_prime(e_prime_mpa: float) -> int:
    """E' (MPa) as the constant-register code, :data:`.formats.E_PRIME` (integer MPa).

    Raises
    ------
    InputRangeError
        Non-finite value (field ``e_prime_mpa``).
    FixedPointOverflow
        The value does not fit Q(32,0).
    """
    return F.E_PRIME.quantize(check_finite("e_prime_mpa", e_prime_mpa), field="e_prime_mpa")


def encode_hertz_inputs(A_per_mm, B_per_mm, load_n, *, e_prime_mpa):
    """Quantize real inputs to stage-D input codes (round half up).

    Parameters
    ----------
    A_per_mm, B_per_mm : float or array_like
        Half relative curvatures, 1/mm -> CURVATURE Q(32,20).
    load_n : float or array_like
        Load, N -> LOAD Q(32,8).
    e_prime_mpa : float
        Effective modulus, MPa -> E_PRIME Q(32,0).

    Returns
    -------
    tuple
        ``(A_code, B_code, W_code, e_prime_code)`` — ints for scalar input, ``int64``
        arrays otherwise.

    Raises
    ------
    InputRangeError
        A non-finite input (naming the field).
    FixedPointOverflow
        A value that does not fit its format (naming the field).
    """
    e_code = encode_e_prime(e_prime_mpa)
    vals = (("A_per_mm", A_per_mm, CURVATURE), ("B_per_mm", B_per_mm, CURVATURE),
            ("load_n", load_n, LOAD))
    if all(np.ndim(v) == 0 for _, v, _ in vals):
        return tuple(fmt.quantize(check_finite(n, v), field=n) for n, v, fmt in vals) \
            + (e_code,)
    return tuple(fmt.quantize_array(check_array_finite(n, v), field=n)
                 for n, v, fmt in vals) + (e_code,)


def decode_hertz_codes(codes) -> HertzGoldenValues:
    """Physical values of golden output codes (scalar :class:`HertzCodes` or the
    array result of :func:`.golden_vec.hertz_golden_array`)."""
    def f(code, frac):
        if isinstance(code, np.ndarray):
            return np.ldexp(code.astype(float), -frac)
        return math.ldexp(int(code), -frac)

    return HertzGoldenValues(
        a_mm=f(codes.a_code, SEMI_AXIS.frac), b_mm=f(codes.b_code, SEMI_AXIS.frac),
        k=f(codes.k_code, F.K_OUT.frac), p_max_mpa=f(codes.p_max_code, PMAX.frac),
        alpha=f(codes.alpha_code, F.ALPHA.frac), R_x_mm=f(codes.R_x_code, CURVATURE.frac),
        R_y_mm=f(codes.R_y_code, CURVATURE.frac),
        A_min_per_mm=f(codes.A_min_code, CURVATURE.frac),
        B_max_per_mm=f(codes.B_max_code, CURVATURE.frac), flags=codes.flags)

