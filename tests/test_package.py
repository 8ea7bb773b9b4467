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


def test_reading_a_pair_imports_no_solver():
    """``import gearcontact.geometry.pair`` (every command that takes ``--pair`` or
    shares its options) imports neither the rest of the geometry nor numba, scipy.optimize
    or matplotlib: they cost about 1 s of CPU per process (docs/performance.md, "Test
    suite budget"); the package's public names load on first use (lazy_names)."""
    import subprocess
    import sys

    code = ("import sys, gearcontact.geometry.pair\n"
            "print(*sorted(m for m in ('numba', 'scipy.optimize', 'matplotlib',\n"
            "      'gearcontact.geometry.flank', 'gearcontact.geometry.conjugate')\n"
            "      if m in sys.modules))")
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True, timeout=300).stdout.split()
    assert loaded == []
