"""One run of the README's export lines per session, shared by the export tests.

The README shows ``gearcontact vectors --out vectors/ ...`` (twice), then
``gearcontact export c --out clib/ && make -C clib/ && clib/gearcontact_check vectors/``
and ``gearcontact export fmu --pair s0003 --kind mesh --out clib_fmu/``. They run once,
verbatim, in a shell (the relative directories land in one session directory):
tests/export/test_readme.py asserts on the runs, and tests/export/test_c_library.py
uses the library that ``make -C clib/`` built (the default ``export c``; rendering
and compiling it a second time proved nothing more).
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def readme_lines(prefix: str) -> list[str]:
    """Lines of README.md that start with ``prefix``, comments stripped."""
    lines = []
    for line in (ROOT / "README.md").read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line.startswith(prefix):
            lines.append(line)
    return lines


def _shell(line: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(["bash", "-c", line], cwd=cwd, capture_output=True, text=True,
                          timeout=900)


@pytest.fixture(scope="session")
def readme_export(tmp_path_factory):
    """``(directory, lines, runs)``: the README's vectors, export c and export fmu lines
    (``lines`` a dict of those three lists) run in order in ``directory``; ``runs`` maps
    each line run to its CompletedProcess. The runs stop at the first line that fails
    (the later lines depend on its files)."""
    if (shutil.which("gearcontact") is None or shutil.which("make") is None
            or shutil.which("gcc") is None):
        pytest.skip("the console script, make and gcc are needed")
    lines = {"vectors": readme_lines("gearcontact vectors --out vectors/"),
             "export_c": readme_lines("gearcontact export c"),
             "export_fmu": readme_lines("gearcontact export fmu")}
    base = tmp_path_factory.mktemp("readme_export")
    runs = {}
    for line in lines["vectors"] + lines["export_c"] + lines["export_fmu"]:
        runs[line] = _shell(line, base)
        if runs[line].returncode != 0:
            break
    return base, lines, runs
