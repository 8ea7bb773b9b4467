"""The pivot's depth of the local synthesis of the pinion settings
(tca.setting_problem ``pivot_depth``, tca.setting_synthesis ``synthesized_machine_pair``;
docs/machine_settings.md sec. 5, "The pivot's depth").

The target, declared before measuring: the bearing centre M at the middle of the pinion's
working depth on the mean section (``SynthesisTargets.centre_profile``, 0.5, the ease-off
synthesis' own centre), for a line-contact base pinion, whose every flank point lies on a
contact line. The pair: the hypoid s0003-centred's blank (formate gear), whose mean
node lies 0.32 mm below the gear tip (gear addendum factor 0.15) where the paint
ellipse of the default length (4.2 mm along the contact line at -19 deg) spans
+-0.69 mm of depth: the pattern reached a flank edge at 31 of 31 phases, with the
standard settings and with the synthesis about the mean node (docs sec. 5).

Truths: the centred pivot is a contact point of the conjugate pair (exact line contact)
and every correction keeps it, its normal and the ratio there (independent envelope
solves, as for the mean node in test_setting_synthesis_line_contact.py); the paint
ellipse at M lies on both flanks at the centre and not at the mean node (the depth
argument above); the criterion of success (the lead's, declared before the work):
fewer phases with the paint ellipse at a flank edge, TE0 p-p not above the standard
settings', the targets met at M to the synthesis' tolerances.
"""

import dataclasses
import math

import numpy as np
import pytest

from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.generated import EnvelopeSolver, mean_contact_guess
from gearcontact.geometry.pair import load_pair, without_easeoff
from gearcontact.tca.analysis import pattern_on_flank
from gearcontact.tca.curvature import contact_ellipse, relative_curvature
from gearcontact.tca.edges import pattern_edges
from gearcontact.tca.mating import solve_mating_point
from gearcontact.tca.mesh import mesh_cycle
from gearcontact.tca.setting_problem import SynthesisProblem, corrected_setup, pattern_run
from gearcontact.tca.setting_pivot import better_pivot as _better_pivot
from gearcontact.tca.setting_synthesis import (SettingSynthesis,
                                               synthesize_settings)
from gearcontact.tca.stencil import gap_at
from gearcontact.tca.types import EdgeContact

SIDE = "drive"


@pytest.fixture(scope="module")
def problems():
    # ~8 s: the s0003-centred blank's formate gear and complementary pinion, 40 x 50
    # nodes, pivoting on the mean node and on the working depth's centre
    pair = without_easeoff(load_pair("s0003-centred"))
    return {d: SynthesisProblem(pair, gear_generation="formate", pivot_depth=d)
            for d in (None, 0.5)}


def test_centred_pivot_is_a_contact_point_kept_by_every_correction(problems):
    prob = problems[0.5]
    pair = prob.pair
    pitch = 2.0 * math.pi / pair.pinion_teeth
    for side in SIDES:
        base_flank = prob.flank(side, np.zeros(3))
        (u_root, u_tip), v_m = base_flank.u_range, float(pair.blank.pitch_point_mm[0])
        u, v = prob.mean_uv[side]
        # the middle of the working depth on the mean section (the pinion flank box's
        # root and tip; 1e-12 mm: arithmetic), above the mean node (0.15 of the depth)
        assert u == pytest.approx(0.5 * (u_root + u_tip), abs=1e-12)
        assert v == pytest.approx(v_m, abs=1e-12)
        assert u - problems[None].mean_uv[side][0] > 0.5
        # a contact point of the conjugate pair: the nearest touch of the base pinion's
        # point leaves no gap and a common normal (line contact; 1e-6 mm / 1e-4 deg:
        # the 40 x 50 node interpolation of the generated flank)
        touch = mean_contact_guess(base_flank, prob.gear[side],
                                   pair.kinematics(with_errors=False), pinion_uv=(u, v),
                                   gear_uv=(prob.start[side].u2, prob.start[side].v2))
        assert touch["gap_mm"] < 1e-6 and touch["normal_angle_deg"] < 1e-4
        # every correction keeps M and its normal (exact envelope node solves to 1e-10;
        # 1e-9 mm / 1e-12 as for the mean node) and the nominal ratio there (the TE
        # parabola's vertex within 1e-3 of a pitch of M's phase, the contact at M's
        # phase M within 1e-3 mm: the local TCA's five-point difference on 40 x 50 nodes)
        solver = EnvelopeSolver(prob.base[side], pair.blank, prob.cone)
        m0 = solver.solve(u, v, solver.initial_guess(u, v))
        for dx in ([0.0, 0.0, 0.0], [0.02, 0.0, 0.0], [0.0, 1e-3, 0.0], [0.0, 0.0, 1.5]):
            s = corrected_setup(prob.base[side], prob.standard[side] + np.array(dx),
                                mean=prob.means[side])
            m1 = EnvelopeSolver(s, pair.blank, prob.cone).solve(u, v, m0.q)
            assert np.abs(m1.x_mm - m0.x_mm).max() < 1e-9
            assert np.abs(m1.n - m0.n).max() < 1e-12
        m = prob.contact(side, prob.standard[side])
        assert abs(m.te_slope_arcsec_per_rad / m.te_curvature_arcsec_per_rad2) < 1e-3 * pitch
        assert np.hypot(m.point.pinion_uv[0] - u, m.point.pinion_uv[1] - v) < 1e-3


def _paint_on_flank(prob, side):
    """Is the paint ellipse at M (the standard crowning about M) on both flanks?"""
    pair = prob.pair
    kin = pair.kinematics()
    flank, gear = prob.flank(side, prob.standard[side]), prob.gear[side]
    mp = solve_mating_point(flank, gear, kin, prob.start[side])
    ell = contact_ellipse(relative_curvature(flank, gear, kin, mp))
    theta = 2.0 * np.pi * np.arange(16) / 16
    field = gap_at(flank, gear, kin, mp, ell.semi_major_mm * np.cos(theta),
                   ell.semi_minor_mm * np.sin(theta), frame="principal")
    return bool(field.on_flank.all())


def test_paint_ellipse_at_m_fits_the_depth_at_the_centre_only(problems):
    # the depth argument (docs sec. 5): at the mean node the ellipse's +-0.69 mm of
    # depth passes the gear tip 0.32 mm above; at the centre it has +-1.08 mm
    for side in SIDES:
        assert not _paint_on_flank(problems[None], side)
        assert _paint_on_flank(problems[0.5], side)


def _edge_phases(prob, side, x, phases=31):
    """(phases with the paint ellipse at a flank edge, TE0 p-p) of the full TCA."""
    pair = prob.pair
    kin = pair.kinematics()
    flank, gear = prob.flank(side, x), prob.gear[side]
    cyc = mesh_cycle(flank, gear, kin, pinion_teeth=pair.pinion_teeth,
                     start=prob.start[side], start_fixed="phi1", phases=phases, pairs=2)
    edges = pattern_edges(flank, gear, kin, cyc, pattern_on_flank(flank, gear, kin, cyc))
    return sum(1 for e in edges if e), float(cyc.te0_pp_arcsec)


def test_standard_crowning_about_the_centre_leaves_the_edges_at_fewer_phases(problems):
    # ~5 s: the standard crowning (25 / 10 um) about each pivot, the full TCA over one
    # pitch (31 phases, 40 x 50 nodes); criterion: fewer edge phases at the centre
    at_node, _ = _edge_phases(problems[None], SIDE, problems[None].standard[SIDE])
    at_centre, _ = _edge_phases(problems[0.5], SIDE, problems[0.5].standard[SIDE])
    assert at_centre < at_node


@pytest.mark.slow
def test_synthesis_about_the_centre_keeps_the_bearing_off_the_edges(problems):
    # ~1 min: the drive side synthesized about both pivots (default targets: TE0 3
    # arcsec, paint ellipse 0.35 x face, path free). The lead's criterion: fewer edge
    # phases than the mean node's synthesis, TE0 p-p not above the standard settings'
    # (the standard crowning about the mean node: the standard pinion, tested to 1e-9
    # in test_setting_synthesis_line_contact.py), the targets met at M within the
    # synthesis' tolerances (5 % of TE level and ellipse length) with the full TCA's
    # TE0 vertex at M (1e-3 mm: the 40 x 50 node interpolation)
    node, centre = problems[None], problems[0.5]
    pair = node.pair
    at_node = synthesize_settings(pair, problem=node, sides=(SIDE,))[SIDE]
    got = synthesize_settings(pair, problem=centre, sides=(SIDE,))[SIDE]
    assert got.met, got.table()
    assert got.vertex_offset_mm < 1e-3
    assert got.point.pinion_uv[0] == pytest.approx(centre.mean_uv[SIDE][0], abs=1e-3)
    _, standard_te0 = _edge_phases(node, SIDE, node.standard[SIDE])
    assert got.tca_te0_pp_arcsec <= standard_te0
    assert got.edge_phases < at_node.edge_phases
    # synthesized_machine_pair keeps it, naming the other pivot's check
    kept = _better_pivot(at_node, got)
    assert kept.x is got.x and "mean node" in kept.other_pivot


def _result(pivot, edges, te0, met=True):
    """A SettingSynthesis with only what the pivot's choice reads."""
    row = ("TE0 peak-to-peak", "arcsec", 3.0, 3.0, 0.15, met)
    return SettingSynthesis("drive", None, np.zeros(3), None, (row,), te0,
                            ("pinion root",) * edges + ("",) * (31 - edges), 0.0, 0, 0.0,
                            pivot=pivot)


def test_the_pivot_kept_is_the_one_with_fewer_edge_phases():
    # the rule (docs sec. 5): fewer edge phases; a tie: the lower TE0 p-p; a missed
    # target loses; the dropped pivot's check is named
    node, centre = "the blank's mean node", "0.50 of the pinion's working depth"
    kept = _better_pivot(_result(node, 31, 2.9), _result(centre, 17, 3.0))
    assert kept.pivot == centre and "mean node: paint ellipse at a flank edge at 31 of 31" \
        in kept.other_pivot
    assert _better_pivot(_result(node, 31, 2.78), _result(centre, 31, 35.7)).pivot == node
    assert _better_pivot(_result(node, 12, 2.9), _result(centre, 3, 2.9, met=False)).pivot \
        == node


# session 25, the bearing's room (test_setting_pivot_room.py): line_room_mm and
# pattern_run against independent evaluations, fresh mating-point solves at the run's
# neighbour phases and the paint ellipse's outline (gap_at) projected on the flanks

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
