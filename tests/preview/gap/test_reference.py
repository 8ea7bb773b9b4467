"""fp64 gap reference against analytic geometry (plane of samples, known offsets)."""

import numpy as np
import pytest

from gearcontact.preview.gap.reference import (gap_reference, gap_sample_terms,
                                               validate_gap_inputs)
from gearcontact.validation import InputRangeError

# Tolerance 1e-12 mm: every analytic case below involves a handful of fp64 operations
# on O(10 mm) numbers (rounding ~1e-15 relative).
TOL = 1e-12


def plane(n_side=4, spacing=1.0):
    """Samples on z = 0 with unit normal +z, row-major grid."""
    xs = (np.arange(n_side) - (n_side - 1) / 2) * spacing
    gx, gy = np.meshgrid(xs, xs)
    g = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
    return g, np.tile([0.0, 0.0, 1.0], (g.shape[0], 1))


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def test_plane_gap_and_residual_are_analytic():
    g, n = plane()
    h, ang = 0.37, 0.3
    p_body = rot_z(ang).T @ np.array([0.1, -0.2, h])     # posed point (0.1, -0.2, h)
    terms = gap_sample_terms(rot_z(ang), np.zeros(3), p_body, g, n)
    # d = p' - g has z-component h: gamma = -h for every sample; rho = lateral dist^2
    np.testing.assert_allclose(terms.gamma_mm, -h, atol=TOL)
    lat = (0.1 - g[:, 0]) ** 2 + (-0.2 - g[:, 1]) ** 2
    np.testing.assert_allclose(terms.rho_mm2, lat, atol=TOL)


def test_gate_picks_nearest_normal_line_and_rejects_all():
    g, n = plane(spacing=1.0)  # only (0.5, -0.5) = idx 6 is within 0.6 mm of (0.1, -0.2)
    t = np.array([0.1, -0.2, 0.25])
    res = gap_reference(np.eye(3), t, np.zeros(3), g, n, tau_mm=0.6)
    assert res.valid and res.min_idx == 6
    assert abs(res.min_gap_mm + 0.25) < TOL
    none = gap_reference(np.eye(3), t, np.zeros(3), g, n, tau_mm=0.1)
    assert not none.valid and none.min_idx == -1 and np.isnan(none.min_gap_mm)


def test_ideal_rule_minimum_abs_gap_and_ties():
    g, n = plane()
    g = g.copy()
    g[:, 2] = 0.5 + np.arange(16) * 0.01   # sample heights; point at z = 0: gamma = g_z
    g[3, 2] = 0.005                        # |gamma| = 0.005 at index 3 (penetration)
    g[9, 2] = -0.005                       # |gamma| = 0.005 at index 9: tie -> index 3
    res = gap_reference(np.eye(3), np.zeros(3), np.zeros(3), g, n, tau_mm=10.0)
    assert res.valid and res.min_idx == 3 and abs(res.min_gap_mm - 0.005) < TOL


def test_lane_rule_equals_ideal_when_one_sample_per_lane():
    rng = np.random.default_rng(7)
    for _ in range(20):
        g = rng.uniform(-3, 3, (16, 3))
        n = rng.normal(size=(16, 3))
        n /= np.linalg.norm(n, axis=1)[:, None]
        args = (rot_z(rng.uniform(0, 6)), rng.uniform(-1, 1, 3), rng.uniform(-1, 1, 3), g, n)
        assert gap_reference(*args, tau_mm=2.0) == gap_reference(*args, tau_mm=2.0, lanes=16)


def test_lane_rule_differs_from_ideal_by_design():
    # two samples in lane 0 (idx 0 and 8): idx 8 is better aligned (smaller rho) but
    # has the larger |gamma|; the lane keeps idx 8, the ideal rule prefers idx 0.
    g = np.zeros((9, 3))
    g[:, 0] = np.arange(9) * 10.0 + 5.0          # far away samples (rejected by gate)
    g[0] = [0.5, 0.0, -0.01]
    g[8] = [0.1, 0.0, -0.5]
    n = np.tile([0.0, 0.0, 1.0], (9, 1))
    ideal = gap_reference(np.eye(3), np.zeros(3), np.zeros(3), g, n, tau_mm=1.0)
    lane = gap_reference(np.eye(3), np.zeros(3), np.zeros(3), g, n, tau_mm=1.0, lanes=8)
    assert (ideal.min_idx, lane.min_idx) == (0, 8)
    assert abs(ideal.min_gap_mm + 0.01) < TOL and abs(lane.min_gap_mm + 0.5) < TOL


@pytest.mark.parametrize("kwargs, field", [
    (dict(p=[np.nan, 0, 0]), "p_mm[0]"),
    (dict(R=np.eye(3) * 1.1), "R"),
    (dict(R=np.diag([1.0, 1.0, -1.0])), "R"),
    (dict(normals=[[0, 0, 1.01]] * 4), "normals[0]"),
    (dict(samples=np.zeros((4, 2))), "samples_xyz_mm.shape"),
    (dict(normals=[[0, 0, 1.0]] * 3), "normals.shape"),
    (dict(t=[0, 0]), "t_mm.shape"),
])
def test_bad_inputs_name_the_field(kwargs, field):
    args = dict(R=np.eye(3), t=np.zeros(3), p=np.zeros(3), samples=np.zeros((4, 3)),
                normals=[[0, 0, 1.0]] * 4)
    args.update(kwargs)
    with pytest.raises(InputRangeError) as exc:
        validate_gap_inputs(args["R"], args["t"], args["p"], args["samples"], args["normals"])
    assert exc.value.field == field


@pytest.mark.parametrize("tau, lanes", [(0.0, None), (np.inf, None), (1.0, 12), (1.0, 128)])
def test_bad_gate_or_lanes(tau, lanes):
    g, n = plane()
    with pytest.raises(InputRangeError):
        gap_reference(np.eye(3), np.zeros(3), np.zeros(3), g, n, tau_mm=tau, lanes=lanes)
