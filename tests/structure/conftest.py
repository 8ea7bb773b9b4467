"""Shared fixtures: both s0003 pairs and their flanks (built once per session; the
centred one is the shared ``s0003_centred`` of tests/conftest.py)."""

import pytest



@pytest.fixture(scope="session")
def pairs(s0003_centred, s0003_calibrated):
    """``name -> (pair, flanks)`` of both calibration pairs: s0003-centred and the
    calibrated s0003 (deeper teeth: 2.9 mm against 2.4 mm; tests/conftest.py)."""
    return {"s0003-centred": s0003_centred, "s0003": s0003_calibrated}
