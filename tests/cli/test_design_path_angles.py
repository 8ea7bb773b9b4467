"""``gearcontact design --synthesize-easeoff`` with a path angle per side, in a real
process (the installed console script).

Truths: each side of s0003 has its own reachable range of path angles on the gear
flank (drive [-7.8, 42.9] deg, coast [-6.8, 43.6] deg, the closed form of
:mod:`gearcontact.tca.path_reach`, which the TCA meets to 0.4 deg, docs/synthesis.md);
a refused angle exits 2 naming its option, its value and its side's range before any TCA
(measured 5-10 s a process: start-up and flanks; the options' parse errors are tested in
process, tests/cli/test_design.py). The slow test checks the written ease-off with an
independent full TCA (edge contact, pairs -2..2, 31 phases) of each side: the path
angle within the synthesis' 2 deg tolerance and every other target within its
tolerance, as tests/tca/test_path_reach.py's slow test.
"""

import os
import shutil
import subprocess
import sys
import tomllib
from types import SimpleNamespace

import pytest

#: This checkout's package first, for the child processes.
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}

#: s0003's reachable ranges, as the error prints them (docs/synthesis.md).
DRIVE = "[-7.8, 42.9] deg on the drive side of s0003"
COAST = "[-6.8, 43.6] deg on the coast side of s0003"


def _design(*argv, timeout=300):
    """Run ``gearcontact design --pair s0003 --synthesize-easeoff ARGV``; (code, out, err)."""
    exe = shutil.which("gearcontact")
    if exe is None:
        pytest.skip("the gearcontact console script is not on PATH (pip install -e .)")
    p = subprocess.run([exe, "design", "--pair", "s0003", "--synthesize-easeoff", *argv],
                       capture_output=True, text=True, env=ENV, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


@pytest.mark.parametrize("argv, named", [
    # one angle for both sides: the drive side (checked first) refuses 43.3, the coast
    # side would take it
    (["--path-angle-deg", "43.3"], f"--path-angle-deg = 43.3 is outside the allowed "
                                   f"range: {DRIVE}"),
    (["--path-angle-drive-deg", "0", "--path-angle-coast-deg", "-10"],
     f"--path-angle-coast-deg = -10.0 is outside the allowed range: {COAST}"),
])
def test_each_side_is_checked_against_its_own_range(tmp_path, argv, named):
    code, out, err = _design(*argv, "--out", str(tmp_path / "x"))
    assert code == 2, err
    assert out == "" and len(err.splitlines()) == 1
    assert err.startswith(f"gearcontact design: error: {named} (the path angles")
    assert not (tmp_path / "x").exists()


@pytest.mark.slow
def test_drive_and_coast_angles_are_synthesized_and_met(tmp_path):
    """s0003 with drive 0 deg and coast 30 deg, a different angle per side in one run
    (measured: 65 + 45 TCA runs, 28 s CPU; achieved -0.0 and 30.0 deg by the
    synthesis' own full TCA)."""
    import numpy as np

    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import EaseOffCoefficients, load_pair
    from gearcontact.tca.synthesis import SynthesisTargets

    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tca"))
    from test_synthesis import full_tca_check

    code, out, err = _design("--path-angle-drive-deg", "0", "--path-angle-coast-deg",
                             "30", "--out", str(tmp_path), timeout=900)
    assert code == 0, err
    doc = tomllib.loads((tmp_path / "easeoff.toml").read_text())["easeoff"]
    pair = load_pair("s0003")
    flanks = build_flanks(pair)
    for side, angle in (("drive", 0.0), ("coast", 30.0)):
        targets = SynthesisTargets(path_angle_deg=angle)
        syn = SimpleNamespace(coefficients=EaseOffCoefficients(**doc[side]), targets=targets)
        dp, misses = full_tca_check(pair, flanks, side, syn)
        assert max(abs(m) for m in misses) <= 1.0, (side, misses)
        assert np.isfinite(dp.path_angle_deg)
        assert abs((dp.path_angle_deg - angle + 90.0) % 180.0 - 90.0) <= targets.tol_angle_deg
