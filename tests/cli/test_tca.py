"""``gearcontact tca`` end to end through :func:`gearcontact.cli.main`.

Truths: the files the issue lists exist with the documented content; the published
s0003 blank angles (docs/spec.md sec. 3) appear in tca.json; the binary phase table decodes to
the JSON table within half an LSB; the stencil passes the preview's format reader.
"""

import json

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.preview.fit.stencil import read_stencil_csv
from gearcontact.preview.qformat import COORD, CURVATURE
from gearcontact.tca.phase_table import decode_binary, read_json


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    d = tmp_path_factory.mktemp("tca") / "new" / "dir"      # created by the command
    assert main(["tca", "--pair", "s0003-centred", "--out", str(d), "--phases", "61",
                 "--quiet"]) == 0
    return d


def test_writes_every_file(out):
    for name in ("tca.json", "te0.csv", "contact_path.csv", "gap_stencil.csv",
                 "gap_field.csv", "phase_table.json", "phase_table.bin", "te0.png",
                 "contact_pattern.png", "flanks_in_mesh.png"):
        assert (out / name).stat().st_size > 0, name


def test_summary_keys_and_values(out):
    doc = json.loads((out / "tca.json").read_text())
    # docs/spec.md sec. 3 published pitch angles (pinion, gear), rounded to 0.01 deg
    assert doc["pitch_angles_deg"] == pytest.approx([6.07, 83.15], abs=0.005)
    assert len(doc["spiral_angles_deg"]) == 2
    assert doc["te0_pp_arcsec"] == pytest.approx(3.4, rel=0.25)
    assert len(doc["mating_point_mm"]) == 3
    # A- >= B- > 0 (1/mm), stage-C naming of docs/spec.md sec. 6
    assert doc["A_minus"] > doc["B_minus"] > 0
    assert doc["phases_per_pitch"] == 61 and doc["pattern_on_flank"] is True


def test_tables_round_trip(out):
    table = read_json(out / "phase_table.json")
    assert len(table.phi1_deg) == 61
    te = np.loadtxt(out / "te0.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(te[:, 0], table.phi1_deg, atol=1e-9)
    np.testing.assert_allclose(te[:, -3], table.te0_arcsec, atol=1e-9)
    raw = (out / "phase_table.bin").read_bytes()
    assert len(raw) < 500                            # "a few hundred bytes"
    dec = decode_binary(raw)
    rows = np.arange(0, 60, 4)                       # 60 distinct phases, 15 records
    np.testing.assert_allclose(dec.point_mm, table.point_mm[rows], atol=COORD.lsb / 2)
    np.testing.assert_allclose(dec.A_minus_per_mm, table.A_minus_per_mm[rows],
                               atol=CURVATURE.lsb / 2)
    gaps = read_stencil_csv(out / "gap_stencil.csv")
    assert gaps[24] == pytest.approx(0.0, abs=1e-9)  # the centre sample is P0


def test_bad_pair_is_one_line_error(tmp_path, capsys):
    assert main(["tca", "--pair", str(tmp_path / "missing.toml"), "--out",
                 str(tmp_path)]) == 2
    assert "error" in capsys.readouterr().err
