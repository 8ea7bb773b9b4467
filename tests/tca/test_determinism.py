"""Identical TCA calls in one process give identical results, bit for bit.

Truth: a result is a function of its inputs alone (docs/architecture.md "Rules"), so two
``analyze_pair`` calls with the same arguments in one process agree to the last bit in
every number, the second hitting the caches the first filled (the gap kernel's spline
tables, the stencil's tables). The comparison against a fresh process is
tests/cli/test_reproducible.py.
"""

from same_results import assert_same


def test_two_tca_calls_are_identical(s0003_centred):
    """``analyze_pair`` twice on s0003-centred (drive, 11 phases): every number of the
    analysis equal (mesh cycle, paths, mean point and curvatures, ellipses, stencil)."""
    from gearcontact.tca.analysis import analyze_pair

    pair, flanks = s0003_centred
    a, b = (analyze_pair(pair, side="drive", phases=11, flanks=flanks)[0] for _ in range(2))
    assert_same(a, b)
