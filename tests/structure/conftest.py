"""Shared fixtures: the s0003 pair and its flanks (built once per session)."""

import pytest

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair


@pytest.fixture(scope="session")
def s0003():
    pair = load_pair("s0003-centred")
    return pair, build_flanks(pair)
