"""s0003 mesh for the twin tests (one TCA per session: 31 phases per pitch keep the
neighbouring pairs' paths, see tests/contact/test_lte.py, at half the cost of 61)."""

import pytest

PHASES = 31
TORQUE_NM = 64.5


@pytest.fixture(scope="session")
def s0003_twin():
    from gearcontact.geometry.pair import load_pair
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.twin.mesh import mesh_table

    pair = load_pair("s0003")
    tca, flanks = analyze_pair(pair, side="drive", phases=PHASES)
    return pair, tca, flanks, mesh_table(tca, flanks, pair, torque_nm=TORQUE_NM)
