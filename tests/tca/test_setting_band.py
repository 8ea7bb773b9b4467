"""The bearing's depth against the flank's (tca.setting_band, written by
tca.setting_synthesis; docs/machine_settings.md sec. 5, "The bearing's depth: room against
need", session 29; issue 27).

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
"""

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from gearcontact.tca import setting_synthesis as ss
from gearcontact.tca.setting_band import DepthNeed, depth_need, ellipse_depth_half_mm


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
