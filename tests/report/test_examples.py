"""The shipped example pairs run the main job end to end (issue 11).

None of them carries an ease-off table, so each run synthesizes one (stated in the
output and in summary.md). Truths: the synthesized TE0 target (3 arcsec at 31 phases)
reappears in the 15-phase TCA within the discretization (2-6.5 arcsec: a coarser
phase grid samples the parabola's ends differently); the bearing at the mean phase is
inside the flank; the loaded patch is Hertzian (LCP p90 within 15 % of the preview
p_max, no edge contact: the patch lies inside the tooth) and the Hertz ellipse fits the
tooth (2a below the face width, 2b below the working depth).
"""

import json
from pathlib import Path

import pytest

from gearcontact.cli import main
from gearcontact.geometry.pair import load_pair

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("name", ["iso23509_f3.toml", "iso23509_f2_spiral_bevel.toml",
                                  "hypoid_11x41_rear_axle.toml"])
def test_example_runs_analyze(name, tmp_path, capsys):
    path = EXAMPLES / name
    assert main(["analyze", "--pair", str(path), "--out", str(tmp_path), "--phases", "15",
                 "--torques", "64.5", "--lte-phases", "0", "--no-figures", "--quiet"]) == 0
    assert "ease-off synthesized" in capsys.readouterr().out
    assert "Ease-off synthesized" in (tmp_path / "summary.md").read_text()
    tca = json.loads((tmp_path / "tca.json").read_text())
    assert 2.0 <= tca["te0_pp_arcsec"] <= 6.5
    edges = tca["phase_edges"]
    assert edges[len(edges) // 2] == ""
    assert sum(1 for e in edges if e) <= len(edges) // 3
    case = json.loads((tmp_path / "ltca.json").read_text())[0]
    assert not case["edge_contact"]
    assert case["p90_mpa"] == pytest.approx(case["preview_p_max_mpa"], rel=0.15)
    pair = load_pair(path)
    blank = pair.blank
    assert 2.0 * case["preview_a_mm"] < pair.gear_face_width_mm
    assert 2.0 * case["preview_b_mm"] < blank.working_depth_mm
