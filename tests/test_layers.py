"""The package's import layers hold (import-linter contracts in pyproject.toml).

Truth: the contracts themselves, checked by ``lint-imports`` on the installed package's
import graph; and the layer list covers every subpackage, so a new package cannot
escape the contract by not being named.
"""

import shutil
import subprocess
import tomllib
from pathlib import Path

import pytest

import gearcontact

ROOT = Path(__file__).resolve().parents[1]
#: Modules below every layer that any layer may use (no gearcontact imports of their own).
UTILITIES = {"threads", "figure_files", "errors", "deprecation", "lazy_names"}


def _config() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]


def test_contracts_kept():
    exe = shutil.which("lint-imports")
    if exe is None:
        pytest.skip("import-linter not installed (test extra)")
    run = subprocess.run([exe, "--config", str(ROOT / "pyproject.toml")], cwd=ROOT,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-2000:]
    assert "0 broken" in run.stdout


def test_every_subpackage_is_layered():
    layers = next(c for c in _config()["contracts"] if c["id"] == "layers")["layers"]
    named = {m.strip().removeprefix("gearcontact.")
             for layer in layers for m in layer.replace(":", "|").split("|")}
    pkg = Path(gearcontact.__file__).parent
    present = {p.name for p in pkg.iterdir() if (p / "__init__.py").exists()}
    present |= {p.stem for p in pkg.glob("*.py") if not p.stem.startswith("_")}
    assert present - named - UTILITIES == set()
    assert named <= present


def test_no_library_module_imports_the_cli():
    import grimp

    graph = grimp.build_graph("gearcontact")
    importers = {m for m in graph.find_modules_that_directly_import("gearcontact.cli")
                 | {i for c in graph.find_children("gearcontact.cli")
                    for i in graph.find_modules_that_directly_import(c)}
                 if not m.startswith("gearcontact.cli")}
    assert importers - {"gearcontact.__main__"} == set()
