"""A simulated SoC behind LiteX's ``litex_server``: the board's host protocol without a board.

``litex_server`` bridges LiteX's ``RemoteClient`` (Etherbone records over TCP) to a board
through a *comm* object (UART, JTAG, UDP, PCIe). :class:`SimComm` is such a comm whose
"board" is the cycle-accurate Amaranth simulation of a gearcontact SoC
(:class:`.driver.SimTransport`), and :func:`serve` runs LiteX's own
``litex.tools.litex_server.RemoteServer`` with it. Everything a host program does
against a board — :class:`.driver.LiteXRemoteTransport`, ``litex_cli``, a user's own
``RemoteClient`` script — then runs unchanged against the simulation: the Etherbone
framing, the server's read merging and its lock are LiteX's, only the last hop differs.
``gearcontact rtl serve`` is the command; the twin's ``soc`` backend takes the address
(``gearcontact twin --backend soc --board HOST:PORT``) for a real board or this server.

References
----------
LiteX ``litex/tools/litex_server.py`` (RemoteServer) and ``litex/tools/remote/
etherbone.py`` (the Etherbone packet format); docs/hardware.md.
"""

from __future__ import annotations

import socket
import threading

from ..validation import InputRangeError
from .driver import LITEX_PIN, DriverError

__all__ = ["SimComm", "serve", "parse_address"]


class SimComm:
    """A LiteX comm (``open``, ``close``, ``read``, ``write``) into a simulated SoC.

    Parameters
    ----------
    kind : str
        SoC kind (:data:`.regmap.SOC_KINDS`).
    e_prime_code : int, optional
        The SoC's baked E' code (Q(32,0), MPa), as for a board build.
    lanes : int
        Gap core lanes.
    """

    def __init__(self, kind: str, *, e_prime_code: int | None = None, lanes: int = 16):
        from .regmap import SOC_KINDS
        if kind not in SOC_KINDS:
            raise InputRangeError("kind", kind, f"one of {list(SOC_KINDS)}")
        self.kind, self.e_prime_code, self.lanes = kind, e_prime_code, lanes
        self.transport = None

    def open(self) -> None:
        from .driver import SimTransport
        if self.transport is None:
            self.transport = SimTransport(self.kind, lanes=self.lanes,
                                          e_prime_code=self.e_prime_code)

    def close(self) -> None:
        if self.transport is not None:
            self.transport.close()
            self.transport = None

    def read(self, addr: int, length: int | None = None, burst: str = "incr"):
        """One word (``length`` None) or a list of ``length`` words, as LiteX's comms."""
        n = 1 if length is None else int(length)
        step = 4 if burst == "incr" else 0
        words = [self.transport.read(addr + step * i) for i in range(n)]
        return words[0] if length is None else words

    def write(self, addr: int, data) -> None:
        """A word or a list of words at consecutive addresses."""
        for i, w in enumerate(data if isinstance(data, (list, tuple)) else [data]):
            self.transport.write(addr + 4 * i, int(w))


def parse_address(text: str, *, field: str = "address") -> tuple[str, int]:
    """``HOST:PORT`` (or ``PORT``, localhost) -> (host, port), with an error naming
    ``field``."""
    host, _, port = text.rpartition(":")
    try:
        p = int(port)
    except ValueError:
        raise InputRangeError(field, text, "HOST:PORT with an integer port") from None
    if not 0 < p < 65536:
        raise InputRangeError(f"{field} port", p, "a TCP port in [1, 65535]")
    return host or "localhost", p


def serve(kind: str, *, host: str = "127.0.0.1", port: int = 1234,
          e_prime_code: int | None = None, lanes: int = 16, on_ready=None) -> None:
    """Serve the simulated SoC ``kind`` on ``host:port`` with LiteX's ``RemoteServer``
    until interrupted (Ctrl-C ends the command).

    ``on_ready()`` (optional) is called once the socket listens and the server thread
    runs: LiteX's own "tcp port" line comes before its ``listen``, so a client that
    connects on it may be refused.

    Raises
    ------
    DriverError
        LiteX missing, or the port cannot be bound.
    """
    try:
        from litex.tools.litex_server import RemoteServer
    except ImportError:
        raise DriverError(f"LiteX is not installed: pip install {LITEX_PIN} "
                          "(or pip install 'gearcontact[board]')") from None
    # RemoteServer binds with SO_REUSEPORT, which lets a second server share a port
    # (clients then land on either): probe without it first
    probe = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        probe.bind((host, int(port)))
    except OSError as exc:
        raise DriverError(f"cannot listen on {host}:{port} ({exc.strerror or exc}): is a "
                          "litex_server or another gearcontact rtl serve running there?"
                          ) from None
    finally:
        probe.close()
    server = RemoteServer(SimComm(kind, e_prime_code=e_prime_code, lanes=lanes),
                          bind_ip=host, bind_port=int(port))
    try:
        server.open()
    except OSError as exc:
        raise DriverError(f"cannot listen on {host}:{port} ({exc})") from None
    try:
        server.start(1)
        if on_ready is not None:
            on_ready()
        threading.Event().wait()
    finally:
        server.close()
