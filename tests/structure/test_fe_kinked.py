"""The FE tooth (gearcontact.structure.fe) of a member with a kinked (Toprem) flank.

Truths:
- each kink gets a node row (structure.fe.flank_rows): its nodes lie on both pieces
  of the flank (the kink line, where the pieces intersect: 1e-9 mm, the bisection's
  rounding), every other flank node on the piece that holds it (evaluated piece by
  piece, geometry.kinked.KinkedFlank.evaluate_piece, 1e-9 mm) and every cell between
  two rows on one piece (no row pair straddles the kink);
- the tetrahedra keep the orientation of the nominal mesh's (none flips or collapses);
- a pair without relief (relief 0) meshes the nominal rows (no moved row);
- (slow) bending --fe runs on the relieved test pair (tests/data/toprem) with default
  options (the console script): the real root, the default mesh's node count (rows
  moved, none added), the line-load deflection rising with height (a cantilever);
- (slow) the kink row changes the tooth's distributed-load compliance by less than the
  FE's own refinement (n_eta 6 -> 12) does.
"""

import dataclasses
import functools
import json

import numpy as np
import pytest
from console_script import run_console

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.kinked import KinkedFlank
from gearcontact.geometry.pair import load_pair
from gearcontact.structure import fe as fe_module
from gearcontact.structure.compliance import FeMesh, flank_compliance
from gearcontact.structure.fe import KINK_CELL, build_fe, fe_node_count, flank_rows
from gearcontact.structure.tooth import tooth_geometry
from gearcontact.validation import InputRangeError

pytest.importorskip("skfem")

TOPREM = "tests/data/toprem/iso23509_f2_toprem.toml"


@pytest.fixture(scope="module")
def toprem():
    pair = load_pair(TOPREM)
    return pair, build_flanks(pair)


def _signed_volumes(p, t):
    a, b, c, d = (p[:, t[k]] for k in range(4))
    return np.einsum("in,in->n", np.cross(b - a, c - a, axis=0), d - a)


def _flank_nodes(model, side):
    """Vertex positions (n_xi + 1, n_eta + 1, 3) of the flank ``side``'s nodes and the
    tooth coordinates (xi, eta) of each."""
    xi = np.repeat(model.xi_levels, len(model.eta_levels))
    eta = np.tile(model.eta_levels, len(model.xi_levels))
    pts, vert = model.node_points(side, xi, eta)
    shape = (len(model.xi_levels), len(model.eta_levels))
    return (model.vertex_positions_mm(vert).reshape(shape + (3,)), pts.xi.reshape(shape),
            pts.eta.reshape(shape))


def test_kink_rows_lie_on_the_kink_and_cells_on_one_piece(toprem):
    pair, flanks = toprem
    tooth = tooth_geometry(flanks, "pinion", material=pair.pinion_material)
    # the default mesh's rows (n_eta 6) on a small mesh otherwise (the ellipse rim)
    kw = dict(n_xi=6, n_eta=6, n_zeta=1, n_rim=1)
    model = build_fe(tooth, **kw)
    nominal = build_fe(tooth, on_kinks=False, **kw)
    assert model.kink_rows == {"coast": (1,), "drive": (1,)}
    assert model.n_nodes == nominal.n_nodes
    for side in ("coast", "drive"):
        flank = getattr(tooth, side)
        assert isinstance(flank, KinkedFlank) and len(flank.kinks) == 1
        r, xi, eta = _flank_nodes(model, side)
        u, v = tooth.flank_parameters(side, xi, eta)
        turn = tooth.coast_turn if side == "coast" else np.eye(3)
        on = [flank.evaluate_piece(k, u, v, second=False).r @ turn.T for k in (0, 1)]
        # the kink row on the flank's own kink line (its 41-node spline: 5e-8 mm off the
        # solved kink between nodes, tests/geometry/test_kinked.py; 1e-6 mm asserted)
        # and on both pieces (their intersection, solved by bisection to rounding;
        # 1e-9 mm as the kink line's own test; measured 7e-15 mm, and the row 2e-8 mm
        # in u off the flank's spline, which would put it 1e-9 mm off a piece)
        u_k = flank.kinks[0].u(v[:, 1])
        assert np.max(np.abs(u[:, 1] - u_k)) < 1e-6
        for k in (0, 1):
            assert np.max(np.linalg.norm(r[:, 1] - on[k][:, 1], axis=-1)) < 1e-9
        # the other nodes on their own piece (the root row below the kink, the rest
        # above), 1e-9 mm: the mesh evaluates the flank, the check each piece itself
        assert np.max(np.linalg.norm(r[:, 0] - on[0][:, 0], axis=-1)) < 1e-9
        assert np.max(np.linalg.norm(r[:, 2:] - on[1][:, 2:], axis=-1)) < 1e-9
        # every cell between two rows on one piece: 9 points along each cell of each
        # column hold one piece, the kink only at a kink row
        s = np.linspace(0.0, 1.0, 9)
        uc = u[:, :-1, None] + s * np.diff(u, axis=1)[:, :, None]
        vc = np.broadcast_to(v[:, :-1, None], uc.shape)
        dist = uc - flank.kinks[0].u(vc)
        inner = dist[:, :, 1:-1]
        assert np.all((inner < 0) == (inner[:, :, :1] < 0))       # one side per cell
        # the nominal mesh (today's) cuts across the kink: row 1 at eta = -2/3 above it
        r0, xi0, eta0 = _flank_nodes(nominal, side)
        u0 = tooth.flank_parameters(side, xi0, eta0)[0]
        assert np.all(u0[:, 0] < u_k) and np.all(u0[:, 1] > u_k)
        # only the kink row moved (the window of one row), the others are nominal
        np.testing.assert_array_equal(eta[:, [0, 2, 3, 4, 5, 6]], eta0[:, [0, 2, 3, 4, 5, 6]])
        # the cells beside it at least KINK_CELL / 2 nominal rows high (the row rule)
        assert np.diff(eta, axis=1).min() >= 0.5 * KINK_CELL * 2.0 / 6
    # no tetrahedron flips or collapses: the same orientation as the nominal mesh's
    # (one index mesh), volumes at least 10 % of their nominal ones (measured 0.30)
    np.testing.assert_array_equal(model.tetrahedra, nominal.tetrahedra)
    every = np.arange(model.tetrahedra.max() + 1)
    vk, vn = (_signed_volumes(m.vertex_positions_mm(every).T, m.tetrahedra)
              for m in (model, nominal))
    assert np.all(np.sign(vk) == np.sign(vn)) and np.all(vn != 0.0)
    assert np.min(vk / vn) > 0.1


def test_a_pair_without_relief_meshes_the_nominal_rows(toprem):
    # relief 0 on the toprem pair's blades: no kink, no moved row (the mesh as before
    # the kink rows; docs/bending.md records compliance.json of s0003, the cylindrical
    # examples and the unrelieved F.2 machine pair identical before and after)
    pair, _ = toprem
    flat = dataclasses.replace(pair, machine=tuple(
        dataclasses.replace(s, blade=dataclasses.replace(s.blade, toprem_angle_deg=0.0))
        for s in pair.machine))
    tooth = tooth_geometry(build_flanks(flat), "pinion", material=flat.pinion_material)
    assert not isinstance(tooth.drive, KinkedFlank)
    m = build_fe(tooth, n_xi=6, n_eta=3, n_zeta=1, n_rim=1)
    assert m.flank_eta is None and m.kink_rows == {"coast": (), "drive": ()}


def test_kink_rows_on_synthetic_heights():
    # the row rule alone (structure.fe._rows_on_kinks): a kink sweeping from near the
    # root (eta -0.95: its row 2, kept 2 KINK_CELL rows inside) to eta 0.3 over 5
    # columns, 6 rows
    rows_of = fe_module._rows_on_kinks
    nominal = np.linspace(-1.0, 1.0, 7)
    kink = np.array([-0.95, -0.6, -0.2, 0.1, 0.3])
    rows, kr = rows_of([kink], nominal, 5, "drive")
    h = 2.0 / 6
    j = kr[0]
    assert kr == (2,)                           # nearest the mean height -0.27
    np.testing.assert_allclose(rows[:, j], np.clip(kink, -1 + 2 * KINK_CELL * h, 1.0), atol=0.0)
    assert np.diff(rows, axis=1).min() >= 0.5 * KINK_CELL * h
    assert np.all(rows[:, [0, -1]] == [-1.0, 1.0])
    # no kink: the nominal rows in every column
    rows, kr = rows_of([], nominal, 5, "drive")
    assert kr == () and np.array_equal(rows, np.broadcast_to(nominal, (5, 7)))
    # two kinks need two interior rows: 2 cells cannot hold them
    with pytest.raises(InputRangeError, match="n_eta"):
        rows_of([kink, kink + 0.3], np.linspace(-1.0, 1.0, 3), 5, "drive")
    # a plate body has no kinks: nominal rows
    from gearcontact.materials import Material
    from gearcontact.structure.tooth import RectangularPlate
    plate = RectangularPlate(10.0, 4.0, 2.0, Material(200_000.0, 0.3))
    rows, kr = flank_rows(plate, np.linspace(-1, 1, 5), 4)
    assert kr == {"coast": (), "drive": ()}


@pytest.mark.slow
def test_bending_fe_on_the_toprem_pair(tmp_path):
    # the console script with default options on the relieved pinion: 16 s of CPU,
    # 13 s wall on an idle machine, 28-31 s at load average 6 on 2 cores
    out = tmp_path / "b"
    code, _, err = run_console("bending", "--pair", TOPREM, "--member", "pinion", "--fe",
                               "--out", out)
    assert code == 0, err
    data = json.loads((out / "compliance.json").read_text())
    assert data["fe_root"] == "cutter" and data["fe_root_note"] is None
    assert data["fe_nodes"] == fe_node_count(12, 6, 3, 4, root=True)   # rows moved, none added
    # a cantilever deflects more under a line load the higher it acts (3 heights)
    line = np.array(data["line_fe_mm_per_n"])
    assert np.all(np.diff(line) > 0), line
    ratio = np.array(data["ratio_shell_to_fe"])
    assert np.all(np.abs(ratio - 1) <= 0.25)   # tests/structure/test_fe.py states why


@pytest.mark.slow
def test_kink_row_changes_compliance_less_than_refinement(toprem, monkeypatch):
    # ~50 s: the relieved pinion's FE (real root) at the default mesh with and without
    # the kink row, and refined over the height (n_eta 12, the lattice heights still
    # rows). Measured: the kink row changes the segment loads by <= 1.8e-4 and the line
    # loads by <= 1.4e-4 (relative); the refinement by <= 1.1e-3 and 7.2e-4. The
    # kink lies 0.3..0.6 mm above the root line, where the 2 deg relief is a few um.
    pair, flanks = toprem
    orig = fe_module.build_fe
    got = {}
    for mesh, on in (((12, 6, 3, 4), True), ((12, 6, 3, 4), False), ((12, 12, 3, 4), False)):
        monkeypatch.setattr(fe_module, "build_fe", functools.partial(orig, on_kinks=on))
        r = flank_compliance(pair, "pinion", flanks=flanks, fe=True, fe_mesh=FeMesh(*mesh))
        got[mesh, on] = np.concatenate([r.segment_fe_mm_per_n, r.line_fe_mm_per_n])
    base = got[(12, 6, 3, 4), False]
    kink = np.abs(got[(12, 6, 3, 4), True] / base - 1.0).max()
    refine = np.abs(got[(12, 12, 3, 4), False] / base - 1.0).max()
    assert 0.0 < kink < refine, (kink, refine)
