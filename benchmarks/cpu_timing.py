"""CPU timing shared by the benchmark scripts: the best of repeated calls and the load
average printed beside every figure (docs/performance.md: benchmarks on a shared
machine say their load)."""

from __future__ import annotations

import os
import time

__all__ = ["best_cpu_s", "load_average"]


def best_cpu_s(fn, repeat: int) -> tuple[float, object]:
    """``(best CPU s, last result)`` of ``repeat`` calls of ``fn`` (process time: the
    least sensitive to other processes on the machine)."""
    best, got = float("inf"), None
    for _ in range(repeat):
        c0 = time.process_time()
        got = fn()
        best = min(best, time.process_time() - c0)
    return best, got


def load_average() -> str:
    """The 1-, 5- and 15-minute load averages, as printed beside the figures."""
    return " ".join(f"{x:.2f}" for x in os.getloadavg())
