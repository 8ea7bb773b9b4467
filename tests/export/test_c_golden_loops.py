"""The golden C code has no data-dependent loop counts (docs/export.md, "Why the golden C
code is deterministic"), measured: gcc's own coverage counters (``--coverage``, gcov)
per vector.

Truth: execution counts of the golden sources' loop headers (every ``for`` and
``while`` line) under ``gearcontact_check``, one vector per run, on the RTL vectors of
every core (corner cases first, then seeded random and raw whole-range words). The
vectors take different paths (a flag returns early, a lift runs or not): each run's
path is the set of lines outside any loop that it executed (the returns taken, the
branches around loops). Claim: runs on the same path execute every loop header the same
number of times, whatever their data -- so no loop's trip count, nor how often a loop
is entered, depends on the data beyond the path's branches. A loop whose bound or exit
read the data would give two runs of one path different counts (its header counts the
tests of its condition): stage D's divide with an early exit where the remainder is 0
(the same quotients: the checker still finds 0 mismatches) fails this test (line 39 run
13 and 12 times on one path; checked once, by hand). Everything runs as a user would: the export's sources,
``gcc``, ``gcov``, the checker on vector files of ``gearcontact vectors``.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

import pytest

from gearcontact.export.c_library import GOLDEN_SOURCES
from gearcontact.hw.vectors import LINE_CORES

ROOT = Path(__file__).resolve().parents[2]
#: every core ``gearcontact vectors`` writes, in the checker's order
CORES = ("gap", "fit", "hertz", "chain", "gap_lean", "hertz_exact", "chain_exact") + LINE_CORES
#: vectors per core: the corner cases come first in the files, then random ones
PER_CORE = 30
LOOP = re.compile(r"^\s*(for|while)\s*\(")

pytestmark = pytest.mark.skipif(
    any(shutil.which(t) is None for t in ("gcc", "gcov")),
    reason="gcc and gcov (Debian: gcc) are needed to measure the golden C code's loops")


def _run(argv, **kw):
    run = subprocess.run(argv, capture_output=True, text=True, timeout=600, **kw)
    assert run.returncode == 0, (argv, run.stdout[-2000:], run.stderr[-2000:])
    return run


def _loop_lines(text: str) -> tuple[set[int], set[int]]:
    """(loop headers, every line of a loop: header and body) of a C source, 1-based: a
    body is the braced block after its header, or the one statement (a nested loop's
    whole extent) that follows it."""
    lines = text.splitlines()
    headers, inside = set(), set()

    def extent(i: int) -> int:
        """Last line (0-based) of the loop whose header is line i."""
        code = lines[i].split("/*")[0].rstrip()
        if code.endswith("{"):
            depth = 0
            for j in range(i, len(lines)):
                depth += lines[j].count("{") - lines[j].count("}")
                if depth == 0:
                    return j
            raise AssertionError(f"unbalanced loop at line {i + 1}")
        if code.endswith(";"):                      # body on the header's line
            return i
        j = i + 1
        if LOOP.match(lines[j]):
            return extent(j)
        while not lines[j].split("/*")[0].rstrip().endswith(";"):
            j += 1
        return j

    for i, line in enumerate(lines):
        if LOOP.match(line):
            headers.add(i + 1)
            inside.update(range(i + 1, extent(i) + 2))
    return headers, inside


def test_golden_loop_counts_do_not_depend_on_the_data(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    lib, vec = tmp_path / "lib", tmp_path / "vectors"
    _run([sys.executable, "-m", "gearcontact", "export", "c", "--out", str(lib)], env=env)
    _run([sys.executable, "-m", "gearcontact", "vectors", "--out", str(vec), "--count", "20",
          "--cores", ",".join(CORES)], env=env)
    obj = tmp_path / "obj"
    obj.mkdir()
    for name in GOLDEN_SOURCES:
        _run(["gcc", "-std=c99", "-O0", "--coverage", "-c", "-o",
              str(obj / name.replace(".c", ".o")), str(lib / name)])
    exe = tmp_path / "check"
    _run(["gcc", "-std=c99", "-O2", "--coverage", "-o", str(exe), str(lib / "gearcontact_check.c"),
          *sorted(str(p) for p in obj.glob("*.o"))])
    # one vector per directory and run: its counters land in counts/<run>/ (GCOV_PREFIX,
    # the object directory's components stripped)
    strip = str(len(obj.resolve().parts) - 1)
    runs = []
    for core in CORES:
        ins = (vec / f"{core}_in.hex").read_text().splitlines()[:PER_CORE]
        outs = (vec / f"{core}_out.hex").read_text().splitlines()[:PER_CORE]
        for k, (i, o) in enumerate(zip(ins, outs)):
            one, counts = tmp_path / "one" / f"{core}.{k}", tmp_path / "counts" / f"{core}.{k}"
            one.mkdir(parents=True)
            (one / f"{core}_in.hex").write_text(i + "\n")
            (one / f"{core}_out.hex").write_text(o + "\n")
            run = _run([str(exe), str(one)], env={**os.environ, "GCOV_PREFIX": str(counts),
                                                   "GCOV_PREFIX_STRIP": strip})
            assert run.stdout == f"{core}: 1 vectors, 0 mismatches\n"
            for gcno in obj.glob("*.gcno"):
                (counts / gcno.name).symlink_to(gcno)
            runs.append((core, counts))
    # the golden sources and the headers they inline (gc_arith.h: the bit length)
    structure = {name: _loop_lines((lib / name).read_text())
                 for name in GOLDEN_SOURCES + ("gc_arith.h", "gc_tables.h")}
    headers_total = sum(len(h) for h, _ in structure.values())
    assert headers_total >= 10                      # the loops the docs name are there
    paths = defaultdict(list)
    for core, counts in runs:
        report = _run(["gcov", "--json-format", "--stdout", "-o", str(counts),
                       *(str(lib / n) for n in GOLDEN_SOURCES)], cwd=counts).stdout
        path, loops = [], []
        for doc in map(json.loads, report.splitlines()):
            for f in doc["files"]:
                headers, inside = structure[Path(f["file"]).name]
                for line in f["lines"]:
                    key = (Path(f["file"]).name, line["line_number"])
                    if key[1] in headers:
                        loops.append((key, line["count"]))
                    elif key[1] not in inside and line["count"] > 0:
                        path.append(key)
        paths[(core, tuple(sorted(path)))].append(dict(loops))
    # the same path, the same count of every loop header; printed: the paths and runs
    shared = 0
    for (core, _), members in paths.items():
        first = members[0]
        for other in members[1:]:
            differ = {k: (first.get(k, 0), other.get(k, 0)) for k in set(first) | set(other)
                      if first.get(k, 0) != other.get(k, 0)}
            assert not differ, (core, differ)
        shared += len(members) - 1
    # not vacuous: most runs share their path with another run, every core's accepted
    # vectors included, and loops ran (the fit's and stage D's helpers, the gap kernel's)
    assert len(runs) >= 250 and shared >= len(runs) // 2, (len(runs), len(paths), shared)
    ran = {k for members in paths.values() for m in members for k, c in m.items() if c > 0}
    assert len(ran) >= headers_total - 2, (sorted(ran), headers_total)
    print(f"{len(runs)} runs, {len(paths)} paths, {shared} runs on a path already seen; "
          f"{len(ran)} of {headers_total} loop headers executed")
