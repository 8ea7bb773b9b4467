"""Loaded TE: the torque-constrained multi-pair LCP and the LTE along the mesh phase.

Independent truths:

* one pair with lever 1 and no opening is exactly the load-constrained LCP of
  :func:`gearcontact.halfspace.lcp.solve_lcp` (theta = delta, same loads), for every
  solver there (agreement to their tolerance, 1e-6 relative);
* two pairs: a nested root find on the load split built on ``solve_lcp`` (equal rotation
  of both pairs, torque balance) -- a different algorithm for the same equations;
* conservation: torque balance sum W_j l_j = T exactly (the constraint is imposed);
  symmetric pairs share equally; a pair out of reach carries nothing;
* analytic limits: Hertzian preview balance with one pair, theta = kappa (T/l)^(2/3)/l;
  the LCP contact compliance of a pure-Hertz gap equals d(delta_Hertz)/dW = (2/3)
  delta/W (exact elliptic Hertz, Johnson 1985 eq. 4.39-4.41); on s0003 at a torque low
  enough for one pair at P0 the LTE rotation is the single-pair approach / lever;
* periodicity: the last phase of a pitch is the first one with the pairs renumbered.
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcontact.analytic.hertz import exact_elliptic_hertz, hamrock_brewe_hertz
from gearcontact.halfspace.grid import TangentGrid
from gearcontact.halfspace.lcp import solve_lcp
from gearcontact.ltca.lte import ARCSEC_PER_RAD, loaded_te
from gearcontact.ltca.lte_phase import preview_balance
from gearcontact.ltca.mesh_lcp import PairBlock, solve_mesh_lcp
from gearcontact.ltca.pair_ltca import single_pair_ltca
from gearcontact.validation import InputRangeError

from hertz_problems import A_PER_MM, E_STAR_MPA

#: Relative agreement of two converged solvers of the same LCP (their tolerance 1e-8 on
#: the load change; residual_tol 1e-6).
SOLVER_RTOL = 1e-6


# ------------------------------------------------------------------ solver (analytic)
@pytest.mark.parametrize("solver", ["pk_cg", "nnls", "active_set"])
def test_single_pair_is_the_load_constrained_lcp(make_hertz, solver):
    pb = make_hertz(10, 6)  # small: the nnls reference is cubic in the cells
    ref = solve_lcp(pb.gap_mm, pb.grid, 1000.0, solver=solver, warn_coarse=False)
    res = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], 1000.0)
    assert res.converged and ref.converged
    assert res.rotation_rad == pytest.approx(ref.delta_mm, rel=SOLVER_RTOL)
    np.testing.assert_allclose(res.loads_n[0], ref.loads_n, rtol=0,
                               atol=SOLVER_RTOL * ref.loads_n.max())


def test_lever_scaling(make_hertz):
    # a lever l and torque l W is the same contact: theta = delta / l, loads unchanged
    pb = make_hertz(3, 8)
    one = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], 1000.0)
    res = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 37.0)], 37000.0)
    assert res.rotation_rad * 37.0 == pytest.approx(one.rotation_rad, rel=1e-9)
    assert res.pair_loads_n[0] == pytest.approx(1000.0, rel=1e-12)


def _nested_reference(p1, p2, l1, l2, g2, torque):
    """Load split by Brent on W1 with solve_lcp per pair: equal rotations."""
    def mismatch(w1):
        w2 = (torque - l1 * w1) / l2
        d1 = solve_lcp(p1.gap_mm, p1.grid, w1).delta_mm
        d2 = solve_lcp(p2.gap_mm, p2.grid, w2).delta_mm
        return d1 / l1 - (d2 + g2) / l2

    w1 = brentq(mismatch, 0.3 * torque / l1, 0.99 * torque / l1, xtol=1e-10)
    return w1, (torque - l1 * w1) / l2, solve_lcp(p1.gap_mm, p1.grid, w1).delta_mm / l1


def test_two_pairs_against_nested_root_find(make_hertz):
    p1, p2 = make_hertz(10, 8), make_hertz(3, 8)
    l1, l2, g2, torque = 40.0, 35.0, 0.004, 40000.0
    res = solve_mesh_lcp([PairBlock(p1.gap_mm, p1.grid, l1),
                          PairBlock(p2.gap_mm, p2.grid, l2, g2)], torque)
    w1, w2, theta = _nested_reference(p1, p2, l1, l2, g2, torque)
    assert res.converged
    np.testing.assert_allclose(res.pair_loads_n, [w1, w2], rtol=SOLVER_RTOL)
    assert res.rotation_rad == pytest.approx(theta, rel=SOLVER_RTOL)
    # torque balance is imposed: exact to round-off
    assert res.pair_loads_n @ [l1, l2] == pytest.approx(torque, rel=1e-12)
    assert res.torque_residual < 1e-12 and res.complementarity_residual < 1e-6
    np.testing.assert_allclose(res.approach_mm, [l1 * theta, l2 * theta - g2],
                               rtol=SOLVER_RTOL)


def test_symmetric_pairs_share_equally_and_far_pair_is_idle(make_hertz):
    pb = make_hertz(10, 8)
    sym = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 30.0)] * 2, 60000.0)
    assert sym.pair_loads_n[0] == pytest.approx(sym.pair_loads_n[1], rel=1e-8)
    one = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 30.0)], 60000.0)
    # opening 1 mm: never reached by an approach of tens of micrometres
    far = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 30.0),
                          PairBlock(pb.gap_mm, pb.grid, 30.0, 1.0)], 60000.0)
    assert far.pair_loads_n[1] == 0.0
    assert far.rotation_rad == pytest.approx(one.rotation_rad, rel=SOLVER_RTOL)


def test_hertz_contact_compliance(make_hertz):
    # c = d delta / dW of a pure-Hertz gap = (2/3) delta_Hertz / W; central difference
    # +-5 % (truncation 2e-4) on 16 cells per semi-axis (approach within 0.5 %, the
    # solver tests' bound): 1 % tolerance
    pb = make_hertz(10, 16)
    w, eps = 1000.0, 0.05
    th = [solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], w * (1 + s * eps)
                         ).rotation_rad for s in (1, -1)]
    c = (th[0] - th[1]) / (2 * eps * w)
    hz = exact_elliptic_hertz(A_PER_MM, 10 * A_PER_MM, w, e_prime_mpa=2 * E_STAR_MPA)
    assert c == pytest.approx(2.0 / 3.0 * hz.approach_mm / w, rel=0.01)


def test_bad_input(make_hertz):
    pb = make_hertz(3, 8)
    with pytest.raises(InputRangeError, match="blocks"):
        solve_mesh_lcp([], 1.0)
    with pytest.raises(InputRangeError, match="torque_nmm"):
        solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], 0.0)
    with pytest.raises(InputRangeError, match="offset_mm"):
        PairBlock(pb.gap_mm, pb.grid, 1.0, -1e-3)
    with pytest.raises(InputRangeError, match="lever_mm"):
        PairBlock(pb.gap_mm, pb.grid, 0.0)
    bad = pb.gap_mm.copy()
    bad[0, 0] = np.nan
    with pytest.raises(InputRangeError, match="gap_mm"):
        PairBlock(bad, pb.grid, 1.0)
    nonuni = TangentGrid.from_edges(np.r_[0.0, 1.0, 3.0], np.r_[0.0, 1.0])
    with pytest.raises(InputRangeError, match="uniform"):
        PairBlock(np.zeros((1, 2)), nonuni, 1.0)


def test_non_convergence_is_reported(make_hertz):
    pb = make_hertz(10, 8)
    res = solve_mesh_lcp([PairBlock(pb.gap_mm, pb.grid, 1.0)], 1000.0, max_iter=2)
    assert not res.converged and res.status == "max_iter" and "stopped" in res.message


def _two_pairs(make_hertz):
    """Two Hertzian pairs on levers 40 and 35 mm, the second open by 4 um: it closes
    at 40 N·m."""
    p1, p2 = make_hertz(10, 8), make_hertz(3, 8)
    return [PairBlock(p1.gap_mm, p1.grid, 40.0), PairBlock(p2.gap_mm, p2.grid, 35.0, 4e-3)]


def test_incremental_displacement_matches_recomputed(make_hertz, monkeypatch):
    # The constrained CG updates C x from the step's C t and adds clipped / re-admitted
    # cells one by one from the real-space kernels; recomputing C x at every step
    # (_REFRESH = 1) follows the same iterates up to round-off: same iteration count,
    # loads within 1e-9 of the largest (the solver tolerance is 1e-8 T), and both final
    # residuals (computed from an exact C x) below the solver's residual_tol.
    from gearcontact.halfspace import constrained_cg

    blocks = _two_pairs(make_hertz)
    fast = solve_mesh_lcp(blocks, 40000.0)
    monkeypatch.setattr(constrained_cg, "_REFRESH", 1)
    exact = solve_mesh_lcp(blocks, 40000.0)
    assert fast.converged and exact.converged
    assert fast.iterations == exact.iterations
    wmax = max(float(w.max()) for w in exact.loads_n)
    for a, b in zip(fast.loads_n, exact.loads_n):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * wmax)
    assert fast.rotation_rad == pytest.approx(exact.rotation_rad, rel=1e-9)
    assert fast.complementarity_residual < 1e-6 and fast.torque_residual < 1e-12


@pytest.mark.parametrize("checks, probe", [(3, 1e-2), (0, 1e-2), (3, 0.0)])
def test_pair_closing_outside_the_windows(make_hertz, monkeypatch, checks, probe):
    # The constrained CG works on windows around the loaded cells; a pair that starts
    # without load (warm start from the first pair alone) is found by the whole-field
    # probe once the change falls below _PROBE (probe = 0: only by the check at
    # convergence) and joins (its window widened, or with _CHECKS = 0 the whole
    # fields): same solution as a cold start, to the solver tolerance.
    from gearcontact.halfspace import constrained_cg

    monkeypatch.setattr(constrained_cg, "_CHECKS", checks)
    monkeypatch.setattr(constrained_cg, "_PROBE", probe)
    blocks = _two_pairs(make_hertz)
    alone = solve_mesh_lcp(blocks[:1], 40000.0)
    warm = solve_mesh_lcp(blocks, 40000.0, warm_start=[alone.pressures_mpa(blocks)[0], None])
    cold = solve_mesh_lcp(blocks, 40000.0)
    assert warm.converged and cold.converged and warm.pair_loads_n[1] > 0.1 * 1000.0
    np.testing.assert_allclose(warm.pair_loads_n, cold.pair_loads_n, rtol=SOLVER_RTOL)
    assert warm.rotation_rad == pytest.approx(cold.rotation_rad, rel=SOLVER_RTOL)


def test_probe_widens_the_windows_before_converging(make_hertz, monkeypatch):
    # Cold start of two pairs where the second one's cells close only once the first
    # one's load has spread: the probe at a change of _PROBE finds them and the windows
    # widen at once, instead of converging on the first window to the tolerance and
    # then again on the widened one. Same solution (solver tolerance), fewer steps
    # (27 against 35 when this was written).
    from gearcontact.halfspace import constrained_cg

    blocks = _two_pairs(make_hertz)
    probed = solve_mesh_lcp(blocks, 40000.0)
    monkeypatch.setattr(constrained_cg, "_PROBE", 0.0)
    late = solve_mesh_lcp(blocks, 40000.0)
    assert probed.converged and late.converged
    assert probed.iterations < late.iterations
    np.testing.assert_allclose(probed.pair_loads_n, late.pair_loads_n, rtol=SOLVER_RTOL)
    assert probed.rotation_rad == pytest.approx(late.rotation_rad, rel=SOLVER_RTOL)


def test_fields_of_other_shapes_are_padded_exactly(make_hertz):
    # Blocks of different field shapes share one batched operator on the largest shape;
    # the padding carries no load, so the result is the one of the same pairs on
    # fields that all have the largest shape (the small field embedded in a larger
    # one, extra cells far open): agreement to the solver tolerance (1e-6 relative).
    p1, p2 = make_hertz(10, 8), make_hertz(3, 6)  # 23 x 23 and 17 x 17 cells
    assert p1.grid.shape != p2.grid.shape
    big = np.full(p1.grid.shape, 1.0)  # 1 mm: never closed
    big[:p2.grid.ny, :p2.grid.nx] = p2.gap_mm
    grid2 = TangentGrid.uniform(p1.grid.nx, p1.grid.ny, dx_mm=float(p2.grid.dx_mm[0]),
                                dy_mm=float(p2.grid.dy_mm[0]))
    mixed = solve_mesh_lcp([PairBlock(p1.gap_mm, p1.grid, 40.0),
                            PairBlock(p2.gap_mm, p2.grid, 35.0, 2e-3)], 40000.0)
    same = solve_mesh_lcp([PairBlock(p1.gap_mm, p1.grid, 40.0),
                           PairBlock(big, grid2, 35.0, 2e-3)], 40000.0)
    assert mixed.converged and same.converged
    assert mixed.loads_n[1].shape == p2.grid.shape
    np.testing.assert_allclose(mixed.pair_loads_n, same.pair_loads_n, rtol=SOLVER_RTOL)
    assert mixed.rotation_rad == pytest.approx(same.rotation_rad, rel=SOLVER_RTOL)
    np.testing.assert_allclose(mixed.loads_n[1], same.loads_n[1][:17, :17], rtol=0,
                               atol=SOLVER_RTOL * same.loads_n[1].max())


# ---------------------------------------------------------------- preview balance
def test_preview_balance_limits():
    # one pair: theta = kappa (T/l)^(2/3) / l exactly
    th, w = preview_balance([36.0], [0.0], [2e-4], 64500.0)
    assert th == pytest.approx(2e-4 * (64500.0 / 36.0) ** (2 / 3) / 36.0, rel=1e-12)
    assert w[0] == pytest.approx(64500.0 / 36.0, rel=1e-12)
    lv, g, kap = np.array([36.0, 38.0, 34.0]), np.array([0.0, 2e-3, 1.0]), np.full(3, 2e-4)
    th, w = preview_balance(lv, g, kap, 64500.0)
    assert w @ lv == pytest.approx(64500.0, rel=1e-12)   # torque balance
    assert w[2] == 0.0                                    # out of reach
    # both loaded pairs at the same rotation: delta_j = kappa W_j^(2/3) = l_j theta - g_j
    np.testing.assert_allclose(kap[:2] * w[:2] ** (2 / 3), lv[:2] * th - g[:2], rtol=1e-10)


# ------------------------------------------------------------------------- s0003
#: 11 phases per pitch: the TCA continuation keeps the neighbouring pairs' paths (at 7
#: or 9 it loses path ends of s0003 and the pairs drop out early)
PHASES = 11
CELLS = 24


@pytest.fixture(scope="module")
def s0003_pair(centred_drive_11):
    """s0003-centred: the session's set-up (tests/ltca/conftest.py), not a second build."""
    return centred_drive_11[0]


@pytest.fixture(scope="module")
def s0003_flanks(centred_drive_11):
    return centred_drive_11[1]


@pytest.fixture(scope="module")
def s0003_tca(centred_drive_11):
    """Drive side at PHASES = 11 phases per pitch: the session's ``centred_drive_11``."""
    assert PHASES == 11
    return centred_drive_11[2]


@pytest.fixture(scope="module")
def lte(s0003_tca, s0003_flanks, s0003_pair):
    return loaded_te(s0003_tca, s0003_flanks, s0003_pair, 64.5, cells=CELLS)


def test_s0003_torque_balance_and_status(lte):
    assert lte.converged
    torque = 64.5e3
    for loads in (lte.pair_loads_lcp_n, lte.pair_loads_pre_n):
        moments = np.nansum(loads * np.nan_to_num(lte.lever_mm), axis=0)
        np.testing.assert_allclose(moments, torque, rtol=1e-10)
    assert lte.active_lcp.min() >= 1 and lte.active_pre.min() >= 1


def test_s0003_sign_and_periodicity(lte, s0003_tca):
    # s0003 drive: envelope = min over the pairs -> loaded TE = TE0 + theta
    assert not s0003_tca.cycle.envelope_is_max and lte.te_sign == 1
    np.testing.assert_allclose(lte.te_lcp_arcsec - lte.te0_arcsec, lte.rotation_lcp_arcsec,
                               rtol=1e-12)
    assert (lte.rotation_lcp_arcsec > 0).all()
    # the last phase is the first with pair j -> j - 1: same state (fields shared), so
    # the same TE up to the solver tolerance (1e-8 on the loads -> ~1e-6 arcsec)
    assert lte.te_lcp_arcsec[-1] == pytest.approx(lte.te_lcp_arcsec[0], abs=1e-4)
    np.testing.assert_allclose(lte.pair_loads_lcp_n[:-1, -1], lte.pair_loads_lcp_n[1:, 0],
                               rtol=1e-5, atol=1e-6)
    assert lte.te_pre_arcsec[-1] == pytest.approx(lte.te_pre_arcsec[0], abs=1e-9)
    # pairs beyond their path ends are kept as edge contacts and unload within the
    # window: nothing is dropped
    assert (lte.dropped_load_n == 0.0).all()


def test_s0003_without_edge_pairs_drops_load(lte, s0003_tca, s0003_flanks, s0003_pair):
    # edge_reach = 0: a pair whose mating point leaves the flanks takes its last load
    # with it, in the same way at both ends of the pitch (phases 0, 5, 10)
    bare = loaded_te(s0003_tca, s0003_flanks, s0003_pair, 64.5, cells=CELLS, stride=5,
                     edge_reach=0.0)
    lost = ~np.isfinite(s0003_tca.cycle.te0_pairs_arcsec[:, -1])
    assert bare.dropped_load_n[-1] > 0.0
    assert bare.dropped_load_n[-1] == pytest.approx(bare.pair_loads_lcp_n[lost, -2].sum())
    assert bare.dropped_load_n[0] == pytest.approx(bare.dropped_load_n[-1], rel=1e-5)
    # the edge pair is an extra contact at the pitch end: the mesh is stiffer with it
    assert lte.rotation_lcp_arcsec[-1] < bare.rotation_lcp_arcsec[-1]
    np.testing.assert_allclose(bare.rotation_lcp_arcsec[1], lte.rotation_lcp_arcsec[5],
                               rtol=SOLVER_RTOL)  # P0: no edge pair in reach


def test_s0003_lcp_close_to_preview_and_continuous(lte):
    # away from the pitch ends (no edge pair loaded) the real gap near each mating point
    # is nearly quadratic: the LCP rotation stays within 5 % of the Hertzian one
    # (measured ~2 %; coarse 24-cell fields, edge trimming)
    same = (lte.active_lcp == lte.active_pre) & (lte.active_lcp == 3)
    assert same.sum() >= 5
    # at the ends the edge pairs are truncated by the flank boundary for the LCP but not
    # for the preview: the LCP mesh is softer there, but not by more than 15 %
    np.testing.assert_array_less(lte.rotation_pre_arcsec, 1.15 * lte.rotation_lcp_arcsec)
    np.testing.assert_allclose(lte.rotation_lcp_arcsec[same], lte.rotation_pre_arcsec[same],
                               rtol=0.05)
    # continuity along the phase: between neighbouring phases the rotation moves by far
    # less than itself (a jump would show a pair switching in or out discontinuously)
    assert np.abs(np.diff(lte.rotation_lcp_arcsec)).max() < 0.05 * lte.rotation_lcp_arcsec.min()
    assert lte.te0_pp_arcsec == pytest.approx(np.ptp(lte.te0_arcsec))


def test_s0003_preview_compliance_is_hertzian(lte, s0003_tca, s0003_pair):
    # transmitting pair alone at P0: c_pre = (2/3) c kappa W^(-1/3) (Hamrock-Brewe
    # scaled by the edge law's c of that row), central difference +-5 %: truncation
    # 0.074 eps^2 = 1.9e-4 -> tolerance 3e-4
    from gearcontact.materials import effective_modulus_mpa
    rc = s0003_tca.mean_curvature
    w = 64.5e3 / lte.reference_lever_mm
    hb = hamrock_brewe_hertz(rc.A_minus_per_mm, rc.B_minus_per_mm, w,
                             e_prime_mpa=effective_modulus_mpa(s0003_pair.pinion_material,
                                                               s0003_pair.gear_material))
    c = lte.compliance_scale_pre[lte.pair_offsets.index(0), lte.reference_index]
    # the centred bearing's ellipse at P0 grazes a flank boundary on the coarse field:
    # its trimmed LCP is softer by less than 1 % (measured 0.07 %)
    assert 1.0 <= c < 1.01
    assert lte.compliance_pre_mm_per_n == pytest.approx(2 / 3 * c * hb.approach_mm / w,
                                                        rel=3e-4)
    # near-Hertzian real gap: LCP within 5 % of the preview (measured ~1.5 %)
    assert lte.compliance_lcp_mm_per_n == pytest.approx(lte.compliance_pre_mm_per_n, rel=0.05)
    # sharing with the neighbours stiffens the mesh
    assert lte.mesh_compliance_lcp_mm_per_n < lte.compliance_lcp_mm_per_n


def test_s0003_single_pair_limit(s0003_tca, s0003_flanks, s0003_pair):
    # at 0.5 N·m the neighbours of P0 stay open (approach ~3 arcsec vs an opening of
    # ~13 arcsec), so the LTE rotation at P0 is the single-pair approach / lever on the
    # same field: equal to solver tolerance
    low = loaded_te(s0003_tca, s0003_flanks, s0003_pair, 0.5, cells=CELLS)
    k = low.reference_index
    assert low.active_lcp[k] == 1
    single = single_pair_ltca(s0003_tca, s0003_flanks, s0003_pair, 0.5, cells=CELLS)
    assert low.rotation_lcp_arcsec[k] == pytest.approx(single.mesh_rotation_arcsec,
                                                       rel=SOLVER_RTOL)
    assert low.rotation_pre_arcsec[k] == pytest.approx(single.preview_mesh_rotation_arcsec,
                                                       rel=1e-9)
    assert single.lever_mm == pytest.approx(low.reference_lever_mm, rel=1e-12)
    assert ARCSEC_PER_RAD == pytest.approx(180 * 3600 / np.pi)


def test_s0003_stride_selects_phases(lte, s0003_tca, s0003_flanks, s0003_pair):
    # every other phase (plus P0): the same states as the full run, to solver tolerance
    # (only the warm starts differ)
    sub = loaded_te(s0003_tca, s0003_flanks, s0003_pair, 64.5, cells=CELLS, stride=2)
    sel = np.array(sorted(set(range(0, PHASES, 2)) | {lte.reference_index}))
    np.testing.assert_array_equal(sub.phi1_rad, lte.phi1_rad[sel])
    np.testing.assert_allclose(sub.rotation_lcp_arcsec, lte.rotation_lcp_arcsec[sel],
                               rtol=SOLVER_RTOL)
    np.testing.assert_allclose(sub.rotation_pre_arcsec, lte.rotation_pre_arcsec[sel],
                               rtol=1e-12)
    assert sub.compliance_lcp_mm_per_n == pytest.approx(lte.compliance_lcp_mm_per_n,
                                                        rel=1e-4)


def test_s0003_bad_input(s0003_tca, s0003_flanks, s0003_pair):
    for kw, match in (({"torque_nm": 0.0}, "torque_nm"), ({"cells": 8}, "cells"),
                      ({"extent_factor": (1.0, 2.0)}, "extent_factor"),
                      ({"compliance_step": 0.0}, "compliance_step"),
                      ({"stride": 0}, "stride"), ({"edge_reach": -0.1}, "edge_reach")):
        args = {"torque_nm": 64.5, **kw}
        with pytest.raises(InputRangeError, match=match):
            loaded_te(s0003_tca, s0003_flanks, s0003_pair, args.pop("torque_nm"), **args)


def test_s0003_posed_field_contains_the_opening(s0003_tca, s0003_flanks, s0003_pair):
    # each pair's field is taken with the gear resting on the transmitting pair: its
    # minimum over the flank is the TCA opening g_j = |TE0_j - TE0_env| l_j, up to the
    # cell-centred sampling of the minimum (at most A-(dt/2)^2 + B-(ds/2)^2 of the local
    # quadric) plus 10 nm for the rotation's non-uniform closing across the field
    from gearcontact.ltca.lte_pairs import PairFields, phase_contacts
    from gearcontact.materials import effective_modulus_mpa
    cyc = s0003_tca.cycle
    kin = s0003_pair.kinematics()
    pin, gear = s0003_flanks.flank("pinion", "drive"), s0003_flanks.flank("gear", "drive")
    e_prime = effective_modulus_mpa(s0003_pair.pinion_material, s0003_pair.gear_material)
    base = int(np.argmin(np.abs(cyc.path.phi1_rad - cyc.phi1_rad[0])))
    fields = PairFields(pin, gear, kin, cyc, torque_nmm=64.5e3, e_prime=e_prime, cells=CELLS,
                        extent=(1.6, 2.0))
    pcs = phase_contacts(pin, gear, kin, cyc, cyc.mean_index, base, e_prime, {}, 0)
    assert len(pcs) == 3
    for pc in pcs:
        gap, grid, off, lever = fields.get(pc)
        assert lever == pytest.approx(pc.lever_mm, rel=1e-12)
        bound = (pc.A_minus_per_mm * (grid.dy_mm[0] / 2) ** 2
                 + pc.B_minus_per_mm * (grid.dx_mm[0] / 2) ** 2 + 1e-5)
        assert gap[~off].min() == pytest.approx(pc.offset_mm, abs=bound)


def test_s0003_coast_side_max_envelope(s0003_pair, s0003_flanks):
    # coast side: the pinion pushes the gear towards +phi2, TE0 is the max over the
    # pairs and the loaded gear lags towards -phi2: TE = TE0 - theta, theta > 0
    from gearcontact.tca.analysis import analyze_pair
    tca = analyze_pair(s0003_pair, side="coast", phases=PHASES, flanks=s0003_flanks)[0]
    assert tca.cycle.envelope_is_max
    res = loaded_te(tca, s0003_flanks, s0003_pair, 64.5, side="coast", cells=CELLS,
                    stride=2)
    assert res.converged and res.te_sign == -1
    assert (res.rotation_lcp_arcsec > 0).all() and (res.rotation_pre_arcsec > 0).all()
    np.testing.assert_allclose(res.te0_arcsec - res.te_lcp_arcsec, res.rotation_lcp_arcsec,
                               rtol=1e-12)
    moments = np.nansum(res.pair_loads_lcp_n * np.nan_to_num(res.lever_mm), axis=0)
    np.testing.assert_allclose(moments, 64.5e3, rtol=1e-10)


# ------------------------------------------------------------------ mesh stiffness
def test_s0003_mesh_stiffness(s0003_tca, s0003_flanks, s0003_pair):
    """Mesh stiffness along the phase (``stiffness=True``), rigid and with bending.

    Truths: (1) the stiffness equals d(torque)/d(rotation) of two *separate* runs at
    T (1 +- 5 %) (their public rotations, cold-started), within 3 % (measured 1.4 %:
    each run sizes its fields by its own Hertzian semi-axes, ~ T^(1/3), so the two
    rotations come from grids 3 % apart whose discretization errors, ~0.5 % of theta
    at 24 cells, do not cancel in a difference of 10 % of theta; the run itself
    differences on one grid); (2) at P0 the stiffness along the normal is the inverse
    of the mesh compliance (same step, same fields; warm vs cold start: solver
    tolerance 1e-8, allowed 1e-6);
    (3) zero-compliance limit: bending scale 0 gives the rigid stiffness (1e-9);
    (4) bending makes the mesh softer at every phase."""
    from gearcontact.ltca.tooth_bending import tooth_bending

    kw = dict(side="drive", cells=24, stride=5)
    pair, flanks, tca = s0003_pair, s0003_flanks, s0003_tca
    bend = tooth_bending(flanks, pair, side="drive")
    res = loaded_te(tca, flanks, pair, 64.5, bending=bend, stiffness=True, **kw)
    assert res.converged
    kr, kb = res.stiffness_rigid_nm_per_rad, res.stiffness_bending_nm_per_rad
    for model, k in ((None, kr), (bend, kb)):
        for h, rtol in ((0.05, 3e-2),):
            hi, lo = (loaded_te(tca, flanks, pair, 64.5 * (1 + f), bending=model, **kw)
                      for f in (h, -h))
            fd = 2 * h * 64.5 / ((hi.rotation_lcp_arcsec - lo.rotation_lcp_arcsec)
                                 / ARCSEC_PER_RAD)
            np.testing.assert_allclose(k, fd, rtol=rtol)
    k0 = res.reference_index
    assert res.mesh_stiffness_n_per_mm(kb[k0]) == pytest.approx(
        1.0 / res.mesh_compliance_lcp_mm_per_n, rel=1e-6)
    assert (kb < kr).all()
    zero = loaded_te(tca, flanks, pair, 64.5, bending=tooth_bending(flanks, pair, side="drive",
                                                                   scale=0.0),
                     stiffness=True, **kw)
    np.testing.assert_allclose(zero.stiffness_bending_nm_per_rad, kr, rtol=1e-9)
    s = res.summary()
    assert s["reference_mesh_stiffness_bending_n_per_mm"] == pytest.approx(
        1e3 * kb[k0] / res.reference_lever_mm ** 2, rel=1e-12)
    header, rows = res.table()
    col = header.index("mesh_stiffness_rigid_nm_per_rad")
    assert [r[col] for r in rows] == list(kr)


def test_calibrated_s0003_needs_three_pairs_and_is_then_periodic(s0003_calibrated):
    """The calibrated preset (coast, tip-edge bearing) loads pairs -3..0 over the pitch
    of its reference window. With the window -2..2 pair -2 carries load at the first
    phase, so pair -3 would at the last: a named error, not a wrong TE (before the check
    the TE_LCP came out -60.5 arcsec at the first phase and -61.4 at the last). With
    the default window -3..3 the last phase repeats the first: TE_LCP equal to the
    solver tolerance (1e-4 arcsec, as the centred test) and the loads shifted by one
    pair (1e-5 relative)."""
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.validation import UnusableInput

    pair, flanks = s0003_calibrated
    narrow, _ = analyze_pair(pair, phases=PHASES, flanks=flanks, pairs=2)
    with pytest.raises(UnusableInput, match=r"pair window -2\.\.2 .* pairs >= 3"):
        loaded_te(narrow, flanks, pair, 64.5, cells=CELLS)
    tca, _ = analyze_pair(pair, phases=PHASES, flanks=flanks)
    assert tca.cycle.pair_offsets == (-3, -2, -1, 0, 1, 2, 3)
    res = loaded_te(tca, flanks, pair, 64.5, cells=CELLS)
    assert res.te_lcp_arcsec[-1] == pytest.approx(res.te_lcp_arcsec[0], abs=1e-4)
    np.testing.assert_allclose(res.pair_loads_lcp_n[:-1, -1], res.pair_loads_lcp_n[1:, 0],
                               rtol=1e-5, atol=1e-6)
    assert res.pair_loads_lcp_n[0, 0] == 0.0 and res.pair_loads_lcp_n[0, -1] > 0.0
