"""LiteX platform of the XC7K480T card (Inspur YPCB-00338; no litex-boards entry).

==========  ====  ======================================================
signal      pin   standard / meaning
==========  ====  ======================================================
clk50       AA28  LVCMOS33, 50 MHz oscillator (period 20 ns constrained)
cpu_reset   R28   LVCMOS33, active-low push button / board reset
==========  ====  ======================================================

The device is xc7k480t-ffg1156-2, spelled ``xc7k480tffg1156-2`` as nextpnr-xilinx and
prjxray-db (openXC7) name their parts. Only the pins the SoC needs are listed; the
host reaches the SoC through the FPGA's own JTAG port (jtagbone, BSCANE2), so no
UART/Ethernet pins are required.
"""

from __future__ import annotations

from litex.build.generic_platform import IOStandard, Pins
from litex.build.xilinx import XilinxPlatform

__all__ = ["CLK_FREQ_HZ", "CLK_PIN", "DEVICE", "RESET_PIN", "Platform"]

#: FPGA part as openXC7 names it (xc7k480t, package ffg1156, speed grade -2).
DEVICE = "xc7k480tffg1156-2"
CLK_PIN, RESET_PIN = "AA28", "R28"
CLK_FREQ_HZ = 50e6

_IO = [
    ("clk50", 0, Pins(CLK_PIN), IOStandard("LVCMOS33")),
    ("cpu_reset_n", 0, Pins(RESET_PIN), IOStandard("LVCMOS33")),
]


class Platform(XilinxPlatform):
    """XC7K480T card; default toolchain ``openxc7`` (yosys + nextpnr-xilinx + prjxray)."""

    default_clk_name = "clk50"
    default_clk_period = 1e9 / CLK_FREQ_HZ

    def __init__(self, toolchain: str = "openxc7"):
        XilinxPlatform.__init__(self, DEVICE, _IO, toolchain=toolchain)

    def do_finalize(self, fragment):
        XilinxPlatform.do_finalize(self, fragment)
        # the create_clock the original bring-up missed (docs/spec.md sec. 7)
        self.add_period_constraint(self.lookup_request("clk50", loose=True),
                                   self.default_clk_period)
