"""The twin built and run twice in one process gives identical results, bit for bit.

Truth: a result is a function of its inputs alone (docs/architecture.md "Rules"): the
model packed again and the compiled loop run again (its preview cache and warm starts
live in arrays each run makes afresh) give every number of the first run.
"""

import math

from same_results import assert_same

from .conftest import TORQUE_NM


def test_the_twin_built_and_run_twice_is_identical(s0003_twin):
    """``simulate`` twice over a tenth of a pitch (reference backend) on s0003_twin's
    mesh table, each with its model packed afresh: the runs equal in every number (the
    mesh table itself: the slow CLI comparison)."""
    from gearcontact.twin.params import default_drivetrain
    from gearcontact.twin.simulate import build_model, simulate

    pair, _, _, mesh = s0003_twin
    dt = default_drivetrain(pair)
    runs = [simulate(build_model(m, dt, TORQUE_NM), speed_rpm=60.0,
                     duration_s=0.1 * m.pitch_rad / (2 * math.pi), step_s=10e-6)
            for m in (mesh, mesh)]
    assert_same(runs[0], runs[1])
