"""Compiled gap-field intersections (:mod:`gearcontact.tca.gap_kernel`).

Truths: (1) the compiled surface evaluations equal the flanks' own ``evaluate``
(FITPACK spline / closed-form cone), inside and beyond the parameter boxes; (2) on
s0003 the compiled gap fields equal the vectorized numpy path of :mod:`.stencil`
(the pre-kernel implementation, still used for surfaces without a compiled form) to
1e-9 mm, with identical on-flank masks; (3) on a sheet with a linear psi field
(reproduced exactly by the quintic spline) each intersection matches an independent
scalar root of the line against the closed-form surface; (4) on a relieved pinion
(geometry.kinked), a relieved formate gear (blade cones at scaled v) and a relieved
generated gear (generated gear sheets) lines through
flank points on both sides of the kink meet the flank at those points, on the compiled
and the numpy path, the compiled kink tables are the kink lines and the compiled point
evaluation is the flank's own.
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


# --- relieved flanks (geometry.kinked): the compiled path on the piece of each iterate

@pytest.fixture(scope="module")
def kinked_pinion():
    """The ISO 23509 F.2 pinion drive flank (examples/machine_settings) with a 2 deg
    Toprem from 2 mm, on a coarse node grid (seconds): kink line inside the flank."""
    import dataclasses

    from gearcontact.geometry.kinked import machine_flank
    from gearcontact.geometry.pair import load_pair

    pair = load_pair("examples/machine_settings/iso23509_f2_machine.toml")
    setup = next(s for s in pair.machine if (s.member, s.side) == ("pinion", "drive"))
    setup = dataclasses.replace(setup, blade=dataclasses.replace(
        setup.blade, toprem_angle_deg=2.0, toprem_depth_mm=2.0))
    return machine_flank(setup, pair.blank, face_width_mm=pair.pinion_face_width_mm,
                         n_u=24, n_v=30)


def test_kink_tables_equal_the_kink_lines(kinked_pinion):
    from scipy.interpolate import CubicSpline

    from gearcontact.geometry.kinked import KinkLine, kink_u

    kink = kinked_pinion.kinks[0]
    lo, hi = kinked_pinion.v_range
    v = np.linspace(lo - 0.3 * (hi - lo), hi + 0.3 * (hi - lo), 997)   # ends continued
    x, c = kink.pp_table
    got = np.array([kink_u(x, c, x.size, vi) for vi in v])
    # inside the box over the whole width: scipy's cubic spline through the nodes, the
    # same piecewise cubic summed in the same order as scipy's PPoly: measured 0 (bit
    # for bit), 1e-12 mm asserted (rounding allowance, e.g. another interval pick)
    want = CubicSpline(kink.v_nodes, kink.u_nodes)(v)
    assert np.abs(got - want).max() < 1e-12 and np.abs(kink.u(v) - want).max() < 1e-12
    # a kink leaving the box (-inf below the root at the toe, +inf above the tip at the
    # heel): the cubic spline of the finite run between, the huge value of each side
    # beyond; padded tables (as KinkedFlank.kink_tables stacks kinks) read the same
    u_nodes = kink.u_nodes.copy()
    u_nodes[:5], u_nodes[-3:] = -np.inf, np.inf
    out = KinkLine("toprem", 0, kink.v_nodes, u_nodes)
    x, c = out.pp_table
    xp, cp = np.concatenate([x, [0.0, 0.0]]), np.concatenate([c, np.zeros((2, 4))])
    got = np.array([kink_u(xp, cp, x.size, vi) for vi in v])
    run = CubicSpline(kink.v_nodes[5:-3], kink.u_nodes[5:-3])
    inner = (v >= kink.v_nodes[5]) & (v < kink.v_nodes[-4])
    toe, heel = v < kink.v_nodes[4], v >= kink.v_nodes[-3]
    assert inner.sum() > 100 and toe.sum() > 100 and heel.sum() > 100
    assert np.abs(got[inner] - run(v[inner])).max() < 1e-12
    assert np.all(got[toe] == -1e300) and np.all(got[heel] == 1e300)
    assert np.array_equal(out.u(v), got)


@pytest.fixture(scope="module")
def kinked_gear():
    """The ISO 23509 F.2 formate gear drive flank (examples/machine_settings) with the
    2 deg Flankrem from 5.5 mm of tests/data/toprem/iso23509_f2_gear_flankrem.toml: two
    blade cones, the upper at a scaled v, kink line inside the flank."""
    from gearcontact.geometry.kinked import machine_flank
    from gearcontact.geometry.pair import load_pair

    pair = load_pair("tests/data/toprem/iso23509_f2_gear_flankrem.toml")
    setup = next(s for s in pair.machine if (s.member, s.side) == ("gear", "drive"))
    return machine_flank(setup, pair.blank, face_width_mm=pair.gear_face_width_mm)


@pytest.fixture(scope="module")
def kinked_generated_gear():
    """The F.2 gear generated by the crown gear of its pitch plane
    (geometry.basic_settings.generated_gear_setups, the flanks of
    tests/geometry/test_generated.py) with the same Flankrem, on a coarse node grid
    (seconds): two generated gear sheets, kink line inside the flank."""
    import dataclasses

    from gearcontact.geometry.basic_settings import generated_gear_setups
    from gearcontact.geometry.kinked import machine_flank
    from gearcontact.geometry.pair import load_pair

    pair = load_pair("examples/machine_settings/iso23509_f2_machine.toml")
    setup = generated_gear_setups(pair)["drive"]
    setup = dataclasses.replace(setup, blade=dataclasses.replace(
        setup.blade, flankrem_angle_deg=2.0, flankrem_depth_mm=5.5))
    return machine_flank(setup, pair.blank, face_width_mm=pair.gear_face_width_mm,
                         n_u=24, n_v=30)


@pytest.mark.parametrize("member", ["pinion", "gear", "generated_gear"])
def test_compiled_kinked_intersections_are_the_flank_points(request, member, monkeypatch):
    # lines through flank points on both sides of the kink line (within 1 um of it and
    # up to 0.3 mm away), along one common direction (the mean of the two pieces'
    # normals at the middle of the kink), 0.02 mm out: each meets the flank at its own
    # point, lambda = -0.02 exactly (the ridge is convex: one crossing). Newton starts
    # 0.15 mm of u and 0.4 mm of v away, so many iterations cross the kink. The pinion:
    # Newton on two radial sheets; the relieved formate gear: every cone in closed form,
    # the root its own piece holds (numpy path: Newton on the cones at scaled v); the
    # relieved generated gear: Newton on two generated gear sheets.
    flank = request.getfixturevalue(f"kinked_{member}")
    kink = flank.kinks[0]
    vm = 0.5 * sum(flank.v_range)
    um = float(kink.u(vm))
    a, b = (flank.evaluate_piece(i, um, vm) for i in (0, 1))
    n = a.n + b.n
    n /= np.linalg.norm(n)
    du = np.array([-0.3, -0.05, -1e-3, -1e-6, 1e-6, 1e-3, 0.05, 0.3])
    vs = vm + np.linspace(-3.0, 3.0, 9)
    V, D = np.meshgrid(vs, du)
    U = kink.u(V) + D
    uv = np.column_stack([U.ravel(), V.ravel()])
    sp = flank.evaluate(uv[:, 0], uv[:, 1])
    q = sp.r + 0.02 * n
    uv0 = uv + np.array([0.15, -0.4])
    pose = (np.eye(3), np.zeros(3))
    runs = {}
    for name in ("compiled", "numpy"):
        if name == "numpy":
            _numpy_path(monkeypatch)
        uv_out = np.empty_like(uv)
        lam, inside = stencil._intersect_many(flank, pose, q, n, uv0.copy(), clamp=True,
                                              tol_mm=1e-11,
                                              sweep=stencil._sweep(uv - uv.mean(0), U.shape),
                                              uv_out=uv_out)
        runs[name] = (lam, inside, uv_out)
        assert inside.all()
        # Newton to 1e-11 mm: measured 8e-15 mm (compiled) / 4e-15 mm (numpy) on the
        # pinion, 2.5e-14 / 2.8e-14 mm on the gear (closed form / Newton), 1.6e-14 /
        # 1.4e-14 mm on the generated gear; 1e-9 mm
        # asserted (the smooth flanks' compiled / numpy agreement tolerance above), the
        # parameters to 1e-8 mm (|r_u|, |r_v| ~ 1; measured 1.4e-14 / 4.2e-14)
        assert np.abs(lam + 0.02).max() < 1e-9, name
        assert np.abs(uv_out - uv).max() < 1e-8, name
        assert np.array_equal(flank.piece_index(uv_out[:, 0], uv_out[:, 1]),
                              flank.piece_index(uv[:, 0], uv[:, 1]))
    (lf, inf, uvf), (ls, ins, uvs) = runs["compiled"], runs["numpy"]
    assert np.array_equal(inf, ins) and np.abs(lf - ls).max() < 1e-9
    assert (stencil._kinks_crossed(flank, uvf) == stencil._kinks_crossed(flank, uvs)
            == [flank.kinks[0].name])


@pytest.mark.parametrize("member", ["pinion", "gear", "generated_gear"])
def test_compiled_point_of_a_kinked_flank_is_its_point(request, member):
    # flank_vector (the compiled edge search's evaluation) against KinkedFlank.point at
    # points on both sides of the kink and beyond the box: the same piece, the same
    # r, r_u, r_v (the same compiled arithmetic, cone at scale v with r_v scaled;
    # measured bit for bit, 1e-12 mm asserted as a rounding allowance)
    from gearcontact.tca.gap_kernel import flank_vector

    flank = request.getfixturevalue(f"kinked_{member}")
    form = kernel_surface(flank)
    (u0, u1), (v0, v1) = flank.u_range, flank.v_range
    rng = np.random.default_rng(11)
    uv = np.column_stack([u0 - 0.2 + (u1 - u0 + 0.4) * rng.random(400),
                          v0 - 1.0 + (v1 - v0 + 2.0) * rng.random(400)])
    k = flank.piece_index(uv[:, 0], uv[:, 1])
    assert set(k) == {0, 1}
    d, vec = np.zeros(6), np.empty((7, 3))
    for u, v in uv:
        flank_vector(*form, u, v, d, vec)
        sp = flank.point(u, v)
        assert np.abs(vec[:3] - np.array([sp.r, sp.r_u, sp.r_v])).max() < 1e-12


def test_kernel_form_of_a_kinked_flank(kinked_pinion, kinked_gear, kinked_generated_gear):
    # two pieces on one knot grid, one kink table; sheets evaluated at scaled v have no
    # compiled form (numpy path); a relieved formate gear's cones do, each with its
    # kernel parameters and its v scale (one at 1, the other not); a relieved generated
    # gear's sheets are generated gear sheets (kind 2); a smooth generated gear sheet
    # keeps the numpy path (pairs whose formate gear would undercut run on one)
    import dataclasses

    kind, par, tx, ty, pc, kx, kc, kn = kernel_surface(kinked_pinion)
    assert kind == 0 and par.shape[0] == tx.shape[0] == pc.shape[0] == 2
    assert kx.shape[0] == kc.shape[0] == kn.shape[0] == 1 and kn[0] == kx.shape[1]
    scaled = dataclasses.replace(kinked_pinion, v_scales=(1.0, 0.5))
    assert kernel_surface(scaled) is None
    kind, par, *_, kx, kc, kn = kernel_surface(kinked_gear)
    assert kind == 1 and par.shape == (2, 19) and kx.shape[0] == 1
    assert tuple(par[:, 18]) == kinked_gear.v_scales and kinked_gear.v_scales[1] != 1.0
    for row, piece in zip(par, kinked_gear.pieces):
        assert np.array_equal(row[:18], piece.kernel_parameters)
    kind, par, tx, *_, kx, kc, kn = kernel_surface(kinked_generated_gear)
    assert kind == 2 and par.shape == (2, 7) and tx.shape[0] == 2 and kx.shape[0] == 1
    assert all(kernel_surface(piece) is None for piece in kinked_generated_gear.pieces)


def _compiled_and_numpy_runs(monkeypatch, path, member, kink):
    """``(fast, slow)``: the relieved pair at ``path`` analyzed with its gap fields on
    the compiled and on the numpy path, after checking what both must share: the 80 x 80
    field and the stencil at P0 (both straddle the ``member``'s kink ``kink``) to the
    smooth flanks' 1e-9 mm with identical masks and kinks, the paint-ellipse check and
    the edges the same."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair
    from gearcontact.tca.analysis import analyze_pair

    pair = load_pair(path)
    flanks = build_flanks(pair)
    assert kernel_surface(flanks.flank(member, pair.design_side)) is not None
    fast = analyze_pair(pair, flanks=flanks)[0]
    _numpy_path(monkeypatch)
    slow = analyze_pair(pair, flanks=flanks)[0]
    for f, s in ((fast.gap_field, slow.gap_field), (fast.stencil, slow.stencil)):
        assert f.kinks == s.kinks == (kink,)
        assert np.array_equal(f.on_flank, s.on_flank)
        assert np.array_equal(np.isfinite(f.gap_mm), np.isfinite(s.gap_mm))
        ok = np.isfinite(s.gap_mm)
        assert ok.any() and np.abs(f.gap_mm[ok] - s.gap_mm[ok]).max() < 1e-9
    assert np.array_equal(fast.pattern_on_flank, slow.pattern_on_flank)
    assert fast.edges == slow.edges
    return fast, slow


@pytest.mark.slow
def test_toprem_pair_analysis_compiled_equals_numpy_path(monkeypatch):
    # ~15 s: the Toprem pair (tests/data/toprem) on both paths (_compiled_and_numpy_runs);
    # TE0 (surface and ridge contacts, not gap fields) the README's 21.4 arcsec with 18
    # of 61 phases on the ridge on both
    fast, slow = _compiled_and_numpy_runs(monkeypatch, "tests/data/toprem/iso23509_f2_toprem"
                                          ".toml", "pinion", "pinion toprem")
    for run in (fast, slow):
        assert round(run.cycle.te0_pp_arcsec, 1) == 21.4
        assert run.edge_contact_counts == {"pinion toprem": 18}


@pytest.mark.slow
def test_flankrem_gear_pair_analysis_compiled_equals_numpy_path(monkeypatch):
    # ~15 s: the relieved-gear pair (tests/data/toprem/iso23509_f2_gear_flankrem.toml)
    # on both paths (the edge search the same on both, so both have the same P0), TE0
    # and the ridge phases equal
    fast, slow = _compiled_and_numpy_runs(
        monkeypatch, "tests/data/toprem/iso23509_f2_gear_flankrem.toml", "gear",
        "gear flankrem")
    assert fast.cycle.te0_pp_arcsec == slow.cycle.te0_pp_arcsec
    assert fast.edge_contact_counts == slow.edge_contact_counts == {"gear flankrem": 23}


@pytest.mark.slow
def test_relieved_generated_gear_pair_analysis_compiled_equals_numpy_path(monkeypatch):
    # ~15 s: the F.2 pinion against the crown-generated F.2 gear with the Flankrem
    # (tests/tca/test_edge_kernel.py, generated_gear_flankrem_pair: two GearSheet
    # pieces), the gap fields on the compiled and on the numpy path (the same edge
    # search): field and stencil at P0 (the field straddles the kink, the 7 x 7 stencil
    # does not) to the smooth flanks' 1e-9 mm (measured 3.4e-14 / 1.6e-14 mm) with
    # identical masks and kinks, the same TE0 and ridge phases
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.tca.analysis import analyze_pair

    from .test_edge_kernel import generated_gear_flankrem_pair

    pair = generated_gear_flankrem_pair()
    flanks = build_flanks(pair)
    assert kernel_surface(flanks.flank("gear", pair.design_side))[0] == 2
    fast = analyze_pair(pair, flanks=flanks)[0]
    _numpy_path(monkeypatch)
    slow = analyze_pair(pair, flanks=flanks)[0]
    assert fast.gap_field.kinks == ("gear flankrem",) and fast.stencil.kinks == ()
    for f, s in ((fast.gap_field, slow.gap_field), (fast.stencil, slow.stencil)):
        assert f.kinks == s.kinks
        assert np.array_equal(f.on_flank, s.on_flank)
        assert np.array_equal(np.isfinite(f.gap_mm), np.isfinite(s.gap_mm))
        ok = np.isfinite(s.gap_mm)
        assert ok.any() and np.abs(f.gap_mm[ok] - s.gap_mm[ok]).max() < 1e-9
    assert fast.cycle.te0_pp_arcsec == slow.cycle.te0_pp_arcsec
    assert fast.edge_contact_counts == slow.edge_contact_counts == {"gear flankrem": 17}
