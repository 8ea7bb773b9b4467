"""The bearing's depth against the flank's and lever 7 (tca.setting_band, tca.setting_pivot
``depth_targets``, tca.setting_candidates; docs/machine_settings.md sec. 5, "The bearing's
depth: room against need", session 29; issue 27).

Truths, declared with the rule (before building it):
- ``ellipse_depth_half_mm`` is the largest ``u`` of the mapped outline ``a cos t du/ds + b
  sin t du/dt``: against a brute-force maximum over 200001 outline points (1e-9
  relative: the grid's step 3e-5 rad leaves a cosine deficit below (3e-5)^2 / 2);
- ``DepthNeed``: ``N = D + 2 h`` by hand (1e-12), the fitting length against an independent
  bisection of ``D + 2 h(a') = W`` (1e-9 relative: the bisection's stop), and the verdicts
  at hand-picked numbers on either side of each threshold (exact);
- ``depth_need`` at s0003-centred's drive mean point: the axes' depth rates by Cramer's
  rule with cross products, ``du/ds = ((e_s x r_v).n) / ((r_u x r_v).n)``, ``du/dt`` the
  same with ``e_t = n x e_s`` (1e-9 relative: the same 2 x 2 algebra, the subtraction of
  ``u1`` costing ~1e-14 of a rate ~ 1), the ellipse the TCA's at M (==), the travel ``(2 pi
  / z1) |du1/dphi1|`` of tca.setting_room_margin's rate (1e-12), the room the box's depth;
- lever 7 (``depth_targets``) by hand: where it applies, the ellipse of the fitting length
  and lever 6's turn once more, in that order (exact); nowhere else (exact).
"""

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from gearcontact.tca import setting_candidates as sc
from gearcontact.tca import setting_synthesis as ss
from gearcontact.tca.setting_band import DepthNeed, depth_need, ellipse_depth_half_mm
from gearcontact.tca.setting_pivot import depth_fitting_targets, depth_targets
from gearcontact.tca.synthesis_targets import SynthesisTargets


def test_the_ellipse_depth_half_against_brute_force():
    t = np.linspace(0.0, 2.0 * np.pi, 200001)
    for a, b, us, ut in ((2.68, 0.58, -0.468, 0.31), (4.2, 0.44, 0.1, -0.9),
                         (1.0, 1.0, 0.0, 0.5), (3.0, 0.2, -0.7, 0.0)):
        brute = np.max(a * np.cos(t) * us + b * np.sin(t) * ut)
        assert ellipse_depth_half_mm(a, b, us, ut) == pytest.approx(brute, rel=1e-9)


def _need(**kw):
    base = dict(travel_mm=4.35, semi_major_mm=2.68, semi_minor_mm=0.58, du_ds=-0.468,
                du_dt=0.31, room_mm=6.65, shortest_mm=3.175)
    return DepthNeed(**{**base, **kw})


def test_the_need_and_the_fitting_ellipse_by_hand():
    d = _need()
    h = math.sqrt((2.68 * 0.468) ** 2 + (0.58 * 0.31) ** 2)
    assert d.half_mm == pytest.approx(h, rel=1e-12)
    assert d.need_mm == pytest.approx(4.35 + 2.0 * h, rel=1e-12)
    # the fitting length: bisection on a' of D + 2 h(a') = W (h rising in a')
    lo, hi = 0.0, 10.0
    while hi - lo > 1e-13:
        mid = 0.5 * (lo + hi)
        if 4.35 + 2.0 * ellipse_depth_half_mm(mid, 0.58, -0.468, 0.31) > 6.65:
            hi = mid
        else:
            lo = mid
    assert d.fitting_length_mm() == pytest.approx(2.0 * lo, rel=1e-9)
    assert d.verdict() == "shorter"          # N 6.87 > 6.65, 2a' 4.85 >= 3.175
    assert "an ellipse of 4.85 mm would fit" in d.text()


def test_the_verdicts_at_their_thresholds():
    assert _need(travel_mm=2.0).verdict() == "fits"             # N 4.53 <= 6.65
    assert "it fits" in _need(travel_mm=2.0).text()
    # the shortest ellipse 3.175 mm fits while D + 2 h(1.5875) <= W: D <= 5.10 here
    h_min = ellipse_depth_half_mm(3.175 / 2.0, 0.58, -0.468, 0.31)
    assert _need(travel_mm=6.65 - 2.0 * h_min - 1e-6).verdict() == "shorter"
    assert _need(travel_mm=6.65 - 2.0 * h_min + 1e-6).verdict() == "none"
    assert "nor with any ellipse of at least 3.17 mm" in _need(travel_mm=5.5).text()
    # the travel and the width alone fill the depth: no ellipse; a length taking no
    # depth: any
    assert _need(travel_mm=6.65 - 2.0 * 0.58 * 0.31 + 1e-9).fitting_length_mm() == 0.0
    assert _need(du_ds=0.0, travel_mm=6.0).fitting_length_mm() == math.inf
    assert _need(du_ds=0.0, travel_mm=6.0).verdict() == "fits"


def test_depth_need_at_s0003s_mean_point(s0003_centred, s0003_drive):
    # ~2 s: the production flanks, the TCA's mean point
    from gearcontact.tca.curvature import contact_ellipse, relative_curvature
    from gearcontact.tca.mating import solve_mating_point
    from gearcontact.tca.setting_room_margin import depth_rate_per_rad

    pair, flanks = s0003_centred
    pinion, gear = flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")
    start = s0003_drive.mean_point.as_guess()
    kin = pair.kinematics()
    got = depth_need(pinion, gear, pair, start, shortest_mm=1.2)
    mp = solve_mating_point(pinion, gear, kin, start)
    rc = relative_curvature(pinion, gear, kin, mp)
    rot = kin.pinion_pose(mp.phi1_rad)[0]
    sp = pinion.point(mp.u1, mp.v1)
    r_u, r_v, n = rot @ sp.r_u, rot @ sp.r_v, rc.normal
    e_s = rc.dir_min
    e_t = np.cross(n, e_s)
    det = np.dot(np.cross(r_u, r_v), n)
    assert got.du_ds == pytest.approx(np.dot(np.cross(e_s, r_v), n) / det, rel=1e-9)
    assert got.du_dt == pytest.approx(np.dot(np.cross(e_t, r_v), n) / det, rel=1e-9)
    ell = contact_ellipse(rc)
    assert (got.semi_major_mm, got.semi_minor_mm) == (ell.semi_major_mm, ell.semi_minor_mm)
    rate = depth_rate_per_rad(pinion, gear, pair, start)
    assert got.travel_mm == pytest.approx(2.0 * math.pi / pair.pinion_teeth * abs(rate),
                                          rel=1e-12)
    assert got.room_mm == pinion.u_range[1] - pinion.u_range[0]
    assert got.shortest_mm == 1.2


def _kept(edges=12, angle=25.0, need=None):
    """A SettingSynthesis with what lever 7 reads."""
    row = ("TE0 peak-to-peak", "arcsec", 3.0, 3.0, 0.15, True)
    return ss.SettingSynthesis("drive", "setup", np.zeros(3),
                               SimpleNamespace(path_angle_deg=angle), (row,), 1.5,
                               ("pinion root",) * edges + ("",) * (31 - edges), 0.0, 0,
                               0.0, pivot="M", depth=_need() if need is None else need)


def test_lever_7_by_hand():
    face = 31.75
    free = SynthesisTargets(pattern_length_ratio=5.36 / face)
    turned = dataclasses.replace(free, path_angle_deg=25.0)      # lever 6's
    point = SimpleNamespace(point_contact=True)
    got = depth_targets(_kept(), turned, point, asked=free, face_mm=face)
    assert [t for t, _ in got] == [
        dataclasses.replace(turned, pattern_length_ratio=_need().fitting_length_mm() / face),
        dataclasses.replace(turned, path_angle_deg=0.0)]
    assert got[1][1] == ", its path at M turned towards lengthwise once more, to 0.0 deg"
    # a free path (lever 6 tried it already): the ellipse only
    assert [t for t, _ in depth_targets(_kept(angle=55.0), free, point, asked=free,
                                        face_mm=face)] == [
        dataclasses.replace(free, pattern_length_ratio=_need().fitting_length_mm() / face)]
    # verdict "none": the turn only; a path within 2 deg of lengthwise: not turned
    none = _need(travel_mm=5.5)
    assert [t.path_angle_deg for t, _ in depth_targets(
        _kept(need=none), turned, point, asked=free, face_mm=face)] == [0.0]
    assert depth_targets(_kept(need=none, angle=1.5), turned, point, asked=free,
                         face_mm=face) == []
    # nowhere else: fits, no edge phase, a line-contact base, a typed path angle, no need
    for r, p, asked in ((_kept(need=_need(travel_mm=2.0)), point, free),
                        (_kept(edges=0), point, free),
                        (_kept(), SimpleNamespace(point_contact=False), free),
                        (_kept(), point, dataclasses.replace(free, path_angle_deg=25.0)),
                        (dataclasses.replace(_kept(), depth=None), point, free)):
        assert depth_targets(r, turned, p, asked=asked, face_mm=face) == []


def test_lever_7_is_wired_after_lever_6(monkeypatch):
    # stand-ins (exact): the best one after levers 1-6 (lever 6's path, 25 deg) gets
    # lever 7's two candidates at its pivot; the kept one is the rank's first
    face = 31.75
    node = SimpleNamespace(point_contact=True, pivot={"drive": "node"},
                           standard={"drive": np.zeros(3)},
                           gear_setups={"drive": "g", "coast": "g"},
                           line_room_mm=lambda side, x: 1.0)
    asked = []

    def synth(pair, *, targets, problem, sides, **options):
        (s, t), = targets.items()
        asked.append((round(t.pattern_length_ratio * face, 9), t.path_angle_deg))
        edges = {None: 15, 25.0: 12, 0.0: 4}.get(t.path_angle_deg, 7)
        if t.path_angle_deg == 25.0 and t.pattern_length_ratio * face < 5.3:
            edges = 9
        return {s: _kept(edges=edges, angle=t.path_angle_deg or 55.0)}

    built = []

    def problem(pair, **kw):
        built.append(kw)
        return SimpleNamespace(point_contact=True, pivot={"drive": "centred"})

    monkeypatch.setattr(sc, "room_pivot", lambda *a, **k: None)
    monkeypatch.setattr(sc, "SynthesisProblem", problem)
    # 7c: the base path's point at the depth's middle (its rule: the slow test below)
    monkeypatch.setattr(sc, "depth_centre_pivot", lambda r, prob, *, side, asked: (
        (5.77, 73.9) if r.point.path_angle_deg == 25.0 else None))
    pair = SimpleNamespace(gear_face_width_mm=face, name="stand-in")
    t = SynthesisTargets(pattern_length_ratio=5.36 / face)
    start = dataclasses.replace(_kept(edges=15, angle=55.0), pivot="node")
    got = sc.pivot_candidates(pair, {"drive": start}, t, ("drive",), {}, True, node=node,
                              problem={"gear": None}, synthesize=synth)
    fit = round(_need().fitting_length_mm(), 9)
    # lever 7 on lever 6's candidate: the fitting ellipse, the path turned to 0, then
    # the fitting ellipse (lever 6's path kept) at the pivot moved to the depth's middle
    assert asked == [(5.36, 25.0), (fit, 25.0), (5.36, 0.0), (fit, 25.0)]
    assert built == [{"gear": None, "pivot_uv": {"drive": (5.77, 73.9)}}]
    assert got["drive"].edge_phases == 4
    assert got["drive"].pivot == ("M, its path at M turned towards lengthwise once more, "
                                  "to 0.0 deg")
    assert "M, moved along the base's path to the middle of the working depth, the paint " \
        f"ellipse's target {fit:.2f} mm: paint ellipse at a flank edge at 9 of 31" in \
        got["drive"].other_pivot


def test_depth_fitting_targets_by_hand():
    face = 31.75
    t = SynthesisTargets(pattern_length_ratio=5.36 / face, path_angle_deg=25.0)
    assert depth_fitting_targets(_kept(), t, face_mm=face) == dataclasses.replace(
        t, pattern_length_ratio=_need().fitting_length_mm() / face)
    # not "shorter", or no need: the targets as they are
    for need in (_need(travel_mm=2.0), _need(travel_mm=5.5)):
        assert depth_fitting_targets(_kept(need=need), t, face_mm=face) is t
    assert depth_fitting_targets(dataclasses.replace(_kept(), depth=None), t,
                                 face_mm=face) is t


@pytest.mark.slow
def test_depth_centre_pivot_on_the_print():
    # ~15 s (a problem of the print's twin, 40 x 50 nodes, and its base path's samples).
    # The rule by hand (exact): the sampled base path point whose u is nearest the
    # middle of the working depth, a point of path_points_inside; not applied where
    # lever 7 does not apply (stand-in results, as test_lever_7_by_hand)
    from gearcontact.tca.mating import solve_mating_point
    from gearcontact.tca.setting_pivot import depth_centre_pivot
    from gearcontact.tca.setting_problem import (PIVOT_MARGIN, SynthesisProblem,
                                                 path_points_inside)

    from . import test_setting_synthesis_typed as typed

    twin, gear = typed.print_twin()
    prob = SynthesisProblem(twin, gear=gear)
    free = SynthesisTargets()
    uv = depth_centre_pivot(_kept(), prob, side="drive", asked=free)
    pinion, g = prob.flank("drive", np.zeros(3)), prob.gear["drive"]
    points = path_points_inside(pinion, g, twin, prob.start["drive"], margin=PIVOT_MARGIN)
    middle = 0.5 * sum(pinion.u_range)
    best = min(abs(p.u1 - middle) for p in points)
    hits = [p for p in points if abs(p.u1 - middle) == best]
    assert uv == (round(float(hits[0].u1), 6), round(float(hits[0].v1), 6))
    at_m = solve_mating_point(pinion, g, twin.kinematics(), prob.start["drive"])
    assert abs(uv[0] - at_m.u1) > 0.05
    assert depth_centre_pivot(_kept(need=_need(travel_mm=2.0)), prob, side="drive",
                              asked=free) is None
    assert depth_centre_pivot(_kept(), prob, side="drive", asked=dataclasses.replace(
        free, path_angle_deg=25.0)) is None


def test_the_need_is_written_beside_the_pivot_where_the_bearing_reaches_an_edge():
    # the head comment's line (report.design writes pivot_text), exact words: after the
    # pivot's line where the paint ellipse reaches an edge, not otherwise, nor without a
    # need
    point = SimpleNamespace(path_angle_deg=25.0, pinion_uv=(5.194, 75.088))
    r = dataclasses.replace(_kept(), point=point)
    pivot, depth = r.pivot_text().split("\n")
    assert pivot == "drive: pivot M at M, pinion (u, v) = 5.194, 75.088 mm"
    assert depth == ("drive: the bearing's depth over a pitch: the contact travels 4.35 mm "
                     "and the paint ellipse (2a 5.36 mm) spans 2.53 mm, 6.88 mm against the "
                     "flank's 6.65 mm: no placement holds it; an ellipse of 4.85 mm would "
                     "fit (first order at M, docs/machine_settings.md sec. 5)")
    assert dataclasses.replace(r, edges=("",) * 31).pivot_text() == pivot
    assert dataclasses.replace(r, depth=None).pivot_text() == pivot
