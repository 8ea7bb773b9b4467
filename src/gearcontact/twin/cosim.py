"""The ``rtl`` twin backend: the golden twin in lockstep with the RTL of stage D.

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
"""

from __future__ import annotations

import time

import numpy as np

from ..preview.stimulus import Stimulus

__all__ = ["replay_on_rtl", "TRACE_COLUMNS"]

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
        ``verilator`` or ``amaranth`` (default :func:`~gearcontact.preview.rtl_engine.
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
    from ..preview.rtl_engine import default_simulator

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
    bad = np.zeros(n, bool)
    for col, field in ((4, "flags"), (5, "a_code"), (6, "b_code"), (7, "p_max_code"),
                       (8, "k_code")):
        bad |= np.asarray(outs[port[field]], np.int64) != trace[:, col]
    out.update(rtl_mismatches=int(bad.sum()), rtl_seconds=secs, rtl_previews_per_s=n / secs)
    if bad.any():
        out["rtl_first_mismatch_step"] = int(trace[np.argmax(bad), 0])
    return out
