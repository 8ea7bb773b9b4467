"""Fixtures of the sweep tests: the centred pair, its flanks and one LocalCluster of
two worker processes shared by the modules (its start-up costs seconds)."""

import pytest


@pytest.fixture(scope="package")
def pair(s0003_centred):
    return s0003_centred[0]


@pytest.fixture(scope="package")
def flanks(s0003_centred):
    return s0003_centred[1]


@pytest.fixture(scope="package")
def client():
    pytest.importorskip("distributed")
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()
