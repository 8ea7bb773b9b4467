"""Descriptor of the stage-C curvature-fit core (:class:`.rtl.FitCore`); see
:mod:`gearcontact.preview.core`."""

from __future__ import annotations

import numpy as np

from ..core import CoreDescriptor, WriteNames, lazy
from ..stimulus import Stimulus
from ...contract.stencil import STENCIL_SIZE

__all__ = ["DESCRIPTORS", "STENCIL_WRITE", "STENCIL_CONTROL", "fit_columns"]

#: The stencil burst of the fit, chain and combinational cores (49 GAP words after a
#: one-cycle ``wr_rst``).
STENCIL_WRITE = WriteNames("wr_en", ("wr_data",), STENCIL_SIZE, clear="wr_rst")
#: Status ports of the stencil cores that the equivalence checks do not compare.
STENCIL_CONTROL = ("busy", "done_pulse", "wr_count", "wr_dropped")


def fit_columns(c, a, b, flags) -> dict:
    """Output columns (by port) of the fit registers: ``c0``..``c5``, ``a_minus``,
    ``b_minus`` and ``flags``."""
    out = {f"c{j}": np.asarray(c)[:, j].astype(np.int64) for j in range(6)}
    out.update(a_minus=np.asarray(a, np.int64), b_minus=np.asarray(b, np.int64),
               flags=np.asarray(flags, np.int64))
    return out


def _fit_golden(st: Stimulus) -> dict:
    from .golden import golden_fit_batch
    g = golden_fit_batch(st.fields["gaps"])
    return fit_columns(g.c_codes, g.a_minus_codes, g.b_minus_codes, g.flags)


def _fit_amaranth(st: Stimulus):
    from .rtl import simulate_fit_core
    outs, cycles = simulate_fit_core(st.fields["gaps"])
    return (fit_columns([o.c_codes for o in outs], [o.a_minus_code for o in outs],
                        [o.b_minus_code for o in outs], [o.flags for o in outs]),
            np.asarray(cycles, np.int64))


def _fit_cycles(st: Stimulus) -> int:
    from .golden import FIT_CYCLES
    return FIT_CYCLES


DESCRIPTORS = (
    CoreDescriptor(
        "fit", "fit.rtl", lazy("fit.rtl", "FitCore"), "fit_core",
        lambda st: ({}, {"wr_data": st.fields["gaps"]}, None), _fit_golden, _fit_amaranth,
        _fit_cycles, control=STENCIL_CONTROL, max_cycles=400, write=STENCIL_WRITE,
        summary="stage C curvature fit (49-tap baked pseudo-inverse MAC + isqrt)"),
)
