"""Machine settings from a target flank (geometry.setting_fit, issue 27 item 4).

Truths:
- the blade through the pivot: the reparameterized blade passes through the pivot point
  with the requested profile angle, its tip radius and depth checked against a
  quadrature of the profile ODE ``rho' = -sigma sin(alpha)``, ``z' = cos(alpha)``
  (independent of the closed forms), also at a curvature of 1e-9 1/mm where the plain
  closed forms cancel;
- round trip: a pinion flank generated from known perturbed settings is recovered
  from the complementary seed (flank and settings);
- s0003: the complementary seed reproduces the conjugate pinion exactly (drive side,
  zero ease-off: corrections and residual ~0), and the coast flank with the analysed
  ease-off (22.9 um) is cut to a stated residual.
"""

import math

import numpy as np
import pytest
from design_space import design_space_candidate
from easeoff_grid import pivot_length_mm, write_grid_csv
from scipy.integrate import quad

from gearcontact.geometry.basic_settings import complementary_pinion_setups
from gearcontact.geometry.conjugate import nominal_pinion_box
from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.generated import generated_pinion_flank
from gearcontact.geometry.machine import BladeSettings, blade_profile
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.easeoff_settings import easeoff_machine_pair
from gearcontact.geometry.setting_fit import (_blade_through, _Pivot, apply_corrections,
                                              fit_pinion_setup, flank_deviation_um)
from gearcontact.validation import InputRangeError


@pytest.mark.parametrize("kind", ["inside", "outside"])
@pytest.mark.parametrize("k", [4e-3, -2e-2, 1e-9, 0.0])
def test_blade_through_pivot_against_quadrature(kind, k):
    blade = BladeSettings(kind, 20.0, 50.0, 0.1)
    pivot = _Pivot(rho_mm=48.0, z_mm=2.0, alpha_rad=math.radians(21.0), curvature_per_mm=0.0)
    alpha = math.radians(22.5)
    got = _blade_through(blade, pivot, alpha=alpha, k=k, rho=48.3)
    l_p = got.profile_reference_mm if k else 2.0 / math.cos(alpha)
    rho, z, a, _ = (float(x) for x in blade_profile(got, l_p))
    # the pivot, to rounding (1e-12 mm, 1e-14 rad)
    assert (rho, z, a) == pytest.approx((48.3, 2.0, alpha), abs=1e-12)
    # independent: integrate the profile ODE from the tip with alpha(l) = alpha + k (l - l_p)
    ang = lambda s: alpha + k * (s - l_p)  # noqa: E731
    z_q = quad(lambda s: math.cos(ang(s)), 0.0, l_p, epsabs=1e-14)[0]
    rho_q = got.point_radius_mm - blade.sigma * quad(lambda s: math.sin(ang(s)), 0.0, l_p,
                                                     epsabs=1e-14)[0]
    assert z_q == pytest.approx(2.0, abs=1e-11)
    assert rho_q == pytest.approx(48.3, abs=1e-11)


#: Known corrections of the round trip: of the size the s0003 coast ease-off needs.
_TRUE = {"cradle_angle_deg": -0.2, "radial_distance_mm": 0.2, "ratio_of_roll": 0.06,
         "modified_roll_2c_per_rad": 0.01, "modified_roll_6d_per_rad2": -0.02,
         "blade_angle_deg": -1.5, "blade_curvature_per_mm": 0.006,
         "blade_cubic_per_mm2": 0.009}


def test_round_trip_recovers_flank_and_settings():
    pair = load_pair("s0003")
    seed = complementary_pinion_setups(pair)["coast"]
    true = apply_corrections(seed, _TRUE, pivot_length_mm=pivot_length_mm(seed, pair.blank))
    target, _ = generated_pinion_flank(true, pair.blank, n_u=30, n_v=40,
                                       pinion_face_width_mm=pair.pinion_face_width_mm)
    fit = fit_pinion_setup(seed, pair.blank, target)
    assert fit.status > 0
    # flank: < 0.1 um (issue truth); measured 5.4e-4 um, the quintic interpolation error
    # of the 30 x 40 target sheet (6e-5 um ... 2e-5 um on 60 x 75)
    cut, _ = generated_pinion_flank(fit.setup, pair.blank, n_u=30, n_v=40,
                                    pinion_face_width_mm=pair.pinion_face_width_mm)
    _, _, dev = flank_deviation_um(cut, target)
    assert np.abs(dev).max() < 0.1
    assert fit.fit_max_um < 0.1
    # settings: each within 0.2 % of its perturbation; measured <= 3e-4 relative (6D,
    # the weakest direction: the target's interpolation error through the conditioning)
    for name, want in _TRUE.items():
        assert fit.corrections[name] == pytest.approx(want, rel=2e-3), name
    # the reach predicted before the search (the seed's deviation outside the span of
    # the sensitivities there, linear): reachable, within 0.15 um; the target is in
    # reach exactly, so what the prediction leaves is the fit's nonlinearity over these
    # corrections (blade angle 1.5 deg, ...): measured 0.093 um max, 0.032 um RMS
    assert fit.predicted_max_um < 0.15 and fit.predicted_rms_um < 0.05


def test_fit_refuses_bad_input():
    pair = load_pair("s0003")
    seed = complementary_pinion_setups(pair)["coast"]
    with pytest.raises(InputRangeError, match="parameters"):
        fit_pinion_setup(seed, pair.blank, None, parameters=("cradle_angle_deg", "spin"))
    with pytest.raises(InputRangeError, match="spin"):
        apply_corrections(seed, {"spin": 1.0}, pivot_length_mm=1.0)
    with pytest.raises(InputRangeError, match="n_u, n_v"):
        fit_pinion_setup(seed, pair.blank, load_pair_target(pair), n_u=2)


def load_pair_target(pair):
    """A stand-in target with the s0003 pinion box (the grid check comes first)."""
    class Target:
        boundary = nominal_pinion_box(pair.blank, pair.pinion_face_width_mm)[1]
    return Target()


@pytest.fixture(scope="module")
def s0003_fit():
    return easeoff_machine_pair(load_pair("s0003"))


def test_s0003_settings_cut_its_easeoff(s0003_fit):
    drive, coast = s0003_fit.sides["drive"], s0003_fit.sides["coast"]
    # drive: zero ease-off; the complementary seed is the conjugate pinion (3e-14 mm,
    # docs/machine_settings.md sec. 4): nothing to correct
    assert drive.max_um < 1e-6
    assert all(abs(x) < 1e-7 for x in drive.fit.corrections.values())
    # coast: the analysed ease-off (max |E| 22.9 um on its 41 x 41 box; the pair file's
    # header: 22.8 on the calibration's) cut to max 0.566 um / RMS 0.120 um (measured on
    # the session-16 re-bake of the preset, 22.6 / 0.560 / 0.119 on the earlier one,
    # docs/calibration.md; a circular blade left 1.23 /
    # 0.39 um, a fourth-order profile form that the blade's cubic profile term takes
    # out, docs/machine_settings.md sec. 6). Bound 0.7 / 0.15 um: 25 % over the
    # measured values (the fit stops at a relative change of 1e-12 in the sum of
    # squares; the margin covers the last digits of a different BLAS), well under the
    # circular blade's 1.23 / 0.39 um, so a lost cubic term fails the test
    assert coast.easeoff_max_um == pytest.approx(22.9, abs=0.1)
    assert coast.max_um < 0.7 and coast.rms_um < 0.15
    # condition 809 measured (741 without the cubic term)
    assert coast.fit.condition_number < 1e4
    # the reach predicted before the fit (linear projection residual at the seed)
    # against the fit on the same grid: 0.550 / 0.146 um against 0.565 / 0.150 um max /
    # RMS (measured); within 0.05 / 0.02 um, the fit's nonlinearity (0.093 um max in the
    # round trip above, whose corrections are larger); drive: nothing to reach (0)
    assert coast.fit.predicted_max_um == pytest.approx(coast.fit.fit_max_um, abs=0.05)
    assert coast.fit.predicted_rms_um == pytest.approx(coast.fit.fit_rms_um, abs=0.02)
    assert drive.fit.predicted_max_um < 1e-6
    pinion = {s.side: s for s in s0003_fit.pair.machine if s.member == "pinion"}
    blade = pinion["coast"].blade
    assert pinion["coast"].settings.modified_roll and blade.profile_radius_mm
    assert blade.profile_cubic_per_mm2 == pytest.approx(0.0091, abs=5e-4)


def _tca(pair):
    from gearcontact.tca.analysis import analyze_pair

    a, _ = analyze_pair(pair, side="coast", phases=61)
    pts = [m for m in a.cycle.path.points if not m.edge]
    slope = np.polyfit([m.v1 for m in pts], [m.u1 for m in pts], 1)[0]
    # surface-to-surface contacts (not on an edge): their profile position u1
    inner = np.array([m.u1 for m in pts if not m.edge_contact])
    return a, math.degrees(math.atan(slope)), inner


@pytest.mark.slow
def test_s0003_fitted_pair_tca_matches_todays(s0003_fit, tmp_path):
    # the written pair, read back, against today's s0003 (coast, the design side)
    from gearcontact.geometry.pair import pair_to_toml

    path = tmp_path / "cut.toml"
    path.write_text(pair_to_toml(s0003_fit.pair))
    today, ang0, in0 = _tca(load_pair("s0003"))
    cut, ang1, in1 = _tca(load_pair(path))
    # TE0 p-p: 3.02 today, 2.97 cut (measured; 3.31 with a circular blade). The
    # residual's effect bound: its spread over the flank over the lever of the gear at
    # P0 (35.7 mm), ~5 arcsec; the measured change is 0.045 arcsec, asserted < 0.2
    coast = s0003_fit.sides["coast"]
    spread = float(coast.residual_um.max() - coast.residual_um.min())
    bound = math.degrees(1e-3 * spread / 35.7) * 3600.0
    assert abs(cut.cycle.te0_pp_arcsec - today.cycle.te0_pp_arcsec) < min(0.2, bound)
    # path: along the face near the pinion tip (s0003's calibrated tip-edge bearing) in
    # both; measured 1.6 deg today, 1.1 deg cut: within 2 deg of lengthwise
    assert abs(ang0) < 2.0 and abs(ang1) < 2.0
    # ... and under the tip line, not on it: 193 surface contacts today, 191 cut, at
    # 0.054-0.441 / 0.149-0.395 mm under the tip (mean 0.243 / 0.250 mm). With a
    # circular blade (the +0.7 um of residual at the tip) every contact of the cut pair
    # was the pinion tip edge. Asserted: >= 90 % of today's surface contacts, the
    # nearest >= 0.1 mm under the tip, the mean within 0.03 mm of today's
    tip = float(build_flanks(load_pair(path)).pinion.side("coast").boundary.u_tip)
    assert len(in1) >= 0.9 * len(in0)
    assert (tip - in1).min() > 0.1
    assert abs(np.mean(in1) - np.mean(in0)) < 0.03


@pytest.mark.slow
def test_s0003_fitted_pair_loaded_te_within_the_residual(s0003_fit, tmp_path):
    # issue 27: the cut pair's LTCA "equals today's within the residual". Truth: the
    # gear is the same and the cut pinion's coast flank lies within eps = the fit's
    # largest residual of today's eased pinion, so every initial gap moves by at most
    # eps; the unloaded contact and the loaded balance at each gear rotation (a
    # positive elastic operator: a larger gap never takes more load) each move by at
    # most eps / lever, the loaded rotation theta = their difference by 2 eps / lever,
    # and so its mean and the loaded TE's peak-to-peak over a pitch (bound set before
    # the run; the smaller of the two reference levers). Same grid rule (cells per
    # field) on both, so its ~1 % discretization (ltca.lte) is common to both.
    # Rigid teeth, 64.5 N m, the TCA's 61 phases (coast, the design side). Measured
    # (session 21): mean rotation 54.585 -> 54.647 arcsec, TE_LCP p-p 10.42 -> 10.66
    # arcsec, bound 6.55 arcsec (eps 0.566 um, lever 35.63 mm); ~2 min.
    from gearcontact.geometry.pair import pair_to_toml
    from gearcontact.ltca.lte import loaded_te
    from gearcontact.tca.analysis import analyze_pair

    path = tmp_path / "cut.toml"
    path.write_text(pair_to_toml(s0003_fit.pair))
    runs = []
    for pair in (load_pair("s0003"), load_pair(path)):
        tca, flanks = analyze_pair(pair, side="coast", phases=61)
        runs.append(loaded_te(tca, flanks, pair, 64.5, side="coast"))
    today, cut = runs
    assert today.converged and cut.converged
    eps_mm = 1e-3 * s0003_fit.sides["coast"].max_um
    lever_mm = min(today.reference_lever_mm, cut.reference_lever_mm)
    bound = math.degrees(2.0 * eps_mm / lever_mm) * 3600.0
    assert abs(cut.rotation_lcp_arcsec.mean() - today.rotation_lcp_arcsec.mean()) < bound
    assert abs(cut.te_lcp_pp_arcsec - today.te_lcp_pp_arcsec) < bound


@pytest.fixture(scope="module")
def s0003_curved_fit():
    from gearcontact.tca.path_curvature import target_path_curvature

    pair = load_pair("s0003")
    return easeoff_machine_pair(pair, paths={"coast": target_path_curvature(pair, "coast")})


def _single_pair(pair):
    from gearcontact.ltca.pair_ltca import single_pair_ltca
    from gearcontact.tca.analysis import analyze_pair

    tca, flanks = analyze_pair(pair, side="coast", phases=61)
    return single_pair_ltca(tca, flanks, pair, 64.5, side="coast")


@pytest.fixture(scope="module")
def s0003_curved_cases(s0003_curved_fit, tmp_path_factory):
    from gearcontact.geometry.pair import pair_to_toml

    path = tmp_path_factory.mktemp("curved") / "cut.toml"
    path.write_text(pair_to_toml(s0003_curved_fit.pair))
    return _single_pair(load_pair("s0003")), _single_pair(load_pair(path))


@pytest.mark.slow
def test_s0003_fitted_pair_hertz_pressure_within_the_curvature_bound(s0003_curved_fit,
                                                                    s0003_curved_cases):
    # issue 27: the cut pair's LTCA "equals today's within the residual", for the
    # contact pressure. The bound declared in docs/machine_settings.md sec. 6 ("The
    # residual's curvature and the pressure it bounds"): the half relative curvatures
    # move by at most a factor 1 +- e and the Hertz peak pressure at the same load by
    # at most 1 - (1 - e)^(2/3), e the residual's largest relative curvature error over
    # the target's contact path (the cut pair's P0 lies on it; the bound checked
    # against analytic.hertz in tests/geometry/test_residual_curvature.py). The fit
    # carried the curvature rows and V_1 (design --contact-curvature).
    coast = s0003_curved_fit.sides["coast"]
    assert coast.curvature_fitted and coast.path is not None
    # what the rows cost in the gap: within the plain fit's asserted 0.7 / 0.15 um
    # max / RMS (measured 0.431 / 0.127 against 0.566 / 0.120 um)
    assert coast.max_um < 0.7 and coast.rms_um < 0.15
    # measured e 0.130 over the path (0.087 at P0): bound 8.9 %; without the rows
    # e 0.208 (14.4 %): the rows must tighten it below 10 %
    e, bound = coast.path.max_error, coast.path.pressure_bound
    assert bound < 0.10
    today, cut = s0003_curved_cases
    # measured: B- 0.000967 -> 0.001028 (+6.3 %, the plain fit +12 %), preview p_max
    # 1448.7 -> 1480.9 MPa (+2.2 %, the plain fit +3.5 %)
    b0, b1 = (c.preview.B_minus_per_mm for c in (today, cut))
    assert abs(b1 / b0 - 1.0) <= e
    assert abs(cut.preview.p_max_mpa / today.preview.p_max_mpa - 1.0) <= bound


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="the single-pair LCP at s0003's P0 is an edge-loaded "
                   "patch at the pinion tip whose loaded area (3.9 mm lengthwise, where the "
                   "gap is not its quadratic at P0) grows by 12 % in the cut pair: -13.2 % "
                   "against the 8.9 % Hertz bound at P0's curvature (docs/machine_settings.md "
                   "sec. 6)")
def test_s0003_fitted_pair_lcp_p90_within_the_curvature_bound(s0003_curved_fit,
                                                             s0003_curved_cases):
    # the same declared bound for the LCP's p90 at P0 (measured 2227.6 -> 1934.6 MPa)
    today, cut = s0003_curved_cases
    bound = s0003_curved_fit.sides["coast"].path.pressure_bound
    assert abs(cut.patch.p90_mpa / today.patch.p90_mpa - 1.0) <= bound


def test_measured_grid_reproduces_the_polynomial_target(tmp_path):
    # a bicubic spline through samples of the (quadratic) ease-off is the ease-off
    # itself: the eased flank from the CSV equals build_flanks' to rounding (1e-15 rad
    # measured, asserted 1e-12 rad ~ 1e-11 mm at R ~ 9 mm)
    from gearcontact.geometry.easeoff import apply_easeoff, read_easeoff_grid
    from gearcontact.geometry.flank import build_flanks

    pair = load_pair("s0003")
    flanks = build_flanks(pair)
    grid = read_easeoff_grid(write_grid_csv(tmp_path / "g.csv", pair, flanks, "coast"))
    assert list(grid) == ["coast"]
    eased = apply_easeoff(flanks.pinion_conjugate.coast, grid["coast"],
                          limit_um=flanks.easeoff_limit_um)
    assert np.abs(eased.psi_nodes - flanks.pinion.coast.psi_nodes).max() < 1e-12
    # a grid short of the flank (0.5 mm under the tip) is refused (easeoff_machine_pair
    # runs this check before any fit)
    short = read_easeoff_grid(write_grid_csv(tmp_path / "s.csv", pair, flanks, "coast", pad=0.5))
    with pytest.raises(InputRangeError, match="covering the active flank"):
        short["coast"].check_covers(flanks.pinion_conjugate.coast.boundary, where="coast")
    with pytest.raises(InputRangeError, match="easeoff_grid"):
        easeoff_machine_pair(pair, easeoff_grid={"flank": short["coast"]})


@pytest.mark.parametrize("text, match", [
    ("side,u_mm,v_mm,easeoff_um\n", "header"),
    ("side,v_mm,u_mm,easeoff_um\nflank,1,2,3\n", "row 2"),
    ("side,v_mm,u_mm,easeoff_um\ncoast,1,2,nan\n", "finite"),
    ("side,v_mm,u_mm,easeoff_um\n" + "".join(f"coast,{v},{u},0\n" for u in range(4)
                                             for v in range(4) if (u, v) != (3, 3)),
     "complete grid"),
])
def test_measured_grid_refuses_bad_files(tmp_path, text, match):
    from gearcontact.geometry.easeoff import read_easeoff_grid

    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(InputRangeError, match=match):
        read_easeoff_grid(path)


def test_cradle_angle_is_a_rigid_turn_about_the_work_axis():
    # with a linear roll, q -> q + d is the roll psi + d: the generated flank turns by
    # R_a d about the work axis, so the sensitivity column of the cradle angle is
    # R_a * (1e-3 deg in rad) times the lever R (e_psi . n) of every node (exact in
    # d; measured relative spread 5e-8: the envelope solves' rounding through the
    # forward difference), asserted to 1e-6
    from gearcontact.geometry.setting_fit import fit_grid, FitProblem, sensitivity

    pair = load_pair("s0003")
    seed = complementary_pinion_setups(pair)["drive"]
    target, _ = generated_pinion_flank(seed, pair.blank, n_u=20, n_v=25,
                                       pinion_face_width_mm=pair.pinion_face_width_mm)
    jac, names = sensitivity(seed, pair.blank, target, names=("cradle_angle_deg",), n_u=5,
                             n_v=6)
    lever = FitProblem(seed, pair.blank, target, names,
                     *fit_grid(target.boundary, 5, 6)).lever_um.ravel()
    want = seed.settings.ratio_of_roll * math.radians(1e-3)
    assert jac[:, 0] / lever == pytest.approx(np.full(30, want), rel=1e-6)


@pytest.mark.slow       # generated gear, two seed fits, two fits, two full flanks: ~90 s
def test_easeoff_of_a_generated_hypoid_is_cut_from_the_conjugate_seed():
    # 13/26, E = 21.3 mm (tests/design_space.py) gets a generated gear; its crown gear's
    # pinion is a point-contact conjugate 115 / 74 um off the line-contact conjugate at
    # a corner (drive / coast). From it the fit did not reach the crowned target (drive
    # ended on an unreached step after 792 evaluations, coast at 62 um; turned first,
    # 19.1 / 9.4 um max). conjugate_seed fits the crown pinion to the conjugate (turn,
    # then SEED_PARAMETERS), the default fit starts there. Truth: the residual of the
    # cut flank against the target (the conjugate pinion + the 10 um crowning ease-off),
    # measured on the full generated flank (120 x 150) by flank_deviation_um, an
    # independent dense grid. Measured 3.78 / 1.52 um max, 0.78 / 0.42 um RMS;
    # asserted with ~20 % margin for the trust region's path on another machine
    # (platform floating point), and well below the crown pinion's 19.1 / 9.4 um
    pair = design_space_candidate(13, 2.0, 0.3, 35.0, 0.3, "drive")   # crowned ease-off
    got = easeoff_machine_pair(pair)
    for side, max_um, rms_um in (("drive", 4.5, 1.0), ("coast", 2.0, 0.55)):
        r = got.sides[side]
        assert r.easeoff_max_um > 5.0          # a target off the conjugate
        assert r.max_um < max_um and r.rms_um < rms_um, (side, r.max_um, r.rms_um)
    assert got.pair.machine[0].settings.ratio_of_roll > 0.0   # the gear stays generated


def test_minimax_fit_of_s0003_coast():
    # objective="minimax" (geometry.minimax_fit from the least-squares solution) on the
    # s0003 coast target (30 x 40 conjugate sheet + ease-off, the default 8 parameters,
    # 9 x 11 grid; ~4 s). Truths: (a) the largest deviation on the fit grid falls below
    # the least-squares fit's (measured 0.293 against 0.560 um; asserted < 0.35 um);
    # (b) Chebyshev alternation, the optimality condition of a minimax fit with n free
    # parameters: at least n + 1 = 9 grid nodes reach the maximum (to 1e-4 um; measured
    # 9, against 1 for the least-squares fit); (c) the fit's RMS is not below the least
    # squares' (0.148 um, its optimum: measured 0.181 um)
    from gearcontact.geometry.setting_fit import DEFAULT_PARAMETERS, fit_grid, FitProblem

    pair = load_pair("s0003")
    target = build_flanks(pair, n_u=30, n_v=40).pinion.side("coast")
    seed = complementary_pinion_setups(pair)["coast"]
    fit = fit_pinion_setup(seed, pair.blank, target, objective="minimax")
    assert fit.objective == "minimax"
    assert fit.rms_fit_max_um == pytest.approx(0.560, abs=0.01)
    assert fit.fit_max_um < 0.35
    prob = FitProblem(seed, pair.blank, target, DEFAULT_PARAMETERS,
                    *fit_grid(target.boundary, 9, 11))
    dev = prob.deviation_um(np.array([fit.corrections[n] for n in DEFAULT_PARAMETERS])
                            / prob.scale)
    assert np.abs(dev).max() == pytest.approx(fit.fit_max_um, abs=1e-9)
    assert (np.abs(dev) >= fit.fit_max_um - 1e-4).sum() >= len(DEFAULT_PARAMETERS) + 1
    assert fit.fit_rms_um > 0.148
    with pytest.raises(InputRangeError, match="objective"):
        fit_pinion_setup(seed, pair.blank, target, objective="max")
