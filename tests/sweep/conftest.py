"""Fixtures of the sweep tests: one LocalCluster of two worker processes shared by the
modules (its start-up costs seconds); the centred pair and its flanks are the shared
``s0003_centred`` of tests/conftest.py."""

import pytest


@pytest.fixture(scope="package")
def client():
    pytest.importorskip("distributed")
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def predicted_face_shift_mm(res, pair, flanks, d) -> float:
    """First-order shift (mm along the gear face, v2) of the drive pattern of the TCA
    ``res`` under the pinion translation ``d`` (mm): the path shift of the tilted TE
    parabolas plus the local shift at P0's phase (tests/sweep/test_cell.py's docstring
    states both and their sources)."""
    import numpy as np

    from gearcontact.tca.curvature import curvature_tensor, flank_frame

    Z = np.array([0.0, 0.0, 1.0])
    path = res.cycle.path
    pts = [p for p in path.points if not p.edge]
    phi = np.array([p.phi1_rad for p in pts]) - path.phi1_ref_rad
    pitch = np.abs(phi) < np.pi / pair.pinion_teeth           # one pitch about P0
    r = np.array([p.point_mm for p in pts])
    n = np.array([p.normal for p in pts])
    theta = (n @ d) / np.einsum("ij,ij->i", n, np.cross(Z, r))       # rad
    te0 = np.array([p.te0_arcsec for p in pts]) / 206264.806           # rad
    te0_curv = 2.0 * np.polyfit(phi[pitch], te0[pitch], 2)[0]         # TE0'', rad/rad^2
    s = np.polyfit(phi[pitch], theta[pitch], 1)[0]
    v2 = np.array([p.v2 for p in pts])
    dv2 = np.polyfit(phi[pitch], v2[pitch], 1)[0]
    along_path = dv2 * (-s / te0_curv)
    # local shift at P0's pinion phase
    mp, kin = res.mean_point, pair.kinematics()
    pin, gear = flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")
    rot1, rot2 = kin.pinion_pose(mp.phi1_rad)[0], kin.gear_pose(mp.phi2_rad)[0]
    sp1, sp2 = pin.point(mp.u1, mp.v1), gear.point(mp.u2, mp.v2)
    frame = flank_frame(sp2, rot2)
    basis, n0, r0 = frame[:, :2], frame[:, 2], np.asarray(mp.point_mm)
    h1 = -curvature_tensor(sp1, rot1, basis)        # pinion normal is -n0
    h2 = curvature_tensor(sp2, rot2, basis)
    th0 = (n0 @ d) / (n0 @ np.cross(Z, r0))
    q = np.linalg.solve(h1 - h2, h1 @ (basis.T @ d) - th0 * h2 @ (basis.T @ np.cross(Z, r0))
                        + th0 * (basis.T @ np.cross(n0, Z)))
    jac = basis.T @ (rot2 @ np.column_stack([sp2.r_u, sp2.r_v]))
    local = np.linalg.solve(jac, q)[1]               # (du2, dv2) -> dv2
    return along_path + local
