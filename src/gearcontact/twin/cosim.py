"""The ``rtl`` and ``soc`` twin backends: the golden twin in lockstep with the hardware.

The twin's state after step ``n + 1`` depends on the contact backend only through the
output codes of the previews at step ``n``. The golden loop records every preview it
evaluates (input codes W and A-, B- -- with stage C per step also the 49 gap codes of
the stencil -- and output codes a, b, p_max, k, flags;
:func:`gearcontact.twin.kernel.run_steps`), and :func:`replay_on_rtl` runs the same
input codes through the RTL -- the C -> D ChainCore on the stencils (806 cycles: fit
core and stage D), else the stage-D HertzCore on A-, B- (Verilator when installed, else
the Amaranth simulator; :mod:`gearcontact.hw.harness_cores`) -- and compares the outputs
code by code (with the chain also the fit core's A-, B- registers).
If every output matches, the RTL-driven twin takes exactly the golden twin's trajectory
(by induction over the steps), so the golden run *is* the RTL co-simulation; a single
mismatch is an error naming the step. This replays a whole run in one bulk simulation
instead of one simulator round trip per step; it is meant for short runs (the RTL rate
is reported).

The ``soc`` backend replays the same trace through the host driver over the register
map (:class:`gearcontact.hw.driver.PreviewDriver` on the ``tri_core`` SoC with
stencils: 49 ``wr_data`` writes, ``W_load``, ``go``; :class:`~gearcontact.hw.driver.
HertzDriver` on ``bhseq_core`` without; a cylindrical pair's line chain through
:class:`gearcontact.hw.line_driver.LineDriver` on ``line_core``, its ``L_line`` beside
the load, a line below 1 mm on the host's lift as traced; the protocol a board uses;
here its transport is the Amaranth simulation of the SoC, ~0.3-0.6 s per preview): one
register transaction per preview, for very short runs.
"""

from __future__ import annotations

import time

import numpy as np

from ..preview.stimulus import Stimulus
from .layout import N_TRACE
from ..validation import UnusableInput

__all__ = ["replay_on_rtl", "replay_on_soc", "TRACE_COLUMNS"]

#: Columns of the golden preview trace (the line chain's runs fill the last three; A, B
#: are then the line core's sorted A_min, B_max, W and L the codes it ran on and
#: ``lift`` the host's lift s of a line below 1 mm, :mod:`.line_law`).
TRACE_COLUMNS = ("step", "A_code", "B_code", "W_code", "flags", "a_code", "b_code",
                 "p_max_code", "k_code", "L_code", "mode", "lift")
assert len(TRACE_COLUMNS) == N_TRACE


def replay_on_rtl(trace: np.ndarray, e_prime_code: int, *, simulator: str | None = None,
                  stencils: np.ndarray | None = None, line: bool = False) -> dict:
    """Run the traced previews on the RTL and compare every output code.

    Parameters
    ----------
    trace : ndarray (N, 12) of int64
        Rows of :data:`TRACE_COLUMNS`.
    e_prime_code : int
        E' register code (Q(32,0), MPa).
    simulator : str or None
        ``verilator`` or ``amaranth`` (default :func:`~gearcontact.hw.rtl_engine.
        default_simulator`).
    stencils : ndarray (N, 49) of int64, optional
        The gap codes of each preview (stage C per step): replayed on the C -> D chain
        core instead of stage D alone.
    line : bool
        The previews are the line chain's (a cylindrical pair, :mod:`.line_law`; with
        ``stencils``): replayed on the ChainLineCore with their ``L`` codes, the line
        core's A_min, B_max and mode compared too.

    Returns
    -------
    dict
        ``rtl_previews``, ``rtl_core``, ``rtl_mismatches`` (0 when bit-identical),
        ``rtl_first_mismatch_step`` (or None), ``rtl_simulator``, ``rtl_seconds``,
        ``rtl_previews_per_s`` (with ``line`` also ``rtl_lifted_previews``: the previews
        run on the host's lift).
    """
    from ..hw.harness_cores import get_bench, simulate
    from ..hw.rtl_engine import default_simulator
    from ..preview.hertz.rtl import OUTPUT_PORTS

    sim = simulator or default_simulator()
    n = int(trace.shape[0])
    if line and stencils is None:
        raise ValueError("replay_on_rtl: the line chain replays stencils")
    core = "hertz" if stencils is None else ("chain_line" if line else "chain")
    out = {"rtl_previews": n, "rtl_core": core, "rtl_mismatches": 0,
           "rtl_first_mismatch_step": None, "rtl_simulator": sim, "rtl_seconds": 0.0,
           "rtl_previews_per_s": 0.0}
    if n == 0:
        return out
    e = np.full(n, int(e_prime_code), np.int64)
    if stencils is None:
        fields = {"A": trace[:, 1], "B": trace[:, 2], "W": trace[:, 3], "e_prime": e}
    else:
        fields = {"gaps": stencils, "W": trace[:, 3], "e_prime": e}
    if line:
        fields["L"] = trace[:, 9]
    st = Stimulus(core, {k: np.asarray(v, np.int64) for k, v in fields.items()},
                  ("twin",) * n, 0)
    t0 = time.perf_counter()
    outs, *_ = simulate(get_bench(core), st, sim)
    secs = time.perf_counter() - t0
    port = {f: p for p, f in OUTPUT_PORTS.items()}
    got = np.column_stack([np.asarray(outs[port[f]], np.int64) for f in _FIELDS])
    if line:        # the line core's sorted inputs and its mode
        got = np.column_stack([got] + [np.asarray(outs[p], np.int64)
                                       for p in ("A_min", "B_max", "mode")])
    elif stencils is not None:        # the fit core's latched A- >= B-: stage D's B, A
        got = np.column_stack([got, np.asarray(outs["b_minus"], np.int64),
                               np.asarray(outs["a_minus"], np.int64)])
    return _compare(trace, got, out, "rtl", secs, line=line)


#: Output fields compared, in the order of trace columns 4..8.
_FIELDS = ("flags", "a_code", "b_code", "p_max_code", "k_code")


def _compare(trace, got, out: dict, prefix: str, secs: float, *, line: bool = False) -> dict:
    """Rows of ``got`` (flags, a, b, p_max, k[, stage D's A, B[, mode]]) against the
    trace; the line chain's replays also count the previews run on the host's lift
    (``<prefix>_lifted_previews``)."""
    want = trace[:, 4:9]
    if got.shape[1] > 5:
        want = np.column_stack([want, trace[:, 1:3]] + ([trace[:, 10]] if got.shape[1] == 8
                                                        else []))
    bad = np.any(got != want, axis=1)
    n = int(trace.shape[0])
    out.update({f"{prefix}_mismatches": int(bad.sum()), f"{prefix}_seconds": secs,
                f"{prefix}_previews_per_s": n / secs if secs > 0 else 0.0})
    if line:
        out[f"{prefix}_lifted_previews"] = int(np.count_nonzero(trace[:, 11]))
    if bad.any():
        out[f"{prefix}_first_mismatch_step"] = int(trace[np.argmax(bad), 0])
    return out


def replay_on_soc(trace: np.ndarray, e_prime_code: int, *,
                  stencils: np.ndarray | None = None, board: tuple | None = None,
                  line: bool = False) -> dict:
    """Replay the traced previews through the register driver of the SoC (``tri_core``
    with ``stencils``, else ``bhseq_core``; ``line_core`` with ``line``, the line chain
    of a cylindrical pair with its traced ``L`` codes: :func:`replay_on_rtl`'s columns)
    and compare every output code (as :func:`replay_on_rtl`).

    ``board``: ``(host, port)`` of a ``litex_server`` in front of a board built with this
    E' (or of ``gearcontact rtl serve``, :mod:`gearcontact.hw.serve`), reached through
    LiteX's ``RemoteClient``; None: the Amaranth simulation of the SoC in this process.

    Returns
    -------
    dict
        ``soc_previews``, ``soc_kind``, ``soc_transport``, ``soc_mismatches``,
        ``soc_first_mismatch_step``, ``soc_seconds``, ``soc_previews_per_s`` (with
        ``line`` also ``soc_lifted_previews``).
    """
    from ..hw.driver import (DriverError, HertzDriver, LiteXRemoteTransport, PreviewDriver,
                             SimTransport, WrongIdentifier)
    from ..hw.line_driver import LineDriver

    if line and stencils is None:
        raise ValueError("replay_on_soc: the line chain replays stencils")
    n = int(trace.shape[0])
    kind = "bhseq_core" if stencils is None else ("line_core" if line else "tri_core")
    where = "simulation" if board is None else f"litex_server {board[0]}:{board[1]}"
    out = {"soc_previews": n, "soc_kind": kind, "soc_transport": where, "soc_mismatches": 0,
           "soc_first_mismatch_step": None, "soc_seconds": 0.0, "soc_previews_per_s": 0.0}
    if n == 0:
        return out
    t0 = time.perf_counter()
    try:
        transport = (SimTransport(kind, e_prime_code=int(e_prime_code)) if board is None
                     else LiteXRemoteTransport(host=board[0], port=int(board[1])))
    except DriverError as exc:      # no server there: the user's address, not a bug
        raise UnusableInput(str(exc)) from None
    try:
        drv = (HertzDriver(transport, kind=kind) if stencils is None
               else LineDriver(transport) if line else PreviewDriver(transport))
    except WrongIdentifier as exc:
        transport.close()
        need = {"tri_core": "tri_core (the C -> D chain: stage C per step)",
                "bhseq_core": "bhseq_core (stage D alone: --curvatures exact)",
                "line_core": "line_core (the line chain of a cylindrical pair)"}[kind]
        raise UnusableInput(f"the SoC at {where} is not the one this replay needs ({exc}): "
                            f"it needs a {need}") from None
    got = np.zeros((n, 5 if stencils is None else 8 if line else 7), np.int64)
    try:
        for i in range(n):
            if stencils is None:
                rb = drv.run(int(trace[i, 1]), int(trace[i, 2]), int(trace[i, 3]))
                got[i] = (rb.flags, rb.a, rb.b, rb.p_max, rb.k)
            elif line:
                got[i] = drv.run(stencils[i], int(trace[i, 3]), int(trace[i, 9])).trace_row()
            else:
                rb = drv.run(stencils[i], int(trace[i, 3]))
                got[i] = (rb.flags, rb.a, rb.b, rb.p_max, rb.k, rb.B, rb.A)
    finally:
        drv.t.close()
    return _compare(trace, got, out, "soc", time.perf_counter() - t0, line=line)
