"""``gearcontact warm-up`` and the first-run note on a cold numba cache.

Truth: numba's own compile events. Each run is a fresh interpreter with its own empty
``NUMBA_CACHE_DIR`` (the state right after an install)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

import gearcontact

SRC = str(Path(gearcontact.__file__).parents[1])

#: Runs the command line with numba's compile events counted; prints the count last.
_COUNTING = r"""
import sys
from numba.core import event
from gearcontact.cli import main
with event.install_recorder("numba:compile") as rec:   # a context manager (numba 0.68)
    code = main(sys.argv[1:])
print("compiled", sum(1 for _, e in rec.buffer if e.is_start), file=sys.stderr)
sys.exit(code)
"""


def _cli(argv, cache, *, count=False):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache),
           "PYTHONPATH": os.pathsep.join([SRC, os.environ.get("PYTHONPATH", "")])}
    head = [sys.executable, "-c", _COUNTING] if count else [sys.executable, "-m",
                                                             "gearcontact"]
    proc = subprocess.run(head + list(argv), env=env, capture_output=True, text=True,
                          timeout=1800, check=False)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stderr


def test_first_run_note_once(tmp_path):
    """A compiling command prints the one-line note on an empty cache, not once the
    cache holds its kernels; a command that compiles nothing never prints it."""
    cache = tmp_path / "numba"
    argv = ["tca", "--pair", "s0003-centred", "--phases", "3", "--quiet", "--no-figures"]
    first = _cli(argv + ["--out", str(tmp_path / "a")], cache)
    notes = [line for line in first.splitlines() if "note: first run" in line]
    assert len(notes) == 1 and "gearcontact warm-up" in notes[0]
    again = _cli(argv + ["--out", str(tmp_path / "b")], cache)
    assert "note: first run" not in again
    other = _cli(["design", "--pair", "s0003"], tmp_path / "other")
    assert "note: first run" not in other


EV = str(Path(SRC).parent / "examples" / "ev_reducer_helical_23x67.toml")


def test_cylindrical_tca_compiles_nothing_and_says_nothing(tmp_path):
    """A cylindrical pair's TCA (closed form, numpy) compiles no kernel on an empty cache
    (numba's compile events: 0), so it prints no note; before, the note's sentinel was
    the bevel TCA's kernel, which no cylindrical command compiles, and every cylindrical
    run printed it."""
    err = _cli(["tca", "--pair", EV, "--phases", "3", "--quiet", "--no-figures",
                "--out", str(tmp_path / "a")], tmp_path / "numba", count=True)
    assert err.strip().splitlines()[-1] == "compiled 0"
    assert "note: first run" not in err


@pytest.mark.slow
def test_cylindrical_note_once(tmp_path):
    """A compiling command on a cylindrical pair (``ltca``, rigid teeth: the half-space
    LCP's kernels) prints the note on an empty cache and not once its kernels are in."""
    cache = tmp_path / "numba"
    argv = ["ltca", "--pair", EV, "--phases", "3", "--cells", "16", "--rigid",
            "--no-figures"]
    first = _cli(argv + ["--out", str(tmp_path / "a")], cache)
    assert sum("note: first run" in line for line in first.splitlines()) == 1
    again = _cli(argv + ["--out", str(tmp_path / "b")], cache, count=True)
    assert "note: first run" not in again


@pytest.mark.slow
def test_warm_up_compiles_everything_a_default_analyze_calls(tmp_path):
    """After ``gearcontact warm-up`` into an empty cache, a default ``analyze`` and a
    default ``twin`` of a shipped example compile no kernel at all (every signature is
    loaded from the cache; the twin's step kernels once took 170 s of CPU on the first
    twin after an install: issue 28 audit)."""
    cache = tmp_path / "numba"
    _cli(["warm-up", "--quiet"], cache)
    err = _cli(["analyze", "--pair", "s0003", "--quiet", "--out", str(tmp_path / "a")],
               cache, count=True)
    assert err.strip().splitlines()[-1] == "compiled 0"
    assert "note: first run" not in err
    example = Path(SRC).parent / "examples" / "hypoid_11x41_rear_axle.toml"
    err = _cli(["twin", "--pair", str(example), "--quiet", "--no-figures",
                "--out", str(tmp_path / "t")], cache, count=True)
    assert err.strip().splitlines()[-1] == "compiled 0"


def test_the_cylindrical_warm_up_pair_is_the_example():
    """The pair file the warm-up ships (the package carries no examples/) is the helical
    example: the same validated pair (dataclass equality, every field)."""
    from gearcontact.cli.warm_up import cylindrical_warm_up_pair
    from gearcontact.geometry.pair import CYLINDRICAL, load_pair

    shipped = load_pair(cylindrical_warm_up_pair(), kinds=(CYLINDRICAL,))
    assert shipped == load_pair(EV, kinds=(CYLINDRICAL,))


@pytest.mark.slow
def test_warm_up_compiles_everything_a_cylindrical_pair_calls(tmp_path):
    """After ``gearcontact warm-up`` into an empty cache, a cylindrical ``twin`` (rigid:
    the line law; ``--bending``: the coupled slice law) and ``analyze`` of the helical
    example compile no kernel (numba's compile events: 0); before the warm-up ran them
    on a cylindrical pair, the first ``analyze`` took 5 min 19 s and the first ``twin``
    16 min on a loaded machine (issue 26 audit)."""
    cache = tmp_path / "numba"
    _cli(["warm-up", "--quiet"], cache)
    for k, extra in enumerate(([], ["--bending"], ["--backend", "golden"])):
        err = _cli(["twin", "--pair", EV, "--duration-ms", "0.2", "--quiet", "--no-figures",
                    *extra, "--out", str(tmp_path / f"t{k}")], cache, count=True)
        assert err.strip().splitlines()[-1] == "compiled 0", extra
        assert "note: first run" not in err
    for k, extra in enumerate(([], ["--rigid"])):
        err = _cli(["analyze", "--pair", EV, "--lte-phases", "5", "--quiet", "--no-figures",
                    *extra, "--out", str(tmp_path / f"a{k}")], cache, count=True)
        assert err.strip().splitlines()[-1] == "compiled 0", extra


def test_warm_up_kind_selects_one_pair_kind(tmp_path):
    """``--kind bevel`` runs only the s0003 analyze and twin, ``--kind cylindrical`` only
    the helical example's four runs, ``all`` (the default) both, in that order; an
    unknown kind is refused naming the option (exit 2) before anything compiles."""
    from gearcontact.cli.warm_up import (CYLINDRICAL_WARM_UP_RUNS, WARM_UP_ARGUMENTS,
                                         TWIN_WARM_UP_ARGUMENTS, warm_up_runs)

    def pairs(kind):
        return [Path(argv[argv.index("--pair") + 1]).stem
                for argv in warm_up_runs(kind, str(tmp_path))]

    assert pairs("bevel") == ["s0003", "s0003"]
    assert pairs("cylindrical") == ["ev_reducer_helical_23x67"] * len(CYLINDRICAL_WARM_UP_RUNS)
    assert pairs("all") == pairs("bevel") + pairs("cylindrical")
    assert warm_up_runs("bevel", str(tmp_path))[0][:len(WARM_UP_ARGUMENTS)] == list(WARM_UP_ARGUMENTS)
    assert warm_up_runs("bevel", str(tmp_path))[1][:len(TWIN_WARM_UP_ARGUMENTS)] == list(
        TWIN_WARM_UP_ARGUMENTS)
    proc = subprocess.run([sys.executable, "-m", "gearcontact", "warm-up", "--kind", "spur"],
                          capture_output=True, text=True, timeout=120, check=False)
    assert proc.returncode == 2 and "--kind" in proc.stderr and "spur" in proc.stderr
