"""The README's commands on the shipped cylindrical example pairs, exactly as written.

Every ``kind = "cylindrical"`` pair file in ``examples/`` appears in the README in a
command; each such line runs with the README's options (only ``--out`` is redirected
into the test's directory) through :func:`gearcontact.cli.main`.

Truths: ``design`` prints the ISO 21771 working pressure angle and transverse contact
ratio of the pair, computed here from the closed forms of ISO 21771 (inv alpha_wt =
inv alpha_t + 2 tan alpha_n (x1 + x2) / (z1 + z2) for the zero-backlash centre distance,
eps_alpha = g_alpha / p_bt), to the 4 decimals printed (alpha_wt at the pair's centre distance a_w, which must
agree with the zero-backlash angle from x1 + x2 to 1e-3 deg); ``tca`` of an unmodified spur pair
at the reference centre distance has TE0 = 0 (conjugate involutes, 1e-3 arcsec, the
issue's bound) and as many pairs in the zone on average as eps_alpha (two count steps
per pitch, each placed within one phase step: 2 / (phases - 1)).
"""

import json
import math
import re
import shlex
import tomllib
from pathlib import Path

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.geometry.pair import CYLINDRICAL, load_pair

from .test_examples import readme_commands

ROOT = Path(__file__).resolve().parents[2]
CYLINDRICAL_EXAMPLES = sorted(p.name for p in (ROOT / "examples").glob("*.toml")
                              if tomllib.loads(p.read_text()).get("kind") == CYLINDRICAL)


def _lines() -> dict[str, list[list[str]]]:
    found: dict[str, list[list[str]]] = {}
    for line in readme_commands():
        argv = shlex.split(line)[1:]
        if "--pair" in argv and Path(argv[argv.index("--pair") + 1]).name in CYLINDRICAL_EXAMPLES:
            found.setdefault(Path(argv[argv.index("--pair") + 1]).name, []).append(argv)
    return found


def _involute(a: float) -> float:
    return math.tan(a) - a


def test_every_cylindrical_example_has_a_readme_command():
    assert len(CYLINDRICAL_EXAMPLES) >= 3
    missing = set(CYLINDRICAL_EXAMPLES) - set(_lines())
    assert not missing, f"README has no command for {missing}"


@pytest.mark.parametrize("argv", [a for v in _lines().values() for a in v if a[0] == "design"],
                         ids=lambda a: Path(a[a.index("--pair") + 1]).stem)
def test_readme_design_cylindrical(argv, capsys):
    assert main(argv) == 0
    text = capsys.readouterr().out
    pair = load_pair(ROOT / argv[argv.index("--pair") + 1], kinds=(CYLINDRICAL,))
    c = tomllib.loads((ROOT / argv[argv.index("--pair") + 1]).read_text())["cylindrical"]
    z1, z2 = pair.pinion_teeth, pair.gear_teeth
    an = math.radians(c["normal_pressure_angle_deg"])
    beta = math.radians(c["helix_angle_deg"])
    at = math.atan(math.tan(an) / math.cos(beta))
    x = c["profile_shift_pinion"] + c["profile_shift_gear"]
    inv = _involute(at) + 2.0 * math.tan(an) * x / (z1 + z2)
    awt_x = at
    for _ in range(60):  # Newton on inv(a) = inv: the zero-backlash working angle
        awt_x -= (_involute(awt_x) - inv) / math.tan(awt_x) ** 2
    # the mesh runs at the pair's centre distance a_w: cos alpha_wt = a cos alpha_t / a_w
    aw = float(re.search(r"centre distance a_w \[mm\]\s+([\d.]+)", text)[1])
    a = 0.5 * (z1 + z2) * c["normal_module_mm"] / math.cos(beta)
    awt = math.acos(a * math.cos(at) / aw)
    printed = float(re.search(r"working pressure angle alpha_wt \[deg\]\s+([\d.]+)", text)[1])
    assert printed == pytest.approx(math.degrees(awt), abs=5e-5)
    # a_w is at most the rounding of published shifts away from zero backlash: the two
    # working angles agree to 1e-3 deg
    assert math.degrees(awt) == pytest.approx(math.degrees(awt_x), abs=1e-3)
    # eps_alpha from the printed diameters (d_a may be shortened, ISO 21771 sec. 5)
    d = {k: [float(v) for v in re.search(rf"{k}\s+([\d.]+)\s+([\d.]+)", text).groups()]
         for k in (r"tip diameter d_a \[mm\]", r"base diameter d_b \[mm\]")}
    (da1, da2), (db1, db2) = d.values()
    mt = c["normal_module_mm"] / math.cos(beta)
    g_alpha = (0.5 * math.sqrt(da1**2 - db1**2) + 0.5 * math.sqrt(da2**2 - db2**2)
               - aw * math.sin(awt))
    eps = g_alpha / (math.pi * mt * math.cos(at))
    printed = float(re.search(r"transverse contact ratio eps_alpha\s+([\d.]+)", text)[1])
    # the printed diameters are rounded to 1e-4 mm: 1e-3 on eps_alpha
    assert printed == pytest.approx(eps, abs=1e-3)


@pytest.mark.parametrize("argv", [a for v in _lines().values() for a in v if a[0] == "tca"],
                         ids=lambda a: Path(a[a.index("--pair") + 1]).stem)
def test_readme_tca_cylindrical(argv, tmp_path):
    argv = list(argv)
    argv[argv.index("--out") + 1] = str(tmp_path / "run")
    assert main(argv) == 0
    pair = load_pair(ROOT / argv[argv.index("--pair") + 1], kinds=(CYLINDRICAL,))
    te = np.genfromtxt(tmp_path / "run" / "te0.csv", delimiter=",", names=True)
    assert np.isfinite(te["te0_arcsec"]).all()
    doc = json.loads((tmp_path / "run" / "tca.json").read_text())
    assert doc["te0_pp_arcsec"] == pytest.approx(np.ptp(te["te0_arcsec"]), abs=1e-9)
    if pair.name == "spur_20x40_m3":
        assert np.abs(te["te0_arcsec"]).max() < 1e-3
        steps = len(te) - 1
        assert np.mean(te["pairs_in_zone"][:-1]) == pytest.approx(
            pair.geometry.transverse_contact_ratio, abs=2 / steps)
