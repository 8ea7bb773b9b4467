"""The machine kinematics of the pinion (and a generated gear) against an independent
peer, SpyGO.

tests/data/spygo/ holds pinion flank points computed by SpyGO (haomjc/SpyGO at 417ac9a,
its own sampler ``hypoid.main.geometry.rz_sampling_casadi``: its 9-joint cradle chain,
its sign matrix, its blade and its equation of meshing) for four pinion flanks whose
settings exercise every pinion word (tilt + swivel, sliding base, MCTB, blank offset,
ratio of roll, 2C, 6D, helical motion V_1 / V_2; right-hand F.2 spiral bevel and
left-hand 10 x 41 hypoid) and for the printed right-hand 10 x 41 gear with tilt, swivel,
2C, 6D, V_1 and V_2 added, each mapped term by term into SpyGO's settings
(tests/data/spygo/README.md; the script that wrote them, make_reference.py, is not run
here). gearcontact cuts the same flanks from its own tables and must go through SpyGO's
points. Tolerances (declared in docs/machine_settings.md sec. 2, "An independent peer:
SpyGO (session 29)"):

- exact envelope nodes: 1e-8 mm along our normal, 1e-9 on the normals' directions: two
  orders above the looser of the two solvers' residual tolerances (gearcontact's node
  equations 1e-10 mm; SpyGO's Newton 1e-12, its residuals checked <= 1e-9 and measured
  <= 4.8e-13 when written; the CSV's 12 decimals 5e-13 mm), four orders below the
  smallest effect of a word read with the other sign (2.3e-2 mm, below);
- the flank surface TCA uses (the 120 x 150 quintic ``RadialSheet`` / ``GearSheet``): 1e-6 mm, the
  sheet's interpolation error between exact nodes (2.5e-7 mm measured at 80 x 100 in
  sec. 6) with margin.
"""

from __future__ import annotations

import csv
import json
import warnings
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.conjugate import UndercutError, nominal_pinion_box
from gearcontact.geometry.generated import (EnvelopeSolver, gear_cone, generated_gear_flank,
                                            generated_pinion_flank, mean_uv, solve_node_grid,
                                            work_to_body)
from gearcontact.geometry.machine import setup_from_tables
from gearcontact.geometry.pair import load_pair

ROOT = Path(__file__).parents[2]
DATA = ROOT / "tests" / "data" / "spygo"
CASES = json.loads((DATA / "cases.json").read_text())
NODE_TOL_MM = 1e-8
NORMAL_TOL = 1e-9
SHEET_TOL_MM = 1e-6
#: A word read with the other sign must move the flank by more than this (or leave no
#: flank through the nodes): 1e5 x NODE_TOL_MM, below the smallest effect measured.
WORD_EFFECT_MM = 1e-3


def _points(name: str) -> dict:
    with open(DATA / "points.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["case"] == name]
    n_u = 1 + max(int(r["i_u"]) for r in rows)
    col = {k: np.array([float(r[k]) for r in rows]).reshape(n_u, -1)
           for k in rows[0] if k != "case"}
    col["x_w"] = np.stack([col["x_mm"], col["y_mm"], col["z_mm"]], axis=-1)
    col["n_w"] = np.stack([col["n_x"], col["n_y"], col["n_z"]], axis=-1)
    return col


def _pair(case: dict):
    with warnings.catch_warnings():    # the hypoid's typed gear page notes its blank
        warnings.simplefilter("ignore")
        return load_pair(ROOT / case["pair"])


def _nodes(pair, case: dict, machine: dict, pts: dict):
    """gearcontact's exact envelope nodes at the (u, v) of SpyGO's points."""
    setup = setup_from_tables(case["member"], case["side"], machine, case["blade"])
    if case["member"] == "gear":
        cone = gear_cone(pair.blank)
    else:
        cone, _ = nominal_pinion_box(pair.blank, pair.pinion_face_width_mm)
    solver = EnvelopeSolver(setup, pair.blank, cone)
    u_m, v_m = mean_uv(setup, pair.blank, cone)
    mean = solver.solve(u_m, v_m, solver.initial_guess(u_m, v_m))
    return solve_node_grid(solver, pts["u_mm"][:, 0], pts["v_mm"][0], u_m, v_m, mean.q)


def _in_body(pair, case: dict, vec, *, point: bool):
    q, t = work_to_body(case["member"], pair.blank)
    return vec @ q.T + (t if point else 0.0)


@pytest.mark.parametrize("name", sorted(CASES))
def test_spygo_points_lie_on_our_envelope(name):
    case, pts = CASES[name], _points(name)
    pair = _pair(case)
    nodes = _nodes(pair, case, case["machine"], pts)
    x_sp = _in_body(pair, case, pts["x_w"], point=True)
    n_sp = _in_body(pair, case, pts["n_w"], point=False)
    # the same (axial position, radius): the work frames' origins and axes are one
    a, b, c = (2, 0, 1) if case["member"] == "gear" else (0, 1, 2)
    assert np.abs(x_sp[..., a] - nodes.x_mm[..., a]).max() < NODE_TOL_MM
    assert np.abs(np.hypot(x_sp[..., b], x_sp[..., c])
                  - np.hypot(nodes.x_mm[..., b], nodes.x_mm[..., c])).max() < NODE_TOL_MM
    # measured 5.3e-13 .. 7.0e-13 mm (both solvers' residuals)
    along = np.einsum("...i,...i->...", x_sp - nodes.x_mm, nodes.n)
    assert np.abs(along).max() < NODE_TOL_MM
    assert np.abs(x_sp - nodes.x_mm).max() < NODE_TOL_MM
    # SpyGO's normal points into the tooth (its blade normal), ours out of it
    assert np.abs(1.0 + np.einsum("...i,...i->...", n_sp, nodes.n)).max() < NORMAL_TOL


#: The words each case moves, read with the other sign (or as SpyGO prints them where
#: the mapping is not the identity): (key, value from the case's own tables).
_FLIPS = {
    "f2_drive": [("sliding_base_mm", lambda m, s: -m["sliding_base_mm"]),
                 ("swivel_deg", lambda m, s: m["swivel_deg"] + 180.0),     # tilt opposite
                 ("swivel_deg", lambda m, s: s["SWIVELANGLE"]),
                 ("ratio_of_roll", lambda m, s: 1.0 / s["RATIOROLL"])],
    "f2_coast_words": [("modified_roll_2c_per_rad", lambda m, s: s["C2"]),
                       ("modified_roll_6d_per_rad2", lambda m, s: -s["D6"]),
                       ("helical_motion_mm_per_rad", lambda m, s: s["H1"]),
                       ("helical_motion_mm_per_rad2", lambda m, s: -s["H2"]),
                       ("machine_centre_to_back_mm", lambda m, s: -s["MACHCTRBACK"]),
                       ("sliding_base_mm", lambda m, s: -s["SLIDINGBASE"])],
    "hypoid_drive_roll": [("cradle_angle_deg", lambda m, s: s["CRADLEANGLE"]),
                          ("blank_offset_mm", lambda m, s: s["BLANKOFFSET"]),
                          ("modified_roll_6d_per_rad2", lambda m, s: -s["D6"]),
                          ("machine_centre_to_back_mm", lambda m, s: -s["MACHCTRBACK"]),
                          ("sliding_base_mm", lambda m, s: -s["SLIDINGBASE"])],
    "hypoid_coast_tilt": [("swivel_deg", lambda m, s: s["SWIVELANGLE"]),
                          ("swivel_deg", lambda m, s: m["swivel_deg"] + 180.0),
                          ("helical_motion_mm_per_rad2", lambda m, s: -s["H2"]),
                          ("sliding_base_mm", lambda m, s: -s["SLIDINGBASE"])],
    "hypoid_gear_drive_words": [("modified_roll_2c_per_rad", lambda m, s: -s["C2"]),
                                ("modified_roll_6d_per_rad2", lambda m, s: -s["D6"]),
                                ("helical_motion_mm_per_rad", lambda m, s: -s["H1"]),
                                ("helical_motion_mm_per_rad2", lambda m, s: -s["H2"]),
                                ("swivel_deg", lambda m, s: s["SWIVELANGLE"]),
                                ("swivel_deg", lambda m, s: m["swivel_deg"] + 180.0),
                                ("blank_offset_mm", lambda m, s: -s["BLANKOFFSET"]),
                                ("sliding_base_mm", lambda m, s: -s["SLIDINGBASE"]),
                                ("machine_centre_to_back_mm", lambda m, s: -s["MACHCTRBACK"])],
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_each_word_read_otherwise_misses_spygo(name):
    # not vacuous: every word of the case, read with the other sign (or typed as SpyGO
    # prints it where the mapping is not the identity), cuts a flank that misses
    # SpyGO's points by > WORD_EFFECT_MM (measured 0.023 .. 59 mm) or whose envelope
    # does not reach the nodes at all
    case, pts = CASES[name], _points(name)
    pair = _pair(case)
    x_sp = _in_body(pair, case, pts["x_w"], point=True)
    for key, value in _FLIPS[name]:
        new = value(case["machine"], case["spygo_machine"])
        if key == "swivel_deg":
            new = (new + 180.0) % 360.0 - 180.0
        assert new != case["machine"].get(key, 0.0), key
        try:
            nodes = _nodes(pair, case, {**case["machine"], key: new}, pts)
        except UndercutError:
            continue
        miss = np.abs(np.einsum("...i,...i->...", x_sp - nodes.x_mm, nodes.n))
        assert not (nodes.converged.all() and miss.max() < WORD_EFFECT_MM), (key, new)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CASES))
def test_spygo_points_lie_on_our_flank_surface(name):
    # the Surface TCA takes (120 x 150 nodes, quintic sheet): 1.4 to 3 s per flank
    case, pts = CASES[name], _points(name)
    pair = _pair(case)
    setup = setup_from_tables(case["member"], case["side"], case["machine"], case["blade"])
    if case["member"] == "gear":
        flank, _ = generated_gear_flank(setup, pair.blank,
                                        gear_face_width_mm=pair.gear_face_width_mm)
    else:
        flank, _ = generated_pinion_flank(setup, pair.blank,
                                          pinion_face_width_mm=pair.pinion_face_width_mm)
    x_sp = _in_body(pair, case, pts["x_w"], point=True)
    u, v = pts["u_mm"], pts["v_mm"]
    assert flank.boundary.contains(u, v).all()
    got = flank.evaluate(u, v, second=False)
    # measured 1e-12 .. 6.4e-11 mm
    assert np.abs(np.einsum("...i,...i->...", x_sp - got.r, got.n)).max() < SHEET_TOL_MM
    assert np.abs(x_sp - got.r).max() < SHEET_TOL_MM
