"""``gearcontact analyze`` with default options on a pair whose pinion blades carry a
Toprem (tests/data/toprem/README.md): the run completes, and what the kink does is
reported, not hidden. The numbers' truths are tests/tca/test_kink_contact.py and
tests/geometry/test_kinked.py; here: the pinion's kink ridge carries the contact where
the flank's normal jumps past the gear's (edge contact ``pinion toprem``, docs/
machine_settings.md sec. 1), and the 7 x 7 stencil at P0 (u = 2.54 mm, the kink at
2.1 mm, the stencil reaching 0.6 mm) straddles the kink and says so."""

import json
from pathlib import Path

import pytest

from gearcontact.cli import main

PAIR = Path(__file__).resolve().parents[1] / "data" / "toprem" / "iso23509_f2_toprem.toml"


@pytest.mark.slow
def test_analyze_runs_on_a_toprem_pair_and_reports_the_kink(tmp_path):
    # ~1 to 2 min (the full analyze job)
    out = tmp_path / "run"
    assert main(["analyze", "--pair", str(PAIR), "--out", str(out), "--quiet"]) == 0
    tca = json.loads((out / "tca.json").read_text())
    assert tca["edge_contact_phases"].get("pinion toprem", 0) > 0
    assert tca["stencil"]["kinks"] == ["pinion toprem"]
    summary = (out / "summary.md").read_text()
    assert "pinion toprem" in summary and "straddles the blade-relief kink" in summary
