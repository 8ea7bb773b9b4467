"""Descriptors of the stage-D cores: the serialized :class:`.rtl.HertzCore` (756 cycles)
and the pipelined :class:`.rtl_pipe.HertzPipe` (initiation interval 1), each in both
Hertz forms, and the line core :class:`.rtl_line.HertzLineCore` (759 cycles, near-line
contact, :mod:`.line`), also in both forms; see :mod:`gearcontact.preview.core`."""

from __future__ import annotations

import numpy as np

from ..core import CoreDescriptor, HostPath, lazy
from ..stimulus import Stimulus

__all__ = ["DESCRIPTORS", "hertz_columns", "LIFT_OUTPUTS"]


def hertz_columns(codes) -> dict:
    """Output columns (by port) from a HertzCodesArray or a list of HertzCodes."""
    from .rtl import OUTPUT_PORTS  # port -> HertzCodes field
    if isinstance(codes, list):
        return {p: np.array([getattr(c, f) for c in codes], np.int64)
                for p, f in OUTPUT_PORTS.items()}
    return {p: np.asarray(getattr(codes, f), np.int64) for p, f in OUTPUT_PORTS.items()}


def _ports(st: Stimulus):
    return {k: st.fields[k] for k in ("A", "B", "W", "e_prime")}, None, None


def _rows(st: Stimulus) -> np.ndarray:
    f = st.fields
    return np.stack([f["A"], f["B"], f["W"], f["e_prime"]], axis=1)


def _golden(hertz_form: str):
    def run(st: Stimulus) -> dict:
        from .golden_vec import hertz_golden_array
        f = st.fields
        return hertz_columns(hertz_golden_array(f["A"], f["B"], f["W"],
                                                e_prime_code=f["e_prime"],
                                                hertz_form=hertz_form))
    return run


def _serial_amaranth(hertz_form: str):
    def run(st: Stimulus):
        from .rtl import simulate_hertz_core
        outs, cycles = simulate_hertz_core(_rows(st), hertz_form=hertz_form)
        return hertz_columns(outs), np.asarray(cycles, np.int64)
    return run


def _serial_cycles(st: Stimulus) -> int:
    from .schedule import HERTZ_CYCLES
    return HERTZ_CYCLES


def _pipe_amaranth(hertz_form: str):
    def run(st: Stimulus):
        from .rtl_pipe import simulate_hertz_pipe
        res = simulate_hertz_pipe(_rows(st), hertz_form=hertz_form)
        acc = res.accept_edges
        ii = (acc[-1] - acc[0]) / (len(acc) - 1) if len(acc) > 1 else None
        return hertz_columns(res.outputs), np.asarray(res.latency, np.int64), ii
    return run


def _pipe_cycles(hertz_form: str):
    def latency(st: Stimulus) -> int:
        from .rtl_pipe import pipe_latency
        return pipe_latency(hertz_form=hertz_form)
    return latency


def _serial(name, top, hertz_form, summary):
    return CoreDescriptor(
        name, "hertz.rtl", lazy("hertz.rtl", "HertzCore"), top, _ports, _golden(hertz_form),
        _serial_amaranth(hertz_form), _serial_cycles,
        control=("go_chain", "busy", "done_pulse"),
        verilog_kwargs={"hertz_form": hertz_form} if hertz_form == "exact" else {},
        stimulus_core="hertz", summary=summary)


def _pipe(name, hertz_form, summary):
    return CoreDescriptor(
        name, "hertz.rtl_pipe", lazy("hertz.rtl_pipe", "HertzPipe"), name, _ports,
        _golden(hertz_form), _pipe_amaranth(hertz_form), _pipe_cycles(hertz_form),
        go="in_valid", done="out_valid", stream=True, max_cycles=1000,
        verilog_kwargs={"hertz_form": hertz_form} if hertz_form == "exact" else {},
        stimulus_core="hertz", summary=summary)


def _line_fields(st: Stimulus):
    f = st.fields
    return f["A"], f["B"], f["W"], f["L"], f["e_prime"]


def _line_ports(st: Stimulus):
    return {k: st.fields[k] for k in ("A", "B", "W", "L", "e_prime")}, None, None


def _line_columns(codes) -> dict:
    """Output columns (by port) from a LineCodesArray or a list of LineCodes."""
    from .rtl_line import LINE_OUTPUT_PORTS
    if isinstance(codes, list):
        return {p: np.array([getattr(c, f) for c in codes], np.int64)
                for p, f in LINE_OUTPUT_PORTS.items()}
    return {p: np.asarray(getattr(codes, f), np.int64) for p, f in LINE_OUTPUT_PORTS.items()}


#: The host's outputs beside the line cores' (the lift s, 0..LIFT_MAX_SHIFT = 8: 4 bits).
LIFT_OUTPUTS = (("lift", 4),)


def _line_golden(hertz_form: str, lifted: bool = False):
    """Golden line core; ``lifted``: the host's path, with its ``lift`` column."""
    def run(st: Stimulus) -> dict:
        from .line_vec import lifted_line_golden_array, line_golden_array
        a, b, w, length, e = _line_fields(st)
        kw = {"e_prime_code": e, "hertz_form": hertz_form}
        if not lifted:
            return _line_columns(line_golden_array(a, b, w, length, **kw))
        codes, lift = lifted_line_golden_array(a, b, w, length, **kw)
        return {**_line_columns(codes), "lift": lift}
    return run


def _line_amaranth(hertz_form: str):
    def run(st: Stimulus):
        from .rtl_line import simulate_line_core
        outs, cycles = simulate_line_core(list(zip(*_line_fields(st))), hertz_form=hertz_form)
        return _line_columns(outs), np.asarray(cycles, np.int64)
    return run


def _line(name, top, hertz_form, summary):
    return CoreDescriptor(
        name, "hertz.rtl_line", lazy("hertz.rtl_line", "HertzLineCore"), top, _line_ports,
        _line_golden(hertz_form), _line_amaranth(hertz_form), _line_cycles,
        control=("busy", "done_pulse"), stimulus_core="hertz_line",
        verilog_kwargs={"hertz_form": hertz_form} if hertz_form == "exact" else {},
        summary=summary,
        host=HostPath(lazy("stimulus_lift", "host_line_stimulus"),
                      _line_golden(hertz_form, lifted=True), LIFT_OUTPUTS))


def _line_cycles(st: Stimulus) -> int:
    from .line import LINE_CYCLES
    return LINE_CYCLES


DESCRIPTORS = (
    _serial("hertz", "hertz_core", "hamrock-brewe",
            "stage D serialized elliptic Hertz (one shared 80-bit divider)"),
    _serial("hertz_exact", "hertz_exact_core", "exact",
            "stage D with hertz_form='exact' (exact k and E tables, 756 cycles)"),
    _pipe("hertz_pipe", "hamrock-brewe",
          "stage D pipelined, initiation interval 1 (one preview per clock, valid/ready "
          "stream; cycles = latency)"),
    _pipe("hertz_pipe_exact", "exact", "pipelined stage D (II = 1) with hertz_form='exact'"),
    _line("hertz_line", "hertz_line_core", "hamrock-brewe",
          "stage D line core: ellipse (radii beyond 1 m by Hertz similarity) or Hertz line "
          "contact of the flank's contact line L, 759 cycles"),
    _line("hertz_line_exact", "hertz_line_exact_core", "exact",
          "stage D line core with hertz_form='exact' (exact k and E tables, 759 cycles)"),
)
