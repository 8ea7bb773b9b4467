"""Host driver of the ``line_core`` SoC: the line chain of a cylindrical pair over the
register map (:mod:`.regmap`, region ``line``; the SoC: :mod:`.soc`).

The protocol is the tri_core's (:class:`.driver.PreviewDriver`) with the contact-line
length written beside the load and the line core's registers read back::

    identify   identifier_mem == "gearcontact line_core"
    reset      line.wr_rst <- 1              (rewind the gap RAM write pointer)
    49 writes  line.wr_data <- g_i           (STENCIL_GAP Q(32,21) mm)
    load       line.W_load <- W              (LOAD Q(32,8) N)
    length     line.L_line <- L              (LINE_LENGTH Q(32,20) mm)
    go         line.go <- 1                  (811 cycles to done)
    poll       line.done bit 0
    read       A, B (the fit's A-, B-), a, b, p_max, k, A_min, B_max, mode;
               flags = done[16..27] (line core 0..7, fit overflow 8..11)

The core answers lines from 1 mm (LINE_LENGTH's envelope); a shorter line is the host's
to lift (:func:`gearcontact.preview.hertz.line.length_lift`: ``2^s W, 2^s L``, undone by
:func:`~gearcontact.preview.hertz.line.unlift_line`). The twin traces the lifted codes
and replays them through :meth:`LineDriver.run` (:func:`gearcontact.twin.cosim.
replay_on_soc`); the ``rtl-soc`` preview backend lifts with the golden engine's encoder
(:meth:`gearcontact.hw.soc_engine.SocEngine.stencil`). The software model of the readback
is :meth:`LineReadback.from_golden` of :func:`gearcontact.preview.chain.chain_line_golden`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from ..contract.qformat import CURVATURE, LOAD
from ..preview.chain import FIT_FLAG_SHIFT
from ..preview.hertz.line import LINE_LENGTH, LineCodes
from .driver import PreviewDriver, PreviewReadback

__all__ = ["LineDriver", "LineReadback"]


@dataclass(frozen=True, kw_only=True)
class LineReadback(PreviewReadback):
    """Codes read from the ``line`` region after done: :class:`.driver.PreviewReadback`'s
    (``A``, ``B`` the fit's A-, B-; ``a``, ``b`` the semi-axes or, in line mode, the
    half-length L/2 and half-width; ``k`` 0 in line mode; ``flags`` the line chain's
    word, :mod:`gearcontact.preview.chain`) and the line core's own.

    Attributes
    ----------
    A_min, B_max : int
        The line core's sorted curvatures (B- after the fit's zero rule), CURVATURE
        Q(32,20) 1/mm.
    mode : int
        1 line mode, 0 elliptic (or flagged).
    scale : int
        The line core's SCALE exponent n (curvatures scaled by 8^n), 0..3.
    """

    A_min: int
    B_max: int
    mode: int
    scale: int

    @classmethod
    def from_golden(cls, golden) -> LineReadback:
        """The readback the golden model predicts: a :class:`~gearcontact.preview.chain.
        ChainLineCodes` projected onto the registers."""
        lc, fit = golden.hertz, golden.fit
        return cls(fit.a_minus_code, fit.b_minus_code, lc.a_code, lc.b_code, lc.p_max_code,
                   lc.k_code, golden.flags, golden.cycles, A_min=lc.A_min_code,
                   B_max=lc.B_max_code, mode=lc.mode, scale=lc.scale)

    def line_codes(self) -> LineCodes:
        """The line core's outputs as :class:`~gearcontact.preview.hertz.line.LineCodes`
        (its flags: the word's line-core bits, below the fit's)."""
        return LineCodes(self.a, self.b, self.p_max, self.k, self.A_min, self.B_max,
                         self.mode, self.scale, self.flags & ((1 << FIT_FLAG_SHIFT) - 1))

    def trace_row(self) -> tuple:
        """``(flags, a, b, p_max, k, A_min, B_max, mode)``: the columns the twin's replay
        compares (:func:`gearcontact.twin.cosim.replay_on_soc`)."""
        return (self.flags, self.a, self.b, self.p_max, self.k, self.A_min, self.B_max,
                self.mode)


class LineDriver(PreviewDriver):
    """The line_core protocol (module docstring): :class:`.driver.PreviewDriver`'s gap
    RAM writes, load and go on the ``line`` region, with the length and the line core's
    readback.

    Parameters
    ----------
    transport : Transport
        Where the registers live (:class:`.driver.SimTransport` of ``"line_core"``, or
        :class:`.driver.LiteXRemoteTransport`).
    check_identity, max_polls, timeout_s : keyword-only
        As :class:`.driver.PreviewDriver` (811 cycles need about 811 reads).
    """

    region = "line"
    kind = "line_core"

    def set_length(self, L_code: int) -> None:
        """``L_line`` <- LINE_LENGTH Q(32,20) code (mm)."""
        self._write("L_line", L_code, LINE_LENGTH, "L_code")

    def read_results(self, status: int | None = None) -> LineReadback:
        """A, B, a, b, p_max, k, A_min, B_max, mode and the flags of the done word."""
        base = super().read_results(status)
        cur = {r: CURVATURE.from_bits(self.t.read(self.addr(r))) for r in ("A_min", "B_max")}
        mode = self.t.read(self.addr("mode"))
        return LineReadback(**asdict(base), **cur, mode=mode & 1, scale=mode >> 1 & 3)

    def run(self, gap_codes, W_code: int, L_code: int) -> LineReadback:
        """Full protocol on one stencil: reset, 49 writes, load, length, go, poll, read.
        Every code is checked against its register's format before the first write."""
        self._bits(L_code, LINE_LENGTH, "L_code")
        self._bits(W_code, LOAD, "W_code")
        self.write_stencil(gap_codes)
        self.set_load(W_code)
        self.set_length(L_code)
        self.go()
        return self.read_results(self.wait_done())
