"""``halfspace.lcp.warm_up`` compiles every kernel specialization a real solve needs.

Truth: in a fresh process with an empty numba cache (``NUMBA_CACHE_DIR``), after
``warm_up`` no compiled function of the LCP path gains a signature while single-pair
LTCAs of s0003-centred run (drive, three grids, torques from Hertzian to far beyond the flank,
warm-started as in the main job) — so ``solve_time_ms`` never includes compilation.
Slow: the fresh process compiles everything (10-20 s).
"""

import os
import subprocess
import sys

import pytest

SCRIPT = r"""
import warnings
from gearcontact.halfspace import constrained_cg, influence, lcp
def sigs():
    return {f"{m.__name__}.{k}": set(map(str, v.signatures)) for m in (constrained_cg, influence, lcp)
            for k, v in vars(m).items() if hasattr(v, "signatures") and hasattr(v, "py_func")}
lcp.warm_up()
before = sigs()
from gearcontact.ltca.pair_ltca import single_pair_ltca
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair
pair = load_pair("s0003-centred")  # drive; the calibrated s0003 puts P0 at the flank edge
tca, flanks = analyze_pair(pair, phases=15)
warnings.simplefilter("ignore")
for cells in (80, 40, 24):
    prev = None
    for torque in (32.25, 64.5, 258.0, 4000.0):
        prev = single_pair_ltca(tca, flanks, pair, torque, cells=cells,
                                warm_start=prev.patch if prev else None)
after = sigs()
new = {k: after[k] - before.get(k, set()) for k in after if after[k] - before.get(k, set())}
print("NEW", new)
"""


@pytest.mark.slow
def test_no_compilation_after_warm_up(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    proc = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                          env=env, timeout=900, check=False)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "NEW {}" in proc.stdout, proc.stdout
