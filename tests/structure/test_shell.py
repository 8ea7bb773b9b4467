"""Shell Rayleigh-Ritz compliance (gearcontact.structure.shell).

Truths:
- uniform cantilever plate, nu = 0, uniform line load on the free edge: the exact
  Timoshenko beam deflection ``P L^3 / (3 E I) + P L / (kappa G A)`` (with nu = 0 the
  plate has no anticlastic coupling and the Mindlin solution is the Timoshenko beam,
  which the Ritz space contains for order >= 2: w is cubic, beta quadratic) -> 1e-9;
- the same plate with nu = 0.3 lies between the plate-strip (D = E t^3 / 12 (1 - nu^2))
  and the beam (E t^3 / 12) values (bracketing theorem of cylindrical bending);
- Maxwell-Betti reciprocity (G symmetric) and positive definiteness on the real teeth;
- nested Ritz spaces: the work-conjugate deflection under a fixed distributed load
  grows monotonically with the order and converges (< 2 % from order 8 to 10);
- tapered cantilever: converged Ritz vs the Timoshenko beam with variable section by
  numerical integration (unit-load method) -> 1 %;
- the plate continued below its root line by a rim segment (a straight rim of the
  root's thickness, its modulus raised over the fillet by the stiffening factor): the
  Timoshenko beam of length L + D with that modulus, by the unit-load integral
  (nu = 0; 1e-6 with a uniform modulus, 1 % with the stiffening: the curvature is then
  not a polynomial and Ritz converges from the stiff side);
- a left-hand tooth (the mirror image of the right-hand one, y -> -y) has the
  right-hand tooth's compliance at the same tooth coordinates (elasticity is invariant
  under a reflection) -> rounding (issue 28: every left-hand pair stopped analyze with
  a negative mid-surface Jacobian);
- bad input -> InputRangeError naming the field.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from gearcontact.materials import Material
from gearcontact.structure.rim import RimSegment, SectionProfile, rim_modulus_factor, rim_segment
from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING
from gearcontact.structure.shell import RIM_BLOCK, RIM_STIFFENING, build_shell, tooth_shell
from gearcontact.structure.tooth import RectangularPlate, tooth_geometry
from gearcontact.validation import InputRangeError

E_MPA = 200_000.0


def edge_line_load_deflection(shell, plate, n=12):
    """Mean free-edge deflection under a unit total load spread uniformly on the edge."""
    g, w = np.polynomial.legendre.leggauss(n)
    G = shell.compliance(plate.points(g, np.ones_like(g))).matrix()
    return (w / 2) @ G @ (w / 2)


def timoshenko(L, W, t, nu):
    I, A = W * t ** 3 / 12.0, W * t
    return L ** 3 / (3 * E_MPA * I) + L / (5.0 / 6.0 * E_MPA / (2 * (1 + nu)) * A)


@pytest.mark.parametrize("order", [2, 3, 6])
def test_cantilever_plate_is_timoshenko_beam_for_nu_zero(order):
    plate = RectangularPlate(10.0, 4.0, 2.0, Material(E_MPA, 0.0))
    d = edge_line_load_deflection(build_shell(plate, order=order), plate)
    assert d == pytest.approx(timoshenko(10.0, 4.0, 2.0, 0.0), rel=1e-9)


def test_cantilever_plate_nu_between_strip_and_beam():
    nu = 0.3
    plate = RectangularPlate(10.0, 4.0, 2.0, Material(E_MPA, nu))
    d = edge_line_load_deflection(build_shell(plate, order=8), plate)
    beam = timoshenko(10.0, 4.0, 2.0, nu)
    I = 4.0 * 8.0 / 12.0
    strip = (1 - nu ** 2) * 1000.0 / (3 * E_MPA * I) + (beam - 1000.0 / (3 * E_MPA * I))
    assert strip < d < beam


def test_tapered_cantilever_against_beam_integral():
    L, W, t0, t1 = 8.0, 3.0, 2.0, 1.0
    plate = RectangularPlate(L, W, t0, Material(E_MPA, 0.0), thickness_tip_mm=t1)
    d = edge_line_load_deflection(build_shell(plate, order=10), plate)
    t = lambda y: t0 + (t1 - t0) * y / L  # noqa: E731
    bend = quad(lambda y: (L - y) ** 2 / (E_MPA * W * t(y) ** 3 / 12), 0, L)[0]
    shear = quad(lambda y: 1.0 / (5 / 6 * E_MPA / 2 * W * t(y)), 0, L)[0]
    # the beam integral ignores the in-plane shear of the taper (a plate effect of
    # order (slope)^2 = 1.6 %): 2 % tolerance
    assert d == pytest.approx(bend + shear, rel=0.02)


@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_tooth_reciprocity_definiteness_convergence(s0003_centred, member):
    pair, flanks = s0003_centred
    tooth = tooth_geometry(flanks, member, material=pair.pinion_material)
    XI, ETA = np.meshgrid(np.linspace(-0.8, 0.8, 5), np.linspace(-0.8, 0.8, 4), indexing="ij")
    pts_d = tooth.points_at("drive", XI.ravel(), ETA.ravel())
    pts_c = tooth.points_at("coast", XI.ravel()[::3], ETA.ravel()[::3])
    g, wg = np.polynomial.legendre.leggauss(14)
    GX, GE = np.meshgrid(g, g, indexing="ij")
    gauss = tooth.points_at("drive", GX.ravel(), GE.ravel())
    gw = np.outer(wg, wg).ravel() / 4.0
    prev = None
    rim = rim_segment(tooth, stiffening=RIM_STIFFENING[member])
    for order in (6, 8, 10, 12):
        shell = build_shell(tooth, order=order, rim=rim)
        G = shell.compliance(pts_d).matrix()
        # Maxwell-Betti: load at i, measure at j == load at j, measure at i
        cross = shell.cross_compliance(pts_c, pts_d)
        assert np.allclose(cross, shell.cross_compliance(pts_d, pts_c).T, rtol=0, atol=1e-18)
        assert np.allclose(G, G.T, rtol=0, atol=1e-18)
        assert np.linalg.eigvalsh(G).min() > 0.0     # 20 points < 3 (order+1)^2 functions
        # a uniform load over the drive flank (14 x 14 Gauss rule: exact for the Ritz
        # polynomials, so it is the distributed load, not point loads): nested spaces
        # -> monotone; point loads are not used here, their Mindlin self-compliance
        # grows like log(order) (the local part the half-space model carries)
        op = shell.compliance(gauss)
        work = gw @ op.apply(gw)
        if prev is not None:
            assert work >= prev * (1 - 1e-9)
            last_change = work / prev - 1.0
        prev = work
    assert last_change < 0.02
    assert shell.n_functions == 3 * 13 ** 2


def test_tooth_shell_is_cached_and_rim_softens(s0003_centred):
    pair, flanks = s0003_centred
    a = tooth_shell(flanks, "gear", material=pair.gear_material, order=5)
    assert tooth_shell(flanks, "gear", material=pair.gear_material, order=5) is a
    # the cached shell is the active model (shell.RIM_BLOCK) with that model's own
    # calibrated rim factor (a definition: exact)
    assert a.rim_block is RIM_BLOCK
    assert a.rim.stiffening == (BLOCK_RIM_STIFFENING if RIM_BLOCK else RIM_STIFFENING["gear"])
    pts = a.body.points_at("drive", [0.0], [0.0])
    soft = a.compliance(pts).matrix()[0, 0]
    hard = build_shell(a.body, order=5, order_face=16).compliance(pts).matrix()[0, 0]
    stiffer_rim = build_shell(a.body, order=5, order_face=16, rim=RimSegment(
        a.rim.depth_mm, a.rim.fillet_mm, 2.0 * a.rim.stiffening),
        rim_block=a.rim_block).compliance(pts).matrix()[0, 0]
    assert soft > stiffer_rim > hard


class _RootedPlate(RectangularPlate):
    """A plate with a member axis along its width and two 'teeth': its rim segment
    continues it straight below the root line with the root's thickness (no widening:
    the faces' radial directions are half a turn = one pitch apart)."""

    axis = np.array([1.0, 0.0, 0.0])
    teeth = 2


@pytest.mark.parametrize("stiffening, rel", [(1.0, 1e-6), (2.5, 1e-2)])
def test_rim_continues_the_cantilever(stiffening, rel):
    # Tolerances: a uniform modulus (stiffening 1) is the Timoshenko beam of length
    # L + D, inside the Ritz space (1e-6: the quadrature of the rim's fillet piece);
    # with the modulus rising over the fillet the exact curvature is not a polynomial
    # and Ritz converges from the stiff side (measured -0.69 % at order 10, -0.40 % at
    # order 12): 1 %.
    L, W, t, D, fillet = 10.0, 4.0, 2.0, 3.0, 1.0
    plate = _RootedPlate(L, W, t, Material(E_MPA, 0.0))
    rim = RimSegment(D, fillet, stiffening)
    d = edge_line_load_deflection(build_shell(plate, order=12, rim=rim), plate)
    I, A, G = W * t ** 3 / 12.0, W * t, 5.0 / 6.0 * E_MPA / 2.0
    # unit-load integrals over the height y from the rim's bottom (modulus factor of
    # the depth D - y below the root line) to the free edge y = L + D
    e = lambda y: E_MPA * float(rim_modulus_factor(rim, D - y))  # noqa: E731
    opt = dict(limit=200, points=[D - fillet])
    bend = quad(lambda y: (L + D - y) ** 2 / (e(y) * I), 0.0, D, **opt)[0] \
        + L ** 3 / (3 * E_MPA * I)
    shear = quad(lambda y: 1.0 / (5.0 / 6.0 * e(y) / 2.0 * A), 0.0, D, **opt)[0] + L / (G * A)
    assert d == pytest.approx(bend + shear, rel=rel)
    assert d <= (bend + shear) * (1 + 1e-9)           # Ritz: never more compliant


@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_left_hand_tooth_is_the_mirror_image(s0003_centred, member):
    from dataclasses import replace

    from gearcontact.geometry.flank import mirror_flank_set

    pair, flanks = s0003_centred
    left = mirror_flank_set(flanks, replace(pair, pinion_hand="left").kinematics(
        with_errors=False))
    xi, eta = np.meshgrid(np.linspace(-0.9, 0.9, 4), np.linspace(-0.9, 0.9, 3))
    G = {}
    for hand, fs in (("right", flanks), ("left", left)):
        shell = build_shell(tooth_geometry(fs, member, material=pair.pinion_material),
                            order=5)
        pts = [shell.body.points_at(side, xi.ravel(), eta.ravel())
               for side in ("drive", "coast")]
        G[hand] = np.hstack([shell.compliance(pts[0]).matrix(),
                             shell.cross_compliance(pts[0], pts[1])])
    # mirrored flanks: positions to 1e-12 mm, derivatives to 1e-10
    # (tests/geometry/test_mirror.py); the compliance follows to relative rounding
    assert np.abs(G["left"] - G["right"]).max() < 1e-9 * np.abs(G["right"]).max()
    assert np.abs(G["right"]).max() > 1e-7      # mm/N: a real compliance


def test_bad_input():
    mat = Material(E_MPA, 0.3)
    plate = RectangularPlate(10.0, 4.0, 2.0, mat)
    with pytest.raises(InputRangeError, match="order"):
        build_shell(plate, order=0)
    with pytest.raises(InputRangeError, match="thickness_root_mm"):
        RectangularPlate(10.0, 4.0, -1.0, mat)
    with pytest.raises(InputRangeError, match="thickness_tip_mm"):
        RectangularPlate(10.0, 4.0, 1.0, mat, thickness_tip_mm=0.0)
    with pytest.raises(InputRangeError, match="rim stiffening"):
        RimSegment(2.0, 0.5, 0.0)
    with pytest.raises(InputRangeError, match="rim fillet_mm"):
        RimSegment(2.0, 3.0)
    with pytest.raises(InputRangeError, match="rim depth_mm"):
        RimSegment(-2.0, 0.5)
    with pytest.raises(InputRangeError, match="section profile depth_mm"):
        SectionProfile((0.0, 0.5, 0.4), (1.0, 1.1, 1.2), 1.5)     # not ascending
    with pytest.raises(InputRangeError, match="section profile widening"):
        SectionProfile((0.0, 0.5), (1.0, -1.1), 1.5)
    with pytest.raises(InputRangeError, match="section profile rim_widening"):
        SectionProfile((0.0, 0.5), (1.0, 1.1), 0.0)
    with pytest.raises(InputRangeError, match="rim profile's last depth_mm"):
        RimSegment(2.0, 0.6, profile=SectionProfile((0.0, 0.5), (1.0, 1.1), 1.5))
    with pytest.raises(InputRangeError, match="fillet_mm"):
        rim_segment(plate, fillet_mm=0.5, profile=SectionProfile((0.0, 0.5), (1.0, 1.1), 1.5))
    with pytest.raises(InputRangeError, match="rim"):
        rim_segment(plate)                       # a plate has no member axis
    # a taper through zero thickness: rejected before any assembly
    with pytest.raises(InputRangeError, match="thickness_mm"):
        build_shell(_Negative(mat), order=2)


class _Negative(RectangularPlate):
    """A plate whose thickness goes negative towards the tip (bad geometry)."""

    def __init__(self, mat):
        super().__init__(10.0, 4.0, 1.0, mat, thickness_tip_mm=1.0)

    def _thickness(self, eta):
        return 1.0 - 1.5 * (np.asarray(eta) + 1.0) / 2.0
