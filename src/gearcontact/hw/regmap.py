"""Register maps of the five SoCs, defined once as data (docs/spec.md sec. 7).

Every consumer reads these tables: the Amaranth register block (:mod:`.bus`,
:mod:`.soc`), the host driver (:mod:`.driver`), the LiteX CSR generation
(:mod:`.litex`) and the tests. The layout follows LiteX's CSR conventions (32-bit CSR
data width, 0x800-byte pages, one register per 32-bit word, byte addresses):

==============  ===========  =============================================================
region          base         content
==============  ===========  =============================================================
``contact``     0x0000       stage A/B readback: gap 0x00, idx 0x04, flags 0x08, magic 0x0C
``ctrl``        0x0800       LiteX ctrl: reset 0x00, scratch 0x04, bus_errors 0x08
``identifier``  0x1000       LiteX ``identifier_mem``: one identifier byte per word
``preview``     0x1800       tri_core C -> D (table below); ``hertz`` in bhseq / dual;
                             ``line`` in line_core (the line chain, below)
``timer0``      0x2000       LiteX timer: load, reload, en, update_value, value, ev_*
``sram``        0x0100_0000  8 KiB scratch RAM (tri_core)
==============  ===========  =============================================================

tri_core ``preview`` region (docs/spec.md sec. 7, exact): wr ``wr_rst`` 0x00, ``wr_data``
0x04, ``W_load`` 0x08, ``go`` 0x0C; rd ``A`` 0x10, ``B`` 0x14, ``a`` 0x18, ``b`` 0x1C,
``p_max`` 0x20, ``k`` 0x24, ``done`` 0x28. That map has no separate flags word: the
``done`` register carries ``done`` in bit 0, ``busy`` in bit 1, and the 12-bit chain
flags word (:mod:`gearcontact.preview.chain`) in bits 16..27 — still one 32-bit read.

line_core ``line`` region (the C -> line-core chain of a cylindrical pair,
:class:`gearcontact.preview.chain_line_rtl.ChainLineCore`): the ``preview`` layout up to
``done`` 0x28 (``A``, ``B`` the fit's A-, B-; ``k`` 0 in line mode; the 12-bit line chain
flags word in ``done`` bits 16..27), then wr ``L_line`` 0x2C (LINE_LENGTH Q(32,20) mm),
rd ``A_min`` 0x30, ``B_max`` 0x34 (the line core's sorted curvatures), ``mode`` 0x38
(bit 0 line mode, bits 1..2 the SCALE exponent n).

Register kinds (:attr:`Register.kind`):

==========  ==========================================================================
``ro``      read-only status, driven by the datapath;
``rw``      storage read back as written (reset value :attr:`Register.reset`);
``wdata``   storage plus a one-cycle write pulse (``wr_data``: one RAM sample per write);
``strobe``  a write with bit 0 set produces a one-cycle pulse (``go``, ``wr_rst``);
            reads return 0.
==========  ==========================================================================
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..preview.chain import CHAIN_LINE_CYCLES, FIT_FLAG_SHIFT
from ..preview.fit.golden import FLAG_BITS as FIT_FLAG_BITS
from ..preview.fit.pinv import N_TAPS
from ..preview.hertz import formats as HF
from ..preview.hertz.line import LINE_LENGTH
from ..contract.qformat import (CURVATURE, GAP, LOAD, PMAX, SEMI_AXIS, STENCIL_GAP,
                                QFormat)

__all__ = [
    "CONTACT_FLAG_BITS",
    "CSR_PAGE",
    "DONE_FLAGS_SHIFT",
    "IDENTS",
    "MAGIC",
    "SOC_KINDS",
    "CYLINDRICAL_SOC_KINDS",
    "SOC_MAPS",
    "SRAM_BASE",
    "SRAM_SIZE",
    "Region",
    "Register",
    "SocMap",
    "get_map",
    "identifier_bytes",
]

# Flag word widths (as chain_rtl / hertz.rtl_datapath derive them; this module stays
# free of Amaranth so that the host driver imports quickly).
CHAIN_FLAG_BITS = FIT_FLAG_SHIFT + FIT_FLAG_BITS
HERTZ_FLAG_BITS = max(HF.FLAG_NAMES).bit_length()

#: LiteX CSR page (``csr_address_width`` 14, 32-bit words: 0x800 bytes per region).
CSR_PAGE = 0x800
#: Base and size of the tri_core scratch SRAM (bytes).
SRAM_BASE, SRAM_SIZE = 0x0100_0000, 8 * 1024
#: Constant of ``contact.magic`` (ASCII "GCNT"): proves the bus reaches a gearcontact SoC.
MAGIC = 0x4743_4E54
#: Position of the chain flags word in the tri_core ``preview.done`` register.
DONE_FLAGS_SHIFT = 16
#: ``contact.flags`` bits.
CONTACT_FLAG_BITS = {"valid": 0, "overflow": 1, "n_error": 2, "done": 3}
assert DONE_FLAGS_SHIFT + CHAIN_FLAG_BITS <= 32


@dataclass(frozen=True)
class Register:
    """One 32-bit CSR word.

    Attributes
    ----------
    name : str
        Register name (LiteX CSR name inside its region).
    offset : int
        Byte offset from the region base (multiple of 4).
    kind : str
        ``ro``, ``rw``, ``wdata`` or ``strobe`` (module docstring).
    fmt : QFormat or None
        Fixed-point format of the value (None: a bit field or raw integer).
    doc : str
        Meaning, units, bit fields.
    width : int
        Significant bits (<= 32); wider values are truncated by the hardware, so the
        driver refuses them.
    reset : int
        Reset value of ``rw`` storage.
    """

    name: str
    offset: int
    kind: str
    fmt: QFormat | None = None
    doc: str = ""
    width: int = 32
    reset: int = 0

    def __post_init__(self):
        if self.offset % 4 or not 0 <= self.offset < CSR_PAGE:
            raise ValueError(f"register {self.name}: bad offset {self.offset:#x}")
        if self.kind not in ("ro", "rw", "wdata", "strobe"):
            raise ValueError(f"register {self.name}: bad kind {self.kind!r}")
        if not 1 <= self.width <= 32:
            raise ValueError(f"register {self.name}: bad width {self.width}")

    @property
    def writable(self) -> bool:
        return self.kind != "ro"


@dataclass(frozen=True)
class Region:
    """A CSR region (LiteX CSR peripheral) or a memory.

    Attributes
    ----------
    name : str
        Region name as in docs/spec.md sec. 7.
    base : int
        Byte address of offset 0.
    registers : tuple of Register
        Registers in address order (empty for a memory).
    size : int
        Bytes decoded (``CSR_PAGE`` for CSR regions).
    litex_name : str
        Name of the region in LiteX's ``csr.csv`` (``identifier_mem`` for
        ``identifier``).
    memory : bool
        True for a RAM (``sram``), which LiteX lists under ``memory_region``.
    listed : bool
        False for a CSR memory (``identifier``): ``csr.csv`` lists its base only.
    """

    name: str
    base: int
    registers: tuple = ()
    size: int = CSR_PAGE
    litex_name: str = ""
    memory: bool = False
    listed: bool = True

    def __post_init__(self):
        offs = [r.offset for r in self.registers]
        if offs != sorted(set(offs)):
            raise ValueError(f"region {self.name}: offsets not strictly increasing")
        if not self.litex_name:
            object.__setattr__(self, "litex_name", self.name)

    def reg(self, name: str) -> Register:
        for r in self.registers:
            if r.name == name:
                return r
        raise KeyError(f"region {self.name!r} has no register {name!r}")

    def addr(self, name: str) -> int:
        """Byte address of register ``name``."""
        return self.base + self.reg(name).offset


@dataclass(frozen=True)
class SocMap:
    """Register map of one SoC top."""

    kind: str
    ident: str
    regions: tuple = field(default=())

    def region(self, name: str) -> Region:
        for r in self.regions:
            if r.name == name:
                return r
        raise KeyError(f"{self.kind} has no region {name!r} "
                       f"(regions: {[r.name for r in self.regions]})")

    def addr(self, region: str, reg: str) -> int:
        """Byte address of ``region.reg``."""
        return self.region(region).addr(reg)

    def csr_regions(self) -> tuple:
        return tuple(r for r in self.regions if not r.memory)

    def flat(self) -> dict:
        """``{"region_reg": byte address}`` for every register (LiteX naming)."""
        return {f"{rg.litex_name}_{r.name}": rg.base + r.offset
                for rg in self.csr_regions() if rg.listed for r in rg.registers}


CONTACT = Region("contact", 0x0000, (
    Register("gap", 0x00, "ro", GAP, "min_gap g*, GAP Q(32,16) mm (0x7FFFFFFF if not valid)"),
    Register("idx", 0x04, "ro", None, "min_idx i* (0xFFFF if not valid)", width=16),
    Register("flags", 0x08, "ro", None,
             "bit 0 valid, 1 overflow, 2 n_error, 3 done (a pass has completed)",
             width=len(CONTACT_FLAG_BITS)),
    Register("magic", 0x0C, "ro", None, f"constant {MAGIC:#010x} ('GCNT')"),
))

CTRL = Region("ctrl", 0x0800, (
    Register("reset", 0x00, "strobe", None,
             "write 1: soft reset of the cores (the contact pass re-runs)", width=1),
    Register("scratch", 0x04, "rw", None, "scratch word", reset=0x1234_5678),
    Register("bus_errors", 0x08, "ro", None, "accesses to unmapped addresses"),
))

#: LiteX ``identifier_mem``: 256 words, one byte of the identifier string each.
IDENT_WORDS = 256
IDENTIFIER = Region("identifier", 0x1000, tuple(
    Register(f"mem{i}", 4 * i, "ro", None, "identifier byte", width=8)
    for i in range(IDENT_WORDS)), litex_name="identifier_mem", listed=False)

TIMER0 = Region("timer0", 0x2000, (
    Register("load", 0x00, "rw", None, "one-shot start value, cycles"),
    Register("reload", 0x04, "rw", None, "periodic reload value, cycles (0: one-shot)"),
    Register("en", 0x08, "rw", None, "1: count down; 0: stop and preload ``load``", width=1),
    Register("update_value", 0x0C, "strobe", None, "write 1: latch the count in value",
             width=1),
    Register("value", 0x10, "ro", None, "count latched by update_value, cycles"),
    Register("ev_status", 0x14, "ro", None, "1 while the count is zero", width=1),
    Register("ev_pending", 0x18, "rw", None,
             "LiteX: zero event pending, write 1 to clear (no CPU, no IRQ; the simulated "
             "SoC keeps plain storage)", width=1),
    Register("ev_enable", 0x1C, "rw", None, "interrupt enable (no CPU: unused)", width=1),
))


#: Result registers shared by the tri_core ``preview`` and the stage-D-only ``hertz`` maps.
_ELLIPSE_REGISTERS = (
    Register("a", 0x18, "ro", SEMI_AXIS, "semi-axis a, SEMI_AXIS Q(32,20) mm"),
    Register("b", 0x1C, "ro", SEMI_AXIS, "semi-axis b, SEMI_AXIS Q(32,20) mm"),
    Register("p_max", 0x20, "ro", PMAX, "peak pressure, PMAX Q(32,8) MPa"),
    Register("k", 0x24, "ro", HF.K_OUT, "ellipticity a/b, K_OUT Q(32,20)"),
)

PREVIEW = Region("preview", 0x1800, (
    Register("wr_rst", 0x00, "strobe", None, "write 1: rewind the gap RAM write pointer",
             width=1),
    Register("wr_data", 0x04, "wdata", STENCIL_GAP,
             f"stencil gap sample, STENCIL_GAP Q(32,21) mm; each write stores one of "
             f"{N_TAPS}"),
    Register("W_load", 0x08, "rw", LOAD, "load W, LOAD Q(32,8) N (captured at go)"),
    Register("go", 0x0C, "strobe", None, "write 1: start the C -> D chain (806 cycles)",
             width=1),
    Register("A", 0x10, "ro", CURVATURE, "fitted A- (stage D B_max), Q(32,20) 1/mm"),
    Register("B", 0x14, "ro", CURVATURE, "fitted B- (stage D A_min), Q(32,20) 1/mm"),
    *_ELLIPSE_REGISTERS,
    Register("done", 0x28, "ro", None,
             f"bit 0 done, bit 1 busy, bits {DONE_FLAGS_SHIFT}.."
             f"{DONE_FLAGS_SHIFT + CHAIN_FLAG_BITS - 1} chain flags word",
             width=DONE_FLAGS_SHIFT + CHAIN_FLAG_BITS),
))

#: Serialized stage D alone (bhseq_core, dual_core): same layout idea as ``preview``.
HERTZ = Region("hertz", 0x1800, (
    Register("A_in", 0x00, "rw", CURVATURE, "half relative curvature, Q(32,20) 1/mm"),
    Register("B_in", 0x04, "rw", CURVATURE, "half relative curvature, Q(32,20) 1/mm"),
    Register("W_load", 0x08, "rw", LOAD, "load W, LOAD Q(32,8) N (captured at go)"),
    Register("go", 0x0C, "strobe", None, "write 1: start stage D (756 cycles)", width=1),
    Register("A", 0x10, "ro", CURVATURE, "B_max = max(A, B), Q(32,20) 1/mm"),
    Register("B", 0x14, "ro", CURVATURE, "A_min = min(A, B), Q(32,20) 1/mm"),
    *_ELLIPSE_REGISTERS,
    Register("done", 0x28, "ro", None,
             f"bit 0 done, bit 1 busy, bits {DONE_FLAGS_SHIFT}.."
             f"{DONE_FLAGS_SHIFT + HERTZ_FLAG_BITS - 1} stage-D flags",
             width=DONE_FLAGS_SHIFT + HERTZ_FLAG_BITS),
))

#: The line chain (line_core): the ``preview`` layout plus the line core's length input,
#: sorted curvatures and mode (module docstring).
LINE = Region("line", 0x1800, (
    *PREVIEW.registers[:3],
    Register("go", 0x0C, "strobe", None,
             f"write 1: start the C -> line-core chain ({CHAIN_LINE_CYCLES} cycles)", width=1),
    Register("A", 0x10, "ro", CURVATURE, "fitted A-, Q(32,20) 1/mm"),
    Register("B", 0x14, "ro", CURVATURE, "fitted B-, Q(32,20) 1/mm"),
    *_ELLIPSE_REGISTERS[:3],
    Register("k", 0x24, "ro", HF.K_OUT, "ellipticity a/b, K_OUT Q(32,20) (elliptic mode; "
                                         "0 in line mode)"),
    Register("done", 0x28, "ro", None,
             f"bit 0 done, bit 1 busy, bits {DONE_FLAGS_SHIFT}.."
             f"{DONE_FLAGS_SHIFT + CHAIN_FLAG_BITS - 1} line chain flags word (line core "
             f"0..7, fit overflow 8..11)",
             width=DONE_FLAGS_SHIFT + CHAIN_FLAG_BITS),
    Register("L_line", 0x2C, "rw", LINE_LENGTH,
             "contact-line length L, LINE_LENGTH Q(32,20) mm (captured at go; from 1 mm: "
             "the host lifts a shorter line)"),
    Register("A_min", 0x30, "ro", CURVATURE,
             "line core's A_min (B- after the fit's zero rule), Q(32,20) 1/mm"),
    Register("B_max", 0x34, "ro", CURVATURE, "line core's B_max, Q(32,20) 1/mm"),
    Register("mode", 0x38, "ro", None, "bit 0: 1 line mode, 0 elliptic (or flagged); "
                                       "bits 1..2: SCALE exponent n", width=3),
))

SRAM = Region("sram", SRAM_BASE, size=SRAM_SIZE, memory=True)

#: Identifier strings (what LiteX's ``identifier_mem`` holds; the driver checks them).
IDENTS = {kind: f"gearcontact {kind}" for kind in
          ("contact_core", "bhseq_core", "dual_core", "tri_core", "line_core")}

SOC_MAPS = {
    "contact_core": SocMap("contact_core", IDENTS["contact_core"],
                           (CONTACT, CTRL, IDENTIFIER, TIMER0)),
    "bhseq_core": SocMap("bhseq_core", IDENTS["bhseq_core"],
                         (CTRL, IDENTIFIER, HERTZ, TIMER0)),
    "dual_core": SocMap("dual_core", IDENTS["dual_core"],
                        (CONTACT, CTRL, IDENTIFIER, HERTZ, TIMER0)),
    "tri_core": SocMap("tri_core", IDENTS["tri_core"],
                       (CONTACT, CTRL, IDENTIFIER, PREVIEW, TIMER0, SRAM)),
    "line_core": SocMap("line_core", IDENTS["line_core"], (CTRL, IDENTIFIER, LINE, TIMER0)),
}
SOC_KINDS = tuple(SOC_MAPS)
#: The SoCs that serve a cylindrical pair: the ones carrying the line chain (the
#: cylindrical twin's ``--backend soc`` replays on ``line_core``, twin.cosim).
CYLINDRICAL_SOC_KINDS = ("line_core",)


def get_map(kind: str) -> SocMap:
    """Register map of SoC ``kind`` (one of :data:`SOC_KINDS`)."""
    try:
        return SOC_MAPS[kind]
    except KeyError:
        from ..validation import InputRangeError
        raise InputRangeError("SoC", kind, f"one of {list(SOC_KINDS)}") from None


def identifier_bytes(ident: str) -> bytes:
    """The ``identifier_mem`` contents: the ASCII string, NUL-terminated."""
    raw = ident.encode("ascii") + b"\0"
    if len(raw) > IDENT_WORDS:
        raise ValueError(f"identifier longer than {IDENT_WORDS - 1} bytes")
    return raw
