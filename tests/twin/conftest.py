"""s0003 mesh for the twin tests (one TCA per session: 31 phases per pitch keep the
neighbouring pairs' paths, see tests/ltca/test_lte.py, at half the cost of 61).

The s0003-centred tables take the untruncated Hertzian law (``edge_law=False``): their
truth is the loaded TE's preview ``TE_pre`` (the same Hertzian pairs), and the rows
whose patch a flank boundary cuts (pairs +-1 near their path ends) would otherwise carry
the LCP's compliance (ltca.edge_law, tested on s0003_coast_twin in test_edge_law.py)."""

from pathlib import Path

import pytest

PHASES = 31
TORQUE_NM = 64.5
#: The ISO 23509 F.2 spiral bevel pair with all four flanks cut from typed machine
#: settings (issue 27: the twin on a pair from the Surface contract's other source).
F2_MACHINE = Path(__file__).resolve().parents[2] / "examples" / "machine_settings" / \
    "iso23509_f2_machine.toml"


@pytest.fixture(scope="session")
def s0003_twin(s0003_centred):
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.twin.mesh import mesh_table

    pair, flanks = s0003_centred
    tca, flanks = analyze_pair(pair, side="drive", phases=PHASES, edge_contact=False,
                               flanks=flanks)
    return pair, tca, flanks, mesh_table(tca, flanks, pair, torque_nm=TORQUE_NM,
                                         edge_law=False)


@pytest.fixture(scope="session")
def f2_machine_twin():
    """``(pair, tca, flanks, mesh)`` of the F.2 machine-settings pair as
    :func:`s0003_twin` builds s0003's (PHASES per pitch, surface TCA, untruncated
    Hertzian law; about 3 s)."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.twin.mesh import mesh_table

    pair = load_pair(F2_MACHINE)
    tca, flanks = analyze_pair(pair, side="drive", phases=PHASES, edge_contact=False,
                               flanks=build_flanks(pair))
    return pair, tca, flanks, mesh_table(tca, flanks, pair, torque_nm=TORQUE_NM,
                                         edge_law=False)


@pytest.fixture(scope="session")
def s0003_drive_bending(s0003_twin):
    """The shell tooth bending of both members on the drive flanks of s0003_twin (about
    4 s, built once for the bending and table tests)."""
    from gearcontact.ltca.tooth_bending import tooth_bending

    pair, _, flanks, _ = s0003_twin
    return tooth_bending(flanks, pair, side="drive")


def quasi_static_bound_arcsec(mesh, rotation_arcsec: float, *,
                              exponent: float = 2.0 / 3.0) -> float:
    """TE tolerance at the phase rows of a quasi-static run against the static loaded TE.

    The twin's pinion carries ``T (1/u + eps')``, so with the motor torque ``T_l / u``
    the mesh torque departs from ``T_l`` by the relative ``u eps'``, which moves the
    Hertzian rotation (``theta ~ T^(2/3)``) by ``(2/3) u |eps'| theta`` (``exponent``:
    1 bounds a rotation with tooth bending, between Hertz and linear); plus 0.003
    arcsec for sampling within 1 % of a row where the TE slope reaches 0.25 arcsec/row.
    """
    import numpy as np

    slope = np.abs(np.diff(mesh.eps_rad) / mesh.step_rad).max()
    return exponent * mesh.ratio * slope * rotation_arcsec + 0.003


@pytest.fixture(scope="session")
def s0003_coast(s0003_twin):
    """The coast flanks' mesh of the same s0003-centred flanks (the reverse law)."""
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.twin.mesh import mesh_table

    pair, _, flanks, _ = s0003_twin
    tca, _ = analyze_pair(pair, side="coast", phases=PHASES, flanks=flanks,
                          edge_contact=False)
    return tca, mesh_table(tca, flanks, pair, side="coast", torque_nm=TORQUE_NM,
                           edge_law=False)


@pytest.fixture(scope="session")
def s0003_coast_twin(s0003_calibrated):
    """``(pair, tca, flanks, mesh)``: the twin's own TCA and mesh table of the calibrated
    s0003 on its design side (coast; :func:`~gearcontact.twin.mesh.pair_mesh_table`,
    the edge-contact TCA, PHASES per pitch): pair 0 runs onto the gear heel and the
    pinion tip (corner) edges at its path end, every row's ellipse is cut by the tip
    (a tip-edge bearing), so its law is the LCP-calibrated one (ltca.edge_law)."""
    from gearcontact.twin.mesh import pair_mesh_table

    pair, flanks = s0003_calibrated
    tca, flanks, mesh = pair_mesh_table(pair, side="coast", torque_nm=TORQUE_NM,
                                        phases=PHASES, flanks=flanks)
    return pair, tca, flanks, mesh


def static_rotation_at(model, psi_rad: float) -> tuple:
    """Rotation (rad) and loaded-flank pair loads (N) carrying the model's load torque at
    the pinion angle ``psi_rad`` on its own compiled law (:func:`gearcontact.twin.
    statics._elastic`), by bisection to 1e-14 relative: an equilibrium independent of
    the integrator (``statics.static_rotation`` solves the first phase only)."""
    from gearcontact.twin import statics
    from gearcontact.twin.model import _prm

    prm = _prm(model, 0.0)
    lo, hi = 0.0, 1e-3
    while statics._elastic(model, prm, hi, psi_rad)[0] < model.torque_nm:
        hi *= 2.0
    while hi - lo > 1e-14 * hi:
        mid = 0.5 * (lo + hi)
        if statics._elastic(model, prm, mid, psi_rad)[0] < model.torque_nm:
            lo = mid
        else:
            hi = mid
    return hi, statics._elastic(model, prm, hi, psi_rad)[1]


def energy_residual(c):
    """Stored + dissipated energy minus the end torques' work (J) of a twin record ``c``,
    relative to the stored energy at the start: 0 by conservation."""
    stored = c["kinetic_j"] + c["shaft_energy_j"] + c["mesh_energy_j"]
    return stored + c["dissipated_j"] - c["input_work_j"] - stored[0]


def frozen_mesh(mesh):
    """The mesh of the first phase at every phase: no explicit phase dependence, so the
    undamped chain is conservative (the real mesh exchanges energy with the rotation
    through its phase-varying levers, openings and curvatures)."""
    import numpy as np
    from dataclasses import replace

    def first(a):
        return np.repeat(a[..., :1], a.shape[-1], axis=-1)
    return replace(mesh, eps_rad=first(mesh.eps_rad), lever_mm=first(mesh.lever_mm),
                   opening_mm=first(mesh.opening_mm), A_minus_per_mm=first(mesh.A_minus_per_mm),
                   stencil_gaps_mm=np.repeat(mesh.stencil_gaps_mm[:, :1],
                                             mesh.stencil_gaps_mm.shape[1], axis=1),
                   B_minus_per_mm=first(mesh.B_minus_per_mm), valid=first(mesh.valid))


def quasi_static_run(pair, mesh, lte, *, backend: str = "reference",
                     hertz_form: str = "hamrock-brewe"):
    """The twin at 60 rpm over two pitches on the loaded TE's preview law (the TCA's
    curvatures), shafts well damped (0.3) so the start transient dies within the first
    pitch, the mesh damper small (0.02: its torque shifts the balance), against the
    static loaded TE ``lte`` (:func:`gearcontact.ltca.lte.loaded_te` on the same TCA).

    Returns ``(res, te_ref, second, rows, row_index)``: the run, ``TE_pre`` interpolated
    at each step's phase, the steps of the second pitch, the steps within 1 % of a TCA
    row, and that row's index in the LTE's phase order. ``hertz_form``: the twin's fp64
    law (:class:`gearcontact.twin.model.TwinModel`)."""
    import math
    from dataclasses import replace

    import numpy as np

    from gearcontact.twin.params import default_drivetrain
    from gearcontact.twin.simulate import build_model, simulate

    dt = replace(default_drivetrain(pair), input_damping_ratio=0.3, output_damping_ratio=0.3,
                 mesh_damping_ratio=0.02)
    pitch = mesh.pitch_rad
    res = simulate(build_model(mesh, dt, TORQUE_NM, backend=backend, curvatures="exact",
                               hertz_form=hertz_form),
                   speed_rpm=60.0, duration_s=2 * pitch / (2 * math.pi), step_s=10e-6)
    c = res.columns
    order = np.arange(len(mesh.psi_rad))[::mesh.motion_sign]     # TCA rows -> motion
    psi = np.mod(c["psi_p_rad"], pitch)
    ref = np.interp(psi, mesh.psi_rad, lte.te_pre_arcsec[order])
    second = c["t_s"] >= 0.5 * res.summary["duration_s"]
    near = np.round(psi / mesh.step_rad)
    rows = np.abs(psi / mesh.step_rad - near) < 0.01
    return res, ref, second, rows, order[near.astype(int)]
