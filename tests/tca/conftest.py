"""Shared TCA fixtures on the built-in s0003-centred pair (tests/conftest.py builds the
pair and its flanks once per session)."""

import pytest

from gearcontact.tca.analysis import analyze_pair


@pytest.fixture(scope="session")
def s0003_drive(s0003_centred):
    """The full unloaded analysis of the drive side (61 phases per pitch)."""
    s0003_pair, s0003_flanks = s0003_centred
    return analyze_pair(s0003_pair, side="drive", flanks=s0003_flanks)[0]
