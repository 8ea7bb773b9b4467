"""Multi-tooth LTCA at P0, rigid and with tooth bending (gearcontact.ltca.multitooth).

Truths:
* the same problem as the loaded TE: the rigid rotation and pair loads equal
  ``loaded_te``'s at the phase of P0 (same pairs, fields and solver; agreement to the
  solver tolerance, 1e-6 relative);
* conservation: torque balance sum_j l_j W_j = T for both solutions (1e-9; the constraint
  is imposed up to rounding) and shares summing to 100 %;
* zero-compliance limit: bending scale 0 gives the rigid solution (1e-9);
* monotonicity: bending makes the rotation larger, and a softer tooth model (scale 2,
  i.e. E / 2) larger still; and it moves load AWAY from the reference pair (the
  direction this model gives, against the published one: docs/bending.md sec. 7 —
  any compliance common to all pairs lets the neighbours, 2.3-2.6 um open, close
  further, and the bending compliance at the neighbours' patches is within 5 % of the
  reference pair's on the centred set-up);
* Hertz: on the centred (Hertzian, no edge) bearing with rigid teeth, CP_max of the
  reference pair equals the Hamrock–Brewe p_max at the load the LCP gives it, within
  5 % (measured 0.7 % at the 24 cells here, 0.05 % at 40; allowed: Hamrock–Brewe is
  within 1.6 % of exact Hertz in p_max, 24 cells put about 6 cells on the minor
  semi-axis, and the real gap is not exactly quadratic over the patch).
"""

import numpy as np
import pytest

from gearcontact.ltca.lte import loaded_te
from gearcontact.ltca.multitooth import multi_tooth_ltca
from gearcontact.ltca.tooth_bending import tooth_bending
from gearcontact.validation import InputRangeError

CELLS, TORQUE = 24, 64.5  # TCA: 11 phases per pitch (conftest centred_drive_11)


@pytest.fixture(scope="module")
def cases(centred_drive_11):
    pair, flanks, tca = centred_drive_11
    out = {}
    for scale in (None, 0.0, 1.0, 2.0):
        bend = None if scale is None else tooth_bending(flanks, pair, side="drive",
                                                        scale=scale)
        out[scale] = multi_tooth_ltca(tca, flanks, pair, TORQUE, side="drive",
                                      bending=bend, cells=CELLS)
    return out


def test_rigid_solution_is_the_loaded_te_at_p0(centred_drive_11, cases):
    pair, flanks, tca = centred_drive_11
    lte = loaded_te(tca, flanks, pair, TORQUE, side="drive", cells=CELLS,
                    stride=len(tca.cycle.phi1_rad))
    k = lte.reference_index
    case = cases[1.0]
    assert case.rotation_rigid_arcsec == pytest.approx(lte.rotation_lcp_arcsec[k], rel=1e-6)
    row = {o: i for i, o in enumerate(lte.pair_offsets)}
    for p in case.pairs:
        assert p.load_rigid_n == pytest.approx(lte.pair_loads_lcp_n[row[p.offset], k],
                                               rel=1e-6, abs=1e-6 * TORQUE)


@pytest.mark.parametrize("scale", [None, 1.0, 2.0])
def test_torque_balance_and_shares(cases, scale):
    c = cases[scale]
    assert c.converged
    torque = 1e3 * TORQUE
    assert sum(p.lever_mm * p.load_n for p in c.pairs) == pytest.approx(torque, rel=1e-9)
    assert sum(p.lever_mm * p.load_rigid_n for p in c.pairs) == pytest.approx(torque,
                                                                               rel=1e-9)
    assert sum(c.load_share_pct) == pytest.approx(100.0, rel=1e-12)
    assert sum(c.load_share_rigid_pct) == pytest.approx(100.0, rel=1e-12)
    assert c.pairs[0].offset == 0 and c.pairs[0].opening_arcsec == 0.0
    s = c.summary()
    assert s["n_engaged"] == sum(w > 0 for w in s["pair_loads_n"])
    assert "solve_ms" not in s


def test_zero_compliance_limit_and_monotone(cases):
    rigid, zero, one, two = cases[None], cases[0.0], cases[1.0], cases[2.0]
    assert zero.rotation_arcsec == pytest.approx(rigid.rotation_rigid_arcsec, rel=1e-9)
    np.testing.assert_allclose([p.load_n for p in zero.pairs],
                               [p.load_rigid_n for p in zero.pairs], rtol=1e-9, atol=1e-9)
    assert rigid.rotation_arcsec == rigid.rotation_rigid_arcsec
    assert one.rotation_rigid_arcsec == rigid.rotation_rigid_arcsec
    assert rigid.rotation_rigid_arcsec < one.rotation_arcsec < two.rotation_arcsec
    # shares monotone in the tooth compliance (E / scale): the reference pair loses load,
    # each neighbour gains (measured 47.2 -> 41.8 -> 40.0 % for scale 0, 1, 2 at 40
    # cells); exact inequalities, the differences are percent, not round-off
    ref = [c.load_share_pct[0] for c in (zero, one, two)]
    assert ref[0] > ref[1] > ref[2]
    for k in range(1, len(one.pairs)):
        assert zero.load_share_pct[k] < one.load_share_pct[k] < two.load_share_pct[k]


def test_cp_max_is_hertzian_on_the_centred_bearing(cases):
    c = cases[None]
    ref = c.pairs[0]
    assert not c.edge_contact and ref.peak.trimmed_cells == 0
    assert ref.peak.cp_max_mpa == pytest.approx(c.preview_p_max_mpa, rel=5e-2)
    assert c.cp_max_mpa <= c.p_peak_cell_mpa * 1.05
    # no edge: the contact line through the contact point is longer than the ellipse,
    # so the preview is the ellipse (docs/hertz.md sec. 6), reported as such
    assert c.preview_mode == "elliptic" and c.summary()["preview_mode"] == "elliptic"
    assert c.line_length_mm > 0


def test_bad_input(centred_drive_11):
    pair, flanks, tca = centred_drive_11
    with pytest.raises(InputRangeError, match="torque"):
        multi_tooth_ltca(tca, flanks, pair, -1.0, side="drive")
    with pytest.raises(InputRangeError, match="cells"):
        multi_tooth_ltca(tca, flanks, pair, TORQUE, side="drive", cells=8)
    with pytest.raises(InputRangeError, match="bending.side"):
        multi_tooth_ltca(tca, flanks, pair, TORQUE, side="drive",
                         bending=tooth_bending(flanks, pair, side="coast"))
