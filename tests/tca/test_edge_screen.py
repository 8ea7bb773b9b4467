"""The screen of the edge check while the surface contact is inside both flanks
(tca.edge_screen; docs/machine_settings.md sec. 5, "The edge check while the surface
contact is inside (session 29)").

Truths:

(a) closed form: on a separation sampled from a parabola ``d(s) = a (s - s0)^2 + c``
    (second differences exact, ``2 a h^2``) the interval bound is at most the parabola's
    true minimum over each interval; an interval whose hits lie outside the other box by
    more than its reach is +inf (cannot touch), one next to a NaN sample -inf;
(b) dense sampling: on s0003's drive at surface phases, the screen's bound of every edge
    (17 samples) is at most the separation of 801 even points of the edge whose line hit
    lies inside the other flank's box, less 1e-9 mm (the line intersections' tolerance).
"""

import numpy as np
import pytest

from gearcontact.tca.edge_contact import edge_parameters, edge_span
from gearcontact.tca.edge_screen import (CURVATURE_FACTOR, edge_gaps, interval_bounds_mm)
from gearcontact.tca.stencil import _intersect_many, evaluate_many


@pytest.mark.parametrize("a, s0, c", [(0.3, 0.37, 0.01), (-0.05, 0.5, 0.2), (2.0, 0.0, 1e-4)])
def test_the_interval_bound_is_below_a_parabolas_minimum(a, s0, c):
    # (a): a parabola's |d''| = 2|a| is its sampled second difference over h^2, so with
    # CURVATURE_FACTOR >= 1 the bound holds; checked against 2001 points per interval
    assert CURVATURE_FACTOR >= 1.0
    s = np.linspace(0.0, 1.0, 17)
    d = a * (s - s0) ** 2 + c
    bounds = interval_bounds_mm(d, np.ones_like(s), np.zeros_like(s))
    for k in range(16):
        fine = np.linspace(s[k], s[k + 1], 2001)
        assert bounds[k] <= (a * (fine - s0) ** 2 + c).min()


def test_an_interval_beyond_the_box_cannot_touch_and_a_nan_is_unknown():
    # (a): hits 1 mm outside the box, flat (no curvature, no shift): +inf; a NaN sample
    # makes the intervals whose bound it enters (its own and the next ones) -inf
    s = np.linspace(0.0, 1.0, 9)
    d = -0.1 * np.ones_like(s)
    assert np.all(interval_bounds_mm(d, -np.ones_like(s), np.zeros_like(s)) == np.inf)
    d[4] = np.nan
    got = interval_bounds_mm(d, np.ones_like(s), np.zeros_like(s))
    assert np.all(got[2:6] == -np.inf) and np.all(np.isfinite(got[[0, 7]]))


def _dense_gaps(pinion, gear, kin, mp, gap, points=801):
    """The separation d and the hit's box margin at ``points`` even points of one edge,
    each line started from the linear interpolation of the screen's own converged hits
    (the same line intersection, :func:`_intersect_many`)."""
    flank = {"pinion": pinion, "gear": gear}
    own = gap.edge.member
    other = "gear" if own == "pinion" else "pinion"
    poses = {"pinion": kin.pinion_pose(mp.phi1_rad), "gear": kin.gear_pose(mp.phi2_rad)}
    s = np.linspace(*edge_span(flank[own], gap.edge.name), points)
    uv = np.array([edge_parameters(flank[own], gap.edge.name, float(t)) for t in s])
    q = evaluate_many(flank[own], uv[:, 0], uv[:, 1])[0] @ poses[own][0].T + poses[own][1]
    n = np.asarray(mp.normal, float)
    start = np.array([(mp.u2, mp.v2) if other == "gear" else (mp.u1, mp.v1)] * points, float)
    hit = np.empty_like(start)
    lam, _ = _intersect_many(flank[other], poses[other], q, n, start, clamp=False,
                             tol_mm=1e-9, uv_out=hit)
    d = -lam if own == "pinion" else lam
    (u0, u1), (v0, v1) = flank[other].u_range, flank[other].v_range
    margin = np.minimum.reduce([hit[:, 0] - u0, u1 - hit[:, 0], hit[:, 1] - v0, v1 - hit[:, 1]])
    return d, margin


def test_the_screens_bound_is_below_the_dense_gap(s0003_centred, s0003_drive):
    # (b) at three surface phases of s0003's drive cycle (its first, middle and last
    # surface contact), every edge whose bound is finite
    pair, flanks = s0003_centred
    pinion, gear = flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")
    kin = pair.kinematics()
    surface = [mp for mp in s0003_drive.cycle.contact if not mp.edge_contact]
    checked = 0
    for mp in (surface[0], surface[len(surface) // 2], surface[-1]):
        for gap in edge_gaps(pinion, gear, kin, mp):
            if not np.isfinite(gap.lower_mm):
                continue
            d, margin = _dense_gaps(pinion, gear, kin, mp, gap)
            inside = np.isfinite(d) & (margin >= 0.0)
            if inside.any():
                assert gap.lower_mm <= d[inside].min() + 1e-9, gap.edge.label
                checked += 1
    assert checked >= 6
