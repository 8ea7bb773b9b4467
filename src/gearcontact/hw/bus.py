"""A 32-bit CSR-style register bus and a register block generated from a map.

Bus protocol (:data:`CSR_BUS`, master's view; all synchronous to ``sync``)

=======  =====  ======  ================================================================
signal   dir    width   meaning
=======  =====  ======  ================================================================
adr      out    32      byte address (bits 1..0 ignored)
dat_w    out    32      write data
we       out    1       write strobe: one cycle per access
re       out    1       read strobe: one cycle per access
dat_r    in     32      read data, valid while ``ack`` is 1
ack      in     1       one cycle after the strobe (every access is acknowledged,
                        unmapped ones too: they read 0 and count a bus error)
=======  =====  ======  ================================================================

An access is the cycle with ``re`` or ``we`` set; its effect happens on that edge:
``rw`` storage takes the new value (visible from the next cycle), ``strobe`` and
``wdata`` pulses are combinational in the access cycle (``wdata`` presents the bus word
itself then), so the datapath acts on the same edge and a read issued right after a
``go`` already sees the cleared ``done``. ``ack`` and ``dat_r`` follow one cycle later. This is the
shape of LiteX's CSR bus behind its Wishbone bridge, so a host sees the same register
behaviour through the simulator and through a board.

:class:`RegisterBlock` builds the decoder and storage for every register of a
:class:`~.regmap.SocMap` (kinds ``ro`` / ``rw`` / ``wdata`` / ``strobe``, see
:mod:`.regmap`) plus the optional RAM region. Register fields are exposed as ports
named ``<region>__<register>`` (and ``<region>__<register>__stb`` for the write pulse
of ``wdata``); ``ro`` registers given in ``constants`` (magic, identifier bytes) are
built as constants instead of ports.
"""

from __future__ import annotations

from amaranth import Module, Mux, Signal
from amaranth.lib import wiring
from amaranth.lib.memory import Memory
from amaranth.lib.wiring import In, Out

from .regmap import SocMap

__all__ = ["CSR_BUS", "RegisterBlock", "port_name"]

#: The bus signature, master's view (slaves use ``In(CSR_BUS)``).
CSR_BUS = wiring.Signature({"adr": Out(32), "dat_w": Out(32), "we": Out(1), "re": Out(1),
                            "dat_r": In(32), "ack": In(1)})


def port_name(region: str, reg: str) -> str:
    """Port name of register ``region.reg`` on a :class:`RegisterBlock`."""
    return f"{region}__{reg}"


class RegisterBlock(wiring.Component):
    """Bus slave holding every register of ``soc_map``.

    Parameters
    ----------
    soc_map : SocMap
        The register map (:mod:`.regmap`).
    constants : dict, optional
        ``{(region, reg): value}`` for ``ro`` registers that are constants.

    Notes
    -----
    Ports: ``bus`` (slave side of :data:`CSR_BUS`); ``error`` (out, 1): high in the
    cycle of an access to an unmapped address; one port per non-constant register
    (``ro``: in, ``rw``/``wdata``: out, ``strobe``: out pulse; width
    :attr:`.regmap.Register.width`), and ``<port>__stb`` (out, 1) for ``wdata``;
    ``strobe`` and ``wdata`` outputs are combinational from the bus (access cycle).
    """

    def __init__(self, soc_map: SocMap, *, constants: dict | None = None):
        self.soc_map = soc_map
        self.constants = dict(constants or {})
        ports = {"bus": In(CSR_BUS), "error": Out(1)}
        for rg in soc_map.csr_regions():
            for r in rg.registers:
                if (rg.name, r.name) in self.constants:
                    if r.kind != "ro":
                        raise ValueError(f"constant register {rg.name}.{r.name} must be ro")
                    continue
                name = port_name(rg.name, r.name)
                if r.kind == "ro":
                    ports[name] = In(r.width)
                elif r.kind == "strobe":
                    ports[name] = Out(1)
                else:
                    ports[name] = Out(r.width, init=r.reset)
                    if r.kind == "wdata":
                        ports[name + "__stb"] = Out(1)
        self._mem = [rg for rg in soc_map.regions if rg.memory]
        if len(self._mem) > 1:
            raise ValueError("at most one memory region")
        super().__init__(ports)

    def elaborate(self, platform):
        m = Module()
        bus = self.bus
        word = bus.adr[2:]
        access = bus.re | bus.we
        rdata = Signal(32)
        mapped = Signal()
        stored = {}
        for rg in self.soc_map.csr_regions():
            for r in rg.registers:
                if r.kind == "wdata":
                    name = port_name(rg.name, r.name)
                    reg = stored[name] = Signal(r.width, init=r.reset, name=name + "_q")
                    m.d.comb += getattr(self, name).eq(
                        Mux(getattr(self, name + "__stb"), bus.dat_w[:r.width], reg))
        self._stored = stored
        with m.Switch(word):
            for rg in self.soc_map.csr_regions():
                for r in rg.registers:
                    with m.Case((rg.base + r.offset) >> 2):
                        self._register(m, rg, r, rdata)
                        m.d.comb += mapped.eq(1)
        mem_hit = Signal()
        if self._mem:
            rg = self._mem[0]
            words = rg.size // 4
            m.submodules.ram = ram = Memory(shape=32, depth=words, init=[])
            wp, rp = ram.write_port(), ram.read_port()
            lo, hi = rg.base >> 2, (rg.base + rg.size) >> 2
            m.d.comb += [mem_hit.eq((word >= lo) & (word < hi)),
                         wp.addr.eq(word - lo), rp.addr.eq(word - lo),
                         wp.data.eq(bus.dat_w), wp.en.eq(bus.we & mem_hit)]
        mem_q = Signal()
        dat_q = Signal(32)
        m.d.sync += [bus.ack.eq(access), mem_q.eq(mem_hit), dat_q.eq(rdata)]
        m.d.comb += self.error.eq(access & ~mapped & ~mem_hit)
        if self._mem:
            m.d.comb += bus.dat_r.eq(Mux(mem_q, rp.data, dat_q))
        else:
            m.d.comb += bus.dat_r.eq(dat_q)
        return m

    def _register(self, m, rg, r, rdata):
        """Read value and write action of register ``r`` when addressed."""
        bus = self.bus
        key = (rg.name, r.name)
        if key in self.constants:
            m.d.comb += rdata.eq(self.constants[key] & 0xFFFF_FFFF)
            return
        port = getattr(self, port_name(rg.name, r.name))
        if r.kind == "ro":
            m.d.comb += rdata.eq(port)
        elif r.kind == "strobe":
            m.d.comb += port.eq(bus.we & bus.dat_w[0])
        elif r.kind == "wdata":
            name = port_name(rg.name, r.name)
            reg = self._stored[name]
            m.d.comb += [rdata.eq(reg), getattr(self, name + "__stb").eq(bus.we)]
            with m.If(bus.we):
                m.d.sync += reg.eq(bus.dat_w[:r.width])
        else:
            m.d.comb += rdata.eq(port)
            with m.If(bus.we):
                m.d.sync += port.eq(bus.dat_w[:r.width])
