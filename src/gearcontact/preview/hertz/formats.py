"""Fixed-point formats, constants, operating envelope and flags of stage D.

All registers are unsigned except the contract inputs/outputs (docs/spec.md sec. 6).
``round_shift`` is round-half-up by shifting; ``floor`` is the divider's exact floor.

===========  ============  ======================================================  ==========
register     format        definition (codes; value = code 2^-frac)                max code
===========  ============  ======================================================  ==========
A, B         Q(32,20)      CURVATURE inputs, 1/mm (half relative curvatures)        2^24
W            Q(32,8)       LOAD input, N                                            2^25
E'           Q(32,0)       effective modulus E' = 2E*, integer MPa (constant        2^21
                           register; steel/steel 229 670)
A_min,B_max  Q(32,20)      sorted curvatures                                        2^24
R_x, R_y     Q(32,20)      round_shift(floor(2^40 / A_min), 1), mm (outputs)        2^30
alpha        UQ(32,24)     floor(B_max 2^24 / A_min) = R_x/R_y                      2^31
R            UQ(33,23)     floor(2^42 / (A_min + B_max)), mm                        2^32
E6           UQ(27,25)     C6 + floor(N5 / alpha) = 6 E_e/pi, E_e = 1+(pi/2-1)/a    < 2^26.6
k  (K)       UQ(29,24)     round_shift(POW interpolation, 16)                       < 2^28.5
k^2 (K2)     UQ(37,28)     round_shift(K K, 20)                                     < 2^36.9
T1           UQ(31,21)     round_shift(K2 E6, 32)            = k^2 E6               < 2^30.9
T2           UQ(39,26)     round_shift(T1 R, 18)             = k^2 E6 R, mm         < 2^38.9
T3           UQ(64,34)     T2 W (exact)                      = k^2 E6 R W, N mm     < 2^63.9
C_a          UQ(64,45)     floor((T3 << 11) / E')            = a^3, mm^3            < 2^62.9
m            UQ(32,29)     C_a 2^-3p in [1, 8); p = floor((msb(C_a) - 45)/3)        < 2^32
c            UQ(47,46)     CBRT interpolation = m^(1/3) in [1, 2)                   < 2^47
a_w          UQ(42,36)     round_shift(c, 10 - p) = a, mm                           < 2^42
b_w          UQ(42,36)     floor((a_w << 24) / K) = a/k, mm                         < 2^42
p_n2         UQ(47,28)     floor((W C3 << 16) / a_w) = 3W/(2 pi a), N/mm            < 2^46.8
p_max        Q(32,8)       round_shift(floor((p_n2 << 17) / b_w), 1), MPa           < 2^31
a, b         Q(32,20)      round_shift(a_w, 16), round_shift(b_w, 16), mm
                           (SEMI_AXIS)
k            Q(32,20)      round_shift(K, 4) (output)
===========  ============  ======================================================  ==========

Constants: ``C6 = round(6/pi 2^25)``, ``N5 = round((3 - 6/pi) 2^49)``,
``C3 = round(3/(2 pi) 2^40)``. Every multiplier product is below 2^64 (docs/spec.md sec. 6
allows 2^66) and every dividend below 2^80 (largest: p_n2, W C3 2^16 < 2^80); the
golden model asserts both on every run. With ``hertz_form="exact"`` the E_e dividend
N5 becomes the EEX table's N(alpha) in the same units (< 2^51; N in [1.09, 1.14] and
E6 = 6E/pi <= 3, so every bound above holds unchanged).

Operating envelope (checked in state SORT; outside it the run is flagged and every
numeric output except the sorted curvature registers reads 0):
curvatures in [2^-11, 2^4] 1/mm (codes [2^9, 2^24]), load in [1, 2^17] N
(codes [2^8, 2^25]), E' in [2^12, 2^21] MPa, and, after DIV_ALPHA, alpha <= 128
(the POW LUT range, alpha code <= 2^31). Inside it no register can overflow (the
bounds above are the envelope corners, asserted in the model and tested at the
corners); ``FLAG_OVERFLOW`` / ``FLAG_DIV_ZERO`` guard the output registers and the
divider against a wrap should that ever be violated.
"""

from __future__ import annotations

import math

from ...contract.envelope import (CURV_MAX_CODE, CURV_MIN_CODE, E_PRIME_MAX_CODE,
                                  E_PRIME_MIN_CODE, LOAD_MAX_CODE, LOAD_MIN_CODE)
from ...validation import InputRangeError
from ...contract.qformat import CURVATURE, LOAD, PMAX, sq, uq

__all__ = [
    "E_PRIME", "K_OUT", "ALPHA", "RADIUS", "E6", "K_INT", "K2", "T1", "T2", "T3", "CA",
    "M_RED", "CBRT_VAL", "AXIS_W", "PN2", "C6", "N5", "C3", "CURV_MIN_CODE",
    "CURV_MAX_CODE", "LOAD_MIN_CODE", "LOAD_MAX_CODE", "E_PRIME_MIN_CODE",
    "E_PRIME_MAX_CODE", "ALPHA_MAX_CODE", "FLAG_NOT_ELLIPTIC", "FLAG_CURV_RANGE",
    "FLAG_LOAD_RANGE", "FLAG_E_PRIME_RANGE", "FLAG_ALPHA_RANGE", "FLAG_OVERFLOW",
    "FLAG_DIV_ZERO", "FLAG_INPUT", "FLAG_NAMES", "flag_names", "C3_FRAC", "PN2_SHIFT", "PMAX_SHIFT",
    "HERTZ_FORMS", "DEFAULT_HERTZ_FORM", "check_hertz_form"]

# ---- register formats (see the table above) ----------------------------------------
E_PRIME = sq(32, 0)        #: E' = 2E*, integer MPa (constant register)
K_OUT = sq(32, 20)         #: ellipticity k = a/b output, dimensionless
ALPHA = uq(32, 24)         #: alpha = R_x/R_y, dimensionless
RADIUS = uq(33, 23)        #: R (curvature-sum radius), mm
E6 = uq(27, 25)            #: 6 E_e / pi, dimensionless
K_INT = uq(29, 24)         #: k internal, dimensionless
K2 = uq(37, 28)            #: k^2, dimensionless
T1 = uq(31, 21)            #: k^2 E6, dimensionless
T2 = uq(39, 26)            #: k^2 E6 R, mm
T3 = uq(64, 34)            #: k^2 E6 R W, N mm
CA = uq(64, 45)            #: C_a = a^3, mm^3
M_RED = uq(32, 29)         #: reduced mantissa m in [1, 8), dimensionless
CBRT_VAL = uq(47, 46)      #: m^(1/3) in [1, 2), dimensionless
AXIS_W = uq(42, 36)        #: internal semi-axes a_w, b_w, mm
PN2 = uq(47, 28)           #: p_n2 = 3W/(2 pi a), N/mm

# ---- constants ----------------------------------------------------------------------
C6 = math.floor(6.0 / math.pi * 2.0 ** E6.frac + 0.5)                      #: 6/pi
N5 = math.floor((3.0 - 6.0 / math.pi) * 2.0 ** (E6.frac + ALPHA.frac) + 0.5)  #: 3-6/pi
C3_FRAC = 40                                                               #: C3 LSB 2^-40
C3 = math.floor(3.0 / (2.0 * math.pi) * 2.0 ** C3_FRAC + 0.5)              #: 3/(2 pi)
#: dividend shifts of DIV_PN2 (16) and DIV_PMAX (17, one extra bit for the final rounding)
PN2_SHIFT = PN2.frac + AXIS_W.frac - LOAD.frac - C3_FRAC
PMAX_SHIFT = PMAX.frac + 1 + AXIS_W.frac - PN2.frac

# ---- operating envelope (codes, inclusive): the inputs' ranges are the data contract's
# (gearcontact.contract.envelope, imported above); the internal alpha bound is stage D's
ALPHA_MAX_CODE = 128 << ALPHA.frac             #: alpha <= 128 (POW LUT segment <= 254)

# ---- flags --------------------------------------------------------------------------
FLAG_NOT_ELLIPTIC = 1 << 0    #: A_min <= 0: no elliptic point contact
FLAG_CURV_RANGE = 1 << 1      #: a positive curvature outside [2^-11, 16] 1/mm
FLAG_LOAD_RANGE = 1 << 2      #: W outside [1, 2^17] N (incl. W <= 0)
FLAG_E_PRIME_RANGE = 1 << 3   #: E' outside [2^12, 2^21] MPa
FLAG_ALPHA_RANGE = 1 << 4     #: alpha = B_max/A_min > 128 (beyond the POW LUT)
FLAG_OVERFLOW = 1 << 5        #: an output does not fit its contract format
FLAG_DIV_ZERO = 1 << 6        #: the divider saw a zero divisor
FLAG_INPUT = FLAG_NOT_ELLIPTIC | FLAG_CURV_RANGE | FLAG_LOAD_RANGE | FLAG_E_PRIME_RANGE

FLAG_NAMES = {FLAG_NOT_ELLIPTIC: "not_elliptic", FLAG_CURV_RANGE: "curvature_range",
              FLAG_LOAD_RANGE: "load_range", FLAG_E_PRIME_RANGE: "e_prime_range",
              FLAG_ALPHA_RANGE: "alpha_range", FLAG_OVERFLOW: "overflow",
              FLAG_DIV_ZERO: "divide_by_zero"}


def flag_names(flags: int) -> tuple[str, ...]:
    """Names of the bits set in a flags word (empty tuple when valid)."""
    return tuple(name for bit, name in FLAG_NAMES.items() if flags & bit)


# ---- Hertz forms ----------------------------------------------------------------------
#: ``"hamrock-brewe"``: the published simplified forms k = alpha^(2/pi),
#: E_e = 1 + (pi/2 - 1)/alpha (the default); ``"exact"``: the POW table holds the exact
#: k(alpha) and a second table of the same geometry the exact elliptic-integral term
#: (:mod:`.luts`), with the same datapath, formats and cycle count.
HERTZ_FORMS = ("hamrock-brewe", "exact")
DEFAULT_HERTZ_FORM = "hamrock-brewe"


def check_hertz_form(hertz_form) -> str:
    """``hertz_form`` if it is one of :data:`HERTZ_FORMS`, else InputRangeError."""
    if hertz_form not in HERTZ_FORMS:
        raise InputRangeError("hertz_form", hertz_form, f"one of {HERTZ_FORMS}")
    return hertz_form
