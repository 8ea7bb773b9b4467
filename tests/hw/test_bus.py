"""The CSR register block: every register kind, constants, RAM, unmapped accesses,
one-cycle acknowledge — driven directly in the Amaranth simulator."""

import gc
import warnings

import pytest
from amaranth.sim import Simulator

from gearcontact.hw.bus import RegisterBlock, port_name
from gearcontact.hw.regmap import (
    CHAIN_FLAG_BITS,
    HERTZ_FLAG_BITS,
    SOC_MAPS,
    SRAM_BASE,
    Region,
    Register,
    get_map,
)
from gearcontact.validation import InputRangeError


def _run(block, body):
    async def tb(ctx):
        bus = block.bus

        async def access(addr, value=None):
            ctx.set(bus.adr, addr)
            ctx.set(bus.we if value is not None else bus.re, 1)
            ctx.set(bus.dat_w, value or 0)
            seen = {}
            for name in ("preview__go", "preview__wr_data__stb", "preview__wr_data",
                         "preview__wr_rst", "error"):
                if hasattr(block, name):
                    seen[name] = ctx.get(getattr(block, name))
            await ctx.tick()
            ctx.set(bus.we, 0)
            ctx.set(bus.re, 0)
            assert ctx.get(bus.ack) == 1
            return ctx.get(bus.dat_r), seen

        await body(ctx, block, access)

    sim = Simulator(block)
    sim.add_clock(1e-8)
    sim.add_testbench(tb)
    sim.run()


def test_register_kinds_and_ram():
    m = get_map("tri_core")
    block = RegisterBlock(m, constants={("contact", "magic"): 0x4743_4E54})

    async def body(ctx, b, access):
        ctx.set(b.preview__A, 0xFFFF_FA0C)
        assert (await access(m.addr("preview", "A")))[0] == 0xFFFF_FA0C     # ro
        assert (await access(m.addr("contact", "magic")))[0] == 0x4743_4E54  # constant
        assert (await access(m.addr("ctrl", "scratch")))[0] == 0x1234_5678  # rw reset
        await access(m.addr("ctrl", "scratch"), 0xCAFE_F00D)
        assert (await access(m.addr("ctrl", "scratch")))[0] == 0xCAFE_F00D
        # strobe: combinational in the access cycle, only with bit 0 set, reads 0
        _, seen = await access(m.addr("preview", "go"), 1)
        assert seen["preview__go"] == 1
        _, seen = await access(m.addr("preview", "go"), 2)
        assert seen["preview__go"] == 0
        assert ctx.get(b.preview__go) == 0
        assert (await access(m.addr("preview", "go")))[0] == 0
        # wdata: the bus word and the pulse in the access cycle, stored for readback
        _, seen = await access(m.addr("preview", "wr_data"), 0x8000_0001)
        assert seen["preview__wr_data__stb"] == 1 and seen["preview__wr_data"] == 0x8000_0001
        assert ctx.get(b.preview__wr_data__stb) == 0
        assert (await access(m.addr("preview", "wr_data")))[0] == 0x8000_0001
        # rw W_load keeps its value
        await access(m.addr("preview", "W_load"), 1000 << 8)
        assert ctx.get(b.preview__W_load) == 1000 << 8
        # SRAM: first and last word
        await access(SRAM_BASE, 0x1111_2222)
        await access(SRAM_BASE + 8188, 0x3333_4444)
        assert (await access(SRAM_BASE))[0] == 0x1111_2222
        assert (await access(SRAM_BASE + 8188))[0] == 0x3333_4444
        # unmapped: acknowledged, reads 0, error pulse
        data, seen = await access(0x0400)
        assert data == 0 and seen["error"] == 1
        data, seen = await access(SRAM_BASE + 8192)
        assert data == 0 and seen["error"] == 1
        _, seen = await access(m.addr("ctrl", "scratch"))
        assert seen["error"] == 0

    _run(block, body)


def test_ports_follow_the_map():
    block = RegisterBlock(get_map("bhseq_core"))
    block._MustUse__silence = True          # inspected, not elaborated
    names = set(block.signature.members)
    assert {port_name("hertz", "A_in"), port_name("hertz", "go"),
            port_name("ctrl", "reset"), "bus", "error"} <= names
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(ValueError, match="must be ro"):
            RegisterBlock(get_map("bhseq_core"), constants={("hertz", "go"): 1})
        gc.collect()


def test_map_validation():
    with pytest.raises(ValueError, match="offset"):
        Register("x", 2, "ro")
    with pytest.raises(ValueError, match="kind"):
        Register("x", 0, "rx")
    with pytest.raises(ValueError, match="increasing"):
        Region("r", 0, (Register("a", 4, "ro"), Register("b", 0, "ro")))
    with pytest.raises(InputRangeError, match="SoC"):
        get_map("quad_core")
    with pytest.raises(KeyError, match="no register"):
        get_map("tri_core").addr("preview", "flags")


def test_flag_widths_match_the_rtl():
    from gearcontact.preview.chain_rtl import CHAIN_FLAG_BITS as rtl_chain
    from gearcontact.preview.hertz.rtl_datapath import FLAG_BITS as rtl_hertz
    assert (CHAIN_FLAG_BITS, HERTZ_FLAG_BITS) == (rtl_chain, rtl_hertz)


def test_spec_section7_tri_core_map():
    m = SOC_MAPS["tri_core"]
    bases = {r.name: r.base for r in m.regions}
    assert bases == {"contact": 0x0000, "ctrl": 0x0800, "identifier": 0x1000,
                     "preview": 0x1800, "timer0": 0x2000, "sram": 0x0100_0000}
    assert m.region("sram").size == 8 * 1024
    assert [(r.name, r.offset) for r in m.region("contact").registers] == [
        ("gap", 0x00), ("idx", 0x04), ("flags", 0x08), ("magic", 0x0C)]
    pv = m.region("preview")
    assert [(r.name, r.offset, r.writable) for r in pv.registers] == [
        ("wr_rst", 0x00, True), ("wr_data", 0x04, True), ("W_load", 0x08, True),
        ("go", 0x0C, True), ("A", 0x10, False), ("B", 0x14, False), ("a", 0x18, False),
        ("b", 0x1C, False), ("p_max", 0x20, False), ("k", 0x24, False),
        ("done", 0x28, False)]
