"""``gearcontact bending`` end to end through :func:`gearcontact.cli.main`.

Truths: the files and JSON keys of the issue (points_mm, shell_mm_per_n, with --fe
fe_mm_per_n and fe_nodes); the shell matrix is symmetric (Maxwell-Betti) and its points
lie on the real drive flank of the gear tooth (distance to the flank surface from the
exact blade cone, < 1e-9 mm); shell vs FE distributed-load ratios within 25 %
(test_fe states why); bad input -> exit 2.
"""

import json

import numpy as np
import pytest

from gearcontact.cli import main


def test_bending_gear_with_fe(tmp_path, s0003_centred):
    pytest.importorskip("skfem")
    out = tmp_path / "b"
    assert main(["bending", "--pair", "s0003-centred", "--member", "gear", "--out", str(out),
                 "--fe", "--points", "3", "2"]) == 0
    data = json.loads((out / "compliance.json").read_text())
    for key in ("points_mm", "shell_mm_per_n", "fe_mm_per_n", "fe_nodes"):
        assert key in data, key
    assert data["fe_root"] == "cutter" and data["fe_root_note"] is None   # the default
    assert (out / "deflection.png").stat().st_size > 0
    G = np.array(data["shell_mm_per_n"])
    assert G.shape == (6, 6) and np.allclose(G, G.T, rtol=1e-12)
    assert data["fe_nodes"] > 1000
    ratio = np.array(data["ratio_shell_to_fe"])
    assert np.all(np.abs(ratio - 1) <= 0.25)   # tests/structure/test_fe.py states why
    # the points are on the gear drive flank: solve the exact cone for (u, v) and compare
    pair, flanks = s0003_centred            # the session's build_flanks(s0003-centred)
    flank = flanks.gear.drive
    from gearcontact.structure.tooth import tooth_geometry

    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    u, v = tooth.flank_parameters("drive", np.array(data["xi"]), np.array(data["eta"]))
    assert np.allclose(flank.evaluate(u, v).r, np.array(data["points_mm"]), atol=1e-9)


def test_bending_bad_input(tmp_path, capsys):
    assert main(["bending", "--member", "pinion", "--order", "0", "--out",
                 str(tmp_path / "x"), "--no-figures"]) == 2
    assert "order" in capsys.readouterr().err


def test_bending_samples_the_design_side(tmp_path, s0003_calibrated):
    """s0003 runs on its coast flanks: without ``--side`` the lattice lies on the gear
    tooth's coast flank (the tooth's own coast face, exact to 1e-12 mm), with
    ``--side drive`` on the drive flank, 1-2.3 mm away; the point compliance is symmetric
    (Maxwell-Betti) on both and differs between the flanks (load offset and tilt
    against the mid-surface: measured 2-26 %)."""
    from gearcontact.structure.tooth import tooth_geometry

    data = {}
    for side in (None, "drive"):
        out = tmp_path / str(side)
        extra = [] if side is None else ["--side", side]
        assert main(["bending", "--pair", "s0003", "--member", "gear", "--out", str(out),
                     "--no-figures", *extra]) == 0
        data[side] = json.loads((out / "compliance.json").read_text())
    pair, flanks = s0003_calibrated          # the session's build_flanks(s0003)
    assert pair.design_side == "coast" and data[None]["side"] == "coast"
    assert data["drive"]["side"] == "drive"
    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    for side, key in (("coast", None), ("drive", "drive")):
        d = data[key]
        pts = tooth.points_at(side, np.array(d["xi"]), np.array(d["eta"])).position_mm
        assert np.allclose(pts, np.array(d["points_mm"]), atol=1e-12)
        G = np.array(d["shell_mm_per_n"])
        assert np.allclose(G, G.T, rtol=1e-12)
    gap = np.linalg.norm(np.array(data[None]["points_mm"]) - np.array(data["drive"]["points_mm"]),
                         axis=1)
    assert gap.min() > 1.0
    ratio = np.array(data[None]["shell_mm_per_n"]) / np.array(data["drive"]["shell_mm_per_n"])
    assert ratio.max() > 1.02


@pytest.mark.parametrize("mesh, needle", [
    ("1 6 3 4", "--fe-mesh NXI = 1 is outside the allowed range: an integer in [6, 32]"),
    ("5 6 3 4", "[6, 32]"),                           # was "n_xi >= 6" after the pair
    ("12 1 3 4", "--fe-mesh NETA = 1"),               # was n_eta in build_fe
    ("64 64 64 64", "--fe-mesh NXI = 64"),            # was "1612 inverted cells"
    ("12 6 3 12", "--fe-mesh NRIM = 12"),             # 2 inverted rim cells on s0003
    ("32 16 8 8", "this mesh has 69,615"),            # 65 (17 * 25 + 38 * 17) P2 nodes
    ("28 8 4 6", "cutter root; this mesh has 23,883"),   # 24 8 4 6 (20,531) is accepted
])
def test_fe_mesh_range_is_the_accepted_one(tmp_path, capsys, monkeypatch, mesh, needle):
    """Issue 28 probe: --fe-mesh advertised [1, 64] and rejected 1-5 or inverted cells
    after the work had begun; the ranges in --help are now the ones accepted, checked
    before any work."""
    import gearcontact.cli.bending as cli_bending

    # the first work is the pair's preparation (its flanks, a synthesis if needed)
    monkeypatch.setattr(cli_bending, "load_pair_for",
                        lambda *a, **k: pytest.fail("the work started"))
    code = main(["bending", "--fe", "--fe-mesh", *mesh.split(), "--out",
                 str(tmp_path / "x"), "--no-figures"])
    err = capsys.readouterr().err
    assert code == 2 and needle in err, err
    assert not (tmp_path / "x").exists()


def test_fe_mesh_help_states_the_accepted_ranges(capsys):
    from gearcontact.cli.bending import FE_MESH_RANGES, MAX_FE_NODES, fe_nodes

    # the real root (default) adds the slot bottoms beside the rim block and the fillet
    # zone's layers beside the tooth; structure.fe.fe_node_count is checked against the
    # built meshes in tests/structure/test_root_fillet.py
    assert fe_nodes(12, 6, 3, 4, "ellipse") == 25 * 21 * 7 == 3675
    assert fe_nodes(12, 6, 3, 4) == 25 * (9 * 15 + 18 * 7) == 6525
    with pytest.raises(SystemExit):
        main(["bending", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert ("face (6-32), height (2-16), thickness (1-8) and rim (1-8), at most 21,000 P2 "
            "nodes") in text
    assert MAX_FE_NODES == 21_000 and FE_MESH_RANGES["NXI"] == (6, 32)


def test_bending_cylindrical_fe_on_the_real_root(tmp_path, capsys):
    """A cylindrical pair: the FE meshes the real root (the rack's trochoids) by default
    and the ellipse root on request, and says which (``fe_root``, the printed line); the
    lattice lies on the flank the pair's drive mesh loads (the clockwise facing one, the
    tooth's "coast" side; exact to 1e-12 mm). A small mesh (6 x 2 x 1 + 1: ~1 s)."""
    pytest.importorskip("skfem")
    from gearcontact.geometry.pair import load_pair
    from gearcontact.structure.cylindrical_tooth import cylindrical_tooth

    pair_file = "examples/spur_20x40_m3.toml"
    data = {}
    for root in (None, "ellipse"):
        out = tmp_path / str(root)
        extra = [] if root is None else ["--fe-root", root]
        assert main(["bending", "--pair", pair_file, "--member", "gear", "--out", str(out),
                     "--no-figures", "--fe", "--fe-mesh", "6", "2", "1", "1", *extra]) == 0
        data[root] = json.loads((out / "compliance.json").read_text())
        printed = capsys.readouterr().out
        assert f"FE ({root or 'cutter'} root" in printed
        assert "points on the flank the drive mesh loads (the tooth's coast side)" in printed
    assert data[None]["fe_root"] == "cutter" and data["ellipse"]["fe_root"] == "ellipse"
    assert data[None]["line_fe_mm_per_n"] != data["ellipse"]["line_fe_mm_per_n"]
    d = data[None]
    assert d["side"] == "coast"
    tooth = cylindrical_tooth(load_pair(pair_file, kinds=("cylindrical",)), "gear")
    pts = tooth.points_at("coast", np.array(d["xi"]), np.array(d["eta"])).position_mm
    assert np.allclose(pts, np.array(d["points_mm"]), atol=1e-12)
