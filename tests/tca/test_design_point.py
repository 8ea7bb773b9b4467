"""tca.design_point: the centre form of the ease-off with its constant as a rigid turn,
the turn's relief, the surface contact ratio of a design point's pair.

Independent truths:
(a) polynomial identity: the coefficients written with ``turn`` are the centred
    quadratic ``Q(p - c)`` minus the relief at the centre carried as a turn,
    ``E(p) = Q(p - c) - Q0 (1 + T(p))`` with ``Q0 = Q(mean - c)`` and ``T`` the turn
    polynomial, at every point (and without ``turn`` the old form ``Q(p - c) - Q0``);
(b) the lever ``L = n . (e_x x r)`` evaluated by its definition on the flank, at
    points off the grid :func:`turn_relief` fits it on: ``L(p) / L(mean) - 1`` held by
    the five terms to a stated residual;
(c) counting: the run of surface points through a phase, in pitches.
"""

import numpy as np
import pytest

from gearcontact.geometry.easeoff import EaseOff
from gearcontact.tca.design_point import (centred_coefficients, surface_contact_ratio,
                                          turn_relief)


def test_turn_coefficients_carry_the_centre_relief_as_a_turn():
    # (a) to 1e-12 um (round-off of terms of ~100 um)
    eta_c, xi_c, pc, lc, tw = 3.66, -1.2, 2.45, 0.0066, 0.04
    turn = np.array([5.9e-3, 1.48e-2, 1.2e-5, -9.8e-5, -8.7e-5])
    u_m, v_m = 4.96, 57.47
    rng = np.random.default_rng(1)
    u = u_m + rng.uniform(-3.0, 10.0, 20)
    v = v_m + rng.uniform(-9.0, 9.0, 20)
    eta, xi = u - u_m, v - v_m
    q = pc * (eta - eta_c) ** 2 + lc * (xi - xi_c) ** 2 + tw * (xi - xi_c) * (eta - eta_c)
    q0 = pc * eta_c ** 2 + lc * xi_c ** 2 + tw * xi_c * eta_c
    t = turn @ np.array([eta, xi, eta ** 2, xi ** 2, xi * eta])
    for with_turn, want in ((True, q - q0 * (1.0 + t)), (False, q - q0)):
        co = centred_coefficients(eta_c, xi_c, pc, lc, tw, turn=turn if with_turn else None)
        got = 1e3 * EaseOff.from_coefficients(co, u_mean_mm=u_m, v_mean_mm=v_m).relief_mm(u, v)
        assert np.max(np.abs(got - want)) < 1e-12


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_turn_relief_holds_the_lever_over_the_flank(s0003_centred, side):
    # (b) on s0003-centred's pinion flanks, at points of the active box off the fit's
    # grid: the relative lever varies by ~0.3 over the box, and the five terms hold it
    # to 2e-3 (measured 4.0e-4 drive, 9.9e-4 coast): a relief Q0 at the centre of 30 um
    # (the 20/20 miter's) is carried as a turn to 0.06 um
    pair, flanks = s0003_centred
    conj = flanks.pinion_conjugate.side(side)
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    t = turn_relief(conj, (u_m, v_m))
    b = conj.boundary
    rng = np.random.default_rng(2)
    u = np.r_[u_m, rng.uniform(b.u_root, b.u_tip, 30)]
    v = np.r_[v_m, rng.uniform(b.v_toe, b.v_heel, 30)]
    s = conj.evaluate(u, v, second=False)
    lever = np.einsum("ni,ni->n", s.n, np.cross(np.array([1.0, 0.0, 0.0]), s.r))
    want = lever[1:] / lever[0] - 1.0
    du, dv = u[1:] - u_m, v[1:] - v_m
    got = t @ np.array([du, dv, du ** 2, dv ** 2, du * dv])
    assert np.ptp(want) > 0.1                  # the lever varies over the flank
    assert np.max(np.abs(got - want)) < 2e-3


class _Path:
    def __init__(self, surface):
        self.surface = np.array(surface, bool)


@pytest.mark.parametrize("surface, index, want", [
    ([0, 1, 1, 1, 1, 0, 1], 2, 4 / 4),     # four surface points of a 4-step pitch
    ([1, 1, 1, 1, 1, 1, 1], 0, 7 / 4),     # to both ends of the path
    ([0, 1, 0, 1, 1, 1, 0], 4, 3 / 4),
    ([0, 1, 0, 1, 1, 1, 0], 2, 0.0),       # no surface contact at the point
])
def test_surface_contact_ratio_counts_the_run_through_the_point(surface, index, want):
    # (c)
    assert surface_contact_ratio(_Path(surface), index, steps_per_pitch=4) == want
