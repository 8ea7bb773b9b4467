"""Local synthesis of the pinion settings against a typed gear (tca.setting_synthesis,
SynthesisProblem(gear=...); issue 27, docs/machine_settings.md sec. 5): the base pinion
is the typed gear's uncrowned pinion (geometry.typed_pinion), M its contact path's point
on the pinion mean section (a generated hypoid gear) or the mean node (a formate gear).

Truths, declared before measuring:
- regression: the blank's own gear typed gives the blank's problem: base pinion setups
  equal to 1e-9 (relative, float fields; typed_pinion reproduces the blank's
  construction to rounding), the pivot M equal exactly for a formate gear (the mean
  node, no solve) and within 1e-6 mm for a generated hypoid gear (the secant of
  setting_problem._path_point_at stops within 1e-6 mm of the mean section), and the full
  synthesis (slow) gives the same corrections within 1e-6 scale steps;
- every correction keeps M and its normal (the envelope node at M of the corrected
  settings equal to the base's within 1e-9 mm, normal 1e-12), as
  tests/tca/test_setting_synthesis.py asserts for the blank's gear.
"""

import dataclasses
from types import SimpleNamespace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.basic_settings import member_setups
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.generated import EnvelopeSolver
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.setting_problem import PIVOT_MARGIN
from gearcontact.tca.setting_synthesis import (_SCALE, SynthesisProblem, corrected_setup,
                                               synthesize_settings)
from gearcontact.tca.solve import solve_tca

F2 = Path(__file__).resolve().parents[2] / "examples" / "iso23509_f2_spiral_bevel.toml"
PRINT = (Path(__file__).resolve().parents[1] / "geometry" / "summary_sheets"
         / "hypoid_10x41_no16_pair.toml")
#: float fields of a setup compared at 1e-9 relative (see the module docstring)
_SETTINGS = ("radial_distance_mm", "cradle_angle_deg", "machine_root_angle_deg",
             "machine_centre_to_back_mm", "sliding_base_mm", "blank_offset_mm",
             "ratio_of_roll", "tilt_deg", "swivel_deg")
_BLADE = ("blade_angle_deg", "point_radius_mm", "edge_radius_mm")


def _same_setup(a, b):
    assert (a.member, a.side, a.blade.kind) == (b.member, b.side, b.blade.kind)
    for f in _SETTINGS:
        assert getattr(a.settings, f) == pytest.approx(getattr(b.settings, f), rel=1e-9,
                                                       abs=1e-9), f
    for f in _BLADE:
        assert getattr(a.blade, f) == pytest.approx(getattr(b.blade, f), rel=1e-9), f
    assert a.settings.modified_roll == b.settings.modified_roll == ()


def _typed(pair, generation, **nodes):
    gear, _ = member_setups(pair, generation)
    return SynthesisProblem(pair, gear=gear, **nodes)


def test_the_blank_formate_gear_typed_is_the_blank_problem():
    # ~10 s (20 x 24 nodes): F.2's formate gear typed; line contact, M the mean node
    pair = load_pair(F2)
    want = SynthesisProblem(pair, gear_generation="formate", n_u=20, n_v=24)
    got = _typed(pair, "formate", n_u=20, n_v=24)
    assert not got.point_contact and not want.point_contact
    for side in SIDES:
        assert got.gear_setups[side] == want.gear_setups[side]      # kept as given
        _same_setup(got.base[side], want.base[side])
        assert got.mean_uv[side] == want.mean_uv[side]
        np.testing.assert_allclose(got.means[side], want.means[side], rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(got.standard[side], want.standard[side], rtol=1e-9,
                                   atol=1e-12)


@pytest.fixture(scope="module")
def typed_hypoid(generated_hypoid_problem):
    # ~10 s: the 13/26 hypoid's generated gear typed
    return _typed(generated_hypoid_problem.pair, "generated"), generated_hypoid_problem


def test_the_blank_generated_hypoid_gear_typed_is_the_blank_problem(typed_hypoid):
    got, want = typed_hypoid
    assert got.point_contact and want.point_contact
    for side in SIDES:
        _same_setup(got.base[side], want.base[side])
        assert np.hypot(*np.subtract(got.mean_uv[side], want.mean_uv[side])) < 1e-6
        assert abs(got.mean_uv[side][1] - float(got.pair.blank.pitch_point_mm[0])) < 1e-6


def _corrections_keep_the_mean_point(prob, side):
    """Each correction's envelope node at M equals the base's (1e-9 mm, normal 1e-12)."""
    base = prob.base[side]
    solver = EnvelopeSolver(base, prob.pair.blank, prob.cone)
    u, v = prob.mean_uv[side]
    m0 = solver.solve(u, v, solver.initial_guess(u, v))
    for x in ([0.02, 0.0, 0.0], [0.0, 1e-3, 0.0], [-0.015, 8e-4, -2.0]):
        s = corrected_setup(base, x, mean=prob.means[side])
        m1 = EnvelopeSolver(s, prob.pair.blank, prob.cone).solve(u, v, m0.q)
        assert np.abs(m1.x_mm - m0.x_mm).max() < 1e-9
        assert np.abs(m1.n - m0.n).max() < 1e-12
        assert s != base


def test_corrections_keep_the_mean_point_of_the_typed_base(typed_hypoid):
    for side in SIDES:
        _corrections_keep_the_mean_point(typed_hypoid[0], side)


@pytest.mark.slow
def test_the_blank_generated_hypoid_gear_typed_synthesizes_the_same(typed_hypoid):
    # ~2.5 min: the same corrections within 1e-6 scale steps (declared above), both met
    got, want = typed_hypoid
    a = synthesize_settings(got.pair, problem=got, phases=11)
    b = synthesize_settings(want.pair, problem=want, phases=11)
    for side in SIDES:
        assert a[side].met and b[side].met
        assert np.all(np.abs(a[side].x - b[side].x) < 1e-6 * _SCALE), (a[side].x, b[side].x)


def test_a_typed_gear_is_kept_in_the_written_pair(monkeypatch):
    # synthesized_machine_pair's bookkeeping, the search replaced by the base pinion: the
    # typed gear (F.2's formate gear, its edge radius changed: not the blank's) is the
    # problem's gear and the result's gear exactly as given
    from gearcontact.tca import setting_synthesis as ss

    pair = load_pair(F2)
    gear, _ = member_setups(pair, "formate")
    gear = {s: dataclasses.replace(g, blade=dataclasses.replace(
        g.blade, edge_radius_mm=g.blade.edge_radius_mm * 0.9)) for s, g in gear.items()}
    seen = {}

    def base_only(pair, *, targets, problem, **options):
        seen["gear"] = problem.gear_setups
        return {s: SimpleNamespace(setup=problem.base[s]) for s in SIDES}

    monkeypatch.setattr(ss, "synthesize_settings", base_only)
    # centre_pivot off: one problem (the pivot's choice: tests/tca/test_setting_pivot_depth.py)
    cut, _ = ss.synthesized_machine_pair(pair, gear=gear, n_u=12, n_v=14, centre_pivot=False)
    assert seen["gear"] == gear
    assert tuple(s for s in cut.machine if s.member == "gear") == tuple(gear[s] for s in SIDES)


def test_a_left_hand_pair_keeps_its_typed_gear(monkeypatch):
    # the left-hand twin's problem gets the typed gear mirrored (mirror_setup, the
    # standard pinion's rule, geometry.typed_pinion), the result the gear as typed (==)
    # and the twin's pinion mirrored (==)
    from gearcontact.geometry.machine import mirror_setup
    from gearcontact.tca import setting_synthesis as ss

    right = load_pair(F2)
    right_gear, _ = member_setups(right, "formate")
    pair = dataclasses.replace(right, pinion_hand="left")
    gear = {s: mirror_setup(g) for s, g in right_gear.items()}     # a left-hand gear
    seen = {}

    def base_only(pair, *, targets, problem, **options):
        seen["problem"] = problem
        return {s: SimpleNamespace(setup=problem.base[s]) for s in SIDES}

    monkeypatch.setattr(ss, "synthesize_settings", base_only)
    cut, _ = ss.synthesized_machine_pair(pair, gear=gear, n_u=12, n_v=14, centre_pivot=False)
    prob = seen["problem"]
    assert prob.pair.pinion_hand == "right"
    assert prob.gear_setups == {s: mirror_setup(gear[s]) for s in SIDES}
    assert tuple(s for s in cut.machine if s.member == "gear") == tuple(gear[s] for s in SIDES)
    assert tuple(s for s in cut.machine if s.member == "pinion") == tuple(
        mirror_setup(prob.base[s]) for s in SIDES)


def print_twin():
    """The published 10 x 41 print's pair (left hand) as its right-hand twin and the
    print's gear mirrored, as synthesized_machine_pair synthesizes it."""
    import warnings

    from gearcontact.geometry.machine import mirror_setup

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's blank note
        pair = load_pair(PRINT)
    gear = {s.side: mirror_setup(s) for s in pair.machine if s.member == "gear"}
    return dataclasses.replace(pair, pinion_hand="right", machine=(), print_gear=()), gear


@pytest.fixture(scope="module")
def print_problem():
    # ~3 s: the print's gear, 40 x 50 nodes
    twin, gear = print_twin()
    return SynthesisProblem(twin, gear=gear)


def test_the_print_gear_has_a_pivot_on_both_sides(print_problem):
    # The drive base pinion's TE0 = 0 path leaves the pinion flank at its root 1.9 mm
    # before the mean section (measured, docs/machine_settings.md sec. 5): its M is the
    # path's point nearest the mean section inside the flank box by PIVOT_MARGIN of the
    # depth and face (declared before measuring). Truths: M lies in that box; it is a
    # point of the conjugate path (the uncrowned base's local TCA at M: TE0 level and
    # slope 0 within the crown-gear pinion's conjugacy tolerance, 1e-4 arcsec over a
    # pitch, 1e-4 arcsec/rad; the contact at M's phase M within 1e-3 mm, the 40 x 50
    # node interpolation); the path between M and the mean section leaves the margin
    # box (M is the nearest inside, to the path's sampling step); every correction
    # keeps M and its normal. The coast M stays on the mean section (1e-6 mm).
    prob = print_problem
    assert prob.point_contact and not prob.off_flank
    v_m = float(prob.pair.blank.pitch_point_mm[0])
    assert abs(prob.mean_uv["coast"][1] - v_m) < 1e-6
    side = "drive"
    u, v = prob.mean_uv[side]
    flank = prob.flank(side, np.zeros(3))
    (u0, u1), (v0, v1) = flank.u_range, flank.v_range
    du, dv = PIVOT_MARGIN * (u1 - u0), PIVOT_MARGIN * (v1 - v0)
    assert u0 + du <= u <= u1 - du and v0 + dv <= v <= v1 - dv
    assert v < v_m - 1.9           # towards the toe, beyond where the path leaves
    m = prob.contact(side, np.zeros(3))
    assert m.te_level_arcsec < 1e-4 and abs(m.te_slope_arcsec_per_rad) < 1e-4
    assert np.hypot(m.point.pinion_uv[0] - u, m.point.pinion_uv[1] - v) < 1e-3
    kin = prob.pair.kinematics()
    h = 2.0 * np.pi / prob.pair.pinion_teeth / 30.0
    path = solve_tca(flank, prob.gear[side], kin, prob.start[side].phi1_rad
                     + h * np.arange(-12, 13), start=prob.start[side], edges=False)
    nearer = [p for p in path.points if not p.edge and abs(p.v1 - v_m) < abs(v - v_m) - 1e-9]
    assert nearer and all(not (u0 + du <= p.u1 <= u1 - du) for p in nearer)
    _corrections_keep_the_mean_point(prob, side)


@pytest.fixture(scope="module")
def print_drive(print_problem):
    # ~1.5 min: the drive side synthesized about its pivot off the mean section
    prob = print_problem
    return synthesize_settings(prob.pair, problem=prob, sides=("drive",))["drive"]


@pytest.mark.slow
def test_the_print_gear_drive_synthesis_meets_the_targets_at_m(print_drive):
    # the targets at M within the synthesis' tolerances (5 % of TE level and ellipse
    # length), as the coast side below
    assert print_drive.met, print_drive.table()


@pytest.fixture(scope="module")
def print_choice():
    # ~1.5-2 min: the command's call on the print (both sides, the candidate choice of a
    # point-contact base, docs/machine_settings.md sec. 5, "The candidate choice for a
    # point-contact base")
    import warnings

    from gearcontact.tca.setting_synthesis import synthesized_machine_pair

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's blank note
        pair = load_pair(PRINT)
    gear = {s.side: s for s in pair.machine if s.member == "gear"}
    return synthesized_machine_pair(pair, gear=gear)[1]


@pytest.mark.slow
def test_the_print_gear_drive_vertex_is_m(print_drive, print_choice):
    # declared before measuring, as the coast side's: the full TCA's TE0 vertex is M
    # within 1e-6 mm. The single candidate (the asked targets at M) misses it (measured:
    # 18.8 mm, the gear heel's edge contact; its paint ellipse at a flank edge at all 31
    # phases, so its pattern run has length 0 in a path of P pitches on the flank); the
    # kept candidate has lever 4's ellipse (declared before measuring it), at its pivot
    # (session 26) or at levers 5-6's (session 27, which keep the best one's length):
    # 2a' = 2a (P - 1) / P (the rule by hand, 1e-9 relative: the target's ratio round
    # trip), targets met, vertex at the kept one's M, fewer edge phases than the single
    # candidate
    run = print_drive.run
    assert run.pitches == 0.0 and np.isnan(run.middle_offset_pitch) and run.path_pitches > 1
    kept = print_choice["drive"]
    assert kept.met, kept.table()
    length = [row for row in kept.rows if "ellipse" in row[0]][0][2]
    asked = [row for row in print_drive.rows if "ellipse" in row[0]][0][2]
    assert length == pytest.approx(asked * (run.path_pitches - 1) / run.path_pitches,
                                   rel=1e-9)
    assert kept.vertex_offset_mm < 1e-6
    assert kept.edge_phases < print_drive.edge_phases
    # session 27's criterion (docs/machine_settings.md sec. 5, "The print's drive
    # bearing", declared before building levers 5-6): fewer drive edge phases than
    # session 26's kept candidate (lever 4 at M: 15 of 31 in this check), none more on
    # the coast (5 of 31); counts, exact
    assert kept.edge_phases < 15
    assert print_choice["coast"].edge_phases <= 5


@pytest.mark.slow
def test_the_print_drive_with_lever_5s_margin(print_choice):
    # session 28's criterion (docs/machine_settings.md sec. 5, "The print's drive
    # bearing: a margin on lever 5's room", declared before building the margin): fewer
    # drive edge phases than session 27's kept candidate (lever 5 without a margin, path
    # turned by lever 6: 13 of 31 in this check), the TE0 vertex at the kept M (1e-6 mm,
    # the strict test's truth), none more on the coast (0 of 31); counts, exact
    kept = print_choice["drive"]
    assert kept.met, kept.table()
    assert kept.vertex_offset_mm < 1e-6
    assert kept.edge_phases < 13
    assert print_choice["coast"].edge_phases <= 0


@pytest.mark.slow
def test_the_print_gear_coast_synthesis(print_problem):
    # ~30-60 s. On the side with M (coast): the corrections keep M and its normal (1e-9
    # mm, 1e-12), the targets are met at M within the synthesis' tolerances and the full
    # TCA's TE0 vertex is M within 1e-6 mm (as tests/tca/test_setting_synthesis.py)
    prob = print_problem
    side = "coast"
    assert side not in prob.off_flank
    assert abs(prob.mean_uv[side][1] - float(prob.pair.blank.pitch_point_mm[0])) < 1e-6
    _corrections_keep_the_mean_point(prob, side)
    r = synthesize_settings(prob.pair, problem=prob, sides=(side,))[side]
    assert r.met, r.table()
    assert r.vertex_offset_mm < 1e-6


@pytest.mark.slow
def test_the_print_drive_bearings_depth(print_choice):
    # session 29 (docs/machine_settings.md sec. 5, "The bearing's depth: room against
    # need", declared before building lever 7): the kept drive bearing's need over a
    # pitch exceeds the flank's working depth (measured 7.04 against 6.65 mm: the
    # statement "no placement holds it", a shorter ellipse fitting: verdict "shorter"),
    # written beside its pivot; N = D + 2h by hand from the result's own numbers
    # (1e-12); the kept bearing's edge phases no more than session 28's (11 of 31 in
    # this check; lever 7, measured and removed: docs), exact; the vertex at the kept M
    # (1e-6 mm), the coast still 0
    kept = print_choice["drive"]
    need = kept.depth
    assert need.need_mm == pytest.approx(need.travel_mm + 2.0 * np.hypot(
        need.semi_major_mm * need.du_ds, need.semi_minor_mm * need.du_dt), rel=1e-12)
    assert need.need_mm > need.room_mm and need.verdict() == "shorter"
    assert need.shortest_mm <= need.fitting_length_mm() < 2.0 * need.semi_major_mm
    assert "no placement holds it" in kept.pivot_text()
    assert kept.met and kept.vertex_offset_mm < 1e-6
    assert kept.edge_phases <= 11
    assert print_choice["coast"].edge_phases <= 0
