"""The candidate choice of the local synthesis for a point-contact base pinion
(tca.setting_candidates ``pivot_candidates``, tca.setting_problem
``_path_point_on_section``; docs/machine_settings.md sec. 5, "The candidate choice for a
point-contact base"; issue 27).

Truths, declared before measuring:
- the candidates of a point-contact base are those of the declared levers and no other
  (no working depth's centre: it is no point of the base's path): M with the asked
  targets, M with the ellipse shortened to its room there (measured at M, the node
  problem), the pivot moved along the base's path to the section of the best one's
  pattern run's middle (``SynthesisProblem(pivot_uv=...)``), and the best one's pivot
  with the ellipse for a run of one pitch; the kept one is ``pivot_rank``'s first
  (tested with stand-in results, exact: the rule's order written by hand);
- a pivot moved along a point-contact base's path is a point of that path (the
  uncrowned base's local TCA at it: TE0 level < 1e-4 arcsec over a pitch, the crown-gear
  pinion's conjugacy tolerance of tests/tca/test_setting_synthesis_typed.py) on the asked
  section (1e-6 mm, the secant's stop), and the section of the default M gives the
  default M (1e-6 mm: both are the secant's stop on the same path); a section the path does not reach inside the flank is no pivot,
  the reason named (the print's drive path leaves the flank at its root 1.9 mm before
  the mean section, measured in session 23).
"""

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

from gearcontact.tca import setting_candidates as sc
from gearcontact.tca import setting_synthesis as ss
from gearcontact.tca.setting_problem import PIVOT_MARGIN, PatternRun, SynthesisProblem
from gearcontact.tca.synthesis_targets import SynthesisTargets

from . import test_setting_synthesis_typed as typed


def _result(side, pivot, edges, te0, run=None):
    """A SettingSynthesis with only what the choice reads."""
    row = ("TE0 peak-to-peak", "arcsec", 3.0, 3.0, 0.15, True)
    return ss.SettingSynthesis(side, f"setup {pivot}", np.zeros(3), None, (row,), te0,
                               ("pinion root",) * edges + ("",) * (31 - edges), 0.0, 0,
                               0.0, pivot=pivot, run=run)


class _Problem:
    """A stand-in point-contact problem: its pivot words, a room of 7 mm at M."""

    point_contact = True

    def __init__(self, name, **kw):
        self.name, self.kw = name, kw
        self.pivot = {s: name for s in ("drive", "coast")}
        self.standard = {s: np.zeros(3) for s in ("drive", "coast")}
        self.gear_setups = {"drive": "g drive", "coast": "g coast"}

    def line_room_mm(self, side, x):
        return 7.0


def test_a_point_contact_base_gets_the_declared_candidates(monkeypatch):
    # stand-ins for the syntheses: drive at the node has 31 edge phases and a pattern
    # run 0.4 pitch long in a path of 2.2 pitches, its middle 0.3 pitch before M; each
    # further candidate's edge count is set here, so the kept one is known by hand
    face = 31.75
    node = _Problem("node")
    built = []

    def problem(pair, **kw):
        built.append(kw)
        return _Problem("moved", **kw)

    edges = {"node": 31, "room": 20, "moved": 12, "length": 9}
    asked = []

    def synth(pair, *, targets, problem, sides, **options):
        (s, t), = targets.items()
        length = t.pattern_length_ratio * face
        asked.append((problem.name, s, round(length, 9)))
        room = abs(length - 7.0) < 1e-9
        kind = ("moved" if room else "length") if problem.name == "moved" else (
            "room" if room else "node")
        return {s: _result(s, problem.pivot[s], edges[kind], 3.0,
                           run=PatternRun(0.4, -0.3, (4.0, 75.0), 2.2))}

    monkeypatch.setattr(sc, "SynthesisProblem", problem)
    # levers 5 and 6 (session 27) do not apply here: their own tests below
    monkeypatch.setattr(sc, "room_pivot", lambda *a, **k: None)
    monkeypatch.setattr(sc, "turned_path_targets", lambda *a, **k: None)
    pair = SimpleNamespace(gear_face_width_mm=face, name="stand-in")
    t = SynthesisTargets(pattern_length_ratio=11.11 / face)
    done = {"drive": _result("drive", "node", 31, 15.7,
                             run=PatternRun(0.4, -0.3, (4.0, 75.0), 2.2))}
    got = sc.pivot_candidates(pair, done, t, ("drive",), {}, True, node=node,
                              problem={"gear": None}, synthesize=synth)
    # one problem built, the moved pivot on the section of the best one's run middle
    # (the room candidate: its run is the same stand-in) and nothing at a depth
    assert built == [{"gear": None, "pivot_uv": {"drive": (4.0, 75.0)}}]
    # the room at M (the node problem), then the run's pivot with the room's targets,
    # then the best one's (the moved one) pivot with 2a' = 7 (2.2 - 1) / (2.2 - 0.4)
    assert asked == [("node", "drive", 7.0), ("moved", "drive", 7.0),
                     ("moved", "drive", round(7.0 * 1.2 / 1.8, 9))]
    kept = got["drive"]
    assert kept.pivot.startswith("moved, the paint ellipse's target shortened for a "
                                 "pattern run of one pitch, 4.67 mm")
    assert kept.edge_phases == 9
    assert "node: paint ellipse at a flank edge at 31 of 31" in kept.other_pivot
    assert "its room along its major axis at M, 7.00 mm" in kept.other_pivot
    assert "moved, the middle of the pattern run of the pivot at node, the paint " \
        "ellipse's target shortened to its room along its major axis at M, 7.00 mm: paint " \
        "ellipse at a flank edge at 12 of 31" in kept.other_pivot


@pytest.fixture(scope="module")
def print_twin():
    # ~1 s: the published 10 x 41 print (its right-hand twin, the gear mirrored)
    return typed.print_twin()


def test_a_pivot_moved_along_the_base_path_is_a_path_point(print_twin):
    # ~20 s (three problems, 20 x 24 nodes)
    twin, gear = print_twin
    base = SynthesisProblem(twin, gear=gear, n_u=20, n_v=24)
    u_c, v_c = base.mean_uv["coast"]
    v_new = v_c - 4.0        # 4 mm towards the toe on the coast path (it climbs heelwards)
    v_m = float(twin.blank.pitch_point_mm[0])
    prob = SynthesisProblem(twin, gear=gear, n_u=20, n_v=24,
                            pivot_uv={"coast": (0.0, v_new), "drive": (5.0, v_m)})
    u, v = prob.mean_uv["coast"]
    assert abs(v - v_new) < 1e-6
    flank = prob.flank("coast", np.zeros(3))
    (u0, u1) = flank.u_range
    du = PIVOT_MARGIN * (u1 - u0)
    assert u0 + du <= u <= u1 - du
    m = prob.contact("coast", np.zeros(3))
    assert m.te_level_arcsec < 1e-4 and abs(m.te_slope_arcsec_per_rad) < 1e-4
    assert np.hypot(m.point.pinion_uv[0] - u, m.point.pinion_uv[1] - v) < 1e-3
    assert "pinion section v = " in prob.pivot["coast"]
    # the drive path does not reach the mean section on the flank: no pivot, the reason
    assert "drive" in prob.off_flank and "drive" not in prob.pivot
    assert f"v = {v_m:.4f} mm" in prob.off_flank["drive"]
    # the default M's own section gives the default M (drive: off the mean section);
    # 4 mm heelwards the coast path has left the flank (measured: it climbs ~0.85 mm of
    # depth per mm of face from M, which lies 2.55 mm below the tip): no pivot, the
    # section named
    u_d, v_d = base.mean_uv["drive"]
    again = SynthesisProblem(twin, gear=gear, n_u=20, n_v=24,
                             pivot_uv={"drive": (0.0, v_d), "coast": (0.0, v_c + 4.0)})
    assert np.hypot(again.mean_uv["drive"][0] - u_d, again.mean_uv["drive"][1] - v_d) < 1e-6
    assert "coast" in again.off_flank and \
        f"v = {v_c + 4.0:.4f} mm" in again.off_flank["coast"]


def test_a_run_of_length_0_shortens_the_ellipse_and_moves_no_pivot():
    # lever 4 (declared before measuring it): a path whose ellipse is at an edge at
    # every phase is a run of R = 0 in its path on the flank of P pitches; truth by
    # hand, 2a' = 2a (P - 1) / P (the print's drive, P = 2.2 in session 25: 11.11 x 1.2
    # / 2.2 mm; 1e-12 relative: arithmetic); no middle, so no run pivot
    from gearcontact.tca.setting_pivot import length_targets, run_pivot

    face = 31.75
    t = SynthesisTargets(pattern_length_ratio=11.11 / face)
    zero = PatternRun(0.0, float("nan"), (float("nan"), float("nan")), 2.2)
    r = _result("drive", "node", 31, 15.7, run=zero)
    got = length_targets(t, r, face_mm=face)
    assert got.pattern_length_ratio * face == pytest.approx(11.11 * 1.2 / 2.2, rel=1e-12)
    assert run_pivot(r) is None
    # a path on the flank not longer than a pitch: nothing to shorten for
    assert length_targets(t, _result("drive", "node", 31, 15.7, run=dataclasses.replace(
        zero, path_pitches=1.0)), face_mm=face) is None


def test_lever_5_adds_the_pivot_moved_to_the_room_with_the_best_ones_targets(monkeypatch):
    # lever 5 of "The print's drive bearing" (declared before building): after levers
    # 1-4, the best one's (here the node's: no other applies) pivot moved along the base's
    # path to room_pivot's point, synthesized with the best one's targets; kept by
    # pivot_rank where it has fewer edge phases (stand-in counts, exact)
    face = 31.75
    node = _Problem("node")
    node.line_room_mm = lambda side, x: 1.0     # below 0.1 x face: no room candidate
    built, asked, looked = [], [], []

    def problem(pair, **kw):
        built.append(kw)
        return _Problem("moved", **kw)

    def synth(pair, *, targets, problem, sides, **options):
        (s, t), = targets.items()
        asked.append((problem.name, s, t))
        return {s: _result(s, problem.pivot[s], 13, 9.8)}

    def room(result, targets, problem, *, side):
        looked.append((result.pivot, targets, problem.name, side))
        return (3.5, 78.3) if problem.name == "node" else None

    monkeypatch.setattr(sc, "SynthesisProblem", problem)
    monkeypatch.setattr(sc, "room_pivot", room)
    monkeypatch.setattr(sc, "turned_path_targets", lambda *a, **k: None)
    pair = SimpleNamespace(gear_face_width_mm=face, name="stand-in")
    t = SynthesisTargets(pattern_length_ratio=5.36 / face)
    done = {"drive": _result("drive", "node", 15, 14.65)}      # no run: levers 2-4 idle
    got = sc.pivot_candidates(pair, done, t, ("drive",), {}, True, node=node,
                              problem={"gear": None}, synthesize=synth)
    assert looked == [("node", t, "node", "drive")]
    assert built == [{"gear": None, "pivot_uv": {"drive": (3.5, 78.3)}}]
    assert asked == [("moved", "drive", t)]
    kept = got["drive"]
    assert kept.pivot == ("moved, moved along the base's path to where its room holds half "
                          "the paint ellipse, 5.36 mm, and its depth travel over half a "
                          "pitch")
    assert kept.edge_phases == 13
    assert kept.other_pivot == ("node: paint ellipse at a flank edge at 15 of 31 phases, "
                                "full TCA TE0 p-p 14.65 arcsec")


class _NoBase:
    """A problem whose every attribute but ``point_contact`` fails: room_pivot must
    decide from its arguments alone where lever 5 does not apply."""

    def __init__(self, point_contact):
        self.point_contact = point_contact

    def __getattr__(self, name):
        raise AssertionError(f"room_pivot read {name}")


def test_room_pivot_applies_only_to_a_free_point_contact_bearing_at_an_edge():
    from gearcontact.tca.setting_pivot import room_pivot

    free = SynthesisTargets()
    assert room_pivot(_result("drive", "M", 15, 14.6), free, _NoBase(False),
                      side="drive") is None          # a line-contact base
    assert room_pivot(_result("drive", "M", 0, 2.0), free, _NoBase(True),
                      side="drive") is None          # no edge phase
    assert room_pivot(_result("drive", "M", 15, 14.6), SynthesisTargets(path_angle_deg=30.0),
                      _NoBase(True), side="drive") is None     # a typed path angle


def test_room_pivot_on_the_print_moves_the_drive_pivot_to_the_room(print_twin):
    # ~7 s on a quiet machine (two problems, 40 x 50 nodes: the synthesis' grid, on
    # which the path points' conjugacy tolerance below was measured). Truths (declared with lever 5, its room
    # asking for half the ellipse a plus the margin m since session 28, and its second
    # form): the margin is the closed form of tca.setting_room_margin (1e-12 relative;
    # its pieces tested there); on each side whose M has less room than a + m the pivot
    # moves to a point of the base's path (the uncrowned base's local TCA there: TE0
    # level < 1e-4 arcsec over a pitch, the crown-gear pinion's conjugacy tolerance, as
    # above): the nearest in phase whose room holds a + m, every sampled point nearer M
    # not holding it, or, where no sampled point holds it, the one of the widest room,
    # which holds a (rooms compared exactly: the same function on the same points). The
    # stand-in results are the uncrowned base (x = 0) with lever 4's ellipse on the drive
    # (5.36 mm, session 26) and the asked one on the coast (11.11 mm)
    from gearcontact.tca.mating import solve_mating_point
    from gearcontact.tca.setting_pivot import room_need_mm, room_pivot
    from gearcontact.tca.setting_problem import line_room_mm, path_points_inside
    from gearcontact.tca.setting_room_margin import (axis_depth_rate, depth_rate_per_rad,
                                                     room_margin_mm)

    twin, gear = print_twin
    prob = SynthesisProblem(twin, gear=gear)
    face = twin.gear_face_width_mm
    kin = twin.kinematics()
    moved = {}
    for side, length in (("drive", 5.36), ("coast", 11.11)):
        t = SynthesisTargets(pattern_length_ratio=length / face)
        edge = _result(side, "M", 15, 14.6)
        uv = room_pivot(edge, t, prob, side=side)
        base, g = prob.flank(side, np.zeros(3)), prob.gear[side]
        at_m = solve_mating_point(base, g, kin, prob.start[side])
        margin = room_margin_mm(
            depth_rate_per_rad=depth_rate_per_rad(base, g, twin, prob.start[side]),
            axis_depth_rate_per_mm=axis_depth_rate(base, g, kin, at_m),
            pinion_teeth=twin.pinion_teeth)
        need = room_need_mm(edge, t, prob, side=side, at_m=at_m)
        assert margin > 0.0
        assert need == pytest.approx(0.5 * length + margin, rel=1e-12)
        room_m = line_room_mm(base, g, kin, at_m)
        assert room_m < need
        points = path_points_inside(base, g, twin, prob.start[side])
        rooms = [line_room_mm(base, g, kin, p) for p in points]
        assert uv is not None
        k = int(np.argmin([np.hypot(p.u1 - uv[0], p.v1 - uv[1]) for p in points]))
        assert np.hypot(points[k].u1 - uv[0], points[k].v1 - uv[1]) < 1e-6    # the rounding
        if rooms[k] >= need:
            gap = abs(points[k].phi1_rad - at_m.phi1_rad)
            assert all(r < need for p, r in zip(points, rooms)
                       if abs(p.phi1_rad - at_m.phi1_rad) < gap - 1e-12)
        else:
            assert max(rooms) < need and rooms[k] == max(rooms)
            assert rooms[k] >= 0.5 * length and rooms[k] > room_m
        moved[side] = uv
    again = SynthesisProblem(twin, gear=gear, pivot_uv=moved)
    for side, uv in moved.items():
        assert abs(again.mean_uv[side][1] - uv[1]) < 1e-6
        m = again.contact(side, np.zeros(3))
        assert m.te_level_arcsec < 1e-4 and abs(m.te_slope_arcsec_per_rad) < 1e-4


def test_lever_6_turns_the_best_ones_path_towards_lengthwise(monkeypatch):
    # the rule by hand (declared before measuring it on any other case): sign(a)
    # max(|a| - 30, 0), exact arithmetic; not tried on a lengthwise path (within the
    # angle tolerance, 2 deg) or where lever 5's conditions fail; wired after lever 5
    # with the best one's pivot and targets (stand-ins, exact)
    from gearcontact.tca.setting_pivot import turned_path_targets

    def at(angle, edges=15):
        return dataclasses.replace(_result("drive", "M", edges, 14.65),
                                   point=SimpleNamespace(path_angle_deg=angle))

    free, point = SynthesisTargets(), SimpleNamespace(point_contact=True)
    assert turned_path_targets(at(60.7), free, point).path_angle_deg == 60.7 - 30.0
    assert turned_path_targets(at(-45.0), free, point).path_angle_deg == -15.0
    assert turned_path_targets(at(12.0), free, point).path_angle_deg == 0.0
    assert turned_path_targets(at(1.0), free, point) is None
    assert turned_path_targets(at(60.7, edges=0), free, point) is None
    assert turned_path_targets(at(60.7), free, SimpleNamespace(point_contact=False)) is None
    assert turned_path_targets(at(60.7), SynthesisTargets(path_angle_deg=60.0), point) is None

    face = 31.75
    node = _Problem("node")
    node.line_room_mm = lambda side, x: 1.0     # below 0.1 x face: no room candidate
    asked = []

    def synth(pair, *, targets, problem, sides, **options):
        (s, t), = targets.items()
        asked.append((problem.name, t.path_angle_deg))
        return {s: _result(s, problem.pivot[s], 13, 9.8)}

    monkeypatch.setattr(sc, "room_pivot", lambda *a, **k: None)
    pair = SimpleNamespace(gear_face_width_mm=face, name="stand-in")
    t = SynthesisTargets(pattern_length_ratio=5.36 / face)
    got = sc.pivot_candidates(pair, {"drive": at(60.7)}, t, ("drive",), {}, True,
                              node=node, problem={"gear": None}, synthesize=synth)
    assert asked == [("node", 60.7 - 30.0)]
    assert got["drive"].pivot == "node, its path at M turned towards lengthwise to 30.7 deg"
    assert got["drive"].edge_phases == 13
