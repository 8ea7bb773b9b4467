"""The shallow-shell membrane-curvature coupling of the bevel shell
(``build_shell(..., membrane=True)``; docs/bending.md sec. 12) against closed forms.

- ``second_form``: the second fundamental form of a circular cylinder and of a
  hyperbolic paraboloid, both given in an oblique parametrization (so that the map to
  the local Cartesian frame, J^-T H J^-1, is exercised), against their textbook values
  (principal curvature -1/R along the circle, 0 along the axis; the hypar z = c x y has
  b_xy = c and b_xx = b_yy = 0 at its saddle point);
- on a flat plate (b = 0) the term vanishes: the cantilever plate is the Timoshenko
  beam exactly, as without it;
- its membrane part: the same plate under an in-plane load along its length at the free
  edge is the bar, P L / (E W t), exactly for nu = 0 (the Ritz space holds the linear
  axial displacement).
"""

from __future__ import annotations

import numpy as np
import pytest

from gearcontact.materials import Material
from gearcontact.structure.shell import build_shell, second_form
from gearcontact.structure.tooth import LoadPoints, MidSurfaceArrays, RectangularPlate

from .test_shell import E_MPA, edge_line_load_deflection, timoshenko


def _surface(position):
    """A MidSurfaceArrays maker from a position function X(xi, eta) (n, 3): tangents by
    complex-step-free central differences of step 1e-6 (independent of second_form's
    1e-3), the normal X_xi x X_eta."""
    def mid(xi, eta):
        xi, eta = np.atleast_1d(xi).astype(float), np.atleast_1d(eta).astype(float)
        h = 1e-6
        x_xi = (position(xi + h, eta) - position(xi - h, eta)) / (2 * h)
        x_eta = (position(xi, eta + h) - position(xi, eta - h)) / (2 * h)
        n = np.cross(x_xi, x_eta)
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        return MidSurfaceArrays(position_mm=position(xi, eta), x_xi=x_xi, x_eta=x_eta,
                                normal=n, thickness_mm=np.ones_like(xi))
    return mid


def test_second_form_of_a_cylinder_obliquely_parametrized():
    R, a, k, c = 25.0, 0.3, 0.2, 2.0       # angle a xi + k eta, axial c eta: oblique

    def position(xi, eta):
        phi = a * xi + k * eta
        return np.stack([R * np.sin(phi), c * eta, R * np.cos(phi)], axis=1)

    xi, eta = np.array([-0.7, 0.0, 0.4]), np.array([0.3, -0.5, 0.9])
    mid = _surface(position)(xi, eta)
    b = second_form(_surface(position), xi, eta)
    # e1 is along the circle; the normal's sign follows X_xi x X_eta
    sign = np.sign(np.einsum("ni,ni->n", mid.normal, mid.position_mm * [1, 0, 1]))
    # tolerance: the central differences of step 1e-3 over the 1e-6 tangents: truncation
    # (a h)^2 / 6 relative ~ 2e-8, rounding ~ 1e-16 R / (1e-6 1e-3) ~ 3e-6 / mm: 1e-5 / mm
    np.testing.assert_allclose(b[0], -sign / R, atol=1e-5)
    np.testing.assert_allclose(b[1:], 0.0, atol=1e-5)


def test_second_form_of_a_hyperbolic_paraboloid_obliquely_parametrized():
    c, s = 0.15, 0.6                       # z = c x y, x = xi + s eta, y = eta

    def position(xi, eta):
        x, y = xi + s * eta, eta
        return np.stack([x, y, c * x * y], axis=1)

    b = second_form(_surface(position), np.zeros(1), np.zeros(1))
    # at the saddle point the normal is +z and e1 = x, e2 = y: b = [[0, c], [c, 0]]
    # (tolerance as above)
    np.testing.assert_allclose(b[:, 0], [0.0, 0.0, c], atol=1e-5)


@pytest.mark.parametrize("order", [2, 6])
def test_flat_plate_with_the_membrane_term_is_the_timoshenko_beam(order):
    plate = RectangularPlate(10.0, 4.0, 2.0, Material(E_MPA, 0.0))
    shell = build_shell(plate, order=order, membrane=True)
    assert shell.n_functions == 5 * (order + 1) ** 2
    # flat: b = 0 and normal loads do no in-plane work, so the plate of sec. 2 exactly
    # (the Ritz space holds the Timoshenko solution for order >= 2; rounding only)
    assert edge_line_load_deflection(shell, plate) == pytest.approx(
        timoshenko(10.0, 4.0, 2.0, 0.0), rel=1e-9)


def test_in_plane_edge_load_is_the_bar():
    L, W, t = 10.0, 4.0, 2.0
    plate = RectangularPlate(L, W, t, Material(E_MPA, 0.0))
    shell = build_shell(plate, order=3, membrane=True)
    g, w = np.polynomial.legendre.leggauss(8)
    mid = plate.mid_surface(g, np.ones_like(g))
    along = mid.x_eta / np.linalg.norm(mid.x_eta, axis=1, keepdims=True)
    pts = LoadPoints(xi=g, eta=np.ones_like(g), direction=along, offset_mm=np.zeros_like(g),
                     position_mm=mid.position_mm)
    G = shell.compliance(pts).matrix()
    # a uniform unit load on the free edge of a clamped strip, nu = 0: u = P x / (E W t)
    # exactly (linear in the height, in the Ritz space); rounding only
    assert (w / 2) @ G @ (w / 2) == pytest.approx(L / (E_MPA * W * t), rel=1e-9)
    # without the term the plate has no in-plane field: a load on the mid-surface along
    # it does no work
    assert np.allclose(build_shell(plate, order=3).compliance(pts).matrix(), 0.0)


def test_membrane_flag_is_checked():
    from gearcontact.validation import InputRangeError

    plate = RectangularPlate(10.0, 4.0, 2.0, Material(E_MPA, 0.0))
    with pytest.raises(InputRangeError, match="membrane"):
        build_shell(plate, order=2, membrane=1)


@pytest.mark.parametrize("oblique", [0.0, 0.2])
def test_rigid_translation_of_a_cylinder_is_strain_free_with_the_shear_coupling(oblique):
    """A rigid translation U of a curved shell strains nothing. In the local frame it is
    w = U . m, u_a = U . e_a, beta = 0: the membrane strain u_a,b - b_ab w vanishes on a
    cylinder (its frame turns only about the normal's plane: no Christoffel terms), and
    the transverse shear w,a + b_ab u_b vanishes only with the curvature in it (Naghdi);
    without it (DMV) the translation costs shear energy -b_ab u_b. Independent truth:
    the invariance of elasticity under rigid motions."""
    from gearcontact.structure.shell import _plate_energy

    R, a, c = 20.0, 0.4, 3.0
    U = np.array([0.3, -0.5, 0.8])

    def surface(xi, eta):       # analytic tangents: the fields below are differenced
        xi, eta = np.atleast_1d(xi).astype(float), np.atleast_1d(eta).astype(float)
        phi = a * xi + oblique * eta
        sin, cos, zero = np.sin(phi), np.cos(phi), np.zeros_like(phi)
        circ = np.stack([cos, zero, -sin], axis=1)
        x_eta = oblique * R * circ + np.stack([zero, c + zero, zero], axis=1)
        return MidSurfaceArrays(
            position_mm=np.stack([R * sin, c * eta, R * cos], axis=1), x_xi=a * R * circ,
            x_eta=x_eta, normal=np.stack([sin, zero, cos], axis=1),   # X_xi x X_eta
            thickness_mm=np.ones_like(xi))
    g, wg = np.polynomial.legendre.leggauss(6)
    XI, ETA = np.meshgrid(g, g, indexing="ij")
    xi, eta, wq = XI.ravel(), ETA.ravel(), np.outer(wg, wg).ravel()

    def fields(x, e):
        from gearcontact.structure.tooth import local_frame
        e1, e2, m = local_frame(surface(x, e))
        zero = np.zeros_like(x)
        return np.stack([m @ U, zero, zero, e1 @ U, e2 @ U])       # (5, n)

    h = 1e-5
    N = fields(xi, eta)[:, None, :]
    Nxi = ((fields(xi + h, eta) - fields(xi - h, eta)) / (2 * h))[:, None, :]
    Neta = ((fields(xi, eta + h) - fields(xi, eta - h)) / (2 * h))[:, None, :]
    curv = second_form(surface, xi, eta)
    one = np.ones(5)
    energy = {shear: one @ _plate_energy(surface(xi, eta), N, Nxi, Neta, wq,
                                         Material(E_MPA, 0.3), curvature=curv,
                                         shear_coupling=shear) @ one
              for shear in (True, False)}
    # DMV: a finite shear energy; Naghdi: zero but for the differences' error (the
    # fields' central differences of step 1e-5: ~1e-10 relative; second_form's of step
    # 1e-3 on exact tangents: ~1e-7 relative), squared in the energy: below 1e-8 of DMV's
    assert energy[False] > 0.0
    assert abs(energy[True]) < 1e-8 * energy[False]


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason=(
    "docs/bending.md sec. 12: declared before measuring, the shallow-shell term should "
    "take the 7-tooth pinion's surplus against its gear down by >= 0.10 in log on one "
    "geometry; measured 0.432 -> 0.396 (-0.036): no better, not shipped"))
def test_membrane_term_brings_the_seven_tooth_pinion_to_its_gear(pairs):
    """The declared criterion 2 of docs/bending.md sec. 12 on the calibrated s0003 pair:
    with the FE on the shell's own ellipse root (one geometry in both models) and the
    shell at the calibrated factor of each model (the plate 1.49, the Naghdi shell 1.30,
    sec. 12's grids), ln(max shell/FE of the pinion / max of the gear) must fall by at
    least 0.10 (the declared 'improved'). Truth: the 3D FE (P2, default mesh)."""
    from gearcontact.structure.compliance import shell_compliance
    from gearcontact.structure.rim import rim_segment
    from gearcontact.structure.shell import ORDER, ORDER_FACE
    from gearcontact.structure.tooth import tooth_geometry

    pair, flanks = pairs["s0003"]
    largest = {}
    for member in ("pinion", "gear"):
        tooth = tooth_geometry(flanks, member, material=getattr(pair, f"{member}_material"))
        out = {}
        for membrane, factor in ((False, 1.49), (True, 1.30)):
            shell = build_shell(tooth, order=ORDER, order_face=ORDER_FACE,
                                rim=rim_segment(tooth, stiffening=factor), membrane=membrane)
            res = shell_compliance(shell, side=pair.design_side, fe=True)
            out[membrane] = max(np.max(res.segment_shell_mm_per_n / res.segment_fe_mm_per_n),
                                np.max(res.line_shell_mm_per_n / res.line_fe_mm_per_n))
        largest[member] = out
    gap = {m: np.log(largest["pinion"][m] / largest["gear"][m]) for m in (False, True)}
    assert gap[False] - gap[True] >= 0.10, gap
