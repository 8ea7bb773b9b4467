"""Fixtures of the sweep tests: the centred pair, its flanks and one LocalCluster of
two worker processes shared by the modules (its start-up costs seconds)."""

import pytest


@pytest.fixture(scope="package")
def pair():
    from gearcontact.geometry.pair import load_pair

    return load_pair("s0003-centred")


@pytest.fixture(scope="package")
def flanks(pair):
    from gearcontact.geometry.flank import build_flanks

    return build_flanks(pair)


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
