"""Benchmark: first-run (cold) vs cached start of the command line (issue 12).

Each command runs in a fresh subprocess twice with one new, empty ``NUMBA_CACHE_DIR``:
the first run compiles every jitted kernel it calls (the situation right after
``pip install``), the second loads them from the on-disk cache that the first run
wrote. A third subprocess runs the cold case again with numba's ``numba:compile``
events recorded and prints the kernels whose compilation cost the most (exclusive
time: a kernel's own compile, without the callees it triggered).

Usage::

    python benchmarks/bench_cold_start.py                      # analyze --pair s0003
    python benchmarks/bench_cold_start.py --command "tca --phases 21"
    python benchmarks/bench_cold_start.py --warm-up            # also `gearcontact warm-up`
    python benchmarks/bench_cold_start.py --top 0              # no per-kernel profile

Wall-clock seconds depend on the load of a shared machine (printed); the CPU seconds
(user + system of the child process; compile times: ``time.process_time`` of the
compiling thread) are the fairer figures.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shlex
import subprocess
import sys
import tempfile
import time

#: Runs ``gearcontact`` in this process with a listener on numba's compile events and
#: writes ``[(qualname, signature, exclusive_s, inclusive_s), ...]`` to argv[1].
_PROFILE = r"""
import json, sys, time
from numba.core import event

records = []
stack = []


class _Listener(event.Listener):
    def on_start(self, ev):
        stack.append([time.process_time(), 0.0])

    def on_end(self, ev):
        start, children = stack.pop()
        total = time.process_time() - start
        if stack:
            stack[-1][1] += total
        disp = ev.data["dispatcher"]
        records.append((disp.py_func.__module__ + "." + disp.py_func.__qualname__,
                        str(ev.data["args"]), total - children, total))


out = sys.argv[1]
sys.argv = ["gearcontact"] + sys.argv[2:]
from gearcontact.cli import main
with event.install_listener("numba:compile", _Listener()):
    code = main()
with open(out, "w") as fh:
    json.dump(records, fh)
sys.exit(code)
"""


def _cpu_children() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run(argv: list[str], env: dict[str, str]) -> tuple[float, float, int]:
    """Wall and CPU seconds (user + system of the child) and the exit code."""
    start, cpu = time.perf_counter(), _cpu_children()
    proc = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True)
    wall, cpu = time.perf_counter() - start, _cpu_children() - cpu
    if proc.returncode != 0:
        print(proc.stderr, file=sys.stderr)
    return wall, cpu, proc.returncode


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--command", default="analyze --pair s0003",
                        help="gearcontact arguments without --out (default: %(default)s)")
    parser.add_argument("--top", type=int, default=15,
                        help="kernels listed by compile time (0: no profile run)")
    parser.add_argument("--warm-up", action="store_true",
                        help="also time `gearcontact warm-up` into a fresh cache and the "
                             "command after it")
    opts = parser.parse_args()

    base = os.environ.copy()
    cli = [sys.executable, "-m", "gearcontact"]
    rows = []
    with tempfile.TemporaryDirectory(prefix="gc-cold-") as tmp:
        def env_with(cache: str) -> dict[str, str]:
            return {**base, "NUMBA_CACHE_DIR": os.path.join(tmp, cache)}

        def command(out: str) -> list[str]:
            return cli + shlex.split(opts.command) + ["--out", os.path.join(tmp, out)]

        def profile(cache: str, out: str) -> list:
            prof = os.path.join(tmp, out + ".json")
            argv = [sys.executable, "-c", _PROFILE, prof] + shlex.split(opts.command) + [
                "--out", os.path.join(tmp, out)]
            _run(argv, env_with(cache))
            with open(prof) as fh:
                return json.load(fh)

        cold = _run(command("o1"), env_with("c1"))
        rows.append(("cold (empty cache)", *cold))
        warm = _run(command("o2"), env_with("c1"))
        rows.append(("cached (second run)", *warm))
        after_records = None
        if opts.warm_up:
            rows.append(("gearcontact warm-up (empty cache)",
                         *_run(cli + ["warm-up"], env_with("c2"))))
            rows.append(("command after warm-up", *_run(command("o3"), env_with("c2"))))
            after_records = profile("c2", "o5")
        records = profile("c3", "o4") if opts.top > 0 else []

    print(f"gearcontact {opts.command}   (load average {os.getloadavg()[0]:.2f} "
          f"{os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f}, {os.cpu_count()} CPUs)")
    print(f"{'case':36s} {'wall s':>8s} {'CPU s':>8s} {'exit':>5s}")
    for name, wall, cpu, code in rows:
        print(f"{name:36s} {wall:8.2f} {cpu:8.2f} {code:5d}")
    print(f"{'compilation (cold - cached)':36s} {cold[0] - warm[0]:8.2f} "
          f"{cold[1] - warm[1]:8.2f}")
    if after_records is not None:
        print(f"{'compilations left after warm-up':36s} {len(after_records):8d} "
              f"({sum(r[2] for r in after_records):.2f} s: "
              f"{', '.join(sorted({r[0].rsplit('.', 1)[-1] for r in after_records})) or '-'})")
    if records:
        total = sum(r[2] for r in records)
        print(f"\n{len(records)} kernel compilations, {total:.2f} CPU s in numba "
              f"(exclusive times, top {opts.top}):")
        print(f"{'kernel':60s} {'excl s':>7s} {'incl s':>7s}  signature")
        for name, sig, excl, incl in sorted(records, key=lambda r: -r[2])[:opts.top]:
            print(f"{name[-60:]:60s} {excl:7.2f} {incl:7.2f}  {sig[:70]}")
        by_module: dict[str, list] = {}
        for name, _sig, excl, _incl in records:
            module = name.split(".<locals>")[0].rsplit(".", 1)[0]
            module = module if module.startswith("gearcontact") else "numba (library)"
            by_module.setdefault(module, []).append(excl)
        print(f"\n{'module':60s} {'excl s':>7s} {'count':>5s}")
        for module, times in sorted(by_module.items(), key=lambda kv: -sum(kv[1])):
            print(f"{module:60s} {sum(times):7.2f} {len(times):5d}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
