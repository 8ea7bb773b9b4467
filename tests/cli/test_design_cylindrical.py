"""``gearcontact design`` on cylindrical pairs (ISO 21771 table and JSON), and the
commands that do not take them yet refusing with exit 2 naming ``kind``."""

import json
import re
from pathlib import Path

import pytest

from gearcontact.cli import main

ROOT = Path(__file__).resolve().parents[2]
FZG = str(ROOT / "examples" / "fzg_c_type.toml")
EV = str(ROOT / "examples" / "ev_reducer_helical_23x67.toml")


def test_design_table_fzg(capsys):
    """The printed table carries the published FZG C values (alpha_wt 22.44 deg,
    eps_alpha 1.44: tests/geometry/cylindrical/README.md) at 4 decimals."""
    assert main(["design", "--pair", FZG]) == 0
    text = capsys.readouterr().out
    assert "ISO 21771" in text
    rows = {cells[0]: cells[1:] for cells in
            (re.split(r"\s{2,}", line.strip()) for line in text.splitlines()[1:])}
    assert rows["tip diameter d_a [mm]"] == ["82.4600", "118.3600"]
    assert float(rows["working pressure angle alpha_wt [deg]"][0]) == pytest.approx(22.44, abs=0.005)
    assert float(rows["transverse contact ratio eps_alpha"][0]) == pytest.approx(1.44, abs=0.005)


def test_design_json_helical(capsys):
    """eps_beta = b sin(beta) / (pi m_n) with b = 30 mm (the smaller face), 1e-12."""
    import math

    assert main(["design", "--pair", EV, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["kind"] == "cylindrical" and out["pair"] == "ev_reducer_helical_23x67"
    assert out["overlap_ratio"] == pytest.approx(30 * math.sin(math.radians(25)) / (2 * math.pi), rel=1e-12)
    assert out["total_contact_ratio"] == pytest.approx(
        out["transverse_contact_ratio"] + out["overlap_ratio"], rel=1e-12)


# (`bending` reads cylindrical pairs since session 18: tests/cli/test_bending.py; `ltca`
# since session 19: tests/cli/test_ltca_cylindrical.py)
@pytest.mark.parametrize("argv", [["design", "--pair", FZG, "--synthesize-easeoff"]])
def test_other_commands_refuse_cylindrical(argv, capsys, tmp_path):
    argv = [str(tmp_path / "out") if a == "OUT" else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "kind = 'cylindrical'" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()
