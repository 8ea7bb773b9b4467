"""Files of the cylindrical loaded TE (report.cylindrical_lte): where a tip edge beyond a
helical line carries, line_load.csv says so and its rows hold that edge's load."""

import csv
import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.pair import ToothModifications
from gearcontact.geometry.pair import load_pair
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.report.cylindrical_lte import write_cylindrical_lte_outputs
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.tca.cylindrical_tip import TIP_EDGES

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_line_load_names_the_edges_beyond_the_lines(tmp_path):
    """The EV pair without micro-geometry at 400 N·m (rigid, 7 phases, 16 rows): the rows
    of ``line_load.csv`` labelled ``"<edge> beyond line"`` carry that edge's normal load
    (sum of N/mm times the row pitch = its share of F_n; 1e-9 relative: the CSV's 12
    digits), with its lever, and ``lte.json`` counts the phases where one carries."""
    p = load_pair(EXAMPLES / "ev_reducer_helical_23x67.toml", kinds=("cylindrical",))
    p = replace(p, modifications_pinion=ToothModifications(member="pinion"),
                modifications_gear=ToothModifications(member="gear"))
    r = cylindrical_loaded_te(p, 400.0, cycle=cylindrical_mesh_cycle(p, phases=7),
                              bending=False, cells_along=16, cells_across=12)
    summary = write_cylindrical_lte_outputs(r, None, p, tmp_path, side="drive", figures=False)
    carry = r.beyond_load_share > 0.0
    assert summary["beyond_line_tip_phases"] == int(carry.any(axis=(0, 2)).sum()) > 0
    assert json.loads((tmp_path / "lte.json").read_text())["beyond_line_max_load_share"] \
        == pytest.approx(r.beyond_load_share.max(), rel=1e-12)
    with open(tmp_path / "line_load.csv") as f:
        rows = list(csv.DictReader(f))
    dz = r.z_mm[1] - r.z_mm[0]
    phi = np.degrees(r.phi1_rad)
    for j, k, e in zip(*np.nonzero(carry)):
        mine = [w for w in rows if w["contact"] == f"{TIP_EDGES[e].label} beyond line"
                and int(w["pair"]) == r.pair_offsets[j]
                and float(w["phi1_deg"]) == pytest.approx(phi[k], abs=1e-9)]
        assert mine
        load = sum(float(w["load_n_per_mm"]) for w in mine) * dz
        assert load == pytest.approx(r.beyond_load_share[j, k, e] * r.normal_load_n, rel=1e-9)
        assert all(float(w["lever_mm"]) == pytest.approx(r.beyond_lever_mm[j, k, e], rel=1e-11)
                   for w in mine)
