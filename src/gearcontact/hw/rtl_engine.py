"""The ``rtl`` preview backend: the Amaranth RTL cores in cycle-accurate simulation.

:class:`RtlEngine` answers the :class:`~gearcontact.preview.engine.PreviewEngine` calls
with the hardware itself: ``hertz`` / ``hertz_batch`` run
:class:`~gearcontact.preview.hertz.rtl.HertzCore` (stage D, 756 cycles) and ``stencil``
runs :class:`~gearcontact.preview.chain_rtl.ChainCore` (C -> D, 806 cycles), under
Verilator when it is installed (compiled once, cached) and otherwise in the Amaranth
simulator. Inputs are validated and quantized exactly as by the ``golden`` backend, and
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
from ..preview.engine import GoldenEngine, PreviewBatch, PreviewResult
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM
from ..preview.hertz.golden import HertzCodes, decode_hertz_codes, encode_hertz_inputs
from ..preview.hertz.golden_vec import HertzCodesArray
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
        self._cores = {"hertz": "hertz" + suffix, "chain": "chain" + suffix}
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

    def hertz(self, A_minus, B_minus, load_n) -> PreviewResult:
        w, codes = self.encode_hertz(A_minus, B_minus, load_n)
        from ..preview.hertz.rtl import OUTPUT_PORTS  # port -> HertzCodes field
        outs, cycles = self._simulate("hertz", {"A": [codes["A_in"]], "B": [codes["B_in"]],
                                                "W": [codes["W"]],
                                                "e_prime": [codes["e_prime"]]})
        hz = HertzCodes(**{f: int(outs[p][0]) for p, f in OUTPUT_PORTS.items()})
        return self._result(hz, w, codes, hz.flag_names, int(cycles[0]))

    def stencil(self, gaps_mm, load_n) -> PreviewResult:
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

    def hertz_batch(self, A_minus, B_minus, load_n) -> PreviewBatch:
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
        return PreviewBatch(self.name, v.a_mm, v.b_mm, v.k, v.p_max_mpa, v.flags)
