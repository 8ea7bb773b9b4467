"""Shared fixtures: both s0003 pairs and their flanks (built once per session; the
centred one is the shared ``s0003_centred`` of tests/conftest.py), and the three gears
without a rim block (set A of docs/bending.md sec. 13)."""

import pytest


@pytest.fixture(scope="session")
def pairs(s0003_centred, s0003_calibrated):
    """``name -> (pair, flanks)`` of both calibration pairs: s0003-centred and the
    calibrated s0003 (deeper teeth: 2.9 mm against 2.4 mm; tests/conftest.py)."""
    return {"s0003-centred": s0003_centred, "s0003": s0003_calibrated}


@pytest.fixture(scope="session")
def gears(pairs, f2_machine_pair):
    """``label -> (pair, flanks)`` of the three gears whose real root ends above their
    fillet height (set A): both s0003 pairs' and the F.2 machine pair's."""
    from gearcontact.geometry.flank import build_flanks

    return {"s0003-centred gear": pairs["s0003-centred"], "s0003 gear": pairs["s0003"],
            "F.2 gear": (f2_machine_pair, build_flanks(f2_machine_pair))}
