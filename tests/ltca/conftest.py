"""Shared set-up of the gear LTCA tests (built once per session)."""

import pytest


@pytest.fixture(scope="session")
def centred_drive_11():
    """``(pair, flanks, tca)`` of s0003-centred, drive side, 11 TCA phases per pitch:
    the shared set-up of the tooth-bending and multi-tooth tests (built once)."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair
    from gearcontact.tca.analysis import analyze_pair

    pair = load_pair("s0003-centred")
    flanks = build_flanks(pair)
    tca = analyze_pair(pair, side="drive", phases=11, flanks=flanks)[0]
    return pair, flanks, tca
