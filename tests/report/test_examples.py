"""The README's commands on the shipped example pairs, exactly as written (issue 28).

Every bevel/hypoid pair file in ``examples/`` appears in the README in an ``analyze`` and a ``twin``
command; each such command runs through the console script in a real process with the
README's options (only ``--out`` is redirected into the test's directory), so the
default options are what is tested: ease-off synthesis (no example carries a table),
TCA, LTCA at four torques, the multi-tooth step and the loaded TE.

Truths (``analyze``): the synthesized TE0 target (3 arcsec at 31 phases) reappears in
the default TCA within the discretization (2-6.5 arcsec); the bearing at the mean phase
is inside the flank; at 64.5 N·m the loaded patch is Hertzian (LCP p90 within 15 % of
the preview p_max, no edge contact) and the Hertz ellipse fits the tooth; the
multi-tooth load shares add up to the total (conservation, 1e-9 %); the loaded TE's
LCPs converged. Truths (``twin``): the mesh carries the load torque on average (static
balance T_mesh = T_load, 3 %: the mean over the second half of the run within the
dynamic swing); the preview law is defined at every loaded step (no saddle).

Cost on the project machine (2 cores): ``analyze`` of an example 31-50 s CPU (the
ease-off synthesis 10-23 s of it, benchmarks/bench_analyze_examples.py); ``twin``
~1.5 min. The F2 twin (cheapest) is in the default
suite, the other twins are slow.
"""

import json
import os
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from readme_lines import readme_commands

import gearcontact
from gearcontact.geometry.pair import load_pair

ROOT = Path(__file__).resolve().parents[2]
#: the bevel/hypoid pairs (cylindrical pairs, ``kind = "cylindrical"``, run ``design``
#: only so far: tests/cli/test_design_cylindrical.py)
EXAMPLES = sorted(p for p in (ROOT / "examples").glob("*.toml")
                  if "[teeth]" in p.read_text() and "kind" not in tomllib.loads(p.read_text()))
#: twin commands in the default suite (the others carry the slow mark)
DEFAULT_TWINS = {"iso23509_f2_spiral_bevel.toml"}


def _example_commands(command: str) -> dict[str, list[str]]:
    found = {}
    for line in readme_commands():
        argv = shlex.split(line)[1:]
        if argv[0] == command and "--pair" in argv:
            pair = argv[argv.index("--pair") + 1]
            if pair.startswith("examples/"):
                found[Path(pair).name] = argv
    return found


def _params(command: str):
    cmds = _example_commands(command)
    for path in EXAMPLES:
        marks = () if command == "analyze" or path.name in DEFAULT_TWINS else (pytest.mark.slow,)
        yield pytest.param(path.name, cmds.get(path.name), id=path.stem, marks=marks)


def _run(argv: list[str], out: Path) -> subprocess.CompletedProcess:
    """The README command in a real process from the repository root, --out redirected."""
    argv = list(argv)
    argv[argv.index("--out") + 1] = str(out)
    src = str(Path(gearcontact.__file__).parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
    return subprocess.run([sys.executable, "-m", "gearcontact", *argv], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=3000, check=False)


def test_every_example_has_readme_commands():
    assert EXAMPLES, "no example pair files found"
    for command in ("analyze", "twin"):
        missing = {p.name for p in EXAMPLES} - set(_example_commands(command))
        assert not missing, f"README has no `gearcontact {command}` line for {missing}"


@pytest.mark.parametrize("name, argv", _params("analyze"))
def test_readme_analyze_example(name, argv, tmp_path):
    assert argv is not None, f"README has no analyze line for {name}"
    proc = _run(argv, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "ease-off synthesized" in proc.stdout
    assert "Ease-off synthesized" in (tmp_path / "summary.md").read_text()
    tca = json.loads((tmp_path / "tca.json").read_text())
    assert 2.0 <= tca["te0_pp_arcsec"] <= 6.5
    edges = tca["phase_edges"]
    assert edges[len(edges) // 2] == ""
    assert sum(1 for e in edges if e) <= len(edges) // 3
    case = next(c for c in json.loads((tmp_path / "ltca.json").read_text())
                if c["torque_nm"] == 64.5)
    assert not case["edge_contact"]
    assert case["p90_mpa"] == pytest.approx(case["preview_p_max_mpa"], rel=0.15)
    pair = load_pair(ROOT / "examples" / name)
    assert 2.0 * case["preview_a_mm"] < pair.gear_face_width_mm
    assert 2.0 * case["preview_b_mm"] < pair.blank.working_depth_mm
    mt = json.loads((tmp_path / "multitooth.json").read_text())
    assert sum(mt["load_share_pct"]) == pytest.approx(100.0, abs=1e-9)
    assert mt["converged"]
    lte = json.loads((tmp_path / "lte.json").read_text())
    for rec in (lte if isinstance(lte, list) else [lte]):
        assert rec["converged"], rec.get("unconverged_phases")


@pytest.mark.parametrize("name, argv", _params("twin"))
def test_readme_twin_example(name, argv, tmp_path):
    assert argv is not None, f"README has no twin line for {name}"
    proc = _run(argv, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    data = json.loads((tmp_path / "twin.json").read_text())
    assert data["easeoff_synthesized"] is True
    assert "ease-off synthesized" in proc.stdout
    assert data["mean_mesh_torque_nm"] == pytest.approx(64.5, rel=0.03)
    assert data["previews_without_contact_law"] == 0
    assert data["steps_outside_datapath"] <= data["steps"]
    if data["previews_outside_datapath"]:
        assert "outside the fixed-point datapath's domain" in proc.stdout
