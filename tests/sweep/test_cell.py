"""One grid point (:func:`gearcontact.sweep.cell.compute_point`): the pattern shift of
a pure E or P error against the first-order kinematics.

Truth (first order in the pinion translation ``d``: ``d = (0, -E, 0)`` for E, ``(P, 0,
0)`` for P, docs/sweeps.md), from the nominal set-up's geometry alone:

1. *Path shift.* At the contact ``r`` with gear normal ``n`` the translation is taken up
   by a gear rotation ``theta = n.d / n.(z x r)`` (tests/geometry/test_kinematics.py),
   i.e. the TE of a pair changes by ``theta(phi1)`` along its path. Each pair's TE0 is
   a parabola ``TE0''/2 (phi1 - phi_v)^2`` about its vertex, all pairs alike one pitch
   apart, so a tilt ``s = d theta / d phi1`` moves every vertex, and with them the
   crossings of neighbouring parabolas that bound the transmitting segment, by
   ``d phi1 = -s / TE0''``; the pattern moves along the path by ``(dv2/dphi1) d phi1``.
2. *Local shift at a held phase.* With the gap ``g(q) = q^T B q / 2`` (B relative
   curvature in the tangent plane, ``B = H1 - H2`` with the flanks' height curvatures
   along the gear normal) the moved pinion and the turned gear add a linear term whose
   minimum moves the contact by ``q = B^-1 [H1 d_t - theta H2 (z x r)_t + theta (n x
   z)_t]`` (Litvin & Fuentes 2004, sec. 9.4-9.5, contact-point displacement from the
   relations between the curvatures).

The sum along the gear face (v2) is compared with the sweep's pattern-centre shift,
symmetrised ``(shift(+e) - shift(-e)) / 2`` (the even second-order part cancels),
within 10 % (measured: 3 % for E, 1 % for P at 10 um); the height shift is below a
tenth of the face shift in both.
"""

import numpy as np
import pytest

from gearcontact.sweep.cell import compute_point
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.curvature import curvature_tensor, flank_frame

PHASES = 61      # the vertex and the segment ends are read on the sampled phases
STEP_MM = 0.01
Z = np.array([0.0, 0.0, 1.0])


@pytest.fixture(scope="module")
def nominal(s0003_centred):
    pair, flanks = s0003_centred
    res, _ = analyze_pair(pair, side="drive", phases=PHASES, flanks=flanks)
    return res, compute_point(pair, flanks, {}, [64.5], side="drive", compute=("tca",),
                              phases=PHASES)


def _predicted_face_shift_mm(res, pair, flanks, d) -> float:
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


@pytest.mark.parametrize("key,direction", [("E_mm", (0.0, -1.0, 0.0)),
                                           ("P_mm", (1.0, 0.0, 0.0))])
def test_pure_e_or_p_moves_the_pattern_as_the_kinematics_predict(s0003_centred, nominal,
                                                                 key, direction):
    pair, flanks = s0003_centred
    res, base = nominal
    d = STEP_MM * np.array(direction)
    want = _predicted_face_shift_mm(res, pair, flanks, d)
    got = {}
    for sign in (1, -1):
        c = compute_point(pair, flanks, {key: sign * STEP_MM}, [64.5], side="drive",
                          compute=("tca",), phases=PHASES)
        assert c["error"] == [""]
        got[sign] = (c["pattern_face_mm"][0] - base["pattern_face_mm"][0],
                     c["pattern_height_mm"][0] - base["pattern_height_mm"][0])
    face = 0.5 * (got[1][0] - got[-1][0])
    height = 0.5 * (got[1][1] - got[-1][1])
    assert abs(want) > 0.2                    # a real move: tenths of a mm per 10 um
    assert face == pytest.approx(want, rel=0.10)
    assert abs(height) < 0.1 * abs(face)
