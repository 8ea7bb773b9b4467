"""Shared by the FMU tests: FMPy in a Python process where gearcontact cannot be
imported (the situation of a twin developer who has only the FMU)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

#: Run in ``python -I`` (no PYTHONPATH, no user site): a meta-path finder refuses every
#: ``gearcontact`` module before any other finder (the editable install would find it),
#: the script checks that ``import gearcontact`` fails, then simulates the FMU with FMPy
#: and writes the result columns as JSON (floats as hex: exact).
_ISOLATED = r'''
import importlib.abc, json, sys

class Blocker(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == "gearcontact" or name.startswith("gearcontact."):
            raise ImportError(f"{name} is blocked: this process has no gearcontact")
        return None

sys.meta_path.insert(0, Blocker())
try:
    import gearcontact  # noqa: F401
except ImportError:
    pass
else:
    raise SystemExit("gearcontact was importable")
import fmpy
args = json.loads(sys.argv[1])
if "input_npy" in args:         # a structured input signal saved by numpy
    import numpy
    args["input"] = numpy.load(args.pop("input_npy"))
res = fmpy.simulate_fmu(args.pop("filename"), **args)
assert not [m for m in sys.modules if m.split(".")[0] == "gearcontact"]
print(json.dumps({n: [float(v).hex() for v in res[n]] for n in res.dtype.names}))
'''


def simulate_isolated(fmu: Path, **kwargs) -> dict:
    """FMPy's ``simulate_fmu(fmu, **kwargs)`` (JSON-able arguments; ``input_npy``: the
    path of a structured input array saved with ``numpy.save``) in a process without
    gearcontact; the result columns as float arrays."""
    run = subprocess.run([sys.executable, "-I", "-c", _ISOLATED,
                          json.dumps({"filename": str(fmu), **kwargs})],
                         capture_output=True, text=True, timeout=300, cwd=fmu.parent)
    assert run.returncode == 0, run.stderr[-2000:]
    cols = json.loads(run.stdout.splitlines()[-1])
    return {n: np.array([float.fromhex(v) for v in vs]) for n, vs in cols.items()}
