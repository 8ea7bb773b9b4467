"""The drivetrain twin against independent truth.

* quasi-static limit: at 60 rpm (mesh 7 Hz, 25x below the lowest elastic mode) the
  dynamic TE equals the static loaded TE ``TE_pre`` of :func:`gearcontact.ltca.lte.
  loaded_te` (same Hertzian pairs, solved there by Brent on the torque balance), and the
  mean mesh torque over whole pitches equals the load torque;
* energy: kinetic + shaft + mesh potential + dissipated = work of the end torques
  (conservation law; without damping the dissipated term is 0);
* linear small vibration: the spectral peaks of a free vibration equal the eigenvalues
  of the linearised chain built here from the drivetrain parameters and the Hertzian
  mesh stiffness (numpy.linalg.eig, independent of the library's matrices);
* contact loss: between the flanks the mesh torque is exactly 0, never NaN;
* golden fixed point vs fp64 within the golden model's documented error;
* bad input -> InputRangeError naming the field.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from gearcontact.ltca.lte import loaded_te
from gearcontact.ltca.lte_phase import preview_balance
from gearcontact.analytic.hertz import hamrock_brewe_hertz
from gearcontact.twin.mesh import mesh_table
from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import (build_model, linearized_modes, simulate,
                                       static_rotation)
from gearcontact.validation import InputRangeError

from .conftest import (TORQUE_NM, energy_residual, frozen_mesh, quasi_static_bound_arcsec,
                       quasi_static_run)

#: Cells of the edge pairs' posed fields in the quasi-static comparison (the opening of
#: an edge pair is the minimum of that field, so both sides must use the same grid).
CELLS = 16


@pytest.fixture(scope="module")
def model(s0003_twin):
    pair, _, _, mesh = s0003_twin
    return build_model(mesh, default_drivetrain(pair), TORQUE_NM)


def _undamped(pair):
    return replace(default_drivetrain(pair), input_damping_ratio=0.0,
                   output_damping_ratio=0.0, mesh_damping_ratio=0.0)


def test_quasi_static_limit_is_the_loaded_te(s0003_twin):
    pair, tca, flanks, _ = s0003_twin
    mesh = mesh_table(tca, flanks, pair, torque_nm=TORQUE_NM, cells=CELLS,
                      edge_law=False)
    # the untruncated law on both sides (loaded_te's default takes the edge law, as the
    # twin's default mesh does: tests/ltca/test_edge_rows.py, tests/twin/test_edge_law.py)
    lte = loaded_te(tca, flanks, pair, TORQUE_NM, cells=CELLS, edge_law=False)
    res, ref, second, rows, _ = quasi_static_run(pair, mesh, lte)
    c = res.columns
    err = np.abs(c["te_arcsec"] - ref)
    # At the TCA rows both solve the same balance up to the twin's torque departure u
    # eps' (conftest.quasi_static_bound_arcsec, ~0.02 arcsec). Between rows the twin
    # interpolates the geometry, the reference the TE: <= 0.09 arcsec at the kinks
    # where an edge pair enters (TE p-p 2.0 arcsec; measured 0.084 since the entering
    # posed pair's opening is the touch of its flanks, ltca.patch_field; 0.08 before).
    bound = quasi_static_bound_arcsec(mesh, lte.rotation_pre_arcsec.mean())
    assert err[second & rows].max() < bound
    assert err[second].max() < 0.09
    assert np.ptp(ref[second]) == pytest.approx(lte.te_pre_pp_arcsec, rel=0.02)
    # mean over one whole pitch: the mesh carries the load torque (1e-4: u eps' averages
    # to 0 over a pitch; the residual is the sampling of the last step)
    assert res.summary["mean_mesh_torque_nm"] == pytest.approx(TORQUE_NM, rel=1e-4)
    assert not np.any(c["mesh_torque_nm"][second] == 0.0)


def test_energy_balance_without_damping(s0003_twin):
    pair, _, _, mesh = s0003_twin
    m = build_model(frozen_mesh(mesh), _undamped(pair), TORQUE_NM)
    kick = np.array([0.0, 0.5, 0.0, 0.0])        # rad/s on the pinion
    vib = 0.5 * m.drivetrain.pinion_inertia_kgm2 * 0.5 ** 2   # energy put in, J
    err = {}
    for h in (4e-6, 2e-6):
        c = simulate(m, speed_rpm=0.0, duration_s=0.02, step_s=h,
                     initial_velocity=kick).columns
        assert np.all(c["dissipated_j"] == 0.0)
        err[h] = np.abs(energy_residual(c)).max()
    # RK4 is 4th order: halving h divides the energy error by >= 2^4 (measured 2^5: the
    # energy error of an oscillator is one order higher); at 2 us (h omega_max = 0.09)
    # it is 6e-5 of the kick energy (the preload, 5e4 times the kick energy, takes part
    # in the error through the cross term k x0 x of the shaft energies): bound 2e-4
    assert err[4e-6] / err[2e-6] > 16.0
    assert err[2e-6] < 2e-4 * vib


def test_energy_balance_with_damping_at_speed(s0003_twin):
    pair, _, _, mesh = s0003_twin
    m = build_model(frozen_mesh(mesh), default_drivetrain(pair), TORQUE_NM)
    res = simulate(m, speed_rpm=3000.0, duration_s=0.01, step_s=5e-6,
                   initial_velocity=[0.0, 2.0, 0.0, 0.0])
    c = res.columns
    # input work = stored + dissipated (dampers and the no-pull clamp of the mesh);
    # measured 4e-10 J against 1.9e-5 J dissipated: bound 1e-4 of it
    assert c["dissipated_j"][-1] > 0.0
    assert np.abs(energy_residual(c)).max() < 1e-4 * c["dissipated_j"][-1]


def test_real_mesh_exchanges_bounded_energy_with_the_rotation(model):
    # the real mesh's potential depends on the phase explicitly (levers, openings,
    # curvatures): the balance then closes up to that exchange, which is periodic in the
    # pitch and bounded by the potential's own variation (no drift)
    dt = replace(model.drivetrain, input_damping_ratio=0.0, output_damping_ratio=0.0,
                 mesh_damping_ratio=0.0)
    m = build_model(model.mesh, dt, TORQUE_NM)
    c = simulate(m, speed_rpm=3000.0, duration_s=0.02, step_s=4e-6).columns
    r = energy_residual(c)
    assert np.abs(r).max() < 1.5 * np.ptp(c["mesh_energy_j"])
    pitch_steps = int(round(2 * math.pi / 7 / (3000 * 2 * math.pi / 60) / 4e-6))
    # one pitch later the residual returns to within 10 % of that bound
    assert abs(r[-1] - r[-1 - pitch_steps]) < 0.15 * np.ptp(c["mesh_energy_j"])


def _hertz_mesh_stiffness(mesh, torque_nm):
    """dT/dtheta (N m/rad) at the first phase from preview_balance (central difference
    +-0.1 %) with Hamrock–Brewe approach coefficients."""
    ok = mesh.valid[:, 0] & mesh.valid[:, 1]
    lv, g = mesh.lever_mm[ok, 0], mesh.opening_mm[ok, 0]
    kap = np.array([hamrock_brewe_hertz(a, b, 1.0, e_prime_mpa=mesh.e_prime_mpa).approach_mm
                    for a, b in zip(mesh.A_minus_per_mm[ok, 0], mesh.B_minus_per_mm[ok, 0])])
    t = 1e3 * torque_nm
    th_p = preview_balance(lv, g, kap, 1.001 * t)[0]
    th_m = preview_balance(lv, g, kap, 0.999 * t)[0]
    return 1e-3 * 0.002 * t / (th_p - th_m)


def _independent_modes(mesh, dt, torque_nm):
    """Eigenfrequencies (Hz) of the linearised chain from the parameters and the
    Hertzian mesh stiffness dT/dtheta of preview_balance (central difference)."""
    k_th = _hertz_mesh_stiffness(mesh, torque_nm)
    de = (mesh.eps_rad[1] - mesh.eps_rad[0]) / mesh.step_rad
    v = np.array([0.0, 1.0 / mesh.ratio + de, -1.0, 0.0])
    k1, k2 = dt.input_stiffness_nm_per_rad, dt.output_stiffness_nm_per_rad
    K = k_th * np.outer(v, v)
    K[:2, :2] += k1 * np.array([[1, -1], [-1, 1]])
    K[2:, 2:] += k2 * np.array([[1, -1], [-1, 1]])
    M = np.diag([dt.motor_inertia_kgm2, dt.pinion_inertia_kgm2, dt.gear_inertia_kgm2,
                 dt.load_inertia_kgm2])
    lam = np.linalg.eig(np.linalg.inv(M) @ K)[0].real
    return np.sort(np.sqrt(np.clip(lam, 0, None)))[1:] / (2 * math.pi)


def _peaks(signal, dt, freqs_hz):
    """Spectral peak nearest each expected frequency (Hann window, parabolic
    interpolation of the log amplitude: ~0.05 bin)."""
    x = (signal - signal.mean()) * np.hanning(signal.size)
    amp = np.log(np.abs(np.fft.rfft(x)) + 1e-300)
    df = 1.0 / (signal.size * dt)
    out = []
    for f in freqs_hz:
        k0 = int(round(f / df))
        lo, hi = max(k0 - 8, 1), k0 + 9
        k = lo + int(np.argmax(amp[lo:hi]))
        a, b, c = amp[k - 1], amp[k], amp[k + 1]
        out.append((k + 0.5 * (a - c) / (a - 2 * b + c)) * df)
    return np.array(out)


def test_free_vibration_frequencies_are_the_linear_eigenvalues(s0003_twin):
    pair, _, _, mesh = s0003_twin
    dt = _undamped(pair)
    m = build_model(mesh, dt, TORQUE_NM, curvatures="exact")   # the closed form's law
    expected = _independent_modes(mesh, dt, TORQUE_NM)
    np.testing.assert_allclose(linearized_modes(m)[1:], expected, rtol=1e-3)
    # a small kick (mesh rotation amplitude ~1e-4 of the static one: the Hertzian
    # nonlinearity shifts frequencies by its square)
    res = simulate(m, speed_rpm=0.0, duration_s=0.2, step_s=5e-6,
                   initial_velocity=[0.0, 0.05, -0.002, 0.0])
    c = res.columns
    # the mesh rotation and the pinion/gear speeds carry every mode
    found_theta = _peaks(c["theta_rad"], 5e-6, expected)
    found_gear = _peaks(c["gear_speed_rad_s"], 5e-6, expected)
    # resolution 5 Hz (0.2 s); the interpolated peak is within 0.3 Hz, plus the RK4
    # period error (h omega)^4/120 < 1e-6: 1 Hz or 0.1 %
    for found in (found_theta, found_gear):
        np.testing.assert_allclose(found, expected, atol=1.0, rtol=1e-3)


def test_contact_loss_gives_zero_torque_and_no_nan(s0003_twin):
    pair, _, _, mesh = s0003_twin
    light = 2.0     # N m on the gear
    m = build_model(mesh, default_drivetrain(pair), light)
    # knock the gear forward: the flanks open, fly through the backlash and hit the
    # coast flank (gear on its shaft: 15 rad/s / 6.5e3 rad/s = 2.3e-3 rad > backlash 1.4e-3)
    res = simulate(m, speed_rpm=3000.0, duration_s=0.01, step_s=5e-6,
                   initial_velocity=[0.0, 0.0, 15.0, 0.0])
    c = res.columns
    s = res.summary
    assert all(np.all(np.isfinite(v)) for v in c.values())
    theta, tm = c["theta_rad"], c["mesh_torque_nm"]
    thb = m.drivetrain.backlash_mm / mesh.reference_lever_mm
    free = (theta < 0.0) & (theta > -thb)
    assert free.any() and np.all(tm[free] == 0.0) and np.all(c["mesh_load_n"][free] == 0.0)
    # coast flank: the mesh torque reverses only beyond the backlash
    assert np.all(tm[theta >= 0.0] >= 0.0)
    assert np.all(tm[theta <= -thb] <= 0.0)
    assert (tm < 0.0).any()
    loss = float(np.mean(c["mesh_torque_nm"][c["t_s"] >= 0.5 * s["duration_s"]] == 0.0))
    assert s["contact_loss"] == pytest.approx(loss)


@pytest.mark.parametrize("curvatures, tol, tol_ellipse", [("exact", 2e-3, 1.5e-3),
                                                          ("stencil", 4e-3, 5e-3)])
def test_golden_equals_reference_within_fixed_point_tolerance(s0003_twin, curvatures, tol,
                                                              tol_ellipse):
    pair, _, _, mesh = s0003_twin
    dt = default_drivetrain(pair)
    runs = {}
    for be in ("reference", "golden"):
        runs[be] = simulate(build_model(mesh, dt, TORQUE_NM, backend=be,
                                        curvatures=curvatures), speed_rpm=3000.0,
                            duration_s=0.01, step_s=10e-6).columns
    r, g = runs["reference"], runs["golden"]
    # golden stage D: a within 3.6e-4, k within 6.8e-4 end to end (preview.hertz.golden);
    # kappa = 3 W F(k)/(pi a E') W^(-2/3) within ~1e-3 and W = (d/kappa)^(3/2) within
    # 1.5e-3 of the static load; a, b, p_max within 1e-3 (golden error + the load's).
    # With stage C the gap samples are quantized too (STENCIL_GAP Q(32,21): 4.8e-7 mm on
    # samples of up to ~0.05 mm, through the degree-6 ROM's noise gain 17: sigma 2.4e-6
    # 1/mm on c3) and B- is a 2^-20 code of ~0.002 1/mm: the fitted curvatures carry up
    # to ~1e-3 more, the load and TE up to 4e-3, the ellipse of the most loaded pair up to
    # 5e-3 (measured 2.3e-3 and 3.7e-3 with the former degree-2 fit at Q(32,16), whose
    # sigma on c3 was 4.5e-6 1/mm)
    w0 = r["mesh_load_n"].mean()
    assert np.abs(g["mesh_load_n"] - r["mesh_load_n"]).max() < tol * w0
    assert np.abs(g["te_arcsec"] - r["te_arcsec"]).max() < tol * np.abs(r["te_arcsec"]).max()
    for key in ("a_mm", "b_mm", "p_max_mpa"):
        np.testing.assert_allclose(g[key], r[key], rtol=tol_ellipse)
    # and it is not the same computation: the fixed point leaves its rounding
    assert np.any(g["mesh_load_n"] != r["mesh_load_n"])


def test_stencil_law_is_the_c_to_d_preview_of_the_stencil(s0003_twin):
    # the static point with stage C per step against an independent balance built on the
    # package's fp64 C -> D chain (fit_curvatures of each pair's stencil, Hamrock–Brewe
    # approach): the same rotation to 1e-9; and it equals the rotation on the TCA's
    # curvatures to stage C's fit bias: the degree-6 fit leaves the gap's terms of degree
    # 8 and up (B- within 1.6e-4 on every row, tests/twin/test_mesh.py), measured 7.5e-6
    # on the rotation (the former quadratic fit's +5 % on B- at P0 moved it by 0.3-10 %)
    from gearcontact.preview.fit.reference import fit_curvatures

    pair, _, _, mesh = s0003_twin
    dt = default_drivetrain(pair)
    theta, loads = static_rotation(build_model(mesh, dt, TORQUE_NM, curvatures="stencil"))
    ok = mesh.valid[:, 0] & mesh.valid[:, 1]
    kap = []
    for g in mesh.stencil_gaps_mm[ok, 0]:
        fit = fit_curvatures(g)
        hb = hamrock_brewe_hertz(fit.A_minus_per_mm, fit.B_minus_per_mm, 1.0,
                                 e_prime_mpa=mesh.e_prime_mpa)
        kap.append(hb.approach_mm)
    th, w = preview_balance(mesh.lever_mm[ok, 0], mesh.opening_mm[ok, 0], np.array(kap),
                            1e3 * TORQUE_NM)
    assert theta == pytest.approx(th, rel=1e-9)
    np.testing.assert_allclose(loads[ok], w, rtol=1e-7, atol=1e-9 * w.sum())
    exact, _ = static_rotation(build_model(mesh, dt, TORQUE_NM, curvatures="exact"))
    assert abs(theta / exact - 1.0) < 1e-4


def test_static_rotation_is_the_hertzian_balance(model, s0003_twin):
    mesh = s0003_twin[3]
    theta, loads = static_rotation(model)
    torque = 1e-3 * float(np.sum(loads * mesh.lever_mm[:, 0]))
    assert torque == pytest.approx(TORQUE_NM, rel=1e-9)


def test_bad_input_names_the_field(model, s0003_twin):
    pair, _, _, mesh = s0003_twin
    with pytest.raises(InputRangeError, match="step_us"):
        simulate(model, speed_rpm=3000.0, duration_s=0.01, step_s=49e-6)   # > h_max 43 us
    with pytest.raises(InputRangeError, match="step_us"):
        simulate(model, speed_rpm=3000.0, duration_s=0.01, step_s=0.5e-6)
    with pytest.raises(InputRangeError, match="backend"):
        build_model(mesh, default_drivetrain(pair), TORQUE_NM, backend="fpga")
    with pytest.raises(InputRangeError, match="speed_rpm"):
        simulate(model, speed_rpm=-1.0, duration_s=0.01, step_s=10e-6)
    with pytest.raises(InputRangeError, match="table"):
        build_model(mesh, default_drivetrain(pair), TORQUE_NM, backend="table")
    with pytest.raises(InputRangeError, match="initial_velocity"):
        simulate(model, speed_rpm=0.0, duration_s=1e-3, step_s=1e-5, initial_velocity=[1.0])
    with pytest.raises(InputRangeError, match="duration_s"):
        simulate(build_model(mesh, default_drivetrain(pair), TORQUE_NM, backend="soc"),
                 speed_rpm=3000.0, duration_s=0.1, step_s=1e-5)
    with pytest.raises(InputRangeError, match="curvatures"):
        build_model(mesh, default_drivetrain(pair), TORQUE_NM, curvatures="fitted")
    with pytest.raises(InputRangeError, match="pinion_inertia_kgm2"):
        replace(default_drivetrain(pair), pinion_inertia_kgm2=-1e-6)


@pytest.mark.parametrize("curvatures", ["exact", "stencil"])
def test_previews_outside_the_datapath_are_counted_and_run_in_fp64(s0003_twin, curvatures):
    """Curvatures outside the fixed-point domain (A- x 300 = 26 1/mm > 16, every row) are
    a result, not a refusal: the golden twin, whose chain flags every preview, evaluates
    them with the fp64 law on the fp64 curvatures, so its trajectory is the reference
    twin's bit for bit (the same law on the same numbers), and both report the same
    counts: every preview and every step outside the domain, none without a law."""
    pair, _, _, mesh = s0003_twin
    steep = replace(mesh, A_minus_per_mm=300.0 * mesh.A_minus_per_mm,
                    stencil_gaps_mm=300.0 * mesh.stencil_gaps_mm)
    runs = {}
    for backend in ("reference", "golden"):
        m = build_model(steep, default_drivetrain(pair), TORQUE_NM, backend=backend,
                        curvatures=curvatures)
        runs[backend] = simulate(m, speed_rpm=3000.0, duration_s=2e-3, step_s=1e-5)
    ref, gold = runs["reference"], runs["golden"]
    for name in ("theta_rad", "mesh_load_n", "a_mm", "p_max_mpa"):
        np.testing.assert_array_equal(gold.columns[name], ref.columns[name])
    for r in (ref, gold):
        s = r.summary
        assert s["steps_outside_datapath"] == s["steps"] == 200
        assert s["previews_outside_datapath"] >= s["steps"]
        assert s["previews_without_contact_law"] == 0
        assert s["outside_datapath_evaluated_by"].startswith("fp64 Hamrock-Brewe")
    assert gold.summary["previews_outside_datapath"] == ref.summary["previews_outside_datapath"]


def test_contact_loss_at_light_load_in_resonance(s0003_twin):
    # The unloaded TE excites the first mode at f_z = f_1 (Kahraman & Singh 1990): at
    # 1 N m the static mesh rotation (~0.6 arcsec) is smaller than the resonant swing, so
    # the teeth separate for part of every cycle; at the nominal 64.5 N m they do not.
    # Measured: 7 % of the time at 1 N m (dynamic factor 2.4), 0 at 64.5 N m.
    pair, _, _, mesh = s0003_twin
    out = {}
    for torque in (1.0, TORQUE_NM):
        m = build_model(mesh, default_drivetrain(pair), torque)
        n_res = 60.0 * linearized_modes(m)[1] / mesh.pinion_teeth
        res = simulate(m, speed_rpm=n_res, duration_s=0.15, step_s=10e-6)
        c = res.columns
        assert all(np.all(np.isfinite(v)) for v in c.values())
        lost = c["theta_rad"] < 0.0
        thb = m.drivetrain.backlash_mm / mesh.reference_lever_mm
        assert np.all(c["mesh_torque_nm"][lost & (c["theta_rad"] > -thb)] == 0.0)
        out[torque] = res.summary
    assert out[1.0]["contact_loss"] > 0.01 and out[1.0]["dynamic_factor"] > 1.5
    assert out[TORQUE_NM]["contact_loss"] == 0.0


def test_speed_controller_recovers_like_the_rigid_pi_loop(s0003_twin):
    # PI on the motor speed, 5 Hz bandwidth (30x below the first mode): on the rigid
    # chain the closed loop is s^2 J + K_p s + K_i with both poles at -w_n = -pi f_c, so
    # an initial speed error e0 of the whole chain decays as e0 (1 - w_n t) exp(-w_n t)
    pair, _, _, mesh = s0003_twin
    dt = replace(default_drivetrain(pair), speed_control_bandwidth_hz=5.0)
    m = build_model(mesh, dt, TORQUE_NM, curvatures="exact")
    e0, omega = 5.0, 3000.0 * 2 * math.pi / 60
    u = mesh.ratio
    res = simulate(m, speed_rpm=3000.0, duration_s=0.4, step_s=10e-6,
                   initial_velocity=[-e0, -e0, -e0 / u, -e0 / u])
    c = res.columns
    t = c["t_s"]
    wn = math.pi * 5.0
    expected = e0 * (1 - wn * t) * np.exp(-wn * t)
    err = omega - c["pinion_speed_rad_s"]
    # the pinion also carries the mesh-excited vibration (~1e-2 rad/s at 350 Hz and up):
    # smooth it over one mesh period, then 2 % of e0
    k = int(round(1 / 350.0 / 10e-6))
    smooth = np.convolve(err, np.ones(k) / k, mode="valid")
    mid = t[k // 2: k // 2 + smooth.size]
    np.testing.assert_allclose(smooth, e0 * (1 - wn * mid) * np.exp(-wn * mid),
                               atol=0.02 * e0)
    # the last raw sample: 2 % of e0 plus the pinion's own mesh vibration, its largest
    # departure from the smoothed speed over the last 20 mesh periods (measured 0.105
    # rad/s at the end since the posed pairs' openings are their touch, bound 0.1 before)
    vib = np.abs(err[k // 2: k // 2 + smooth.size] - smooth)[-20 * k:].max()
    assert abs(err[-1]) < 0.02 * e0 + vib and expected.min() < -0.1 * e0   # overshoot seen
    # and the bandwidth is bounded by the first mode
    with pytest.raises(InputRangeError, match="speed_control_bandwidth_hz"):
        simulate(build_model(mesh, replace(dt, speed_control_bandwidth_hz=100.0),
                             TORQUE_NM), speed_rpm=3000.0, duration_s=1e-3, step_s=1e-5)


def test_two_inertia_mesh_mode_closed_form(s0003_twin):
    # shafts 1e6 times softer: pinion and gear vibrate on the mesh alone, the two-inertia
    # closed form omega^2 = k_theta (v_p^2 / J_p + 1 / J_g), v_p = 1/u + eps'
    pair, _, _, mesh = s0003_twin
    dt = replace(_undamped(pair), input_stiffness_nm_per_rad=1e-2,
                 output_stiffness_nm_per_rad=1e-2)
    m = build_model(mesh, dt, TORQUE_NM, curvatures="exact")   # the closed form's law
    k_th = _hertz_mesh_stiffness(mesh, TORQUE_NM)
    v_p = 1.0 / mesh.ratio + (mesh.eps_rad[1] - mesh.eps_rad[0]) / mesh.step_rad
    f_closed = math.sqrt(k_th * (v_p ** 2 / dt.pinion_inertia_kgm2
                                 + 1.0 / dt.gear_inertia_kgm2)) / (2 * math.pi)
    # the library's eig (the soft shafts shift it by ~1e-6)
    assert linearized_modes(m)[-1] == pytest.approx(f_closed, rel=1e-4)
    # the free vibration of the twin rings at it (0.05 s: 20 Hz bins, interpolated peak
    # within 0.2 %)
    res = simulate(m, speed_rpm=0.0, duration_s=0.05, step_s=2e-6,
                   initial_velocity=[0.0, 0.05, 0.0, 0.0])
    found = _peaks(res.columns["theta_rad"], 2e-6, [f_closed])[0]
    assert found == pytest.approx(f_closed, rel=2e-3)


def test_compiled_law_failure_is_a_check_failed_naming_it(s0003_twin, monkeypatch):
    """A failure the compiled step loop raises (line_law._coupled_state's ArithmeticError:
    the coupled slice law's Newton did not converge) reaches the caller as CheckFailed
    (the CLI's exit 4, "a Newton iteration failed inside a run"), its message kept and
    the steps named. The kernel is replaced by one that raises it in its first block
    (the compile call of one step runs the real kernel); the FMU's own report of the
    same failure: tests/export/test_fmu_cylindrical.py."""
    from gearcontact.errors import CheckFailed
    from gearcontact.twin import kernel as K

    pair, _, _, mesh = s0003_twin
    model = build_model(mesh, default_drivetrain(pair), torque_nm=64.5)
    real = K.run_steps

    def failing(y, t0, n_steps, *args):
        if n_steps > 1:
            raise ArithmeticError("coupled slice law: no convergence (docs/cylindrical.md "
                                  "sec. 10)")
        return real(y, t0, n_steps, *args)

    monkeypatch.setattr(K, "run_steps", failing)
    with pytest.raises(CheckFailed, match=r"steps 0\.\.\d+ .*coupled slice law: no "
                                          r"convergence"):
        simulate(model, speed_rpm=3000.0, duration_s=5e-3, step_s=1e-5)
