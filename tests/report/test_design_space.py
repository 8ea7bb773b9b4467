"""Issue 28: every pair of the design space that ``design`` accepts runs the main job.

``gearcontact analyze --pair FILE --out DIR --phases N`` with every other option at its
default (four operating torques, the multi-tooth LTCA with tooth bending, the loaded TE
over every TCA phase, the ease-off synthesis, the figures) exits 0 on random accepted
pairs of tests/design_space.py (the slow test draws both hands: a left-hand pair's
tooth bending once stopped every run, tests/structure/test_shell.py), and its files obey
truths the job does not impose on itself one file from another: the torque balance of
every single-pair LTCA, load shares summing to 100 %, the loaded TE's TE0 equal to the
TCA's te0.csv, every preview value present or a status saying why.

Cost (2 shared cores, warm numba cache, 11 phases): 21-26 s per analyze with the
machine otherwise quiet, up to 80 s under load; the default test runs one accepted pair
(28-50 s), the slow one nine (257 s quiet, 438 s under load).
"""

import csv
import json
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

from design_space import HANDS, SPACE, command_on_accepted_pair

#: TCA phases per pitch of the runs here (default 61): the loaded TE runs on all of them.
PHASES = 11


def _rows(path: Path) -> list[dict]:
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def _analyze_accepted_pair(*point):
    with command_on_accepted_pair("analyze", point,
                                  options=("--phases", str(PHASES))) as (_, run, out):
        assert run.returncode == 0, run.stderr
        _check_results(out)


def _check_results(out: Path):
    # single-pair LTCA: the normal load times its lever is the gear torque (N·mm vs
    # N·m: exact up to rounding, 1e-9)
    for case in json.loads((out / "ltca.json").read_text()):
        assert case["load_n"] * case["lever_mm"] * 1e-3 == pytest.approx(case["torque_nm"],
                                                                        rel=1e-9)
        assert case["status"] == "converged"
    # multi-tooth LTCA: shares of the pair loads, summing to 100 % (rounding only)
    mt = json.loads((out / "multitooth.json").read_text())
    for key, loads in (("load_share_pct", "pair_loads_n"),
                       ("load_share_rigid_pct", "pair_loads_rigid_n")):
        assert sum(mt[key]) == pytest.approx(100.0, abs=1e-9)
        assert np.allclose(mt[key], 100.0 * np.array(mt[loads]) / sum(mt[loads]),
                           rtol=0, atol=1e-9)
        assert min(mt[loads]) >= 0.0
    assert mt["converged"] and mt["n_engaged"] >= 1
    # loaded TE: converged on every phase; its TE0 is the TCA's (te0.csv, an
    # independent file of the TCA stage) at the phases it ran (file rounding, 1e-6")
    lte = json.loads((out / "lte.json").read_text())
    assert lte["converged"] and lte["unconverged_phases"] == 0
    assert lte["phases"] == PHASES
    rows = _rows(out / "lte.csv")
    assert [r["status"] for r in rows] == ["converged"] * PHASES
    te0 = {round(float(r["phi1_deg"]), 6): float(r["te0_arcsec"])
           for r in _rows(out / "te0.csv")}
    for r in rows:
        assert float(r["te0_arcsec"]) == pytest.approx(te0[round(float(r["phi1_deg"]), 6)],
                                                       abs=1e-6)
    assert lte["te0_pp_arcsec"] == pytest.approx(
        np.ptp([float(r["te0_arcsec"]) for r in rows]), abs=1e-6)
    assert lte["mesh_compliance_lcp_mm_per_n"] > 0.0
    # preview.csv: the fp64 preview always has a value; each fixed-point result has one
    # with status "ok", or none and a status naming why
    for r in _rows(out / "preview.csv"):
        assert np.isfinite(float(r["ref_p_max_mpa"])) and float(r["ref_p_max_mpa"]) > 0
        for value, status in (("golden_p_max_mpa", "golden_status"),
                              ("chain_p_max_mpa", "chain_status")):
            assert r[status], r
            if r[status] == "ok":
                assert float(r[value]) > 0.0, r
            else:
                assert r[value] == "", r


@settings(max_examples=1, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(**SPACE)
def test_accepted_pair_runs_analyze(z1, ratio, offset_frac, beta, face_frac, side):
    _analyze_accepted_pair(z1, ratio, offset_frac, beta, face_frac, side)


@pytest.mark.slow
@settings(max_examples=9, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(**SPACE, hand=HANDS)
def test_accepted_pairs_run_analyze_slow(z1, ratio, offset_frac, beta, face_frac, side, hand):
    _analyze_accepted_pair(z1, ratio, offset_frac, beta, face_frac, side, hand)


#: Issue 28 item 1's low-ratio spiral bevel pairs (ISO 23509 F.2's data, 20 pinion
#: teeth, 25 mm faces): the 1:1 miter pair of the issue's reproduction (F.2's gear
#: addendum factor) and 20/30 with ISO's c_ham = 0.21 + 0.29 / u^2 for u = 1.5. The
#: formate gear undercuts both pinions; both get the generated gear
#: (docs/geometry.md sec. 7.6). Cost (test, load ~3 on 2 cores): 20/30 47 s, 20/20
#: 57 s (session 11: 126 s and about 14 min, the 20/20 synthesis 207 TCA runs without
#: meeting its targets; now 51 runs, all met through the overlap path angle,
#: docs/synthesis.md "Low ratios").
LOW_RATIO = {"20-20": (20, 0.24737), "20-30": (30, 0.33889)}


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(LOW_RATIO))
def test_low_ratio_pairs_design_and_analyze(tmp_path, name):
    import sys

    z2, c_ham = LOW_RATIO[name]
    # the reproduction: the example's lines edited (no [easeoff.*] table, so
    # analyze synthesizes the ease-off as for every pair without one)
    text = (Path(__file__).resolve().parents[2] / "examples"
            / "iso23509_f2_spiral_bevel.toml").read_text()
    for old, new in (("pinion = 14", "pinion = 20"), ("gear = 39", f"gear = {z2}"),
                     ("gear_addendum_factor = 0.24737", f"gear_addendum_factor = {c_ham}"),
                     ("face_width_mm = 25.4", "face_width_mm = 25.0")):
        assert old in text
        text = text.replace(old, new)
    (tmp_path / "pair.toml").write_text(text)
    cmd = [sys.executable, "-m", "gearcontact"]
    run = subprocess.run(cmd + ["design", "--pair", str(tmp_path / "pair.toml")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "gear flanks: generated" in run.stdout
    out = tmp_path / "out"
    t0 = time.perf_counter()
    run = subprocess.run(cmd + ["analyze", "--pair", str(tmp_path / "pair.toml"), "--out",
                                str(out), "--phases", str(PHASES), "--quiet"],
                         capture_output=True, text=True)
    print(f"analyze {name}: exit {run.returncode}, {time.perf_counter() - t0:.1f} s")
    assert run.returncode == 0, run.stderr
    _check_results(out)


#: Low-ratio pairs without a table (F.3 data, beta1 35 deg, face 0.3 R_m; (z1, u, E / r2)
#: of tests/tca/test_predicted_bearing.py's RECOUNT) whose contact-path check now takes
#: the synthesis' overlap path angle (deg, predicted), refused before (the default
#: bearing's eps_p below 0.85) but for the last two.
TURNED = {(9, 1.5, 0.0): 22.8, (9, 1.5, 0.3): 28.4, (9, 2.0, 0.0): 17.1,
          (9, 2.0, 0.3): 28.3, (9, 2.5, 0.3): 26.7, (13, 1.0, 0.0): 23.5,
          (13, 1.0, 0.3): 21.3, (13, 1.5, 0.3): 21.9, (9, 2.5, 0.0): 13.9,
          (13, 1.5, 0.0): 16.7}


@pytest.mark.slow
@pytest.mark.parametrize("point", sorted(TURNED))
def test_pairs_the_synthesis_bearing_accepts_analyze(point, tmp_path):
    """``analyze`` (11 phases, every other option default: the synthesis included) exits
    0 on each, its synthesis turns the path to the predicted angle (the same closed form
    on the full flanks: within 0.1 deg), and its files obey the truths above (3-8 min a
    pair under load)."""
    import re
    import shutil

    from design_space import bare_candidate
    from gearcontact.geometry.pair import pair_to_toml

    z1, u, e = point
    (tmp_path / "pair.toml").write_text(pair_to_toml(bare_candidate(z1, u, e, 35.0, 0.3, "drive")))
    out = tmp_path / "out"
    run = subprocess.run([shutil.which("gearcontact"), "analyze", "--pair",
                          str(tmp_path / "pair.toml"), "--out", str(out), "--phases",
                          str(PHASES), "--quiet"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    chosen = re.search(r"path angle chosen: ([-0-9.]+) deg", (out / "summary.md").read_text())
    assert float(chosen.group(1)) == pytest.approx(TURNED[point], abs=0.1)
    _check_results(out)
