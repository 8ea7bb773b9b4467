"""The main job end to end on s0003 (reduced phase count to stay fast).

Truths checked: the preview is Hertz (p_max ~ W^(1/3) exactly for fixed curvatures);
LCP load balance; at the lowest torque the loaded patch lies inside the flank and the
real gap field is close to quadratic, so the LCP peak equals the Hertzian p_max within
the quadratic-fit deviation (2 %, Johnson 1985 ch. 4); pressures and approach increase
with load; the golden preview agrees with fp64 within its 0.5 % acceptance bound.
"""

import json

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.preview.engine import GoldenEngine
from gearcontact.report.analyze import (PREVIEW_COLUMNS, _golden_preview, _missing_warning,
                                        published_values, run_analysis)

TORQUES = (32.25, 64.5, 258.0)


@pytest.fixture(scope="module")
def analysis(tmp_path_factory):
    out = tmp_path_factory.mktemp("analyze")
    return run_analysis("s0003-centred", out_dir=out, torques_nm=TORQUES, phases=15, progress=False)


def test_files_written(analysis):
    out = analysis.out_dir
    for name in ("design.json", "tca.json", "te0.csv", "gap_stencil.csv", "phase_table.bin",
                 "ltca.json", "ltca_torques.csv", "preview.csv", "pressure_64.5Nm.csv",
                 "pressure_maps.png", "pressure_vs_load.png", "summary.md", "te0.png",
                 "contact_pattern.png", "lte.json", "lte.csv", "lte.png", "precision.csv",
                 "precision.png", "latency.json"):
        assert (out / name).stat().st_size > 0, name
    # every figure also as SVG beside its PNG (gearcontact.figure_files)
    pngs = sorted(out.glob("*.png"))
    assert len(pngs) >= 7
    assert [p.name for p in pngs if not p.with_suffix(".svg").is_file()] == []
    rows = json.loads((out / "ltca.json").read_text())
    assert [r["torque_nm"] for r in rows] == list(TORQUES)
    for key in ("load_n", "p_mean_mpa", "p90_mpa", "p_peak_mpa", "delta_mm",
                "mesh_rotation_arcsec", "n_contact_cells", "preview_p_max_mpa", "solver"):
        assert key in rows[0]
    text = (out / "summary.md").read_text()
    assert "preview vs p90" in text and "3.4" in text  # published TE0 beside ours


def test_preview_is_hertzian_in_load(analysis):
    w = np.array([c.load_n for c in analysis.cases])
    p = np.array([c.preview.p_max_mpa for c in analysis.cases])
    # same curvatures at every torque: p_max / W^(1/3) is constant to rounding
    np.testing.assert_allclose(p / np.cbrt(w), p[0] / np.cbrt(w[0]), rtol=1e-12)


def test_lcp_load_balance_and_monotonic(analysis):
    cases = analysis.cases
    for c in cases:
        assert c.patch.converged
        # sum of nodal loads = W (the load constraint closes delta)
        assert c.patch.lcp.loads_n.sum() == pytest.approx(c.load_n, rel=1e-8)
    for a, b in zip(cases, cases[1:]):
        assert b.patch.p_mean_mpa > a.patch.p_mean_mpa
        assert b.patch.p90_mpa > a.patch.p90_mpa
        assert b.patch.delta_mm > a.patch.delta_mm
        assert b.mesh_rotation_arcsec > a.mesh_rotation_arcsec


def test_low_load_patch_is_hertzian(analysis):
    c = analysis.cases[0]
    assert not c.edge_contact
    assert c.patch.p_peak_mpa == pytest.approx(c.preview.p_max_mpa, rel=0.02)
    # rigid approach vs the Hertzian approach of the same curvatures
    assert c.mesh_rotation_arcsec == pytest.approx(c.preview_mesh_rotation_arcsec, rel=0.03)


def test_high_load_reaches_flank_edge(analysis):
    # at 258 N·m the bearing runs off the tooth: edge contact with a tip spike
    c = analysis.cases[-1]
    assert c.edge_contact
    assert c.patch.p_peak_mpa > 2.0 * c.patch.p90_mpa


def test_golden_preview_matches_reference(analysis):
    for c, g in zip(analysis.cases, analysis.golden):
        assert g.valid
        assert g.p_max_mpa == pytest.approx(c.preview.p_max_mpa, rel=5e-3)
    # C -> D is the line chain (fit core into the line core, 52 + 759 edges); s0003's
    # ellipse fits its flank, so it answers in elliptic mode
    assert all(ch.cycles == 811 and ch.mode == "elliptic" for ch in analysis.golden_chain)


def test_preview_csv_says_which_mode_evaluated_each_torque(analysis):
    # s0003's curvatures lie inside the published core's range: every fixed-point column
    # evaluated; the line core in elliptic mode (at 258 N·m the flank cuts the major axis
    # at L = 4.96 mm < 2a = 7.1 mm, but the ellipse's peak stays the higher of the two
    # lower bounds) and equal to the fp64 rule within the 0.5 % acceptance bound
    lines = (analysis.out_dir / "preview.csv").read_text().splitlines()
    assert lines[0].split(",") == PREVIEW_COLUMNS
    rows = [dict(zip(PREVIEW_COLUMNS, ln.split(","))) for ln in lines[1:]]
    assert len(rows) == len(TORQUES)
    for row, ref in zip(rows, analysis.reference):
        assert row["golden_status"] == row["chain_status"] == "ok"
        assert (row["ref_mode"] == row["golden_mode"] == row["chain_mode"] == ref.mode
                == "elliptic")
        assert row["chain_cycles"] == "811"
        c = next(c for c in analysis.cases if c.torque_nm == float(row["torque_nm"]))
        width = float(c.patch.grid.dx_mm.sum())
        assert 0 < float(row["line_length_mm"]) <= width + 1e-9   # cut by flank or field
        assert float(row["golden_p_max_mpa"]) == pytest.approx(ref.p_max_mpa, rel=5e-3)


def test_missing_fixed_point_results_are_statuses_and_one_warning_line():
    gold = GoldenEngine()
    # published path below its curvature range: not evaluated (the engine's check);
    # the line core flags a 2 m contact line; inside both: ok
    res = [_golden_preview(gold.hertz, 0.0246, 2.3e-4, 603.0),
           _golden_preview(gold.hertz, 0.0246, 2.3e-4, 603.0, line_length_mm=2000.0),
           _golden_preview(gold.hertz, 0.0246, 2.3e-4, 603.0, line_length_mm=20.0)]
    assert [st for _, st in res] == ["outside_envelope", "flagged:length_range", "ok"]
    assert res[0][0] is None and res[1][0].p_max_mpa == 0 and res[2][0].mode == "elliptic"
    msg = _missing_warning(res, [res[2]] * 3)
    assert "\n" not in msg and "golden D (line core) p_max missing for 2 of 3 torques" in msg
    assert "flagged:length_range" in msg and "outside_envelope" in msg
    assert "C->D" not in msg
    assert _missing_warning([res[2]], [res[2]]) is None


def test_published_values_have_provenance():
    pub = published_values("s0003")
    assert "_provenance" in pub and pub["te0_pp_arcsec"] == 3.40
    assert published_values("no-such-pair") is None


def test_cli_analyze(tmp_path, capsys):
    code = main(["analyze", "--pair", "s0003-centred", "--out", str(tmp_path / "o"), "--torques",
                 "64.5", "--phases", "9", "--no-figures", "--quiet", "--lte-phases", "0"])
    assert code == 0
    assert "summary.md" in capsys.readouterr().out
    assert (tmp_path / "o" / "summary.md").exists()
    assert not (tmp_path / "o" / "pressure_maps.png").exists()
    assert not (tmp_path / "o" / "lte.json").exists()  # --lte-phases 0 skips the LTE
    # --no-figures: the summary links no PNG; the manifest lists every file written
    assert ".png" not in (tmp_path / "o" / "summary.md").read_text()
    run = json.loads((tmp_path / "o" / "run.json").read_text())
    listed = sorted(f["path"] for f in run["files"])
    assert listed == sorted(p.name for p in (tmp_path / "o").iterdir()
                            if not p.name.startswith(".") and p.name != "run.json")
    assert {"tca_s", "ltca_solve_ms", "preview_cpu", "jit_warm_up_s"} <= set(run["timings_s"])


def test_cli_analyze_calibrated_preset(tmp_path, capsys):
    # the README's main job on the calibrated preset: the design-point table shows P0
    # reached (docs/calibration.md) and the loaded patch is edge-loaded (peak > 3 x p90).
    # 61 phases: P0 is the discrete TE0 vertex, within half a phase step (~0.03 mm at 61
    # phases per pitch, ~0.15 mm at 15) of the calibrated continuous vertex
    code = main(["analyze", "--pair", "s0003", "--out", str(tmp_path / "o"), "--torques",
                 "64.5", "--phases", "61", "--no-figures", "--quiet", "--lte-phases", "0"])
    assert code == 0
    text = (tmp_path / "o" / "summary.md").read_text()
    assert "## Design point (coast flank pair)" in text
    rows = [r for r in text.splitlines() if r.startswith("| P0 ")]
    assert len(rows) == 4 and all(r.endswith("| yes |") for r in rows)
    case = json.loads((tmp_path / "o" / "ltca.json").read_text())[0]
    assert case["p_peak_mpa"] > 3.0 * case["p90_mpa"]


def test_cli_analyze_bad_torque(tmp_path, capsys):
    code = main(["analyze", "--out", str(tmp_path / "o"), "--torques", "-3", "--phases", "9",
                 "--quiet"])
    assert code == 2
    assert "--torques" in capsys.readouterr().err


def test_lte_in_main_job(analysis):
    # the loaded TE of the main job: torque balance closes at every phase and the loaded
    # rotation reduces the unloaded TE variation (load sharing smooths it)
    lte = analysis.lte
    d = json.loads((analysis.out_dir / "lte.json").read_text())
    assert d["te_lcp_pp_arcsec"] == pytest.approx(lte.te_lcp_pp_arcsec)
    assert 0.0 < lte.te_lcp_pp_arcsec < analysis.tca.cycle.te0_pp_arcsec
    assert 0.0 < lte.te_pre_pp_arcsec < analysis.tca.cycle.te0_pp_arcsec


def test_multitooth_in_main_job(analysis):
    # the multi-tooth section: the written JSON is the computed case (no timings in it),
    # shares sum to 100 %, bending rotates more, and summary.md sets the published
    # 74.6 / 22.6 / 2.8 %, +12 % and CP_max 2714 MPa beside ours
    mt = analysis.multitooth
    d = json.loads((analysis.out_dir / "multitooth.json").read_text())
    assert d["load_share_pct"] == pytest.approx(mt.load_share_pct, rel=1e-15)
    assert sum(d["load_share_pct"]) == pytest.approx(100.0, rel=1e-12)
    assert d["mesh_rotation_arcsec"] > d["mesh_rotation_rigid_arcsec"] and d["converged"]
    assert "solve_ms" not in d and analysis.timings_s["multi_tooth_solve_ms"] > 0
    assert (analysis.out_dir / "multitooth.png").stat().st_size > 0
    text = (analysis.out_dir / "summary.md").read_text()
    assert "## Multi-tooth loaded contact at P0" in text
    for published in ("74.6 / 22.6 / 2.8", "| 2714 |", "| 12 |", "| 124.4 |"):
        assert published in text, published


def test_law_status_columns(analysis):
    """s0003's curvature ratios (those the previews took, checked here) lie inside the
    range where Hamrock–Brewe is within 5 % of exact Hertz (ratio <= 122, docs/hertz.md
    sec. 7): every law status column is ok."""
    lines = (analysis.out_dir / "preview.csv").read_text().splitlines()
    rows = [dict(zip(PREVIEW_COLUMNS, ln.split(","))) for ln in lines[1:]]
    for row, ref in zip(rows, analysis.reference):
        assert max(ref.A_minus_per_mm, ref.B_minus_per_mm) < 122.0 * min(
            ref.A_minus_per_mm, ref.B_minus_per_mm)
        assert row["ref_law_status"] == row["golden_law_status"] == \
            row["chain_law_status"] == "ok"


def test_each_torque_is_solved_from_its_own_torque_alone(analysis):
    """A torque's LTCA does not depend on the torques solved before it in the job: each
    row equals, bit for bit, the library's own solve of that torque alone in this process
    (no tolerance: identical inputs give identical results, docs/architecture.md
    "Rules"; the LCP's own tolerance, 1e-8, would let a solve warm-started from the
    previous torque end elsewhere)."""
    from gearcontact.ltca.pair_ltca import single_pair_ltca

    from same_results import assert_same

    for case in analysis.cases[1:]:
        alone = single_pair_ltca(analysis.tca, analysis.flanks, analysis.pair,
                                 case.torque_nm, side=analysis.side)
        assert_same(case, alone)
