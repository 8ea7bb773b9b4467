"""Descriptors of the stage A/B gap kernel (:class:`.rtl.GapCore`, L = 16 lanes): the
published netlist and the 15-DSP ``lean`` variant. See :mod:`gearcontact.preview.core`.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from ..core import CoreDescriptor, WriteNames, lazy
from ..stimulus import Stimulus

__all__ = ["DESCRIPTORS", "GAP_LANES"]

#: Lanes of the gap core under test and export (samples per pass: ``n_samples``).
GAP_LANES = 16
_GAP_MAX = 16 * GAP_LANES


def _gap_ports(st: Stimulus):
    f = st.fields
    n, N = f["g"].shape[:2]
    inputs = {"r": f["r"].reshape(n, 9), "t": f["t"], "p": f["p"], "tau2": f["tau2"],
              "n_samples": np.full(n, N, np.int64)}
    return inputs, {"w_g": f["g"], "w_n": f["nrm"]}, None


def _gap_golden(st: Stimulus, variant: str = "published") -> dict:
    from .fast import gap_golden_batch
    f = st.fields
    n = len(st)
    cols = {k: np.empty(n, np.int64) for k in ("gap", "idx", "valid", "overflow")}
    # one batch call per run of consecutive vectors sharing samples and gate
    same = np.zeros(n, bool)
    if n > 1:
        same[1:] = ((f["g"][1:] == f["g"][:-1]).all(axis=(1, 2))
                    & (f["nrm"][1:] == f["nrm"][:-1]).all(axis=(1, 2))
                    & (f["tau2"][1:] == f["tau2"][:-1]))
    starts = np.flatnonzero(~same).tolist() + [n]
    for a, b in zip(starts[:-1], starts[1:]):
        o = gap_golden_batch(f["r"][a:b], f["t"][a:b], f["p"][a:b], f["g"][a], f["nrm"][a],
                             int(f["tau2"][a]), lanes=GAP_LANES, variant=variant)
        cols["gap"][a:b], cols["idx"][a:b] = o.min_gap_code, o.min_idx
        cols["valid"][a:b], cols["overflow"][a:b] = o.valid, o.overflow
    return cols


def _gap_amaranth(st: Stimulus, variant: str = "published"):
    from .golden import GapVector
    from .rtl import simulate_gap_core
    f = st.fields
    vecs = [GapVector(r_code=f["r"][i], t_code=f["t"][i], p_code=f["p"][i],
                      g_code=f["g"][i], n_code=f["nrm"][i], tau2_code=int(f["tau2"][i]))
            for i in range(len(st))]
    outs, cycles = simulate_gap_core(vecs, lanes=GAP_LANES, variant=variant)
    return ({"gap": np.array([o.min_gap_code for o in outs], np.int64),
             "idx": np.array([o.min_idx for o in outs], np.int64),
             "valid": np.array([o.valid for o in outs], np.int64),
             "overflow": np.array([o.overflow for o in outs], np.int64)},
            np.asarray(cycles, np.int64))


def _gap_cycles(st: Stimulus) -> int:
    from .golden import gap_latency
    return gap_latency(st.fields["g"].shape[1], GAP_LANES)


def _gap_core(name: str, top: str, variant: str, summary: str) -> CoreDescriptor:
    return CoreDescriptor(
        name, "gap.rtl", lazy("gap.rtl", "GapCore"), top, _gap_ports,
        partial(_gap_golden, variant=variant), partial(_gap_amaranth, variant=variant),
        _gap_cycles, go="go", done="done",
        control=("w_ready", "busy", "done_pulse", "n_error"), max_cycles=4 * _GAP_MAX,
        write=WriteNames("w_valid", ("w_g", "w_n"), _GAP_MAX, addr="w_addr"),
        verilog_kwargs={"lanes": GAP_LANES, "variant": variant},
        stimulus_core="gap", summary=summary)


DESCRIPTORS = (
    _gap_core("gap", "gap_core", "published",
              f"stage A/B gap kernel, L = {GAP_LANES} lanes, N = 16 samples"),
    _gap_core("gap_lean", "gap_lean_core", "lean",
              f"gap kernel variant 'lean' (15 DSP48E1 per lane), L = {GAP_LANES}"),
)
