"""The restoring square-root unit of the line-contact stage, bit-serial and fast path.

One unsigned digit-by-digit (restoring) square root over an 80-bit radicand register
(Parhami, *Computer Arithmetic*, 2nd ed., 2010, sec. 21.2; the same recurrence as the
divider of :mod:`.divider` with the trial subtrahend ``4 root + 1``): each of the 40
iterations brings down the next two radicand bits (MSB first) into the partial
remainder, trial-subtracts ``4 root + 1`` and keeps the difference when it is
non-negative, producing one root bit. After 40 iterations the root register holds
``floor(sqrt(N))`` and the remainder ``N - root^2`` exactly, for every
``0 <= N < 2**80``.

:func:`restoring_sqrt` is the cycle-by-cycle model (one loop iteration = one cycle),
:func:`floor_sqrt` the fast path (:func:`math.isqrt`); the tests prove them equal.
"""

from __future__ import annotations

import math

__all__ = ["SQRT_BITS", "SQRT_ITERATIONS", "SQRT_CYCLES", "restoring_sqrt", "floor_sqrt"]

SQRT_BITS = 80                     #: radicand register width, bits
SQRT_ITERATIONS = SQRT_BITS // 2   #: one root bit per cycle: 40
SQRT_CYCLES = SQRT_ITERATIONS + 3  #: + operand load, start, root write-back: 43


def _check(radicand: int, width: int) -> None:
    if width % 2 or not 0 <= radicand < (1 << width):
        raise ValueError(f"radicand {radicand} does not fit the {width}-bit register")


def restoring_sqrt(radicand: int, *, width: int = SQRT_BITS) -> tuple[int, int]:
    """Bit-serial restoring square root, one iteration per cycle.

    Parameters
    ----------
    radicand : int
        Unsigned radicand, ``0 <= N < 2**width``.
    width : int
        Register width (even); ``width/2`` iterations.

    Returns
    -------
    (root, remainder) : tuple of int
        ``floor(sqrt(N))`` and ``N - root**2``.
    """
    _check(radicand, width)
    rem = 0
    root = 0
    for i in range(width // 2 - 1, -1, -1):
        rem = (rem << 2) | ((radicand >> (2 * i)) & 3)   # next two radicand bits
        trial = rem - ((root << 2) | 1)                   # (2 root + 1)^2 - (2 root)^2
        if trial >= 0:
            rem = trial
            root = (root << 1) | 1
        else:
            root <<= 1
    return root, rem


def floor_sqrt(radicand: int, *, width: int = SQRT_BITS) -> tuple[int, int]:
    """Fast path with results identical to :func:`restoring_sqrt`."""
    _check(radicand, width)
    root = math.isqrt(radicand)
    return root, radicand - root * root
