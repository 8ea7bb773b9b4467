"""Shared TCA fixtures on the built-in s0003-centred pair (tests/conftest.py builds the
pair and its flanks once per session)."""

import numpy as np
import pytest

from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.solve import solve_tca


@pytest.fixture(scope="session")
def s0003_drive(s0003_centred):
    """The full unloaded analysis of the drive side (61 phases per pitch)."""
    s0003_pair, s0003_flanks = s0003_centred
    return analyze_pair(s0003_pair, side="drive", flanks=s0003_flanks)[0]


@pytest.fixture(scope="session")
def full_path(s0003_centred, s0003_drive):
    """The nominal drive path of one pair over the mesh cycle's phases with its whole
    edge tails (no TE0 limit: the mesh cycle cuts tails that cannot carry)."""
    s0003_pair, s0003_flanks = s0003_centred
    pinion = s0003_flanks.flank("pinion", "drive")
    gear = s0003_flanks.flank("gear", "drive")
    return solve_tca(pinion, gear, s0003_pair.kinematics(), s0003_drive.cycle.path.phi1_rad,
                     start=s0003_drive.mean_point.as_guess(), edge_te_limit_arcsec=np.inf)
