"""The shared 80-bit restoring divider: bit-serial model == exact floor division."""

import numpy as np
import pytest

from gearcontact.preview.hertz.divider import (DIVIDER_BITS, DIVISION_CYCLES, floor_divide,
                                               restoring_divide)


def test_cycle_constants():
    assert DIVIDER_BITS == 80 and DIVISION_CYCLES == 83     # docs/spec.md sec. 6: 80 + 3 handshake


def test_restoring_equals_floor_random():
    rng = np.random.default_rng(7)
    for _ in range(300):
        nbits = int(rng.integers(1, 81))
        dbits = int(rng.integers(1, 81))
        n = int(rng.integers(0, 1 << 62)) << max(0, nbits - 62) if nbits > 62 \
            else int(rng.integers(0, 1 << nbits))
        n %= 1 << 80
        d = max(1, int(rng.integers(0, 1 << min(dbits, 62))) << max(0, dbits - 62))
        d %= 1 << 80
        d = d or 1
        r1, r2 = restoring_divide(n, d), floor_divide(n, d)
        assert r1 == r2                                        # bit-exact
        assert r1.quotient * d + r1.remainder == n and 0 <= r1.remainder < d


@pytest.mark.parametrize("n,d", [(0, 1), (1, 1), ((1 << 80) - 1, 1), ((1 << 80) - 1,
                                 (1 << 80) - 1), (1 << 79, 3), (12345, 1 << 79)])
def test_restoring_corners(n, d):
    assert restoring_divide(n, d) == floor_divide(n, d)
    assert restoring_divide(n, d).quotient == n // d


def test_divide_by_zero_semantics():
    # the restoring recurrence never restores with D = 0: quotient all ones, rem = N
    r = restoring_divide(987654321, 0)
    assert r.divide_by_zero and r.quotient == (1 << 80) - 1 and r.remainder == 987654321
    assert floor_divide(987654321, 0) == r


def test_operand_width_checked():
    with pytest.raises(ValueError, match="dividend"):
        restoring_divide(1 << 80, 3)
    with pytest.raises(ValueError, match="divisor"):
        floor_divide(5, -1)
