"""Speed sweep: the resonance the linear model predicts, and determinism across workers.

Truth: the mesh excites the chain at f_z = z1 n / 60; the dynamic factor peaks where
f_z meets the first elastic mode f_1 of the linearised chain (eig), i.e. at
n = 60 f_1 / z1 (~1465 rpm for s0003), and not 30 % away from it (Kahraman & Singh
1990, primary resonance).
"""

import numpy as np
import pytest

from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import build_model, linearized_modes
from gearcontact.twin.sweep import parse_speed_range, speed_sweep
from gearcontact.validation import InputRangeError

from .conftest import TORQUE_NM


def test_primary_resonance_at_the_first_mode(s0003_twin):
    pair, _, _, mesh = s0003_twin
    model = build_model(mesh, default_drivetrain(pair), TORQUE_NM)
    f1 = linearized_modes(model)[1]
    n_res = 60.0 * f1 / mesh.pinion_teeth
    speeds = np.array([0.7, 1.0, 1.3]) * n_res
    sw = speed_sweep({"reference": model}, speeds, workers=1)
    df = sw.rows["reference"]["dynamic_factor"]
    # measured on the s0003 defaults: 1.06 at resonance, 1.01 either side
    assert df[1] > df[0] + 0.02 and df[1] > df[2] + 0.02
    assert sw.resonance_speeds_rpm(orders=(1,))[(1, float(f1))] == pytest.approx(n_res)


def test_parallel_equals_serial(s0003_twin):
    pair, _, _, mesh = s0003_twin
    model = build_model(mesh, default_drivetrain(pair), TORQUE_NM)
    speeds = [2000.0, 3000.0]
    a = speed_sweep({"r": model}, speeds, workers=1, mesh_cycles=2, settle_s=0.0)
    b = speed_sweep({"r": model}, speeds, workers=2, mesh_cycles=2, settle_s=0.0)
    for key in ("dynamic_factor", "dte_pp_arcsec", "contact_loss"):
        np.testing.assert_array_equal(a.rows["r"][key], b.rows["r"][key])


def test_speed_range_parsing():
    np.testing.assert_allclose(parse_speed_range("500:8000:100"), np.arange(500, 8001, 100))
    for bad in ("500:100:10", "a:b:c", "0:100:10", "100:200:-5"):
        with pytest.raises(InputRangeError, match="--speed-sweep"):
            parse_speed_range(bad)


def test_speeds_checked_before_the_workers(s0003_twin, monkeypatch):
    """A speed above simulate's limit was met inside a worker, whose InputRangeError
    (not picklable then) broke the pool: BrokenProcessPool, exit 1 (issue 28 probe).
    Now every speed is checked before any worker starts."""
    import gearcontact.twin.sweep as sweep_mod

    pair, _, _, mesh = s0003_twin
    model = build_model(mesh, default_drivetrain(pair), TORQUE_NM)
    monkeypatch.setattr(sweep_mod, "ProcessPoolExecutor",
                        lambda *a, **k: pytest.fail("a worker started"))
    with pytest.raises(InputRangeError, match=r"speeds_rpm = 105000.0 .*\[0, 100000\]"):
        speed_sweep({"r": model}, [95000.0, 105000.0], workers=2)


def test_errors_cross_the_process_pool_intact():
    """The root of the BrokenProcessPool: InputRangeError's pickle rebuilt it from its
    message alone, a TypeError in the parent. Every package error now round-trips with
    its class, message and fields (OutputDirectoryError: another __init__)."""
    import pickle
    from types import SimpleNamespace

    from gearcontact.cli.outdir import OutputDirectoryError
    from gearcontact.halfspace.lcp import LcpConvergenceError

    # what LcpConvergenceError reads of a ContactResult
    result = SimpleNamespace(solver="pk_cg", status="max_iter", message="1000 iterations")
    for exc in (InputRangeError("speed_rpm", 1.05e5, "[0, 100000]"),
                OutputDirectoryError("/x", "why"), LcpConvergenceError(result)):
        back = pickle.loads(pickle.dumps(exc))
        assert type(back) is type(exc) and str(back) == str(exc)
        assert back.__dict__.keys() == exc.__dict__.keys()
