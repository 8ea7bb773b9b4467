"""Package-level contracts: the public API resolves, and the README's test command is
exactly what CI runs."""

import re
from pathlib import Path

import gearcontact

ROOT = Path(__file__).resolve().parents[1]


def test_public_api_resolves():
    import importlib

    for package in ("gearcontact", "gearcontact.geometry", "gearcontact.halfspace",
                    "gearcontact.sweep"):
        module = importlib.import_module(package)       # names served by lazy_names
        for name in module.__all__:
            assert getattr(module, name) is not None, (package, name)


def test_readme_test_command_is_ci_command():
    readme = (ROOT / "README.md").read_text()
    ci = (ROOT / ".ci" / "run").read_text()
    ci_cmd = [ln.strip() for ln in ci.splitlines() if "pytest" in ln and not ln.lstrip().startswith("#")]
    assert len(ci_cmd) == 1
    blocks = re.findall(r"```sh\n(.*?)```", readme, flags=re.S)
    assert any(ci_cmd[0] == ln.strip() for b in blocks for ln in b.splitlines())


def test_readme_main_job_uses_analyze():
    readme = (ROOT / "README.md").read_text()
    assert "gearcontact analyze --pair s0003 --out" in readme
