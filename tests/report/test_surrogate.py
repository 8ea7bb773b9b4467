"""Neural surrogate vs the physics-direct preview (docs/spec.md sec. 8, item 3).

Truths: the preview *is* Hamrock–Brewe, so its error against that truth is zero (to
rounding, 1e-12 %); against the exact elliptic Hertz solution it is the Hamrock–Brewe
approximation error, at most 1.6 % in p_max over ratios 1..100 (docs/geometry.md sec. 5)
and independent of the load (p_max ~ W^(1/3) in both). The MLP is a least-squares fit:
inside its training box it must be accurate (< 3 % RMSE, the issue's bound; the published
network reached 0.94 %), outside it nothing holds it to the physics, so its error there
must exceed the in-box error many times over (measured ~40x; asserted 5x). Seeded runs
are identical. The anchored study's labels are the LCP p90 of the library's own
single-pair LTCA, re-derived here by an independent solve.
"""

import numpy as np
import pytest

pytest.importorskip("sklearn")

from gearcontact.ltca.pair_ltca import single_pair_ltca  # noqa: E402
from gearcontact.geometry.pair import load_pair  # noqa: E402
from gearcontact.report.surrogate import (  # noqa: E402
    MlpSpec, anchored_study, relative_rmse_pct, synthetic_study)
from gearcontact.validation import InputRangeError  # noqa: E402


@pytest.fixture(scope="module")
def synthetic():
    return synthetic_study(n_train=1000, n_test=400, seed=3)


def test_preview_is_hamrock_brewe(synthetic):
    r = synthetic.rmse_pct["preview"]
    assert r["hamrock_brewe"]["in_box"] < 1e-12
    assert r["hamrock_brewe"]["out_of_box"] < 1e-12
    # vs exact Hertz: the HB approximation error, <= 1.6 % and the same in and out
    assert 0.1 < r["exact"]["in_box"] <= 1.6
    assert r["exact"]["out_of_box"] == pytest.approx(r["exact"]["in_box"], abs=0.2)


def test_mlp_accurate_in_box_not_outside(synthetic):
    r = synthetic.rmse_pct["mlp"]
    assert r["exact"]["in_box"] < 3.0
    assert r["exact"]["out_of_box"] > 5.0 * r["exact"]["in_box"]
    # the preview (physics) beats the MLP outside the box against either truth
    pre = synthetic.rmse_pct["preview"]
    assert r["exact"]["out_of_box"] > 3.0 * pre["exact"]["out_of_box"]
    assert r["hamrock_brewe"]["out_of_box"] > pre["hamrock_brewe"]["out_of_box"]


def test_seeded_and_reproducible(synthetic):
    again = synthetic_study(n_train=1000, n_test=400, seed=3)
    assert again.rmse_pct == synthetic.rmse_pct
    np.testing.assert_array_equal(again.mlp_err_pct, synthetic.mlp_err_pct)


def test_relative_rmse():
    # errors +1 % and -3 %: sqrt((1 + 9) / 2) = sqrt(5) %
    assert relative_rmse_pct([101.0, 97.0], [100.0, 100.0]) == pytest.approx(np.sqrt(5.0))


def test_bad_input_named():
    with pytest.raises(InputRangeError, match="n_train"):
        synthetic_study(n_train=10)
    pair = load_pair("s0003")
    with pytest.raises(InputRangeError, match="extrap_torques_nm"):
        anchored_study(None, None, pair, train_torques_nm=(32.25, 64.5),
                       extrap_torques_nm=(50.0,))
    with pytest.raises(InputRangeError, match="train_torques_nm"):
        anchored_study(None, None, pair, train_torques_nm=(32.25,), extrap_torques_nm=(129,))


def test_mlp_spec_describes_itself():
    text = MlpSpec().describe()
    assert "32 x 32" in text and "tanh" in text and "seed 0" in text


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_anchored_study_on_s0003(s0003_calibrated, s0003_calibrated_tca15):
    pair, flanks = s0003_calibrated
    tca = s0003_calibrated_tca15
    train = (32.25, 45.0, 64.5)
    st = anchored_study(tca, flanks, pair, train_torques_nm=train, extrap_torques_nm=(258.0,))
    # training cost: one LCP solve per training torque, timed
    assert st.lcp_solves == 3 and st.lcp_wall_s > 0.0 and st.lcp_solver_s > 0.0
    # label = the library's LCP p90 (independent solve at the top torque, same solver)
    top = single_pair_ltca(tca, flanks, pair, 258.0)
    assert st.extrap_p90_mpa[0] == pytest.approx(top.patch.p90_mpa, rel=1e-6)
    # the preview is Hertzian in the load: p_max / W^(1/3) constant to rounding
    w = np.concatenate([st.train_load_n, st.extrap_load_n])
    p = np.concatenate([st.preview_train_mpa, st.preview_extrap_mpa])
    np.testing.assert_allclose(p / np.cbrt(w), p[0] / np.cbrt(w[0]), rtol=1e-12)
    # the MLP reproduces its training labels (3 points, smooth) and fails beyond them
    assert st.rmse_pct["mlp"]["train"] < 1.0
    assert st.rmse_pct["mlp"]["extrap"] > 10.0 * st.rmse_pct["mlp"]["train"]
