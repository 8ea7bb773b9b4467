"""Benchmark: ``gearcontact analyze --pair examples/<pair>.toml`` with default options on
every shipped example (issue 28: the main job on ordinary pairs), wall and CPU time.

Each run is the console script in its own process (numba's on-disk cache as it is: run
``gearcontact warm-up`` first to exclude compilation), into a temporary directory. The
table gives wall time, the child's CPU time (user + system, the fairer figure on a
shared machine), the split of run.json's stage timings (ease-off synthesis, TCA, LTCA,
LTE, multi-tooth) and the load average before and after.

Measured on the project machine (2 cores, load 0.1-1.2, warm numba cache), wall / CPU
s: hypoid 11x41 168 / 162 (ease-off synthesis 144), F.2 spiral bevel 95 / 96 (73),
F.3 99 / 100 (77): the synthesis is 75-85 % of the main job on a pair without an
ease-off table; TCA 4.5-6.2 s, LTE 4.3-4.8 s, multi-tooth 1.2-1.3 s.

After the reduced-TCA synthesis (session 7, docs/synthesis.md; machine shared, load
5.5-7 on 2 cores, numba cache of a fresh worktree: the first run compiled), wall / CPU
s: hypoid 11x41 219 / 50 (ease-off synthesis 10.1), F.2 spiral bevel 176 / 32 (22.6),
F.3 158 / 31 (13.4): CPU time down 3.0-3.3x, the synthesis 6-14x; the wall times are
those of the load (the child had about a fifth of a core).

After the edge-contact check and the miter's synthesis (session 12; measured on 3c5d414,
warm cache, load 1.0 rising to 8), wall / CPU s, every example exit 0: hypoid 11x41 42.0 /
17.9 (synthesis 2.3, LTE 16.3), F.2 50.1 / 19.8 (3.3, 18.7), F.3 72.5 / 24.6 (3.6,
28.1); cylindrical EV 23x67 38.3 / 38.3 (Harris map 26.2), FZG C 32.9 / 24.6, spur
20x40 79.8 / 27.7.

Issue 28's acceptance audit (session 16, on 9c868c3: the operating-load edge law and the
degree-6 ROM merged; numba cache filled by ``gearcontact warm-up`` first, which took 293 s
CPU and 24.5 min wall into the fresh worktree's empty cache; load average 10-14 on the 2
cores, so wall is 5-7 times CPU), wall / CPU s, every example exit 0: hypoid 11x41 200 /
20.3, F.2 163 / 20.9, F.3 143 / 21.5; cylindrical EV 23x67 338 / 51.7, FZG C 115 / 25.9,
spur 20x40 104 / 30.0; the typed machine settings of F.2 (examples/machine_settings/) 145
/ 27.1. The whole audit (``twin`` too, and the design-space variants) is the table in
docs/performance.md, "Issue 28 acceptance audit".

Run: ``python benchmarks/bench_analyze_examples.py [--pair FILE ...]``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _examples() -> list[Path]:
    # every shipped pair, the typed machine settings in examples/machine_settings/ too
    return sorted(p for p in (ROOT / "examples").rglob("*.toml") if "[teeth]" in p.read_text())


def _timings(run_json: Path) -> dict:
    """Every float timing of run.json (seconds), flattened with dotted keys."""
    flat = {}

    def walk(prefix, obj):
        if isinstance(obj, dict):
            for k, v in obj.items():
                walk(f"{prefix}.{k}" if prefix else k, v)
        elif isinstance(obj, float):
            flat[prefix] = obj

    walk("", json.loads(run_json.read_text()).get("timings_s", {}))
    return flat


def bench(pair: Path) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "gearcontact", "analyze", "--pair",
                               str(pair), "--out", tmp], capture_output=True, text=True,
                              check=False)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        timings = _timings(Path(tmp) / "run.json") if proc.returncode == 0 else {}
    return {"pair": pair.stem, "exit": proc.returncode, "wall_s": wall, "cpu_s": cpu,
            "timings": timings, "stderr": proc.stderr.strip().splitlines()[-1:]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pair", action="append", type=Path, help="pair file (default: every "
                    "example in examples/)")
    args = ap.parse_args()
    pairs = args.pair or _examples()
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    rows = [bench(p) for p in pairs]
    print(f"{'pair':<28}{'exit':>5}{'wall s':>9}{'CPU s':>9}  stages (wall s)")
    for r in rows:
        stages = ", ".join(f"{k} {v:.1f}" for k, v in r["timings"].items() if v >= 0.5)
        print(f"{r['pair']:<28}{r['exit']:>5}{r['wall_s']:>9.1f}{r['cpu_s']:>9.1f}  "
              f"{stages or r['stderr']}")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
