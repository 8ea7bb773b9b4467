"""``gearcontact tca`` end to end through :func:`gearcontact.cli.main`.

Truths: the files the issue lists exist with the documented content; the published
s0003 blank angles (docs/spec.md sec. 3) appear in tca.json; the binary phase table decodes to
the JSON table within half an LSB; the stencil passes the preview's format reader.
"""

import json

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.contract.stencil import read_stencil_csv
from gearcontact.contract.qformat import COORD, CURVATURE
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


def _s0003_centred_with(tmp_path, assembly: str):
    from importlib import resources

    text = resources.files("gearcontact").joinpath("data/pairs/s0003-centred.toml").read_text()
    path = tmp_path / "misaligned.toml"
    path.write_text(text.split("[assembly]")[0] + f"\n[assembly]\n{assembly}\n")
    return path


def test_misaligned_pair_reports_edges(tmp_path, capsys):
    """E = -0.2 mm (issue 11): a result, with the edge phases named in tca.json and
    phase_table.json, never a traceback."""
    pair = _s0003_centred_with(tmp_path, "E_mm = -0.2")
    out = tmp_path / "out"
    assert main(["tca", "--pair", str(pair), "--out", str(out), "--phases", "15",
                 "--quiet", "--no-figures"]) == 0
    assert "edge contact" in capsys.readouterr().out
    doc = json.loads((out / "tca.json").read_text())
    assert sum(doc["edge_phases"].values()) == 15 and len(doc["phase_edges"]) == 15
    assert json.loads((out / "phase_table.json").read_text())["edges"] == doc["phase_edges"]


def test_pattern_off_the_flank_exits_2_naming_the_edge(tmp_path, capsys):
    """G = -10 mm: the contact has left the flank at every start; one line, exit 2."""
    pair = _s0003_centred_with(tmp_path, "G_mm = -10.0")
    assert main(["tca", "--pair", str(pair), "--out", str(tmp_path / "o"), "--phases", "15",
                 "--quiet", "--no-figures"]) == 2
    err = capsys.readouterr().err
    assert "off the flank" in err and "pinion heel" in err and len(err.splitlines()) == 1


def test_zero_easeoff_reports_line_contact(tmp_path, capsys):
    """Explicit zero ease-off: tca reports the line contact (exit 0, tca.json), the
    loaded commands name it (exit 2)."""
    from importlib import resources

    text = resources.files("gearcontact").joinpath("data/pairs/s0003-centred.toml").read_text()
    head = text[:text.index("[easeoff.drive]")]
    pair = tmp_path / "zero.toml"
    pair.write_text(head + "[easeoff.drive]\nprofile_angle_um_per_mm = 0.0\n")
    out = tmp_path / "out"
    assert main(["tca", "--pair", str(pair), "--out", str(out), "--quiet"]) == 0
    doc = json.loads((out / "tca.json").read_text())
    assert doc["line_contact"] and doc["te0_max_abs_arcsec"] < 1e-3
    assert main(["ltca", "--pair", str(pair), "--out", str(tmp_path / "l")]) == 2
    assert "line contact" in capsys.readouterr().err


def test_misaligned_pair_loads_the_edge(tmp_path):
    """ltca and lte on misaligned s0003-centred (issue 11) run: E = -0.2 mm puts the
    patch on the pinion-tip / gear-heel edge, which the LCP reports as edge contact
    with an edge spike (sharp edge: peak several times p90); P = +0.1 mm through lte."""
    pair = _s0003_centred_with(tmp_path, "E_mm = -0.2")
    assert main(["ltca", "--pair", str(pair), "--out", str(tmp_path / "l"), "--phases", "15",
                 "--no-figures"]) == 0
    doc = json.loads((tmp_path / "l" / "ltca.json").read_text())
    assert doc["edge_contact"] and doc["p_peak_mpa"] > 3.0 * doc["p90_mpa"]
    pair = _s0003_centred_with(tmp_path, "P_mm = 0.1")
    assert main(["lte", "--pair", str(pair), "--out", str(tmp_path / "t"), "--phases", "15",
                 "--quiet", "--no-figures"]) == 0


def test_edge_to_surface_contact_is_written(tmp_path, capsys):
    """E = +0.2 mm (issue 11; the surface contact lies beyond the pinion toe at every
    phase): tca exits 0 and marks every phase's contact kind in tca.json and
    contact_path.csv; ltca at 64.5 N·m solves the edge-loaded patch and names the edge
    it reaches in ltca.json."""
    out = tmp_path / "t"
    assert main(["tca", "--pair", "s0003-centred", "--misalignment", "E=0.2", "--out",
                 str(out), "--phases", "15", "--quiet", "--no-figures"]) == 0
    assert "edge touches the other flank" in capsys.readouterr().out
    doc = json.loads((out / "tca.json").read_text())
    assert len(doc["phase_contact"]) == 15
    assert doc["mean_point_contact"] == "pinion toe"
    assert sum(doc["edge_contact_phases"].values()) == sum(
        1 for k in doc["phase_contact"] if k != "surface")
    rows = (out / "contact_path.csv").read_text().splitlines()
    assert rows[0].endswith(",edge_contact") and any(r.endswith(",pinion toe") for r in rows)
    lt = tmp_path / "l"
    assert main(["ltca", "--pair", "s0003-centred", "--misalignment", "E=0.2", "--out",
                 str(lt), "--phases", "15", "--cells", "48", "--no-figures"]) == 0
    doc = json.loads((lt / "ltca.json").read_text())
    assert doc["tca_edge_contact"] == "pinion toe" and doc["edge_contact"]
    assert "pinion toe" in doc["edge_contact_edges"] and doc["edge_pressure_ratio_p90"] > 1.0
