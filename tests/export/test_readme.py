"""The README's export lines, exactly as written, in a real shell.

The README shows ``gearcontact vectors --out vectors/ ...`` (twice) and then
``gearcontact export c --out clib/ && make -C clib/ && clib/gearcontact_check vectors/``
and ``gearcontact export fmu --pair s0003 --kind mesh --out clib_fmu/``, then
``gearcontact export flanks --pair s0003 --out flanks/``. They run here verbatim
(default options; the relative directories land in the test's directory). Truth: the
checker's own per-core comparison of the golden C with the golden model's vectors (0
mismatches, no tolerance), FMPy's FMI 3.0 schema validation, and for the flanks the CMM
grid points of the CSV files (the Surface contract's points, tests/export/
test_flanks.py) lying on the STEP faces read back by gmsh within the issue's 0.5 um.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
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
    assert vectors and len(export_c) == 1 and len(export_fmu) == 1
    for line in vectors:
        run = _shell(line, tmp_path)
        assert run.returncode == 0, (line, run.stderr)
    run = _shell(export_c[0], tmp_path)
    assert run.returncode == 0, (export_c[0], run.stdout, run.stderr)
    checked = re.findall(r"^(\w+): (\d+) vectors, (\d+) mismatches$", run.stdout, re.M)
    written = {p.stem for p in (tmp_path / "vectors").glob("*.jsonl")}
    assert written and {core for core, _, _ in checked} == written, run.stdout
    assert all(int(n) > 0 and int(m) == 0 for _, n, m in checked), run.stdout

    run = _shell(export_fmu[0], tmp_path)
    assert run.returncode == 0, (export_fmu[0], run.stderr)
    fmus = list((tmp_path / "clib_fmu").glob("*.fmu"))
    assert len(fmus) == 1
    fmpy = pytest.importorskip("fmpy.validation", reason="the fmu extra (FMPy)")
    assert fmpy.validate_fmu(str(fmus[0])) == []


@pytest.mark.skipif(shutil.which("gearcontact") is None,
                    reason="the console script is needed")
def test_readme_export_flanks_line_as_written(tmp_path):
    gmsh = pytest.importorskip("gmsh", reason="the export extra (gmsh)")
    lines = _readme_lines("gearcontact export flanks")
    assert len(lines) == 1
    run = _shell(lines[0], tmp_path)
    assert run.returncode == 0, (lines[0], run.stderr)
    out = tmp_path / "flanks"
    gmsh.initialize(argv=[], readConfigFiles=False, interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        for member in ("pinion", "gear"):
            gmsh.model.add(member)
            ents = gmsh.model.occ.importShapes(str(out / f"{member}_flanks.step"))
            gmsh.model.occ.synchronize()
            faces = {gmsh.model.getEntityName(*e).rsplit("/", 1)[-1]: e[1] for e in ents}
            for side in ("drive", "coast"):
                rows = [line.split(",") for line in
                        (out / f"{member}_{side}.csv").read_text().splitlines()
                        if line[:1].isdigit()]
                pts = np.array([[float(x) for x in r[4:7]] for r in rows])
                assert pts.shape == (45, 3)             # the default 5 x 9 grid
                near, _ = gmsh.model.getClosestPoint(2, faces[f"{member}_{side}"],
                                                     pts.ravel())
                gap = np.linalg.norm(np.reshape(near, (-1, 3)) - pts, axis=-1).max()
                assert gap <= 0.5e-3, (member, side, gap)
            gmsh.model.remove()
    finally:
        gmsh.finalize()
