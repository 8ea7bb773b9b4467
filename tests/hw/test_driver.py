"""Host driver: the tri_core register protocol end to end on the simulated SoC (bit-exact
with chain_golden, done 806 edges after go), stage D through bhseq_core, and the
driver's errors on bad input or a misbehaving bus."""

import dataclasses

import pytest

from gearcontact.hw import driver as drv
from gearcontact.hw.regmap import DONE_FLAGS_SHIFT, MAGIC, get_map, identifier_bytes
from gearcontact.preview.chain import chain_golden
from gearcontact.preview.hertz.golden import hertz_golden
from gearcontact.preview.hertz.schedule import CHAIN_CYCLES, HERTZ_CYCLES
from gearcontact.contract.qformat import FixedPointOverflow
from gearcontact.preview.stimulus import (
    STEEL_E_PRIME_CODE,
    chain_stimulus,
    hertz_stimulus,
)
from gearcontact.validation import InputRangeError


@pytest.fixture(scope="module")
def tri():
    with drv.SimTransport("tri_core") as t:
        yield drv.PreviewDriver(t)


def _chain_cases():
    st = chain_stimulus(2, seed=3)
    f = st.fields
    keep = [i for i, lab in enumerate(st.labels)
            if f["e_prime"][i] == STEEL_E_PRIME_CODE][:3] + [len(st) - 2, len(st) - 1]
    return [(st.labels[i], [int(x) for x in f["gaps"][i]], int(f["W"][i])) for i in keep]


@pytest.mark.parametrize("label,gaps,W", _chain_cases())
def test_tri_core_protocol_bit_exact_with_chain_golden(tri, label, gaps, W):
    rb = tri.run(gaps, W)
    gold = chain_golden(gaps, W, e_prime_code=STEEL_E_PRIME_CODE)
    assert rb == drv.PreviewReadback.from_golden(gold), label
    assert rb.cycles == CHAIN_CYCLES == 806


def test_tri_core_back_to_back_and_rewrite_only_load(tri):
    gaps, W = next((g, w) for _, g, w in _chain_cases()
                   if chain_golden(g, w, e_prime_code=STEEL_E_PRIME_CODE).flags == 0)
    first = tri.run(gaps, W)
    tri.set_load(W // 2 + 1)
    tri.go()
    rb = tri.read_results(tri.wait_done())
    gold = chain_golden(gaps, W // 2 + 1, e_prime_code=STEEL_E_PRIME_CODE)
    assert rb == drv.PreviewReadback.from_golden(gold)
    assert rb.flags == 0 and rb.p_max != first.p_max


def test_tri_core_identity_and_contact(tri):
    assert tri.identify() == "gearcontact tri_core"
    c = tri.read_contact()
    assert c.done and c.valid


def test_bhseq_protocol_bit_exact_with_hertz_golden():
    f = hertz_stimulus(1, seed=5).fields
    with drv.SimTransport("bhseq_core") as t:
        d = drv.HertzDriver(t)
        for i in (0, 3, len(f["A"]) - 1):
            if f["e_prime"][i] != STEEL_E_PRIME_CODE:
                continue
            a, b, w = (int(f[k][i]) for k in ("A", "B", "W"))
            rb = d.run(a, b, w)
            gold = hertz_golden(a, b, w, e_prime_code=STEEL_E_PRIME_CODE)
            assert rb == dataclasses.replace(drv.PreviewReadback.from_golden(gold),
                                             cycles=HERTZ_CYCLES)


def _rtl_soc():
    from gearcontact.hw import backends  # noqa: F401 (registers rtl-soc)
    from gearcontact.preview.engine import BACKENDS, get_engine
    assert "rtl-soc" in BACKENDS
    return get_engine("rtl-soc")


def _soc_stencil():
    from gearcontact.contract.stencil import stencil_coordinates
    s, t = stencil_coordinates()
    return 0.04 * s ** 2 + 0.01 * t ** 2 + 0.002 * s * t


def test_rtl_soc_engine_backend_equals_golden():
    from gearcontact.preview.engine import get_engine
    gaps = _soc_stencil()
    eng = _rtl_soc()
    try:
        got = eng.stencil(gaps, 900.0)
        got_h = eng.hertz(0.05, 0.01, 1000.0)
    finally:
        eng.close()
    gold = get_engine("golden").stencil(gaps, 900.0)
    gold_h = get_engine("golden").hertz(0.05, 0.01, 1000.0)
    assert got.cycles == CHAIN_CYCLES and got.valid and got.backend == "rtl-soc"
    assert (got.a_mm, got.b_mm, got.p_max_mpa, got.k, got.A_minus_per_mm,
            got.B_minus_per_mm, got.flags) == (gold.a_mm, gold.b_mm, gold.p_max_mpa, gold.k,
                                               gold.A_minus_per_mm, gold.B_minus_per_mm,
                                               gold.flags)
    assert got_h.cycles == HERTZ_CYCLES and got_h.valid
    for k in ("a", "b", "k", "p_max", "A_min", "B_max", "flags", "A_in", "B_in", "W"):
        assert got_h.codes[k] == gold_h.codes[k], k


def test_rtl_soc_engine_returns_the_register_values(monkeypatch):
    """The backend reports what it read from the registers, not the golden numbers: a
    readback with p_max and k off by one LSB shows up decoded in the result."""
    eng = _rtl_soc()
    real = drv.PreviewDriver.run

    def corrupted(self, gap_codes, W_code):
        rb = real(self, gap_codes, W_code)
        return dataclasses.replace(rb, p_max=rb.p_max + 1, k=rb.k - 1)

    monkeypatch.setattr(drv.PreviewDriver, "run", corrupted)
    from gearcontact.preview.engine import get_engine
    gaps = _soc_stencil()
    try:
        got = eng.stencil(gaps, 900.0)
    finally:
        eng.close()
    gold = get_engine("golden").stencil(gaps, 900.0)
    assert got.codes["p_max"] == gold.codes["p_max"] + 1
    assert got.p_max_mpa == gold.p_max_mpa + 2.0 ** -8        # PMAX Q(32,8) LSB, MPa
    assert got.k == gold.k - 2.0 ** -20                        # K_OUT Q(32,20) LSB
    assert got.a_mm == gold.a_mm


# ------------------------------------------------------------------ bad input / bus ---
class FakeTransport:
    """Dict-backed tri_core registers: done never rises unless told to."""

    def __init__(self, magic=MAGIC, ident="gearcontact tri_core", done=0):
        m = get_map("tri_core")
        self.mem = {m.addr("contact", "magic"): magic}
        base = m.region("identifier").base
        for i, c in enumerate(identifier_bytes(ident)):
            self.mem[base + 4 * i] = c
        self.mem[m.addr("preview", "done")] = done
        self.writes = []

    def read(self, addr):
        return self.mem.get(addr, 0)

    def write(self, addr, value):
        self.writes.append((addr, value))

    def close(self):
        pass


def test_wrong_magic_and_identifier():
    with pytest.raises(drv.WrongIdentifier, match="magic"):
        drv.PreviewDriver(FakeTransport(magic=0xDEADBEEF))
    with pytest.raises(drv.WrongIdentifier, match="gearcontact bhseq_core"):
        drv.PreviewDriver(FakeTransport(ident="gearcontact bhseq_core"))
    with pytest.raises(drv.DriverError, match="not a transport"):
        drv.PreviewDriver(object())


def test_timeout_waiting_for_done():
    d = drv.PreviewDriver(FakeTransport(), max_polls=50)
    d.go()
    with pytest.raises(drv.DoneTimeout, match="50 polls"):
        d.wait_done()
    d = drv.PreviewDriver(FakeTransport(), timeout_s=0.01)
    with pytest.raises(drv.DoneTimeout, match="0.01 s"):
        d.wait_done()


def test_stencil_length_and_formats_checked_before_any_write():
    t = FakeTransport()
    d = drv.PreviewDriver(t)
    for bad in ([0] * 48, [0] * 50, []):
        with pytest.raises(InputRangeError, match="exactly 49"):
            d.write_stencil(bad)
    with pytest.raises(FixedPointOverflow, match=r"gap_codes\[7\]"):
        d.write_stencil([0] * 7 + [1 << 31] + [0] * 41)
    with pytest.raises(InputRangeError, match=r"gap_codes\[0\]"):
        d.write_stencil([0.5] + [0] * 48)
    with pytest.raises(FixedPointOverflow, match="W_code"):
        d.set_load(-(1 << 31) - 1)
    with pytest.raises(InputRangeError, match="W_code"):
        d.set_load(True)
    assert t.writes == []


def test_negative_codes_are_written_as_twos_complement():
    t = FakeTransport(done=1 | (0x123 << DONE_FLAGS_SHIFT))
    d = drv.PreviewDriver(t)
    d.write_stencil([-1] * 49)
    assert t.writes[1:] == [(0x1804, 0xFFFF_FFFF)] * 49 and t.writes[0] == (0x1800, 1)
    assert d.read_results().flags == 0x123


def test_sim_transport_rejects_bad_addresses():
    with drv.SimTransport("bhseq_core") as t:
        with pytest.raises(InputRangeError, match="word-aligned"):
            t.read(0x1802)
        with pytest.raises(InputRangeError, match="bus word"):
            t.write(0x804, -1)
        t.write(0x804, 7)
        assert t.read(0x804) == 7
    with pytest.raises(drv.DriverError, match="closed"):
        t.read(0)


def test_litex_remote_transport_errors():
    pytest.importorskip("litex", reason=f"LiteX not installed: pip install {drv.LITEX_PIN}")
    with pytest.raises(InputRangeError, match="port"):
        drv.LiteXRemoteTransport(port=0)
    with pytest.raises(drv.DriverError, match="litex_server"):
        drv.LiteXRemoteTransport(host="127.0.0.1", port=1)


def test_importing_the_driver_does_not_load_amaranth():
    import subprocess
    import sys
    code = ("import sys, gearcontact.hw.driver as d, gearcontact.hw.backends, "
            "gearcontact.preview.engine as e; "
            "assert 'rtl-soc' in e.BACKENDS; assert 'amaranth' not in sys.modules")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_rtl_soc_exact_form_reads_back_the_exact_tables():
    """hertz_form='exact' builds the SoC with the exact-Hertz tables: the registers read
    back equal the exact-form golden model (and differ from the published form)."""
    from gearcontact.hw import backends  # noqa: F401
    from gearcontact.preview.engine import get_engine
    eng = get_engine("rtl-soc", hertz_form="exact")
    try:
        got = eng.hertz(0.05, 0.01, 1000.0)
    finally:
        eng.close()
    gold = get_engine("golden", hertz_form="exact").hertz(0.05, 0.01, 1000.0)
    assert got.hertz_form == "exact" and got.cycles == HERTZ_CYCLES
    for k in ("a", "b", "k", "p_max", "flags"):
        assert got.codes[k] == gold.codes[k], k
    assert got.codes["k"] != get_engine("golden").hertz(0.05, 0.01, 1000.0).codes["k"]
