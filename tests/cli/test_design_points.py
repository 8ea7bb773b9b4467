"""``gearcontact design --machine-settings --target-flank`` with scattered measured points
(a measuring room's output: missing points, irregular positions; docs/export.md "The
measuring grid", geometry.point_fit).

Refusals exit 2 naming the file, the field, the value and the allowed range: those
inside the file before any flank is built, unobservable settings after the flanks and
before any fit. The slow test runs the whole command on a flank cut from known settings
and checks the written settings against them (the library's recovery:
tests/geometry/test_point_fit.py).
"""

import numpy as np
import pytest

from gearcontact.cli import main

HEAD = "member,flank,L_mm,R_mm,deviation_um\n"


def _run(path, *extra):
    return main(["design", "--pair", "s0003", "--machine-settings", "--target-flank",
                 str(path), *extra])


@pytest.mark.parametrize("rows, word", [
    # 5 points on the blank (L 27.70..43.91 mm) where the default fit has 8 settings
    ([(30.0 + k, 6.0 + 0.2 * k, 1.0) for k in range(5)],
     "m.csv: pinion coast points = 5 is outside the allowed range: at least 8, one per "
     "fitted setting (cradle_angle_deg, radial_distance_mm"),
    # two points 0.5 um apart (a point given twice, its coordinates rounded differently)
    ([(35.0, 6.5, 1.0), (36.0, 6.6, 0.0), (35.0005, 6.5, 1.2)],
     "m.csv: line 4 = 'pinion coast L = 35.0005, R = 6.5 (also line 2: L = 35.0, R = 6.5)' "
     "is outside the allowed range: each (L, R) once per flank: points more than 0.001 mm "
     "apart in L or R"),
    # NaN deviation, and a point off the blank's flank (6 mm past the heel)
    ([(35.0, 6.5, float("nan"))], "m.csv: line 2 deviation_um = 'nan' is outside the "
     "allowed range: a finite number"),
    ([(35.0, 6.5, 0.0), (50.0, 9.0, 0.0)], "m.csv: line 3 (pinion coast, L = 50.0 mm, "
     "R = 9.0 mm) = 'off the flank of the pinion blank' is outside the allowed range: "
     "L 27.7045..43.9131 mm"),
])
def test_bad_scattered_points_exit_2_before_any_flank(capsys, tmp_path, monkeypatch, rows,
                                                      word):
    # refused in the check: the flanks are never built (build_flanks raising proves it)
    import gearcontact.geometry.flank as flank

    monkeypatch.setattr(flank, "build_flanks", lambda *a, **k: pytest.fail("built flanks"))
    path = tmp_path / "m.csv"
    path.write_text(HEAD + "".join(f"pinion,coast,{L!r},{R!r},{d!r}\n" for L, R, d in rows))
    assert _run(path) == 2
    err = capsys.readouterr().err
    assert word in err, err


def test_points_on_one_profile_line_exit_2_naming_the_unobservable_settings(
        capsys, tmp_path, s0003_calibrated):
    # 20 points on the nominal coast flank's mid-face profile line (deviation 0): the
    # seed's sensitivity has six settings in its null space (geometry.point_fit,
    # smallest relative singular value ~2e-9); refused after the flanks (~7 s), before
    # any fit
    _, flanks = s0003_calibrated
    nominal = flanks.pinion.coast
    b = nominal.boundary
    s = nominal.evaluate(np.linspace(b.u_root, b.u_tip, 20),
                         np.full(20, 0.5 * (b.v_toe + b.v_heel)))
    path = tmp_path / "line.csv"
    path.write_text(HEAD + "".join(f"pinion,coast,{float(x)!r},{float(np.hypot(y, z))!r},0\n"
                                   for x, y, z in s.r))
    assert _run(path) == 2
    err = capsys.readouterr().err
    assert "line.csv: pinion coast: points = 'rank-deficient (settings not observable at " \
           "these points: " in err, err
    assert "cradle_angle_deg" in err and "radial_distance_mm" in err
    assert "allowed range: points spread over the flank's profile and length (relative " \
           "singular value >= 0.0001), or fewer settings" in err


@pytest.mark.slow       # flanks, two fits, two cut flanks: ~20 s
def test_scattered_points_of_a_known_cut_give_its_settings(capsys, tmp_path, s0003_calibrated):
    # s0003's coast pinion cut from its seed + the known correction of
    # tests/geometry/test_point_fit.py, measured at 60 seeded random points: the command
    # writes the coast pinion's settings of that cut (each setting within 1e-6 of its
    # size + 5e-4 of its correction: the library's recovery, measured 6.1e-5 of the
    # correction), the residual at the points in its table and in
    # machine_settings_points.csv (one line per point, the file's lines and values)
    from easeoff_grid import cut_from_known, write_points_csv

    from gearcontact.geometry.pair import load_pair

    pair, flanks = s0003_calibrated
    seed, true, truth = cut_from_known(pair)
    b = flanks.pinion.coast.boundary
    rng = np.random.default_rng(27)
    u = rng.uniform(max(b.u_root, truth.boundary.u_root), b.u_tip, 60)
    v = rng.uniform(b.v_toe, b.v_heel, 60)
    path = tmp_path / "cmm.csv"
    dev = write_points_csv(path, flanks.pinion.coast, truth, "coast", u, v)
    assert _run(path, "--out", str(tmp_path / "o")) == 0
    out = capsys.readouterr().out
    assert "coast: target 60 scattered measured points (--target-flank): ease-off and " \
           "residual at the points" in out
    toml = (tmp_path / "o" / "machine_settings.toml").read_text()
    assert "pinion coast (60 measured points (--target-flank))" in toml
    got = {s.side: s for s in load_pair(tmp_path / "o" / "machine_settings.toml").machine
           if s.member == "pinion"}["coast"]
    for part in ("settings", "blade"):
        x, want, was = (getattr(s, part) for s in (got, true, seed))
        for f in x.__dataclass_fields__:
            a, w, s0 = (np.atleast_1d(getattr(o, f)) for o in (x, want, was))
            if a.dtype.kind == "f" and w.size:
                assert a.size == w.size, f
                s0 = s0 if s0.size == w.size else np.zeros_like(w)   # the seed's linear roll
                assert np.all(np.abs(a - w) <= 1e-6 * np.abs(w) + 5e-4 * np.abs(w - s0)), f
    rows = (tmp_path / "o" / "machine_settings_points.csv").read_text().splitlines()
    assert rows[0] == "member,flank,line,L_mm,R_mm,deviation_um,u_mm,v_mm,residual_um"
    cells = [r.split(",") for r in rows[1:]]
    assert [int(c[2]) for c in cells] == list(range(2, 62))
    assert np.array_equal([float(c[5]) for c in cells], dev)
    res = np.array([float(c[8]) for c in cells])
    # residual of the cut flank (120 x 150 sheet) at the points: the fit's ~1e-6 um plus
    # the two sheets' interpolation (measured 5.0e-5 um); asserted 0.01 um. The table's row is
    # that of the file
    print("residual at the points, max", np.abs(res).max())
    assert np.abs(res).max() < 0.01
    row = [r for r in out.splitlines() if r.startswith("| coast |")][0].split("|")
    assert float(row[3]) == pytest.approx(np.abs(res).max(), abs=5e-4)
    assert float(row[4]) == pytest.approx(np.sqrt(np.mean(res ** 2)), abs=5e-4)
