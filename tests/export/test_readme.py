"""The README's export lines, exactly as written, in a real shell.

The README shows ``gearcontact vectors --out vectors/ ...`` (twice) and then
``gearcontact export c --out clib/ && make -C clib/ && clib/build/gearcontact_check vectors/``
and ``gearcontact export fmu --pair s0003 --kind mesh|drivetrain --out ...`` (the mesh
and the drivetrain FMU, ~16 s each: the default 61 phases). They run
verbatim (default options; the relative directories land in one directory), once per
session in tests/export/conftest.py (``readme_export``, whose ``clib/`` the C library
tests reuse). Truth: the checker's own per-core comparison of the golden C with the
golden model's vectors (0 mismatches, no tolerance) and FMPy's FMI 3.0 schema
validation.
"""

from __future__ import annotations

import re

import pytest


def test_readme_export_lines_as_written(readme_export):
    base, lines, runs = readme_export
    vectors, export_c, export_fmu = lines["vectors"], lines["export_c"], lines["export_fmu"]
    assert vectors and len(export_c) == 1 and len(export_fmu) == 2
    for line in vectors:
        run = runs[line]
        assert run.returncode == 0, (line, run.stderr)
    run = runs[export_c[0]]
    assert run.returncode == 0, (export_c[0], run.stdout, run.stderr)
    checked = re.findall(r"^(\w+): (\d+) vectors, (\d+) mismatches$", run.stdout, re.M)
    written = {p.stem for p in (base / "vectors").glob("*.jsonl")}
    assert written and {core for core, _, _ in checked} == written, run.stdout
    assert all(int(n) > 0 and int(m) == 0 for _, n, m in checked), run.stdout

    fmpy = pytest.importorskip("fmpy.validation", reason="the fmu extra (FMPy)")
    for line, out in zip(export_fmu, ("clib_fmu", "twin_fmu")):
        run = runs[line]
        assert run.returncode == 0, (line, run.stderr)
        fmus = list((base / out).glob("*.fmu"))
        assert len(fmus) == 1
        assert fmpy.validate_fmu(str(fmus[0])) == []
