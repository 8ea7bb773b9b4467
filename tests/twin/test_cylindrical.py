"""The twin of a cylindrical pair (twin.cylindrical, table backend) against independent
truths: the mesh table's lever r_b2 cos(beta_b) (ISO 21771 base circle, the normal
through the base helix; also a pinion tip's edge row, touching the gear's involute),
the static point equal to the loaded TE's rotation at the torque (the LCP it
tabulates), and the first mesh resonance against ISO 6336-1's
resonance speed n_E1 = 30 000 / (pi z1) sqrt(c_gamma / m_red) (clause 6.5.3)."""

import math
from pathlib import Path

import numpy as np
import pytest

from gearcontact.analytic.iso6336 import resonance_speed_rpm
from gearcontact.geometry.pair import load_pair
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.report.cylindrical_lte import iso_method_b, iso_reduced_mass_kg_per_mm
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.tca.types import ARCSEC_PER_RAD
from gearcontact.twin.cylindrical import cylindrical_mesh_table, cylindrical_model
from gearcontact.twin.statics import linear_matrices, linearized_modes, static_rotation
from gearcontact.validation import InputRangeError

EV = Path(__file__).resolve().parents[2] / "examples" / "ev_reducer_helical_23x67.toml"
TORQUE_NM = 300.0       # F_t / b = 134 N/mm: inside Method B's range (>= 100 N/mm)


@pytest.fixture(scope="module")
def pair():
    return load_pair(EV, kinds=("cylindrical",))


@pytest.fixture(scope="module")
def model(pair):
    return cylindrical_model(pair, torque_nm=TORQUE_NM, phases=7, backend="table")


def test_mesh_table(pair):
    g = pair.geometry
    for facing, sign in (("cw", 1), ("ccw", -1)):
        cyc = cylindrical_mesh_cycle(pair, facing=facing, phases=7)
        mesh = cylindrical_mesh_table(pair, cyc)
        lever = 0.5 * g.base_diameter_gear_mm * math.cos(math.radians(g.base_helix_angle_deg))
        assert mesh.motion_sign == sign
        line = mesh.valid & (mesh.contact_mode == 0)
        np.testing.assert_allclose(mesh.lever_mm[line], lever, rtol=1e-15)
        # edge rows (a tip edge touching first): a pinion tip touches the gear's involute
        # helicoid, whose normal is tangent to its base cylinder: lever r_b2 cos(beta_b)
        # to the solve (1e-9); a gear tip touches the pinion's, off the plane of action
        edge = mesh.valid & (mesh.contact_mode == 1)
        assert edge.any() and set(mesh.edge_label[edge]) <= {"pinion tip", "gear tip"}
        np.testing.assert_allclose(mesh.lever_mm[edge & (mesh.edge_label == "pinion tip")],
                                   lever, rtol=1e-9)
        assert np.all(mesh.lever_mm[edge] > 0.5 * lever)
        assert np.all(mesh.lever_mm[edge] <= lever * (1 + 1e-9))
        assert mesh.reference_lever_mm == pytest.approx(lever, rel=1e-15)
        # along the motion: psi increasing over one pitch, eps = m TE0 (the gear lags)
        assert mesh.psi_rad[0] == 0.0 and mesh.psi_rad[-1] == pytest.approx(
            2 * math.pi / pair.pinion_teeth, rel=1e-12)
        assert np.all(mesh.eps_rad < 0.0)
        # the transmitting pair is closed at every phase
        assert np.all((mesh.valid & (mesh.opening_mm == 0.0)).any(axis=0))


@pytest.mark.parametrize("bending", [False, True])
def test_static_point_is_the_loaded_te(pair, model, bending):
    """The table interpolates the LCP's rotation between ladder torques; at the nominal
    torque (a ladder point) the static rotation at the first phase is the loaded TE's
    |TE - TE0| there, to the bisection (1e-15 relative) and the table's T^(2/3) read-back
    (1e-9): rigid teeth (the twin's default) and with tooth bending (``bending=True``)."""
    if bending:
        model = cylindrical_model(pair, torque_nm=TORQUE_NM, phases=7, bending=True,
                                  backend="table")
    theta, _ = static_rotation(model)
    cyc = cylindrical_mesh_cycle(pair, phases=7)
    lte = cylindrical_loaded_te(pair, TORQUE_NM, cycle=cyc, cells_along=40, bending=bending)
    want = abs(lte.te0_arcsec[0] - lte.lte_arcsec[0]) / ARCSEC_PER_RAD
    assert theta == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("backend", ["table", "reference"])
def test_first_mesh_resonance_against_iso_n_e1(pair, model, backend):
    """The chain's highest mode is the mesh mode (pinion and gear on the mesh spring):
    its speed n = 60 f / z1 against n_E1 with the twin's own transverse mesh stiffness
    c_t = k_theta / (r_b2^2 b) within 5 % (the twin adds half of each shaft to the
    members and couples them to motor and load through the shafts; the standard takes
    the gear's m* as u^2 times the pinion's geometric factor: measured -4.2 %); and
    against n_E1 with Method B's c_gamma_alpha: the ratio is sqrt(c_t / c_gamma_alpha)
    within the same 5 % (rigid teeth are stiffer than the standard's tooth with bending
    and foundation: 36 against 17.6 N/(mm·µm), ratio 1.37). The same for the fp64
    preview twin, whose line law carries the crowned lines' loaded length (c_t 37.6
    N/(mm·µm), mode at 26,109 rpm: as the table's within 4 %)."""
    if backend == "reference":
        model = cylindrical_model(pair, torque_nm=TORQUE_NM, phases=7)
    g = pair.geometry
    modes = linearized_modes(model)
    _, _, k_th = linear_matrices(model)
    n_twin = 60.0 * modes[-1] / pair.pinion_teeth
    c_t = k_th / (0.5e-3 * g.base_diameter_gear_mm) ** 2 * 1e-6 / g.face_width_mm
    m_red = iso_reduced_mass_kg_per_mm(pair)
    n_own = resonance_speed_rpm(pinion_teeth=pair.pinion_teeth, c_gamma_n_per_mm_um=c_t,
                                reduced_mass_kg_per_mm=m_red)
    assert n_twin == pytest.approx(n_own, rel=5e-2)
    iso = iso_method_b(pair)
    c_ga = iso.c_gamma_alpha_n_per_mm_um
    n_e1 = resonance_speed_rpm(pinion_teeth=pair.pinion_teeth, c_gamma_n_per_mm_um=c_ga,
                               reduced_mass_kg_per_mm=m_red)
    assert n_twin / n_e1 == pytest.approx(math.sqrt(c_t / c_ga), rel=5e-2)
    assert 1.0 < n_twin / n_e1 < math.sqrt(10.0)


def test_refused_before_work(pair):
    """An unknown backend is named; the loaded-TE table's rows are counted."""
    with pytest.raises(InputRangeError, match="backend.*cylindrical"):
        cylindrical_model(pair, torque_nm=TORQUE_NM, backend="tri_core")
    with pytest.raises(InputRangeError, match="table_cells"):
        cylindrical_model(pair, torque_nm=TORQUE_NM, bending=True, table_cells=0,
                          backend="table")


def test_preview_and_table_twins_carry_the_load(pair, model):
    """Conservation: the fp64 preview twin (the line chain as the law) and the table twin
    at 3000 rpm (mesh 1150 Hz, well below the mesh mode), 20 ms: the mean normal mesh
    force over the settled half is F_n = T2 / (r_b2 cos beta_b) (ISO 6336-1) within
    0.1 % (the mean of the dynamic part over ~11 mesh cycles; measured < 0.01 %) for
    both, and the static loads sum to F_n to the statics' bisection (1e-9); the two
    static rotations agree as :func:`test_preview_static_rotation_against_the_lcp`
    says (rigid teeth: within -6 % / 0)."""
    from gearcontact.twin.simulate import simulate

    g = pair.geometry
    f_n = 1e3 * TORQUE_NM / (0.5 * g.base_diameter_gear_mm
                             * math.cos(math.radians(g.base_helix_angle_deg)))
    preview = cylindrical_model(pair, torque_nm=TORQUE_NM, phases=7)
    assert preview.backend == "reference" and preview.curvatures == "line"
    for m in (preview, model):
        res = simulate(m, speed_rpm=3000.0, duration_s=0.02, step_s=10e-6)
        assert res.summary["mean_mesh_load_n"] == pytest.approx(f_n, rel=1e-3)
        assert res.summary["static_mesh_load_n"] == pytest.approx(f_n, rel=1e-9) or \
            m.backend == "table"        # the table holds no pair loads
    ratio = static_rotation(preview)[0] / static_rotation(model)[0]
    assert -0.06 < ratio - 1.0 < 0.0


@pytest.mark.parametrize("torque", [64.5, TORQUE_NM])
@pytest.mark.parametrize("bending", [False, True])
def test_preview_static_rotation_against_the_lcp(pair, torque, bending):
    """The crowned, tip-relieved EV lines carry their load where the ease-off along the
    line lies below the approach: the preview twin's line law (twin.line_law: the
    loaded length and interference of the line's 16 slices, the finite line's modulus,
    the line chain run on the loaded length; with bending, the shells' Gram weighted by
    the loaded slices) against the loaded TE of the same teeth at the first phase
    (ltca.cylindrical_lte, the half-space LCP of the same gap field, 40 rows along,
    rigid or with the same shells: an independent solver), at 64.5 N·m (29 N/mm) and
    300 N·m (134 N/mm).

    Rigid: bound -6 % < twin / LCP - 1 < 0 (measured -1.8 % / -2.7 %): the law is the
    energy mean of a uniform strip, 3.2-3.4 % below the LCP on a finite cylinder
    (tests/analytic/test_hertz.py) and 3.2 % below the exact Hertz ellipse of a crowned
    line (test_line_law.py), plus the LCP's grid. With bending: -3 % < twin / LCP - 1 <
    8 % (measured +4.0 % / +1.8 %): the bending load takes the contact's shape on the
    loaded slices, where the shells would spread it (the LCP's line load is flatter
    with bending): a trial shape, which by Castigliano's minimum overestimates the
    compliance, on top of the rigid margin. Before the loaded length (the uniform
    line over the whole line) the ratios were 0.54 / 0.72 rigid and 0.64 / 0.83 bent.
    7 phases as the table model: the twin's law takes the pairs on both rows of its
    interval, so a coarser cycle drops the pairs about to leave (3 phases: a half pitch)."""
    cyc = cylindrical_mesh_cycle(pair, phases=7)
    preview = cylindrical_model(pair, torque_nm=torque, phases=7, bending=bending)
    theta, loads = static_rotation(preview)
    lte = cylindrical_loaded_te(pair, torque, cycle=cyc, cells_along=40, bending=bending)
    want = abs(lte.te0_arcsec[0] - lte.lte_arcsec[0]) / ARCSEC_PER_RAD
    lo, hi = (-0.03, 0.08) if bending else (-0.06, 0.0)
    assert lo < theta / want - 1.0 < hi
    assert loads.sum() == pytest.approx(lte.normal_load_n, rel=1e-9)


@pytest.mark.slow
def test_dynamic_factor_peaks_at_the_mesh_mode(pair, model):
    """Time-domain sweep (table law, RK4 10 us) at 0.8, 0.95, 1.0, 1.05, 1.2 times the
    linearised mesh mode's speed (25,644 rpm): the dynamic factor is largest at the mode
    (the primary resonance, Kahraman & Singh 1990) and above 1.15 there (measured 1.234
    at 26,000 rpm in benchmarks/bench_twin_cylindrical_resonance.py); about 15 s."""
    from gearcontact.twin.sweep import speed_sweep

    n_mode = 60.0 * linearized_modes(model)[-1] / pair.pinion_teeth
    speeds = n_mode * np.array([0.8, 0.95, 1.0, 1.05, 1.2])
    sw = speed_sweep({"table": model}, speeds, settle_s=0.02, mesh_cycles=10, workers=1)
    k = sw.rows["table"]["dynamic_factor"]
    assert int(np.argmax(k)) == 2 and k[2] > 1.15
    assert np.all(sw.rows["table"]["contact_loss"] == 0.0)


@pytest.mark.slow
def test_preview_dynamic_factor_peaks_at_its_mesh_mode(pair):
    """The fp64 preview twin (the line chain as the law) swept at 0.8, 0.95, 1.0, 1.05,
    1.2 times its own linearised mesh mode's speed: the dynamic factor is largest at the
    mode (the primary resonance) and the pair stays in contact; about 10 s."""
    from gearcontact.twin.sweep import speed_sweep

    preview = cylindrical_model(pair, torque_nm=TORQUE_NM, phases=7)
    n_mode = 60.0 * linearized_modes(preview)[-1] / pair.pinion_teeth
    speeds = n_mode * np.array([0.8, 0.95, 1.0, 1.05, 1.2])
    sw = speed_sweep({"reference": preview}, speeds, settle_s=0.02, mesh_cycles=10,
                     workers=1)
    k = sw.rows["reference"]["dynamic_factor"]
    assert int(np.argmax(k)) == 2 and k[2] > 1.1
    assert np.all(sw.rows["reference"]["contact_loss"] == 0.0)
