"""Conjugate pinion: equation of meshing, line contact, interpolation accuracy, regularity."""

import numpy as np
import pytest

from gearcontact.geometry.conjugate import (MeshingError, UndercutError,
                                            conjugate_pinion_flank)
from gearcontact.geometry.cutter import place_cutter
from gearcontact.geometry.formate import SIDES, gear_flank
from gearcontact.geometry.kinematics import rot_x, rot_z
from gearcontact.geometry.sampling import sample_grid


@pytest.mark.parametrize("side", SIDES)
def test_meshing_equation_at_every_node(s0003_centred, side):
    flanks = s0003_centred[1]
    c = flanks.pinion_conjugate.side(side)
    n = c.nodes
    assert n.psi_rad.shape == (120, 150)
    # recompute f = N . v12 independently with MeshKinematics (|f| < 1e-9 mm/rad required)
    f = np.einsum("...i,...i->...", n.n_f, flanks.kinematics.relative_velocity(n.x_f_mm))
    assert np.abs(f).max() < 1e-9
    # the pinion node really is the gear point carried by the pinion rotation u*phi2
    for i, j in ((0, 0), (60, 75), (119, 149)):
        phi2 = n.phi2_rad[i, j]
        x1 = rot_x(flanks.blank.ratio * phi2) @ (n.x_f_mm[i, j] - flanks.kinematics.pinion_centre)
        assert np.allclose(x1, n.x1_mm[i, j], atol=1e-12)
        g = flanks.flank("gear", side).blade.evaluate(n.h_mm[i, j], n.theta_rad[i, j])
        assert np.allclose(rot_z(phi2) @ g.x, n.x_f_mm[i, j], atol=1e-12)
        # and it has the node's axial position and radius
        assert x1[0] == pytest.approx(c.v_nodes[j], abs=1e-10)
        assert np.hypot(x1[1], x1[2]) == pytest.approx(c.cone.radius_mm(c.u_nodes[i], c.v_nodes[j]), abs=1e-10)


@pytest.mark.parametrize("side", SIDES)
def test_line_contact_without_easeoff(s0003_centred, side):
    # Independent construction of the instantaneous contact line at gear angle phi2:
    # on the gear flank solve f(h, theta, phi2) = 0 for theta at fixed h (1-D Newton with
    # a finite-difference slope), carry the points to the pinion body frame and compare
    # with the interpolated conjugate pinion sheet. Required: gap < 1e-6 mm along it.
    flanks = s0003_centred[1]
    c = flanks.pinion_conjugate.side(side)
    g = flanks.flank("gear", side)
    kin = flanks.kinematics
    for dphi in (-0.05, 0.0, 0.05):
        phi = flanks.mean_contact[side]["phi2_rad"] + dphi
        h = np.linspace(-0.3, 1.4, 25)
        th = np.full_like(h, g.blade_parameters(*flanks.mean_contact[side]["gear_uv"])[1])
        for _ in range(40):
            f = c.solver.meshing_function(h, th, phi)
            th = th - f * 1e-7 / (c.solver.meshing_function(h, th + 1e-7, phi) - f)
        b = g.blade.evaluate(h, th)
        Xf, Nf = b.x @ rot_z(phi).T, b.n @ rot_z(phi).T
        assert np.abs(np.einsum("ij,ij->i", Nf, kin.relative_velocity(Xf))).max() < 1e-9
        R = rot_x(kin.ratio * phi)
        X1, N1 = (Xf - kin.pinion_centre) @ R.T, -(Nf @ R.T)
        u, v, _ = c.locate(X1)
        inside = c.boundary.contains(u, v)
        assert inside.sum() >= 5
        s = c.evaluate(u[inside], v[inside])
        gap = np.einsum("ij,ij->i", X1[inside] - s.r, s.n)
        assert np.abs(gap).max() < 1e-6
        assert np.linalg.norm(s.r - X1[inside], axis=-1).max() < 1e-6
        # common normal, opposite orientation (both point out of their own tooth)
        assert np.linalg.norm(s.n - N1[inside], axis=-1).max() < 1e-8


@pytest.mark.parametrize("side", SIDES)
def test_interpolant_matches_exact_solves(s0003_centred, side):
    # flanks from the 120 x 150 exact grid, evaluated at random off-grid points, against
    # an exact solve of the node equations there: < 0.05 um (5e-5 mm) required.
    flanks = s0003_centred[1]
    c = flanks.pinion_conjugate.side(side)
    rng = np.random.default_rng(7)
    u = rng.uniform(*c.u_range, 200)
    v = rng.uniform(*c.v_range, 200)
    ex = c.exact(u, v)
    s = c.evaluate(u, v)
    assert np.linalg.norm(s.r - ex.x1_mm, axis=-1).max() < 5e-5
    assert np.linalg.norm(s.n - ex.n1, axis=-1).max() < 1e-7
    # interpolated point = Surface protocol point
    p = c.point(float(u[0]), float(v[0]))
    assert np.allclose(p.r, s.r[0], atol=1e-13)


@pytest.mark.parametrize("side", SIDES)
def test_pinion_second_derivatives_consistent(s0003_centred, side):
    # r_uu, r_uv, r_vv from the spline formulas vs central differences of r_u, r_v
    # (step 1e-5 mm: truncation ~1e-10, rounding ~1e-9 relative)
    flanks = s0003_centred[1]
    f = flanks.pinion.side(side)
    u0, v0, e = 1.1, 36.0, 1e-5
    p = f.point(u0, v0)
    assert np.allclose((f.point(u0 + e, v0).r_u - f.point(u0 - e, v0).r_u) / (2 * e), p.r_uu, atol=1e-6)
    assert np.allclose((f.point(u0, v0 + e).r_u - f.point(u0, v0 - e).r_u) / (2 * e), p.r_uv, atol=1e-6)
    assert np.allclose((f.point(u0, v0 + e).r_v - f.point(u0, v0 - e).r_v) / (2 * e), p.r_vv, atol=1e-6)


def test_pinion_flank_orientation(s0003_centred):
    # the pinion tooth lies between its drive and coast flanks: both outward normals
    # point away from the tooth centre (mean angular position of the two flanks)
    flanks = s0003_centred[1]
    d, c = flanks.pinion.side("drive"), flanks.pinion.side("coast")
    u, v = 1.0, 36.0
    pd, pc = d.point(u, v), c.point(u, v)
    mid = 0.5 * (pd.r + pc.r)
    assert (pd.r - mid) @ pd.n > 0 and (pc.r - mid) @ pc.n > 0
    # positive tooth thickness over the whole active flank (no pointed tooth)
    grid_d, grid_c = sample_grid(d, 16, 22), sample_grid(c, 16, 22)
    gap = np.linalg.norm(grid_d.positions_mm - grid_c.positions_mm, axis=-1)
    assert gap.min() > 0.1


def test_drive_flank_is_gear_convex(s0003_centred):
    # drive: the pinion pushes the gear when the gear turns towards -z (documented sign):
    # the gear convex flank's normal has n . (z x X) > 0 at the mean contact
    flanks = s0003_centred[1]
    g = flanks.flank("gear", "drive")
    p = g.point(*flanks.mean_contact["drive"]["gear_uv"])
    assert p.n @ np.cross([0, 0, 1.0], p.r) > 0
    assert sample_grid(g, 4, 4).curvatures_per_mm[..., 0].max() < 0  # convex


def test_limit_line_detected(s0003_centred):
    # A 5-tooth pinion with a large gear addendum (c_ham = 0.5) and an 8 deg drive blade:
    # the envelope folds (limit line, Litvin & Fuentes 2004, sec. 6.3) above the line
    # the gear tip generates, i.e. inside the active pinion flank. Must raise with the
    # location, never return a flank.
    from dataclasses import replace
    s0003 = s0003_centred[0]
    pair = replace(s0003, pinion_teeth=5, gear_teeth=70, gear_addendum_factor=0.5,
                   cutter=replace(s0003.cutter, pressure_angle_drive_deg=8.0))
    blank = pair.blank
    _, inside, _ = place_cutter(blank, point_width_mm=pair.cutter.point_width_mm)
    g = gear_flank(blank, inside, side="drive", gear_face_width_mm=pair.gear_face_width_mm,
                   edge_radius_mm=pair.cutter.edge_radius_mm)
    with pytest.raises(UndercutError) as err:
        conjugate_pinion_flank(g, blank=blank, kinematics=pair.kinematics(with_errors=False),
                               pinion_face_width_mm=pair.pinion_face_width_mm, n_u=12, n_v=12)
    assert err.value.field == "gear_addendum_factor" and err.value.value == 0.5
    assert "undercut" in err.value.allowed and "gear tip zone" in err.value.allowed
    # the named fix is real: with the gear addendum factor it gives, the same blade
    # generates the drive flank (the limit line does not depend on the addenda)
    fixed = replace(pair, gear_addendum_factor=err.value.fix)
    blank = fixed.blank
    _, inside, _ = place_cutter(blank, point_width_mm=fixed.cutter.point_width_mm)
    g = gear_flank(blank, inside, side="drive", gear_face_width_mm=fixed.gear_face_width_mm,
                   edge_radius_mm=fixed.cutter.edge_radius_mm)
    c, _ = conjugate_pinion_flank(g, blank=blank, kinematics=fixed.kinematics(with_errors=False),
                                  pinion_face_width_mm=fixed.pinion_face_width_mm, n_u=12, n_v=12)
    assert c.nodes.df_dphi2.min() > 0
    # the regular s0003 design has no limit line in its box: df/dphi2 keeps its sign
    # and stays far from zero (checked on the production grid elsewhere)


def test_iso_f3_example_generates_with_fold_below_gear_tip_line():
    # The ISO 23509 F.3 pair (13/42) cut as a formate gear: on the pinion coast flank at
    # the toe the envelope folds (limit line) just below the line generated by the gear
    # tip, i.e. in the fillet zone. The active box must stop above that fold (its edge
    # is the gear tip line or moved up by the node margin) and the nodes stay regular.
    from pathlib import Path

    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair
    pair = load_pair(Path(__file__).resolve().parents[2] / "examples" / "iso23509_f3.toml")
    fs = build_flanks(pair, n_u=30, n_v=40)
    for side in SIDES:
        c = fs.pinion_conjugate.side(side)
        assert np.abs(c.nodes.meshing_residual).max() < 1e-9
        assert c.nodes.df_dphi2.min() > 0  # no limit line among the nodes
        # the gear point generating the active root edge is at or above the gear tip
        ex = c.exact(np.full(5, c.u_range[0]), np.linspace(*c.v_range, 5))
        assert ex.h_mm.min() >= -fs.blank.addendum_gear_mm - 1e-6


def _f3(**changes):
    """The ISO 23509 F.3 pair (13/42, E = 15 mm, beta1 = 50 deg) with ``changes``."""
    from dataclasses import replace
    from pathlib import Path

    from gearcontact.geometry.pair import load_pair
    pair = load_pair(Path(__file__).resolve().parents[2] / "examples" / "iso23509_f3.toml")
    return replace(pair, **changes)


def _check_trimmed_at_limit_line(fs):
    """Shared checks of a flank set whose pinion root edge may be trimmed at a limit line."""
    from gearcontact.geometry.conjugate import _MAX_UNDERCUT
    trimmed = 0
    for side in SIDES:
        c = fs.pinion_conjugate.side(side)
        # every node meets the equation of meshing (1e-9 mm/rad: Newton converged) and
        # df/dphi2 keeps the mean-point sign (no limit line among the nodes)
        assert np.abs(c.nodes.meshing_residual).max() < 1e-9
        assert c.nodes.df_dphi2.min() > 0
        # the root edge is generated by the active gear flank (at or above the gear tip)
        v = np.linspace(*c.v_range, 9)
        ex = c.exact(np.full(9, c.u_range[0]), v)
        assert ex.h_mm.min() >= -fs.blank.addendum_gear_mm - 1e-6
        # interpolant at the (possibly trimmed) root edge vs exact solves: the trim keeps
        # the spline's accuracy there (0.1 um on the coarse test grids of >= 60 x 80
        # nodes; measured 1.7e-5 mm at 60 x 80 and 1.3e-6 mm at the production
        # 120 x 150 for F.3 at 25 deg with c_ham = 0.165, docs/geometry.md)
        assert np.linalg.norm(c.evaluate(np.full(9, c.u_range[0]), v).r - ex.x1_mm,
                              axis=-1).max() < 1e-4
        assert 0.0 <= c.gear_tip_undercut_mm <= _MAX_UNDERCUT * fs.blank.addendum_gear_mm
        if c.gear_tip_undercut_mm > 0.0:
            trimmed += 1
            # independent sign of the limit line: 0.3 mm below the trimmed edge the node
            # equations are singular or unsolvable on some section (the envelope ends)
            s = c.solver.solve(np.full(9, c.u_range[0] - 0.3), v,
                               np.stack([ex.h_mm, ex.theta_rad, ex.phi2_rad], axis=-1),
                               strict=False)
            det_edge = np.abs(ex.jacobian_det)
            assert (~s.converged).any() or (np.abs(s.jacobian_det) < det_edge).any()
    return trimmed


def test_f3_spiral_45_generates_trimmed_at_the_limit_line():
    # Regression (issue 28): the F.3 pair at beta1 = 45 deg failed with "an envelope
    # reaching the line generated by the gear tip". Cause: on the coast flank near the
    # toe the envelope of the formate gear reaches its limit line (cusp, the node
    # Jacobian -> 0 while df/dphi2 stays ~47 mm/rad) at gear h = -1.69 mm, above the gear
    # tip h = -1.97 mm. The active profile now ends at the limit line.
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.generation import check_generation
    pair = _f3(pinion_spiral_angle_deg=45.0)
    fs = build_flanks(pair, n_u=60, n_v=80)
    assert _check_trimmed_at_limit_line(fs) >= 1
    # the design-time check (no grid) finds the same active boxes and trims, exactly
    for side, got in check_generation(pair).items():
        c = fs.pinion_conjugate.side(side)
        assert got["active_box"] == c.boundary
        assert got["gear_tip_undercut_mm"] == c.gear_tip_undercut_mm


def test_f3_spiral_25_undercut_names_the_fix():
    # At beta1 = 25 deg the limit line on the coast flank's toe leaves 53 % of the gear
    # addendum without a conjugate partner (> 50 %): the formate gear's active flank is
    # undercut, and its active-box step names gear_addendum_factor and a value that
    # avoids it. design now takes the generated gear for this pair instead
    # (docs/geometry.md sec. 7.6); with the fix it verified before (0.164, sec. 7.2)
    # the formate gear generates, trimmed at the limit line.
    from dataclasses import replace

    from gearcontact.geometry.conjugate import pinion_active_box
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.formate import gear_flanks
    from gearcontact.geometry.gear_generation import gear_generation
    pair = _f3(pinion_spiral_angle_deg=25.0)
    with pytest.raises(UndercutError) as err:
        pinion_active_box(gear_flanks(pair)[1]["coast"], blank=pair.blank,
                          kinematics=pair.kinematics(with_errors=False),
                          pinion_face_width_mm=pair.pinion_face_width_mm)
    assert err.value.field == "gear_addendum_factor" and err.value.value == 0.35
    assert 0.0 < err.value.fix < 0.35
    assert "coast flank is undercut" in err.value.allowed
    assert gear_generation(pair)[0] == "generated"
    fixed = replace(pair, gear_addendum_factor=0.164)
    assert gear_generation(fixed)[0] == "formate"
    fs = build_flanks(fixed, n_u=60, n_v=80)
    _check_trimmed_at_limit_line(fs)


@pytest.mark.slow
@pytest.mark.parametrize("changes", [
    dict(pinion_spiral_angle_deg=30.0), dict(pinion_spiral_angle_deg=35.0),
    dict(pinion_spiral_angle_deg=40.0), dict(pinion_spiral_angle_deg=20.0,
                                             gear_addendum_factor=0.15),
    dict(offset_mm=0.0), dict(pinion_teeth=9, gear_teeth=37),
    dict(pinion_teeth=8, gear_teeth=39, offset_mm=25.0),
    dict(pinion_teeth=17, gear_teeth=51, offset_mm=12.0),
    dict(pinion_teeth=5, gear_teeth=50)])
def test_f3_variants_generate(changes):
    # The F.3 variants of issue 28 that failed before the limit-line trim (see
    # docs/geometry.md for the measured trims).
    from gearcontact.geometry.flank import build_flanks
    _check_trimmed_at_limit_line(build_flanks(_f3(**changes), n_u=60, n_v=80))
