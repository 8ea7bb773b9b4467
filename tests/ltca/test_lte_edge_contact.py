"""Loaded TE where the transmitting contact is an edge contact (issue 28), on
CHATTER_PAIR of tests/design_space.py (drive, 61 phases: the pinion's root edge carries
rows 44-60 and 0; rigid teeth, 64.5 N·m, 40 cells, the loaded TE's defaults).

Truths:

1. *The field holds the touch*: the edge contact's field (:func:`~gearcontact.tca.
   edge_field.edge_gap_field` in :class:`~gearcontact.ltca.lte_pairs.PairFields`) has
   its least initial separation at the TCA's touch, 0, to the grid's resolution: between
   -1e-9 mm and the Taylor separation half a cell inside the edge, ``m h_t / 2 + (1/2)
   B_tt (h_t / 2)^2`` (``m``: inward slope, ``B``: the smooth flanks' relative
   curvature at the contact, from the surfaces' derivatives), +5 % for the cubic terms.
   Before, the surface-frame field's least gap lay 21-22 um above (rows 44-55).
2. *Continuity*: where the transmitting contact passes from the surface to the edge
   (rows 43 -> 44 and 0 -> 1) TE_LCP may jump by no more than TE0's own jump plus the
   growth of the approach when the edge cuts the patch: a Hertzian contact cut through
   its centre carries its load ``W`` on half its ellipse, which needs at most the
   approach of the whole ellipse under ``2 W`` (the half of that pressure, the other
   half removed, deflects the surface less everywhere: Boussinesq's kernel is positive;
   Johnson 1985 sec. 3.4), so the rotation grows by at most ``(2^(2/3) - 1)
   delta_H(W) / l`` (Hamrock-Brewe ``delta_H`` of the pair's nearest surface contact,
   ``W = T / l``). Before: 23.6 arcsec at 43 -> 44.
3. *Load balance*: ``sum_j W_j l_j = T`` at every row, to 1e-9 relative (the solver
   rescales the torque shares to T; rounding).

Cost: about 60 s (pair, TCA, 61 LCP phases): slow.
"""

import numpy as np
import pytest

from design_space import CHATTER_PAIR, design_space_pair
from table_fields import table_fields
from gearcontact.analytic.hertz import hamrock_brewe_hertz
from gearcontact.geometry.pair import pair_to_toml
from gearcontact.ltca.lte import loaded_te
from gearcontact.ltca.lte_pairs import phase_contacts
from gearcontact.ltca.pair_ltca import ARCSEC_PER_RAD
from gearcontact.materials import effective_modulus_mpa
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.curvature import curvature_tensor, relative_curvature
from gearcontact.tca.edge_contact import inward_slope
from gearcontact.tca.synthesis import prepare_pair

TORQUE_NM, SIDE = 64.5, "drive"


@pytest.fixture(scope="module")
def chatter(tmp_path_factory):
    # through its pair file, as the commands see it (the file's ease-off tables are
    # kept; a GearPair without tables would get a synthesized ease-off)
    path = tmp_path_factory.mktemp("chatter") / "chatter.toml"
    path.write_text(pair_to_toml(design_space_pair(*CHATTER_PAIR)))
    prepared = prepare_pair(path)
    pair, flanks = prepared.pair, prepared.flank_set()
    tca = analyze_pair(pair, side=SIDE, phases=61, flanks=flanks)[0]
    lte = loaded_te(tca, flanks, pair, TORQUE_NM, side=SIDE)
    return pair, flanks, tca, lte


def _edge_rows(tca):
    return np.array([bool(mp.edge_contact) for mp in tca.cycle.contact])


@pytest.mark.slow
def test_edge_field_holds_the_touch(chatter):
    pair, flanks, tca, _ = chatter
    t = table_fields(pair, tca, flanks, SIDE, TORQUE_NM)
    cycle, kin, pinion, gear, e_prime, fields, base = (t.cycle, t.kin, t.pinion, t.gear,
                                                       t.e_prime, t.fields, t.base)
    rows = np.flatnonzero(_edge_rows(tca))
    assert rows.size >= 12
    for k in rows:
        pc = next(p for p in phase_contacts(pinion, gear, kin, cycle, int(k), base, e_prime,
                                            {}, 0)
                  if cycle.path.points[p.path_index].edge_contact and p.opening_arcsec == 0.0)
        mp = cycle.path.points[pc.path_index]
        gap, grid, off, _ = fields.get(pc)
        axes = fields.frames[pc.field_key][1]
        h_t = float(grid.dy_mm[0])
        rot1, rot2 = kin.pinion_pose(mp.phi1_rad)[0], kin.gear_pose(mp.phi2_rad)[0]
        b = -(curvature_tensor(pinion.point(mp.u1, mp.v1), rot1, axes[:, :2])
              + curvature_tensor(gear.point(mp.u2, mp.v2), rot2, axes[:, :2]))
        bound = (inward_slope(pinion, gear, kin, mp) * 0.5 * h_t
                 + 0.5 * float(b[1, 1]) * (0.5 * h_t) ** 2)
        g_min = float(gap[~off].min())
        assert -1e-9 <= g_min <= 1.05 * bound + 1e-9, (k, g_min, bound)


@pytest.mark.slow
def test_loaded_te_is_continuous_into_the_edge(chatter):
    pair, flanks, tca, lte = chatter
    edge = _edge_rows(tca)
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    switches = [k for k in range(1, len(edge)) if edge[k] != edge[k - 1]]
    assert len(switches) == 2        # 43 -> 44 and 0 -> 1
    for k in switches:
        surface = k - 1 if edge[k] else k
        i0 = lte.pair_offsets.index(0)
        lever = float(lte.lever_mm[i0, surface])
        load = 1e3 * TORQUE_NM / lever
        mp = tca.cycle.contact[surface]
        rc = relative_curvature(flanks.flank("pinion", SIDE), flanks.flank("gear", SIDE),
                                pair.kinematics(), mp)
        delta = hamrock_brewe_hertz(rc.A_minus_per_mm, rc.B_minus_per_mm, load,
                                    e_prime_mpa=e_prime).approach_mm
        bound = (2.0 ** (2.0 / 3.0) - 1.0) * delta / lever * ARCSEC_PER_RAD
        jump = abs(lte.te_lcp_arcsec[k] - lte.te_lcp_arcsec[k - 1])
        jump0 = abs(lte.te0_arcsec[k] - lte.te0_arcsec[k - 1])
        assert jump <= jump0 + bound, (k, jump, jump0, bound)


@pytest.mark.slow
def test_load_balance_at_every_row(chatter):
    *_, lte = chatter
    assert lte.converged
    torque = (lte.pair_loads_lcp_n * np.nan_to_num(lte.lever_mm)).sum(axis=0)
    np.testing.assert_allclose(torque, 1e3 * TORQUE_NM, rtol=1e-9)
