"""LiteX SoC for the XC7K480T card: jtagbone bridge + CSRs from the register map.

:class:`BoardSoC` is a ``SoCMini`` (no CPU) whose only bus master is the jtagbone bridge
(``add_jtagbone``: BSCANE2 on the FPGA's JTAG port; the host runs ``litex_server
--jtag`` and :class:`gearcontact.hw.driver.LiteXRemoteTransport`). The Amaranth
:class:`gearcontact.hw.soc.SocDatapath` Verilog is added with ``add_source`` and
instantiated with ``Instance``; each datapath region of :mod:`gearcontact.hw.regmap`
becomes a LiteX CSR peripheral whose CSRs are created in table order, so their
addresses are the map's offsets (CSR data width 32, paging 0x800, the region's CSR
location = base / 0x800). ``ctrl`` (reset, scratch, bus_errors), ``identifier_mem``
(the map's identifier string) and ``timer0`` are LiteX's own; the 8 KiB SRAM is
LiteX's integrated SRAM at 0x0100_0000; the CSR window starts at bus address 0.

Register kinds map to LiteX CSRs as: ``ro`` -> ``CSRStatus`` (constants as its reset
value), ``rw`` -> ``CSRStorage``, ``wdata`` -> ``CSRStorage`` with ``re`` as the write
pulse, ``strobe`` -> ``CSRStorage(1)`` with ``re & storage[0]`` as the pulse.

:func:`generate` writes everything without running a vendor tool (LiteX ``Builder``
with ``compile_gateware=False``).
"""

from __future__ import annotations

import logging
import os
import tempfile
from pathlib import Path

from litex.build.io import CRG
from litex.soc.integration.builder import Builder
from litex.soc.integration.soc_core import SoCCore, SoCMini
from litex.soc.interconnect.csr import AutoCSR, CSRStatus, CSRStorage
from migen import ClockSignal, Instance, Module, ResetSignal, Signal

from ..bus import port_name
from ..regmap import CSR_PAGE, SRAM_SIZE, SocMap, get_map
from ..reproducible import reproducible_tree
from ..soc import _DATAPATH_REGIONS, PROBE_BITS, _constants, datapath_ports
from .platform import CLK_FREQ_HZ, Platform

__all__ = ["BUILD_SCRIPT_NOTE", "BoardSoC", "RegionCSRs", "generate"]


class RegionCSRs(Module, AutoCSR):
    """The CSRs of one datapath region, created in map order (addresses = offsets).

    Attributes
    ----------
    inputs : dict
        Datapath input port name -> Migen expression (storage / pulses).
    outputs : dict
        Datapath output port name -> ``CSRStatus.status`` signal to drive.
    """

    def __init__(self, region, constants: dict):
        self.inputs, self.outputs = {}, {}
        for i, r in enumerate(region.registers):
            port = port_name(region.name, r.name)
            key = (region.name, r.name)
            if r.kind == "ro":
                csr = CSRStatus(r.width, name=r.name, reset=constants.get(key, 0),
                                description=r.doc)
                if key not in constants:
                    self.outputs[port] = csr.status
            else:
                csr = CSRStorage(r.width, name=r.name, reset=r.reset, description=r.doc)
                if r.kind == "strobe":
                    self.inputs[port] = csr.re & csr.storage[0]
                else:
                    self.inputs[port] = csr.storage
                    if r.kind == "wdata":
                        self.inputs[port + "__stb"] = csr.re
            setattr(self, f"csr_{i:03d}_{r.name}", csr)


class BoardSoC(SoCMini):
    """SoC ``kind`` on the XC7K480T card (module docstring).

    Parameters
    ----------
    platform : Platform
        The board (:mod:`.platform`).
    kind : str
        One of :data:`gearcontact.hw.regmap.SOC_KINDS`.
    datapath_verilog : path
        Verilog of ``SocDatapath(kind)`` with top module ``<kind>_datapath``.
    """

    mem_map = {**SoCCore.mem_map, "csr": 0x0000_0000}  # noqa: RUF012 -- LiteX API

    def __init__(self, platform, kind: str, datapath_verilog, *,
                 sys_clk_freq: float = CLK_FREQ_HZ):
        smap: SocMap = get_map(kind)
        self.csr_map = {rg.litex_name: rg.base // CSR_PAGE for rg in smap.csr_regions()}
        sram = any(rg.memory for rg in smap.regions)
        SoCMini.__init__(self, platform, sys_clk_freq, ident=smap.ident, ident_version=False,
                         with_timer="timer0" in self.csr_map,
                         integrated_sram_size=SRAM_SIZE if sram else 0,
                         csr_data_width=32, csr_paging=CSR_PAGE)
        self.crg = CRG(platform.request("clk50"), ~platform.request("cpu_reset_n"))
        self.add_jtagbone()

        const = _constants(smap)
        ports = {}
        for rg in smap.csr_regions():
            if rg.name in _DATAPATH_REGIONS:
                mod = RegionCSRs(rg, const)
                self.add_module(name=rg.litex_name, module=mod)
                ports.update({f"i_{k}": v for k, v in mod.inputs.items()})
                ports.update({f"o_{k}": v for k, v in mod.outputs.items()})
        expected = set(datapath_ports(smap, const))
        assert {p[2:] for p in ports} == expected, "LiteX CSRs and datapath ports differ"
        self.probe_cycles = Signal(PROBE_BITS)
        self.specials += Instance(f"{kind}_datapath", i_clk=ClockSignal("sys"),
                                  i_rst=ResetSignal("sys"), o_probe_cycles=self.probe_cycles,
                                  **ports)
        platform.add_source(str(datapath_verilog))


#: What the generated README says about the build script.
BUILD_SCRIPT_NOTE = """\
The openXC7 build script is LiteX's own ``build_<name>.sh`` (toolchain ``openxc7``:
yosys synth_xilinx -> nextpnr-xilinx -> fasm2frames -> xc7frames2bit). LiteX needs the
chip database and prjxray-db paths while it writes the script; they were placeholders
here, so the script reads them from the environment instead:

    export CHIPDB=/path/to/nextpnr-xilinx/chipdb          # holds {dbpart}.bin
    export PRJXRAY_DB_DIR=/path/to/prjxray-db              # holds kintex7/
    cd gateware && sh build_{name}.sh

Multipliers: add ``-nodsp`` to the synth_xilinx line if nextpnr-xilinx hits the
DSP-cascade router bug the published build avoided (docs/spec.md sec. 7) — at the cost of
~200k LUT for tri_core.
"""


def generate(out_dir, *, kind: str = "tri_core", lanes: int = 16,
             e_prime_code: int | None = None, name: str | None = None) -> dict:
    """Write the board flow of SoC ``kind`` into ``out_dir`` (nothing is run).

    Parameters
    ----------
    out_dir : path
        Output directory (created): ``amaranth/<kind>_datapath.v``, ``gateware/``
        (``<name>.v`` top, ``<name>.xdc`` with ``create_clock``, ``build_<name>.sh``),
        ``csr.csv``, ``csr.json``, ``README.md``.
    kind, lanes, e_prime_code : keyword-only
        SoC parameters (:class:`gearcontact.hw.soc.SocDatapath`).
    name : str, keyword-only
        Build name (default ``gearcontact_<kind>``).

    Returns
    -------
    dict
        ``verilog``, ``datapath``, ``xdc``, ``script``, ``csr_csv``, ``csr_json``,
        ``readme`` -> paths.
    """
    from ...preview.stimulus import STEEL_E_PRIME_CODE
    from ..soc import convert_verilog

    smap = get_map(kind)
    out = Path(out_dir).resolve()
    name = name or f"gearcontact_{kind}"
    (out / "amaranth").mkdir(parents=True, exist_ok=True)
    dp = out / "amaranth" / f"{kind}_datapath.v"
    dp.write_text(convert_verilog(kind, lanes=lanes, datapath_only=True,
                                  e_prime_code=STEEL_E_PRIME_CODE if e_prime_code is None
                                  else e_prime_code))
    quiet = logging.root.manager.disable
    logging.disable(logging.INFO)              # LiteX's SoC / bus / CSR INFO report
    try:
        paths = _build(out, kind, name, dp)
    finally:
        logging.disable(quiet)
    readme = out / "README.md"
    readme.write_text(f"# {smap.ident} on the XC7K480T card\n\n"
                      f"Generated by `gearcontact rtl soc`; jtagbone is the only bus master.\n"
                      f"Clock 50 MHz on AA28 (create_clock in gateware/{name}.xdc), "
                      f"reset R28 (active low).\n\n"
                      + BUILD_SCRIPT_NOTE.format(dbpart=paths.pop("dbpart"), name=name)
                      + "\nHost side: `litex_server --jtag` then "
                        "`gearcontact.hw.driver.PreviewDriver(LiteXRemoteTransport())`.\n")
    # byte-identical across runs and install locations (issue 12)
    reproducible_tree(out, here=out / "gateware")
    return {**paths, "datapath": dp, "csr_csv": out / "csr.csv",
            "csr_json": out / "csr.json", "readme": readme}


def _build(out: Path, kind: str, name: str, dp: Path) -> dict:
    """LiteX SoC + Builder run (no gateware compile); post-processes script and XDC."""
    platform = Platform(toolchain="openxc7")
    soc = BoardSoC(platform, kind, dp)
    builder = Builder(soc, output_dir=str(out), compile_software=False,
                      compile_gateware=False, csr_csv=str(out / "csr.csv"),
                      csr_json=str(out / "csr.json"))
    with tempfile.TemporaryDirectory() as tmp:
        chipdb = Path(tmp) / "chipdb"
        prjxray = Path(tmp) / "prjxray-db"
        chipdb.mkdir()
        (prjxray / "kintex7").mkdir(parents=True)
        dbpart = _dbpart(platform)
        (chipdb / f"{dbpart}.bin").write_bytes(b"")
        saved = {k: os.environ.get(k) for k in ("CHIPDB", "PRJXRAY_DB_DIR")}
        os.environ.update(CHIPDB=str(chipdb), PRJXRAY_DB_DIR=str(prjxray))
        try:
            builder.build(build_name=name, run=False)
        finally:
            for k, v in saved.items():
                if v is None:
                    os.environ.pop(k, None)
                else:
                    os.environ[k] = v
        gw = out / "gateware"
        script = gw / f"build_{name}.sh"
        text = script.read_text()
        text = text.replace(str(chipdb), "${CHIPDB:?set CHIPDB to the nextpnr-xilinx chipdb dir}")
        text = text.replace(str(prjxray), "${PRJXRAY_DB_DIR:?set PRJXRAY_DB_DIR}")
        script.write_text(text)
    xdc = gw / f"{name}.xdc"
    # LiteX 2024.12's yosys+nextpnr XDC writer leaves "-name {name}" unformatted
    xdc.write_text(xdc.read_text().replace("-name {name}", "-name clk50"))
    return {"verilog": gw / f"{name}.v", "xdc": xdc, "script": script, "dbpart": dbpart}


def _dbpart(platform) -> str:
    """nextpnr-xilinx chip database name LiteX derives from the device."""
    tc = platform.toolchain
    tc.platform = platform
    tc._check_properties()
    return tc.dbpart
