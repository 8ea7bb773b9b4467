"""Grid convergence of the edge law's rows (ltca.patch_field, ltca.edge_law; issue 28 A).

On the calibrated s0003 coast (its design side: a tip-edge bearing; the session's
61-phase TCA ``s0003_calibrated_tca``, 64.5 N·m, the loaded TE's 40 cells), the rows
whose contact sits at a flank edge: the TCA's edge contacts (pinion tip, gear heel
corner) and the posed-field rows of the pair past its path's end nearest contact.

Truths:

1. *Grid convergence against a fresh fine LCP*: each row's calibration approach at
   ``T/16, T/4, T`` (:func:`gearcontact.ltca.edge_law.edge_compliance`, 40 cells) is
   the approach of a fresh LCP on fields of twice the cells (80 per side, fitted to the
   patch by :func:`gearcontact.ltca.patch_field.patch_approach`) within 3 %: the grid's
   share of the 4 % the twin's static approach is tested to against the LCP; measured
   at most 1.36 % over 110 approaches (session 27, the posed rows counted from their
   searched touch; 2.8 % from the fitted field's least gap, posed rows at T/16). The 40-cell field unfitted was 5-13 %
   off at the TCA's edge rows and 14-63 % at the posed rows (whose opening moved by
   1-11 um between 40 and 80 cells).
2. *Touch*: a posed row's opening (:func:`gearcontact.ltca.patch_field.touch_gap_mm`)
   is at most its field's least gap on the flank (it searches from there), and the same
   on 40 and 80 cells to 0.1 um (measured 0.04 um: the search follows the flank boundary
   downhill from different least nodes); the least gaps of the two fields differ by up
   to 8 um here.

A miter pair (tests/design_space.py MITER_PAIR, slow): truth 1 on its transmitting edge
rows; its approaching pinion-heel edge rows (open 3.5-18 um) are not converged (strict
xfail with the measured figures).
"""

import numpy as np
import pytest

from gearcontact.ltca.edge_law import edge_compliance, edge_datum_mm
from gearcontact.ltca.edge_rows import is_cut, is_edge_row
from gearcontact.ltca.lte_pairs import PairFields, phase_contacts
from gearcontact.ltca.patch_field import patch_approach, touch_gap_mm
from gearcontact.materials import effective_modulus_mpa

TORQUE_NM, COARSE, FINE = 64.5, 40, 80
#: Posed-field rows checked: those nearest contact (opening below this), mm.
POSED_OPENING_MM = 0.015


def _edge_rows(pair, flanks, tca, side, cells, *, posed: bool = True):
    """``(fields, [PairContact])``: the edge rows of the TCA's cycle (one per path index):
    every TCA edge contact and (``posed``) the posed rows open by less than
    POSED_OPENING_MM."""
    cycle, kin = tca.cycle, pair.kinematics()
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    fields = PairFields(pinion, gear, kin, cycle, torque_nmm=1e3 * TORQUE_NM,
                        e_prime=e_prime, cells=cells, extent=(1.6, 2.0))
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    out = {}
    for k in range(len(cycle.phi1_rad)):
        for pc in phase_contacts(pinion, gear, kin, cycle, k, base, e_prime, {},
                                 round(0.5 * cycle.step_index)):
            if pc.path_index in out or not is_edge_row(fields, pc):
                continue
            pc = fields.resolve(pc)
            if pc.edge and not (posed and pc.offset_mm < POSED_OPENING_MM):
                continue
            if is_cut(fields, pc, torque_nmm=1e3 * TORQUE_NM):
                out[pc.path_index] = pc
    return fields, [out[i] for i in sorted(out)]


def _check_convergence(pair, flanks, tca, side, *, posed: bool = True,
                       opening_max_mm: float = np.inf) -> list[float]:
    """Truth 1 at every edge row open by at most ``opening_max_mm``; returns the
    relative errors."""
    materials = (pair.pinion_material, pair.gear_material)
    coarse, rows = _edge_rows(pair, flanks, tca, side, COARSE, posed=posed)
    fine, fine_rows = _edge_rows(pair, flanks, tca, side, FINE, posed=posed)
    fine_rows = {pc.path_index: pc for pc in fine_rows}
    errors = []
    for pc in rows:
        if pc.offset_mm > opening_max_mm:
            continue
        law = edge_compliance(coarse, pc, materials=materials, torque_nmm=1e3 * TORQUE_NM)
        pf = fine_rows.get(pc.path_index, pc)
        for w, a in zip(law.loads_n, law.approach_lcp_mm):
            truth, _ = patch_approach(fine, pf, float(w), materials,
                                      datum_mm=edge_datum_mm(pf))
            errors.append(abs(a / truth - 1.0))
            assert abs(a / truth - 1.0) <= 0.03, (pc.path_index, w, a, truth)
    return errors


def test_tca_edge_rows_converge_in_the_cells(s0003_calibrated, s0003_calibrated_tca):
    """Truth 1 at the TCA's edge rows (tip, heel corner: 14 approaches within 0.68 % from
    their touch, session 28; 0.67 % from the grid floor; about 15 s)."""
    pair, flanks = s0003_calibrated
    errors = _check_convergence(pair, flanks, s0003_calibrated_tca, "coast", posed=False)
    print(f"s0003 TCA edge rows: {len(errors)} approaches, 40 vs 80 cells within "
          f"{100 * max(errors):.2f} %")
    assert len(errors) >= 6        # the tip and heel-corner rows at three loads, at least


@pytest.mark.slow
def test_edge_rows_converge_in_the_cells(s0003_calibrated, s0003_calibrated_tca):
    """Truth 1 at every edge row near contact (110 approaches; measured within 1.36 %;
    about 1 min)."""
    pair, flanks = s0003_calibrated
    errors = _check_convergence(pair, flanks, s0003_calibrated_tca, "coast")
    print(f"s0003 edge rows: {len(errors)} approaches, 40 vs 80 cells within "
          f"{100 * max(errors):.2f} %")
    assert len(errors) >= 30


def test_posed_opening_is_the_touch(s0003_calibrated, s0003_calibrated_tca):
    pair, flanks = s0003_calibrated
    coarse, rows = _edge_rows(pair, flanks, s0003_calibrated_tca, "coast", COARSE)
    fine, _ = _edge_rows(pair, flanks, s0003_calibrated_tca, "coast", FINE)
    posed = [pc for pc in rows if pc.edge]
    assert posed
    for pc in posed:
        gap, _, off, _ = coarse.get(pc)
        assert pc.offset_mm <= float(gap[~off].min())
        assert touch_gap_mm(fine, pc) == pytest.approx(pc.offset_mm, abs=1e-4)


def _miter(tmp_path):
    """``(pair, flanks, tca)`` of MITER_PAIR (drive, 31 phases, as the twin's tests
    prepare it)."""
    from design_space import MITER_PAIR, design_space_pair
    from gearcontact.geometry.pair import pair_to_toml
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.tca.synthesis import prepare_pair

    path = tmp_path / "pair.toml"
    path.write_text(pair_to_toml(design_space_pair(*MITER_PAIR)))
    prepared = prepare_pair(path)
    pair = prepared.pair
    tca, flanks = analyze_pair(pair, side="drive", phases=31, flanks=prepared.flank_set())
    return pair, flanks, tca


@pytest.mark.slow
def test_edge_rows_converge_on_the_miter_pair(tmp_path):
    """Truth 1 on MITER_PAIR's transmitting pinion-root edge rows (the pair carrying the
    whole torque; measured 9 approaches within 1.43 % from their touch, session 28; 0.9 %
    from the grid floor). About 2 min."""
    pair, flanks, tca = _miter(tmp_path)
    errors = _check_convergence(pair, flanks, tca, "drive", opening_max_mm=0.0)
    print(f"miter edge rows: {len(errors)} approaches, within {100 * max(errors):.2f} %")
    assert len(errors) >= 6


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="MITER_PAIR's approaching pinion-heel edge rows "
                   "(open 3.5-18 um) are not converged at 40 cells: at T/16 0.79 vs 1.02 "
                   "(80 cells) vs 1.12 um (160) (issue 28, session 16; docs/twin.md)")
def test_approaching_heel_rows_converge_on_the_miter_pair(tmp_path):
    """Truth 1 on every edge row of MITER_PAIR near contact. About 3 min."""
    pair, flanks, tca = _miter(tmp_path)
    _check_convergence(pair, flanks, tca, "drive")


@pytest.mark.parametrize("box", [(-0.31, 0.57, 0.0, 0.9), (0.2, 1.1, -0.05, 0.4),
                                 (-2.0, -0.5, -1.0, -0.2)])
def test_patch_grid_covers_the_box_with_borders_on_the_axes(box):
    """The fitted field's cells cover ``box`` with ``cells`` cells across each side
    (+1 where a border is moved out to a whole cell), uniform, and ``s = 0``, ``t = 0``
    are cell borders (1e-12 mm: rounding of the cell centres)."""
    from gearcontact.ltca.patch_field import patch_grid

    cells = 40
    s_axis, t_axis, grid = patch_grid(box, cells)
    for axis, (lo, hi) in ((s_axis, box[:2]), (t_axis, box[2:])):
        h = axis[1] - axis[0]
        assert h == pytest.approx((hi - lo) / cells, rel=1e-12)
        np.testing.assert_allclose(np.diff(axis), h, rtol=1e-9)
        assert axis[0] - h / 2 <= lo + 1e-12 and axis[-1] + h / 2 >= hi - 1e-12
        assert len(axis) in (cells, cells + 1)
        borders = axis / h - 0.5
        np.testing.assert_allclose(borders, np.round(borders), atol=1e-9)
    np.testing.assert_allclose(grid.x_mm, s_axis)
    np.testing.assert_allclose(grid.y_mm, t_axis)
