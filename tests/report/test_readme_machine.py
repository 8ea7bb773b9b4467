"""The README's machine-settings lines, verbatim, in a real process (issue 27).

``gearcontact design --pair examples/iso23509_f2_spiral_bevel.toml --machine-settings
--out mach/`` writes the standard settings of the F.2 pair; ``gearcontact analyze --pair
mach/machine_settings.toml --out results/f2_machine`` runs the main job on the flanks cut
from them. Both lines run as printed from a scratch directory holding a link to
``examples/``, so their relative paths resolve as in a checkout.

Truths: the written file loads back as the F.2 pair with settings for all four flanks
(that the settings reproduce the blank's spiral and pressure angles is
tests/geometry/test_basic_settings.py's); ``analyze`` synthesizes no ease-off for it,
conserves load in the multi-tooth step (shares add to 100 %, 1e-9 %) and its loaded
TE's LCPs converged.
"""

import json
import os
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

import gearcontact
from gearcontact.geometry.pair import load_pair

from .test_examples import readme_commands

ROOT = Path(__file__).resolve().parents[2]


def _readme_lines() -> list[str]:
    design = [c for c in readme_commands() if "--machine-settings" in c]
    analyze = [c for c in readme_commands()
               if c.startswith("gearcontact analyze") and "machine_settings.toml" in c]
    assert len(design) == 1 and len(analyze) == 1, (design, analyze)
    return [design[0], analyze[0]]


def _run(line: str, cwd: Path) -> subprocess.CompletedProcess:
    src = str(Path(gearcontact.__file__).parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
    return subprocess.run([sys.executable, "-m", "gearcontact", *shlex.split(line)[1:]],
                          cwd=cwd, env=env, capture_output=True, text=True, timeout=3000,
                          check=False)


def test_readme_machine_settings_lines(tmp_path):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    design, analyze = _readme_lines()
    proc = _run(design, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    written = tmp_path / "mach" / "machine_settings.toml"
    pair = load_pair(written)
    assert len(pair.machine) == 4
    base = load_pair(ROOT / "examples" / "iso23509_f2_spiral_bevel.toml")
    assert (pair.pinion_teeth, pair.gear_teeth) == (base.pinion_teeth, base.gear_teeth)
    proc = _run(analyze, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    out = tmp_path / "results" / "f2_machine"
    assert "ease-off synthesized" not in proc.stdout
    tca = json.loads((out / "tca.json").read_text())
    assert tca["te0_pp_arcsec"] > 0.0
    mt = json.loads((out / "multitooth.json").read_text())
    assert sum(mt["load_share_pct"]) == pytest.approx(100.0, abs=1e-9)
    lte = json.loads((out / "lte.json").read_text())
    for rec in (lte if isinstance(lte, list) else [lte]):
        assert rec["converged"], rec.get("unconverged_phases")
