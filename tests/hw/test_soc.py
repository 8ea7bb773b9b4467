"""SoC tops through the simulation transport: contact readback equals the golden gap
pass, identifier/magic, ctrl (soft reset, scratch, bus errors), timer0, dual_core."""

import pytest

from gearcontact.hw import driver as drv
from gearcontact.hw.regmap import IDENTS, MAGIC, get_map
from gearcontact.hw.soc import SocDatapath, baked_contact_vector
from gearcontact.preview.gap.golden import gap_golden_codes, gap_latency
from gearcontact.preview.hertz.golden import hertz_golden
from gearcontact.preview.hertz.schedule import HERTZ_CYCLES
from gearcontact.preview.stimulus import STEEL_E_PRIME_CODE


@pytest.fixture(scope="module")
def contact():
    with drv.SimTransport("contact_core") as t:
        yield t


def _contact_expected():
    g = gap_golden_codes(baked_contact_vector(), lanes=16)
    return drv.ContactReadback(g.min_gap_code, g.min_idx, g.valid, g.overflow, False, True)


def test_contact_readback_equals_golden_pass(contact):
    m = get_map("contact_core")
    vec = baked_contact_vector()
    # N write cycles + go + the gap core latency (26 at N = L = 16)
    contact.idle(vec.n_samples + 1 + gap_latency(16, 16))
    assert contact.read(m.addr("contact", "magic")) == MAGIC
    d = drv.ContactDriver(contact)
    assert d.read_identifier() == IDENTS["contact_core"]
    assert d.read_contact() == _contact_expected()


def test_contact_pass_latency_is_exact():
    with drv.SimTransport("contact_core") as t:
        m = get_map("contact_core")
        vec = baked_contact_vector()
        # after reset: N write edges, the go edge, latency - 1 edges to the gap
        # core's done, one edge into contact.flags; a read returns the state before
        # its own edge
        t.idle(vec.n_samples + gap_latency(16, 16))
        assert not t.read(m.addr("contact", "flags")) & 8
        assert t.read(m.addr("contact", "flags")) & 8


def test_ctrl_soft_reset_reruns_the_contact_pass(contact):
    m = get_map("contact_core")
    contact.write(m.addr("ctrl", "reset"), 1)
    assert contact.read(m.addr("contact", "flags")) & 8 == 0
    contact.idle(60)
    assert contact.read(m.addr("contact", "flags")) & 8
    assert contact.read(m.addr("ctrl", "scratch")) == 0x1234_5678


def test_bus_errors_count_unmapped_accesses(contact):
    m = get_map("contact_core")
    before = contact.read(m.addr("ctrl", "bus_errors"))
    contact.read(0x1800)               # no preview region in contact_core
    contact.write(0x0100_0000, 5)      # no SRAM either
    assert contact.read(m.addr("ctrl", "bus_errors")) == before + 2


def test_timer0_counts_down_and_latches(contact):
    m = get_map("contact_core")
    a = lambda r: m.addr("timer0", r)
    contact.write(a("load"), 1000)
    contact.write(a("en"), 1)          # count = load after this edge
    contact.idle(10)                   # ten edges down
    contact.write(a("update_value"), 1)    # latches the count before its edge
    assert contact.read(a("value")) == 1000 - 10
    contact.write(a("en"), 0)


def test_dual_core_contact_and_hertz():
    with drv.SimTransport("dual_core") as t:
        d = drv.HertzDriver(t, kind="dual_core")
        a, b, w = 52_429, 10_486, 1000 << 8
        rb = d.run(a, b, w)
        gold = hertz_golden(a, b, w, e_prime_code=STEEL_E_PRIME_CODE)
        assert rb == drv.PreviewReadback.from_golden(gold).__class__(
            **{**drv.PreviewReadback.from_golden(gold).__dict__, "cycles": HERTZ_CYCLES})
        assert rb.flags == 0
        assert d.read_contact() == _contact_expected()


def test_datapath_ports_are_the_register_ports():
    dp = SocDatapath("tri_core")
    dp._MustUse__silence = True             # inspected, not elaborated
    names = set(dp.signature.members)
    assert {"contact__gap", "preview__wr_data", "preview__wr_data__stb", "preview__go",
            "preview__done", "probe_cycles"} <= names
    assert "contact__magic" not in names and "ctrl__reset" not in names


def test_contact_core_with_8_lanes_is_exact_and_faster():
    """L = 8 halves the DSP of the contact readback and, at N = 16, shortens the pass
    (gap_latency(16, 8) = 18 < 26 cycles): same golden model at that lane count."""
    vec = baked_contact_vector()
    assert gap_latency(16, 8) == 18 < gap_latency(16, 16) == 26
    g = gap_golden_codes(vec, lanes=8)
    with drv.SimTransport("contact_core", lanes=8) as t:
        m = get_map("contact_core")
        t.idle(vec.n_samples + gap_latency(16, 8))
        assert not t.read(m.addr("contact", "flags")) & 8
        assert drv.ContactDriver(t).read_contact() == drv.ContactReadback(g.min_gap_code, g.min_idx, g.valid,
                                                       g.overflow, False, True)
