"""The tooth without a rim block as a Ritz solid (``structure.tooth_solid``,
``build_shell(..., rim_block=True, solid_tooth=True)``; docs/bending.md sec. 13, session 25).

Truths: the geometry (the solid's faces are the tooth's flanks and fillet, to rounding),
the Ritz property of nested trial spaces (the compliance never falls as the degrees
rise), the unchanged model of a tooth with a block, and the 3D FE (test_no_block_fe.py's
set-up: the rim clamped at the shell's fillet height, no block below it).
"""

from __future__ import annotations

import numpy as np
import pytest

from gearcontact.structure.rim import rim_points, rim_segment
from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING
from gearcontact.structure.shell import build_shell
from gearcontact.structure.tooth import tooth_geometry
from gearcontact.structure.tooth_solid import _mapping, solid_count


@pytest.fixture(scope="module")
def gear_no_block(s0003_centred):
    """The s0003-centred gear tooth and its rim clamped at its fillet height (no block)."""
    pair, flanks = s0003_centred
    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    rim = rim_segment(tooth, depth_mm=rim_segment(tooth).fillet_mm,
                      stiffening=BLOCK_RIM_STIFFENING)
    return tooth, rim


def _solid(tooth, rim, degrees):
    return build_shell(tooth, order=2, order_face=2, rim=rim, rim_block=True,
                       solid_tooth=True, solid_degrees=degrees, solid_points=(8, 6, 4))


def test_solid_faces_are_the_flanks_and_the_fillet(gear_no_block):
    """The map of the solid at zeta~ = -1 / 1 is the coast / drive flank point of the same
    (xi, eta) (``ToothGeometry.side_points``), at the root line both pieces meet, and the
    fillet piece is ``rim.rim_points``: exact formulas, so within 1e-9 mm (rounding)."""
    tooth, rim = gear_no_block
    model = _solid(tooth, rim, (1, 1, 1))
    split = model.rim_split
    xi = np.linspace(-1.0, 1.0, 7)
    eta = np.linspace(-1.0, 1.0, 7)
    X, E = (a.ravel() for a in np.meshgrid(xi, eta))
    eta_r = split + 0.5 * (1.0 - split) * (E + 1.0)
    pc, pd = tooth.side_points(X, E)
    for across, want in ((-1.0, pc), (1.0, pd)):
        q = np.stack([X, eta_r, np.full_like(X, across)], axis=1)
        assert np.max(np.abs(_mapping(model, "tooth")(q) - want)) < 1e-9
    # the root line from both pieces, and the clamped bottom on the rim's points
    q = np.stack([xi, np.full_like(xi, split), np.zeros_like(xi)], axis=1)
    assert np.max(np.abs(_mapping(model, "tooth")(q) - _mapping(model, "fillet")(q))) < 1e-9
    q[:, 1] = -1.0
    bottom = rim_points(tooth, rim, xi, np.full_like(xi, rim.depth_mm), np.full_like(xi, 0.5))
    assert np.max(np.abs(_mapping(model, "fillet")(q) - bottom)) < 1e-9


def test_solid_compliance_never_falls_with_the_degrees(gear_no_block):
    """Nested trial spaces on one quadrature: the compliance under a fixed load (drive-flank
    points at mid-height, one at a time and all together) never falls as the degrees rise
    (Ritz; tolerance 1e-9 relative, rounding of the factorization)."""
    tooth, rim = gear_no_block
    pts = tooth.points_at("drive", np.linspace(-0.6, 0.6, 5), np.zeros(5))
    prev = None
    for degrees in ((2, 2, 1), (3, 3, 2), (4, 4, 3)):
        model = _solid(tooth, rim, degrees)
        assert model.n_functions == solid_count(degrees) == 3 * np.prod(np.add(degrees, 1))
        G = model.compliance(pts).matrix()
        c = np.concatenate([np.diag(G), [G.sum()]])
        assert np.allclose(G, G.T, rtol=0, atol=1e-12 * np.abs(G).max())
        if prev is not None:
            assert np.all(c >= prev * (1.0 - 1e-9)), (c, prev)
        prev = c


def test_solid_tooth_leaves_a_tooth_with_a_block_unchanged(s0003_centred):
    """``solid_tooth`` acts on a tooth without a block only: on the s0003-centred gear with
    its default rim (a block below the fillet) the shell is the block model's, the same
    Cholesky factor bit for bit (one code path)."""
    pair, flanks = s0003_centred
    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    rim = rim_segment(tooth, stiffening=BLOCK_RIM_STIFFENING)
    kw = dict(order=3, order_face=3, rim=rim, rim_block=True, block_orders=(2, 1, 1))
    a = build_shell(tooth, **kw)
    b = build_shell(tooth, solid_tooth=True, **kw)
    assert b.solid_degrees is None and a.n_functions == b.n_functions
    assert np.array_equal(a.cholesky, b.cholesky)
