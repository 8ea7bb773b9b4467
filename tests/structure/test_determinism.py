"""The tooth compliance computed twice in one process is identical, bit for bit.

Truth: a result is a function of its inputs alone (docs/architecture.md "Rules"); the
second call takes the shell from the first's cache (``structure.shell``'s
``lru_cache``), so a cached operator that its first user changed would show here.
"""

from same_results import assert_same


def test_two_compliance_calls_are_identical(s0003_centred):
    """``flank_compliance`` of the s0003-centred gear twice (Ritz orders 3 x 3, the
    default 3 x 3 lattice, no FE): every number equal."""
    from gearcontact.structure.compliance import flank_compliance

    pair, flanks = s0003_centred
    a, b = (flank_compliance(pair, "gear", flanks=flanks, order=3, order_face=3)
            for _ in range(2))
    assert_same(a, b)


def test_the_shell_does_not_depend_on_the_blas_thread_count(s0003_centred):
    """The s0003-centred gear's shell (default orders) built with BLAS limited to one
    thread and to two: the stiffness's Cholesky factor equal in every bit. Threaded BLAS
    sums in an order set by its thread count (before the shell built on one thread, the
    factor differed by up to 6e-8 and the loaded TE with bending by 1.6e-9 arcsec), so a
    machine with other cores, or OPENBLAS_NUM_THREADS set (Dask's workers set it to 1),
    wrote other files. Skipped on a one-core machine, where both builds run one thread."""
    import os

    import pytest
    from threadpoolctl import threadpool_limits

    from gearcontact.structure.shell import tooth_shell

    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: BLAS runs one thread either way")
    pair, flanks = s0003_centred
    build = tooth_shell.__wrapped__        # past the cache: two builds
    shells = []
    for threads in (1, 2):
        with threadpool_limits(limits=threads, user_api="blas"):
            shells.append(build(flanks, "gear", material=pair.gear_material))
    assert_same(shells[0], shells[1])

