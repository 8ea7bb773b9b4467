"""The preview engine in line mode (``line_length_mm=L``): reference, golden and rtl.

Truths: the Hertz line contact of a cylinder of length L,
:func:`gearcontact.analytic.hertz.line_contact_hertz` (Johnson 1985 sec. 4.3; itself
tested as the long-ellipse limit of exact elliptic Hertz), for a long ellipse truncated
to L; the fp64 mode rule at the golden model's decoded input codes (the datapath's
accuracy, docs/hertz.md sec. 6); the scalar golden engine (batch == scalar, bit for bit:
equal floats decoded from equal codes); the Amaranth RTL == golden bit for bit.
"""

import math

import numpy as np
import pytest

from gearcontact.analytic.hertz import line_contact_hertz
from gearcontact.preview.engine import GoldenEngine, ReferenceEngine
from gearcontact.validation import InputRangeError

LSB_P = 2.0 ** -8      # PMAX Q(32,8), MPa
LSB_AX = 2.0 ** -20    # SEMI_AXIS Q(32,20), mm

#: Long ellipses (B- along the line 1e-6 1/mm: R_x = 500 m) cut by flanks of length L;
#: (A- across, B- along, W, L): R = 1/(2 A-) across the line.
LONG = [(0.025, 1e-6, 500.0, 10.0), (0.0246, 2e-6, 4825.0, 13.3),
        (0.2, 1e-5, 20_000.0, 60.0), (0.004, 3e-7, 800.0, 150.0)]


def _cols(cases):
    return [np.array(c) for c in zip(*cases)]


def _quantization_bound(A, W, L, e_prime, p):
    """|p(codes) - p(real)| of p0 ~ sqrt(A W E' / L) from the half-LSB input rounding
    (A, L: 2^-21 mm, W: 2^-9 N, E': 0.5 MPa), first order."""
    return 0.5 * p * (2.0 ** -21 / A + 2.0 ** -9 / W + 2.0 ** -21 / L + 0.5 / e_prime)


def test_long_ellipse_truncated_to_l_is_the_line_contact_of_length_l():
    A, B, W, L = _cols(LONG)
    ref = ReferenceEngine().hertz_batch(A, B, W, line_length_mm=L)
    gold_engine = GoldenEngine()
    gold = gold_engine.hertz_batch(A, B, W, line_length_mm=L)
    ep = gold_engine.e_prime_mpa
    assert list(ref.mode) == list(gold.mode) == ["line"] * len(LONG)
    assert not gold.flags.any()
    for i, (a, _, w, length) in enumerate(LONG):
        truth = line_contact_hertz(0.5 / a, w, length, e_prime_mpa=ep)
        # fp64: the same closed form, a few roundings
        assert ref.p_max_mpa[i] == pytest.approx(truth.p_max_mpa, rel=1e-13)
        assert ref.b_mm[i] == pytest.approx(truth.b_mm, rel=1e-13)
        assert ref.a_mm[i] == length / 2
        # golden: the input rounding (first order) plus the datapath's rounding, measured
        # within 0.54 LSB of p and 0.70 LSB of b at the decoded codes (20,000 points)
        p = truth.p_max_mpa
        assert abs(gold.p_max_mpa[i] - p) <= _quantization_bound(a, w, length, ep, p) + LSB_P
        assert abs(gold.b_mm[i] - truth.b_mm) <= \
            _quantization_bound(a, w, length, ep, truth.b_mm) + LSB_AX
        assert abs(gold.a_mm[i] - length / 2) <= LSB_AX
        assert gold.k[i] == pytest.approx(gold.a_mm[i] / gold.b_mm[i], rel=1e-15)


def _random(n, seed):
    """A- (across) in [2^-10, 1] 1/mm, ratio 1 .. 1e4 (both modes, every SCALE n), W in
    [10, 2e4] N, L in [2, 200] mm; curvatures in both orders."""
    rng = np.random.default_rng(seed)
    a = np.exp(rng.uniform(np.log(2.0 ** -10), 0.0, n))
    b = a / np.exp(rng.uniform(0.0, np.log(1e4), n))
    w = np.exp(rng.uniform(np.log(10.0), np.log(20_000.0), n))
    length = np.exp(rng.uniform(np.log(2.0), np.log(200.0), n))
    swap = rng.random(n) < 0.5
    return np.where(swap, b, a), np.where(swap, a, b), w, length


def test_golden_batch_equals_scalar_engine():
    A, B, W, L = _random(300, seed=41)
    L[:10] = 2000.0                                     # flagged: length_range
    gold = GoldenEngine()
    batch = gold.hertz_batch(A, B, W, line_length_mm=L)
    for i in range(A.size):
        r = gold.hertz(A[i], B[i], W[i], line_length_mm=L[i])
        assert (batch.a_mm[i], batch.b_mm[i], batch.k[i], batch.p_max_mpa[i]) == \
            (r.a_mm, r.b_mm, r.k, r.p_max_mpa), i
        assert batch.mode[i] == r.mode and int(batch.flags[i]) == r.codes["flags"]
    assert set(batch.mode) == {"elliptic", "line", "flagged"}


def test_golden_equals_reference_rule_within_the_datapath_accuracy():
    # the fp64 rule at the decoded input codes: same mode everywhere; line mode within
    # one output LSB (measured 0.54 LSB of p, 0.70 of b); elliptic mode within the
    # published core's 1.5e-4 plus one LSB (its POW table; measured 1.54e-4 in all)
    A, B, W, L = _random(2000, seed=42)
    gold = GoldenEngine()
    c = gold.encode_line_batch(A, B, W, L)
    keep = (c["A_in"] > 0) & (c["B_in"] > 0)     # the engine takes positive curvatures

    def dec(k, frac):
        return np.ldexp(c[k][keep].astype(float), -frac)
    g = gold.hertz_batch(A[keep], B[keep], W[keep], line_length_mm=L[keep])
    ref = ReferenceEngine(material=gold.material)
    ref.e_prime_mpa = float(c["e_prime"][0])       # E' as the constant register holds it
    r = ref.hertz_batch(dec("A_in", 20), dec("B_in", 20), dec("W", 8),
                        line_length_mm=dec("L", 20))
    assert np.array_equal(g.mode, r.mode)
    line = g.mode == "line"
    assert 300 < line.sum() < keep.sum() - 300
    assert np.all(np.abs(g.p_max_mpa - r.p_max_mpa)[line] <= LSB_P)
    assert np.all(np.abs(g.b_mm - r.b_mm)[line] <= LSB_AX)
    ell = ~line
    assert np.all(np.abs(g.p_max_mpa - r.p_max_mpa)[ell] <= 1.5e-4 * r.p_max_mpa[ell] + LSB_P)


def test_published_batch_says_elliptic_or_flagged():
    g = GoldenEngine().hertz_batch([0.1, 0.1], [0.02, 0.0005], [1000.0, 1000.0])
    assert list(g.mode) == ["elliptic", "flagged"]          # alpha 200 > 128: flagged
    r = ReferenceEngine().hertz_batch([0.1], [0.02], [1000.0])
    assert list(r.mode) == ["elliptic"]


def test_batch_inputs_are_checked_naming_the_element():
    gold, ref = GoldenEngine(), ReferenceEngine()
    for bad in (0.0, -1.0, math.nan):
        for engine in (gold, ref):
            with pytest.raises(InputRangeError, match=r"line_length_mm\[1\]"):
                engine.hertz_batch([0.1, 0.1], [0.02, 0.02], 100.0,
                                   line_length_mm=[10.0, bad])
    # beyond the line core's [1, 1024] mm: the golden model flags it (a datapath
    # result), the reference mirrors the domain by raising, the host-side fp64 has none
    assert gold.hertz_batch(0.1, 0.02, 100.0, line_length_mm=2000.0).flags[0] == 1 << 7
    with pytest.raises(InputRangeError, match="line_length_mm"):
        ref.hertz_batch(0.1, 0.02, 100.0, line_length_mm=2000.0)
    host = ReferenceEngine(envelope=False).hertz_batch(0.1, 0.02, 100.0,
                                                       line_length_mm=2000.0)
    assert host.mode[0] == "elliptic"


def test_rtl_batch_and_stencil_equal_golden_bit_for_bit():
    """Amaranth simulator: the line core on three vectors (elliptic at SCALE n = 1, line,
    flagged) and the line chain on one stencil (a 0.4 mm line, lifted); about 10 s."""
    from gearcontact.hw.rtl_engine import RtlEngine
    from gearcontact.preview.stimulus import _elliptic
    rtl, gold = RtlEngine(simulator="amaranth"), GoldenEngine()
    args = ([0.0246, 0.025, 0.1], [2.3e-4, 1e-6, 0.02], [603.0, 500.0, 100.0])
    kw = {"line_length_mm": [20.0, 10.0, 2000.0]}
    got, want = rtl.hertz_batch(*args, **kw), gold.hertz_batch(*args, **kw)
    for f in ("a_mm", "b_mm", "k", "p_max_mpa", "flags", "mode"):
        assert np.array_equal(getattr(got, f), getattr(want, f)), f
    assert list(got.mode) == ["elliptic", "line", "flagged"]
    # the chain on a line below the core's 1 mm (an end-loaded line's L_eq): both run
    # the host's lift, 2^2 x (300 N, 0.4 mm), and answer the same codes
    gaps = _elliptic(0.0246, 0.0, 0.3, 0.0, 0.01, -0.02)      # a cylinder: B- = 0
    got = rtl.stencil(gaps, 300.0, line_length_mm=0.4)
    want = gold.stencil(gaps, 300.0, line_length_mm=0.4)
    assert got.codes == want.codes and got.cycles == want.cycles == 811
    assert got.codes["lift"] == 2 and got.a_mm == pytest.approx(0.2, abs=2.0 ** -20)
    assert got.mode == want.mode == "line" and got.p_max_mpa == want.p_max_mpa
