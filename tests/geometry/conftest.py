"""Shared fixtures: the s0003 pair and its flank set (built once per session)."""

import pytest

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair


@pytest.fixture(scope="session")
def s0003():
    return load_pair("s0003-centred")


@pytest.fixture(scope="session")
def flanks(s0003):
    # the production 120 x 150 node grid (about 2 s)
    return build_flanks(s0003)
