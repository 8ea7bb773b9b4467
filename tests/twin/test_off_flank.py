"""The law of mesh-table rows whose field lies wholly off the flank (:mod:`gearcontact.
ltca.off_flank`; docs/twin.md "Rows wholly off the flank: the edge law at the touch").

On s0003 coast (the twin's fixture, 31 phases, rigid) pair +1 comes within the reach at
3 phases with its field wholly off the flank; its touch is a corner of the gear's face
end and the pinion's tip on a sliver of overlapping flank.

Truths:

1. (default) those rows carry the LCP's law (scale > 1, exponent the LCP's) as
   equivalent curvatures and keep their opening and lever; the touch point the law's
   field is centred on lies on the flank region's border within a sample's rise of the
   searched touch. The LCP of every calibration load converges (phase 3's ``T/16`` on
   the refined start), and the LCP's local exponent between the two least loads is
   nearer a corner's 1/2 than 2/3 (the corner's law below the calibration).
2. (slow) the loaded TE's model -- the torque-constrained half-space LCP of every pair of
   the phase (:func:`gearcontact.ltca.mesh_lcp.solve_mesh_lcp`, rigid), pair +1 on a
   field covering the flank region near its touch at N = 80 and 160 cells per side --
   at 645 and 1290 N·m: at every phase where the LCP loads pair +1, the law's approach
   ``c(W) kappa W^(2/3)`` at the LCP's load equals the LCP's ``l theta - g`` within the
   tolerance declared in docs/twin.md before measuring (the law, as the truth, counting
   its approach from the searched touch ``g``, session 27); the law the loaded TE's preview
   ``TE_pre`` takes for the pair at those torques (its fields sized by them, where the
   pair's rows are posed-field rows: ``row_law``, a corner's continuation below the
   calibration) likewise.
"""

import numpy as np
import pytest

from gearcontact.analytic.hertz import hamrock_brewe_hertz
from gearcontact.ltca.edge_law import EDGE_LOAD_FRACTIONS
from gearcontact.ltca.edge_rows import preview_edge_balance, row_law
from gearcontact.ltca.flank_touch import flank_gaps_mm
from gearcontact.ltca.lte_pairs import PairFields, phase_contacts
from gearcontact.ltca.lte_phase import preview_balance
from gearcontact.ltca.mesh_lcp import PairBlock, solve_mesh_lcp
from gearcontact.ltca.pair_ltca import OFF_FLANK_GAP_MM
from gearcontact.ltca.patch_field import patch_grid
from gearcontact.materials import effective_modulus_mpa
from gearcontact.ltca.off_flank import TouchField, is_wholly_off, touch_law, touch_point

from .conftest import TORQUE_NM

#: Interpolation of the law between its calibration loads (as tests/ltca/test_edge_rows.py:
#: within 1.4 % of the LCP at T/8 on s0003's edge rows, 2 % allowed).
INTERPOLATION = 0.02


def _fields(pair, tca, flanks, torque_nmm: float) -> PairFields:
    """The mesh table's fields (:func:`gearcontact.twin.mesh.mesh_table`'s arguments)."""
    kin = pair.kinematics()
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    return PairFields(flanks.flank("pinion", "coast"), flanks.flank("gear", "coast"), kin,
                      tca.cycle, torque_nmm=torque_nmm, e_prime=e_prime, cells=40,
                      extent=(1.6, 2.0))


def _contacts(fields, tca, k: int) -> list:
    """The potential contacts of TCA phase ``k`` (as the table makes them), resolved."""
    cycle = tca.cycle
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    pinion, gear, kin = fields.args
    out = phase_contacts(pinion, gear, kin, cycle, k, base, fields.e_prime, {},
                         round(0.5 * cycle.step_index))
    return [fields.resolve(pc) for pc in out]


def _wholly_off_rows(mesh, tca, fields):
    """``((table row, table column, TCA phase), contact)`` of the rows the law of this
    module gives: posed-field rows whose field has no flank cell."""
    cycle = tca.cycle
    out = []
    for i, kk in zip(*np.nonzero(mesh.valid & (mesh.contact_mode == 2))):
        k = int(np.argmin(np.abs(cycle.phi1_rad - mesh.phi1_rad[kk])))
        pc = next(p for p in _contacts(fields, tca, k) if p.offset == cycle.pair_offsets[i])
        if is_wholly_off(fields, pc):
            out.append(((int(i), int(kk), k), pc))
    return out


def test_s0003_wholly_off_rows_take_the_edge_law_at_their_touch(s0003_coast_twin):
    """Truth 1 (module docstring; the rows valid before are the previous table's in every
    array: tests/twin/test_mesh_reach.py ``_against_previous``). About 2 s."""
    pair, tca, flanks, mesh = s0003_coast_twin
    mats = (pair.pinion_material, pair.gear_material)
    fields = _fields(pair, tca, flanks, 1e3 * TORQUE_NM)
    rows = _wholly_off_rows(mesh, tca, fields)
    assert len(rows) == 3               # pair +1 at 3 phases (session 24)
    for (i, kk, _), pc in rows:
        c = mesh.edge_compliance_scale[i, kk]
        # the edge contact is 6-17 times softer than the Hertz law of the nearest surface
        # contact (docs/twin.md); 1 would be that law, an exponent 0 a failed calibration
        assert c > 2.0 and 0.3 < mesh.edge_exponent[i, kk] < 1.0
        # the row keeps its opening (the searched touch) and lever, and carries the law as
        # equivalent curvatures: A-, B- times c^3 (gearcontact.ltca.edge_law)
        assert mesh.opening_mm[i, kk] == pc.offset_mm and mesh.lever_mm[i, kk] == pc.lever_mm
        np.testing.assert_allclose([mesh.A_minus_per_mm[i, kk], mesh.B_minus_per_mm[i, kk]],
                                   [c ** 3 * pc.A_minus_per_mm, c ** 3 * pc.B_minus_per_mm],
                                   rtol=1e-12)   # one product's rounding
        # the touch field's centre: a border sample, above the searched touch (the least
        # gap over the flank) by at most the border's rise between two samples
        _, _, g = touch_point(fields, pc)
        assert pc.offset_mm <= g <= pc.offset_mm + 20e-3   # um: 3.5-8.9 measured
        # every load of the calibration converged (session 25: phase 3's T/16 did not,
        # its patch on one cell of the 40-cell touch field); a corner's law below it
        law = touch_law(fields, pc, materials=mats, torque_nmm=1e3 * TORQUE_NM)
        assert law.loads_n.size == len(EDGE_LOAD_FRACTIONS)
        assert 0.5 < law.low_local_exponent < 7.0 / 12.0 and law.low_exponent == 0.5
        # the table's scale is the law's at the operating floor T/16 (pair +1 carries
        # nothing at rest at 64.5 N·m): one exp/log round trip of rounding
        assert c == pytest.approx(float(law.scale_at(law.loads_n[0])), rel=1e-12)


def _truth_block(fields, pc, cells: int) -> PairBlock:
    """Pair +1's block of the truth LCP: the flank region near its touch (the touch field's
    flank cells widened by a cell) at ``cells`` cells per side, in the row's frame."""
    tf = TouchField(fields, pc, torque_nmm=fields.torque)
    _, grid, off, lever = tf.field
    hs, ht = float(grid.dx_mm[0]), float(grid.dy_mm[0])
    box = (tf.s_mm[~off].min() - hs, tf.s_mm[~off].max() + hs,
           tf.t_mm[~off].min() - ht, tf.t_mm[~off].max() + ht)
    s_axis, t_axis, grid = patch_grid(box, cells)
    s, t = np.meshgrid(s_axis, t_axis)
    gap = flank_gaps_mm(fields, pc, s, t)
    return PairBlock(np.where(np.isfinite(gap), gap, OFF_FLANK_GAP_MM), grid, lever, 0.0)


def _truth(pair, tca, flanks, mesh, fields64, row, torque_nm, cells):
    """The coupled LCP at the row's phase: ``(theta, load of pair +1, lever, touch)`` and
    the twin's quasi-static load of pair +1 (the table's law, rigid)."""
    mats = (pair.pinion_material, pair.gear_material)
    fields = _fields(pair, tca, flanks, 1e3 * torque_nm)
    res, j, pc, blocks = coupled_column(fields, tca, mesh, row, mats,
                                        lambda pc: _truth_block(fields64, pc, cells))
    return res.rotation_rad, float(res.pair_loads_n[j]), blocks[j].lever_mm, pc


def coupled_column(fields, tca, mesh, row, materials, target_block):
    """The torque-constrained LCP (rigid) of the valid pairs of the row's table column at
    ``fields.torque``: each pair on its loaded-TE field, the row's pair on
    ``target_block(contact)``. Returns ``(result, the row's block index, its contact,
    blocks)``."""
    i, kk, k = row
    offsets = [tca.cycle.pair_offsets[j] for j in np.flatnonzero(mesh.valid[:, kk])]
    blocks, target = [], None
    for pc in _contacts(fields, tca, k):
        if pc.offset not in offsets:
            continue
        if pc.offset == tca.cycle.pair_offsets[i]:
            target = (len(blocks), pc)
            blocks.append(target_block(pc))
        else:
            blocks.append(fields.block(pc, rigid=True)[0])
    res = solve_mesh_lcp(blocks, fields.torque, materials=materials)
    assert res.converged
    return (res, *target, blocks)


#: The cases the declared tolerance does not hold (docs/twin.md, measured): none. Row
#: (4, 3) at 1290 N·m (the LCP loading pair +1 with 168 N) was -15.2 % against 13.0 %
#: (session 25: the T/16 LCP failed on the touch field), then -4.4 % against 2.2 %
#: (session 26: -2.8 % of it the law's datum, its fitted field's least gap 0.57 um above
#: the searched touch from which the truth's l theta - g counts); session 27, the law
#: counting from the searched touch (ltca.edge_law.edge_datum_mm): -1.0 % against 2.2 %.
DIFFERS: set = set()
#: The points TE_pre's law (calibrated at its own torque) does not meet the declared
#: bound (measured; docs/twin.md): point -> reason.
DIFFERS_TE_PRE: dict = {}


@pytest.fixture(scope="module")
def s0003_off_rows(s0003_coast_twin):
    pair, tca, flanks, mesh = s0003_coast_twin
    fields64 = _fields(pair, tca, flanks, 1e3 * TORQUE_NM)
    return fields64, _wholly_off_rows(mesh, tca, fields64)


@pytest.fixture(scope="module")
def coupled_lcp(s0003_coast_twin, s0003_off_rows):
    """``(index, torque) -> (load of pair +1 at 160 cells (N), at 80 cells (N), its
    approach l theta - g at 160 cells (mm), the mesh error)``: the truth, once per
    point for the twin's and TE_pre's tests (the LCP's mesh error as declared: its
    approach at 80 against 160 cells, relative)."""
    pair, tca, flanks, mesh = s0003_coast_twin
    fields64, rows = s0003_off_rows
    memo = {}

    def get(index, torque):
        if (index, torque) not in memo:
            (i, kk, _), _ = rows[index]
            out = {}
            for cells in (80, 160):
                theta, w, lever, _ = _truth(pair, tca, flanks, mesh, fields64, rows[index][0],
                                            torque, cells)
                out[cells] = (w, lever * theta - mesh.opening_mm[i, kk])
            approach = out[160][1]
            memo[index, torque] = (out[160][0], out[80][0], approach,
                                   abs(out[80][1] - approach) / abs(approach))
        return memo[index, torque]
    return get


def _law_against(law, pc, e_prime, w, approach, mesh_error, label):
    """Assert the law's approach ``c(W) kappa W^(2/3)`` at the LCP's load against the
    LCP's within the declared bound (module docstring, truth 2): below the least
    calibration load the LCP's local exponent lies between its own at the two least
    loads and the law's asymptote (docs/twin.md, session 26), + the interpolation + the
    LCP's mesh error; and nearer than the Hertzian law of the row's curvatures."""
    lo = law.loads_n[0]
    bound = (abs(law.low_local_exponent - law.low_exponent) * max(np.log(lo / w), 0.0)
             + INTERPOLATION + mesh_error)
    kap0 = hamrock_brewe_hertz(pc.A_minus_per_mm, pc.B_minus_per_mm, 1.0,
                               e_prime_mpa=e_prime).approach_mm
    got = float(law.scale_at(w)) * kap0 * w ** (2 / 3)
    hertz = kap0 * w ** (2 / 3)
    print(f"   {label} law {1e3 * got:.3f} um, Hertz {1e3 * hertz:.3f} um; loads "
          f"{law.loads_n.round(1)} N, n_lo {law.low_local_exponent:.4f}, m "
          f"{law.low_exponent}; rel {got / approach - 1:+.4f}, bound {bound:.4f} "
          f"(mesh error {mesh_error:.4f})")
    assert abs(got - approach) < abs(hertz - approach)
    assert abs(got / approach - 1.0) <= bound


@pytest.mark.slow
@pytest.mark.parametrize("torque", [645.0, 1290.0])
@pytest.mark.parametrize("index", [0, 1, 2])
def test_s0003_pair_plus_one_against_the_coupled_lcp(s0003_coast_twin, s0003_off_rows,
                                                      coupled_lcp, index, torque, request):
    """Truth 2 (module docstring), per wholly-off row and torque; where the LCP leaves
    the pair open, the twin's quasi-static balance does too. About 10 s each."""
    if (index, torque) in DIFFERS:
        request.applymarker(pytest.mark.xfail(strict=True, reason="differs (docs/twin.md)"))
    pair, tca, flanks, mesh = s0003_coast_twin
    fields64, rows = s0003_off_rows
    assert len(rows) == 3
    row, pc = rows[index]
    i, kk, k = row
    mats = (pair.pinion_material, pair.gear_material)
    law = touch_law(fields64, pc, materials=mats, torque_nmm=1e3 * TORQUE_NM)
    on = mesh.valid[:, kk]
    j = list(np.flatnonzero(on)).index(i)
    kappa = np.array([hamrock_brewe_hertz(a, b, 1.0, e_prime_mpa=mesh.e_prime_mpa)
                      .approach_mm for a, b in zip(mesh.A_minus_per_mm[on, kk],
                                                   mesh.B_minus_per_mm[on, kk])])
    w, w80, approach, mesh_error = coupled_lcp(index, torque)
    theta_twin, w_twin = preview_balance(mesh.lever_mm[on, kk], mesh.opening_mm[on, kk],
                                         kappa, 1e3 * torque)
    print(f"\nrow ({i},{kk}) {torque} N·m: LCP W {w:.1f} N (80 cells {w80:.1f}), "
          f"approach {1e3 * approach:.3f} um; twin quasi-static W {w_twin[j]:.1f} N, "
          f"rotation {theta_twin:.6e} rad, table's fixed c at the LCP's load "
          f"{1e3 * kappa[j] * max(w, 0.0) ** (2 / 3):.3f} um")
    if w <= 0.0:
        assert w_twin[j] == 0.0
        return
    _law_against(law, pc, fields64.e_prime, w, approach, mesh_error, "twin")


@pytest.mark.slow
@pytest.mark.parametrize("torque", [645.0, 1290.0])
@pytest.mark.parametrize("index", [0, 1, 2])
def test_s0003_te_pre_takes_the_law_against_the_coupled_lcp(s0003_coast_twin,
                                                             s0003_off_rows, coupled_lcp,
                                                             index, torque, request):
    """Truth 2 for the loaded TE's preview (docs/twin.md, session 26, "TE_pre"): the law
    ``TE_pre`` takes for pair +1 (:func:`gearcontact.ltca.edge_rows.row_law` on the
    loaded TE's fields at that torque, calibrated at its fractions) against the coupled
    LCP at the LCP's load, with the same bound; its balance
    (:func:`~gearcontact.ltca.edge_rows.preview_edge_balance`) gives the pair that law's
    scale at its own load. About 10 s each (the truth shared with the twin's test)."""
    if (index, torque) in DIFFERS_TE_PRE:
        request.applymarker(pytest.mark.xfail(strict=True, reason=DIFFERS_TE_PRE[
            index, torque]))
    pair, tca, flanks, _ = s0003_coast_twin
    _, rows = s0003_off_rows
    (i, _, k), _ = rows[index]
    mats = (pair.pinion_material, pair.gear_material)
    fields = _fields(pair, tca, flanks, 1e3 * torque)
    contacts = _contacts(fields, tca, k)
    jj = next(n for n, p in enumerate(contacts) if p.offset == tca.cycle.pair_offsets[i])
    pc = contacts[jj]
    law = row_law(fields, pc, materials=mats, torque_nmm=1e3 * torque, cache={})
    assert law is not None
    _, scales, _, loads = preview_edge_balance(contacts, fields, 1e3 * torque,
                                               materials=mats, cache={})
    w, _, approach, mesh_error = coupled_lcp(index, torque)
    print(f"\nrow {index} {torque} N·m: TE_pre W {loads[jj]:.1f} N, c {scales[jj]:.4f}; "
          f"LCP W {w:.1f} N, approach {1e3 * approach:.3f} um")
    if loads[jj] > 0.0:
        # the twin's operating rule (edge_law.operating_scales: at least T/16), to the
        # operating loads' last pass (OPERATING_PASSES = 3, each shrinking a load's
        # change by |n - 2/3| <= 0.17): 1 %
        floor = EDGE_LOAD_FRACTIONS[0] * 1e3 * torque / pc.lever_mm
        assert scales[jj] == pytest.approx(float(law.scale_at(max(loads[jj], floor))),
                                           rel=0.01)
    if w <= 0.0:
        return
    _law_against(law, pc, fields.e_prime, w, approach, mesh_error, "TE_pre")
