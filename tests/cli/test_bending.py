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


def test_bending_gear_with_fe(tmp_path):
    pytest.importorskip("skfem")
    out = tmp_path / "b"
    assert main(["bending", "--pair", "s0003-centred", "--member", "gear", "--out", str(out),
                 "--fe", "--points", "3", "2"]) == 0
    data = json.loads((out / "compliance.json").read_text())
    for key in ("points_mm", "shell_mm_per_n", "fe_mm_per_n", "fe_nodes"):
        assert key in data, key
    assert (out / "deflection.png").stat().st_size > 0
    G = np.array(data["shell_mm_per_n"])
    assert G.shape == (6, 6) and np.allclose(G, G.T, rtol=1e-12)
    assert data["fe_nodes"] > 1000
    ratio = np.array(data["ratio_shell_to_fe"])
    assert np.all(np.abs(ratio - 1) <= 0.25)   # tests/structure/test_fe.py states why
    # the points are on the gear drive flank: solve the exact cone for (u, v) and compare
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair

    pair = load_pair("s0003-centred")
    flanks = build_flanks(pair)
    flank = flanks.gear.drive
    from gearcontact.structure.tooth import tooth_geometry

    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    u, v = tooth.flank_parameters("drive", np.array(data["xi"]), np.array(data["eta"]))
    assert np.allclose(flank.evaluate(u, v).r, np.array(data["points_mm"]), atol=1e-9)


def test_bending_bad_input(tmp_path, capsys):
    assert main(["bending", "--member", "pinion", "--order", "0", "--out",
                 str(tmp_path / "x"), "--no-figures"]) == 2
    assert "order" in capsys.readouterr().err
