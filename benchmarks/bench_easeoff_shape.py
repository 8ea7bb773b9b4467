"""Benchmark: the cost of the hollow ease-off check when a pair is loaded
(:func:`gearcontact.geometry.easeoff_shape.check_easeoff_shape`, run by
:func:`gearcontact.geometry.settings_check.check_settings`; docs/machine_settings.md
sec. 2, "The hollow ease-off warning").

Each pair runs in a fresh subprocess: the check once cold (the first call loads the
numba-cached spline kernels of :mod:`gearcontact.geometry.sheet`, which a TCA of the
pair loads anyway) and then warm, each as wall and CPU seconds (``time.process_time``),
beside the whole settings check (:func:`~gearcontact.geometry.settings_check.check_settings`,
this check included) run warm.

Usage::

    python benchmarks/bench_easeoff_shape.py
    python benchmarks/bench_easeoff_shape.py --pairs FILE.toml ...   # pairs with pinion settings

Wall seconds depend on the load of the shared machine (printed); CPU seconds are the
fairer figures.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys

_CHILD = r"""
import json, sys, time
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.easeoff_shape import check_easeoff_shape
from gearcontact.geometry.settings_check import check_settings

pair = load_pair(sys.argv[1])
out = {}
for label in ("cold", "warm"):
    w, c = time.perf_counter(), time.process_time()
    got = check_easeoff_shape(pair)
    out[label] = (time.perf_counter() - w, time.process_time() - c)
w, c = time.perf_counter(), time.process_time()
check_settings(pair)
out["settings_check"] = (time.perf_counter() - w, time.process_time() - c)
out["flanks"] = [] if got is None else [(s.side, s.C_p_um, s.C_l_um) for s in got.flanks]
out["missing"] = {"both": "no pinion settings"} if got is None else got.missing
print(json.dumps(out))
"""

DEFAULT_PAIRS = ("examples/machine_settings/iso23509_f2_machine.toml",)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", nargs="+", default=DEFAULT_PAIRS)
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} "
          f"{os.getloadavg()[2]:.2f}")
    print(f"{'pair':<58} {'cold wall/cpu s':>16} {'warm wall/cpu s':>16} "
          f"{'settings check s':>17}")
    for pair in args.pairs:
        got = json.loads(subprocess.run([sys.executable, "-c", _CHILD, pair], check=True,
                                        capture_output=True, text=True).stdout)
        cells = [f"{got[k][0]:.3f}/{got[k][1]:.3f}" for k in ("cold", "warm",
                                                               "settings_check")]
        print(f"{pair:<58} {cells[0]:>16} {cells[1]:>16} {cells[2]:>17}")
        for side, c_p, c_l in got["flanks"]:
            print(f"    {side}: C_p {c_p:+.2f} um, C_l {c_l:+.2f} um")
        for side, why in got["missing"].items():
            print(f"    {side}: {why}")
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
