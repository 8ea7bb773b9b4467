"""The line core of stage D (:mod:`gearcontact.preview.hertz.line`): near-line contact.

Truths: Hertz line contact of a cylinder of length L (Johnson 1985, sec. 4.3),
p0 = sqrt(W E* / (pi R L)), written out here from E* and R (not through the package);
the exact Hertz similarity (curvatures x 8^n -> semi-axes / 2^n, p_max x 4^n); the
restoring square root equals ``math.isqrt``; the golden model against the fp64 model of
the same mode rule at the decoded input codes (datapath) and at the real inputs (end to
end); the published cores' cycle counts are untouched.
"""

import math

import numpy as np
import pytest

from gearcontact.preview.hertz import formats as F
from gearcontact.preview.hertz import line as LN
from gearcontact.preview.hertz.golden import encode_hertz_inputs, hertz_golden
from gearcontact.preview.hertz.line import (LENGTH_MAX_CODE, LINE_CYCLES, LINE_STAGE_CYCLES,
                                            MODE_ELLIPTIC, MODE_LINE, decode_line_codes,
                                            encode_length, line_golden, scale_exponent)
from gearcontact.preview.hertz.reference import hertz_preview, truncated_preview
from gearcontact.preview.hertz.schedule import CHAIN_CYCLES, HERTZ_CYCLES
from gearcontact.preview.hertz.sqrt import floor_sqrt, restoring_sqrt
from gearcontact.validation import InputRangeError

from .conftest import E_PRIMES

EP = E_PRIMES["steel"]
LSB_P = 2.0 ** -8      # PMAX Q(32,8) output LSB, MPa
LSB_AX = 2.0 ** -20    # SEMI_AXIS Q(32,20) output LSB, mm


def _golden(A, B, W, L, ep=EP, **kw):
    a_c, b_c, w_c, e_c = encode_hertz_inputs(A, B, W, e_prime_mpa=ep)
    lc = line_golden(a_c, b_c, w_c, encode_length(L), e_prime_code=e_c, **kw)
    return lc, decode_line_codes(lc)


def _johnson_line(W, R, L, ep):
    """Johnson 1985 sec. 4.3: p0 = sqrt(P E*/(pi R)), b = sqrt(4 P R/(pi E*)), P = W/L."""
    e_star = ep / 2.0
    P = W / L
    return math.sqrt(P * e_star / (math.pi * R)), math.sqrt(4.0 * P * R / (math.pi * e_star))


def test_restoring_sqrt_is_floor_sqrt():
    rng = np.random.default_rng(3)
    corners = [0, 1, 2, 3, 4, (1 << 80) - 1, (1 << 40) ** 2 - 1, (1 << 40) ** 2 - 2]
    for n in corners + [int(x) << int(s) for x, s in zip(rng.integers(1, 1 << 62, 500),
                                                         rng.integers(0, 18, 500))]:
        assert restoring_sqrt(n) == floor_sqrt(n)
        root, rem = floor_sqrt(n)
        assert root * root <= n < (root + 1) ** 2 and rem == n - root * root


#: (W N, L mm) of the long ellipses truncated to the flank (also run through the RTL:
#: tests/preview/hertz/test_rtl_line.py).
JOHNSON_CASES = [(500.0, 10.0), (4825.0, 13.3), (20_000.0, 60.0)]


@pytest.mark.parametrize("W, L", JOHNSON_CASES)
def test_long_ellipse_truncated_to_l_is_johnson_line_contact(W, L):
    # B- = 1e-6 1/mm: a ratio of 2.5e4 (R_x = 500 m), an ellipse far longer than L;
    # the across curvature A- = 0.025 1/mm gives R = 1/(2 A-) = 20 mm
    A, B = 0.025, 1e-6
    R = 0.5 / A
    p0, b0 = _johnson_line(W, R, L, EP)
    for envelope in (True, False):
        tp = truncated_preview(A, B, W, L, e_prime_mpa=EP, envelope=envelope)
        assert tp.mode == "line"
        # same closed form in fp64: only rounding of a few operations
        assert tp.p_max_mpa == pytest.approx(p0, rel=1e-13)
        assert tp.b_mm == pytest.approx(b0, rel=1e-13)
        assert tp.a_mm == L / 2
        # equilibrium of the semi-elliptic strip: pi p0 b L / 2 = W
        assert math.pi * tp.p_max_mpa * tp.b_mm * L / 2 == pytest.approx(W, rel=1e-13)
    lc, v = _golden(A, B, W, L)
    assert lc.valid and lc.mode == MODE_LINE
    # end to end: A- and W quantized (2^-21/A- = 1.9e-5, 2^-9/W), p ~ sqrt(A- W), the
    # datapath within one output LSB (measured, docs/hertz.md sec. 6)
    assert abs(v["p_max_mpa"] - p0) <= 2e-5 * p0 + LSB_P
    assert abs(v["b_mm"] - b0) <= 2e-5 * b0 + LSB_AX
    assert abs(v["a_mm"] - L / 2) <= LSB_AX


def test_cylinder_a_min_zero_is_line_contact():
    # A_min = 0: a cylinder, no ellipse at all; R = 1/(2 * 0.05) = 10 mm
    p0, b0 = _johnson_line(1000.0, 10.0, 20.0, EP)
    tp = truncated_preview(0.0, 0.05, 1000.0, 20.0, e_prime_mpa=EP)
    assert tp.mode == "line" and tp.p_max_mpa == pytest.approx(p0, rel=1e-13)
    a_c, b_c, w_c, e_c = encode_hertz_inputs(0.0, 0.05, 1000.0, e_prime_mpa=EP)
    lc = line_golden(a_c, b_c, w_c, encode_length(20.0), e_prime_code=e_c)
    v = decode_line_codes(lc)
    assert lc.mode == MODE_LINE and lc.scale == 0
    # B = 0.05 quantized: 2^-21/0.05 = 1e-5 relative (p ~ B^(1/2), b ~ B^(-1/2))
    assert abs(v["p_max_mpa"] - p0) <= 1e-5 * p0 + LSB_P
    assert abs(v["b_mm"] - b0) <= 1e-5 * b0 + LSB_AX


def test_short_ellipse_stays_elliptic_and_equals_published_core():
    # an ellipse well inside the flank, curvatures inside the published range: the
    # line core's answer is the published core's, bit for bit
    A, B, W = 0.1, 0.02, 1000.0
    lc, _ = _golden(A, B, W, 50.0)
    a_c, b_c, w_c, e_c = encode_hertz_inputs(A, B, W, e_prime_mpa=EP)
    hz = hertz_golden(a_c, b_c, w_c, e_prime_code=e_c)
    assert lc.mode == MODE_ELLIPTIC and lc.scale == 0
    assert (lc.a_code, lc.b_code, lc.p_max_code, lc.k_code) == (hz.a_code, hz.b_code,
                                                                  hz.p_max_code, hz.k_code)


def test_hertz_similarity_behind_scale():
    # curvatures x 8 -> a, b / 2 and p_max x 4 at the same load (exact in fp64)
    base = hertz_preview(2e-4, 0.02, 1500.0, e_prime_mpa=EP, envelope=False)
    sc = hertz_preview(8 * 2e-4, 8 * 0.02, 1500.0, e_prime_mpa=EP, envelope=False)
    assert sc.a_mm * 2 == pytest.approx(base.a_mm, rel=1e-14)
    assert sc.b_mm * 2 == pytest.approx(base.b_mm, rel=1e-14)
    assert sc.p_max_mpa / 4 == pytest.approx(base.p_max_mpa, rel=1e-14)


@pytest.mark.parametrize("a_min, b_max, n", [(512, 1 << 16, 0), (511, 1 << 16, 1),
                                             (64, 1 << 12, 1), (63, 1 << 12, 2),
                                             (1, 100, 3), (0, 1 << 20, 0),
                                             (100, 1 << 21, 1), (100, 1 << 22, 0)])
def test_scale_exponent(a_min, b_max, n):
    # smallest n with A_min 8^n >= 2^9, capped where B_max 8^n would pass 2^24
    assert scale_exponent(a_min, b_max) == n


def test_scaled_elliptic_matches_fp64_hertz():
    # F3-like phase: B- = 2.3e-4 1/mm (R_x = 2.2 m, below the published 2^-11), ratio
    # 107, a = 3.4 mm well inside L = 20 mm: elliptic via SCALE n = 1
    A, B, W = 0.0246, 2.3e-4, 603.0
    lc, v = _golden(A, B, W, 20.0)
    ref = hertz_preview(A, B, W, e_prime_mpa=EP, envelope=False)
    assert lc.mode == MODE_ELLIPTIC and lc.scale == 1
    # end to end 2e-3: B- carries 2^-21/2.3e-4 = 2.1e-3 input quantization (a ~ B^-0.42
    # at this ratio), plus the datapath's 1.4e-4 (docs/hertz.md sec. 6)
    for key, val in (("a_mm", ref.a_mm), ("b_mm", ref.b_mm), ("p_max_mpa", ref.p_max_mpa)):
        assert v[key] == pytest.approx(val, rel=2e-3)


def _random_inputs(n, seed):
    rng = np.random.default_rng(seed)
    b = np.exp(rng.uniform(np.log(1e-3), 0.0, n))
    a = b / np.exp(rng.uniform(0.0, np.log(1e5), n))
    w = np.exp(rng.uniform(np.log(10.0), np.log(20_000.0), n))
    length = np.exp(rng.uniform(np.log(5.0), np.log(200.0), n))
    return a, b, w, length


@pytest.mark.parametrize("material", sorted(E_PRIMES))
def test_golden_against_reference_of_the_same_rule(material):
    # 300 seeded points per material: B_max in [1e-3, 1], ratio up to 1e5, W in
    # [10, 2e4] N, L in [5, 200] mm. Datapath (fp64 at the decoded input codes): the
    # same mode, and every output within one output LSB (the scaled ellipse's a, b:
    # 2^n LSB) plus 1.5e-4 relative (the published core's POW error, its own tests);
    # measured on 12 000 points: 1.3e-4 (docs/hertz.md sec. 6).
    ep = E_PRIMES[material]
    modes = set()
    for a, b, w, length in zip(*_random_inputs(300, seed=len(material))):
        a_c, b_c, w_c, e_c = encode_hertz_inputs(a, b, w, e_prime_mpa=ep)
        l_c = encode_length(length)
        lc = line_golden(a_c, b_c, w_c, l_c, e_prime_code=e_c)
        v = decode_line_codes(lc)
        dec = [math.ldexp(a_c, -20), math.ldexp(b_c, -20), math.ldexp(w_c, -8),
               math.ldexp(l_c, -20)]
        tp = truncated_preview(*dec, e_prime_mpa=e_c)
        assert lc.valid and tp.mode == lc.mode_name
        modes.add(tp.mode)
        lsb = LSB_AX * (2 ** lc.scale if lc.mode == MODE_ELLIPTIC else 1)
        assert abs(v["p_max_mpa"] - tp.p_max_mpa) <= 1.5e-4 * tp.p_max_mpa + LSB_P
        assert abs(v["a_mm"] - tp.a_mm) <= 1.5e-4 * tp.a_mm + lsb
        assert abs(v["b_mm"] - tp.b_mm) <= 1.5e-4 * tp.b_mm + lsb
    assert modes == {"elliptic", "line"}


def test_exact_form_line_core():
    # hertz_form="exact": the wrapped datapath holds exact k and E (its own tests); the
    # line core's elliptic answer is then exact Hertz within the same 1.5e-4 + LSB at
    # the decoded codes, and the line answer does not depend on the form
    for a, b, w, length in zip(*_random_inputs(40, seed=99)):
        a_c, b_c, w_c, e_c = encode_hertz_inputs(a, b, w, e_prime_mpa=EP)
        l_c = encode_length(length)
        lc = line_golden(a_c, b_c, w_c, l_c, e_prime_code=e_c, hertz_form="exact")
        v = decode_line_codes(lc)
        dec = [math.ldexp(a_c, -20), math.ldexp(b_c, -20), math.ldexp(w_c, -8),
               math.ldexp(l_c, -20)]
        tp = truncated_preview(*dec, e_prime_mpa=e_c, hertz_form="exact")
        assert tp.mode == lc.mode_name
        assert abs(v["p_max_mpa"] - tp.p_max_mpa) <= 1.5e-4 * tp.p_max_mpa + LSB_P
        if lc.mode == MODE_LINE:
            assert lc == line_golden(a_c, b_c, w_c, l_c, e_prime_code=e_c)


def test_pressure_continuous_where_the_mode_changes():
    # load sweep through the switch of an F3-like bearing (L = 13.3 mm): the larger of
    # the two lower bounds, so p_max(W) has no jump; a plain a > L/2 switch would drop
    # it by ~18 % here. Steps of 0.2 % in W change a W^(1/3) law by 0.07 %; allow 0.2 %.
    loads = np.geomspace(2000.0, 20_000.0, 1200)
    p = np.array([truncated_preview(0.0246, 2.3e-4, w, 13.3, e_prime_mpa=EP).p_max_mpa
                  for w in loads])
    modes = [truncated_preview(0.0246, 2.3e-4, w, 13.3, e_prime_mpa=EP).mode for w in loads]
    assert modes[0] == "elliptic" and modes[-1] == "line"
    assert np.all(np.diff(p) > 0) and np.max(np.diff(p) / p[:-1]) < 2e-3


def test_line_core_flags_its_envelope():
    a_c, b_c, w_c, e_c = encode_hertz_inputs(0.001, 0.05, 1000.0, e_prime_mpa=EP)
    ok = encode_length(20.0)
    cases = {
        "length_range": (a_c, b_c, w_c, LENGTH_MAX_CODE + 1),
        "not_elliptic": (-5, b_c, w_c, ok),                    # saddle: no contact line
        "curvature_range": (a_c, (16 << 20) + 1, w_c, ok),     # R across below 1/32 mm
        "load_range": (a_c, b_c, 0, ok),
    }
    for name, (a, b, w, length) in cases.items():
        lc = line_golden(a, b, w, length, e_prime_code=e_c)
        assert lc.flag_names == (name,) and lc.mode_name == "flagged"
        assert (lc.a_code, lc.b_code, lc.p_max_code, lc.k_code) == (0, 0, 0, 0)


def test_reference_envelope_and_inputs():
    with pytest.raises(InputRangeError, match="line_length_mm"):
        truncated_preview(0.001, 0.05, 1000.0, 2000.0, e_prime_mpa=EP)
    with pytest.raises(InputRangeError, match="B_max"):
        truncated_preview(0.0, 0.0, 1000.0, 20.0, e_prime_mpa=EP, envelope=False)
    with pytest.raises(InputRangeError, match="A_minus"):
        truncated_preview(-0.001, 0.05, 1000.0, 20.0, e_prime_mpa=EP)
    # envelope=False: any positive input, the physics alone (an ellipse of ratio 800
    # that fits L stays an ellipse; the datapath's rule gives the line contact there)
    phys = truncated_preview(3e-5, 0.0246, 4825.0, 50.3, e_prime_mpa=EP, envelope=False)
    core = truncated_preview(3e-5, 0.0246, 4825.0, 50.3, e_prime_mpa=EP)
    assert phys.mode == "elliptic" and core.mode == "line"


def test_cycle_counts():
    # the published cores unchanged; the line core wraps the 756-cycle core with its
    # own divider and square-root unit running meanwhile (211 cycles) + 3 cycles
    assert (HERTZ_CYCLES, CHAIN_CYCLES) == (756, 806)
    assert LINE_STAGE_CYCLES == 83 + 2 + 43 + 83 == 211
    assert LINE_CYCLES == HERTZ_CYCLES + 3 == 759


def test_flag_word_of_the_published_cores_unchanged():
    # the length flag lives in the line core's own name map (the published cores' flag
    # width and the chain's packing of stage-D flags stay as they were)
    assert max(F.FLAG_NAMES) == F.FLAG_DIV_ZERO == 1 << 6


EP_CODE = encode_hertz_inputs(1.0, 1.0, 1.0, e_prime_mpa=EP)[3]


def _ideal(monkeypatch, A, B, W, L):
    """The line core without its 1 mm floor (LENGTH_MIN_CODE lowered to the lift's
    least length): every line-stage register depends on W / L only (QPI = floor(16 W
    C_IPI / L)), so a lifted input's registers stay within their documented bounds."""
    monkeypatch.setattr(LN, "LENGTH_MIN_CODE", LN.LENGTH_MIN_CODE >> LN.LIFT_MAX_SHIFT)
    lc = line_golden(A, B, W, L, e_prime_code=EP_CODE)
    monkeypatch.undo()
    return lc


def test_lift_is_bit_exact_in_line_mode(monkeypatch):
    """A line below the core's 1 mm run on (2^s W, 2^s L) (host lift): QPI = floor(16 W
    C_IPI / L) is the same integer for (k W, k L), so every line register and output but
    a = rs(L, 1) is the same; unlifted a = rs(rs(2^s L, 1), s) = rs(L, 1). Truth: the
    core without its floor (:func:`_ideal`), bit for bit on 600 seeded inputs with
    gear-like curvatures (A_min 0 to 2^-6 1/mm along the line, B_max 2^-9 to 2^-3
    across), every lifted line-mode answer (mode, scale, every code). The lift's
    elliptic answer is never returned (flagged length_range): the ellipse of 2^s W is
    only 2^(s/3) longer while the line is 2^s longer, so the lifted SELECT may keep
    an ellipse the unlifted one truncates; the converse cannot happen (a lifted line
    mode means 2 a_e(2^s W) > 2^s L, so 2 a_e(W) > 2^(2s/3) L > L, and p_e(W) < p_l
    with a margin of 2^(s/3)), which the bit-equality of the mode checks."""
    rng = np.random.default_rng(26)
    seen = {"line": 0, "flagged": 0}
    for _ in range(600):
        A = int(rng.integers(0, 1 << 14))
        B = int(rng.integers(1 << 11, 1 << 17))
        W = int(rng.integers(1 << 8, 1 << 20))           # 1 N to 4 kN
        L = int(rng.integers(LN.LENGTH_MIN_CODE >> LN.LIFT_MAX_SHIFT, LN.LENGTH_MIN_CODE))
        s = LN.length_lift(W, L)
        if s == 0:                                       # 2^s W beyond the load range
            assert W << (LN.LIFT_MAX_SHIFT) > F.LOAD_MAX_CODE
            continue
        assert (L << s) >= LN.LENGTH_MIN_CODE > (L << (s - 1))
        got = LN.unlift_line_codes(line_golden(A, B, W << s, L << s, e_prime_code=EP_CODE), s)
        ideal = _ideal(monkeypatch, A, B, W, L)
        if got.valid:
            assert got == ideal
            seen["line"] += 1
        else:
            assert got.flag_names == ("length_range",)
            assert (got.a_code, got.b_code, got.p_max_code, got.k_code) == (0, 0, 0, 0)
            seen["flagged"] += 1
    assert seen["line"] > 300 and seen["flagged"] > 0


def test_lift_range():
    # below 2^-8 mm, at or above 1 mm, or a lifted load beyond 2^17 N: no lift
    one = LN.LENGTH_MIN_CODE
    assert LN.length_lift(1000 << 8, one) == 0
    assert LN.length_lift(1000 << 8, one - 1) == 1
    assert LN.length_lift(1000 << 8, one >> 3) == 3
    assert LN.length_lift(1000 << 8, (one >> 8) - 1) == 0
    assert LN.length_lift(F.LOAD_MAX_CODE >> 2, one >> 2) == 2
    assert LN.length_lift((F.LOAD_MAX_CODE >> 2) + 1, one >> 2) == 0
    assert LN.length_lift(0, one >> 2) == 0
    # a = rs(L, 1) of the unlifted L, round half up
    assert LN.unlift_line(5 << 2, 7, 9, 0, MODE_LINE, 0, 3)[0] == 3


@pytest.mark.parametrize("A, L", [(2.0 ** -21, 0.4), (1e-5, 0.4), (2.0 ** -21, 0.03),
                                  (1e-4, 0.7)])
def test_short_line_is_johnson_line_contact(A, L):
    """A line below 1 mm (an end-loaded line's L_eq): fp64 and golden (the engines, the
    host's lift) against Johnson 1985 eq. 4.45, p0 = sqrt(W E*/(pi R L)), R = 1/(2
    B-) = 10 mm, W = 300 N. fp64 to 1e-13 (rounding); golden within the quantization of
    B- (2^-21 / 0.05 = 1e-5 relative, p ~ B^(1/2)), L (2^-21 / L relative, p ~
    L^(-1/2)) and W (2^-9 / 300) plus one output LSB, as for L >= 1 mm (above)."""
    from gearcontact.preview.engine import get_engine

    W, B = 300.0, 0.05
    p0, b0 = _johnson_line(W, 0.5 / B, L, EP)
    ref = get_engine("reference").hertz(A, B, W, line_length_mm=L)
    assert ref.mode == "line"
    assert ref.p_max_mpa == pytest.approx(p0, rel=1e-13)
    assert ref.b_mm == pytest.approx(b0, rel=1e-13)
    gold = get_engine("golden").hertz(A, B, W, line_length_mm=L)
    assert gold.mode == "line" and gold.valid
    assert gold.codes["lift"] > 0 and gold.codes["L"] >= LN.LENGTH_MIN_CODE
    q = 1e-5 + 2.0 ** -21 / L + 2.0 ** -9 / W
    assert abs(gold.p_max_mpa - p0) <= q * p0 + LSB_P
    assert abs(gold.b_mm - b0) <= q * b0 + LSB_AX
    assert abs(gold.a_mm - L / 2) <= LSB_AX


def test_short_line_whose_ellipse_fits_is_refused_and_flagged():
    # a ball-like contact (A = B = 0.05 1/mm, R = 10 mm) at 10 N: a = 0.11 mm fits a
    # 0.5 mm line; the lifted run keeps the ellipse, which is 2^s W's: refused / flagged
    from gearcontact.preview.engine import get_engine

    with pytest.raises(InputRangeError, match="line_length_mm"):
        get_engine("reference").hertz(0.05, 0.05, 10.0, line_length_mm=0.5)
    gold = get_engine("golden").hertz(0.05, 0.05, 10.0, line_length_mm=0.5)
    assert gold.mode == "flagged" and gold.flags == ("length_range",)


def test_batch_lifts_as_the_single_run():
    # hertz_batch runs the same lift elementwise: the 0.4 mm line in line mode with the
    # single run's numbers, the fitting ellipse on 0.5 mm flagged, a 20 mm line unlifted
    from gearcontact.preview.engine import get_engine

    gold = get_engine("golden")
    A, B, W, L = [1e-5, 0.05, 1e-5], [0.05, 0.05, 0.05], [300.0, 10.0, 300.0], [0.4, 0.5, 20.0]
    batch = gold.hertz_batch(A, B, W, line_length_mm=L)
    assert list(batch.mode) == ["line", "flagged", "line"]
    for i in (0, 2):
        one = gold.hertz(A[i], B[i], W[i], line_length_mm=L[i])
        assert (batch.p_max_mpa[i], batch.b_mm[i], batch.a_mm[i]) == (one.p_max_mpa,
                                                                     one.b_mm, one.a_mm)
    assert batch.flags[1] == LN.FLAG_LENGTH_RANGE
