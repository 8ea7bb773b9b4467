"""Shared fixtures: the s0003-centred pair and its flank set (tests/conftest.py builds
them once per session)."""

import pytest


@pytest.fixture(scope="session")
def s0003(s0003_centred):
    return s0003_centred[0]


@pytest.fixture(scope="session")
def flanks(s0003_centred):
    # the production 120 x 150 node grid
    return s0003_centred[1]
