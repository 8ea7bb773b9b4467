"""The published register maps against the cores' signatures: every register that a SoC
wires to a core port holds exactly that port's width (truth: the component's
``signature.members``, via the harness' :func:`member_port`), and the ``done`` register
has room for the core's flags word above ``DONE_FLAGS_SHIFT``."""

import pytest

from gearcontact.hw.harness_cores import get_bench, member_port
from gearcontact.hw.regmap import CONTACT_FLAG_BITS, DONE_FLAGS_SHIFT, get_map

#: Register -> core port, as hw.soc wires them (tri_core: ChainCore; bhseq: HertzCore;
#: contact: GapCore through ContactRunner; line_core: ChainLineCore).
WIRING = {
    ("contact_core", "contact", "gap"): {"gap": "gap", "idx": "idx"},
    ("tri_core", "preview", "chain"): {"wr_data": "wr_data", "W_load": "W", "A": "a_minus",
                                       "B": "b_minus", "a": "a", "b": "b", "p_max": "p_max",
                                       "k": "k"},
    ("bhseq_core", "hertz", "hertz"): {"A_in": "A", "B_in": "B", "W_load": "W",
                                       "A": "B_max", "B": "A_min", "a": "a", "b": "b",
                                       "p_max": "p_max", "k": "k"},
    ("line_core", "line", "chain_line"): {"wr_data": "wr_data", "W_load": "W", "L_line": "L",
                                          "A": "a_minus", "B": "b_minus", "a": "a", "b": "b",
                                          "p_max": "p_max", "k": "k", "A_min": "A_min",
                                          "B_max": "B_max"},
}


@pytest.mark.parametrize("kind, region, core", list(WIRING))
def test_register_widths_follow_the_core_signature(kind, region, core):
    comp = get_bench(core).make_component()
    comp._MustUse__silence = True                 # inspected, not elaborated
    members = comp.signature.members
    reg = get_map(kind).region(region)
    for name, port in WIRING[(kind, region, core)].items():
        r = reg.reg(name)
        p = member_port(port, members[port].shape)
        assert (r.fmt.bits if r.fmt is not None else r.width) == p.width, (name, port)
        assert r.fmt is None or r.fmt.signed == p.signed, (name, port)
    if "flags" in members:
        flags = member_port("flags", members["flags"].shape)
        assert reg.reg("done").width == DONE_FLAGS_SHIFT + flags.width
    else:  # the gap core's status bits, one per contact.flags bit
        assert reg.reg("flags").width == len(CONTACT_FLAG_BITS)
        assert {"valid", "overflow", "n_error", "done"} <= set(members)


def test_line_region_keeps_the_preview_layout():
    """line_core's ``line`` region is the tri_core ``preview`` protocol (same offsets,
    kinds and Q formats up to ``done``) with the length and the line core's registers
    after it; every fixed-point register names its Q format in its description."""
    pre, line = get_map("tri_core").region("preview"), get_map("line_core").region("line")
    for r in pre.registers:
        q = line.reg(r.name)
        assert (q.offset, q.kind, q.fmt) == (r.offset, r.kind, r.fmt), r.name
    extra = {r.name: r.offset for r in line.registers if r.offset > pre.reg("done").offset}
    assert extra == {"L_line": 0x2C, "A_min": 0x30, "B_max": 0x34, "mode": 0x38}
    assert line.reg("mode").width == 3      # bit 0 mode, bits 1..2 the SCALE exponent
    for r in line.registers:
        assert r.fmt is None or str(r.fmt) in r.doc, r.name
