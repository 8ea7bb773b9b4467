"""The reverse flank: its own law from its own TCA, the free play between the flanks,
and torque reversal through the backlash.

Truths:
- the geometric free play the twin derives from the two TCAs equals the separation of
  the reverse flanks measured on the real surfaces (gap field) with the gear posed at
  the loaded flanks' unloaded contact (s0003-centred: -7.4 to -8.7 um, the generated
  teeth interfere; the designed backlash_mm is added to it);
- the reverse flank's torque at a closure is the Hertzian balance of the coast pairs
  (levers, openings and Hamrock–Brewe approach coefficients of the coast mesh,
  :func:`gearcontact.analytic.hertz.hamrock_brewe_hertz`), not the drive law mirrored;
- through the backlash the mesh torque reverses only once the reverse flanks close;
- the Newton solve of the Hertz + bending law inverts ``d = kappa W^(2/3) + c_b W``.
"""

from dataclasses import replace

import numpy as np
import pytest

from gearcontact.analytic.hertz import hamrock_brewe_hertz
from gearcontact.tca.load import torque_lever_mm
from gearcontact.tca.stencil import gap_field
from gearcontact.twin import kernel as K
from gearcontact.twin.mesh import free_play_rad, reverse_law
from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import _fit_args, _prm, build_model, simulate

from .conftest import TORQUE_NM

ARCSEC = 206264.80624709636


def test_free_play_is_the_gap_of_the_posed_reverse_flanks(s0003_twin, s0003_coast):
    pair, tca, flanks, mesh = s0003_twin
    ctca, cmesh = s0003_coast
    kin = pair.kinematics()
    cyc, ccyc = tca.cycle, ctca.cycle
    pin, gear = flanks.flank("pinion", "coast"), flanks.flank("gear", "coast")
    base = int(np.argmin(np.abs(ccyc.path.phi1_rad - ccyc.phi1_rad[0])))
    pitch = mesh.pitch_rad
    for k in (3, len(ccyc.phi1_rad) // 2):
        mp = ccyc.path.points[base + k]
        x = mp.phi1_rad
        # the loaded (drive) flanks' unloaded gear angle at this pinion angle
        env = np.interp(np.mod(x - cyc.phi1_rad[0], pitch) + cyc.phi1_rad[0], cyc.phi1_rad,
                        cyc.envelope_arcsec)
        phi2 = cyc.path.phi2_ref_rad + (x - cyc.path.phi1_ref_rad) / cyc.path.ratio + env / ARCSEC
        f = gap_field(pin, gear, kin, replace(mp, phi2_rad=float(phi2)),
                      half_extent_mm=(0.3, 0.1), side=9, allow_outside=True)
        lever = torque_lever_mm(mp.point_mm, mp.normal)
        psi = mesh.motion_sign * (x - mesh.phi1_rad[0])
        b = float(free_play_rad(mesh, cmesh, np.array([psi]))[0])
        # 0.15 um: the minimum of a 9 x 9 sampled gap (cell 0.07 mm, curvature ~0.1/mm)
        assert f.gap_mm.min() == pytest.approx(lever * b, abs=1.5e-4)
        assert -10e-3 < lever * b < -5e-3          # the measured interference, mm


def test_reverse_flank_has_its_own_hertzian_law(s0003_twin, s0003_coast):
    pair, _, _, mesh = s0003_twin
    _, cmesh = s0003_coast
    # the TCA's curvatures: the independent balance below is built on them
    model = build_model(mesh, default_drivetrain(pair), TORQUE_NM, reverse=cmesh,
                        curvatures="exact")
    prm = _prm(model, 0.0)
    a = model.arrays
    c_r, big = reverse_law(mesh, cmesh)
    kr = len(cmesh.psi_rad) // 2
    psi = c_r - cmesh.psi_rad[kr] - 1e-9 * cmesh.step_rad    # just past coast row kr
    # coast closure 3 arcsec: gear ahead of the drive pose by free play + backlash + 3"
    th_r = 3.0 / ARCSEC
    eps_r = cmesh.eps_rad[kr]
    y = np.zeros(K.N_STATE)
    y[1] = psi
    y[2] = th_r + psi / mesh.ratio - eps_r + big + prm[K.P_THB]
    y[0], y[3] = y[1], y[2]                           # shafts untwisted, at rest
    dy = np.zeros(K.N_STATE)
    n_p = a["lever"].shape[1]
    dy = np.zeros((1, K.N_STATE))
    th, th_r_k, t_mesh, w = K._deriv(y, prm, a["eps"], a["lever"], a["opening"], a["cv"],
                                     a["valid"], a["cb"], 0, np.full((2, n_p), 1e3),
                                     np.full((2, n_p, K.N_CACHE), -1.0), a["pow_lut"],
                                     a["cbrt_lut"], a["cst"], np.zeros((0, K.N_TRACE), np.int64),
                                     np.zeros(K.N_COUNT, np.int64), _fit_args(a, 0), a["tab_theta"], a["tab_t23"],
                                     a["tab_w23"], dy, 0, np.zeros((2, n_p)), np.zeros((2, 4)),
                                     np.zeros(K.N_PREVIEW))
    dy = dy[0]
    assert th_r_k == pytest.approx(th_r, rel=1e-6)
    assert th < 0.0                                   # the drive flanks are open
    # independent: the coast pairs' Hertzian balance at closure th_r
    ok = cmesh.valid[:, kr]
    t_coast = 0.0
    for lv, g, A, B in zip(cmesh.lever_mm[ok, kr], cmesh.opening_mm[ok, kr],
                           cmesh.A_minus_per_mm[ok, kr], cmesh.B_minus_per_mm[ok, kr]):
        kap = hamrock_brewe_hertz(A, B, 1.0, e_prime_mpa=cmesh.e_prime_mpa).approach_mm
        d = lv * th_r - g
        if d > 0:
            t_coast += 1e-3 * lv * (d / kap) ** 1.5
    assert -t_mesh == pytest.approx(t_coast, rel=1e-9)
    # the drive law mirrored at the same closure is a different stiffness
    mirrored = build_model(mesh, default_drivetrain(pair), TORQUE_NM)
    from gearcontact.twin.simulate import _elastic
    i = int(np.argmin(np.abs(mesh.psi_rad - np.mod(psi, mesh.pitch_rad))))
    t_drive = _elastic(mirrored, _prm(mirrored, 0.0), th_r, mesh.psi_rad[i])[0]
    assert abs(t_drive / t_coast - 1.0) > 0.02
    # the gear is pushed back, the pinion forward through the coast law's own slope
    der = (cmesh.eps_rad[kr + 1] - cmesh.eps_rad[kr]) / cmesh.step_rad
    assert dy[6] * prm[K.P_JG] == pytest.approx(t_mesh, rel=1e-12)
    assert dy[5] * prm[K.P_JP] == pytest.approx(-t_mesh * (1.0 / mesh.ratio + der), rel=1e-9)


def test_torque_reversal_through_the_backlash(s0003_twin, s0003_coast):
    """A forward kick of the gear: it leaves the drive flank, crosses the free play and
    strikes the coast flank; the mesh torque is negative only where the coast flanks
    close (theta <= -(b + theta_b)), zero in between, and the run stays finite."""
    pair, _, _, mesh = s0003_twin
    _, cmesh = s0003_coast
    model = build_model(mesh, default_drivetrain(pair), 5.0, reverse=cmesh)
    res = simulate(model, speed_rpm=300.0, duration_s=0.004, step_s=1e-5,
                   initial_velocity=[0.0, 0.0, 10.0, 0.0])
    c = res.columns
    theta, t = c["theta_rad"], c["mesh_torque_nm"]
    assert np.all(np.isfinite(t))
    coast = t < 0.0
    assert coast.any() and (t > 0.0).any() and (t == 0.0).any()
    gap = free_play_rad(mesh, cmesh, c["psi_p_rad"]) + model.drivetrain.backlash_mm / \
        mesh.reference_lever_mm
    closure = -theta - gap                  # coast approach (rad), > 0 in contact
    assert np.all(closure[coast] >= -1e-12)
    free = (theta < 0.0) & (closure < 0.0)
    assert free.any() and np.all(t[free] == 0.0)


def test_backlash_must_clear_the_interference(s0003_twin, s0003_coast):
    """s0003-centred's generated flanks interfere by ~9.5 um: a smaller designed
    backlash is a named error, a larger one runs."""
    from dataclasses import replace as dc_replace

    from gearcontact.validation import InputRangeError
    pair, _, _, mesh = s0003_twin
    _, cmesh = s0003_coast
    dt = default_drivetrain(pair)
    with pytest.raises(InputRangeError, match="drivetrain.backlash_mm"):
        build_model(mesh, dc_replace(dt, backlash_mm=0.005), TORQUE_NM, reverse=cmesh)
    build_model(mesh, dc_replace(dt, backlash_mm=0.011), TORQUE_NM, reverse=cmesh)


@pytest.mark.parametrize("d, kap, cb", [(1e-3, 2e-4, 0.0), (1e-3, 2e-4, 1e-6),
                                        (5e-2, 1e-4, 5e-5), (1e-6, 3e-4, 1e-5)])
@pytest.mark.parametrize("s_prev", [-1.0, 1e-3, 1.0, 1e3])
def test_bending_law_inverts(d, kap, cb, s_prev):
    """From the bound start or any previous solution (far below or above the root)."""
    w, s = K._pair_load(d, kap, cb, s_prev)
    assert kap * w ** (2.0 / 3.0) + cb * w == pytest.approx(d, rel=1e-12)
    if cb > 0.0:                        # the next start: W^(1/3), to rounding
        assert s ** 3 == pytest.approx(w, rel=1e-14)
