"""Host driver of the SoCs: the register protocol over an exchangeable transport.

A transport moves 32-bit words at byte addresses (:class:`Transport`):

* :class:`SimTransport` — the Amaranth simulation of a :class:`.soc.SocTop`, bus
  accesses cycle by cycle (one edge each), with the cycle count and the
  go-to-done probe;
* :class:`LiteXRemoteTransport` — LiteX's ``RemoteClient`` talking to
  ``litex_server`` (jtagbone or etherbone bridge) for a real board.

:class:`PreviewDriver` speaks the tri_core protocol (docs/spec.md sec. 7, map in
:mod:`.regmap`)::

    identify   contact.magic == MAGIC and identifier_mem == "gearcontact tri_core"
    reset      preview.wr_rst <- 1            (rewind the gap RAM write pointer)
    49 writes  preview.wr_data <- g_i         (STENCIL_GAP Q(32,21))
    load       preview.W_load <- W            (LOAD Q(32,8))
    go         preview.go <- 1
    poll       preview.done bit 0 (timeout: DoneTimeout)
    read       A, B, a, b, p_max, k; flags = done[16..27]

:class:`HertzDriver` does the same for stage D alone (bhseq_core, dual_core).
The preview engine backend ``rtl-soc`` that runs the simulated SoCs through these
drivers is :class:`gearcontact.hw.soc_engine.SocEngine`; Amaranth is imported only when
a simulation is created.
"""

from __future__ import annotations

import queue
import threading
import time
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

from ..deprecation import moved_names
from ..preview.fit.pinv import N_TAPS
from ..preview.hertz import formats as HF
from ..contract.qformat import (CURVATURE, GAP, LOAD, PMAX, SEMI_AXIS, STENCIL_GAP,
                                QFormat)
from ..validation import InputRangeError
from .regmap import (
    CONTACT_FLAG_BITS,
    DONE_FLAGS_SHIFT,
    IDENT_WORDS,
    MAGIC,
    SocMap,
    get_map,
)

__all__ = [
    "LITEX_PIN",
    "ContactDriver",
    "ContactReadback",
    "DoneTimeout",
    "DriverError",
    "HertzDriver",
    "LiteXRemoteTransport",
    "PreviewDriver",
    "PreviewReadback",
    "SimTransport",
    "Transport",
    "WrongIdentifier",
]

#: pip requirement of the board flow (pyproject optional extra ``board``).
LITEX_PIN = "litex==2024.12 migen==0.10.0"


class DriverError(RuntimeError):
    """A register-protocol failure (message names the register and the value)."""


class WrongIdentifier(DriverError):
    """The bus does not reach the expected SoC (magic or identifier mismatch)."""


class DoneTimeout(DriverError):
    """``done`` did not rise within the poll limit."""


@runtime_checkable
class Transport(Protocol):
    """Word access at byte addresses."""

    def read(self, addr: int) -> int:
        """Read the 32-bit word at byte address ``addr``."""
        ...

    def write(self, addr: int, value: int) -> None:
        """Write the 32-bit word ``value`` at byte address ``addr``."""
        ...

    def close(self) -> None:
        ...


# ---------------------------------------------------------------------------------
# transports
# ---------------------------------------------------------------------------------
class SimTransport:
    """Transport into the Amaranth simulation of :class:`.soc.SocTop` (``kind``).

    The simulator runs in a worker thread; each :meth:`read` / :meth:`write` is one bus
    access (strobe edge + acknowledge, one clock edge), so :attr:`cycles` counts clock
    edges exactly as the hardware would see them.

    Parameters
    ----------
    kind : str
        SoC kind (default ``tri_core``).
    lanes, e_prime_code, hertz_form : keyword-only
        SoC parameters (:class:`.soc.SocTop`).
    reply_timeout : float, keyword-only
        Seconds to wait for the simulator thread before raising DriverError.
    """

    def __init__(self, kind: str = "tri_core", *, lanes: int = 16,
                 e_prime_code: int | None = None, hertz_form: str = HF.DEFAULT_HERTZ_FORM,
                 reply_timeout: float = 300.0):
        from amaranth.sim import Simulator

        from ..preview.stimulus import STEEL_E_PRIME_CODE
        from .soc import SocTop
        self.kind = kind
        self.soc_map = get_map(kind)
        e = STEEL_E_PRIME_CODE if e_prime_code is None else int(e_prime_code)
        self.e_prime_code = e
        self.top = SocTop(kind, lanes=lanes, e_prime_code=e, hertz_form=hertz_form)
        self.reply_timeout = reply_timeout
        self.cycles = 0
        self._req: queue.Queue = queue.Queue()
        self._rep: queue.Queue = queue.Queue()
        self._closed = False
        sim = Simulator(self.top)
        sim.add_clock(1e-8)
        sim.add_testbench(self._bench)
        self._thread = threading.Thread(target=self._run, args=(sim,), daemon=True,
                                        name=f"sim-{kind}")
        self._thread.start()

    def _run(self, sim):
        try:
            sim.run()
        except BaseException as exc:  # noqa: BLE001 -- re-raised in the caller's thread
            self._rep.put(("err", exc))

    async def _bench(self, ctx):
        bus = self.top.bus
        while True:
            op, *args = self._req.get()
            try:
                if op == "close":
                    return
                if op == "idle":
                    await ctx.tick().repeat(args[0])
                    self.cycles += args[0]
                    self._rep.put(("ok", None))
                elif op == "probe":
                    self._rep.put(("ok", ctx.get(self.top.probe_cycles)))
                else:
                    ctx.set(bus.adr, args[0])
                    ctx.set(bus.we if op == "w" else bus.re, 1)
                    if op == "w":
                        ctx.set(bus.dat_w, args[1])
                    await ctx.tick()
                    ctx.set(bus.we, 0)
                    ctx.set(bus.re, 0)
                    self.cycles += 1
                    if not ctx.get(bus.ack):
                        raise DriverError(f"no bus acknowledge at {args[0]:#x}")
                    self._rep.put(("ok", ctx.get(bus.dat_r) if op == "r" else None))
            except Exception as exc:  # noqa: BLE001 -- re-raised in the caller's thread
                self._rep.put(("err", exc))

    def _call(self, *req):
        if self._closed:
            raise DriverError("the simulation transport is closed")
        self._req.put(req)
        try:
            status, value = self._rep.get(timeout=self.reply_timeout)
        except queue.Empty:
            raise DriverError(f"simulator did not answer {req[0]!r} within "
                              f"{self.reply_timeout} s") from None
        if status == "err":
            raise value
        return value

    @staticmethod
    def _check_addr(addr) -> int:
        if isinstance(addr, bool) or not isinstance(addr, int) or not 0 <= addr < 1 << 32 \
                or addr % 4:
            raise InputRangeError("bus address", addr, "a word-aligned 32-bit byte address")
        return addr

    def read(self, addr: int) -> int:
        return self._call("r", self._check_addr(addr))

    def write(self, addr: int, value: int) -> None:
        if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < 1 << 32:
            raise InputRangeError("bus word", value, "an integer in [0, 2^32)")
        self._call("w", self._check_addr(addr), value)

    def idle(self, n: int) -> None:
        """Let ``n`` clock edges pass without a bus access."""
        self._call("idle", int(n))

    def probe_cycles(self) -> int:
        """Edges from the last accepted go to done (:class:`.soc.SocDatapath`)."""
        return self._call("probe")

    def close(self) -> None:
        if not self._closed:
            self._req.put(("close",))
            self._closed = True
            self._thread.join(timeout=10)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class LiteXRemoteTransport:
    """Transport through LiteX's ``RemoteClient`` (``litex_server`` on the host).

    Start the server first, e.g. ``litex_server --jtag --jtag-config=<openocd cfg>``
    (jtagbone) or ``litex_server --udp --udp-ip=<board ip>`` (etherbone).

    Parameters
    ----------
    host, port : keyword-only
        ``litex_server`` address (default localhost:1234).
    csr_csv : path, keyword-only, optional
        The board's ``csr.csv`` (from ``gearcontact rtl soc``), for RemoteClient's
        register names; byte addresses from :mod:`.regmap` are used either way.
    """

    def __init__(self, *, host: str = "localhost", port: int = 1234,
                 csr_csv: str | None = None, debug: bool = False):
        try:
            from litex import RemoteClient
        except ImportError:
            raise DriverError(f"LiteX is not installed: pip install {LITEX_PIN} "
                              "(or pip install 'gearcontact[board]')") from None
        if isinstance(port, bool) or not isinstance(port, int) or not 0 < port < 65536:
            raise InputRangeError("port", port, "a TCP port in [1, 65535]")
        self._client = RemoteClient(host=host, port=port, csr_csv=csr_csv, debug=debug)
        try:
            self._client.open()
        except OSError as exc:
            raise DriverError(f"cannot reach litex_server at {host}:{port} ({exc}); start "
                              "it first: 'litex_server --jtag' (jtagbone) for a board, "
                              "'gearcontact rtl serve' for the simulated SoC") from None

    def read(self, addr: int) -> int:
        return int(self._client.read(addr))

    def write(self, addr: int, value: int) -> None:
        self._client.write(addr, value)

    def close(self) -> None:
        self._client.close()


# ---------------------------------------------------------------------------------
# drivers
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class PreviewReadback:
    """Codes read from the ``preview`` (or ``hertz``) region after done.

    Attributes
    ----------
    A, B : int
        A- and B- (stage D's B_max and A_min), CURVATURE Q(32,20) 1/mm.
    a, b : int
        Semi-axes, SEMI_AXIS Q(32,20) mm.
    p_max : int
        Peak pressure, PMAX Q(32,8) MPa.
    k : int
        Ellipticity, K_OUT Q(32,20).
    flags : int
        Chain flags word (tri_core) or stage-D flags (bhseq), 0 = valid.
    cycles : int or None
        Edges from go to done when the transport can measure them (simulation).
    """

    A: int
    B: int
    a: int
    b: int
    p_max: int
    k: int
    flags: int
    cycles: int | None = None

    @classmethod
    def from_golden(cls, golden) -> PreviewReadback:
        """Project a golden :class:`~gearcontact.preview.chain.ChainCodes` (or
        :class:`~gearcontact.preview.hertz.golden.HertzCodes`) onto the readback."""
        hz = getattr(golden, "hertz", golden)
        return cls(hz.B_max_code, hz.A_min_code, hz.a_code, hz.b_code, hz.p_max_code,
                   hz.k_code, golden.flags, getattr(golden, "cycles", None))


@dataclass(frozen=True)
class ContactReadback:
    """The ``contact`` region: gap (GAP Q(32,16) mm), idx, flag bits."""

    gap: int
    idx: int
    valid: bool
    overflow: bool
    n_error: bool
    done: bool


_READ_FORMATS = {"A": CURVATURE, "B": CURVATURE, "a": SEMI_AXIS, "b": SEMI_AXIS,
                 "p_max": PMAX, "k": HF.K_OUT}


class _Driver:
    region = ""

    def __init__(self, transport: Transport, *, kind: str, check_identity: bool = True,
                 max_polls: int = 100_000, timeout_s: float | None = None):
        if not isinstance(transport, Transport):
            raise DriverError(f"{transport!r} is not a transport (read/write/close)")
        self.t = transport
        self.map: SocMap = get_map(kind)
        self.max_polls = int(max_polls)
        self.timeout_s = None if timeout_s is None else float(timeout_s)
        self._reg = self.map.region(self.region)
        if check_identity:
            self.identify()

    def addr(self, reg: str) -> int:
        return self._reg.addr(reg)

    def read_identifier(self) -> str:
        """The identifier string (``identifier_mem`` bytes up to NUL)."""
        base = self.map.region("identifier").base
        out = bytearray()
        for i in range(IDENT_WORDS):
            c = self.t.read(base + 4 * i) & 0xFF
            if c == 0:
                break
            out.append(c)
        return out.decode("ascii", errors="replace")

    def identify(self) -> str:
        """Check ``contact.magic`` (when mapped) and the identifier; return it."""
        if "contact" in [r.name for r in self.map.regions]:
            magic = self.t.read(self.map.addr("contact", "magic"))
            if magic != MAGIC:
                raise WrongIdentifier(f"contact.magic reads {magic:#010x}, expected "
                                      f"{MAGIC:#010x}: the bus does not reach a "
                                      f"gearcontact {self.map.kind}")
        ident = self.read_identifier()
        if ident != self.map.ident:
            raise WrongIdentifier(f"identifier reads {ident!r}, expected {self.map.ident!r}")
        return ident

    @staticmethod
    def _bits(code, fmt: QFormat, field: str) -> int:
        """Register word of ``code``; FixedPointOverflow if it does not fit ``fmt``."""
        if isinstance(code, bool) or not hasattr(code, "__index__"):
            raise InputRangeError(field, code, f"an integer {fmt} register code")
        return fmt.to_bits(fmt.check(int(code), field=field))

    def _write(self, reg: str, code: int, fmt: QFormat, field: str):
        self.t.write(self.addr(reg), self._bits(code, fmt, field))

    def go(self) -> None:
        self.t.write(self.addr("go"), 1)

    def wait_done(self) -> int:
        """Poll ``done`` until bit 0 is set; return the status word."""
        t_end = None if self.timeout_s is None else time.monotonic() + self.timeout_s
        for _ in range(self.max_polls):
            st = self.t.read(self.addr("done"))
            if st & 1:
                return st
            if t_end is not None and time.monotonic() > t_end:
                break
        raise DoneTimeout(f"{self.map.kind}: {self.region}.done stayed 0 after "
                          f"{self.max_polls} polls" + (f" / {self.timeout_s} s" if t_end else ""))

    def read_results(self, status: int | None = None) -> PreviewReadback:
        """A, B, a, b, p_max, k and the flags from the done word."""
        if status is None:
            status = self.t.read(self.addr("done"))
        vals = {r: f.from_bits(self.t.read(self.addr(r))) for r, f in _READ_FORMATS.items()}
        probe = getattr(self.t, "probe_cycles", None)
        return PreviewReadback(**vals, flags=status >> DONE_FLAGS_SHIFT,
                               cycles=probe() if probe else None)

    def read_contact(self) -> ContactReadback:
        """The ``contact`` readback (stage A/B pass)."""
        c = self.map.region("contact")
        gap = GAP.from_bits(self.t.read(c.addr("gap")))
        idx = self.t.read(c.addr("idx")) & 0xFFFF
        fl = self.t.read(c.addr("flags"))
        bits = {k: bool(fl >> b & 1) for k, b in CONTACT_FLAG_BITS.items()}
        return ContactReadback(gap, idx, **bits)


class PreviewDriver(_Driver):
    """tri_core C -> D protocol (module docstring).

    Parameters
    ----------
    transport : Transport
        Where the registers live.
    check_identity : bool, keyword-only
        Verify magic and identifier on construction (WrongIdentifier).
    max_polls, timeout_s : keyword-only
        Give up waiting for done (DoneTimeout) after this many reads, or after this many
        seconds of wall time (default None: reads only — a simulation under load is
        slow in wall time but exact in reads; 806 cycles need about 806 reads).
    """

    region = "preview"
    kind = "tri_core"

    def __init__(self, transport: Transport, **kw):
        super().__init__(transport, kind=self.kind, **kw)

    def reset(self) -> None:
        """Rewind the gap RAM write pointer (``wr_rst``)."""
        self.t.write(self.addr("wr_rst"), 1)

    def write_stencil(self, gap_codes) -> None:
        """Reset the pointer and write the 49 STENCIL_GAP Q(32,21) codes."""
        codes = list(gap_codes)
        if len(codes) != N_TAPS:
            raise InputRangeError("stencil length", len(codes),
                                  f"exactly {N_TAPS} gap samples (STENCIL_GAP "
                                  f"{STENCIL_GAP} codes)")
        words = [self._bits(c, STENCIL_GAP, f"gap_codes[{i}]") for i, c in enumerate(codes)]
        self.reset()
        for w in words:
            self.t.write(self.addr("wr_data"), w)

    def set_load(self, W_code: int) -> None:
        """``W_load`` <- LOAD Q(32,8) code."""
        self._write("W_load", W_code, LOAD, "W_code")

    def run(self, gap_codes, W_code: int) -> PreviewReadback:
        """Full protocol on one stencil: reset, 49 writes, load, go, poll, read."""
        self.write_stencil(gap_codes)
        self.set_load(W_code)
        self.go()
        return self.read_results(self.wait_done())


class ContactDriver(_Driver):
    """Stage A/B readback (``contact`` region) of any SoC that has one."""

    region = "contact"

    def __init__(self, transport: Transport, *, kind: str = "contact_core", **kw):
        if "contact" not in [r.name for r in get_map(kind).regions]:
            raise InputRangeError("SoC", kind, "a SoC with a contact region")
        super().__init__(transport, kind=kind, **kw)


class HertzDriver(_Driver):
    """Stage-D protocol of bhseq_core / dual_core (``hertz`` region)."""

    region = "hertz"

    def __init__(self, transport: Transport, *, kind: str = "bhseq_core", **kw):
        if kind not in ("bhseq_core", "dual_core"):
            raise InputRangeError("SoC", kind, "bhseq_core or dual_core")
        super().__init__(transport, kind=kind, **kw)

    def run(self, A_code: int, B_code: int, W_code: int) -> PreviewReadback:
        """Write A, B, W, go, poll, read."""
        self._write("A_in", A_code, CURVATURE, "A_code")
        self._write("B_in", B_code, CURVATURE, "B_code")
        self._write("W_load", W_code, LOAD, "W_code")
        self.go()
        return self.read_results(self.wait_done())


# the rtl-soc preview backend, moved to .soc_engine (one release)
__getattr__ = moved_names(__name__, {"SocEngine": "gearcontact.hw.soc_engine:SocEngine"})
