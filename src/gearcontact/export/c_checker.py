"""What the exported checker program knows of each core: vector layouts and C calls.

``gearcontact_check`` reads the ``$readmemh`` files of ``gearcontact vectors``; its field
tables are :func:`gearcontact.hw.vectors.vector_layout` (the same layouts the writer
and the Verilator harness use), and each core's C call is described here once
(:data:`C_CORES`: function, argument ports, the form argument, result struct). The
template ``data/templates/c/gearcontact_check.c.j2`` turns :func:`checker_cores` into
C tables and one adapter per core.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..hw.harness_cores import get_bench
from ..hw.vectors import EXPORT_CORES, vector_layout

__all__ = ["CCall", "C_CORES", "checker_cores", "other_cores"]


@dataclass(frozen=True)
class CCall:
    """The golden C function that computes one vector core.

    Attributes
    ----------
    function : str
        C function name.
    args : tuple of str
        Input ports passed, in argument order (a scalar port as a value, an array
        port, e.g. the 49 gap samples, as a pointer to its elements).
    extra : str
        Trailing C argument(s) (the Hertz form), verbatim.
    result_type : str
        Returned struct type; its members are named after the output ports.
    arg_types : tuple of (str, str), optional
        ``(port, C type)`` of the arguments that are not ``int32_t`` (the 64-bit gate,
        the sample count).
    host_outputs : tuple of (str, str, tuple of str), optional
        ``(port, C function, argument ports)`` of the outputs the host adds (the line
        cores' ``lift``: ``gc_line_length_lift(W, L)``), each a function of scalar input
        ports returning an integer.
    """

    function: str
    args: tuple
    extra: str
    result_type: str
    arg_types: tuple = ()
    host_outputs: tuple = ()

    def arg_type(self, port: str) -> str:
        """C type of argument port ``port``."""
        return dict(self.arg_types).get(port, "int32_t")


_GAP_ARGS = ("w_g", "w_n", "r", "t", "p", "tau2", "n_samples")
_GAP_TYPES = (("tau2", "uint64_t"), ("n_samples", "int"))
#: The line cores' host output: the lift of a line shorter than 1 mm.
_LIFT = (("lift", "gc_line_length_lift", ("W", "L")),)

#: Vector cores the golden C library implements (the checker runs them in the file
#: order of ``gearcontact vectors``, :data:`~gearcontact.hw.vectors.EXPORT_CORES`).
C_CORES = {
    "gap": CCall("gc_gap_golden", _GAP_ARGS, "GC_GAP_PUBLISHED", "gc_gap_codes", _GAP_TYPES),
    "fit": CCall("gc_fit_golden", ("wr_data",), "", "gc_fit_codes"),
    "hertz": CCall("gc_hertz_golden", ("A", "B", "W", "e_prime"), "GC_HERTZ_HAMROCK_BREWE",
                   "gc_hertz_codes"),
    "chain": CCall("gc_chain_golden", ("wr_data", "W", "e_prime"), "GC_HERTZ_HAMROCK_BREWE",
                   "gc_chain_codes"),
    "hertz_exact": CCall("gc_hertz_golden", ("A", "B", "W", "e_prime"), "GC_HERTZ_EXACT",
                         "gc_hertz_codes"),
    "chain_exact": CCall("gc_chain_golden", ("wr_data", "W", "e_prime"), "GC_HERTZ_EXACT",
                         "gc_chain_codes"),
    "gap_lean": CCall("gc_gap_golden", _GAP_ARGS, "GC_GAP_LEAN", "gc_gap_codes", _GAP_TYPES),
    "hertz_line": CCall("gc_line_golden", ("A", "B", "W", "L", "e_prime"),
                        "GC_HERTZ_HAMROCK_BREWE", "gc_line_codes", host_outputs=_LIFT),
    "hertz_line_exact": CCall("gc_line_golden", ("A", "B", "W", "L", "e_prime"),
                              "GC_HERTZ_EXACT", "gc_line_codes", host_outputs=_LIFT),
    "chain_line": CCall("gc_chain_line_golden", ("wr_data", "W", "L", "e_prime"),
                        "GC_HERTZ_HAMROCK_BREWE", "gc_chain_line_codes", host_outputs=_LIFT),
}


def _offsets(fields) -> dict[str, int]:
    """Position of each field's first element among the flattened values of a line."""
    out, pos = {}, 0
    for f in fields:
        out[f.name] = pos
        pos += f.count
    return out


def checker_cores() -> list[dict]:
    """Template context of every core in :data:`C_CORES`: name, summary, input and
    output fields (:class:`~gearcontact.hw.vectors.HexField`), each argument's offset
    and element count, the C call's argument list and ``(member, offset)`` of every
    output element."""
    cores = []
    for name in (c for c in EXPORT_CORES if c in C_CORES):
        call = C_CORES[name]
        ins, outs = vector_layout(name)
        in_at, out_at = _offsets(ins), _offsets(outs)
        if any(f.count != 1 for f in outs):
            raise ValueError(f"core {name}: array outputs need an adapter of their own")
        count = {f.name: f.count for f in ins}
        args = [{"offset": in_at[a], "count": count[a], "type": call.arg_type(a)}
                for a in call.args]
        call_args = [f"v{i}" if a["count"] > 1 else f"v{i}[0]" for i, a in enumerate(args)]
        host = {port: f"{fn}({', '.join(call_args[call.args.index(a)] for a in fargs)})"
                for port, fn, fargs in call.host_outputs}
        cores.append({"name": name, "summary": get_bench(name).summary,
                      "ins": ins, "outs": outs,
                      "args": args,
                      "call_args": call_args + ([call.extra] if call.extra else []),
                      "function": call.function, "result_type": call.result_type,
                      "out_members": [(f.name, out_at[f.name]) for f in outs
                                      if f.name not in host],
                      "host_outputs": [(host[f.name], out_at[f.name]) for f in outs
                                       if f.name in host]})
    return cores


def other_cores() -> list[str]:
    """Vector cores of ``gearcontact vectors`` the C library does not implement yet."""
    return [c for c in EXPORT_CORES if c not in C_CORES]
