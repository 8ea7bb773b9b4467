"""The solid tooth's far field against the FE's (docs/bending.md sec. 13, session 26).

Declared before measuring (docs/bending.md, "The solid tooth's far field"): the far field
of the Ritz solid tooth (its mid-surface patch compliance minus the half-space's at the
same depth, Vijayakar's split) against the FE's (its loaded-flank patch compliance under
the consistent pressure load minus the half-space's surface near field of the same
patch), on set A's three gears without a block, 9 segment and 3 line patches each:
every ratio in 0.84 .. 1.19.

Measured: it differs, because the truth's far field changes sign (the tooth clamped
within millimetres below a low patch indents less than a half-space), so the ratio is
undefined (slow strict xfail). A second criterion, declared after the first gear and
before the two others ran: the combined loaded-flank compliance the LTCA's contact
sees, HS_s + far_solid, against the FE's, in the same band on the two held-out gears.
Met (1.026 .. 1.162; the seen gear 1.039 .. 1.088), where today's plate operator gives
1.45 .. 2.60 (slow test; a coarse-mesh default test).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from gearcontact.materials import Material
from gearcontact.structure.compliance import FeMesh, _cutter_fillets, _real_root
from gearcontact.structure.near_field import (FlankPatch, fe_patch_compliance,
                                              halfspace_below, halfspace_surface,
                                              patch_points, patch_rectangle,
                                              solid_far_field, solid_far_field_matrix,
                                              solid_patch_compliance)
from gearcontact.structure.rim import rim_segment
from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING, NoBlockWarning, has_block
from gearcontact.structure.shell import ORDER, ORDER_FACE, build_shell, tooth_shell
from gearcontact.structure.tooth import RectangularPlate, tooth_geometry

#: Set A's band (test_no_block_fe.BAND), declared for the far-field ratios.
BAND = (0.84, 1.19)
#: The default-suite test's FE mesh: the default mesh's node lines along the face and the
#: height (the patches' bounds), fewer cells across, in the rim and the slots.
COARSE = FeMesh(12, 6, 2, 2, 2, 1)
#: Its measured error on the combined ratio: the largest |log(coarse / default)| over the
#: s0003-centred gear's 12 patches, 0.027, rounded up to 0.01 (docs/bending.md).
COARSE_LOG_ERROR = 0.03
#: The declared ratio criterion's measured failure (the strict xfail's reason).
FAR_RATIOS = {"s0003-centred gear": (-1.54, 5.01), "s0003 gear": (-8.45, 3.47),
              "F.2 gear": (-4.85, 2.41)}
#: The default FE mesh's node-line steps: xi 1/6 (12 cells), eta 1/3 (6 cells).
_DXI, _DETA = 2.0 / 12, 2.0 / 6


def set_a_patches(side: str, half_height: float = _DETA) -> list[FlankPatch]:
    """The 12 patches of set A (docs/bending.md, session 26): the 9 segment patches at
    xi = -1/2, 0, 1/2 x eta = -1/3, 0, 1/3 (the segment's 5 node columns, clipped inside
    the face as its loads are; ``half_height`` in eta either side, by default one row of
    the default mesh), then the 3 line patches."""
    out = []
    for xc in (-0.5, 0.0, 0.5):
        c = int(np.clip(round((xc + 1.0) / _DXI), 3, 9))
        for ec in (-1 / 3, 0.0, 1 / 3):
            out.append(FlankPatch(side, (-1.0 + (c - 2) * _DXI, -1.0 + (c + 2) * _DXI),
                                  (ec - half_height, ec + half_height)))
    for ec in (-1 / 3, 0.0, 1 / 3):
        out.append(FlankPatch(side, (-1.0 + _DXI, 1.0 - _DXI),
                              (ec - half_height, ec + half_height)))
    return out


def far_field_table(pair, flanks, member: str, fe_mesh: FeMesh = FeMesh(), *,
                    half_height: float = _DETA, solid_degrees=None) -> dict:
    """Every quantity of the declared comparison on one tooth without a block (set A's
    set-up, test_no_block_fe.no_block_ratios): arrays over the 12 patches, mm/N
    (``half_height`` and ``solid_degrees`` for the diagnostics of docs/bending.md)."""
    from gearcontact.structure.fe import build_fe

    material = getattr(pair, f"{member}_material")
    tooth = tooth_geometry(flanks, member, material=material)
    rim = rim_segment(tooth, depth_mm=rim_segment(tooth).fillet_mm,
                      stiffening=BLOCK_RIM_STIFFENING)
    assert not has_block(rim)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NoBlockWarning)
        plate = tooth_shell(flanks, member, material=material, rim=rim)
    solid = build_shell(tooth, order=ORDER, order_face=ORDER_FACE, rim=rim, rim_block=True,
                        solid_tooth=True, **({} if solid_degrees is None
                                             else {"solid_degrees": solid_degrees}))
    root, why = _real_root(plate, lambda: _cutter_fillets(pair, flanks, member), fe_mesh)
    assert why is None, why
    fe = build_fe(tooth, n_xi=fe_mesh.n_xi, n_eta=fe_mesh.n_eta, n_zeta=fe_mesh.n_zeta,
                  n_rim=fe_mesh.n_rim, root=root, n_fillet=fe_mesh.n_fillet,
                  n_slot=fe_mesh.n_slot)
    rows = []
    for patch in set_a_patches(pair.design_side, half_height):
        s = solid_far_field(solid, patch)
        s["fe_flank"] = fe_patch_compliance(fe, patch)
        s["plate"] = solid_patch_compliance(plate, patch, at="flank")
        rows.append(s)
    out = {k: np.array([r[k] for r in rows]) for k in rows[0]}
    out["fe_far"] = out["fe_flank"] - out["halfspace_surface"]
    return out


# ---------------------------------------------------------------- default tests (seconds)

STEEL = Material(youngs_modulus_mpa=209000.0, poisson_ratio=0.3)


def test_halfspace_below_tends_to_the_point_load_far_and_to_the_surface_near():
    """Boussinesq over the patch against two closed forms: far below (depth 40 x the
    patch) the point load on the axis, P (3 - 2 nu) / (4 pi G z) (Johnson eq. 3.20 at
    r = 0), within 1e-3 (the patch's finite size changes it by (a / z)^2 ~ 6e-4); and at
    a depth of 1/100 of the patch the mean over the patch tends to Love's surface mean
    (halfspace_surface), within 1 % (the mean's own change over that depth is
    O(z / a) = 1 %; measured 0.6 %)."""
    E, nu = 209000.0, 0.3
    g = E / (2 * (1 + nu))
    z = 40.0
    u = halfspace_below(1.0, 0.5, np.array([[0.0, 0.0, z]]), np.array([1.0]),
                        youngs_modulus_mpa=E, poisson_ratio=nu)
    assert u == pytest.approx((3 - 2 * nu) / (4 * np.pi * g * z), rel=1e-3)
    x, w = np.polynomial.legendre.leggauss(20)
    X, Y = np.meshgrid(0.5 * x, 0.5 * x, indexing="ij")
    at = np.stack([X.ravel(), Y.ravel(), np.full(X.size, 0.01)], axis=1)
    near = halfspace_below(1.0, 1.0, at, np.outer(w, w).ravel() / 4.0,
                           youngs_modulus_mpa=E, poisson_ratio=nu, points=(160, 160))
    assert near == pytest.approx(halfspace_surface(1.0, 1.0, youngs_modulus_mpa=E,
                                                   poisson_ratio=nu), rel=0.01)


def test_halfspace_surface_of_a_square_is_loves_mean():
    """The mean surface displacement of a uniformly loaded square of side a is
    0.9464 (1 - nu^2) P / (E a) (the closed-form mean of Love's rectangle: (4/pi)
    [asinh 1 + (1 - sqrt 2)/3] = 0.94640); within 1e-4 (Gauss receivers)."""
    coef = 4.0 / np.pi * (np.arcsinh(1.0) + (1.0 - np.sqrt(2.0)) / 3.0)
    got = halfspace_surface(2.0, 2.0, youngs_modulus_mpa=209000.0, poisson_ratio=0.3)
    assert got == pytest.approx(coef * 0.91 / (209000.0 * 2.0), rel=1e-4)


def test_patch_area_and_rectangle_on_a_flat_plate():
    """On a flat plate (closed-form faces) the patch's area weights sum to its area and
    its rectangle is its sides (exact up to the differences' rounding, 1e-9)."""
    plate = RectangularPlate(length_mm=6.0, width_mm=20.0, thickness_root_mm=2.0,
                             material=STEEL)
    patch = FlankPatch("drive", (-0.5, 0.5), (-0.2, 0.4))
    _, area = patch_points(plate, patch)
    assert area.sum() == pytest.approx(10.0 * 1.8, rel=1e-9)
    assert patch_rectangle(plate, patch) == pytest.approx((10.0, 1.8), rel=1e-9)


def test_point_operator_integrates_to_the_patch_far_field(s0003_centred):
    """solid_far_field_matrix, integrated over a patch's Gauss points with the pressure's
    weights, against solid_far_field of the same patch (the s0003-centred gear's solid
    tooth at small degrees (6, 4, 2), seconds; the middle segment and the middle line
    patch). The solid parts are the same sums (1e-9 relative); the half-space parts are
    two quadratures of one Boussinesq integral, on the curved flank with 3D distances
    against the flat rectangle of the patch: declared within 3 % of the half-space part
    before the run (the flank's curvature over the patch, (L / R)^2 of a few percent at
    most, and the point sum at 0.1-0.3 mm spacing under a 1.2 mm depth)."""
    pair, flanks = s0003_centred
    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    rim = rim_segment(tooth, depth_mm=rim_segment(tooth).fillet_mm,
                      stiffening=BLOCK_RIM_STIFFENING)
    model = build_shell(tooth, order=ORDER, order_face=ORDER_FACE, rim=rim, rim_block=True,
                        solid_tooth=True, solid_degrees=(6, 4, 2))
    patches = set_a_patches(pair.design_side)
    for patch in (patches[4], patches[10]):
        pts, area = patch_points(tooth, patch)
        w = area / area.sum()
        got = w @ solid_far_field_matrix(model, pts) @ w
        ref = solid_far_field(model, patch)
        assert got == pytest.approx(ref["far"], abs=0.03 * ref["halfspace_mid"])


# ---------------------------------------------------------------- the gears


@pytest.fixture(scope="module")
def coarse_centred_table(s0003_centred):
    """far_field_table of the s0003-centred gear on COARSE (about 10-20 s)."""
    pytest.importorskip("skfem")
    pair, flanks = s0003_centred
    return far_field_table(pair, flanks, "gear", COARSE)


def _combined(t) -> np.ndarray:
    return (t["halfspace_surface"] + t["far"]) / t["fe_flank"]


def test_split_meets_the_fe_on_a_coarse_mesh(coarse_centred_table):
    """The s0003-centred gear on COARSE against its FE (truth: the P2 FE's loaded-flank
    patch compliance under the consistent pressure load). The combined loaded-flank
    compliance of the split, HS_s + far_solid, within set A's band widened on each side
    by the coarse mesh's measured error, [0.84 exp(-0.03), 1.19 exp(0.03)] =
    [0.815, 1.226] (measured 1.053 .. 1.119; default mesh 1.039 .. 1.088). Today's
    operator, HS_s + the plate, lies above that band at every patch (measured
    1.497 .. 2.254): the test tells the split from the plate."""
    t = coarse_centred_table
    lo, hi = BAND[0] * np.exp(-COARSE_LOG_ERROR), BAND[1] * np.exp(COARSE_LOG_ERROR)
    r = _combined(t)
    assert np.all((r >= lo) & (r <= hi)), r
    plate = (t["halfspace_surface"] + t["plate"]) / t["fe_flank"]
    assert np.all(plate > hi), plate


def test_far_field_is_negative_under_the_low_patches(coarse_centred_table):
    """The measured reason the declared ratio is undefined and the split is not a
    compliance: under the four patches at eta = -1/3 the FE's loaded flank gives less
    than the half-space's surface near field alone (far_FE < 0; measured -0.54 ..
    -0.36 x 1e-6 mm/N on COARSE, -0.50 .. -0.34 on the default mesh), and so does the
    split (far_solid -0.38 .. -0.28 x 1e-6). Both signs are asserted, not their sizes."""
    t = coarse_centred_table
    low = [0, 3, 6, 9]
    assert np.all(t["fe_far"][low] < 0.0), t["fe_far"][low]
    assert np.all(t["far"][low] < 0.0), t["far"][low]


@pytest.fixture(scope="module")
def gear_tables(gears):
    """far_field_table of set A's three gears on the default mesh (about 2 min)."""
    pytest.importorskip("skfem")
    return {name: far_field_table(pair, flanks, "gear") for name, (pair, flanks)
            in gears.items()}


@pytest.mark.slow
def test_split_meets_the_fe_on_set_a(gear_tables):
    """The second criterion (declared before the s0003 and F.2 gears ran): HS_s +
    far_solid over the FE's loaded-flank patch compliance in 0.84 .. 1.19 at all 36
    patches (measured 1.026 .. 1.162)."""
    for name, t in gear_tables.items():
        r = _combined(t)
        assert np.all((r >= BAND[0]) & (r <= BAND[1])), (name, r)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="differs: the truth's far field changes sign under "
                   f"the low patches, far_solid / far_FE spans {FAR_RATIOS} "
                   "(docs/bending.md sec. 13, session 26)")
def test_declared_far_field_ratio_on_set_a(gear_tables):
    """The declared criterion: far_solid / far_FE in 0.84 .. 1.19 at all 36 patches."""
    for name, t in gear_tables.items():
        r = t["far"] / t["fe_far"]
        assert np.all((r >= BAND[0]) & (r <= BAND[1])), (name, r)


#: Criterion 1 of session 27 (docs/bending.md sec. 13, "The split in the LTCA"): the
#: held-out gears at patch widths within 0.1-0.4 mm, the patch two FE cells high.
NARROW = {"s0003 gear": ((24, 48), (0.265, 0.132)), "F.2 gear": ((48,), (0.309,))}


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason=(
    "differs: (HS_s + far_solid) / C_FE_front 1.119-1.220 (s0003 gear, 0.265 mm), "
    "1.139-1.299 (0.132 mm), 1.089-1.235 (F.2 gear, 0.309 mm); the split's far field is "
    "width-independent while the FE recovers only ~57 % of the half-space's local log "
    "growth per halving of the width (unconverged truth at these widths, docs/bending.md "
    "sec. 13, session 27)"))
def test_split_at_narrow_patches(gears):
    """Declared before measuring: at every patch of the held-out gears at widths of
    0.1-0.4 mm, (HS_s + far_solid) / C_FE_front in set A's band 0.84 .. 1.19, FE
    24 x n_eta x 3 + 4 (3, 2) with the patch two cells high (about 3 min)."""
    pytest.importorskip("skfem")
    from gearcontact.structure.compliance import FeMesh

    for name, (n_etas, widths) in NARROW.items():
        pair, flanks = gears[name]
        for n_eta, width in zip(n_etas, widths):
            t = far_field_table(pair, flanks, "gear", FeMesh(24, n_eta, 3, 4, 3, 2),
                                half_height=2.0 / n_eta)
            assert t["width_mm"].mean() == pytest.approx(width, abs=1e-3)
            r = _combined(t)
            assert np.all((r >= BAND[0]) & (r <= BAND[1])), (name, n_eta, r)
