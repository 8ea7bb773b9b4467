"""The line chain (C -> line core): :func:`gearcontact.preview.chain.chain_line_golden`,
its batch and fp64 twins and :class:`gearcontact.preview.chain_line_rtl.ChainLineCore`.

Truths: the Hertz line contact of a cylinder of length L
(:func:`gearcontact.analytic.hertz.line_contact_hertz`, Johnson 1985 sec. 4.3) for the
stencil of an exact cylinder (B- = 0) and of a long ellipse truncated to L; the
published chain's codes where the ellipse fits its flank (the line core wraps the
published datapath unchanged); the scalar golden model (batch == scalar); the RTL in
the Amaranth simulator == golden bit for bit with 811 cycles.
"""

import numpy as np
import pytest

from gearcontact.analytic.hertz import line_contact_hertz
from gearcontact.preview.chain import (CHAIN_CYCLES, CHAIN_LINE_CYCLES, LINE_B_ZERO_CODES,
                                       chain_flag_names, chain_golden, chain_line_golden,
                                       chain_line_golden_batch, chain_line_reference)
from gearcontact.preview.fit.golden import encode_gaps
from gearcontact.preview.fit.pinv import coefficient_error_bound
from gearcontact.preview.hertz.line import MODE_LINE, encode_length
from gearcontact.preview.stimulus import STEEL_E_PRIME_CODE as EP
from gearcontact.preview.stimulus import _elliptic, chain_stimulus

LSB_P = 2.0 ** -8     # PMAX Q(32,8), MPa
W1K = 1000 << 8


def _codes(gaps_mm):
    return [int(x) for x in encode_gaps(gaps_mm)]


def test_cycle_counts():
    # the published chain unchanged; the line chain: fit (52) then the line core (759)
    assert (CHAIN_CYCLES, CHAIN_LINE_CYCLES) == (806, 52 + 759)


@pytest.mark.parametrize("theta", [0.0, 0.3, 1.1])
def test_cylinder_stencil_is_the_line_contact_of_length_l(theta):
    # gap A s'^2 of a cylinder (axis at theta): no ellipse at all, the line contact of
    # length L with R = 1/(2 A) across it
    A, W, L = 0.0246, 2000.0, 10.0
    gaps = _elliptic(A, 0.0, theta, 0.001, 0.01, -0.02)
    truth = line_contact_hertz(0.5 / A, W, L, e_prime_mpa=float(EP))
    ref = chain_line_reference(gaps, W, L, e_prime_mpa=float(EP))
    # fp64: the fit is exact on a quadratic up to rounding (B- ~ 1e-16 either sign,
    # taken as 0 within the fit's resolution)
    assert ref.hertz.mode == "line"
    assert ref.fit.A_minus_per_mm == pytest.approx(A, rel=1e-12)
    assert ref.hertz.p_max_mpa == pytest.approx(truth.p_max_mpa, rel=1e-12)
    gold = chain_line_golden(_codes(gaps), int(W * 256), encode_length(L), e_prime_code=EP)
    assert gold.flags == 0 and gold.hertz.mode == MODE_LINE
    # golden: |dA-| of the fit (its rigorous coefficient bound, |dh| + |dr| <= |dc3| +
    # |dc5| + |dc4|/2) enters p0 ~ sqrt(A-) at half weight, plus one output LSB
    c = coefficient_error_bound(gaps)
    d_a = c[3] + c[5] + c[4] / 2
    p = gold.hertz.p_max_code * LSB_P
    assert abs(p - truth.p_max_mpa) <= 0.5 * d_a / A * truth.p_max_mpa + LSB_P
    # the fitted B- is noise around 0 (within its resolution): a line contact, no saddle
    assert abs(gold.fit.b_minus_code) <= LINE_B_ZERO_CODES and gold.hertz.A_min_code >= 0


def test_long_ellipse_stencil_truncated_to_l():
    # B- = 2e-6 1/mm along (R_x = 250 m): the ellipse is far longer than L = 13.3 mm
    A, B, W, L = 0.0246, 2e-6, 4825.0, 13.3
    gaps = _elliptic(A, B, 0.4, 0.0, 0.0, 0.0)
    truth = line_contact_hertz(0.5 / A, W, L, e_prime_mpa=float(EP))
    ref = chain_line_reference(gaps, W, L, e_prime_mpa=float(EP))
    assert ref.hertz.mode == "line"
    assert ref.hertz.p_max_mpa == pytest.approx(truth.p_max_mpa, rel=1e-9)
    gold = chain_line_golden(_codes(gaps), int(W * 256), encode_length(L), e_prime_code=EP)
    assert gold.hertz.mode == MODE_LINE
    c = coefficient_error_bound(gaps)
    p = gold.hertz.p_max_code * LSB_P
    assert abs(p - truth.p_max_mpa) <= \
        0.5 * (c[3] + c[5] + c[4] / 2) / A * truth.p_max_mpa + LSB_P


def test_ellipse_inside_the_flank_is_the_published_chain_bit_for_bit():
    gaps = _elliptic(0.05, 0.01, 0.4, 0.0, 0.05, -0.02)
    pub = chain_golden(_codes(gaps), W1K, e_prime_code=EP)
    line = chain_line_golden(_codes(gaps), W1K, encode_length(50.0), e_prime_code=EP)
    assert line.hertz.mode_name == "elliptic" and line.hertz.scale == 0
    assert (line.hertz.a_code, line.hertz.b_code, line.hertz.p_max_code, line.hertz.k_code) \
        == (pub.hertz.a_code, pub.hertz.b_code, pub.hertz.p_max_code, pub.hertz.k_code)
    assert (pub.cycles, line.cycles) == (806, 811)


def test_batch_equals_scalar():
    st = chain_stimulus(150, seed=8)
    rng = np.random.default_rng(8)
    gaps, w = st.fields["gaps"], st.fields["W"]
    e = st.fields["e_prime"]
    length = np.array([encode_length(x) for x in np.exp(rng.uniform(0.0, 7.0, len(st)))])
    batch = chain_line_golden_batch(gaps, w, length, e_prime_code=e)
    for i in range(len(st)):
        one = chain_line_golden([int(x) for x in gaps[i]], int(w[i]), int(length[i]),
                                e_prime_code=int(e[i]))
        assert int(batch.flags[i]) == one.flags
        assert int(batch.fit.b_minus_codes[i]) == one.fit.b_minus_code
        for f in ("a_code", "b_code", "p_max_code", "k_code", "A_min_code", "B_max_code",
                  "mode", "scale", "flags"):
            assert int(getattr(batch.hertz, f)[i]) == getattr(one.hertz, f), (i, f)
    names = batch.hertz.mode_names
    assert {"elliptic", "line", "flagged"} <= set(names.tolist())


def test_flag_names_of_the_line_chain():
    # bit 7 is the line core's length flag; the fit's overflow bits from bit 8
    assert chain_flag_names((1 << 7) | (1 << 8), line=True) == ("fit_coefficient_overflow",
                                                                  "length_range")
    gaps = _elliptic(0.05, 0.01, 0.4, 0.0, 0.05, -0.02)
    res = chain_line_golden(_codes(gaps), W1K, encode_length(2000.0), e_prime_code=EP)
    assert res.flag_names == ("length_range",)


def test_rtl_equals_golden_bit_for_bit_811_cycles():
    """Amaranth simulator, five stencils: elliptic (n = 0 and n = 1), a cylinder (line),
    a saddle (flagged not_elliptic), a fit overflow (flagged; about 8 s)."""
    from gearcontact.preview.chain_line_rtl import simulate_chain_line_core
    from gearcontact.contract.qformat import STENCIL_GAP
    stencils = [_elliptic(0.05, 0.01, 0.4, 0.0, 0.05, -0.02),
                _elliptic(0.0246, 2.3e-4, 0.3, 0.0, 0.01, -0.02),
                _elliptic(0.0246, 0.0, 0.3, 0.0, 0.01, -0.02),
                _elliptic(0.02, -0.001, 0.0, 0.0, 0.0, 0.0),
                _elliptic(0.0, 0.0, 0.0, 0.0, 0.0, 0.0) + np.where(
                    np.arange(49) % 2, STENCIL_GAP.max_value, STENCIL_GAP.min_value)]
    codes = np.array([encode_gaps(g) for g in stencils])
    w = [W1K, 603 << 8, 2000 << 8, W1K, W1K]
    length = [encode_length(x) for x in (50.0, 20.0, 10.0, 10.0, 10.0)]
    outs, cycles = simulate_chain_line_core(codes, w, length, e_prime_code=EP)
    assert cycles == [CHAIN_LINE_CYCLES] * 5
    want = [chain_line_golden([int(x) for x in c], wi, li, e_prime_code=EP)
            for c, wi, li in zip(codes, w, length)]
    assert outs == want
    assert [o.hertz.mode_name for o in want] == ["elliptic", "elliptic", "line", "flagged",
                                                 "flagged"]
    assert want[1].hertz.scale == 1 and want[4].flags >> 8
