"""The pinion of a typed spiral bevel gear cut with modified roll, fitted to the gear's
conjugate pinion (geometry.typed_pinion_fit; issue 27, docs/machine_settings.md sec. 5,
"A typed spiral bevel gear with modified roll: the pinion fitted to its conjugate").

Truths, declared before measuring (docs sec. 5):

(a) the fit's target and residual: on the blank's own generated spiral bevel gear (linear
    roll, the cradle axis the instantaneous axis of both relative motions) the derived
    pinion is the gear's line-contact conjugate (three-surface tangency, Litvin & Fuentes
    2004 sec. 20.2; test_typed_pinion_motion.py), so its residual angle against the
    conjugate target vanishes up to the target's own spline error (exact meshing nodes at
    its cell centres, measured in the same process) doubled;
(b) the first-order bound: the uncrowned fitted pinion's TE0 p-p is at most
    (z1/z2)(max dpsi - min dpsi) + 1e-4 arcsec (the TCA's conjugacy tolerance), dpsi
    the residual angle of the pinion against the conjugate, spline error included
    (slow; through the CLI in tests/cli/test_design_typed_motion.py);
(c) only a spiral bevel's generated gear with a modified roll or helical motion is fitted:
    a hypoid's derived pinion is conjugate and stays as it was (no fit, the same tables);
(d) the bound on the contact lines (session 27, declared before measuring): the envelope's
    lower term on a grid whose lines and values are known in closed form, and, on the
    linear-roll gear of (a), a bound that vanishes for the exactly conjugate pinion.
"""

import dataclasses
import warnings

import numpy as np
import pytest
from geometry.test_typed_pinion import F2, _quiet_load
from geometry.test_typed_pinion_motion import modified_gear

from gearcontact.errors import CheckFailed
from gearcontact.geometry import typed_pinion_fit
from gearcontact.geometry.basic_settings import standard_machine_pair
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.typed_pinion import typed_gear_cut, typed_gear_pinion_setups
from gearcontact.geometry.typed_pinion_fit import (ConjugateFit, conjugate_fitted_setups,
                                                   conjugate_target, contact_line_bound_arcsec,
                                                   line_envelope_min, needs_conjugate_fit,
                                                   residual_angles, spline_error_rad)

PRINT = "tests/geometry/summary_sheets/hypoid_10x41_no16_pair.toml"
#: The strict xfail's gear of session 24: F.2's generated gear with 2C = +-0.05.
TWO_C = {"drive": (dict(modified_roll=(0.05,)), {}), "coast": (dict(modified_roll=(-0.05,)), {})}


@pytest.fixture(scope="module")
def f2_generated():
    return standard_machine_pair(load_pair(F2), gear_generation="generated")


def _gear(pair) -> dict:
    return {s.side: s for s in pair.machine if s.member == "gear"}


def test_only_a_spiral_bevels_generated_gear_with_a_roll_law_is_fitted(f2_generated):
    # (c): the selection, before any flank
    gear = modified_gear(f2_generated, TWO_C)
    assert needs_conjugate_fit(f2_generated, gear["drive"])
    assert not needs_conjugate_fit(f2_generated, _gear(f2_generated)["drive"])   # linear roll
    helical = modified_gear(f2_generated, {"coast": (dict(helical_motion=(0.5,)), {})})
    assert needs_conjugate_fit(f2_generated, helical["coast"])
    formate = _gear(standard_machine_pair(load_pair(F2), gear_generation="formate"))["drive"]
    formate = dataclasses.replace(formate, settings=dataclasses.replace(
        formate.settings, modified_roll=(0.05,)))
    assert not needs_conjugate_fit(f2_generated, formate)       # no roll: nothing moves
    hypoid = _quiet_load(PRINT)
    from geometry.test_typed_pinion_motion import MODIFIED
    assert not any(needs_conjugate_fit(hypoid, g) for g in modified_gear(hypoid, MODIFIED).values())


def test_a_hypoid_gear_with_modified_roll_keeps_its_derived_pinion():
    # (c): the print's gear with 2C, 6D, helical motion: no fit, the pinion tables those
    # of the reversed motion, crowned as before (typed_gear_cut == its pair, fits empty)
    from geometry.test_typed_pinion_motion import MODIFIED

    hypoid = _quiet_load(PRINT)
    cut, fits = typed_gear_cut(hypoid, modified_gear(hypoid, MODIFIED),
                               lengthwise_crowning_um=0.0, blade_profile_crowning_um=0.0)
    assert fits == {}
    twin = dataclasses.replace(hypoid, pinion_hand="right", machine=(), print_gear=())
    from gearcontact.geometry.machine import mirror_setup
    derived = typed_gear_pinion_setups(
        twin, {s: mirror_setup(g) for s, g in modified_gear(hypoid, MODIFIED).items()},
        mirrored=True)
    assert {s.side: s for s in cut.machine if s.member == "pinion"} == {
        side: mirror_setup(p) for side, p in derived.items()}


def test_the_conjugate_target_of_a_linear_roll_is_the_derived_pinion(f2_generated):
    # (a): the blank's generated gear, linear roll: the derived (crown gear's) pinion is
    # its line-contact conjugate, so the residual angle against the target is within
    # twice the target's spline error (measured in the same process)
    gear = _gear(f2_generated)["drive"]
    seed = typed_gear_pinion_setups(f2_generated, _gear(f2_generated))["drive"]
    target = conjugate_target(f2_generated, gear)
    cut = machine_flank(seed, f2_generated.blank, face_width_mm=f2_generated.pinion_face_width_mm)
    u, v, d, dpsi = residual_angles(cut, target)
    spline = spline_error_rad(target)
    assert np.abs(dpsi).max() <= 2.0 * spline
    assert np.abs(d).max() < 0.01          # um: not vacuous, the unit is um
    # (d): both at exact nodes the derived pinion is the conjugate, TE0 = 0: the bound on
    # the contact lines vanishes to the TCA's conjugacy tolerance, 1e-4 arcsec (the
    # flank-wide bound carries the sheet's spline error, 2 x 1.6e-7 rad = 0.03 arcsec)
    assert 0.0 <= contact_line_bound_arcsec(f2_generated, seed, target, cut) < 1e-4


def test_the_envelope_of_the_contact_lines_on_a_closed_form_grid():
    # (d): phi = v on a 21 x 41 grid of [0, 1]^2 (the lines are the rows v = const), m =
    # 3 phi - (u - 1/2)^2: M(phi) = 3 phi (u = 1/2 a node), exact on each edge (m linear
    # in phi along v, the u-edges at one phase skipped). Pitch 0.4: the envelope
    # max_k M(phi + 0.4 k) over phi in [0, 1] has its least value just past a jump, 3 (1 -
    # 0.4) = 1.8, sampled at 2000 phases a pitch (one step, 3 x 0.4 / 2000 = 6e-4, the
    # tolerance, 1e-12 for rounding either side: the sample one step past the jump is
    # 1.8 + 6e-4 exactly); a mask cutting the lines above v = 0.3 leaves the phases (0.3,
    # 0.4) of the pitch without a line: -inf
    u, v = np.meshgrid(np.linspace(0.0, 1.0, 21), np.linspace(0.0, 1.0, 41), indexing="ij")
    m = 3.0 * v - (u - 0.5) ** 2
    ok = np.ones(u.shape, bool)
    got = line_envelope_min(v, m, ok, pitch_rad=0.4)
    assert 1.8 - 1e-12 <= got <= 1.8 + 6e-4 + 1e-12
    # a node column off the line maximum (u = 1/2 masked) lowers M to 3 phi - 0.05^2
    ok_mid = ok.copy()
    ok_mid[10] = False
    assert abs(line_envelope_min(v, m, ok_mid, pitch_rad=0.4) - (got - 0.0025)) < 1e-12
    assert line_envelope_min(v, m, v <= 0.3, pitch_rad=0.4) == -np.inf


def test_a_residual_above_the_bound_is_refused_naming_the_side(f2_generated, monkeypatch):
    # the refusal (declared): a fit whose residual exceeds RESIDUAL_BOUND_UM (2 um) is no
    # conjugate pinion: CheckFailed naming the side, its residual and the bound
    gear = modified_gear(f2_generated, TWO_C)
    seeds = typed_gear_pinion_setups(f2_generated, gear)

    def fake(pair, g, seed):     # a fit 2.5 um off: the refusal alone under test
        return ConjugateFit(side=g.side, fit=None, max_um=2.5, rms_um=0.5, dpsi_min_rad=0.0,
                            dpsi_max_rad=1e-5, spline_error_rad=0.0, te_bound_arcsec=1.0,
                            seed_max_um=18.0)

    monkeypatch.setattr(typed_pinion_fit, "fit_to_conjugate", fake)
    with pytest.raises(CheckFailed, match=r"drive: .*residual max 2\.500 um.*bound 2 um"):
        conjugate_fitted_setups(f2_generated, gear, seeds)


@pytest.mark.slow
def test_the_fitted_pinion_of_f2s_gear_with_2c_is_conjugate_within_its_bound(f2_generated):
    # (b) in the library (TCA 40 x 50 nodes, 31 phases): F.2's generated gear with 2C =
    # +0.05 on the drive side: the derived pinion is far off (not vacuous: > 10 um,
    # measured 18.1 um), the fit within the 2 um bound, and TE0 p-p of the uncrowned
    # pair at most the fit's first-order bound + 1e-4 arcsec
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.tca.analysis import analyze_pair

    cut, fits = typed_gear_cut(f2_generated, modified_gear(f2_generated, TWO_C),
                               lengthwise_crowning_um=0.0, blade_profile_crowning_um=0.0)
    fit = fits["drive"]
    assert fit.seed_max_um > 10.0
    assert fit.max_um <= typed_pinion_fit.RESIDUAL_BOUND_UM
    result, _ = analyze_pair(cut, side="drive", phases=31, flanks=build_flanks(cut, n_u=40, n_v=50))
    assert result.cycle.te0_pp_arcsec <= fit.te_bound_arcsec + 1e-4


@pytest.mark.slow
def test_a_left_hand_pair_gets_its_twins_fitted_pinion_mirrored():
    # a left-hand F.2 with 2C = 0.05 typed on its generated drive gear: the fit runs on
    # the right-hand twin (the gear mirrored: 2C -0.05), and the pinion written is the
    # twin's fitted pinion mirrored, exactly (mirror_setup; == as floats), the coast
    # (linear roll) not fitted. Measured: residual 0.471 um, ~20 s
    from gearcontact.geometry.machine import mirror_setup

    blank = load_pair(F2)
    left = standard_machine_pair(dataclasses.replace(blank, pinion_hand="left"),
                                 gear_generation="generated")
    gear = modified_gear(left, {"drive": (dict(modified_roll=(0.05,)), {})})
    cut, fits = typed_gear_cut(left, gear, lengthwise_crowning_um=0.0,
                               blade_profile_crowning_um=0.0)
    twin_cut, twin_fits = typed_gear_cut(
        standard_machine_pair(blank, gear_generation="generated"),
        {s: mirror_setup(g) for s, g in gear.items()}, lengthwise_crowning_um=0.0,
        blade_profile_crowning_um=0.0)
    assert sorted(fits) == sorted(twin_fits) == ["drive"]
    assert fits["drive"].max_um == twin_fits["drive"].max_um
    assert {s.side: s for s in cut.machine if s.member == "pinion"} == {
        s.side: mirror_setup(s) for s in twin_cut.machine if s.member == "pinion"}
    assert {s.side: s for s in cut.machine if s.member == "gear"} == gear   # as typed


@pytest.mark.slow
def test_a_derived_pinion_short_of_the_conjugate_starts_on_its_own_box(f2_generated):
    # 2C = 0.2 on F.2's generated drive gear: the derived pinion's envelope does not reach
    # the conjugate's root (u 1.22 mm; its own box from 1.74 mm), so the fit starts over
    # the part it covers and then takes the whole box (seed_trimmed); the result is a
    # pinion within the declared 2 um (measured 0.663 um; the derived pinion 175.5 um
    # off where it reached). Before, the derived pinion was written as it was
    gear = modified_gear(f2_generated, {"drive": (dict(modified_roll=(0.2,)), {})})
    _, fits = typed_gear_cut(f2_generated, gear)
    assert fits["drive"].seed_trimmed
    assert fits["drive"].max_um <= typed_pinion_fit.RESIDUAL_BOUND_UM
    assert fits["drive"].stage == 1          # within the bound: no refit


@pytest.mark.slow
def test_a_fit_above_the_bound_is_refitted_with_every_setting(f2_generated):
    # the second fit (session 27, declared before measuring, docs sec. 5): 2C 0.05 with 6D
    # 1.0 on F.2's generated drive gear was refused at 2.080 um with the default eight;
    # refitted (every setting, then minimax) it is within the unchanged 2 um (measured
    # 1.570 um at stage 3) and no worse than the default fit's 60 x 75 residual, which it
    # started from (the lowest kept)
    gear = modified_gear(f2_generated, {"drive": (dict(modified_roll=(0.05, 1.0)), {})})
    _, fits = typed_gear_cut(f2_generated, gear)
    assert fits["drive"].stage > 1
    assert fits["drive"].max_um <= typed_pinion_fit.RESIDUAL_BOUND_UM


def _e0_pair():
    from design_space import bare_candidate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # the blank's notes
        return standard_machine_pair(bare_candidate(13, 2, 0, 35, 0.3, "drive"),
                                     gear_generation="generated")


@pytest.mark.slow
@pytest.mark.parametrize("side", ["drive", "coast"])
def test_the_13_26_pair_is_within_its_bound_on_the_contact_lines(side):
    # (d) on the 13/26 at E 0 (its standard generated gear, 2C +-0.05; the table of docs
    # sec. 5), library TCA at the CLI's 120 x 150 nodes, 31 phases: TE0 p-p at most the
    # bound on the contact lines + 1e-4 arcsec (the TCA's conjugacy tolerance). Measured
    # (session 28, the pinion fitted at exact nodes and the TCA's edge search finding the
    # pinion heel's first touch, tests/tca/test_edge_touching_stretch.py against a
    # brute-force search) drive 0.432 against 0.501; coast 0.989 against 0.534, a strict
    # xfail until session 29: the TCA's pair -1 stayed on edge contacts at phases 24-29
    # (-0.72 to -0.99 arcsec) while its surface point inside both flanks touched first
    # (brute force, tests/tca/sheet_touch.py: -0.415 to -0.463). With the surface's return
    # (tca.solve, docs sec. 5 "The edge check while the surface contact is inside")
    # coast 0.46296 against 0.534, the brute force's 0.46296. Session 27's pinion with the
    # fixed TCA: drive 0.5074 against 0.5321 (a strict xfail at 0.712 before the
    # edge-search fix), coast 0.880 against 1.545
    from gearcontact.tca.analysis import analyze_pair

    pair = _e0_pair()
    cut, fits = typed_gear_cut(pair, modified_gear(pair, TWO_C), lengthwise_crowning_um=0.0,
                               blade_profile_crowning_um=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # the typed gear's check against the blank
        result, _ = analyze_pair(cut, side=side, phases=31)
    assert result.cycle.te0_pp_arcsec <= fits[side].te_bound_arcsec + 1e-4


@pytest.mark.slow
def test_a_refitted_pinion_past_the_conjugates_box_differs(f2_generated):
    # (d) on the refitted 2C 0.05 + 6D 1.0 (F.2's generated drive gear), uncrowned,
    # library TCA at 120 x 150 nodes, 31 phases, + 1e-4 arcsec (the TCA's tolerance).
    # A strict xfail until session 29 (6.516 against the bound 4.843; on session 27's
    # pinion 6.742 against 5.660): the TCA's pair stayed on surface contacts while the
    # gear's tip and root edges touched first (docs sec. 5, "The edge check while the
    # surface contact is inside"). Measured with the edge check: 3.01813 arcsec, the
    # brute-force first touch's 3.01813 (tests/tca/sheet_touch.py, every phase within
    # 2.4e-7 arcsec), against the bound 4.843. The name is kept for the test map
    from gearcontact.tca.analysis import analyze_pair

    gear = modified_gear(f2_generated, {"drive": (dict(modified_roll=(0.05, 1.0)), {})})
    cut, fits = typed_gear_cut(f2_generated, gear, lengthwise_crowning_um=0.0,
                               blade_profile_crowning_um=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # the typed gear's check against the blank
        result, _ = analyze_pair(cut, side="drive", phases=31)
    assert result.cycle.te0_pp_arcsec <= fits["drive"].te_bound_arcsec + 1e-4


@pytest.fixture(scope="module")
def helical_v1_3(f2_generated):
    """F.2's generated drive gear with a helical motion V_1 = 3 mm/rad (refused at 3.297
    um before session 28), its derived pinion and its conjugate target."""
    gear = modified_gear(f2_generated, {"drive": (dict(helical_motion=(3.0,)), {})})
    seed = typed_gear_pinion_setups(f2_generated, gear)["drive"]
    return gear, seed, conjugate_target(f2_generated, gear["drive"])


@pytest.mark.slow
def test_the_conjugates_sheet_is_off_its_exact_nodes_at_the_toe_root_corner(
        f2_generated, helical_v1_3):
    # the diagnosis of docs sec. 5 ("Why V_1 = 3 was refused"), as a truth about the
    # target: at the fit grid's toe-root corner node the conjugate's quintic sheet lies
    # more than the 2 um bound off its own exact meshing nodes (measured 5.04 um; the
    # sheet's outer node row is conjugate to the gear sheet extrapolated past its nodes),
    # while at every other node of the 9 x 11 grid within 0.05 um (measured 0.01 um):
    # both targets through the same FitProblem, the seed's nodes shared, so the
    # difference is the target's alone
    from gearcontact.geometry.setting_fit import FitProblem
    from gearcontact.geometry.typed_pinion_fit import ExactConjugate

    _, seed, target = helical_v1_3
    b = target.boundary
    grid = (np.linspace(b.u_root, b.u_tip, 9), np.linspace(b.v_toe, b.v_heel, 11))
    sheet, exact = (FitProblem(seed, f2_generated.blank, t, (), *grid).deviation_um(np.zeros(0))
                    .reshape(9, 11) for t in (target, ExactConjugate(target)))
    diff = np.abs(sheet - exact)
    assert diff[0, 0] > typed_pinion_fit.RESIDUAL_BOUND_UM
    diff[0, 0] = 0.0
    assert diff.max() < 0.05


@pytest.mark.slow
def test_a_helical_motion_v1_3_gear_gets_a_pinion_within_the_bound(f2_generated):
    # V_1 = 3 mm/rad on F.2's generated drive gear, refused before (3.297 um against the
    # conjugate's sheet): fitted to the exact conjugate (docs sec. 5, declared) it is
    # within the unchanged 2 um at stage 1 (measured 0.207 um), and the uncrowned pair's
    # TE0 p-p (library TCA at the CLI's 120 x 150 nodes, 31 phases) lies within the
    # bound on the contact lines + 1e-4 arcsec (the TCA's conjugacy tolerance; measured
    # 0.1735 against 0.1870 arcsec)
    from gearcontact.tca.analysis import analyze_pair

    gear = modified_gear(f2_generated, {"drive": (dict(helical_motion=(3.0,)), {})})
    cut, fits = typed_gear_cut(f2_generated, gear, lengthwise_crowning_um=0.0,
                               blade_profile_crowning_um=0.0)
    fit = fits["drive"]
    assert fit.stage == 1
    assert fit.max_um <= typed_pinion_fit.RESIDUAL_BOUND_UM
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # the typed gear's check against the blank
        result, _ = analyze_pair(cut, side="drive", phases=31)
    assert result.cycle.te0_pp_arcsec <= fit.te_bound_arcsec + 1e-4


@pytest.mark.slow
def test_a_fit_whose_warm_start_jumps_a_branch_restarts(f2_generated, helical_v1_3):
    # the warm-started node solve (docs sec. 5, declared): every setting fitted from the
    # default fit against the conjugate's sheet (session 27's stage 2 on V_1 = 3) jumped
    # 71 of 99 nodes onto another envelope branch at its 27th evaluation and reported a
    # fit-grid maximum of 3899 um for a set-up 3.3 um off. The fit's own maximum must
    # equal that of its set-up solved afresh by continuation from the mean node (a new
    # FitProblem), to 1e-6 um (rounding of the two node solves)
    from gearcontact.geometry.setting_fit import PARAMETERS, FitProblem, fit_pinion_setup

    _, seed, target = helical_v1_3
    first = fit_pinion_setup(seed, f2_generated.blank, target)
    fit = fit_pinion_setup(first.setup, f2_generated.blank, target, parameters=tuple(PARAMETERS))
    b = target.boundary
    fresh = FitProblem(fit.setup, f2_generated.blank, target, (),
                       np.linspace(b.u_root, b.u_tip, 9), np.linspace(b.v_toe, b.v_heel, 11))
    assert abs(fit.fit_max_um - np.abs(fresh.deviation_um(np.zeros(0))).max()) < 1e-6
