"""The screen of the edge check while the surface contact is inside both flanks
(tca.edge_screen; docs/machine_settings.md sec. 5, "The edge check while the surface
contact is inside (session 29)").

Truths:

(a) closed form: on a turn gap sampled from a parabola ``g(s) = a (s - s0)^2 + c``
    (second differences exact, ``2 a h^2``) the interval bound is at most the parabola's
    true minimum over each interval; an interval whose touches lie outside the other box
    by more than its reach is +inf (cannot touch); both ends unsolved: +inf (no touch,
    the exact search's rule);
(b) dense sampling: on s0003's coast at surface phases, the screen's bound of every edge
    (17 samples, refined) is at most the turn gap of 801 even points of the edge whose
    touch lies inside the other flank's box (the same point solve, :func:`edge_turns`),
    less 1e-12 rad (the point solves' tolerance 1e-9 mm over radii > 10 mm);
(b') dense sampling, the finer screen: on the calibrated s0003's coast TCA (15 phases)
    every edge screened again at FINE_SAMPLES (its bound -inf at 17) has a bound at most
    the turn gap of 801 even points whose touch lies inside the other box, less 1e-12 rad
    (as (b));
(c) an independent solver: the compiled screen (tca.screen_kernel, the default where both
    flanks have a kernel form) against the numpy path (vectorized Newton, LAPACK solves,
    the flanks' vectorized ``evaluate``) at the same surface contacts, with the Newton
    starts carried along (``memo``): the same samples solved, the same edges ruled out,
    turn gaps within 2e-10 rad and margins within 2e-9 mm (two solutions of the same
    equations, each to a residual below 1e-9 mm: 2e-9 mm over flank derivatives >= 1
    and radii >= 10 mm), lower bounds within 1e-9 rad (a bound is a sample's gap less
    ``4 |second difference| / 8`` (or ``2 g_a - g_a' - 4 |...|``): at most 4.5 times
    the gaps' error).
"""

import numpy as np
import pytest

from gearcontact.tca.edge_contact import edge_span
from gearcontact.tca.edge_screen import (CURVATURE_FACTOR, FINE_SAMPLES, edge_gaps,
                                         edge_turns, interval_bounds)


@pytest.mark.parametrize("a, s0, c", [(0.3, 0.37, 0.01), (-0.05, 0.5, 0.2), (2.0, 0.0, 1e-4)])
def test_the_interval_bound_is_below_a_parabolas_minimum(a, s0, c):
    # (a): a parabola's |g''| = 2|a| is its sampled second difference over h^2, so with
    # CURVATURE_FACTOR >= 1 the bound holds; checked against 2001 points per interval
    assert CURVATURE_FACTOR >= 1.0
    s = np.linspace(0.0, 1.0, 17)
    g = a * (s - s0) ** 2 + c
    bounds = interval_bounds(g, np.ones_like(s))
    for k in range(16):
        fine = np.linspace(s[k], s[k + 1], 2001)
        assert bounds[k] <= (a * (fine - s0) ** 2 + c).min()
    # with the samples past the middle unsolved, the interval at the boundary is bounded
    # by the extrapolation from its solved end: still below the parabola there
    g[9:] = np.nan
    bounds = interval_bounds(g, np.ones_like(s))
    fine = np.linspace(s[8], s[9], 2001)
    assert bounds[8] <= (a * (fine - s0) ** 2 + c).min()
    assert np.all(bounds[9:] == np.inf)


def test_an_interval_beyond_the_box_cannot_touch():
    # (a): touches 1 mm outside the box, flat (no curvature): +inf
    s = np.linspace(0.0, 1.0, 9)
    g = -0.1 * np.ones_like(s)
    assert np.all(interval_bounds(g, -np.ones_like(s)) == np.inf)
    assert np.all(interval_bounds(g, np.ones_like(s)) < 0.0)


def _coast_contacts(s0003_centred):
    """s0003's coast flanks, kinematics, direction and three surface contacts (the flank
    set's mean contact turned by -0.1, 0, +0.1 rad of the pinion)."""
    from gearcontact.tca.analysis import reference_start
    from gearcontact.tca.edge_contact import pushes_forward
    from gearcontact.tca.mating import solve_mating_point

    pair, flanks = s0003_centred
    pinion, gear = flanks.flank("pinion", "coast"), flanks.flank("gear", "coast")
    kin = pair.kinematics()
    start, fixed = reference_start(pair, flanks, "coast")
    mp0 = solve_mating_point(pinion, gear, kin, start, fixed=fixed)
    forward = pushes_forward(gear, kin, mp0.as_guess())
    contacts = []
    for dphi in (-0.1, 0.0, 0.1):
        guess = mp0.as_guess()
        guess = type(guess)(guess.u1, guess.v1, guess.u2, guess.v2, guess.phi1_rad + dphi,
                            guess.phi2_rad + dphi / kin.ratio)
        contacts.append(solve_mating_point(pinion, gear, kin, guess))
    return pinion, gear, kin, forward, contacts


def test_the_compiled_screen_is_the_numpy_screen(s0003_centred, monkeypatch):
    # (c): the compiled screen against the numpy path, the starts carried along both
    from gearcontact.tca import edge_screen

    pinion, gear, kin, forward, contacts = _coast_contacts(s0003_centred)
    memo_c, memo_n = {}, {}
    compared = 0
    for mp in contacts:
        assert edge_screen._compiled_screen(pinion, gear, kin, mp, edge_screen.flank_edges(
            pinion, gear), [np.linspace(0.0, 1.0, 17)] * 8, forward=forward,
            memo=None) is not None
        got = edge_gaps(pinion, gear, kin, mp, forward=forward, memo=memo_c)
        with monkeypatch.context() as m:
            m.setattr(edge_screen, "_compiled_screen", lambda *a, **k: None)
            ref = edge_gaps(pinion, gear, kin, mp, forward=forward, memo=memo_n)
        for a, b in zip(got, ref):
            assert a.edge == b.edge
            np.testing.assert_array_equal(a.s_mm, b.s_mm)
            np.testing.assert_array_equal(np.isnan(a.gap_rad), np.isnan(b.gap_rad))
            np.testing.assert_allclose(a.gap_rad, b.gap_rad, rtol=0, atol=2e-10)
            np.testing.assert_allclose(a.margin_mm, b.margin_mm, rtol=0, atol=2e-9)
            assert a.ruled_out == b.ruled_out, a.edge.label
            if np.isfinite(b.lower_rad):
                assert abs(a.lower_rad - b.lower_rad) <= 1e-9, a.edge.label
            else:
                assert a.lower_rad == b.lower_rad, a.edge.label
            compared += np.isfinite(b.gap_rad).sum()
    assert compared >= 100


def test_the_screens_bound_is_below_the_dense_gap(s0003_centred):
    # (b) on s0003's coast at three surface phases of its TCA path (the path of
    # test_tca's coast cycle is not built here: the surface points are solved from the
    # flank set's mean contact, turned by -0.1, 0, +0.1 rad of the pinion)
    pinion, gear, kin, forward, contacts = _coast_contacts(s0003_centred)
    flank = {"pinion": pinion, "gear": gear}
    checked = 0
    for mp in contacts:
        for gap in edge_gaps(pinion, gear, kin, mp, forward=forward):
            if not np.isfinite(gap.lower_rad):
                continue
            s = np.linspace(*edge_span(flank[gap.edge.member], gap.edge.name), 801)
            g, margin = edge_turns(pinion, gear, kin, mp, gap.edge, s, forward=forward)
            inside = np.isfinite(g) & (margin >= 0.0)
            if inside.any():
                assert gap.lower_rad <= g[inside].min() + 1e-12, gap.edge.label
                checked += 1
    assert checked >= 6


def test_the_finer_screens_bound_is_below_the_dense_gap(s0003_calibrated, monkeypatch):
    # (b'): the finer screens of a TCA path (their memo starts as on the path), each
    # checked against 801 points solved from the contact
    from gearcontact.tca import edge_screen
    from gearcontact.tca.analysis import analyze_pair

    pair, flanks = s0003_calibrated
    finer = []
    screen = edge_screen._screen

    def recorded(pinion, gear, kin, mp, **kw):
        out = screen(pinion, gear, kin, mp, **kw)
        if kw["samples"] == FINE_SAMPLES:
            finer.extend((pinion, gear, kin, mp, kw["forward"], got) for got in out)
        return out

    monkeypatch.setattr(edge_screen, "_screen", recorded)
    analyze_pair(pair, side="coast", phases=15, flanks=flanks)
    checked = 0
    for pinion, gear, kin, mp, forward, got in finer:
        assert got.s_mm.size == FINE_SAMPLES
        if not np.isfinite(got.lower_rad):
            continue
        flank = {"pinion": pinion, "gear": gear}[got.edge.member]
        s = np.linspace(*edge_span(flank, got.edge.name), 801)
        g, margin = edge_turns(pinion, gear, kin, mp, got.edge, s, forward=forward)
        inside = np.isfinite(g) & (margin >= 0.0)
        if inside.any():
            assert got.lower_rad <= g[inside].min() + 1e-12, got.edge.label
            checked += 1
    assert len(finer) >= 10 and checked >= 6, (len(finer), checked)   # 15 and 11
