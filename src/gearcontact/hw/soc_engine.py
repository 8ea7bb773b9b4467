"""The ``rtl-soc`` preview backend: the simulated SoCs behind the host drivers.

:class:`SocEngine` answers the :class:`~gearcontact.preview.engine.PreviewEngine` calls
with the register values the drivers read back from the Amaranth simulation of the SoC
(:class:`.driver.SimTransport`): stencils on ``tri_core`` (:class:`.driver.
PreviewDriver`), stage D on ``bhseq_core`` (:class:`.driver.HertzDriver`) and a
stencil in line mode (``line_length_mm``) on ``line_core``
(:class:`.line_driver.LineDriver`), a line below the core's 1 mm on the host's lift.
Registered by :mod:`.backends`.
"""

from __future__ import annotations

from ..preview.engine import GoldenEngine, PreviewBatch
from ..preview.hertz import formats as HF
from ..validation import InputRangeError
from .driver import HertzDriver, PreviewDriver, PreviewReadback, SimTransport
from .line_driver import LineDriver

__all__ = ["SocEngine"]

#: The driver of each SoC kind the backend runs.
_DRIVERS = {"tri_core": PreviewDriver, "line_core": LineDriver, "bhseq_core": HertzDriver}


class SocEngine(GoldenEngine):
    """Preview backend ``rtl-soc``: the golden model's quantization, evaluated by the
    simulated SoCs through the register drivers (tri_core for stencils, bhseq_core
    for stage D, line_core for stencils in line mode). Results are the values read back from the registers (decoded from
    their Q formats), their flags word and the measured cycles; nothing is taken from
    the golden model. Both Hertz forms (``hertz_form`` sets the tables of the simulated
    SoC's stage D). Registered by :mod:`.backends`."""

    name = "rtl-soc"

    def __init__(self, **kw):
        super().__init__(**kw)
        self._drivers: dict = {}

    def _driver(self, kind):
        if kind not in self._drivers:
            t = SimTransport(kind, e_prime_code=self.e_prime_code, hertz_form=self.hertz_form)
            self._drivers[kind] = _DRIVERS[kind](t)
        return self._drivers[kind]

    def close(self) -> None:
        for d in self._drivers.values():
            d.t.close()
        self._drivers.clear()

    def _from_readback(self, rb: PreviewReadback, load_n: float, codes: dict,
                       hertz_flags: int, flag_names: tuple):
        """PreviewResult of the register codes: A- / B- are stage D's B_max / A_min; the
        SoC maps have no R_x, R_y, alpha registers (their codes are not reported)."""
        from ..preview.hertz.golden import HertzCodes
        hz = HertzCodes(a_code=rb.a, b_code=rb.b, p_max_code=rb.p_max, k_code=rb.k,
                        A_min_code=rb.B, B_max_code=rb.A, R_x_code=0, R_y_code=0,
                        alpha_code=0, flags=hertz_flags)
        return self._result(hz, load_n, dict(codes, flags=rb.flags), flag_names, rb.cycles)

    @staticmethod
    def _no_line_core(line_length_mm) -> None:
        """Stage D alone has no line core on a SoC (line_core carries it behind stage C):
        line mode is refused there, named."""
        if line_length_mm is not None:
            raise InputRangeError("line_length_mm (backend rtl-soc, stage D alone)",
                                  line_length_mm, "None: the line core sits behind stage C "
                                  "on the line_core SoC (use stencil(..., line_length_mm=L)"
                                  ", or the backends golden or rtl)")

    def _stencil_line(self, gaps_mm, load_n, line_length_mm):
        """The line chain through :class:`.line_driver.LineDriver` on the line_core SoC, a
        line below 1 mm on the host's lift (the golden encoder's, undone on the
        readback's line-core codes)."""
        from ..preview.chain import chain_flag_names
        w, gap_codes, w_c, l_c, lift = self.encode_stencil_line(gaps_mm, load_n,
                                                                 line_length_mm)
        rb = self._driver("line_core").run([int(x) for x in gap_codes], w_c, l_c)
        codes = {"W": w_c, "L": l_c, "lift": lift, "e_prime": self.e_prime_code,
                 "A_fit": rb.A, "B_fit": rb.B, "flags": rb.flags}
        return self._line_result(rb.line_codes(), w, codes, rb.cycles,
                                 chain_flag_names(rb.flags, line=True))

    def stencil(self, gaps_mm, load_n, *, line_length_mm=None):
        from ..preview.chain import FIT_FLAG_SHIFT, chain_flag_names
        if line_length_mm is not None:
            return self._stencil_line(gaps_mm, load_n, line_length_mm)
        w, gap_codes, w_c = self.encode_stencil(gaps_mm, load_n)
        rb = self._driver("tri_core").run([int(x) for x in gap_codes], w_c)
        codes = {"W": w_c, "e_prime": self.e_prime_code, "A_fit": rb.A, "B_fit": rb.B}
        return self._from_readback(rb, w, codes, rb.flags & ((1 << FIT_FLAG_SHIFT) - 1),
                                   chain_flag_names(rb.flags))

    def hertz(self, A_minus, B_minus, load_n, *, line_length_mm=None):
        self._no_line_core(line_length_mm)
        w, codes = self.encode_hertz(A_minus, B_minus, load_n)
        rb = self._driver("bhseq_core").run(codes["A_in"], codes["B_in"], codes["W"])
        return self._from_readback(rb, w, codes, rb.flags, HF.flag_names(rb.flags))

    def hertz_batch(self, A_minus, B_minus, load_n, *, line_length_mm=None) -> PreviewBatch:
        import numpy as np

        from ..preview.engine import elliptic_modes
        self._no_line_core(line_length_mm)
        A, B, W = np.broadcast_arrays(np.asarray(A_minus, float), np.asarray(B_minus, float),
                                      np.asarray(load_n, float))
        res = [self.hertz(a, b, w) for a, b, w in zip(A.ravel(), B.ravel(), W.ravel())]
        shape = A.shape

        def col(f):
            return np.array([f(r) for r in res]).reshape(shape)
        return PreviewBatch(self.name, col(lambda r: r.a_mm), col(lambda r: r.b_mm),
                            col(lambda r: r.k), col(lambda r: r.p_max_mpa),
                            flags := col(lambda r: r.codes["flags"]).astype(np.int64),
                            elliptic_modes(shape, flags))
