"""The line_core SoC through its host driver (hw.line_driver): the line chain's register
protocol end to end on the simulated SoC against the golden model
(preview.chain.chain_line_golden, projected onto the registers by
LineReadback.from_golden) bit for bit, ``done`` 811 edges after ``go`` (CHAIN_LINE_CYCLES:
the fit's 52 + the line core's 759) and 873 bus edges per preview; the ``rtl-soc``
backend's line mode with the host's lift of a line below 1 mm against the golden
backend; bad codes refused before any write, a SoC of another kind named."""

import pytest

from gearcontact.contract.qformat import FixedPointOverflow
from gearcontact.hw import driver as drv
from gearcontact.hw.line_driver import LineDriver, LineReadback
from gearcontact.preview.chain import CHAIN_LINE_CYCLES, chain_line_golden
from gearcontact.preview.fit.pinv import N_TAPS
from gearcontact.preview.stimulus import STEEL_E_PRIME_CODE, chain_line_stimulus
from gearcontact.validation import InputRangeError

from .test_driver import FakeTransport

#: Bus edges of one preview: wr_rst, 49 wr_data, W_load, L_line, go (53 writes); one
#: poll of ``done`` per edge until it rises (811); 9 result reads (A, B, a, b, p_max, k,
#: A_min, B_max, mode).
BUS_EDGES = 1 + N_TAPS + 3 + CHAIN_LINE_CYCLES + 9


@pytest.fixture(scope="module")
def line():
    with drv.SimTransport("line_core") as t:
        yield LineDriver(t)


def _cases():
    """Corner vectors of the line chain (cylinder, saddle, coefficient overflow, the
    length envelope's ends, flagged) and two random ones, at the SoC's steel E'."""
    st = chain_line_stimulus(2, seed=3)
    f = st.fields
    want = ("cylinder (B = 0)", "saddle", "alternating min/max codes (coefficient overflow)",
            "elliptic stencil, length at the minimum", "elliptic stencil, length below the "
            "envelope", "random")
    keep = [i for i, lab in enumerate(st.labels)
            if lab in want and f["e_prime"][i] == STEEL_E_PRIME_CODE]
    return [(st.labels[i], [int(x) for x in f["gaps"][i]], int(f["W"][i]), int(f["L"][i]))
            for i in keep]


@pytest.mark.parametrize("label,gaps,W,L", _cases())
def test_line_core_protocol_bit_exact_with_the_golden_chain(line, label, gaps, W, L):
    c0 = line.t.cycles
    rb = line.run(gaps, W, L)
    gold = chain_line_golden(gaps, W, L, e_prime_code=STEEL_E_PRIME_CODE)
    assert rb == LineReadback.from_golden(gold), label
    assert rb.cycles == CHAIN_LINE_CYCLES == 811
    assert line.t.cycles - c0 == BUS_EDGES == 873


def test_the_cases_cover_both_modes_and_flags():
    """The vectors above are not all alike: line and elliptic answers and flagged ones."""
    gold = [chain_line_golden(g, w, n, e_prime_code=STEEL_E_PRIME_CODE)
            for _, g, w, n in _cases()]
    assert len(gold) >= 6
    assert {g.hertz.mode for g in gold if g.flags == 0} == {0, 1}
    assert any(g.flags >> 8 for g in gold) and any(g.flags & 0xFF for g in gold)


def test_rtl_soc_line_mode_with_the_hosts_lift_equals_golden():
    """``rtl-soc`` ``stencil(..., line_length_mm=L)``: a 0.4 mm line runs on the host's
    lift 2^2 x (300 N, 0.4 mm) through the line_core SoC and answers the golden
    backend's codes (the lift undone: a = 0.2 mm); a 12 mm line without a lift; stage D
    alone in line mode is refused, named (no SoC carries the line core without the fit)."""
    from gearcontact.hw import backends  # noqa: F401 (registers rtl-soc)
    from gearcontact.preview.engine import get_engine
    from gearcontact.preview.stimulus import _elliptic
    gaps = _elliptic(0.0246, 0.0, 0.3, 0.0, 0.01, -0.02)      # a cylinder: B- = 0
    eng, gold = get_engine("rtl-soc"), get_engine("golden")
    try:
        for length, lift in ((0.4, 2), (12.0, 0)):
            got = eng.stencil(gaps, 300.0, line_length_mm=length)
            want = gold.stencil(gaps, 300.0, line_length_mm=length)
            assert got.codes == want.codes and got.codes["lift"] == lift
            assert got.cycles == want.cycles == CHAIN_LINE_CYCLES
            assert got.mode == "line" and got.backend == "rtl-soc"
            assert got.a_mm == pytest.approx(length / 2, abs=2.0 ** -20)
        with pytest.raises(InputRangeError, match="line_length_mm.*line_core"):
            eng.hertz(0.05, 1e-6, 300.0, line_length_mm=12.0)
    finally:
        eng.close()


def test_bad_codes_refused_before_any_write_and_the_wrong_soc_named():
    t = FakeTransport(ident="gearcontact line_core")     # the same identifier base
    d = LineDriver(t)
    with pytest.raises(FixedPointOverflow, match="L_code"):
        d.run([0] * N_TAPS, 1000 << 8, 1 << 31)
    with pytest.raises(InputRangeError, match="L_code"):
        d.run([0] * N_TAPS, 1000 << 8, 2.5)
    with pytest.raises(FixedPointOverflow, match="W_code"):
        d.run([0] * N_TAPS, 1 << 31, 20 << 20)
    with pytest.raises(InputRangeError, match="exactly 49"):
        d.run([0] * 48, 1000 << 8, 20 << 20)
    assert t.writes == []
    with pytest.raises(drv.WrongIdentifier, match="expected 'gearcontact line_core'"):
        LineDriver(FakeTransport())
