"""The five SoC tops of docs/spec.md sec. 7 in Amaranth: cores behind the register bus.

=================  =====================================================================
kind               datapath
=================  =====================================================================
``contact_core``   :class:`ContactRunner` (stage A/B, ``GapCore`` L = 16, baked pass)
``bhseq_core``     serialized stage D (``HertzCore``, 756 cycles) behind ``hertz``
``dual_core``      contact + stage D behind one readback
``tri_core``       contact + C -> D chain (``ChainCore``: 49-sample gap RAM written over
                   the bus, W_load, go; 806 cycles) behind ``preview``, 8 KiB SRAM
``line_core``      the line chain of a cylindrical pair (``ChainLineCore``: the same gap
                   RAM writes, W_load, L_line, go; 811 cycles) behind ``line``
=================  =====================================================================

Every top is split in two so that the LiteX board flow reuses the same RTL:

* :class:`SocDatapath` — the cores with one port per register of the map
  (:func:`.bus.port_name`; ``ro`` registers are outputs, writable ones inputs); this is
  the module LiteX wraps with ``Instance`` (:mod:`.litex`).
* :class:`SocTop` — :class:`.bus.RegisterBlock` + the datapath + the LiteX-compatible
  system registers (``ctrl``: soft reset, scratch, bus error count; ``identifier``;
  ``timer0``), i.e. what the board's jtagbone bridge sees, for simulation and synthesis.

Constant registers (not written by the host): ``contact.magic`` = :data:`.regmap.MAGIC`
and E' = 2E* of the Hertz stage, an E_PRIME Q(32,0) code in MPa baked at elaboration
(default steel/steel, :data:`gearcontact.preview.stimulus.STEEL_E_PRIME_CODE`).

The contact pass (stage A/B) runs by itself after every reset: :class:`ContactRunner`
writes its baked samples into the gap core's banks (N cycles), pulses ``go`` and the
gap core's outputs are the ``contact`` readback (``flags`` bit 3 says the pass is done).
"""

from __future__ import annotations

from amaranth import Array, Cat, Const, Module, ResetInserter, Signal
from amaranth.back import verilog
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from ..preview.chain_line_rtl import ChainLineCore
from ..preview.chain_rtl import ChainCore
from ..preview.gap.golden import GapVector
from ..preview.gap.rtl import GapCore
from ..preview.hertz import formats as HF
from ..preview.hertz.rtl import HertzCore
from ..preview.stimulus import STEEL_E_PRIME_CODE, gap_stimulus
from .bus import CSR_BUS, RegisterBlock, port_name
from .regmap import (
    CONTACT_FLAG_BITS,
    DONE_FLAGS_SHIFT,
    MAGIC,
    SocMap,
    get_map,
    identifier_bytes,
)

__all__ = [
    "PROBE_BITS",
    "ContactRunner",
    "SocDatapath",
    "SocTop",
    "baked_contact_vector",
    "convert_verilog",
    "datapath_ports",
]

#: Width of the ``probe_cycles`` output (edges from an accepted go to done).
PROBE_BITS = 16


def baked_contact_vector(seed: int = 0) -> GapVector:
    """The pass baked into the contact runner: the first seeded random 16-sample pass of
    :func:`gearcontact.preview.stimulus.gap_stimulus` (``seed``), so the golden model
    (:func:`gearcontact.preview.gap.golden.gap_golden_codes`) predicts the readback."""
    s = gap_stimulus(1, seed, n_samples=16, corners=False).fields
    return GapVector(s["r"][0], s["t"][0], s["p"][0], s["g"][0], s["nrm"][0],
                     int(s["tau2"][0]))


def _pack(row, bits: int) -> int:
    """Two's-complement codes packed element 0 first (an ``ArrayLayout`` value)."""
    mask = (1 << bits) - 1
    return sum((int(c) & mask) << (bits * i) for i, c in enumerate(row))


class ContactRunner(wiring.Component):
    """Stage A/B with a baked pass, run once after reset (``contact`` readback).

    Parameters
    ----------
    lanes : int
        Gap core lanes L (default 16).
    vector : GapVector, optional
        The baked pass (default :func:`baked_contact_vector`).

    Notes
    -----
    Ports: ``gap`` out signed(32) GAP Q(32,16) mm; ``idx`` out 16; ``flags`` out 4
    (bit 0 valid, 1 overflow, 2 n_error, 3 done). Schedule after reset: N write cycles,
    one go cycle, then the gap core's latency (26 cycles at N = L = 16).
    """

    def __init__(self, *, lanes: int = 16, vector: GapVector | None = None):
        self.vector = baked_contact_vector() if vector is None else vector
        self.lanes = lanes
        super().__init__({"gap": Out(32), "idx": Out(16), "flags": Out(4)})

    def elaborate(self, platform):
        m = Module()
        vec = self.vector
        n = vec.n_samples
        m.submodules.gap = gap = GapCore(lanes=self.lanes, max_samples=max(2 * self.lanes,
                                                                           1 << (n - 1).bit_length()))
        cnt = Signal(range(n + 2))
        done = Signal()
        g_rom = Array(Const(_pack(row, 24), 72) for row in vec.g_code)
        n_rom = Array(Const(_pack(row, 21), 63) for row in vec.n_code)
        loading = cnt < n
        m.d.comb += [gap.w_valid.eq(loading), gap.w_addr.eq(cnt),
                     gap.w_g.as_value().eq(g_rom[cnt]), gap.w_n.as_value().eq(n_rom[cnt]),
                     gap.go.eq(cnt == n), gap.n_samples.eq(n),
                     gap.tau2.eq(int(vec.tau2_code))]
        m.d.comb += [gap.r[i].eq(int(c)) for i, c in enumerate(vec.r_code.ravel())]
        m.d.comb += [gap.t[i].eq(int(c)) for i, c in enumerate(vec.t_code)]
        m.d.comb += [gap.p[i].eq(int(c)) for i, c in enumerate(vec.p_code)]
        with m.If(cnt <= n):
            m.d.sync += cnt.eq(cnt + 1)
        with m.If(gap.done):
            m.d.sync += done.eq(1)
        fl = {"valid": gap.valid, "overflow": gap.overflow, "n_error": gap.n_error,
              "done": done}
        m.d.comb += [self.gap.eq(gap.gap), self.idx.eq(gap.idx)]
        m.d.comb += [self.flags[b].eq(fl[k]) for k, b in CONTACT_FLAG_BITS.items()]
        return m


#: Regions whose registers the datapath serves (the rest is system logic).
_DATAPATH_REGIONS = ("contact", "preview", "hertz", "line")


def datapath_ports(soc_map: SocMap, constants: dict) -> dict:
    """Port signature of :class:`SocDatapath`: register ports, direction flipped."""
    ports = {}
    for rg in soc_map.csr_regions():
        if rg.name not in _DATAPATH_REGIONS:
            continue
        for r in rg.registers:
            if (rg.name, r.name) in constants:
                continue
            name = port_name(rg.name, r.name)
            if r.kind == "ro":
                ports[name] = Out(r.width)
            elif r.kind == "strobe":
                ports[name] = In(1)
            else:
                ports[name] = In(r.width)
                if r.kind == "wdata":
                    ports[name + "__stb"] = In(1)
    return ports


def _constants(soc_map: SocMap) -> dict:
    """Constant ``ro`` registers: contact magic and the identifier bytes."""
    const = {}
    names = [rg.name for rg in soc_map.regions]
    if "contact" in names:
        const[("contact", "magic")] = MAGIC
    if "identifier" in names:
        raw = identifier_bytes(soc_map.ident)
        for r in soc_map.region("identifier").registers:
            i = r.offset // 4
            const[("identifier", r.name)] = raw[i] if i < len(raw) else 0
    return const


class SocDatapath(wiring.Component):
    """The cores of SoC ``kind`` with one port per datapath register.

    Parameters
    ----------
    kind : str
        One of :data:`.regmap.SOC_KINDS`.
    lanes : int, keyword-only
        Gap core lanes (contact readback), default 16.
    e_prime_code : int, keyword-only
        Baked E', E_PRIME Q(32,0) MPa.
    hertz_form : {"hamrock-brewe", "exact"}, keyword-only
        Stage-D tables of the preview / Hertz core (default the published form).

    Notes
    -----
    Ports: :func:`datapath_ports` of the map, plus ``probe_cycles`` (out,
    :data:`PROBE_BITS`): edges from the last accepted ``go`` of the preview / Hertz
    core to its ``done`` (806 for tri_core, 811 for line_core, 756 for bhseq/dual), a
    simulation and bring-up probe that is not on the bus.
    """

    def __init__(self, kind: str, *, lanes: int = 16, e_prime_code: int = STEEL_E_PRIME_CODE,
                 hertz_form: str = HF.DEFAULT_HERTZ_FORM):
        self.kind = kind
        self.soc_map = get_map(kind)
        self.lanes = lanes
        self.e_prime_code = int(e_prime_code)
        self.hertz_form = HF.check_hertz_form(hertz_form)
        ports = datapath_ports(self.soc_map, _constants(self.soc_map))
        ports["probe_cycles"] = Out(PROBE_BITS)
        super().__init__(ports)

    def _p(self, region, reg):
        return getattr(self, port_name(region, reg))

    def elaborate(self, platform):
        m = Module()
        names = [rg.name for rg in self.soc_map.regions]
        if "contact" in names:
            m.submodules.contact = c = ContactRunner(lanes=self.lanes)
            m.d.comb += [self._p("contact", "gap").eq(c.gap),
                         self._p("contact", "idx").eq(c.idx),
                         self._p("contact", "flags").eq(c.flags)]
        core = None
        chain = next((r for r in ("preview", "line") if r in names), None)
        if chain is not None:       # a C -> D chain: the gap RAM written over the bus
            cls = ChainCore if chain == "preview" else ChainLineCore
            m.submodules.chain = core = cls(hertz_form=self.hertz_form)
            P = lambda r: self._p(chain, r)
            m.d.comb += [core.wr_rst.eq(P("wr_rst")), core.wr_en.eq(P("wr_data__stb")),
                         core.wr_data.eq(P("wr_data")), core.W.eq(P("W_load")),
                         core.e_prime.eq(self.e_prime_code), core.go.eq(P("go")),
                         P("A").eq(core.a_minus), P("B").eq(core.b_minus)]
            if chain == "line":
                m.d.comb += [core.L.eq(P("L_line")), P("A_min").eq(core.A_min),
                             P("B_max").eq(core.B_max),
                             P("mode").eq(Cat(core.mode, core.scale))]
            go = P("go")
        elif "hertz" in names:
            m.submodules.hertz = core = HertzCore(hertz_form=self.hertz_form)
            P = lambda r: self._p("hertz", r)
            m.d.comb += [core.A.eq(P("A_in")), core.B.eq(P("B_in")), core.W.eq(P("W_load")),
                         core.e_prime.eq(self.e_prime_code), core.go.eq(P("go")),
                         core.go_chain.eq(0),
                         P("A").eq(core.B_max), P("B").eq(core.A_min)]
            go = P("go")
        if core is not None:
            m.d.comb += [P("a").eq(core.a), P("b").eq(core.b), P("p_max").eq(core.p_max),
                         P("k").eq(core.k),
                         P("done").eq(Cat(core.done, core.busy,
                                          Const(0, DONE_FLAGS_SHIFT - 2), core.flags))]
            # probe: the go edge is edge 1; the count stops on the edge raising done
            cnt, run = Signal(PROBE_BITS), Signal()
            with m.If(go & ~core.busy):
                m.d.sync += [cnt.eq(1), run.eq(1)]
            with m.Elif(run & ~core.done):
                m.d.sync += cnt.eq(cnt + 1)
            with m.Elif(run):
                m.d.sync += run.eq(0)
            m.d.comb += self.probe_cycles.eq(cnt)
        return m


class SocTop(wiring.Component):
    """SoC ``kind``: register block + datapath + ctrl / identifier / timer0.

    Parameters
    ----------
    kind : str
        One of :data:`.regmap.SOC_KINDS`.
    lanes, e_prime_code, hertz_form : keyword-only
        See :class:`SocDatapath`.

    Notes
    -----
    Ports: ``bus`` (slave, :data:`.bus.CSR_BUS`), ``probe_cycles`` (out, 16, see
    :class:`SocDatapath`). ``ctrl.reset`` resets the datapath (as LiteX's ``ctrl``
    resets the SoC; the gap RAM keeps its contents); the register block, SRAM and
    timer are not reset by it.
    """

    def __init__(self, kind: str, *, lanes: int = 16, e_prime_code: int = STEEL_E_PRIME_CODE,
                 hertz_form: str = HF.DEFAULT_HERTZ_FORM):
        self.kind = kind
        self.soc_map = get_map(kind)
        self.lanes = lanes
        self.e_prime_code = int(e_prime_code)
        self.hertz_form = HF.check_hertz_form(hertz_form)
        super().__init__({"bus": In(CSR_BUS), "probe_cycles": Out(PROBE_BITS)})

    def elaborate(self, platform):
        m = Module()
        const = _constants(self.soc_map)
        m.submodules.regs = regs = RegisterBlock(self.soc_map, constants=const)
        dp = SocDatapath(self.kind, lanes=self.lanes, e_prime_code=self.e_prime_code,
                         hertz_form=self.hertz_form)
        soft_rst = regs.ctrl__reset
        m.submodules.datapath = ResetInserter(soft_rst)(dp)
        wiring.connect(m, wiring.flipped(self.bus), regs.bus)
        for name, member in dp.signature.members.items():
            if name == "probe_cycles":
                continue
            if member.flow == Out:
                m.d.comb += getattr(regs, name).eq(getattr(dp, name))
            else:
                m.d.comb += getattr(dp, name).eq(getattr(regs, name))
        m.d.comb += self.probe_cycles.eq(dp.probe_cycles)
        # ctrl.bus_errors
        errors = Signal(32)
        with m.If(regs.error):
            m.d.sync += errors.eq(errors + 1)
        m.d.comb += regs.ctrl__bus_errors.eq(errors)
        self._timer(m, regs)
        return m

    @staticmethod
    def _timer(m, regs):
        """LiteX ``Timer`` semantics: down-counter preloaded with ``load`` while
        disabled, reloading ``reload`` at zero while enabled; ``update_value`` latches."""
        count, value = Signal(32), Signal(32)
        with m.If(regs.timer0__en):
            with m.If(count == 0):
                m.d.sync += count.eq(regs.timer0__reload)
            with m.Else():
                m.d.sync += count.eq(count - 1)
        with m.Else():
            m.d.sync += count.eq(regs.timer0__load)
        with m.If(regs.timer0__update_value):
            m.d.sync += value.eq(count)
        m.d.comb += [regs.timer0__value.eq(value), regs.timer0__ev_status.eq(count == 0)]


def convert_verilog(kind: str, *, lanes: int = 16, e_prime_code: int = STEEL_E_PRIME_CODE,
                    datapath_only: bool = False, name: str | None = None,
                    hertz_form: str = HF.DEFAULT_HERTZ_FORM) -> str:
    """Verilog of :class:`SocTop` (or of :class:`SocDatapath` for LiteX wrapping).

    Parameters
    ----------
    kind : str
        One of :data:`.regmap.SOC_KINDS`.
    lanes, e_prime_code, hertz_form : keyword-only
        See :class:`SocDatapath`.
    datapath_only : bool, keyword-only
        Emit the datapath (register ports, no bus) instead of the bus top.
    name : str, keyword-only
        Verilog module name (default ``kind`` or ``kind + "_datapath"``).
    """
    cls = SocDatapath if datapath_only else SocTop
    top = cls(kind, lanes=lanes, e_prime_code=e_prime_code, hertz_form=hertz_form)
    name = name or (kind + "_datapath" if datapath_only else kind)
    return verilog.convert(top, name=name, strip_internal_attrs=True)
