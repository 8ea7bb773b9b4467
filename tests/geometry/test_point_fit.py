"""Machine settings fitted at scattered measured points (gearcontact.geometry.point_fit,
issue 27 item 4: "a measured deviation grid as CSV" from a measuring room).

Independent truths: a pinion flank cut from known settings (s0003's coast seed with a
known correction of the size its ease-off needs), measured in the test at seeded
random points of the nominal flank (deviations = distances along the nominal normals
to the cut flank, found by Newton's method on the two sheets: tests/easeoff_grid.py),
gives back the known correction; with noise of known standard deviation added, the
least-squares statistics (residual RMS ~ sigma sqrt((N - P) / N), each setting within
its standard error); points on one or two profile lines (or a small patch) leave
combinations of settings that move no point, named in the refusal.
"""

import numpy as np
import pytest
from easeoff_grid import KNOWN_CORRECTION as KNOWN
from easeoff_grid import cut_from_known, write_points_csv

from gearcontact.geometry.measuring_grid import measured_points, read_measured_grid
from gearcontact.geometry.point_fit import PointProblem, fit_points, point_problem
from gearcontact.geometry.setting_fit import DEFAULT_PARAMETERS
from gearcontact.validation import InputRangeError

N_POINTS = 60


@pytest.fixture(scope="module")
def cut_coast(s0003_calibrated):
    """``(pair, nominal, seed, truth, box)``: s0003's nominal coast pinion, the seed,
    the flank cut by the seed + KNOWN (30 x 40 sheet) and the box both cover."""
    pair, flanks = s0003_calibrated
    seed, _, truth = cut_from_known(pair)
    nominal = flanks.pinion.coast
    a, b = nominal.boundary, truth.boundary
    box = (max(a.u_root, b.u_root), min(a.u_tip, b.u_tip), max(a.v_toe, b.v_toe),
           min(a.v_heel, b.v_heel))
    return pair, nominal, seed, truth, box


def _measure(tmp_path, cut_coast, u, v, noise_um=None):
    """The cut flank measured at nominal (u, v), through the file and its reader."""
    pair, nominal, _, truth, _ = cut_coast
    path = tmp_path / "cmm.csv"
    write_points_csv(path, nominal, truth, "coast", u, v, noise_um=noise_um)
    measured = read_measured_grid(path, members=("pinion",))["pinion", "coast"]
    return measured_points(measured, nominal, where=str(path))


def _scattered(box, n, seed=27):
    """n seeded uniform random points of the box (irregular, no two on a line)."""
    rng = np.random.default_rng(seed)
    return rng.uniform(box[0], box[1], n), rng.uniform(box[2], box[3], n)


def test_scattered_points_give_back_the_known_settings(tmp_path, cut_coast):
    # 60 random points (seed 27) of the flank cut by seed + KNOWN: the fit from the seed
    # recovers every correction within 5e-4 of its value (measured 6.1e-5, the 6D
    # coefficient, the weakest direction: the truth's 30 x 40 sheet interpolates its
    # envelope to ~5e-4 um, amplified by the conditioning, smallest relative singular
    # value ~2e-3) and passes through the points within 1e-3 um (measured 5e-5 um
    # max); ~2 s
    pair, _, seed, _, box = cut_coast
    points = _measure(tmp_path, cut_coast, *_scattered(box, N_POINTS))
    assert len(points.line) == N_POINTS and np.abs(points.deviation_um).max() > 20.0
    fit = fit_points(seed, pair.blank, points)
    print("max relative error", max(abs(fit.corrections[n] / w - 1) for n, w in KNOWN.items()),
          "fit max", fit.fit_max_um, "evaluations", fit.evaluations, "s", fit.seconds)
    assert fit.status > 0 and fit.fit_max_um < 1e-3
    for name, want in KNOWN.items():
        assert fit.corrections[name] == pytest.approx(want, rel=5e-4), name


def test_noise_of_known_sigma_gives_least_squares_statistics(tmp_path, cut_coast):
    # the same 60 points with Gaussian noise, sigma 0.5 um (seed 5): the least-squares
    # residual RMS at the points is sigma sqrt((N - P) / N) = 0.465 um in expectation
    # (N = 60 points, P = 8 settings; its spread ~ 1/sqrt(2 (N - P)) = 10 %: asserted
    # within 30 %), and each setting's error stays within 4 standard errors
    # sigma sqrt(diag((J^T J)^-1)) of the sensitivity J at the solution (a 4-sigma
    # bound: fails by chance with probability 6e-5 per setting)
    pair, _, seed, _, box = cut_coast
    u, v = _scattered(box, N_POINTS)
    sigma = 0.5
    noise = sigma * np.random.default_rng(5).standard_normal(N_POINTS)
    points = _measure(tmp_path, cut_coast, u, v, noise_um=noise)
    fit = fit_points(seed, pair.blank, points)
    expect = sigma * np.sqrt((N_POINTS - len(KNOWN)) / N_POINTS)
    print("RMS", fit.fit_rms_um, "expected", expect)
    assert fit.fit_rms_um == pytest.approx(expect, rel=0.3)
    prob = PointProblem(seed, pair.blank, points, DEFAULT_PARAMETERS)
    x = np.array([fit.corrections[n] for n in DEFAULT_PARAMETERS]) / prob.scale
    jac = prob.jacobian(x)
    se = sigma * np.sqrt(np.diag(np.linalg.inv(jac.T @ jac))) * prob.scale
    err = np.array([fit.corrections[n] - KNOWN[n] for n in DEFAULT_PARAMETERS])
    print("errors in standard errors", dict(zip(DEFAULT_PARAMETERS, np.round(err / se, 2))))
    print("standard errors", dict(zip(DEFAULT_PARAMETERS, se)))
    assert np.all(np.abs(err) < 4.0 * se)


@pytest.mark.parametrize("layout, named", [
    # one profile line at mid-face: six settings named (smallest relative singular
    # value 2.3e-9), the rigid turn and the radial distance among them
    ("profile line", ("cradle_angle_deg", "radial_distance_mm")),
    # two profile lines near the face ends: the turn and the radial distance remain
    # inseparable (8.2e-7, the same direction as the full flank's weakest one)
    ("two profile lines", ("radial_distance_mm", "cradle_angle_deg")),
    # 30 random points in a 0.5 x 2 mm patch at the toe-root corner (3.3e-5)
    ("patch", ("radial_distance_mm", "cradle_angle_deg")),
])
def test_points_that_leave_settings_unobservable_are_refused(tmp_path, cut_coast, layout,
                                                             named):
    pair, _, seed, _, (u0, u1, v0, v1) = cut_coast
    u, v = {"profile line": (np.linspace(u0, u1, 20), np.full(20, 0.5 * (v0 + v1))),
            "two profile lines": (np.tile(np.linspace(u0, u1, 10), 2),
                                  np.repeat([v0 + 1.0, v1 - 1.0], 10)),
            "patch": _scattered((u0, u0 + 0.5, v0, v0 + 2.0), 30)}[layout]
    points = _measure(tmp_path, cut_coast, u, v)
    with pytest.raises(InputRangeError, match=r"cmm.csv: pinion coast: points = 'rank-"
                       r"deficient \(settings not observable at these points: ") as exc:
        point_problem(seed, pair.blank, points, where="cmm.csv")
    msg = str(exc.value)
    print(layout, msg)
    listed = msg.split("at these points: ")[1].split(";")[0].split(", ")
    assert set(named) <= set(listed)
    assert "relative singular value >= 0.0001" in msg


def test_fewer_points_than_settings_are_refused(tmp_path, cut_coast):
    pair, _, seed, _, box = cut_coast
    points = _measure(tmp_path, cut_coast, *_scattered(box, 7))
    with pytest.raises(InputRangeError, match=r"pinion coast points = 7 .*at least 8, one "
                       r"per fitted setting \(cradle_angle_deg,"):
        point_problem(seed, pair.blank, points)
    # three settings: 7 points are enough (the rigid turn, the radial distance and the
    # blade angle: well separated, a full-rank 7 x 3 sensitivity)
    got = point_problem(seed, pair.blank, points, parameters=(
        "cradle_angle_deg", "radial_distance_mm", "blade_angle_deg"))
    assert got.U.shape == (7,)


@pytest.mark.slow       # least squares, then minimax: ~6 s
def test_minimax_at_noisy_points_equioscillates(tmp_path, cut_coast):
    # objective="minimax" on the noisy 60 points (sigma 0.5 um, as above): the largest
    # residual at the points falls below the least-squares fit's (measured 0.868
    # against 1.286 um) and at least P + 1 = 9 points reach it (Chebyshev alternation,
    # the optimality condition of a minimax fit with P free settings; to 1e-4 um), the
    # RMS not below the least squares' (its optimum: 0.540 against 0.431 um)
    pair, _, seed, _, box = cut_coast
    noise = 0.5 * np.random.default_rng(5).standard_normal(N_POINTS)
    points = _measure(tmp_path, cut_coast, *_scattered(box, N_POINTS), noise_um=noise)
    fit = fit_points(seed, pair.blank, points, objective="minimax")
    print("minimax", fit.fit_max_um, fit.rms_fit_max_um, fit.fit_rms_um)
    assert fit.fit_max_um < fit.rms_fit_max_um - 0.1
    prob = PointProblem(seed, pair.blank, points, DEFAULT_PARAMETERS)
    dev = prob.deviation_um(np.array([fit.corrections[n] for n in DEFAULT_PARAMETERS])
                            / prob.scale)
    assert np.abs(dev).max() == pytest.approx(fit.fit_max_um, abs=1e-9)
    assert (np.abs(dev) >= fit.fit_max_um - 1e-4).sum() >= len(DEFAULT_PARAMETERS) + 1
    assert fit.fit_rms_um > 0.431
