"""Benchmark: the hollow ease-off check of a generated gear's pinions when a pair is
loaded (:func:`gearcontact.geometry.settings_check.completed_settings`, on the gear
boxes the reader's generation check traced), against ``design``'s own measurement
(``check_settings(easeoff_generated=True)``, the boxes traced afresh) and against a
whole ``tca`` run of the pair (docs/machine_settings.md sec. 2, "The hollow ease-off
warning").

Pairs: the standard settings with a generated gear of the 11 x 41 rear axle, of F.3 and
of F.2 (examples/). CPU seconds (``time.process_time``), best of ``--repeat`` warm calls
in one process (numba caches loaded by a first call not counted); ``tca`` through the
command line in this process (61 phases, figures off), best of two warm runs, the load
check included in it, and as a user runs it: ``python -m gearcontact tca`` in a fresh
process (its CPU seconds from ``resource.getrusage(RUSAGE_CHILDREN)``: interpreter
start, imports and the numba cache loads included). The verdicts are compared exactly
(``EaseOffShape`` equality: the same floats).

Usage::

    python benchmarks/bench_generated_load_check.py [--repeat 3]

Wall seconds depend on the load of the shared machine (printed before and after); CPU
seconds are the fairer figures.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import resource
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

from cpu_timing import best_cpu_s, load_average

ROOT = Path(__file__).resolve().parents[1]
PAIRS = ("hypoid_11x41_rear_axle", "iso23509_f3", "iso23509_f2_spiral_bevel")


def main() -> None:
    from gearcontact.cli import main as cli
    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.generation import check_generation
    from gearcontact.geometry.pair import load_pair, pair_to_toml
    from gearcontact.geometry.settings_check import check_settings, completed_settings

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"load average {load_average()}")
    print("| pair | load check CPU s (reused gear box) | design's check of the same flanks "
          "CPU s | verdict equal | `tca` CPU s in process / console | share of a `tca` in "
          "process / console |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in PAIRS:
            pair = standard_machine_pair(load_pair(ROOT / "examples" / f"{name}.toml"),
                                         gear_generation="generated")
            loaded = check_settings(pair)
            boxes = check_generation(pair)
            completed_settings(pair, loaded, boxes, warn=False)      # warm
            load_s, done = best_cpu_s(lambda: completed_settings(pair, loaded, boxes, warn=False),
                                 args.repeat)
            shape_s, design = best_cpu_s(
                lambda: check_settings(pair, easeoff_generated=True).easeoff, args.repeat)
            blank_s, _ = best_cpu_s(lambda: check_settings(pair), args.repeat)
            equal = done.easeoff.flanks == design.flanks and done.easeoff.missing == {}
            path = Path(tmp) / f"{name}.toml"
            path.write_text(pair_to_toml(pair))
            tca = []
            for k in range(3):
                c0 = time.process_time()
                with contextlib.redirect_stdout(io.StringIO()), \
                        contextlib.redirect_stderr(io.StringIO()):
                    code = cli(["tca", "--pair", str(path), "--out", str(Path(tmp) / f"t{k}"),
                                "--no-figures", "--quiet", "--force"])
                tca.append(time.process_time() - c0)
                assert code == 0, name
            tca_s = min(tca[1:])        # the first pays the numba cache loads
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run([sys.executable, "-m", "gearcontact", "tca", "--pair", str(path),
                            "--out", str(Path(tmp) / "console"), "--no-figures", "--quiet",
                            "--force"], check=True, capture_output=True)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            console_s = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            print(f"| {name} | {load_s:.3f} | {shape_s - blank_s:.3f} | {equal} | "
                  f"{tca_s:.2f} / {console_s:.2f} | {load_s / tca_s:.1%} / "
                  f"{load_s / console_s:.1%} |", flush=True)
    print(f"load average {load_average()}")


if __name__ == "__main__":
    main()
