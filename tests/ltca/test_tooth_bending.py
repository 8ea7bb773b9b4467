"""Loaded TE of s0003 with tooth bending (gearcontact.ltca.tooth_bending + lte).

Truths:
* zero-compliance limit (bending scale 0): the rigid-tooth loaded TE (rotations and
  pair loads to 1e-9 relative; the rigid path itself is unchanged bit for bit, checked
  in test_mesh_lcp.py);
* conservation at every phase with bending: torque balance sum_j W_j l_j = T (1e-10)
  and load shares summing to 100 %, every solve converged (complementarity residual
  below the solver's 1e-6);
* monotonicity: a softer tooth model (compliance x2, i.e. E / 2) rotates more at every
  phase, and bending makes the mesh compliance larger than the rigid one;
* the sub-lattice + spline evaluation of a 40 x 40 field's block equals the exact
  evaluation at every cell within 2e-3 of its largest entry (measured 1.1e-3; the
  model itself is within 25 % of 3D FE, so this is far below its accuracy);
* Maxwell-Betti: the pair's bending block F F^T is symmetric positive semi-definite by
  construction; it equals the sum of the pinion and gear shell compliances at its cells
  within 1e-4 of its largest entry (the flank-rows spline: measured 4e-5, below);
* the flank-rows spline (a tensor cubic over a 193 x 33 lattice of the flank) gives the
  exact shell compliance between random flank points, box corners included, within
  1e-4 of the largest self-compliance (measured 4.3e-5 pinion, 1.5e-5 gear on s0003).
"""

import numpy as np
import pytest

from gearcontact.ltca.lte import loaded_te
from gearcontact.ltca.tooth_bending import flank_rows, tooth_bending
from gearcontact.validation import InputRangeError

CELLS, STRIDE = 24, 5  # TCA: 11 phases per pitch (conftest centred_drive_11)


def run(centred_drive_11, scale=None):
    pair, flanks, tca = centred_drive_11
    bend = None if scale is None else tooth_bending(flanks, pair, side="drive", scale=scale)
    return loaded_te(tca, flanks, pair, 64.5, cells=CELLS, stride=STRIDE, bending=bend)


@pytest.fixture(scope="module")
def results(centred_drive_11):
    return {s: run(centred_drive_11, s) for s in (None, 0.0, 1.0, 2.0)}


def test_zero_compliance_limit(results):
    rigid, zero = results[None], results[0.0]
    np.testing.assert_allclose(zero.rotation_lcp_arcsec, rigid.rotation_lcp_arcsec, rtol=1e-9)
    np.testing.assert_allclose(zero.pair_loads_lcp_n, rigid.pair_loads_lcp_n, rtol=1e-9,
                               atol=1e-9 * rigid.pair_loads_lcp_n.max())


def test_balance_and_shares_with_bending(results):
    res = results[1.0]
    assert res.converged
    moments = np.nansum(res.pair_loads_lcp_n * np.nan_to_num(res.lever_mm), axis=0)
    np.testing.assert_allclose(moments, 64.5e3, rtol=1e-10)
    shares = 100 * res.pair_loads_lcp_n / res.pair_loads_lcp_n.sum(axis=0)
    np.testing.assert_allclose(shares.sum(axis=0), 100.0, rtol=1e-12)


def test_softer_teeth_rotate_more(results):
    rigid, one, two = results[None], results[1.0], results[2.0]
    assert (one.rotation_lcp_arcsec > rigid.rotation_lcp_arcsec).all()
    assert (two.rotation_lcp_arcsec > one.rotation_lcp_arcsec).all()
    assert two.mesh_compliance_lcp_mm_per_n > one.mesh_compliance_lcp_mm_per_n \
        > rigid.mesh_compliance_lcp_mm_per_n


def test_block_is_the_sum_of_both_teeth(centred_drive_11):
    pair, flanks, _ = centred_drive_11
    bend = tooth_bending(flanks, pair, side="drive")
    uv1 = np.array([[1.2, 36.0], [1.0, 34.0]])
    uv2 = np.array([[1.1, 0.5], [1.3, -1.0]])
    F = bend.factor(uv1, uv2, (1, 2)).reshape(2, -1)
    G = F @ F.T
    want = [bend.pinion.compliance(bend.pinion.body.flank_points("drive", *uv1.T)).matrix(),
            bend.gear.compliance(bend.gear.body.flank_points("drive", *uv2.T)).matrix()]
    exact = want[0] + want[1]
    assert np.abs(G - exact).max() <= 1e-4 * exact.max()
    np.testing.assert_allclose(G, G.T, rtol=0, atol=1e-15 * exact.max())
    assert np.linalg.eigvalsh(G).min() > 0


@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_flank_rows_match_exact_shell(centred_drive_11, member):
    pair, flanks, _ = centred_drive_11
    bend = tooth_bending(flanks, pair, side="drive")
    shell = getattr(bend, member)
    flank = shell.body.drive
    rng = np.random.default_rng(7)
    (u0, u1), (v0, v1) = flank.u_range, flank.v_range
    uv = np.vstack([np.column_stack([rng.uniform(u0, u1, 150), rng.uniform(v0, v1, 150)]),
                    [[u0, v0], [u0, v1], [u1, v0], [u1, v1]]])
    rows = flank_rows(shell, "drive").rows(uv)
    g = rows @ rows.T
    exact = shell.compliance(shell.body.flank_points("drive", *uv.T)).matrix()
    assert np.abs(g - exact).max() <= 1e-4 * np.diag(exact).max()


def test_bad_input(centred_drive_11):
    pair, flanks, tca = centred_drive_11
    with pytest.raises(InputRangeError, match="bending scale"):
        tooth_bending(flanks, pair, side="drive", scale=-1.0)
    bend = tooth_bending(flanks, pair, side="coast")
    with pytest.raises(InputRangeError, match="bending.side"):
        loaded_te(tca, flanks, pair, 64.5, cells=CELLS, stride=STRIDE, bending=bend)


def test_sub_lattice_interpolation_matches_exact(centred_drive_11):
    pair, flanks, _ = centred_drive_11
    bend = tooth_bending(flanks, pair, side="drive")
    # a 40 x 40 field, 7 x 1 mm, affine in the cell index like the tangent-plane map,
    # at mid flank of both teeth (the s0003 reference pair's neighbourhood)
    J, I = np.meshgrid(np.arange(40), np.arange(40), indexing="ij")
    uv1 = np.column_stack([(1.2 + 0.02 * (J - 20) + 0.005 * (I - 20)).ravel(),
                           (35.0 + 0.17 * (I - 20) - 0.01 * (J - 20)).ravel()])
    uv2 = np.column_stack([(1.3 + 0.02 * (J - 20) - 0.004 * (I - 20)).ravel(),
                           (0.5 + 0.17 * (I - 20) + 0.01 * (J - 20)).ravel()])
    fast = bend.factor(uv1, uv2, (40, 40)).reshape(1600, -1)
    exact = bend.factor(uv1, uv2, (40, 40), nodes=(40, 40)).reshape(1600, -1)
    sub = np.arange(0, 1600, 7)  # every 7th cell: a 229 x 229 block of G
    g_fast, g_exact = fast[sub] @ fast[sub].T, exact[sub] @ exact[sub].T
    assert np.abs(g_fast - g_exact).max() <= 2e-3 * g_exact.max()
