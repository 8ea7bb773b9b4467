"""Compiled gap-field intersections (:mod:`gearcontact.tca.gap_kernel`).

Truths: (1) the compiled surface evaluations equal the flanks' own ``evaluate``
(FITPACK spline / closed-form cone), inside and beyond the parameter boxes; (2) on
s0003 the compiled gap fields equal the vectorized numpy path of :mod:`.stencil`
(the pre-kernel implementation, still used for surfaces without a compiled form) to
1e-9 mm, with identical on-flank masks; (3) on a sheet with a linear psi field
(reproduced exactly by the quintic spline) each intersection matches an independent
scalar root of the line against the closed-form surface.
"""

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcontact.geometry.formate import FlankBoundary, cone_vector
from gearcontact.geometry.sheet import PinionCone, RadialSheet
from gearcontact.tca import stencil
from gearcontact.tca.gap_kernel import kernel_surface, sheet_point


def _numpy_path(monkeypatch):
    monkeypatch.setattr(stencil, "kernel_surface", lambda surface: None)


@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_compiled_evaluation_equals_flank_evaluate(s0003_centred, member):
    s0003_flanks = s0003_centred[1]
    rng = np.random.default_rng(3)
    d = np.zeros(6)
    vec = np.empty((7, 3))
    for side in ("drive", "coast"):
        surf = s0003_flanks.flank(member, side)
        kind, par, tx, ty, pc = kernel_surface(surf)[:5]   # one piece, no kink
        par, tx, ty, pc = par[0], tx[0], ty[0], pc[0]
        lo = np.array([surf.u_range[0], surf.v_range[0]])
        hi = np.array([surf.u_range[1], surf.v_range[1]])
        inner = lo + (hi - lo) * rng.random((300, 2))
        # beyond the box: positions continue as the flank's own evaluate does
        outer = lo - 0.5 * (hi - lo) + 2.0 * (hi - lo) * rng.random((300, 2))
        for uv, rows in ((inner, 3), (outer, 1)):
            ref = surf.evaluate(uv[:, 0], uv[:, 1])
            for i, (u, v) in enumerate(uv):
                if kind == 0:
                    sheet_point(par, tx, ty, pc, u, v, d, vec)
                else:
                    cone_vector(par, u, v, False, vec)
                for row, want in zip(range(rows), (ref.r, ref.r_u, ref.r_v)):
                    assert np.abs(vec[row] - want[i]).max() < 1e-10


def _fields(flanks, pair, mp, allow_outside, frame="principal"):
    pin, gear = flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")
    return stencil.gap_field(pin, gear, pair.kinematics(), mp, half_extent_mm=(4.0, 0.8),
                             side=24, frame=frame, allow_outside=allow_outside)


@pytest.mark.parametrize("allow_outside", [False, True])
def test_compiled_gap_field_equals_numpy_path(s0003_centred, s0003_drive,
                                               allow_outside, monkeypatch):
    s0003_pair, s0003_flanks = s0003_centred
    path = s0003_drive.cycle.path
    interior = np.flatnonzero(~path.edge)
    # P0, and a point near the path's end whose field is partly off the flanks
    points = [s0003_drive.mean_point, path.points[interior[3]]]
    fast = [_fields(s0003_flanks, s0003_pair, mp, allow_outside) for mp in points]
    _numpy_path(monkeypatch)
    slow = [_fields(s0003_flanks, s0003_pair, mp, allow_outside) for mp in points]
    for f, s in zip(fast, slow):
        assert np.array_equal(f.on_flank, s.on_flank)
        ok = np.isfinite(s.gap_mm)
        # wherever the numpy path converged the compiled one does, to the same root;
        # continuation points it left unconverged may converge now (off the flank)
        assert np.isfinite(f.gap_mm[ok]).all()
        assert np.isfinite(f.gap_mm[f.on_flank]).all()
        assert np.abs(f.gap_mm[ok] - s.gap_mm[ok]).max() < 1e-9
        if not allow_outside:
            assert np.array_equal(np.isfinite(f.gap_mm), ok)
    assert slow[1].on_flank.any() and not slow[1].on_flank.all()


def test_compiled_stencil_equals_numpy_path(s0003_centred, s0003_drive,
                                            monkeypatch):
    s0003_pair, s0003_flanks = s0003_centred
    pin, gear = s0003_flanks.flank("pinion", "drive"), s0003_flanks.flank("gear", "drive")
    kin, mp = s0003_pair.kinematics(), s0003_drive.mean_point
    fast = stencil.hardware_stencil(pin, gear, kin, mp, off_flank="quadric")
    _numpy_path(monkeypatch)
    slow = stencil.hardware_stencil(pin, gear, kin, mp, off_flank="quadric")
    assert np.array_equal(fast.on_flank, slow.on_flank)
    assert np.abs(fast.gap_mm - slow.gap_mm).max() < 1e-9


def _linear_sheet():
    cone = PinionCone(apex_x_mm=-40.0, tan_delta=0.12, root_offset_mm=0.6)
    u, v = np.linspace(-0.2, 3.2, 14), np.linspace(-0.3, 12.3, 17)
    U, V = np.meshgrid(u, v, indexing="ij")
    psi = 0.4 + 0.05 * U - 0.01 * V
    return RadialSheet(side="drive", cone=cone, u_nodes=u, v_nodes=v, psi_nodes=psi,
                       normal_sign=1.0, boundary=FlankBoundary(0.0, 3.0, 0.0, 12.0))


def test_sheet_intersections_match_closed_form():
    sheet = _linear_sheet()
    rot = np.eye(3)
    c = np.array([0.0, 0.5, -0.3])
    u0, v0 = 1.5, 6.0
    sp = sheet.point(u0, v0)
    n = np.cross(sp.r_u, sp.r_v)
    n /= np.linalg.norm(n)
    e1 = sp.r_u / np.linalg.norm(sp.r_u)
    e2 = np.cross(n, e1)
    st = np.stack(np.meshgrid(np.linspace(-1.0, 1.0, 9), np.linspace(-2.0, 2.0, 11)), -1)
    q = sp.r + c + st.reshape(-1, 2) @ np.stack([e1, e2])
    jac = np.stack([e1, e2]) @ np.column_stack([sp.r_u, sp.r_v])
    uv0 = np.array([u0, v0]) + st.reshape(-1, 2) @ np.linalg.inv(jac).T
    lam, inside = stencil._intersect_many(sheet, (rot, c), q, n, uv0, clamp=True,
                                          tol_mm=1e-11, sweep=stencil._sweep(
                                              st.reshape(-1, 2), st.shape[:2]))
    assert inside.all()

    def f(t, qi):
        x = qi + t * n - c
        radius = np.hypot(x[1], x[2])
        u = radius - sheet.cone.root_radius_mm(x[0])
        return np.arctan2(x[2], x[1]) - (0.4 + 0.05 * u - 0.01 * x[0])

    truth = np.array([brentq(f, -1.0, 1.0, args=(qi,), xtol=1e-15) for qi in q])
    assert np.abs(lam - truth).max() < 1e-9


def test_cone_lines_closed_form(s0003_centred):
    # a line through a flank point along its normal meets the blade cone there
    # (lambda = 0 to rounding) and again across the cutter (the far root is not
    # taken); a line parallel to the axis at the axis never meets it (NaN)
    from gearcontact.tca.gap_kernel import cone_lines
    s0003_flanks = s0003_centred[1]
    gear = s0003_flanks.flank("gear", "drive")
    par = gear.kernel_parameters
    rot, trans = np.eye(3), np.zeros(3)
    lo = np.array([gear.u_range[0], gear.v_range[0]])
    hi = np.array([gear.u_range[1], gear.v_range[1]])
    rng = np.random.default_rng(5)
    uv = lo + (hi - lo) * (0.1 + 0.8 * rng.random((50, 2)))
    pts = [gear.point(u, v) for u, v in uv]
    for sp, (u, v) in zip(pts, uv):
        shift = 0.3 * sp.n                                 # start 0.3 mm off the flank
        uv_out = np.empty((1, 2))
        lam, ins = cone_lines(par, rot, trans, (sp.r + shift)[None, :], sp.n,
                              np.array([[u, v]]), lo, hi, True, uv_out)
        assert ins[0] and abs(lam[0] + 0.3) < 1e-12
        # the root's (u, v) is the flank point's (rounding of the inverse map)
        assert np.abs(uv_out[0] - (u, v)).max() < 1e-9
    axis_line = par[0:3][None, :]
    uv_out = np.zeros((1, 2))
    lam, ins = cone_lines(par, rot, trans, axis_line, par[3:6], np.zeros((1, 2)), lo, hi,
                          False, uv_out)
    assert np.isnan(lam[0]) and not ins[0] and np.isnan(uv_out).all()
