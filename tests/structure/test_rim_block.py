"""The rim block below the fillet as a Ritz solid (``structure.rim_block``,
docs/bending.md sec. 13) on the calibrated s0003 pinion, whose tooth wraps furthest
about its axis (7 teeth).

Truths: the plate's fields carried into the block have the gradients of their own
displacement (central differences of u, independent of the chain rule the module
writes out); nested Ritz spaces on one quadrature (the compliance never falls as the
enrichment grows); the enrichment's energy is the solid's of ``structure.ritz_solid``
(tested there against elasticity).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from gearcontact.structure.rim import RimSegment, rim_mid_surface, rim_segment
from gearcontact.structure.rim_block import _plate_gradients
from gearcontact.structure.shell import build_shell
from gearcontact.structure.tooth import local_frame, tooth_geometry
from gearcontact.validation import InputRangeError

#: Small Ritz orders (plate over the height, along the face): seconds per build.
ORDERS = dict(order=3, order_face=4)


@pytest.fixture(scope="module")
def pinion(pairs):
    pair, flanks = pairs["s0003"]
    tooth = tooth_geometry(flanks, "pinion", material=pair.pinion_material)
    return tooth, rim_segment(tooth, stiffening=1.49)


def test_carried_plate_fields_have_their_displacements_gradients(pinion):
    """d u / d(xi, s, zeta) of every carried plate function (w m + z beta_k e_k, frame
    and thickness turning) against central differences of u itself (1e-6 of the largest
    gradient: the module differentiates the frame with step 1e-3, the test u with 1e-4,
    both O(h^2) on a smooth frame; measured 3.4e-7)."""
    tooth, rim = pinion
    model = build_shell(tooth, rim=rim, rim_block=True, block_orders=None, **ORDERS)
    xi = np.array([-0.7, 0.1, 0.8])
    s = np.array([0.6, 1.4, 2.2]) * rim.depth_mm / 2.9
    zeta = np.array([0.15, 0.5, 0.9])
    rate = (model.rim_split + 1.0) / rim.depth_mm

    def u(x, d, z):
        """Displacements (m_plate, n, 3) of the plate functions at (x, d, z), n = 9."""
        X, D = np.repeat(x, 3), np.repeat(d, 3)
        Z = np.tile(z, len(x))
        mid = rim_mid_surface(tooth, rim, X, D)
        e1, e2, m = local_frame(mid)
        N = model._functions(X, model.rim_split - rate * D)[0][0]
        off = ((Z - 0.5) * mid.thickness_mm)[None, :, None]
        return np.concatenate([N[..., None] * m, off * N[..., None] * e1,
                               off * N[..., None] * e2])

    got = _plate_gradients(model, xi, s, 3, zeta)
    h = 1e-4
    want = np.stack([(u(xi + h, s, zeta) - u(xi - h, s, zeta)) / (2 * h),
                     (u(xi, s + h, zeta) - u(xi, s - h, zeta)) / (2 * h),
                     (u(xi, s, zeta + h) - u(xi, s, zeta - h)) / (2 * h)], axis=-1)
    err = np.max(np.abs(got - want)) / np.max(np.abs(want))
    assert err < 1e-6


def test_enrichment_only_softens(pinion):
    """Nested spaces on one quadrature: the deflection under a whole-face load on the
    drive flank at mid-height never falls as the enrichment's orders rise (None ->
    (2, 1, 1) -> (4, 2, 2); 1e-10 relative: rounding of the factorizations), and rises
    (the plate's kinematics alone in the solid is a constraint)."""
    tooth, rim = pinion
    pts = tooth.points_at("drive", np.linspace(-0.9, 0.9, 7), np.zeros(7))
    out = []
    for orders in (None, (2, 1, 1), (4, 2, 2)):
        model = build_shell(tooth, rim=rim, rim_block=True, block_orders=orders,
                            block_points=(12, 8, 6), **ORDERS)
        G = model.compliance(pts).matrix()
        out.append(float(np.sum(G)) / len(pts) ** 2)
    assert out[0] < out[1] * (1 + 1e-10) and out[1] < out[2] * (1 + 1e-10), out
    assert out[2] > 1.01 * out[0], out


def test_loads_reach_only_the_plate(pinion):
    """Flank loads do no work on the enrichment (it lives below the fillet)."""
    tooth, rim = pinion
    model = build_shell(tooth, rim=rim, rim_block=True, block_orders=(1, 1, 1),
                        block_points=(8, 4, 2), **ORDERS)
    assert model.n_plate == 3 * 4 * 5
    phi = model.load_vectors(tooth.points_at("coast", np.array([0.0, 0.5]),
                                             np.array([-1.0, 0.5])))
    assert phi.shape == (2, model.n_functions) and model.n_functions == model.n_plate + 24
    assert np.all(phi[:, model.n_plate:] == 0.0) and np.any(phi[:, :model.n_plate] != 0.0)


def test_bad_input_is_named(pinion):
    tooth, rim = pinion
    with pytest.raises(InputRangeError, match="rim"):
        build_shell(tooth, rim=None, rim_block=True, **ORDERS)
    with pytest.raises(InputRangeError, match="block_orders"):
        build_shell(tooth, rim=rim, rim_block=True, block_orders=(1, 2), **ORDERS)
    with pytest.raises(InputRangeError, match="block_orders"):
        build_shell(tooth, rim=rim, rim_block=True, block_orders=(1, -1, 2), **ORDERS)
    with pytest.raises(InputRangeError, match="rim_block"):
        build_shell(tooth, rim=rim, rim_block=True, membrane=True, **ORDERS)
    with pytest.raises(InputRangeError, match="rim_block"):
        build_shell(tooth, rim=rim, rim_block=1, **ORDERS)


#: Orders of the continuity test's block (enrichment, Gauss nodes): small, seconds.
THIN = dict(block_orders=(2, 1, 1), block_points=(12, 8, 4))


def test_block_of_vanishing_depth_tends_to_the_plate(pinion):
    """docs/bending.md sec. 13, "Teeth without a block" (declared before measuring): the
    fillet F fixed, the rim's bottom at D = F + h, the block model at the calibrated
    factor; truth: the plate alone at h = 0 (the same fillet and factor), the self
    compliances at 7 points of the drive flank at mid-height and the whole-face sum.

    1. h = 0: the block model is the plate alone (no enrichment; 1e-12: one code path);
    2. h = BLOCK_MIN_DEPTH D (the solid): within 1e-2 (the O(h) bound with a constant
       up to 10, a full block being tens of % of the compliance);
    3. O(h): the difference at h = 1e-2 D at least 5 times that at 1e-3 D (10 for an
       exact first order; 5 leaves room for the O(h^2) term);
    4. h = BLOCK_MIN_DEPTH D / 2 (no solid: the plate through the sliver): within 1e-2."""
    from gearcontact.structure.rim_block import (BLOCK_MIN_DEPTH, BLOCK_RIM_STIFFENING,
                                                 NoBlockWarning)

    tooth, rim = pinion
    fil = rim.fillet_mm
    pts = tooth.points_at("drive", np.linspace(-0.9, 0.9, 7), np.zeros(7))

    def values(h, **opts):
        d = fil / (1.0 - h)                       # h as a fraction of D = F + h D
        seg = RimSegment(depth_mm=d, fillet_mm=fil if h else d,
                         stiffening=BLOCK_RIM_STIFFENING)
        model = build_shell(tooth, rim=seg, **ORDERS, **opts)
        G = model.compliance(pts).matrix()
        return model, np.append(np.diag(G), np.sum(G))

    plate, want = values(0.0)
    with pytest.warns(NoBlockWarning, match=r"no block below the fillet .* not calibrated"):
        same, got = values(0.0, rim_block=True, **THIN)
    assert not same.rim_block and same.n_functions == plate.n_functions
    assert np.max(np.abs(got / want - 1.0)) < 1e-12
    err = {}
    for h in (1e-2, BLOCK_MIN_DEPTH, 0.5 * BLOCK_MIN_DEPTH):
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always", NoBlockWarning)
            model, got = values(h, rim_block=True, **THIN)
        # the warning exactly where the plate continues (no block for the solid)
        assert bool(seen) is (h < BLOCK_MIN_DEPTH), (h, seen)
        assert model.rim_block is (h >= BLOCK_MIN_DEPTH), h
        err[h] = float(np.max(np.abs(got / want - 1.0)))
    print("relative difference from the plate alone by h / D:", err)
    assert err[BLOCK_MIN_DEPTH] < 1e-2, err
    assert err[1e-2] >= 5.0 * err[BLOCK_MIN_DEPTH], err
    assert err[0.5 * BLOCK_MIN_DEPTH] < 1e-2, err


def _ratios(pair, flanks, member, shell, fe_root):
    """(largest, smallest) shell / FE over the 12 distributed loads of the default
    lattice and FE mesh (``structure.compliance.compare_on_root``: the calibration's
    path), the FE on the ellipse or the real ("cutter") root."""
    from gearcontact.structure.compliance import FeMesh, _cutter_fillets, compare_on_root

    res = compare_on_root(shell, lambda: _cutter_fillets(pair, flanks, member),
                          name=pair.name, side=pair.design_side, xi=(-0.5, 0.0, 0.5),
                          eta=(-1 / 3, 0.0, 1 / 3), fe=True, fe_mesh=FeMesh(),
                          fe_root=fe_root)
    assert res.fe_root == fe_root
    r = np.concatenate([res.segment_shell_mm_per_n / res.segment_fe_mm_per_n,
                        res.line_shell_mm_per_n / res.line_fe_mm_per_n])
    return float(r.max()), float(r.min())


@pytest.mark.slow
def test_block_brings_the_seven_tooth_pinion_to_its_gear(pairs):
    """Criterion 1 of docs/bending.md sec. 13 (sec. 12's, declared before measuring) on
    the calibrated s0003 pair: with the FE on the shell's own ellipse root (one geometry
    in both models), the plate at its factor 1.49 and the block model at its own
    calibrated factor (:data:`BLOCK_RIM_STIFFENING`), ln(max shell/FE of the pinion /
    max of the gear) must fall by at least 0.10 (the declared 'improved'). Truth: the 3D
    FE (P2, default mesh)."""
    from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING
    from gearcontact.structure.shell import ORDER, ORDER_FACE

    pair, flanks = pairs["s0003"]
    gap = {}
    for block in (False, True):
        largest = {}
        for member in ("pinion", "gear"):
            tooth = tooth_geometry(flanks, member,
                                   material=getattr(pair, f"{member}_material"))
            if block:
                shell = build_shell(tooth, order=ORDER, order_face=ORDER_FACE,
                                    rim=rim_segment(tooth, stiffening=BLOCK_RIM_STIFFENING),
                                    rim_block=True)
            else:
                shell = build_shell(tooth, order=ORDER, order_face=ORDER_FACE,
                                    rim=rim_segment(tooth, stiffening=1.49))
            largest[member] = _ratios(pair, flanks, member, shell, "ellipse")[0]
        gap[block] = np.log(largest["pinion"] / largest["gear"])
    assert gap[False] - gap[True] >= 0.10, gap


@pytest.mark.slow
@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_block_model_on_the_real_roots_of_s0003(pairs, member):
    """The s0003 teeth on their real roots (the calibration's FE, default mesh, the 12
    loads), the block model at :data:`BLOCK_RIM_STIFFENING`: within the band declared
    in docs/bending.md sec. 12 for a new term, 0.84 .. 1.19, and the pinion's largest
    ratio <= 1.15 (the band's 'improved' condition)."""
    from gearcontact.structure.shell import tooth_shell

    pair, flanks = pairs["s0003"]
    shell = tooth_shell(flanks, member, material=getattr(pair, f"{member}_material"),
                        rim_block=True)
    hi, lo = _ratios(pair, flanks, member, shell, "cutter")
    assert 0.84 <= lo and hi <= 1.19, (lo, hi)
    if member == "pinion":
        assert hi <= 1.15, hi
