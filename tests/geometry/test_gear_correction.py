"""Gear machine-setting correction from a measured gear flank (geometry.gear_correction,
geometry.setting_fit for either member; issue 27 item 4, docs/machine_settings.md sec. 6
"Gear flanks").

Truths:
- self-consistency: a gear cut from its nominal settings with known perturbations
  (formate: the ISO 23509 F.2 spiral bevel of examples/machine_settings and the 11/41
  hypoid's formate gear; generated: the 11/41 hypoid's gear rolled on its crown gear),
  measured on the nominal CMM grid as the deviation CSV ``design --target-flank``
  takes, fitted from the nominal settings: every correction within the first-order
  bound of the data's own error through the fit's Jacobian, the residual at the
  points < 0.01 um;
- identifiability: on a formate gear with a straight blade and no tilt the sliding
  base moves the cutter along its axis, which moves the blade cone exactly as a cutter
  radius change of ``tan(alpha)`` times as much: their sensitivity columns are
  parallel (a closed form, independent of the fit); such a pair of settings is refused
  naming both, not fitted;
- the pinion path of the generalised fit: the same solver, sheet and lever as before
  (structure, bit for bit; the fits themselves were compared with the code before the
  generalisation in one process, docs/machine_settings.md sec. 6).
"""

import math

import numpy as np
import pytest
from easeoff_grid import (GEAR_FORMATE_PERTURBATION, GEAR_GENERATED_PERTURBATION,
                         member_pivot_length_mm, write_gear_measured_csv)

from gearcontact.geometry.basic_settings import formate_gear_setups, generated_gear_setups
from gearcontact.geometry.conjugate import nominal_pinion_box
from gearcontact.geometry.gear_correction import gear_correction, gear_seeds
from gearcontact.geometry.generated import (EnvelopeSolver, gear_cone, gear_flank_of,
                                            generated_gear_flank)
from gearcontact.geometry.machine import mirror_setup
from gearcontact.geometry.measuring_grid import (MeasuredFlank, measured_points,
                                                 measuring_grid, read_member_targets)
from gearcontact.geometry.member_envelope import (FormateSolver, angle_lever, member_cone,
                                                  member_solver)
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.point_fit import PointProblem
from gearcontact.geometry.setting_fit import (FORMATE_GEAR_PARAMETERS,
                                              GENERATED_GEAR_PARAMETERS, FitProblem,
                                              fit_grid, apply_corrections,
                                              default_parameters, fit_member_setup)
from gearcontact.validation import InputRangeError

F2 = "examples/machine_settings/iso23509_f2_machine.toml"
HYPOID = "examples/hypoid_11x41_rear_axle.toml"

#: Known perturbations, each moving the flank by ~1-10 um (a measured gear's size).
_FORMATE, _GENERATED = GEAR_FORMATE_PERTURBATION, GEAR_GENERATED_PERTURBATION


def _case(which, side):
    if which == "f2 formate":
        pair = load_pair(F2)
        return pair, gear_seeds(pair, "formate")[side], _FORMATE
    pair = load_pair(HYPOID)
    if which == "hypoid formate":
        return pair, formate_gear_setups(pair)[side], _FORMATE
    return pair, generated_gear_setups(pair)[side], _GENERATED


@pytest.mark.parametrize("which, side", [("f2 formate", "drive"), ("f2 formate", "coast"),
                                         ("hypoid formate", "coast"),
                                         ("hypoid generated", "drive")])
def test_gear_cut_from_perturbed_settings_is_recovered_from_its_csv(tmp_path, which, side):
    # ~1 s per formate case, ~3 s for the generated gear (two 60 x 75 sheets, the fit)
    pair, seed, pert = _case(which, side)
    assert seed.settings.formate == (which != "hypoid generated")
    names = default_parameters(seed)
    assert set(pert) == set(names)
    true = apply_corrections(seed, pert, pivot_length_mm=member_pivot_length_mm(seed, pair.blank))
    path = tmp_path / "gear.csv"
    _, dev = write_gear_measured_csv(path, pair, seed, true, side)
    assert np.abs(dev).max() > 5.0                     # a target well off the nominal
    pinion_rows, gear_rows = read_member_targets(path, pair=pair)
    assert pinion_rows == {} and set(gear_rows) == {side}

    done = gear_correction(pair, gear_rows, seeds={side: seed})
    r = done.sides[side]
    assert r.fit.status > 0
    # the residual at the 99 points: < 0.01 um (measured 3e-11 .. 5e-10 um), and over
    # the flank (the bicubic through the grid's deviations, 60 x 75 points: its
    # interpolation error of the smooth deviation, measured 1.6e-7 .. 4.7e-5 um)
    assert r.fit.fit_max_um < 0.01
    assert r.flank_max_um < 0.01
    # Tolerance of each setting: the data's own error e (the points against the cut
    # flank as the fit solves it: a formate gear's exact cone against its node solver,
    # ~6e-11 um; the generated gear's 60 x 75 sheet, ~6e-9 um) moves the least-squares
    # solution by J^+ e to first order, so |x_i - x_true,i| <= |row_i(J^+)| |e|
    # (Cauchy-Schwarz, J the scaled Jacobian at the solution), as
    # tests/geometry/test_setting_fit_relieved.py; measured 0.01 to 0.3 of the bound.
    prob = PointProblem(seed, pair.blank, r.points, names)
    x = np.array([r.fit.corrections[n] for n in names]) / prob.scale
    jac = prob.jacobian(x)
    e = PointProblem(true, pair.blank, r.points, names).deviation_um(np.zeros(len(names)))
    bound = prob.scale * np.linalg.norm(np.linalg.pinv(jac), axis=1) * np.linalg.norm(e)
    for name, b in zip(names, bound):
        assert abs(r.fit.corrections[name] - pert[name]) <= b, (name, r.fit.corrections[name],
                                                                 pert[name], b)
    assert done.setups[side] == r.fit.setup
    assert done.setups[side].settings.formate == seed.settings.formate


def test_left_hand_pair_is_its_twin_mirrored(tmp_path):
    # A left-hand F.2 pair (the blank's formate gear): its gear measured on a CMM reads
    # the same L, R and normal deviations as its right-hand twin's (the mirror image
    # y -> -y, docs/export.md). The twin's gear cut with the perturbation, measured,
    # fitted on the left-hand pair: the settings are the mirror image of the twin's cut
    # settings (machine.mirror_setup: cradle angle and blank offset change sign), each
    # within the first-order bound of the twin's fit (< 2e-11 here, test above), taken
    # as 1e-9 (mm, deg); ~1 s.
    text = open("examples/iso23509_f2_spiral_bevel.toml").read()
    left_file = tmp_path / "left.toml"
    left_file.write_text(text.replace('pinion_hand = "right"', 'pinion_hand = "left"'))
    left, right = load_pair(left_file), load_pair("examples/iso23509_f2_spiral_bevel.toml")
    assert left.pinion_hand == "left"
    seed = gear_seeds(right, "formate")["drive"]
    assert gear_seeds(left, "formate")["drive"] == mirror_setup(seed)
    true = apply_corrections(seed, _FORMATE,
                             pivot_length_mm=member_pivot_length_mm(seed, right.blank))
    path = tmp_path / "gear.csv"
    write_gear_measured_csv(path, right, seed, true, "drive")
    _, rows = read_member_targets(path)
    got = gear_correction(left, rows, seeds=gear_seeds(left, "formate")).setups["drive"]
    want = mirror_setup(true)
    assert want.settings.cradle_angle_deg == -true.settings.cradle_angle_deg
    for f in ("radial_distance_mm", "cradle_angle_deg", "machine_root_angle_deg",
              "machine_centre_to_back_mm", "sliding_base_mm", "blank_offset_mm"):
        assert abs(getattr(got.settings, f) - getattr(want.settings, f)) < 1e-9, f
    for f in ("blade_angle_deg", "point_radius_mm"):
        assert abs(getattr(got.blade, f) - getattr(want.blade, f)) < 1e-9, f


def _zero_points(pair, seed, side):
    nominal = gear_flank_of(seed, pair.blank, gear_face_width_mm=pair.gear_face_width_mm)
    g = measuring_grid(nominal, member="gear", flank=side, rows=9, cols=11)
    m = MeasuredFlank(member="gear", flank=side, L_mm=g.L_mm, R_mm=g.R_mm,
                      deviation_um=np.zeros(len(g.L_mm)), line=np.arange(2, 2 + len(g.L_mm)))
    return m, measured_points(m, nominal, where="x", uv=(g.u_mm, g.v_mm),
                              cone=gear_cone(pair.blank))


def test_generated_gear_sheet_target_on_the_fit_grid():
    # fit_member_setup's grid path for a gear: the target a 60 x 75 generated gear sheet
    # cut with known perturbations (the hypoid's generated gear, drive), the default
    # seven from the nominal; settings within the first-order bound of the target's
    # own error on the 9 x 11 fit grid (the sheet against the exact envelope there), as
    # above; ~3 s. A formate gear's FormateFlank (its own (u, v)) is refused as target.
    pair, seed, pert = _case("hypoid generated", "drive")
    names = default_parameters(seed)
    true = apply_corrections(seed, pert, pivot_length_mm=member_pivot_length_mm(seed, pair.blank))
    target, _ = generated_gear_flank(true, pair.blank, n_u=60, n_v=75,
                                     gear_face_width_mm=pair.gear_face_width_mm)
    fit = fit_member_setup(seed, pair.blank, target)
    assert fit.status > 0 and fit.fit_max_um < 0.01
    grid = fit_grid(target.boundary, 9, 11)
    prob = FitProblem(seed, pair.blank, target, names, *grid)
    x = np.array([fit.corrections[n] for n in names]) / prob.scale
    jac = prob.jacobian(x)
    e = FitProblem(true, pair.blank, target, names, *grid).deviation_um(np.zeros(len(names)))
    bound = prob.scale * np.linalg.norm(np.linalg.pinv(jac), axis=1) * np.linalg.norm(e)
    for name, b in zip(names, bound):
        assert abs(fit.corrections[name] - pert[name]) <= b, (name, fit.corrections[name], b)
    formate = load_pair(F2)
    gear = gear_seeds(formate, "formate")["drive"]
    cone = gear_flank_of(gear, formate.blank, gear_face_width_mm=formate.gear_face_width_mm)
    with pytest.raises(InputRangeError, match="target = 'FormateFlank'.*gear sheet"):
        fit_member_setup(gear, formate.blank, cone)


def test_formate_sliding_base_and_cutter_radius_are_one_direction_and_refused():
    # The F.2 formate gear (straight blade, tilt 0): a sliding base step dX moves the
    # blade cone along the cutter axis, the same cone as a cutter radius step of
    # -sigma tan(alpha) dX at the pivot (the cone rho(z) = rho_0 - sigma z tan(alpha),
    # depth measured from the tip plane): the two sensitivity columns are parallel with
    # the ratio tan(alpha) x their scales (both 1e-3 mm), a closed form; to 1e-6
    # relative (the forward differences' truncation, step 1e-6 mm of the flank).
    pair = load_pair(F2)
    seed = gear_seeds(pair, "formate")["drive"]
    m, pts = _zero_points(pair, seed, "drive")
    names = ("sliding_base_mm", "blade_radius_mm")
    jac = PointProblem(seed, pair.blank, pts, names).jacobian(np.zeros(2))
    ratio = jac[:, 0] / jac[:, 1]
    alpha = math.radians(seed.blade.blade_angle_deg)
    assert np.abs(np.abs(ratio) - math.tan(alpha)).max() < 1e-6 * math.tan(alpha)
    # refused before any fit, naming both settings and the singular value
    with pytest.raises(InputRangeError) as exc:
        gear_correction(pair, {"drive": m}, seeds={"drive": seed},
                        parameters=FORMATE_GEAR_PARAMETERS + ("sliding_base_mm",))
    msg = str(exc.value)
    assert "rank-deficient" in msg and "sliding_base_mm" in msg and "blade_radius_mm" in msg


def test_default_subsets_are_separable_and_reported():
    # the default subsets pass the identifiability check (smallest relative singular
    # value of the column-normalized sensitivity >= 1e-4, point_fit.RANK_TOLERANCE),
    # and the fit reports that value: F.2 formate drive and the hypoid's generated gear
    pair = load_pair(F2)
    seed = gear_seeds(pair, "formate")["drive"]
    m, _ = _zero_points(pair, seed, "drive")
    r = gear_correction(pair, {"drive": m}, seeds={"drive": seed}).sides["drive"]
    assert 1e-4 <= r.relative_singular_value < 1.0
    assert r.fit.fit_max_um < 1e-6          # the nominal itself: nothing to correct
    assert max(abs(v) for v in r.fit.corrections.values()) < 1e-9


@pytest.mark.parametrize("name", ["ratio_of_roll", "blade_curvature_per_mm",
                                  "modified_roll_2c_per_rad"])
def test_formate_gear_refuses_roll_and_curvature(name):
    pair = load_pair(F2)
    seed = gear_seeds(pair, "formate")["drive"]
    with pytest.raises(InputRangeError, match=f"formate gear.*{name}"):
        fit_member_setup(seed, pair.blank, None, parameters=("blade_angle_deg", name))


def test_default_parameters_by_member_and_method():
    pair = load_pair(HYPOID)
    assert default_parameters(formate_gear_setups(pair)["drive"]) == FORMATE_GEAR_PARAMETERS
    assert default_parameters(generated_gear_setups(pair)["drive"]) == \
        GENERATED_GEAR_PARAMETERS


def test_pinion_path_uses_the_same_sheet_solver_and_lever_as_before():
    # the generalisation's member switches, pinion side: the blank's pinion cone, the
    # envelope solver itself (not a subclass), and the lever R (e_psi . n) of the former
    # inline formula, bit for bit (exact equality)
    pair = load_pair("s0003")
    cone = member_cone("pinion", pair.blank)
    assert cone == nominal_pinion_box(pair.blank, 1.0)[0]
    setup = formate_gear_setups(pair)["drive"]
    assert type(member_solver(setup, pair.blank, member_cone("gear", pair.blank))) is \
        FormateSolver
    rng = np.random.default_rng(3)
    r, n = rng.normal(size=(7, 5, 3)), rng.normal(size=(7, 5, 3))
    psi, lever = angle_lever("pinion", r, n)
    psi_old = np.arctan2(r[..., 2], r[..., 1])
    rad = np.hypot(r[..., 1], r[..., 2])
    e_psi = np.stack([np.zeros_like(rad), -np.sin(psi_old), np.cos(psi_old)], -1)
    assert np.array_equal(psi, psi_old)
    assert np.array_equal(lever, 1e3 * rad * np.einsum("...i,...i->...", e_psi, n))
    from gearcontact.geometry.basic_settings import complementary_pinion_setups

    pin = complementary_pinion_setups(pair)["coast"]
    assert type(member_solver(pin, pair.blank, cone)) is EnvelopeSolver


def test_formate_solver_is_the_formate_flank():
    # the formate gear's node solver (roll held at 0) against the exact blade cone of
    # generated.formate_gear_flank (an independent closed form, FormateFlank): the
    # cone's points on the CMM grid are on the solved flank to 1e-6 um along the normal
    # (the node equations are solved to 1e-10 mm in height and radius, ~1e-7 um along
    # the normal; measured 6e-11 um)
    pair = load_pair(F2)
    seed = gear_seeds(pair, "formate")["coast"]
    _, pts = _zero_points(pair, seed, "coast")        # points of the exact cone
    e = PointProblem(seed, pair.blank, pts, ("blade_angle_deg",)).deviation_um(np.zeros(1))
    assert np.abs(e).max() < 1e-6          # um
