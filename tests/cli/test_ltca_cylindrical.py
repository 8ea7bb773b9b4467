"""``gearcontact ltca`` on a cylindrical pair, run as a user runs it (default options:
64.5 N·m, 61 phases, 40 cells along the face, tooth bending) through
`gearcontact.cli.main` (the helical example's as the README's line), a rerun into the same directory, and the options it refuses.

Truths: the files are the loaded TE's own result at its pitch-point phase (the same
library call ``gearcontact lte`` makes, 1e-12; and the ``lte`` command's own files at
that phase, byte for byte); the normal load of the torque F_n = T2 / (r_b2 cos beta_b)
(ISO 6336-1, 1e-12); the torque balance sum(load lever) = T2 (the LCP's constraint,
1e-9 as tests/cli/test_lte_cylindrical.py); on the spur example at the pitch point a
single pair, whose mid-face pressure is Johnson 1985 eq. 4.45 for its own line load
(the tolerance of tests/ltca/test_cylindrical_lte.py::test_line_contact_hertz_at_the_pitch_point).
"""

import json
import math
import shlex
from pathlib import Path

import numpy as np
import pytest
from readme_lines import readme_commands

from gearcontact.cli import main
from gearcontact.geometry.pair import CYLINDRICAL, load_pair
from gearcontact.halfspace.lcp import resolve_e_star
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.validation import InputRangeError

ROOT = Path(__file__).resolve().parents[2]
EV = str(ROOT / "examples" / "ev_reducer_helical_23x67.toml")
SPUR = str(ROOT / "examples" / "spur_20x40_m3.toml")
FILES = ("ltca.json", "line_load.csv", "pressure_map.csv", "pressure_map.png")


def _run(tmp_path_factory, pair, name):
    d = tmp_path_factory.mktemp(name) / "run"
    assert main(["ltca", "--pair", pair, "--out", str(d)]) == 0
    return d


@pytest.fixture(scope="module")
def spur_out(tmp_path_factory):
    return _run(tmp_path_factory, SPUR, "ltca_spur")


@pytest.fixture(scope="module")
def ev_out(tmp_path_factory):
    """The README's line for the helical example (default options), --out redirected."""
    line = [c for c in readme_commands() if c.startswith("gearcontact ltca --pair examples/ev_")]
    assert len(line) == 1, "README has one ltca line for the helical example"
    argv = shlex.split(line[0])[1:]
    assert argv == ["ltca", "--pair", "examples/ev_reducer_helical_23x67.toml", "--out",
                    argv[-1]]
    return _run(tmp_path_factory, EV, "ltca_ev")


def _lever_mm(pair):
    g = pair.geometry
    return 0.5 * g.base_diameter_gear_mm * math.cos(math.radians(g.base_helix_angle_deg))


@pytest.mark.parametrize("which", ["spur", "ev"])
def test_files_load_and_torque_balance(which, spur_out, ev_out):
    out, path = (spur_out, SPUR) if which == "spur" else (ev_out, EV)
    for name in FILES:
        assert (out / name).stat().st_size > 0, name
    pair = load_pair(path, kinds=(CYLINDRICAL,))
    doc = json.loads((out / "ltca.json").read_text())
    assert doc["teeth"] == "bending" and doc["converged"] and not doc["edge_touch"]
    assert doc["torque_gear_nm"] == 64.5 and doc["phase_index"] == 30   # the defaults
    lever = _lever_mm(pair)
    assert doc["normal_load_n"] == pytest.approx(64.5e3 / lever, rel=1e-12)
    # the LCP's torque balance (its tolerance 1e-8 on the complementarity; 1e-9 as lte)
    moment = sum(p["load_n"] * p["lever_mm"]
                 + sum(b["load_n"] * b["lever_mm"] for b in p["beyond_line"].values())
                 for p in doc["pairs"])
    assert moment / 1e3 == pytest.approx(64.5, rel=1e-9)
    lines = np.genfromtxt(out / "line_load.csv", delimiter=",", names=True, dtype=None,
                          encoding=None)
    dz = doc["grid_dy_mm"] * math.cos(math.radians(pair.geometry.base_helix_angle_deg))
    assert (lines["load_n_per_mm"] * lines["lever_mm"]).sum() * dz / 1e3 == pytest.approx(
        64.5, rel=1e-9)
    # approach = r_b2 cos(beta_b) theta, theta the loaded TE's lag beyond TE0 (arcsec)
    assert doc["approach_mm"] == pytest.approx(lever * doc["rotation_rad"], rel=1e-12)
    assert doc["rotation_arcsec"] == pytest.approx(doc["te0_arcsec"] - doc["lte_arcsec"],
                                                   rel=1e-9)
    # the pressure map integrates to each pair's load (cell area dx dy)
    pm = np.genfromtxt(out / "pressure_map.csv", delimiter=",", names=True)
    for p in doc["pairs"]:
        on = pm["pair"] == p["pair"]
        total = pm["pressure_mpa"][on].sum() * doc["grid_dx_mm"] * doc["grid_dy_mm"]
        assert total == pytest.approx(p["load_n"] + sum(
            b["load_n"] for b in p["beyond_line"].values()), rel=1e-9)
        assert pm["pressure_mpa"][on].max() == pytest.approx(p["p_max_mpa"], rel=1e-11)
    if which == "ev":       # eps_gamma 3.1: three lines carry at the pitch point
        assert doc["pairs_loaded"] == 3


def test_spur_pitch_point_is_line_hertz(spur_out):
    """Single contact at the pitch point (eps_alpha 1.635): one pair carries all of F_n;
    at mid-face its peak pressure across the line is Johnson 1985 eq. 4.45, p0 =
    sqrt(w E* / (pi R)), w the LCP's own line load there (the half-space and bending
    raise the load towards the face ends, where the uncrowned line ends on sharp edges:
    p_max sits there), 1/R = 1/(r_b1 tan a_wt) + 1/(r_b2 tan a_wt). Tolerance as
    tests/ltca/test_cylindrical_lte.py: dx/2 off the peak, p0 (1 - (dx/2b)^2/2), plus
    0.5 % for the piecewise-constant pressure (measured -0.32 % at 24 cells across)."""
    doc = json.loads((spur_out / "ltca.json").read_text())
    assert doc["pairs_loaded"] == 1 and doc["pairs"][0]["pair"] == 0
    assert doc["pairs"][0]["load_share"] == pytest.approx(1.0, rel=1e-9)
    assert doc["p_max_on_edge"] and doc["pairs"][0]["line_end_loaded"]
    pair = load_pair(SPUR, kinds=(CYLINDRICAL,))
    g = pair.geometry
    tan_a = math.tan(math.radians(g.working_pressure_angle_deg))
    R = 1.0 / (2.0 / (g.base_diameter_pinion_mm * tan_a) + 2.0 / (g.base_diameter_gear_mm * tan_a))
    e_star = resolve_e_star((pair.pinion_material, pair.gear_material))
    lines = np.genfromtxt(spur_out / "line_load.csv", delimiter=",", names=True, dtype=None,
                          encoding=None)
    assert len(lines) == 40
    mid = [19, 20]                        # the two rows either side of mid-face z = 0
    assert lines["pinion_z_mm"][mid].sum() == pytest.approx(0.0, abs=1e-12)
    w = lines["load_n_per_mm"][mid].mean()
    p_lcp = lines["peak_pressure_mpa"][mid].mean()
    p0 = math.sqrt(w * e_star / (math.pi * R))
    half_width = math.sqrt(4.0 * w * R / (math.pi * e_star))
    tol = 0.5 * (doc["grid_dx_mm"] / (2.0 * half_width)) ** 2 + 5e-3
    assert abs(p_lcp / p0 - 1.0) < tol


def test_is_the_loaded_te_phase(ev_out):
    """The written numbers are those of the loaded TE that ``gearcontact lte`` computes
    with its defaults (the same library call: unloaded cycle of 61 phases, then
    cylindrical_loaded_te with 40 cells along and bending), at index 30: the pitch-point
    phase, 1e-12 (the same arithmetic)."""
    pair = load_pair(EV, kinds=(CYLINDRICAL,))
    cycle = cylindrical_mesh_cycle(pair, facing="cw", phases=61)
    res = cylindrical_loaded_te(pair, 64.5, cycle=cycle, bending=True, cells_along=40)
    doc = json.loads((ev_out / "ltca.json").read_text())
    k = 30
    assert doc["phi1_deg"] == pytest.approx(math.degrees(cycle.phi1_rad[k]), rel=1e-12)
    for key, value in (("lte_arcsec", res.lte_arcsec[k]), ("te0_arcsec", res.te0_arcsec[k]),
                       ("p_max_mpa", res.max_pressure_mpa[k]),
                       ("mesh_stiffness_n_per_mm_um", res.stiffness_n_per_mm_um[k])):
        assert doc[key] == pytest.approx(float(value), rel=1e-12), key
    assert doc["rotation_arcsec"] == pytest.approx(
        float(res.te0_arcsec[k] - res.lte_arcsec[k]), rel=1e-9)   # arcsec differences
    shares = {p["pair"]: p["load_share"] for p in doc["pairs"]}
    expect = {j: float(s) for j, s in zip(res.pair_offsets, res.load_share[:, k]) if s > 0}
    assert shares.keys() == expect.keys()
    for j in shares:
        assert shares[j] == pytest.approx(expect[j], rel=1e-12)
    lines = np.genfromtxt(ev_out / "line_load.csv", delimiter=",", names=True, dtype=None,
                          encoding=None)
    for j in shares:
        p = res.pair_offsets.index(j)
        on = (lines["pair"] == j) & (lines["contact"] == "line")
        np.testing.assert_allclose(lines["load_n_per_mm"][on], res.line_load_n_per_mm[p, k],
                                   rtol=1e-11, atol=1e-9)   # CSV: 12 significant digits


def test_agrees_with_the_lte_command_files(tmp_path):
    """``lte`` and ``ltca`` with the same options write the same line_load.csv rows at the
    pitch-point phase (byte for byte) and the same lte.csv numbers (12 digits); 5 phases
    and 16 cells keep the lte run's rigid-tooth loaded TE and 5 x 5 Harris map short."""
    opts = ["--pair", EV, "--phases", "5", "--cells", "16", "--no-figures"]
    assert main(["lte", *opts, "--out", str(tmp_path / "lte")]) == 0
    assert main(["ltca", *opts, "--out", str(tmp_path / "ltca")]) == 0
    doc = json.loads((tmp_path / "ltca" / "ltca.json").read_text())
    assert doc["phase_index"] == 2
    head, *rows = (tmp_path / "ltca" / "line_load.csv").read_text().splitlines()
    lte_head, *lte_rows = (tmp_path / "lte" / "line_load.csv").read_text().splitlines()
    assert head == lte_head
    phi = f"{doc['phi1_deg']:.12g}"
    assert rows == [r for r in lte_rows if r.split(",")[0] == phi] and rows
    lte = np.genfromtxt(tmp_path / "lte" / "lte.csv", delimiter=",", names=True)
    row = lte[doc["phase_index"]]
    assert f"{row['phi1_deg']:.12g}" == phi
    for col, key in (("lte_arcsec", "lte_arcsec"), ("max_pressure_mpa", "p_max_mpa"),
                     ("mesh_stiffness_n_per_mm_um", "mesh_stiffness_n_per_mm_um")):
        assert float(f"{doc[key]:.12g}") == row[col], col


def test_rerun_into_the_same_directory(ev_out):
    """The same command into its own previous run's directory: accepted, and the result
    files identical (run.json's SHA-256 of each; timings live only in run.json)."""
    before = {f["path"]: f["sha256"] for f in
              json.loads((ev_out / "run.json").read_text())["files"]}
    assert main(["ltca", "--pair", EV, "--out", str(ev_out)]) == 0
    after = {f["path"]: f["sha256"] for f in
             json.loads((ev_out / "run.json").read_text())["files"]}
    assert set(FILES) <= set(after) and after == before


@pytest.mark.parametrize("extra", [["--multi-tooth"], ["--multi-tooth-cells", "40"],
                                   ["--solver", "nnls"], ["--export-problem"],
                                   ["--misalignment", "E=0.01"]])
def test_options_refused_for_a_cylindrical_pair(extra, tmp_path, capsys):
    d = tmp_path / "out"
    assert main(["ltca", "--pair", EV, "--out", str(d), *extra]) == 2
    err = capsys.readouterr().err
    assert extra[0] in err and "cylindrical" in err and "Traceback" not in err
    assert not d.exists()                                  # before any work


@pytest.mark.parametrize("command", ["ltca", "lte"])
def test_cells_named_along_the_face(command, tmp_path, capsys):
    """A cylindrical pair's --cells count cells along the face (its grid is not square):
    the refusal says so, a bevel pair's says per side of its square field."""
    for pair, where in ((EV, "along the face"), ("s0003", "per side")):
        d = tmp_path / pair.replace("/", "_")
        assert main([command, "--pair", pair, "--out", str(d), "--cells", "5"]) == 2
        err = capsys.readouterr().err
        assert "--cells = 5 is outside the allowed range: an integer in [16, " in err
        assert err.rstrip().endswith(where) and not d.exists()


@pytest.mark.parametrize("command", [["ltca"], ["lte"], ["twin"], ["export", "fmu"],
                                     ["sweep"], ["analyze"]])
def test_torque_beyond_the_preview_envelope_refused(command, tmp_path, capsys):
    """A cylindrical pair's torque is held to the preview envelope as a bevel pair's:
    its whole normal load W = T2 / (r_b2 cos beta_b) <= 131072 N (one pair carries it at
    a single-contact phase). Truth: the EV pair's lever from the ISO 21771 closed forms
    written out here (m_n 2, alpha_n 20 deg, beta 25 deg, z2 67: r_b2 = z2 m_n
    cos(alpha_t) / (2 cos(beta)), whatever the profile shift and centre distance); the
    limit printed to 6 digits. Before this check 1e9 N·m ran the twin for minutes, and
    (session 21) analyze's --lte-torque 1e6 N·m ran on for minutes too."""
    beta, alpha_n = math.radians(25.0), math.radians(20.0)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    r_b2 = 67 * 2.0 * math.cos(alpha_t) / (2 * math.cos(beta))
    beta_b = math.asin(math.sin(beta) * math.cos(alpha_n))
    limit = 131072.0 * r_b2 * math.cos(beta_b) / 1e3
    opt = {"sweep": "--torques", "analyze": "--lte-torque"}.get(command[0], "--torque")
    d = tmp_path / "out"
    assert main([*command, "--pair", EV, "--out", str(d), opt, "1e9"]) == 2
    err = capsys.readouterr().err
    assert f"{opt} (N·m) = 1000000000.0 is outside the allowed range: (0, {limit:.6g}]" in err
    assert not d.exists()
    assert main([*command, "--pair", EV, "--out", str(d), opt, f"{limit * 1.001:.6g}"]) == 2


def test_rigid_refused_for_a_bevel_pair(tmp_path, capsys):
    d = tmp_path / "out"
    assert main(["ltca", "--pair", "s0003", "--out", str(d), "--rigid"]) == 2
    err = capsys.readouterr().err
    assert "--rigid" in err and "Traceback" not in err
    assert not d.exists()


def test_rigid_teeth_turn_less(tmp_path):
    """--rigid: the contact's compliance alone; the shells' bending is in series with it,
    so the same load turns the gear further with bending (3 phases, 16 cells: cheap)."""
    turn = {}
    for teeth, extra in (("rigid", ["--rigid"]), ("bending", [])):
        d = tmp_path / teeth
        assert main(["ltca", "--pair", SPUR, "--phases", "3", "--cells", "16", "--no-figures",
                     "--out", str(d), *extra]) == 0
        doc = json.loads((d / "ltca.json").read_text())
        assert doc["teeth"] == teeth and doc["phase_index"] == 1 and doc["pairs_loaded"] == 1
        turn[teeth] = doc["rotation_rad"]
    assert 0.0 < turn["rigid"] < turn["bending"]


def test_fields_at_outside_the_cycle_refused():
    pair = load_pair(SPUR, kinds=(CYLINDRICAL,))
    cycle = cylindrical_mesh_cycle(pair, phases=3)
    with pytest.raises(InputRangeError, match="fields_at"):
        cylindrical_loaded_te(pair, 64.5, cycle=cycle, fields_at=3)
