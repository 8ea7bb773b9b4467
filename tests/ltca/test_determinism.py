"""Identical LTCA calls in one process give identical results, bit for bit.

Truth: a result is a function of its inputs alone (docs/architecture.md "Rules",
"Determinism"), so two calls with the same arguments in one process, whatever ran
before them, agree to the last bit in every number (no tolerance). Caches a call fills
(the influence kernels, the gap kernel's spline tables) are hit by the second call, so
a cache that kept a warm start or an array mutated by its first user would show here. The comparison against a fresh process is
tests/cli/test_reproducible.py.
"""

import pytest

from same_results import assert_same

TORQUE_NM = 64.5


@pytest.fixture(scope="module")
def s0003_coast_tca(s0003_calibrated, s0003_calibrated_tca15):
    """The calibrated s0003 on its design side (coast, a tip-edge bearing: the LTCA's
    trimmed re-solve runs too) with its TCA at 15 phases per pitch (the session's)."""
    pair, flanks = s0003_calibrated
    return pair, flanks, s0003_calibrated_tca15


def test_two_single_pair_solves_are_identical(s0003_coast_tca):
    """``single_pair_ltca`` twice on s0003 at 64.5 N·m (40 cells): every number of the
    load case equal (the p90 that moved by 1e-11 MPa between two solves of one torque
    in the analyze job, which warm-started the second from the first)."""
    from gearcontact.ltca.pair_ltca import single_pair_ltca

    pair, flanks, tca = s0003_coast_tca
    a, b = (single_pair_ltca(tca, flanks, pair, TORQUE_NM, cells=40) for _ in range(2))
    assert a.patch.converged
    assert a.resolved is not None          # the trimmed re-solve ran too
    assert_same(a, b)


def test_two_loaded_te_calls_are_identical(s0003_coast_tca):
    """``loaded_te`` twice (rigid teeth, 24 cells, every 5th of 15 phases; with bending in
    the slow CLI comparison): every number equal, the pair fields, the per-phase LCPs
    warm-started along the pitch and the edge laws included."""
    from gearcontact.ltca.lte import loaded_te

    pair, flanks, tca = s0003_coast_tca
    a, b = (loaded_te(tca, flanks, pair, TORQUE_NM, cells=24, stride=5) for _ in range(2))
    assert a.converged
    assert_same(a, b)
