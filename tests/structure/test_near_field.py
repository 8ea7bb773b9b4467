"""The solid tooth's far field against the FE's (docs/bending.md sec. 13, session 26).

Declared before measuring (docs/bending.md, "The solid tooth's far field"): the far field
of the Ritz solid tooth (its mid-surface patch compliance minus the half-space's at the
same depth, Vijayakar's split) against the FE's (its loaded-flank patch compliance under
the consistent pressure load minus the half-space's surface near field of the same
patch), on set A's three gears without a block, 9 segment and 3 line patches each:
every ratio in 0.84 .. 1.19.
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
                                              solid_far_field, solid_patch_compliance)
from gearcontact.structure.rim import rim_segment
from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING, NoBlockWarning, has_block
from gearcontact.structure.shell import ORDER, ORDER_FACE, build_shell, tooth_shell
from gearcontact.structure.tooth import RectangularPlate, tooth_geometry

#: Set A's band (test_no_block_fe.BAND), declared for the far-field ratios.
BAND = (0.84, 1.19)
#: The default FE mesh's node-line steps: xi 1/6 (12 cells), eta 1/3 (6 cells).
_DXI, _DETA = 2.0 / 12, 2.0 / 6


def set_a_patches(side: str) -> list[FlankPatch]:
    """The 12 patches of set A (docs/bending.md, session 26): the 9 segment patches at
    xi = -1/2, 0, 1/2 x eta = -1/3, 0, 1/3 (the segment's 5 node columns, clipped inside
    the face as its loads are; one row either side), then the 3 line patches."""
    out = []
    for xc in (-0.5, 0.0, 0.5):
        c = int(np.clip(round((xc + 1.0) / _DXI), 3, 9))
        for ec in (-1 / 3, 0.0, 1 / 3):
            out.append(FlankPatch(side, (-1.0 + (c - 2) * _DXI, -1.0 + (c + 2) * _DXI),
                                  (ec - _DETA, ec + _DETA)))
    for ec in (-1 / 3, 0.0, 1 / 3):
        out.append(FlankPatch(side, (-1.0 + _DXI, 1.0 - _DXI), (ec - _DETA, ec + _DETA)))
    return out


def far_field_table(pair, flanks, member: str, fe_mesh: FeMesh = FeMesh()) -> dict:
    """Every quantity of the declared comparison on one tooth without a block (set A's
    set-up, test_no_block_fe.no_block_ratios): arrays over the 12 patches, mm/N."""
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
                        solid_tooth=True)
    root, why = _real_root(plate, lambda: _cutter_fillets(pair, flanks, member), fe_mesh)
    assert why is None, why
    fe = build_fe(tooth, n_xi=fe_mesh.n_xi, n_eta=fe_mesh.n_eta, n_zeta=fe_mesh.n_zeta,
                  n_rim=fe_mesh.n_rim, root=root, n_fillet=fe_mesh.n_fillet,
                  n_slot=fe_mesh.n_slot)
    rows = []
    for patch in set_a_patches(pair.design_side):
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
