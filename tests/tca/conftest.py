"""Shared TCA fixtures on the built-in s0003 pair (flanks built once per session)."""

import pytest

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair


@pytest.fixture(scope="session")
def s0003_pair():
    return load_pair("s0003-centred")


@pytest.fixture(scope="session")
def s0003_flanks(s0003_pair):
    return build_flanks(s0003_pair)


@pytest.fixture(scope="session")
def s0003_drive(s0003_pair, s0003_flanks):
    """The full unloaded analysis of the drive side (61 phases per pitch)."""
    return analyze_pair(s0003_pair, side="drive", flanks=s0003_flanks)[0]
