"""Descriptors of the C -> D chains (:class:`.chain_rtl.ChainCore` in both Hertz forms,
:class:`.chain_pipe.ChainPipe` with the pipelined stage D, the line chain
:class:`.chain_line_rtl.ChainLineCore`) and of the combinational C + D core
(:class:`.comb_rtl.CombCore`); see :mod:`.core`."""

from __future__ import annotations

import numpy as np

from .core import CoreDescriptor, HostPath, lazy
from .fit.cores import STENCIL_CONTROL, STENCIL_WRITE, fit_columns
from .hertz.cores import LIFT_OUTPUTS, hertz_columns
from .stimulus import Stimulus

__all__ = ["DESCRIPTORS", "CHAIN_PORTS"]

#: Stage-D outputs of the chain cores (beside the fit registers and the chain flags).
CHAIN_PORTS = ("a", "b", "p_max", "k", "R_x", "R_y", "alpha")


def _chain_cols(hertz, fit_c, fit_a, fit_b, flags) -> dict:
    """Chain/comb output columns: stage-D outputs, the fit registers, the chain flags."""
    h = hertz_columns(hertz)
    cols = {p: h[p] for p in CHAIN_PORTS}
    cols.update(fit_columns(fit_c, fit_a, fit_b, flags))
    return cols


def _chain_ports(st: Stimulus):
    f = st.fields
    return {"W": f["W"], "e_prime": f["e_prime"]}, {"wr_data": f["gaps"]}, None


def _chain_golden(hertz_form: str = "hamrock-brewe"):
    def run(st: Stimulus) -> dict:
        from .chain import chain_golden_batch
        f = st.fields
        res = chain_golden_batch(f["gaps"], f["W"], e_prime_code=f["e_prime"],
                                 hertz_form=hertz_form)
        return _chain_cols(res.hertz, res.fit.c_codes, res.fit.a_minus_codes,
                           res.fit.b_minus_codes, res.flags)
    return run


def _chain_amaranth(module: str, runner: str, **kwargs):
    def run(st: Stimulus):
        import importlib
        fn = getattr(importlib.import_module(f"gearcontact.preview.{module}"), runner)
        f = st.fields
        outs, cycles = [None] * len(st), np.zeros(len(st), np.int64)
        for e in np.unique(f["e_prime"]):          # the runners take one E' per call
            idx = np.flatnonzero(f["e_prime"] == e)
            o, c = fn(f["gaps"][idx], f["W"][idx], e_prime_code=int(e), **kwargs)
            for i, oi, ci in zip(idx, o, c):
                outs[i], cycles[i] = oi, ci
        return _chain_cols([o.hertz for o in outs], [o.fit.c_codes for o in outs],
                           [o.fit.a_minus_code for o in outs],
                           [o.fit.b_minus_code for o in outs], [o.flags for o in outs]), cycles
    return run


def _line_chain_ports(st: Stimulus):
    f = st.fields
    return {"W": f["W"], "e_prime": f["e_prime"], "L": f["L"]}, {"wr_data": f["gaps"]}, None


def _line_chain_cols(fit_c, fit_a, fit_b, fit_flags, line, flags) -> dict:
    """Line-chain output columns: the line core's, the fit registers, the chain flags
    (line-core flags and the fit's overflow bits) and the fit's whole flags word."""
    from .hertz.cores import _line_columns
    cols = fit_columns(fit_c, fit_a, fit_b, flags)
    cols.update({p: v for p, v in _line_columns(line).items() if p != "flags"})
    cols["fit_flags"] = np.asarray(fit_flags, np.int64)
    return cols


def _line_chain_golden(lifted: bool = False):
    """Golden line chain; ``lifted``: the host's path, with its ``lift`` column."""
    def run(st: Stimulus) -> dict:
        from .chain import chain_line_golden_batch, lifted_chain_line_golden_batch
        f = st.fields
        args, kw = (f["gaps"], f["W"], f["L"]), {"e_prime_code": f["e_prime"]}
        res, lift = (lifted_chain_line_golden_batch(*args, **kw) if lifted
                     else (chain_line_golden_batch(*args, **kw), None))
        cols = _line_chain_cols(res.fit.c_codes, res.fit.a_minus_codes,
                                res.fit.b_minus_codes, res.fit.flags, res.hertz, res.flags)
        return cols if lift is None else {**cols, "lift": lift}
    return run


def _line_chain_amaranth(st: Stimulus):
    from .chain_line_rtl import simulate_chain_line_core
    f = st.fields
    outs, cycles = [None] * len(st), np.zeros(len(st), np.int64)
    for e in np.unique(f["e_prime"]):              # the runner takes one E' per call
        idx = np.flatnonzero(f["e_prime"] == e)
        o, c = simulate_chain_line_core(f["gaps"][idx], f["W"][idx], f["L"][idx],
                                        e_prime_code=int(e))
        for i, oi, ci in zip(idx, o, c):
            outs[i], cycles[i] = oi, ci
    return _line_chain_cols([o.fit.c_codes for o in outs], [o.fit.a_minus_code for o in outs],
                            [o.fit.b_minus_code for o in outs], [o.fit.flags for o in outs],
                            [o.hertz for o in outs], [o.flags for o in outs]), cycles


def _line_chain_cycles(st: Stimulus) -> int:
    from .chain import CHAIN_LINE_CYCLES
    return CHAIN_LINE_CYCLES


def _chain_cycles(st: Stimulus) -> int:
    from .hertz.schedule import CHAIN_CYCLES
    return CHAIN_CYCLES


def _pipe_cycles(st: Stimulus) -> int:
    from .chain_pipe import CHAIN_PIPE_CYCLES
    return CHAIN_PIPE_CYCLES


def _comb_cycles(st: Stimulus) -> int:
    from .hertz.schedule import COMB_CYCLES
    return COMB_CYCLES


def _stencil_core(name, module, cls, top, golden, amaranth, cycles, summary, **kw):
    return CoreDescriptor(name, module, lazy(module, cls), top, _chain_ports, golden,
                          amaranth, cycles, control=STENCIL_CONTROL, write=STENCIL_WRITE,
                          stimulus_core="chain", summary=summary, **kw)


DESCRIPTORS = (
    _stencil_core("chain", "chain_rtl", "ChainCore", "chain_core", _chain_golden(),
                  _chain_amaranth("chain_rtl", "simulate_chain_core"), _chain_cycles,
                  "C -> D chain: fit core feeding the serialized stage D"),
    _stencil_core("chain_exact", "chain_rtl", "ChainCore", "chain_exact_core",
                  _chain_golden("exact"),
                  _chain_amaranth("chain_rtl", "simulate_chain_core", hertz_form="exact"),
                  _chain_cycles, "C -> D chain with stage D in hertz_form='exact'",
                  verilog_kwargs={"hertz_form": "exact"}),
    _stencil_core("chain_pipe", "chain_pipe", "ChainPipe", "chain_pipe", _chain_golden(),
                  _chain_amaranth("chain_pipe", "simulate_chain_pipe"), _pipe_cycles,
                  "C -> D chain with the pipelined stage D (hertz_pipe; 142 cycles)"),
    _stencil_core("comb", "comb_rtl", "CombCore", "comb_core", _chain_golden(),
                  _chain_amaranth("comb_rtl", "simulate_comb_core"), _comb_cycles,
                  "combinational C + D variant (array dividers, pipelined)"),
    _stencil_core("comb_exact", "comb_rtl", "CombCore", "comb_exact_core",
                  _chain_golden("exact"),
                  _chain_amaranth("comb_rtl", "simulate_comb_core", hertz_form="exact"),
                  _comb_cycles, "combinational C + D with hertz_form='exact' (58 cycles)",
                  verilog_kwargs={"hertz_form": "exact"}),
    CoreDescriptor("chain_line", "chain_line_rtl", lazy("chain_line_rtl", "ChainLineCore"),
                   "chain_line_core", _line_chain_ports, _line_chain_golden(),
                   _line_chain_amaranth, _line_chain_cycles, control=STENCIL_CONTROL,
                   write=STENCIL_WRITE, stimulus_core="chain_line",
                   host=HostPath(lazy("stimulus_lift", "host_chain_line_stimulus"),
                                 _line_chain_golden(lifted=True), LIFT_OUTPUTS),
                   summary="C -> line core chain: fit core feeding the line core of stage D "
                           "(811 cycles)"),
)
