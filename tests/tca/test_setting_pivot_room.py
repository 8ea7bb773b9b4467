"""The further pivot candidates of the local synthesis (tca.setting_synthesis
``_pivot_candidates``; docs/machine_settings.md sec. 5, "The bearing's room"): the paint
ellipse's target shortened to the contact line's room at the centred pivot
(``room_targets``, ``setting_problem.line_room_mm``), the pivot moved to the middle
of the best candidate's pattern run (``run_pivot``, ``setting_problem.pattern_run``),
and the ellipse shortened for a pattern run of one pitch (``length_targets``), each kept
by ``_better_pivot`` (tca.setting_pivot) (fewest edge phases, then the lowest TE0 p-p, then the
first given; a missed target loses).

The choice logic is tested against results written by hand (the rule's truth computed
in the test); ``line_room_mm`` and ``pattern_run`` on the s0003-centred blank (formate
gear, 40 x 50 nodes, the standard crowning about the mean node and the centre) against
independent evaluations: fresh mating-point solves at the run's neighbour phases and
the paint ellipse's outline (``gap_at``) projected on the flanks.
"""

import dataclasses
import math

import numpy as np
import pytest

from gearcontact.geometry.pair import load_pair, without_easeoff
from gearcontact.tca.analysis import pattern_on_flank
from gearcontact.tca.curvature import contact_ellipse, relative_curvature
from gearcontact.tca.mating import solve_mating_point
from gearcontact.tca.mesh import mesh_cycle
from gearcontact.tca.setting_problem import PatternRun, SynthesisProblem, pattern_run
from gearcontact.tca.setting_pivot import length_targets, room_targets, run_pivot
from gearcontact.tca.setting_synthesis import SettingSynthesis, _better_pivot
from gearcontact.tca.stencil import gap_at
from gearcontact.tca.synthesis_targets import SynthesisTargets
from gearcontact.tca.types import EdgeContact

SIDE = "drive"


def _result(pivot, edges, te0, met=True, run=None):
    """A SettingSynthesis with only what the choice reads."""
    row = ("TE0 peak-to-peak", "arcsec", 3.0, 3.0, 0.15, met)
    return SettingSynthesis("drive", None, np.zeros(3), None, (row,), te0,
                            ("pinion root",) * edges + ("",) * (31 - edges), 0.0, 0, 0.0,
                            pivot=pivot, run=run)


def test_the_kept_pivot_of_several_is_the_ranked_first():
    # the rule's truth by hand: rank (missed, edge phases, TE0 p-p), ties to the first
    node, centre = _result("node", 31, 2.78), _result("centre", 31, 35.7)
    room = _result("room", 4, 3.1)
    run = _result("run", 4, 3.1)
    kept = _better_pivot(node, centre, room, run)
    assert kept.pivot == "room"
    # every dropped one is named, in the order given, with its check
    assert kept.other_pivot == (
        "node: paint ellipse at a flank edge at 31 of 31 phases, full TCA TE0 p-p 2.78 "
        "arcsec; centre: paint ellipse at a flank edge at 31 of 31 phases, full TCA TE0 "
        "p-p 35.70 arcsec; run: paint ellipse at a flank edge at 4 of 31 phases, full TCA "
        "TE0 p-p 3.10 arcsec")
    assert _better_pivot(node, _result("short", 0, 1.0, met=False)).pivot == "node"
    assert _better_pivot(node, centre).pivot == "node"


def test_the_room_target_is_the_room_where_the_ellipse_exceeds_it():
    t = SynthesisTargets(te0_pp_arcsec=3.0, pattern_length_ratio=0.35)
    face = 30.0             # target 2a = 10.5 mm
    got = room_targets(t, room_mm=5.98, face_mm=face)
    # 2a = the room exactly (ratio x face, 1e-12 mm: arithmetic); the rest kept (==)
    assert got.pattern_length_ratio * face == pytest.approx(5.98, abs=1e-12)
    assert got.te0_pp_arcsec == t.te0_pp_arcsec and got.path_angle_deg is None
    assert got.centre_profile == t.centre_profile
    assert room_targets(t, room_mm=10.5, face_mm=face) is None      # fits: not tried
    assert room_targets(t, room_mm=11.0, face_mm=face) is None
    # below the targets' range (0.1 x face = 3 mm): not tried, never clipped
    assert room_targets(t, room_mm=2.9, face_mm=face) is None
    assert room_targets(t, room_mm=3.0, face_mm=face).pattern_length_ratio == \
        pytest.approx(0.1, abs=1e-15)


def test_the_length_target_makes_the_run_a_pitch_to_first_order():
    # the 13/26 drive at the mean node (docs sec. 5): path on the flank 1.30 pitches,
    # pattern run 0.77, 2a 8.33 mm of a 23.8 mm face; truth by hand:
    # 2a' = 2a (P - 1) / (P - R)
    t = SynthesisTargets(pattern_length_ratio=8.33 / 23.8)
    run = PatternRun(0.77, -0.15, (5.98, 70.34), 1.30)
    got = length_targets(t, _result("node", 6, 6.31, run=run), face_mm=23.8)
    assert got.pattern_length_ratio * 23.8 == pytest.approx(8.33 * 0.30 / 0.53, rel=1e-12)
    # a run of a pitch, a path not longer than one, no edges, or below 0.1 x face: None
    for r in (PatternRun(1.0, 0.0, (0, 0), 1.3), PatternRun(0.5, 0.0, (0, 0), 1.0)):
        assert length_targets(t, _result("node", 6, 6.31, run=r), face_mm=23.8) is None
    assert length_targets(t, _result("node", 0, 6.31, run=run), face_mm=23.8) is None
    assert length_targets(t, _result("node", 6, 6.31), face_mm=23.8) is None
    assert length_targets(t, _result("node", 6, 6.31, run=PatternRun(
        0.1, 0.0, (0, 0), 1.05)), face_mm=23.8) is None     # 8.33 x 0.05 / 0.95 < 2.38


def test_the_run_pivot_moves_only_an_edged_result_off_its_run():
    run = PatternRun(1.1, -0.2, (5.5000004, 70.0000006))
    # rounded to 1e-6 mm, the digits the head comment prints
    assert run_pivot(_result("node", 6, 6.3, run=run)) == (5.5, 70.000001)
    # no edge phases, no run, or the run's middle within a phase step (1/30 pitch)
    assert run_pivot(_result("node", 0, 6.3, run=run)) is None
    assert run_pivot(_result("node", 6, 6.3)) is None
    assert run_pivot(_result("node", 6, 6.3, run=PatternRun(1.1, 0.03, (5.5, 70.0)))) is None
    assert run_pivot(_result("node", 6, 6.3, run=PatternRun(1.1, -0.034, (1.0, 2.0)))) == \
        (1.0, 2.0)
    assert run_pivot(_result("node", 6, 6.3, run=PatternRun(1.1, 0.03, (5.5, 70.0)))) is None


@pytest.fixture(scope="module")
def problems():
    # ~8 s: the s0003-centred blank's formate gear and complementary pinion, 40 x 50
    # nodes, pivoting on the mean node and on the working depth's centre
    pair = without_easeoff(load_pair("s0003-centred"))
    return {d: SynthesisProblem(pair, gear_generation="formate", pivot_depth=d)
            for d in (None, 0.5)}


def _ellipse_at_m(prob, side):
    pair = prob.pair
    kin = pair.kinematics()
    flank, gear = prob.flank(side, prob.standard[side]), prob.gear[side]
    mp = solve_mating_point(flank, gear, kin, prob.start[side])
    return flank, gear, kin, mp, contact_ellipse(relative_curvature(flank, gear, kin, mp))


def test_line_room_bounds_the_ellipse_at_m(problems):
    # ~2 s. The room's contract by direct projections (gap_at along the major axis):
    # +-room inside both flanks, room + 2 x 0.01 mm (the bisection's stop) outside on
    # one side. Against the paint ellipse's outline (16 points, the pattern's own
    # test): the ellipse at the centre lies on the flanks (test_setting_pivot_depth), so
    # its semi-major axis is within the room; at the mean node it is not, its
    # semi-major axis beyond the room (the depth argument, docs sec. 5)
    for side in ("drive", "coast"):
        rooms = {}
        for depth, prob in problems.items():
            flank, gear, kin, mp, ell = _ellipse_at_m(prob, side)
            room = prob.line_room_mm(side, prob.standard[side])
            on = gap_at(flank, gear, kin, mp, np.array([room, -room]), np.zeros(2)).on_flank
            assert on.all()
            off = gap_at(flank, gear, kin, mp, np.array([room + 0.02, -room - 0.02]),
                         np.zeros(2)).on_flank
            assert not off.all()
            theta = 2.0 * np.pi * np.arange(16) / 16
            outline = gap_at(flank, gear, kin, mp, ell.semi_major_mm * np.cos(theta),
                             ell.semi_minor_mm * np.sin(theta)).on_flank.all()
            if outline:
                assert ell.semi_major_mm <= room
            else:
                # the outline off a flank: the major axis' ends off too, or the minor
                assert ell.semi_major_mm > room or not gap_at(
                    flank, gear, kin, mp, np.zeros(2),
                    ell.semi_minor_mm * np.array([1.0, -1.0])).on_flank.all()
            rooms[depth] = (room, ell.semi_major_mm)
        assert rooms[None][0] < rooms[None][1] <= rooms[0.5][0]


def test_pattern_run_ends_where_the_ellipse_leaves_a_flank(problems):
    # ~5 s: the standard crowning about the centre, the full TCA (31 phases, pairs
    # -2..2); the run of pair 0's path around M's phase. Independent check at the
    # run's ends and one phase step beyond: a fresh mating-point solve at that phase
    # and the paint ellipse's outline there (pattern_on_flank on those contacts)
    prob = problems[0.5]
    pair = prob.pair
    kin = pair.kinematics()
    flank, gear, start = prob.flank(SIDE, prob.standard[SIDE]), prob.gear[SIDE], prob.start[SIDE]
    cyc = mesh_cycle(flank, gear, kin, pinion_teeth=pair.pinion_teeth, start=start,
                     start_fixed="phi1", phases=31, pairs=2)
    run = pattern_run(flank, gear, kin, cyc.path, phi1_rad=start.phi1_rad,
                      pinion_teeth=pair.pinion_teeth)
    pitch = 2.0 * math.pi / pair.pinion_teeth
    step = pitch / 30.0
    assert run is not None and 0.0 < run.pitches <= run.path_pitches
    mid = start.phi1_rad + run.middle_offset_pitch * pitch
    lo, hi = mid - 0.5 * run.pitches * pitch, mid + 0.5 * run.pitches * pitch
    # the phases inside the run's ends and beyond them, by fresh solves from the path's
    # nearest point (1e-9 rad: a phase of the path's own grid)
    phases = {"end lo": lo, "end hi": hi, "beyond lo": lo - step, "beyond hi": hi + step}
    points = {}
    for name, phi in phases.items():
        near = min(cyc.path.points, key=lambda p: abs(p.phi1_rad - phi))
        assert abs(near.phi1_rad - phi) < 1e-9 or name.startswith("beyond")
        try:
            points[name] = solve_mating_point(flank, gear, kin, dataclasses.replace(
                near.as_guess(), phi1_rad=phi))
        except (EdgeContact, ArithmeticError):   # the contact itself off a flank
            assert name.startswith("beyond")
    names = list(points)
    ells = [contact_ellipse(relative_curvature(flank, gear, kin, points[n])) for n in names]

    class _Cycle:
        contact, ellipse = [points[n] for n in names], ells

    on = dict(zip(names, pattern_on_flank(flank, gear, kin, _Cycle)))
    assert on["end lo"] and on["end hi"]
    assert not on.get("beyond lo", False) or lo - step < cyc.path.points[0].phi1_rad
    assert not on.get("beyond hi", False) or hi + step > cyc.path.points[-1].phi1_rad
    # the middle's flank point: a path point within half a phase step of the middle
    # (the nearer of two at a half step)
    near = [(p.u1, p.v1) for p in cyc.path.points
            if abs(p.phi1_rad - mid) <= 0.5 * step + 1e-12]
    assert run.middle_uv in near


@pytest.mark.slow
def test_f3_coast_bearing_leaves_the_edges_at_fewer_phases():
    # ~3-4 min (about 10 syntheses of one side, 40 x 50 nodes). ISO 23509 F.3 coast,
    # where the session-24 rule kept 31 of 31 edge phases (the ellipse 10.5 mm against
    # a contact-line chord of 12 mm; docs sec. 5, "The bearing's room"). The criterion
    # declared before the work: fewer edge phases than the session-24 rule's choice
    # (the mean node and the centre, computed here by the same code without
    # bearing_room), the targets met at M (the synthesis' 5 % tolerances), the full
    # TCA's TE0 vertex at M (1e-3 mm: the 40 x 50 node interpolation) and TE0 p-p not
    # above the standard settings' (the standard crowning about the mean node)
    from pathlib import Path

    from gearcontact.tca.setting_synthesis import _pivot_candidates, synthesize_settings
    pair = load_pair(Path(__file__).resolve().parents[2] / "examples" / "iso23509_f3.toml")
    side = "coast"
    node = SynthesisProblem(pair, gear_generation="formate")
    done = synthesize_settings(pair, problem=node, sides=(side,))
    options = dict(node=node, problem=dict(gear_generation="formate", gear=None))
    before = _pivot_candidates(pair, done, SynthesisTargets(), (side,), {}, False,
                               **options)[side]
    after = _pivot_candidates(pair, done, SynthesisTargets(), (side,), {}, True,
                              **options)[side]
    assert after.met, after.table()
    assert after.edge_phases < before.edge_phases
    assert after.vertex_offset_mm < 1e-3
    kin = pair.kinematics()
    flank, gear = node.flank(side, node.standard[side]), node.gear[side]
    cyc = mesh_cycle(flank, gear, kin, pinion_teeth=pair.pinion_teeth, start=node.start[side],
                     start_fixed="phi1", phases=31, pairs=2)
    assert after.tca_te0_pp_arcsec <= cyc.te0_pp_arcsec
