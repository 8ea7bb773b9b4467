"""One BLAS thread for the small dense products of the contact and structure models.

On a shared machine threaded BLAS spins its threads for matrix products of a few
hundred rows and costs 10-60x the single-threaded time (measured on 2 cores at load
10: a 357 x 357 ``eigh`` 4.1 s threaded vs 0.04 s on one thread). ``threadpoolctl``'s
``threadpool_limits`` re-scans the loaded libraries on every call (~9 ms), so one
controller is made on first use and reused.
"""

from __future__ import annotations

from contextlib import AbstractContextManager

__all__ = ["one_blas_thread"]

_CONTROLLER = None


def one_blas_thread() -> AbstractContextManager:
    """Context manager limiting BLAS/OpenMP pools to one thread (cached controller)."""
    global _CONTROLLER
    if _CONTROLLER is None:
        from threadpoolctl import ThreadpoolController

        _CONTROLLER = ThreadpoolController()
    return _CONTROLLER.limit(limits=1)
