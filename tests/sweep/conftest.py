"""Fixtures of the sweep tests: one LocalCluster of two worker processes shared by the
modules (its start-up costs seconds); the centred pair and its flanks are the shared
``s0003_centred`` of tests/conftest.py."""

import pytest


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
