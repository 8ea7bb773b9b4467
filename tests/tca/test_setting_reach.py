"""Reach model of the local setting synthesis (tca.setting_reach).

Truths: the closed forms of a quadratic ease-off at M (Litvin & Fuentes 2004, sec. 9.2;
the module docstring): an ease-off Hessian linear in the corrections gives back the
corrections of any target exactly; a path along the contact line needs an infinite
correction (refused for certain); and on the 13/26 hypoid (tests/design_space.py:
generated_hypoid) the corrections the model predicts meet the targets when the real
local TCA is run at them, and agree with the ones the synthesis finds (slow: the
synthesis itself, which from the standard crowning missed the drive -35.6 deg of
docs/machine_settings.md sec. 5 and now starts from the model).
"""

import math

import numpy as np
import pytest

from gearcontact.tca.setting_reach import (MAX_STEPS, ReachModel, chord_step, reach_model,
                                            target_misses)
from gearcontact.tca.setting_synthesis import _SCALE, synthesize_settings
from gearcontact.tca.synthesis import SynthesisTargets
from gearcontact.validation import InputRangeError

#: A quadratic ease-off at M: paint film (mm), the level (arcsec) per det H / H_ll, the
#: contact line's angle (deg), the Hessian (l, m frame, 1/mm) at x = 0 and per
#: unit of each correction (1/mm): made up, of the size of the 13/26 hypoid's.
#: unit of each correction (roll curvature 1, blade curvature 1/mm, radius mm): of the
#: size the model fits on the 13/26 hypoid's coast side (path -84 deg at the start).
DELTA, K, LINE = 0.006, 17361.0, -9.3
H0 = np.array([[3.3e-4, 0.9e-4], [0.9e-4, 1.3e-3]])
DH = [np.array([[0.0, -1.4e-3], [-1.4e-3, 0.077]]), np.array([[0.029, 0.18], [0.18, 0.5]]),
      np.array([[-1.9e-4, 3.0e-5], [3.0e-5, 1.0e-4]])]


def _quadratic_contact(x):
    """(level arcsec, ellipse 2a mm, path deg, ellipse axis deg) of ``H0 + sum x_i DH_i``
    from the closed forms: (2a)^2 = 8 delta / H_ll, cot psi = -H_lm / H_ll, level
    = K det H / H_ll."""
    h = H0 + sum(xi * d for xi, d in zip(x, DH))
    psi = math.degrees(math.atan2(h[0, 0], -h[0, 1]))
    path = (LINE + psi + 90.0) % 180.0 - 90.0
    return (K * np.linalg.det(h) / h[0, 0], math.sqrt(8.0 * DELTA / h[0, 0]), path, LINE)


def _quadratic_model(x0=(0.0, 0.0, 0.0), *, radius=60.0, psi_m=-0.01):
    x0 = np.asarray(x0, float)
    scales = np.array([1e-3, 2e-4, 0.2])
    step = 5.0
    start = _quadratic_contact(x0)
    plus = [_quadratic_contact(x0 + step * scales * e) for e in np.eye(3)]
    minus = [_quadratic_contact(x0 - step * scales * e) for e in np.eye(3)]
    return ReachModel.from_evaluations("coast", x0, scales, start, plus, minus,
                                       psi_m_rad=psi_m, point_radius_mm=radius, step=step)


def test_quadratic_easeoff_gives_back_the_corrections_of_any_target():
    # with H linear in the corrections the coordinates are exactly linear: the fitted
    # level scale is 1 / (8 delta K) and every target's corrections meet it to
    # rounding (1e-9 relative / deg), across the path angles either side of the line
    # (not vacuous: the start's level, ellipse and path are 21 arcsec, 12 mm, -84 deg)
    model = _quadratic_model()
    assert model.level_scale == pytest.approx(1.0 / (8.0 * DELTA * K), rel=1e-9)
    for angle in (-80.0, -38.0, -20.0, 5.0, 40.0, 85.0):
        t = SynthesisTargets(te0_pp_arcsec=3.0, path_angle_deg=angle)
        p = model.predict(t, length_mm=9.0)
        level, length, path, _ = _quadratic_contact(p.x)
        assert level == pytest.approx(3.0, rel=1e-9)
        assert length == pytest.approx(9.0, rel=1e-9)
        assert abs((path - angle + 90.0) % 180.0 - 90.0) < 1e-7
        assert p.residual < 1e-6 and not p.limit
        assert p.verdict == ("reachable" if p.step_scales <= MAX_STEPS
                             else "beyond the model's range")
        assert p.predicted[2] == pytest.approx(angle, abs=1e-7)


def test_one_chord_step_lands_on_the_target_where_the_coordinates_are_linear():
    # the chord step applies the model's Jacobian to the miss in y measured at x: with y
    # exactly linear (the quadratic ease-off) one step from anywhere is the solution
    # (1e-9 of the corrections: rounding of the 3 x 3 solve)
    model = _quadratic_model()
    t = SynthesisTargets(te0_pp_arcsec=3.0, path_angle_deg=-38.0)
    p = model.predict(t, length_mm=9.0)
    x = p.x + np.array([0.01, -0.001, 0.3])
    level, length, path, _ = _quadratic_contact(x)
    x1 = chord_step(model, p, x, (level, length, path), targets=t, length_mm=9.0)
    assert np.abs((x1 - p.x) / model.scales).max() < 1e-6


def test_a_path_along_the_contact_line_is_refused_for_certain():
    # psi -> 0 needs H_lm -> infinity: at 0.01 deg from the line a hard limit of the
    # settings is crossed within 1 % of the step, so the refusal is certain; 10 deg from
    # it the step is inside the limits (not refused: it is not certain)
    model = _quadratic_model()
    near = model.predict(SynthesisTargets(path_angle_deg=LINE + 0.01), length_mm=9.0)
    assert near.certain and not near.reachable and near.share < 0.01
    assert "of the step" in near.limit
    off = model.predict(SynthesisTargets(path_angle_deg=LINE + 10.0), length_mm=9.0)
    assert not off.certain and not off.limit
    with pytest.raises(InputRangeError, match="path_angle_deg"):
        model.predict(SynthesisTargets(), length_mm=9.0)


@pytest.fixture(scope="module")
def problem(generated_hypoid_problem):
    return generated_hypoid_problem


def test_predicted_corrections_meet_a_coast_target(problem):
    # ~10 s (seven local TCAs for the model, one at its corrections). Coast -70 deg (8
    # scale steps from the standard crowning): the real local TCA at the predicted
    # corrections meets all three targets within the synthesis' tolerances (5 %, 5 %,
    # 2 deg; measured: residual 0.49 of them), and the corrections are the synthesis'
    # (recorded, 40 x 50 nodes, docs/machine_settings.md sec. 5: roll curvature
    # +0.00233, blade -0.000396 /mm, radius -2.839 mm) within 31 % of the 8-step
    # prediction per correction (the largest error measured, coast 10 deg; here 5 %)
    model = reach_model(problem, "coast", scales=_SCALE)
    length = 0.35 * problem.pair.gear_face_width_mm
    t = SynthesisTargets(path_angle_deg=-70.0)
    p = model.predict(t, length_mm=length)
    assert p.verdict == "reachable" and p.step_scales < 10
    m = problem.contact("coast", p.x)
    sign = math.copysign(1.0, problem.contact("coast", problem.standard["coast"])
                         .te_curvature_arcsec_per_rad2)
    level = sign * math.copysign(m.te_level_arcsec, m.te_curvature_arcsec_per_rad2)
    r = target_misses(t, length, level, m.point.paint_length_mm, m.point.path_angle_deg)
    assert np.abs(r).max() <= 1.0, r
    found = np.array([0.00233, -0.000396, -2.839])
    assert (np.abs(p.x - found) / _SCALE).max() < 0.31 * p.step_scales
    # along the contact line (the start's ellipse axis, -9.3 deg) the refusal is certain
    line = model.predict(SynthesisTargets(path_angle_deg=round(model.line_angle_deg, 1)),
                         length_mm=length)
    assert abs(model.line_angle_deg + 9.3) < 0.5 and line.certain
    assert line.verdict == "out of reach (certain)"


@pytest.mark.slow
def test_synthesis_meets_the_drive_target_the_model_predicts(problem):
    # drive -35.6 deg: from the standard crowning the synthesis missed it (path -4.3 deg,
    # ellipse 10.0 mm: another basin); the model predicts it reachable (140 scale steps)
    # and, started from its corrections, the synthesis meets all three targets; the
    # predicted corrections are those found within 10 % of the roll curvature and the
    # blade curvature and 0.5 mm of the radius (measured 5 % / 4 % / 0.35 mm); ~2-3 min
    done = synthesize_settings(problem.pair, targets={"drive": SynthesisTargets(
        path_angle_deg=-35.6)}, sides=("drive",), phases=7, problem=problem)["drive"]
    assert done.reach.reachable and not done.reach.certain
    assert done.met and done.residual < 1.0
    assert abs(done.reach.x[0] - done.x[0]) < 0.1 * abs(done.x[0])
    assert abs(done.reach.x[1] - done.x[1]) < 0.1 * abs(done.x[1])
    assert abs(done.reach.x[2] - done.x[2]) < 0.5
