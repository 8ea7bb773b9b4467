"""TCA Newton solve on an analytic pair with closed-form contact (tests/tca/analytic.py).

Truth: a sphere on the pinion against a torus on the gear touch where the distance of
the sphere centre from the posed core circle equals r + Rs; phi2(phi1) is an
independent scalar root (brentq, xtol 1e-15 rad).

A surface path that folds back in phi1 (issue 28: 7/70 teeth, offset 0.49 r2, 50 deg,
where ``twin``'s surface-only TCA stopped with a Newton failure) ends at the fold: its
last surface phase lies before the largest phi1 of the mating path (the path followed
with the pinion height ``u1`` held instead of phi1), the next one is an edge phase.
"""

from dataclasses import replace

import numpy as np
from scipy.optimize import brentq
import pytest

from gearcontact.geometry.kinematics import AssemblyErrors
from gearcontact.tca.mating import _residual_and_jacobian
from gearcontact.tca.mating import solve_mating_point
from gearcontact.tca.solve import solve_tca
from gearcontact.tca.types import (ARCSEC_PER_RAD, ContactGuess, EdgeContact,
                                   TcaConvergenceError)

from .analytic import Torus, sphere_torus_case

PHIS = np.radians(np.linspace(-20.0, 20.0, 21))


def _guess(case, phi1=0.0):
    return ContactGuess(np.pi / 2 + 0.02, 0.03, case.tube_angle - 0.02, 0.02, phi1,
                        phi1 / case.kin.ratio + 0.002)


@pytest.mark.parametrize("errors", [None, AssemblyErrors(E_mm=0.05, P_mm=-0.04,
                                                         G_mm=0.03, alpha_deg=0.05)])
def test_path_matches_closed_form_contact(errors):
    case = sphere_torus_case(errors=errors)
    path = solve_tca(case.pinion, case.gear, case.kin, PHIS, start=_guess(case))
    assert not path.edge.any()
    ref_phi2 = case.truth(path.phi1_ref_rad)[0]
    for mp in path.points:
        phi2, point, normal, _, _ = case.truth(mp.phi1_rad)
        # Newton stops at |residual| < 1e-10 mm on a ~40 mm lever: 1e-12 rad, 1e-9 mm
        assert mp.phi2_rad == pytest.approx(phi2, abs=1e-12)
        np.testing.assert_allclose(mp.point_mm, point, atol=1e-9)
        np.testing.assert_allclose(mp.normal, normal, atol=1e-11)
        te = ((phi2 - ref_phi2) - (mp.phi1_rad - path.phi1_ref_rad) / case.kin.ratio)
        assert mp.te0_arcsec == pytest.approx(te * ARCSEC_PER_RAD, abs=1e-6)
        assert mp.iterations <= 6      # quadratic convergence from the secant predictor


def test_analytic_jacobian_matches_finite_differences():
    case = sphere_torus_case(errors=AssemblyErrors(E_mm=0.1, alpha_deg=0.2))
    x = np.array([1.5, 0.1, 0.25, -0.05, 0.07, 0.01])
    _, _, jac = _residual_and_jacobian(case.pinion, case.gear, case.kin, x)
    h = 1e-6
    for k in range(6):
        dx = np.zeros(6)
        dx[k] = h
        # the tangent basis is frozen at x (its derivative multiplies n1 + n2, dropped
        # by design), so difference the residual projected on the basis at x
        rp, (_, n2p), _ = _residual_and_jacobian(case.pinion, case.gear, case.kin, x + dx,
                                                 jacobian=False)
        rm, _, _ = _residual_and_jacobian(case.pinion, case.gear, case.kin, x - dx,
                                          jacobian=False)
        # position rows are exact; central differences are accurate to O(h^2) ~ 1e-9
        np.testing.assert_allclose((rp[:3] - rm[:3]) / (2 * h), jac[:3, k], atol=1e-7)


def test_normal_rows_of_jacobian_at_contact():
    """At a contact (n1 + n2 = 0) the dropped basis term vanishes: the normal rows are
    the exact derivatives there (central differences, atol 1e-7)."""
    case = sphere_torus_case()
    mp = solve_mating_point(case.pinion, case.gear, case.kin, _guess(case))
    x = np.array([mp.u1, mp.v1, mp.u2, mp.v2, mp.phi1_rad, mp.phi2_rad])
    _, (_, n2), jac = _residual_and_jacobian(case.pinion, case.gear, case.kin, x)
    from gearcontact.tca.mating import _tangent_basis
    basis = _tangent_basis(n2)
    h = 1e-6
    for k in range(6):
        dx = np.zeros(6)
        dx[k] = h
        normals = []
        for sign in (1, -1):
            y = x + sign * dx
            r1 = case.kin.pinion_pose(y[4])[0] @ case.pinion.point(y[0], y[1]).n
            r2 = case.kin.gear_pose(y[5])[0] @ case.gear.point(y[2], y[3]).n
            normals.append(basis.T @ (r1 + r2))
        np.testing.assert_allclose((normals[0] - normals[1]) / (2 * h), jac[3:, k],
                                   atol=1e-7)


def test_start_with_fixed_gear_parameter():
    case = sphere_torus_case()
    g = _guess(case)
    start = ContactGuess(g.u1, g.v1, case.tube_angle + 0.003, g.v2, 0.01, 0.001)
    path = solve_tca(case.pinion, case.gear, case.kin, PHIS, start=start, start_fixed="u2")
    ref = solve_mating_point(case.pinion, case.gear, case.kin, start, fixed="u2")
    assert ref.u2 == case.tube_angle + 0.003
    assert path.phi1_ref_rad == pytest.approx(ref.phi1_rad, abs=1e-14)
    i = int(np.argmin(np.abs(path.phi1_rad - ref.phi1_rad)))
    assert path.phi1_rad[i] - ref.phi1_rad != 0.0   # a grid phase, not the reference


def test_edge_contact_is_flagged_not_extrapolated():
    """Surface contact only (``edges=False``): the march stops at the first edge."""
    case = sphere_torus_case()
    g = case.gear
    narrow = Torus(g.center, g.frame, g.core_radius, g.tube_radius, g.u_range, (-0.04, 0.04))
    path = solve_tca(case.pinion, narrow, case.kin, PHIS, start=_guess(case), edges=False)
    edge = path.edge
    assert edge.any() and not edge.all()
    for mp in path.points:
        # independent truth: gear azimuth v of the true contact point
        phi2, point, _, _, _ = case.truth(mp.phi1_rad)
        rot, t = case.kin.gear_pose(phi2)
        d = rot.T @ (point - t) - g.center
        v_true = np.arctan2(d @ g.frame[:, 1], d @ g.frame[:, 0])
        if mp.edge:
            assert abs(v_true) > 0.04 - 1e-9
            assert mp.edge_where.startswith("gear v") and np.isnan(mp.point_mm).all()
        else:
            assert abs(v_true) <= 0.04 and mp.v2 == pytest.approx(v_true, abs=1e-10)
    # the march stops at the first edge: edge phases are contiguous at both ends
    inner = np.flatnonzero(~edge)
    assert np.all(np.diff(inner) == 1)


def _meridian_touch(case, narrow, phi1, v, phi2_guess):
    """Closed-form edge truth: the gear edge at azimuth ``v`` is a meridian circle of
    the torus (centre ``m``, radius ``r``, plane normal ``a``); the sphere (centre
    ``c``, radius ``Rs``) touches it when the distance from ``c`` to the circle,
    ``sqrt(h^2 + (rho - r)^2)`` with ``h = (c - m).a`` and ``rho`` the in-plane
    distance, equals ``Rs`` (brentq in phi2)."""
    c = case.sphere_centre(phi1)
    e1, e2, e3 = narrow.frame.T

    def gap(phi2):
        rot, t = case.kin.gear_pose(phi2)
        radial = rot @ (np.cos(v) * e1 + np.sin(v) * e2)
        a = rot @ (-np.sin(v) * e1 + np.cos(v) * e2)
        m = rot @ narrow.center + t + narrow.core_radius * radial
        d = c - m
        h = d @ a
        rho = np.linalg.norm(d - h * a)
        return np.hypot(h, rho - narrow.tube_radius) - case.pinion.radius

    return brentq(gap, phi2_guess - 0.02, phi2_guess + 0.02, xtol=1e-15, rtol=1e-15)


def test_edge_contact_beyond_a_narrow_face_matches_the_closed_form():
    """With edge contact (default) the path continues beyond the band's ends as the
    torus's edge circle touching the sphere; its gear angle matches the closed-form
    circle-sphere touch within 1e-9 rad (Newton 1e-10 mm over ~30 mm radii; Brent along
    the edge 1e-5 mm, second order in phi2), and TE0 is continuous across the switch."""
    from gearcontact.tca.types import ARCSEC_PER_RAD

    case = sphere_torus_case()
    g = case.gear
    narrow = Torus(g.center, g.frame, g.core_radius, g.tube_radius, g.u_range, (-0.04, 0.04))
    # the whole edge tails (no TE0 limit): the truth holds wherever an edge touches
    path = solve_tca(case.pinion, narrow, case.kin, PHIS, start=_guess(case),
                     edge_te_limit_arcsec=np.inf)
    kinds = [mp.edge_contact for mp in path.points]
    assert "gear toe" in kinds and "gear heel" in kinds
    checked = 0
    for mp in path.points:
        if not mp.edge_contact:
            continue
        v = narrow.v_range[0] if mp.edge_contact == "gear toe" else narrow.v_range[1]
        assert mp.v2 == v
        phi2 = _meridian_touch(case, narrow, mp.phi1_rad, v, mp.phi2_rad)
        assert mp.phi2_rad == pytest.approx(phi2, abs=1e-9)
        checked += 1
    assert checked >= 4
    # continuity: TE0 steps across each switch no more than the largest step inside
    te = path.te0_arcsec[~path.edge]
    steps = np.abs(np.diff(te))
    surf = np.array([not mp.edge_contact for mp in path.points if not mp.edge])
    inner = steps[surf[1:] & surf[:-1]]
    assert steps.max() <= 2.0 * inner.max() + 1e-9 * ARCSEC_PER_RAD


def test_single_solve_raises_edge_contact():
    case = sphere_torus_case()
    g = case.gear
    narrow = Torus(g.center, g.frame, g.core_radius, g.tube_radius, g.u_range, (-0.04, 0.04))
    with pytest.raises(EdgeContact, match="gear v max"):
        solve_mating_point(case.pinion, narrow, case.kin, _guess(case, np.radians(-15)))


def test_non_convergence_names_phase_and_residual():
    case = sphere_torus_case()
    with pytest.raises(TcaConvergenceError, match=r"phi1 = 5\.000000 deg: residual"):
        solve_mating_point(case.pinion, case.gear, case.kin,
                           _guess(case, np.radians(5.0)), max_iter=1)


@pytest.fixture(scope="module")
def folding_pair():
    """A design-space pair whose drive path folds back near the pinion root at phi1
    ~92.3 deg (coarse flank grid, 40 x 50 nodes: 4-12 s; the fold is 0.05 deg from
    that of the production grid), its drive flanks and kinematics."""
    from design_space import design_space_candidate

    from gearcontact.geometry.flank import build_flanks

    pair = design_space_candidate(7, 10.0, 0.49, 50.0, 0.3, "drive")
    flanks = build_flanks(pair, n_u=40, n_v=50)
    return (flanks.flank("pinion", "drive"), flanks.flank("gear", "drive"),
            pair.kinematics(with_errors=True))


def test_surface_path_ends_at_a_fold(folding_pair):
    pinion, gear, kin = folding_pair
    start = ContactGuess(1.098, 72.206, 3.735, 9.735, np.radians(88.0), 0.1539)
    phis = np.radians(np.arange(88.0, 95.0, 0.5))
    path = solve_tca(pinion, gear, kin, phis, start=start, edges=False)
    # the fold: the largest phi1 of the mating path, u1 held over the path's last 0.07 mm
    fold = max(solve_mating_point(pinion, gear, kin, replace(start, u1=u1, phi1_rad=np.radians(
        92.0), u2=3.99, v2=9.72, v1=72.4, phi2_rad=0.1613), fixed="u1").phi1_rad
               for u1 in np.linspace(0.93, 1.0, 15))
    surface = [mp for mp in path.points if not mp.edge]
    assert surface and max(mp.phi1_rad for mp in surface) < fold
    first_edge = next(mp for mp in path.points if mp.edge)
    assert first_edge.phi1_rad > fold
    assert np.degrees(first_edge.phi1_rad - max(mp.phi1_rad for mp in surface)) == \
        pytest.approx(0.5)          # the next phase of the grid, not an earlier stop
    assert first_edge.edge_where == "pinion u min"   # an edge at the pinion root
    assert all(mp.residual < 1e-9 for mp in surface)
    # the edge-contact path (analyze's) takes the same surface points before the fold
    full = solve_tca(pinion, gear, kin, phis, start=start)
    for a, b in zip(path.points, full.points):
        if not a.edge:
            assert (a.u1, a.v1, a.phi2_rad) == (b.u1, b.v1, b.phi2_rad)


def test_phases_must_increase():
    case = sphere_torus_case()
    with pytest.raises(ValueError, match="strictly increasing"):
        solve_tca(case.pinion, case.gear, case.kin, [0.1, 0.0], start=_guess(case))
