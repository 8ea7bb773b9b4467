"""Shared by the export tests.

- FMPy in a Python process where gearcontact cannot be imported (the situation of a
  twin developer who has only the FMU): :func:`simulate_isolated`, :func:`run_isolated`
  (a docs snippet as written).
- One run of the README's export lines per test run (both xdist workers: tests/run_once.py),
  shared by the export tests.
  
  The README shows ``gearcontact vectors --out vectors/ ...`` (three times: the default
  cores, the variants, the line cores), then
  ``gearcontact export c --out clib/ && make -C clib/ && clib/build/gearcontact_check vectors/``
  and ``gearcontact export fmu --pair s0003 --kind mesh|drivetrain --out ...``. They run once,
  verbatim, in a shell (the relative directories land in one session directory):
  tests/export/test_readme.py asserts on the runs, and tests/export/test_c_library.py
  uses the library that ``make -C clib/`` built (the default ``export c``; rendering
  and compiling it a second time proved nothing more).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from readme_lines import readme_commands
from run_once import run_once

ROOT = Path(__file__).resolve().parents[2]


def export_fmu_cli(*args, cwd) -> subprocess.CompletedProcess:
    """``gearcontact export fmu ARGS`` in a real process from this checkout's sources."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    return subprocess.run([sys.executable, "-m", "gearcontact", "export", "fmu", *args],
                          capture_output=True, text=True, env=env, cwd=cwd, timeout=600)


def _shell(line: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(["bash", "-c", line], cwd=cwd, capture_output=True, text=True,
                          timeout=900)


@pytest.fixture(scope="session")
def readme_export(tmp_path_factory):
    """``(directory, lines, runs)``: the README's vectors, export c and export fmu lines
    (``lines`` a dict of those three lists) run in order in ``directory``; ``runs`` maps
    each line run to its CompletedProcess. The runs stop at the first line that fails
    (the later lines depend on its files). Once per test run: the pytest-xdist workers
    share the directory (tests/run_once.py)."""
    if (shutil.which("gearcontact") is None or shutil.which("make") is None
            or shutil.which("gcc") is None):
        pytest.skip("the console script, make and gcc are needed")
    lines = {"vectors": readme_commands("gearcontact vectors --out vectors/"),
             "export_c": readme_commands("gearcontact export c"),
             "export_fmu": readme_commands("gearcontact export fmu")}

    def build(base):
        runs = {}
        for line in lines["vectors"] + lines["export_c"] + lines["export_fmu"]:
            run = _shell(line, base)
            runs[line] = [run.returncode, run.stdout, run.stderr]
            if run.returncode != 0:
                break
        return runs

    base, runs = run_once(tmp_path_factory, "readme_export", build)
    return base, lines, {line: subprocess.CompletedProcess(["bash", "-c", line], *run)
                         for line, run in runs.items()}


#: Run in ``python -I`` (no PYTHONPATH, no user site): a meta-path finder refuses every
#: ``gearcontact`` module before any other finder (the editable install would find it),
#: and the script checks that ``import gearcontact`` fails before it goes on.
_BLOCKER = r'''
import importlib.abc, sys

class Blocker(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == "gearcontact" or name.startswith("gearcontact."):
            raise ImportError(f"{name} is blocked: this process has no gearcontact")
        return None

sys.meta_path.insert(0, Blocker())
try:
    import gearcontact  # noqa: F401
except ImportError:
    pass
else:
    raise SystemExit("gearcontact was importable")
'''

#: ... then simulates the FMU with FMPy and writes the result columns as JSON (floats as
#: hex: exact).
_ISOLATED = _BLOCKER + r'''
import json
import fmpy
args = json.loads(sys.argv[1])
if "input_npy" in args:         # a structured input signal saved by numpy
    import numpy
    args["input"] = numpy.load(args.pop("input_npy"))
res = fmpy.simulate_fmu(args.pop("filename"), **args)
assert not [m for m in sys.modules if m.split(".")[0] == "gearcontact"]
print(json.dumps({n: [float(v).hex() for v in res[n]] for n in res.dtype.names}))
'''


def simulate_isolated(fmu: Path, **kwargs) -> dict:
    """FMPy's ``simulate_fmu(fmu, **kwargs)`` (JSON-able arguments; ``input_npy``: the
    path of a structured input array saved with ``numpy.save``) in a process without
    gearcontact; the result columns as float arrays."""
    run = subprocess.run([sys.executable, "-I", "-c", _ISOLATED,
                          json.dumps({"filename": str(fmu), **kwargs})],
                         capture_output=True, text=True, timeout=300, cwd=fmu.parent)
    assert run.returncode == 0, run.stderr[-2000:]
    cols = json.loads(run.stdout.splitlines()[-1])
    return {n: np.array([float.fromhex(v) for v in vs]) for n, vs in cols.items()}


def run_isolated(code: str, cwd: Path) -> str:
    """Python ``code`` as written (a docs snippet) in a process without gearcontact, in
    ``cwd``; its stdout."""
    run = subprocess.run([sys.executable, "-I", "-c", _BLOCKER + code], cwd=cwd,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stdout


def docs_snippet(chapter: str) -> str:
    """The ``python`` block under "## Use from FMPy" of the chapter of docs/export.md
    whose title starts with ``chapter``."""
    text = (ROOT / "docs" / "export.md").read_text()
    part = text.split("\n# " + chapter, 1)[1].split("\n# ", 1)[0]
    return part.split("## Use from FMPy", 1)[1].split("```python\n", 1)[1].split("```")[0]
