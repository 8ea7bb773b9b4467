"""The ``rtl`` and ``soc`` twin backends: the golden twin in lockstep with the hardware.

The twin's state after step ``n + 1`` depends on the contact backend only through the
stage-D output codes of the previews at step ``n``. The golden loop records every
preview it evaluates (input codes A-, B-, W and output codes a, b, p_max, k, flags;
:func:`gearcontact.twin.kernel.run_steps`), and :func:`replay_on_rtl` runs the same
input codes through the HertzCore RTL (Verilator when installed, else the Amaranth
simulator; :mod:`gearcontact.hw.harness_cores`) and compares the outputs code by code.
If every output matches, the RTL-driven twin takes exactly the golden twin's trajectory
(by induction over the steps), so the golden run *is* the RTL co-simulation; a single
mismatch is an error naming the step. This replays a whole run in one bulk simulation
instead of one simulator round trip per step; it is meant for short runs (the RTL rate
is reported).

The ``soc`` backend replays the same trace through the host driver over the register
map (:class:`gearcontact.hw.driver.HertzDriver` on the ``bhseq_core`` SoC, the protocol a
board uses; here its transport is the Amaranth simulation of the SoC, ~0.3 s per
preview): one register transaction per preview, for very short runs.
"""

from __future__ import annotations

import time

import numpy as np

from ..preview.stimulus import Stimulus

__all__ = ["replay_on_rtl", "replay_on_soc", "TRACE_COLUMNS"]

#: Columns of the golden preview trace.
TRACE_COLUMNS = ("step", "A_code", "B_code", "W_code", "flags", "a_code", "b_code",
                 "p_max_code", "k_code")


def replay_on_rtl(trace: np.ndarray, e_prime_code: int, *, simulator: str | None = None
                  ) -> dict:
    """Run the traced stage-D inputs on the RTL and compare every output code.

    Parameters
    ----------
    trace : ndarray (N, 9) of int64
        Rows of :data:`TRACE_COLUMNS`.
    e_prime_code : int
        E' register code (Q(32,0), MPa).
    simulator : str or None
        ``verilator`` or ``amaranth`` (default :func:`~gearcontact.hw.rtl_engine.
        default_simulator`).

    Returns
    -------
    dict
        ``rtl_previews``, ``rtl_mismatches`` (0 when bit-identical),
        ``rtl_first_mismatch_step`` (or None), ``rtl_simulator``, ``rtl_seconds``,
        ``rtl_previews_per_s``.
    """
    from ..hw.harness_cores import get_bench, simulate
    from ..preview.hertz.rtl import OUTPUT_PORTS
    from ..hw.rtl_engine import default_simulator

    sim = simulator or default_simulator()
    n = int(trace.shape[0])
    out = {"rtl_previews": n, "rtl_mismatches": 0, "rtl_first_mismatch_step": None,
           "rtl_simulator": sim, "rtl_seconds": 0.0, "rtl_previews_per_s": 0.0}
    if n == 0:
        return out
    fields = {"A": trace[:, 1], "B": trace[:, 2], "W": trace[:, 3],
              "e_prime": np.full(n, int(e_prime_code), np.int64)}
    st = Stimulus("hertz", {k: np.asarray(v, np.int64) for k, v in fields.items()},
                  ("twin",) * n, 0)
    t0 = time.perf_counter()
    outs, *_ = simulate(get_bench("hertz"), st, sim)
    secs = time.perf_counter() - t0
    port = {f: p for p, f in OUTPUT_PORTS.items()}
    got = np.column_stack([np.asarray(outs[port[f]], np.int64) for f in _FIELDS])
    return _compare(trace, got, out, "rtl", secs)


#: Output fields compared, in the order of trace columns 4..8.
_FIELDS = ("flags", "a_code", "b_code", "p_max_code", "k_code")


def _compare(trace, got, out: dict, prefix: str, secs: float) -> dict:
    bad = np.any(got != trace[:, 4:9], axis=1)
    n = int(trace.shape[0])
    out.update({f"{prefix}_mismatches": int(bad.sum()), f"{prefix}_seconds": secs,
                f"{prefix}_previews_per_s": n / secs if secs > 0 else 0.0})
    if bad.any():
        out[f"{prefix}_first_mismatch_step"] = int(trace[np.argmax(bad), 0])
    return out


def replay_on_soc(trace: np.ndarray, e_prime_code: int) -> dict:
    """Replay the traced previews through the register driver of the simulated
    ``bhseq_core`` SoC and compare every output code (as :func:`replay_on_rtl`).

    Returns
    -------
    dict
        ``soc_previews``, ``soc_mismatches``, ``soc_first_mismatch_step``, ``soc_seconds``,
        ``soc_previews_per_s``.
    """
    from ..hw.driver import HertzDriver, SimTransport

    n = int(trace.shape[0])
    out = {"soc_previews": n, "soc_mismatches": 0, "soc_first_mismatch_step": None,
           "soc_seconds": 0.0, "soc_previews_per_s": 0.0}
    if n == 0:
        return out
    t0 = time.perf_counter()
    drv = HertzDriver(SimTransport("bhseq_core", e_prime_code=int(e_prime_code)),
                      kind="bhseq_core")
    got = np.zeros((n, 5), np.int64)
    try:
        for i in range(n):
            rb = drv.run(int(trace[i, 1]), int(trace[i, 2]), int(trace[i, 3]))
            got[i] = (rb.flags, rb.a, rb.b, rb.p_max, rb.k)
    finally:
        drv.t.close()
    return _compare(trace, got, out, "soc", time.perf_counter() - t0)
