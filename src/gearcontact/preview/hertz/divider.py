"""The shared 80-bit restoring divider of stage D, bit-serial and fast-path models.

Every division of the serialized stage D goes through one unsigned restoring divider
(Hennessy & Patterson, *Computer Architecture*, 5th ed., App. J.2; Parhami, *Computer
Arithmetic*, 2nd ed., 2010, sec. 13.1): an 80-bit dividend register N, a divisor
register D and a partial-remainder register. Each of the 80 iterations shifts the next
dividend bit (MSB first) into the partial remainder, trial-subtracts D and keeps the
difference when it is non-negative, producing one quotient bit. After 80 iterations
the quotient register holds ``floor(N / D)`` and the remainder ``N mod D`` exactly, for
every ``0 <= N < 2**80`` and ``D >= 1``. A zero divisor is reported through a flag;
the datapath then reads the quotient all-ones, the remainder N (what the restoring
recurrence yields), and never uses the result (the caller flags the run instead).

:func:`restoring_divide` is the cycle-by-cycle model (one loop iteration = one divider
cycle), :func:`floor_divide` the fast path used by the golden model; the tests prove
them equal (random operands and corners).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["DIVIDER_BITS", "DIVIDER_CYCLES", "DIVIDER_HANDSHAKE_CYCLES", "DIVISION_CYCLES",
           "DivisionResult", "restoring_divide", "floor_divide"]

DIVIDER_BITS = 80                 #: dividend / quotient register width, bits
DIVIDER_CYCLES = DIVIDER_BITS     #: one quotient bit per cycle
DIVIDER_HANDSHAKE_CYCLES = 3      #: operand load, start, quotient write-back
DIVISION_CYCLES = DIVIDER_CYCLES + DIVIDER_HANDSHAKE_CYCLES   #: 83 per division


@dataclass(frozen=True)
class DivisionResult:
    """Outcome of one division on the shared divider.

    Attributes
    ----------
    quotient : int
        ``floor(N/D)`` (all ones, ``2**80 - 1``, when ``D == 0``), unsigned integer.
    remainder : int
        ``N mod D`` (``N`` when ``D == 0``), unsigned integer.
    divide_by_zero : bool
        True when the divisor was zero.
    """

    quotient: int
    remainder: int
    divide_by_zero: bool


def _check_operands(numerator: int, divisor: int, width: int) -> None:
    if not 0 <= numerator < (1 << width):
        raise ValueError(f"dividend {numerator} does not fit the {width}-bit register")
    if not 0 <= divisor < (1 << width):
        raise ValueError(f"divisor {divisor} does not fit the {width}-bit register")


def restoring_divide(numerator: int, divisor: int, *, width: int = DIVIDER_BITS
                     ) -> DivisionResult:
    """Bit-serial restoring division, one iteration per divider cycle.

    Parameters
    ----------
    numerator : int
        Unsigned dividend, ``0 <= N < 2**width``.
    divisor : int
        Unsigned divisor, ``0 <= D < 2**width``.
    width : int
        Register width = number of iterations (80 in stage D).

    Returns
    -------
    DivisionResult
    """
    _check_operands(numerator, divisor, width)
    rem = 0
    quo = 0
    for i in range(width - 1, -1, -1):
        rem = (rem << 1) | ((numerator >> i) & 1)      # shift in the next dividend bit
        trial = rem - divisor                           # trial subtraction
        if trial >= 0:                                  # keep it: quotient bit 1
            rem = trial
            quo = (quo << 1) | 1
        else:                                           # restore: quotient bit 0
            quo <<= 1
    return DivisionResult(quo, rem, divisor == 0)


def floor_divide(numerator: int, divisor: int, *, width: int = DIVIDER_BITS
                 ) -> DivisionResult:
    """Fast path with results identical to :func:`restoring_divide` (Python ints)."""
    _check_operands(numerator, divisor, width)
    if divisor == 0:
        return DivisionResult((1 << width) - 1, numerator, True)
    q, r = divmod(numerator, divisor)
    return DivisionResult(q, r, False)
