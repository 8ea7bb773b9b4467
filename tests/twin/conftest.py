"""s0003 mesh for the twin tests (one TCA per session: 31 phases per pitch keep the
neighbouring pairs' paths, see tests/ltca/test_lte.py, at half the cost of 61).

The s0003-centred tables take the untruncated Hertzian law (``edge_law=False``): their
truth is the loaded TE's preview ``TE_pre`` (the same Hertzian pairs), and the rows
whose patch a flank boundary cuts (pairs +-1 near their path ends) would otherwise carry
the LCP's compliance (ltca.edge_law, tested on s0003_coast_twin in test_edge_law.py)."""

import pytest

PHASES = 31
TORQUE_NM = 64.5


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
