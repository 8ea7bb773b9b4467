"""The rtl and soc twin backends: the golden twin in lockstep with the RTL (Verilator when
installed, else the Amaranth simulator): the C -> D ChainCore with stage C per step
(curvatures="stencil"), HertzCore with the TCA's curvatures (curvatures="exact").

Truth: RTL == golden bit for bit on every preview of a short run (the equivalence the
hardware tests establish on random vectors, here on the twin's own inputs), hence the
rtl twin's trajectory is the golden one exactly; a corrupted golden output -- a stage-D
output or the fit core's curvature -- is reported at its step (the comparison is not
vacuous).
"""

import pytest

import numpy as np

from gearcontact.preview.hertz.golden import encode_e_prime
from gearcontact.twin.cosim import replay_on_rtl
from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import build_model, simulate

from .conftest import TORQUE_NM


@pytest.mark.parametrize("curvatures, core", [("stencil", "chain"), ("exact", "hertz")])
def test_rtl_twin_is_the_golden_twin_bit_for_bit(s0003_twin, curvatures, core):
    pair, _, _, mesh = s0003_twin
    dt = default_drivetrain(pair)
    kw = dict(speed_rpm=3000.0, duration_s=1e-3, step_s=10e-6)
    rtl = simulate(build_model(mesh, dt, TORQUE_NM, backend="rtl", curvatures=curvatures),
                   **kw)
    gold = simulate(build_model(mesh, dt, TORQUE_NM, backend="golden",
                                curvatures=curvatures), **kw)
    s = rtl.summary
    # 100 steps x 3-4 loaded pairs, one preview each per step
    assert s["rtl_mismatches"] == 0 and s["rtl_previews"] >= 300
    assert s["rtl_core"] == core and s["curvatures"] == curvatures
    for key, col in gold.columns.items():
        np.testing.assert_array_equal(rtl.columns[key], col, err_msg=key)


def test_a_wrong_output_is_caught(s0003_twin):
    from gearcontact.twin import kernel as K
    from gearcontact.twin.simulate import _fit_args, _prm, static_rotation

    pair, _, _, mesh = s0003_twin
    m = build_model(mesh, default_drivetrain(pair), TORQUE_NM, backend="golden")
    # a small trace from the compiled loop itself (stage C per step: the stencils too)
    a = m.arrays
    prm = _prm(m, 0.0)
    trace = np.zeros((40, 9), np.int64)
    fit = _fit_args(a, 40)
    tcount = np.zeros(K.N_COUNT, np.int64)
    y = np.zeros(K.N_STATE)
    y[2] = mesh.eps_rad[0] - static_rotation(m)[0]      # static start, at rest
    K.run_steps(y, 0.0, 10, 1e-5, prm, a["eps"], a["lever"], a["opening"], a["cv"],
                a["valid"], a["cb"], 1, np.full((2, a["lever"].shape[1]), 500.0), a["pow_lut"],
                a["cbrt_lut"], a["cst"], trace, tcount, fit, a["tab_theta"], a["tab_t23"],
                a["tab_w23"], np.zeros((10, K.N_REC)), 0, 1)
    n = int(tcount[0])
    assert n >= 20           # 10 steps x 2-4 loaded pairs
    e_code = encode_e_prime(mesh.e_prime_mpa)
    stencils = fit[4][:n]
    assert np.count_nonzero(stencils) > 40 * n     # 49 gap codes per preview, ~all non-zero
    assert replay_on_rtl(trace[:n], e_code, stencils=stencils)["rtl_mismatches"] == 0
    for col in (7, 2):          # one LSB of p_max, then of the fit core's A-
        bad = trace[:n].copy()
        bad[17, col] += 1
        rep = replay_on_rtl(bad, e_code, stencils=stencils)
        assert rep["rtl_mismatches"] == 1 and rep["rtl_first_mismatch_step"] == trace[17, 0]


def test_soc_twin_through_the_register_driver(s0003_twin):
    # the host driver's register protocol on the simulated tri_core SoC (49 wr_data
    # writes, W_load, go, poll, read per preview in the Amaranth simulator): 3 steps,
    # every preview bit-identical
    pair, _, _, mesh = s0003_twin
    dt = default_drivetrain(pair)
    kw = dict(speed_rpm=3000.0, duration_s=30e-6, step_s=10e-6)
    soc = simulate(build_model(mesh, dt, TORQUE_NM, backend="soc"), **kw)
    gold = simulate(build_model(mesh, dt, TORQUE_NM, backend="golden"), **kw)
    assert soc.summary["soc_mismatches"] == 0 and soc.summary["soc_previews"] >= 6
    assert soc.summary["soc_kind"] == "tri_core"
    np.testing.assert_array_equal(soc.columns["mesh_load_n"], gold.columns["mesh_load_n"])


def test_soc_twin_through_a_board_address(s0003_twin, served_tri_core):
    # the board path: LiteX's RemoteClient over TCP to `gearcontact rtl serve` (LiteX's
    # RemoteServer in front of the simulated tri_core), every preview bit-identical;
    # a SoC of the wrong kind there is a named error
    from gearcontact.validation import InputRangeError, UnusableInput

    pair, _, _, mesh = s0003_twin
    dt = default_drivetrain(pair)
    kw = dict(speed_rpm=3000.0, duration_s=30e-6, step_s=10e-6)
    soc = simulate(build_model(mesh, dt, TORQUE_NM, backend="soc"), board=served_tri_core,
                   **kw)
    gold = simulate(build_model(mesh, dt, TORQUE_NM, backend="golden"), **kw)
    s = soc.summary
    assert s["soc_mismatches"] == 0 and s["soc_previews"] >= 6
    assert s["soc_transport"] == "litex_server {}:{}".format(*served_tri_core)
    np.testing.assert_array_equal(soc.columns["mesh_load_n"], gold.columns["mesh_load_n"])
    with pytest.raises(UnusableInput, match="bhseq_core"):
        simulate(build_model(mesh, dt, TORQUE_NM, backend="soc", curvatures="exact"),
                 board=served_tri_core, **kw)
    with pytest.raises(InputRangeError, match="board"):
        simulate(build_model(mesh, dt, TORQUE_NM), board=served_tri_core, **kw)
    # a cylindrical pair's line chain needs the line_core SoC: the tri_core there (no
    # line core) is named before any preview is written
    from gearcontact.twin.cosim import TRACE_COLUMNS, replay_on_soc
    with pytest.raises(UnusableInput, match="needs a line_core"):
        replay_on_soc(np.zeros((1, len(TRACE_COLUMNS)), np.int64), 229670,
                      stencils=np.zeros((1, 49), np.int64), board=served_tri_core, line=True)
