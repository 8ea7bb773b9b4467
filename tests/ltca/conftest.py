"""Shared set-up of the gear LTCA tests (built once per session)."""

import pytest


@pytest.fixture(scope="session")
def centred_drive_11(s0003_centred):
    """``(pair, flanks, tca)`` of s0003-centred, drive side, 11 TCA phases per pitch:
    the shared set-up of the tooth-bending and multi-tooth tests (built once)."""
    from gearcontact.tca.analysis import analyze_pair

    pair, flanks = s0003_centred
    tca = analyze_pair(pair, side="drive", phases=11, flanks=flanks)[0]
    return pair, flanks, tca
