"""The README's export lines, exactly as written, in a real shell.

The README shows ``gearcontact vectors --out vectors/ ...`` (twice) and then
``gearcontact export c --out clib/ && make -C clib/ && clib/build/gearcontact_check vectors/``
and ``gearcontact export fmu --pair s0003 --kind mesh|drivetrain --out ...`` (the mesh
and the drivetrain FMU, ~16 s each: the default 61 phases). They run here
verbatim (default options; the relative directories land in the test's directory).
Truth: the checker's own per-core comparison of the golden C with the golden model's
vectors (0 mismatches, no tolerance) and FMPy's FMI 3.0 schema validation.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _readme_lines(prefix: str) -> list[str]:
    lines = []
    for line in (ROOT / "README.md").read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line.startswith(prefix):
            lines.append(line)
    return lines


def _shell(line: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(["bash", "-c", line], cwd=cwd, capture_output=True, text=True,
                          timeout=900)


@pytest.mark.skipif(shutil.which("gearcontact") is None or shutil.which("make") is None
                    or shutil.which("gcc") is None,
                    reason="the console script, make and gcc are needed")
def test_readme_export_lines_as_written(tmp_path):
    vectors = _readme_lines("gearcontact vectors --out vectors/")
    export_c = _readme_lines("gearcontact export c")
    export_fmu = _readme_lines("gearcontact export fmu")
    assert vectors and len(export_c) == 1 and len(export_fmu) == 2
    for line in vectors:
        run = _shell(line, tmp_path)
        assert run.returncode == 0, (line, run.stderr)
    run = _shell(export_c[0], tmp_path)
    assert run.returncode == 0, (export_c[0], run.stdout, run.stderr)
    checked = re.findall(r"^(\w+): (\d+) vectors, (\d+) mismatches$", run.stdout, re.M)
    written = {p.stem for p in (tmp_path / "vectors").glob("*.jsonl")}
    assert written and {core for core, _, _ in checked} == written, run.stdout
    assert all(int(n) > 0 and int(m) == 0 for _, n, m in checked), run.stdout

    fmpy = pytest.importorskip("fmpy.validation", reason="the fmu extra (FMPy)")
    for line, out in zip(export_fmu, ("clib_fmu", "twin_fmu")):
        run = _shell(line, tmp_path)
        assert run.returncode == 0, (line, run.stderr)
        fmus = list((tmp_path / out).glob("*.fmu"))
        assert len(fmus) == 1
        assert fmpy.validate_fmu(str(fmus[0])) == []
