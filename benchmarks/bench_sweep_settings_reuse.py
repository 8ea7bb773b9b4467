"""Benchmark: a settings sweep reusing the flanks a variant leaves unchanged
(``sweep.settings_keys.VARIANT_FLANKS``, ``geometry.flank_reuse``; docs/sweeps.md, "A
pair cut from machine settings").

1. Per variant, in this process: the CPU seconds of building a setting variant of the
   F.2 settings pair (``sweep.design.build_variant``: read, ``prepare_pair``'s checks,
   the four flanks) cut afresh (reuse off), and with reuse in the order a sweep builds
   them: the first variant (all cut), then the pinion's drive 2C changed twice, then the
   gear's drive sliding base changed, then a variant built before. Best of
   ``--repeat`` (each repeat with an empty cache); the flanks each variant cut are
   counted.
2. The example line of docs/sweeps.md (3 x 3 cells over the pinion's drive 2C and E,
   ``--compute tca,ltca``, 21 phases, ``--workers 2``) run by the command line of the
   code before (commit ``--before``, exported into a temporary directory) and of this
   tree: wall seconds, CPU seconds of the command and its worker processes
   (``RUSAGE_CHILDREN``), each variant's build time as its worker measured it
   (``flank_build_s``); and the two stores compared (every variable but the build
   times, ``==``). Each tree runs an untimed one-cell sweep first (numba's cache).

The load average is printed before and after (the machine is shared; a run beside
other work is slower, wall more than CPU).

Usage::

    python benchmarks/bench_sweep_settings_reuse.py [--repeat 2] [--before 5c3078b] [--no-sweep]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

from cpu_timing import best_cpu_s, load_average

ROOT = Path(__file__).resolve().parents[1]
F2 = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"
ROLL = "machine.pinion.drive.modified_roll_2c_per_rad"
SLIDE = "machine.gear.drive.sliding_base_mm"
#: The variants of part 1, in the order built: (label, design).
SEQUENCE = (("2C = -0.02 (first: all cut)", ((ROLL, -0.02),)),
            ("2C = 0 (pinion drive key)", ((ROLL, 0.0),)),
            ("2C = +0.02 (pinion drive key)", ((ROLL, 0.02),)),
            ("2C = +0.02, sliding base -5.7 (gear drive key)", ((ROLL, 0.02), (SLIDE, -5.7))),
            ("2C = 0 again (built before)", ((ROLL, 0.0),)))
SWEEP = ["sweep", "--pair", str(F2), "--vary", f"{ROLL}=-0.02:0.02:3",
         "--vary", "E=-0.05:0.05:3", "--compute", "tca,ltca", "--phases", "21",
         "--workers", "2", "--quiet"]


def per_variant(repeat: int) -> None:
    from gearcontact.geometry.flank_reuse import FlankCache
    from gearcontact.geometry.pair import load_pair
    from gearcontact.sweep import settings_keys
    from gearcontact.sweep.design import build_variant

    pair = load_pair(F2)
    build_variant(pair, SEQUENCE[0][1])                       # warm (imports, numba)
    fresh, reused, cut = {}, {}, {}
    for _ in range(repeat):
        cache = FlankCache()
        for label, design in SEQUENCE:
            settings_keys.VARIANT_FLANKS = None
            fresh[label] = min(fresh.get(label, 1e9),
                               best_cpu_s(lambda: build_variant(pair, design), 1)[0])
            settings_keys.VARIANT_FLANKS = cache
            before = dict(cache.misses)
            s, got = best_cpu_s(lambda: build_variant(pair, design), 1)
            assert not got.error, got.error
            reused[label] = min(reused.get(label, 1e9), s)
            name = "gearcontact.geometry.kinked.machine_flank"
            cut[label] = cache.misses.get(name, 0) - before.get(name, 0)
    print("| variant | fresh CPU s | reused CPU s | flanks cut |")
    print("|---|---:|---:|---:|")
    for label, _ in SEQUENCE:
        print(f"| {label} | {fresh[label]:.2f} | {reused[label]:.2f} | {cut[label]} |",
              flush=True)


def run_sweep_cli(src: Path, out: Path) -> tuple[float, float]:
    """``(wall s, CPU s of the command and its children)`` of the example sweep run with
    the package at ``src``."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "gearcontact", *SWEEP, "--out", str(out)],
                   env=env, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime)


def warm(src: Path, tmp: Path) -> None:
    """One cell with the package at ``src`` (numba's cache, imports), untimed."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    subprocess.run([sys.executable, "-m", "gearcontact", "sweep", "--pair", str(F2),
                    "--vary", f"{ROLL}=0:0:1", "--phases", "5", "--workers", "0",
                    "--quiet", "--out", str(tmp / f"warm_{src.parent.name}")],
                   env=env, check=True, stdout=subprocess.DEVNULL)


def whole_sweep(before: str) -> None:
    import numpy as np
    import xarray as xr

    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        old = tmp / "before"
        old.mkdir()
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", before, "src"],
                                 check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(old)], input=archive, check=True)
        trees = {f"before ({before})": old / "src", "reuse (this tree)": ROOT / "src"}
        rows, stores = [], {}
        for name, src in trees.items():
            warm(src, tmp)
            out = tmp / f"out_{name.split()[0]}"
            wall, cpu = run_sweep_cli(src, out)
            ds = xr.open_zarr(out / "sweep.zarr", consolidated=False).load()
            builds = np.unique(ds["flank_build_s"].values)      # one per variant
            rows.append((name, wall, cpu, builds))
            stores[name] = ds.drop_vars("flank_build_s")
        print("| code | wall s | CPU s (command + workers) | variant builds s (on the workers) |")
        print("|---|---:|---:|---|")
        for name, wall, cpu, builds in rows:
            print(f"| {name} | {wall:.1f} | {cpu:.1f} | "
                  f"{', '.join(f'{b:.2f}' for b in builds)} |")
        a, b = stores.values()
        xr.testing.assert_identical(a, b)
        print("stores identical but the build times (xarray assert_identical)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--before", default="5c3078b", help="commit of the code before")
    ap.add_argument("--no-sweep", action="store_true", help="part 1 only")
    args = ap.parse_args()
    print(f"load average {load_average()}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        per_variant(args.repeat)
    print(f"load average {load_average()}", flush=True)
    if not args.no_sweep:
        whole_sweep(args.before)
        print(f"load average {load_average()}")


if __name__ == "__main__":
    main()
