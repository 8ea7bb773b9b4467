"""Shared fixtures: the s0003 pairs and their flanks (built once per session)."""

import pytest



@pytest.fixture(scope="session")
def s0003(s0003_centred):
    """``(pair, flanks)`` of s0003-centred (tests/conftest.py)."""
    return s0003_centred


@pytest.fixture(scope="session")
def pairs(s0003, s0003_calibrated):
    """``name -> (pair, flanks)`` of both calibration pairs: s0003-centred and the
    calibrated s0003 (deeper teeth: 2.9 mm against 2.4 mm)."""
    return {"s0003-centred": s0003, "s0003": s0003_calibrated}
