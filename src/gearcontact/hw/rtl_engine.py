"""The ``rtl`` preview backend: the Amaranth RTL cores in cycle-accurate simulation.

:class:`RtlEngine` answers the :class:`~gearcontact.preview.engine.PreviewEngine` calls
with the hardware itself: ``hertz`` / ``hertz_batch`` run
:class:`~gearcontact.preview.hertz.rtl.HertzCore` (stage D, 756 cycles) and ``stencil``
runs :class:`~gearcontact.preview.chain_rtl.ChainCore` (C -> D, 806 cycles), under
Verilator when it is installed (compiled once, cached) and otherwise in the Amaranth
simulator. In line mode (``line_length_mm=L``) ``hertz`` / ``hertz_batch`` run
:class:`~gearcontact.preview.hertz.rtl_line.HertzLineCore` (759 cycles; Verilator core
``hertz_line``, the exact form in the Amaranth simulator) and ``stencil`` runs
:class:`~gearcontact.preview.chain_line_rtl.ChainLineCore` (811 cycles, Amaranth
simulator). Inputs are validated and quantized exactly as by the ``golden`` backend, and
the result carries the raw register codes, the flags and ``cycles`` = the cycle count
measured in simulation, so ``rtl`` and ``golden`` results compare equal field by field
except for ``backend``.

The backend is registered in :data:`gearcontact.preview.engine.BACKENDS` by
:mod:`.backends` through a lazy factory: importing it does not import Amaranth or build
anything until ``get_engine("rtl")``.
"""

from __future__ import annotations

import os

import numpy as np

from ..materials import STEEL, Material
from ..validation import InputRangeError
from ..preview import chain
from ..preview.engine import GoldenEngine, PreviewBatch, PreviewResult, elliptic_modes
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM
from ..preview.hertz.golden import HertzCodes, decode_hertz_codes, encode_hertz_inputs
from ..preview.hertz.golden_vec import HertzCodesArray
from ..preview.hertz.line import LineCodes
from ..preview.hertz.line_vec import LineCodesArray
from ..preview.stimulus import Stimulus

__all__ = ["RtlEngine", "default_simulator", "SIMULATOR_ENV"]

#: Environment variable forcing the simulator (``verilator`` or ``amaranth``).
SIMULATOR_ENV = "GEARCONTACT_RTL_SIMULATOR"


def default_simulator() -> str:
    """``$GEARCONTACT_RTL_SIMULATOR`` if set, else ``verilator`` when installed, else
    ``amaranth``."""
    from .verilator import verilator_available
    env = os.environ.get(SIMULATOR_ENV)
    if env:
        return env
    return "verilator" if verilator_available() else "amaranth"


class RtlEngine(GoldenEngine):
    """RTL-simulation backend (same interface and quantization as ``golden``).

    Parameters
    ----------
    material, material2 : Material
        The two bodies (default steel/steel); E' is the constant register code.
    simulator : {"verilator", "amaranth"}, optional
        Default :func:`default_simulator`.
    hertz_form : {"hamrock-brewe", "exact"}
        Stage-D ROM contents: the ``hertz`` / ``chain`` cores, or ``hertz_exact`` /
        ``chain_exact`` (:mod:`gearcontact.hw.harness_cores`).

    Raises
    ------
    gearcontact.hw.verilator.VerilatorNotFound
        ``simulator="verilator"`` without Verilator installed (names the apt package).
    """

    name = "rtl"

    def __init__(self, *, material: Material = STEEL, material2: Material | None = None,
                 simulator: str | None = None, hertz_form: str = DEFAULT_HERTZ_FORM):
        from .harness_cores import SIMULATORS
        super().__init__(material=material, material2=material2, hertz_form=hertz_form)
        suffix = "_exact" if self.hertz_form == "exact" else ""
        self._cores = {"hertz": "hertz" + suffix, "chain": "chain" + suffix,
                       "hertz_line": "hertz_line"}
        self.simulator = simulator or default_simulator()
        if self.simulator not in SIMULATORS:
            raise InputRangeError("simulator", self.simulator, f"one of {list(SIMULATORS)}")
        if self.simulator == "verilator":
            from .verilator import require_verilator
            require_verilator()

    def _simulate(self, core: str, fields: dict):
        """Run vectors (dict of code arrays) on ``core``: (outputs, cycles)."""
        from .harness_cores import get_bench, simulate
        core = self._cores[core]
        n = len(next(iter(fields.values())))
        st = Stimulus(core, {k: np.asarray(v, np.int64) for k, v in fields.items()},
                      ("engine",) * n, 0)
        outs, cycles, *_ = simulate(get_bench(core), st, self.simulator)
        return outs, cycles

    def _simulate_line(self, A, B, W, L, e_prime) -> tuple[LineCodesArray, np.ndarray]:
        """The line core on code arrays (one shape): (codes, cycles)."""
        from ..preview.hertz.rtl_line import LINE_OUTPUT_PORTS, simulate_line_core
        shape = np.shape(A)
        cols = [np.asarray(x, np.int64).ravel() for x in (A, B, W, L, e_prime)]
        if self.hertz_form == DEFAULT_HERTZ_FORM:
            outs, cycles = self._simulate("hertz_line", dict(zip(("A", "B", "W", "L",
                                                                   "e_prime"), cols)))
            return LineCodesArray(**{f: np.asarray(outs[p], np.int64).reshape(shape)
                                     for p, f in LINE_OUTPUT_PORTS.items()}), cycles
        # no Verilator harness of the exact-form line core: Amaranth's simulator
        res, cycles = simulate_line_core(list(zip(*cols)), hertz_form=self.hertz_form)
        return LineCodesArray(**{f: np.array([getattr(r, f) for r in res],
                                             np.int64).reshape(shape)
                                 for f in LINE_OUTPUT_PORTS.values()}), np.asarray(cycles)

    def _line(self, A_minus, B_minus, load_n, line_length_mm) -> PreviewResult:
        w, codes = self.encode_line(A_minus, B_minus, load_n, line_length_mm)
        lca, cycles = self._simulate_line(*([codes[k]] for k in ("A_in", "B_in", "W", "L",
                                                                 "e_prime")))
        lc = LineCodes(**{f: int(getattr(lca, f)[0]) for f in LineCodes.__dataclass_fields__})
        return self._line_result(lc, w, codes, int(cycles[0]))

    def _line_batch(self, A_minus, B_minus, load_n, line_length_mm) -> PreviewBatch:
        c = self.encode_line_batch(A_minus, B_minus, load_n, line_length_mm)
        lca, _ = self._simulate_line(c["A_in"], c["B_in"], c["W"], c["L"], c["e_prime"])
        return self._line_batch_result(lca, c["lift"])

    def _stencil_line(self, gaps_mm, load_n, line_length_mm) -> PreviewResult:
        from ..preview.chain_line_rtl import simulate_chain_line_core
        w, gap_codes, w_c, l_c, lift = self.encode_stencil_line(gaps_mm, load_n,
                                                                 line_length_mm)
        (res,), (cycles,) = simulate_chain_line_core(gap_codes[None, :], [w_c], [l_c],
                                                     e_prime_code=self.e_prime_code,
                                                     hertz_form=self.hertz_form)
        codes = {"W": w_c, "L": l_c, "lift": lift, "e_prime": self.e_prime_code,
                 "A_fit": res.fit.a_minus_code, "B_fit": res.fit.b_minus_code,
                 "flags": res.flags}
        return self._line_result(res.hertz, w, codes, int(cycles), res.flag_names)

    def hertz(self, A_minus, B_minus, load_n, *, line_length_mm=None) -> PreviewResult:
        if line_length_mm is not None:
            return self._line(A_minus, B_minus, load_n, line_length_mm)
        w, codes = self.encode_hertz(A_minus, B_minus, load_n)
        from ..preview.hertz.rtl import OUTPUT_PORTS  # port -> HertzCodes field
        outs, cycles = self._simulate("hertz", {"A": [codes["A_in"]], "B": [codes["B_in"]],
                                                "W": [codes["W"]],
                                                "e_prime": [codes["e_prime"]]})
        hz = HertzCodes(**{f: int(outs[p][0]) for p, f in OUTPUT_PORTS.items()})
        return self._result(hz, w, codes, hz.flag_names, int(cycles[0]))

    def stencil(self, gaps_mm, load_n, *, line_length_mm=None) -> PreviewResult:
        if line_length_mm is not None:
            return self._stencil_line(gaps_mm, load_n, line_length_mm)
        w, gap_codes, w_c = self.encode_stencil(gaps_mm, load_n)
        outs, cycles = self._simulate("chain", {"gaps": gap_codes[None, :], "W": [w_c],
                                                "e_prime": [self.e_prime_code]})
        o = {k: int(v[0]) for k, v in outs.items()}
        flags = o["flags"]
        hz = HertzCodes(o["a"], o["b"], o["p_max"], o["k"], o["b_minus"], o["a_minus"],
                        o["R_x"], o["R_y"], o["alpha"],
                        flags & ((1 << chain.FIT_FLAG_SHIFT) - 1))
        codes = {"W": w_c, "e_prime": self.e_prime_code, "A_fit": o["a_minus"],
                 "B_fit": o["b_minus"], "flags": flags}
        return self._result(hz, w, codes, chain.chain_flag_names(flags), int(cycles[0]))

    def hertz_batch(self, A_minus, B_minus, load_n, *, line_length_mm=None) -> PreviewBatch:
        if line_length_mm is not None:
            return self._line_batch(A_minus, B_minus, load_n, line_length_mm)
        a_c, b_c, w_c, e_c = encode_hertz_inputs(
            np.atleast_1d(np.asarray(A_minus, dtype=float)),
            np.atleast_1d(np.asarray(B_minus, dtype=float)),
            np.atleast_1d(np.asarray(load_n, dtype=float)), e_prime_mpa=self.e_prime_mpa)
        a_c, b_c, w_c = np.broadcast_arrays(a_c, b_c, w_c)
        shape = a_c.shape
        outs, _ = self._simulate("hertz", {"A": a_c.ravel(), "B": b_c.ravel(),
                                           "W": w_c.ravel(),
                                           "e_prime": np.full(a_c.size, e_c)})
        from ..preview.hertz.rtl import OUTPUT_PORTS
        v = decode_hertz_codes(HertzCodesArray(**{f: outs[p].reshape(shape)
                                                  for p, f in OUTPUT_PORTS.items()}))
        return PreviewBatch(self.name, v.a_mm, v.b_mm, v.k, v.p_max_mpa, v.flags,
                            elliptic_modes(v.flags.shape, v.flags))
