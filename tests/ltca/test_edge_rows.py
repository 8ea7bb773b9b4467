"""The loaded TE's preview (``TE_pre``) with the edge law (ltca.edge_rows: the twin's
LCP-calibrated law where a flank boundary cuts a pair's patch), on the calibrated s0003
(coast, its design side: a tip-edge bearing; the session's 61-phase TCA
``s0003_calibrated_tca``, every 10th phase, rigid teeth, 64.5 N·m, the loaded TE's 40
cells).

Truths:

1. *TE_pre's approach = a fresh LCP*: at every phase, each preview pair whose law is
   scaled (``c != 1``) and that carries at least a twentieth of the torque closes by
   ``l theta_pre - g`` under its preview load ``W``; the half-space LCP on the pair's
   own field (:class:`~gearcontact.ltca.lte_pairs.PairFields`, solved here again with
   :func:`gearcontact.halfspace.lcp.solve_lcp`) at ``W`` gives the same approach
   within the fixed-exponent law's own error, ``|ln(delta_pre / delta_LCP)| <= |n -
   2/3| ln 4 + 0.02`` with ``n`` the LCP's exponent between ``W / 2`` and ``2 W`` (the
   bound of tests/twin/test_edge_law.py for the twin's law, the same function).
   The untruncated law (``edge_law=False``) misses the same LCP by more at the scaled
   rows (it is what the scale corrects).
2. *Torque balance*: ``sum_j W_j l_j = T`` at every phase to 1e-10.
3. *Same law as the twin*: the scale of each row is its calibration
   (:func:`~gearcontact.ltca.edge_rows.row_law`, the function the twin's mesh table
   calls) at the load it carries, ``c = law.scale_at(max(W, T / 16 / l))``
   (:func:`~gearcontact.ltca.edge_law.operating_scales`), to the fixed-point passes'
   convergence (1 %: a pass shrinks a load change's effect on ``c`` by ``|n - 2/3|``
   <= 0.15, three passes), and ``kappa_pre = c kappa_H`` exactly.

Cost: about 15 s (7 phases, their calibrations and the check's LCP solves).
"""

import numpy as np
import pytest

from gearcontact.halfspace.lcp import solve_lcp
from gearcontact.ltca.edge_law import EDGE_LOAD_FRACTIONS
from gearcontact.ltca.edge_rows import is_cut, row_law
from gearcontact.ltca.lte import loaded_te
from gearcontact.ltca.lte_pairs import PairFields, phase_contacts
from gearcontact.ltca.pair_ltca import ARCSEC_PER_RAD
from gearcontact.materials import effective_modulus_mpa

TORQUE_NM, STRIDE = 64.5, 10


@pytest.fixture(scope="module")
def coast(s0003_calibrated, s0003_calibrated_tca):
    pair, flanks = s0003_calibrated
    tca = s0003_calibrated_tca
    lte = loaded_te(tca, flanks, pair, TORQUE_NM, side="coast", stride=STRIDE)
    return pair, flanks, tca, lte


def _contacts(pair, flanks, tca, lte, k):
    """The loaded TE's resolved contacts at its phase ``k`` and their fields."""
    cycle, kin = tca.cycle, pair.kinematics()
    pinion, gear = flanks.flank("pinion", "coast"), flanks.flank("gear", "coast")
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    fields = PairFields(pinion, gear, kin, cycle, torque_nmm=1e3 * TORQUE_NM,
                        e_prime=e_prime, cells=40, extent=(1.6, 2.0))
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    kk = int(np.flatnonzero(np.isclose(cycle.phi1_rad, lte.phi1_rad[k], rtol=0, atol=1e-15))[0])
    pcs = phase_contacts(pinion, gear, kin, cycle, kk, base, e_prime, {},
                         round(0.5 * cycle.step_index))
    return fields, [fields.resolve(pc) for pc in pcs]


def _lcp_approach(fields, pc, load, materials):
    gap, grid, _, _ = fields.get(pc)
    res = solve_lcp(gap, grid, load, materials=materials, warn_coarse=False)
    assert res.converged
    return float(res.delta_mm) - pc.offset_mm


def test_te_pre_at_cut_rows_is_the_lcp(coast):
    pair, flanks, tca, lte = coast
    materials = (pair.pinion_material, pair.gear_material)
    torque = 1e3 * TORQUE_NM
    theta = lte.rotation_pre_arcsec / ARCSEC_PER_RAD
    moments = np.nansum(lte.pair_loads_pre_n * np.nan_to_num(lte.lever_mm), axis=0)
    np.testing.assert_allclose(moments, torque, rtol=1e-10)         # truth 2
    checked, hertz_worse, cache = 0, 0, {}
    for k in range(len(lte.phi1_rad)):
        fields, pcs = _contacts(pair, flanks, tca, lte, k)
        for pc in pcs:
            i = lte.pair_offsets.index(pc.offset)
            w, c = float(lte.pair_loads_pre_n[i, k]), float(lte.compliance_scale_pre[i, k])
            if w <= 0.0:
                continue
            if c != 1.0:        # truth 3: the twin's row law, kappa scaled by its c
                assert is_cut(fields, pc, torque_nmm=torque)
                law = row_law(fields, pc, materials=materials, torque_nmm=torque,
                              cache=cache)
                floor = EDGE_LOAD_FRACTIONS[0] * torque / pc.lever_mm
                assert c == pytest.approx(float(law.scale_at(max(w, floor))), rel=0.01)
            if c == 1.0 or w * pc.lever_mm < 0.05 * torque:
                continue
            d_pre = pc.lever_mm * theta[k] - pc.offset_mm
            assert d_pre == pytest.approx(c * pc.kappa_mm_per_n23 * w ** (2 / 3), rel=1e-9)
            d = [_lcp_approach(fields, pc, s * w, materials) for s in (0.5, 1.0, 2.0)]
            n = np.polyfit(np.log([0.5, 1.0, 2.0]), np.log(d), 1)[0]
            tol = abs(n - 2.0 / 3.0) * np.log(4.0) + 0.02
            assert abs(np.log(d_pre / d[1])) <= tol, (k, pc.offset, d_pre, d[1], n)
            # the untruncated Hertz law at the same load misses the LCP by more
            hertz_worse += abs(np.log(d_pre / c / d[1])) > abs(np.log(d_pre / d[1]))
            checked += 1
    assert checked >= 3 and hertz_worse == checked, (checked, hertz_worse)
    assert lte.summary()["preview_scaled_entries"] >= checked


def test_multi_tooth_preview_is_te_pre_at_p0(coast):
    """The multi-tooth step's preview (:func:`gearcontact.ltca.multitooth.multi_tooth_ltca`,
    issue 28 B) takes the edge law through the same function as ``TE_pre``
    (:func:`gearcontact.ltca.edge_rows.preview_edge_balance`): on s0003 coast, where the
    tip cuts every pair's ellipse, its rotation at P0 is the loaded TE's ``TE_pre``
    rotation there (1e-9: the same balance on the same contacts; the LTE's rows are
    calibrated in its own cache, so to the law's passes, 1e-6 relative at most), each
    scaled pair closes by ``c kappa W^(2/3)`` (1e-9), its ``c`` is its row law's at its load
    (1 %, truth 3) and its approach a fresh LCP's within the bound of truth 1; the
    untruncated law (``edge_law=False``) gives a stiffer mesh (smaller rotation)."""
    from gearcontact.ltca.multitooth import multi_tooth_ltca

    pair, flanks, tca, lte = coast
    materials = (pair.pinion_material, pair.gear_material)
    torque = 1e3 * TORQUE_NM
    mt = multi_tooth_ltca(tca, flanks, pair, TORQUE_NM, side="coast")
    flat = multi_tooth_ltca(tca, flanks, pair, TORQUE_NM, side="coast", edge_law=False)
    k = lte.reference_index
    assert mt.rotation_pre_arcsec == pytest.approx(lte.rotation_pre_arcsec[k], rel=1e-6)
    assert flat.rotation_pre_arcsec < mt.rotation_pre_arcsec
    theta = mt.rotation_pre_arcsec / ARCSEC_PER_RAD
    fields, pcs = _contacts(pair, flanks, tca, lte, k)
    by_offset = {pc.offset: pc for pc in pcs}
    checked, cache = 0, {}
    for p in mt.preview_pairs:
        if p.scale == 1.0 or p.load_n * p.lever_mm < 0.05 * torque:
            continue
        pc = by_offset[p.offset]
        d_pre = p.lever_mm * theta - p.opening_mm
        assert d_pre == pytest.approx(p.kappa_mm_per_n23 * p.load_n ** (2 / 3), rel=1e-9)
        assert p.kappa_mm_per_n23 == pytest.approx(p.scale * pc.kappa_mm_per_n23, rel=1e-12)
        law = row_law(fields, pc, materials=materials, torque_nmm=torque, cache=cache)
        floor = EDGE_LOAD_FRACTIONS[0] * torque / pc.lever_mm
        assert p.scale == pytest.approx(float(law.scale_at(max(p.load_n, floor))), rel=0.01)
        d = [_lcp_approach(fields, pc, s * p.load_n, materials) for s in (0.5, 1.0, 2.0)]
        n = np.polyfit(np.log([0.5, 1.0, 2.0]), np.log(d), 1)[0]
        assert abs(np.log(d_pre / d[1])) <= abs(n - 2.0 / 3.0) * np.log(4.0) + 0.02
        checked += 1
    assert checked >= 1
