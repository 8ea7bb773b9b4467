"""``gearcontact warm-up``: compile the numba kernels ahead of the first real run.

The compiled kernels (TCA gap search, spline and flank evaluation, the LCP solvers,
tooth bending) are kept in numba's on-disk cache: ``NUMBA_CACHE_DIR`` if set, else
``__pycache__`` beside the sources, or a user cache directory when the installation is
read-only. That cache is keyed to the source files and to this CPU, so a wheel does not
carry it; the first command after an install compiles instead (docs/performance.md
gives the times). ``gearcontact warm-up`` does that compilation at a moment of the
user's choosing (an image build, a CI step, right after ``pip install``): it runs a
small ``gearcontact analyze`` and a short ``gearcontact twin`` of the default pair
(few phases, two torques, 1 ms of simulated time, no figures) in a temporary
directory, which call every kernel signature a default run of either calls; then the
same on a cylindrical pair (the helical example, shipped in the package): a small
``analyze`` (line-contact LCP with tooth bending, the preview's line chain; again
rigid) and a short ``twin`` with rigid teeth (the line law) and with ``--bending`` (the
coupled slice law); the directory is deleted; then the compiled edge search of a pair
with a relieved flank (:func:`gearcontact.tca.edge_kernel.warm_up`). ``--kind bevel`` or
``--kind cylindrical`` compiles one pair kind's kernels only. The commands that
compile print one line on stderr when they find the cache cold (:func:`note_cold_cache`).
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["register", "run", "cache_is_cold", "cache_directory", "note_cold_cache",
           "WARM_UP_ARGUMENTS", "TWIN_WARM_UP_ARGUMENTS", "CYLINDRICAL_WARM_UP_RUNS",
           "cylindrical_warm_up_pair", "COMPILING_COMMANDS", "WARM_UP_KINDS",
           "warm_up_runs"]

#: The run that compiles the kernels: every stage of ``analyze`` (design, TCA, LTCA,
#: multi-tooth mesh, loaded TE, fixed-point preview) at the smallest useful size.
WARM_UP_ARGUMENTS = ("analyze", "--pair", "s0003", "--phases", "9", "--torques", "64.5",
                     "258", "--lte-phases", "3", "--no-figures", "--quiet")
#: The run that compiles the twin's step kernels (their own; a default ``twin`` on a
#: cache that only the analyze run filled compiled for 170 s of CPU, issue 28 audit):
#: the default backend and curvature source at the smallest useful size.
TWIN_WARM_UP_ARGUMENTS = ("twin", "--pair", "s0003", "--phases", "9", "--duration-ms", "1",
                          "--no-figures", "--quiet")

#: The runs that compile a cylindrical pair's kernels (none of which a bevel run calls:
#: on a cold cache the first ``analyze`` of the helical example took 5 min 19 s and the
#: first ``twin`` 16 min at load 15, issue 26 audit, docs/cylindrical.md sec. 13), each
#: given ``--pair`` (:func:`cylindrical_warm_up_pair`) and ``--out``: every stage of
#: ``analyze`` (TE0, loaded TE with bending, Harris map, preview line chain; again with
#: rigid teeth) and the twin rigid (line law) and with ``--bending`` (coupled slice law),
#: at the smallest useful size. The other backends (golden, table, rtl, soc) step the
#: same compiled kernels; ``ltca``, ``lte`` and ``sweep`` call a subset (measured with
#: numba's compile events, docs/performance.md).
CYLINDRICAL_WARM_UP_RUNS = (
    ("analyze", "--phases", "3", "--lte-phases", "3", "--no-figures", "--quiet"),
    # rigid teeth: the preview's rigid line law (``ltca.slice_law.loaded_line``)
    ("analyze", "--phases", "3", "--lte-phases", "3", "--rigid", "--no-figures", "--quiet"),
    ("twin", "--phases", "3", "--duration-ms", "0.1", "--no-figures", "--quiet"),
    ("twin", "--phases", "3", "--duration-ms", "0.1", "--bending", "--no-figures",
     "--quiet"),
)

#: The values of ``warm-up --kind``.
WARM_UP_KINDS = ("all", "bevel", "cylindrical")

#: Commands that call numba kernels whose compilation takes seconds on a cold cache.
COMPILING_COMMANDS = frozenset({"analyze", "reproduce", "tca", "ltca", "lte", "bending",
                                "sweep", "twin"})


def register(sub) -> None:
    p = sub.add_parser("warm-up", help="compile the numba kernels into their on-disk cache "
                                       "now (once after an install; later runs load them)",
                       description=__doc__.split("\n\n")[1])
    p.add_argument("--kind", choices=WARM_UP_KINDS, default="all",
                   help="which pair kind's kernels to compile: bevel (the s0003 analyze and "
                        "twin, the relieved edge search), cylindrical (the helical "
                        "example's analyze and twin) or all (default)")
    p.add_argument("--quiet", action="store_true",
                   help="no progress bar, nothing printed on success")
    p.set_defaults(func=run)


#: Commands that compile nothing on a cylindrical pair (its TCA is closed form and
#: numpy; its tooth bending is the shell's linear algebra).
CYLINDRICAL_UNCOMPILED = frozenset({"tca", "bending"})


def _sentinel(kind: str | None = None):
    """A kernel every compiling command on a pair of ``kind`` calls: the TCA line
    intersection (a bevel pair), the half-space LCP's step (a cylindrical pair, whose
    TCA never calls the former, so that the note came back on every run)."""
    if kind == "cylindrical":
        from ..halfspace.constrained_cg import _step
        return _step
    from ..tca.gap_kernel import intersect_lines
    return intersect_lines


def cache_directory() -> Path | None:
    """Where numba keeps the cached kernels of this installation (None if unknown)."""
    try:
        from numba.core.caching import FunctionCache
        return Path(FunctionCache(_sentinel().py_func)._cache_path)
    except Exception:  # noqa: BLE001  (numba internals: no message rather than a failure)
        return None


def cache_is_cold(kind: str | None = None) -> bool:
    """Whether numba's cache holds no compiled code of the current sources for the
    sentinel kernel of a pair of ``kind`` (a fresh install, or sources changed since the
    last run)."""
    try:
        from numba.core.caching import FunctionCache
        return not FunctionCache(_sentinel(kind).py_func)._cache_file._load_index()
    except Exception:  # noqa: BLE001  (numba internals: assume warm, print nothing)
        return False


#: The compilation's CPU time the note quotes, by pair kind (docs/performance.md: a
#: bevel pair, issue 28 audit; a cylindrical pair, session 21 on the helical example).
_COMPILE_CPU = {None: "about 25 s of CPU, 3 min more for the twin's",
                "bevel": "about 25 s of CPU, 3 min more for the twin's",
                "cylindrical": "about 40 s of CPU, 3 min more for the twin's"}


def note_cold_cache(command: str, kind: str | None = None) -> None:
    """One line on stderr when ``command`` on a pair of ``kind`` (None: a bevel pair or
    none) is about to compile on a cold cache."""
    if kind == "cylindrical" and command in CYLINDRICAL_UNCOMPILED:
        return
    if command in COMPILING_COMMANDS and cache_is_cold(kind):
        print(f"gearcontact {command}: note: first run after install (or a source change): "
              "numba compiles its kernels into its cache now "
              f"(once: {_COMPILE_CPU.get(kind, _COMPILE_CPU[None])}); "
              "`gearcontact warm-up` does this ahead of time", file=sys.stderr)


def cylindrical_warm_up_pair() -> Path:
    """The pair file of the cylindrical warm-up runs:
    ``examples/ev_reducer_helical_23x67.toml`` as shipped in the package data
    (``data/warm_up/``)."""
    from importlib import resources
    return Path(str(resources.files("gearcontact").joinpath(
        "data/warm_up/ev_reducer_helical_23x67.toml")))


def warm_up_runs(kind: str, directory: str) -> list[list[str]]:
    """The command lines ``warm-up --kind kind`` runs, each writing under ``directory``."""
    runs = []
    if kind in ("all", "bevel"):
        runs += [[*WARM_UP_ARGUMENTS, "--out", os.path.join(directory, "run")],
                 [*TWIN_WARM_UP_ARGUMENTS, "--out", os.path.join(directory, "twin")]]
    if kind in ("all", "cylindrical"):
        runs += [[*argv, "--pair", str(cylindrical_warm_up_pair()),
                  "--out", os.path.join(directory, f"cylindrical{k}")]
                 for k, argv in enumerate(CYLINDRICAL_WARM_UP_RUNS)]
    return runs


def run(args) -> int:
    from tqdm import tqdm

    from . import main

    start = time.perf_counter()
    where = cache_directory()
    # the bar writes to the terminal's stderr: the runs' own output is captured
    bar_file = sys.stderr
    with tempfile.TemporaryDirectory(prefix="gearcontact-warm-up-") as tmp:
        runs = warm_up_runs(args.kind, tmp)
        captured = io.StringIO()
        code = 0
        with tqdm(total=len(runs), desc="warm-up", unit="run", file=bar_file,
                  disable=args.quiet) as bar, \
                contextlib.redirect_stdout(captured), contextlib.redirect_stderr(captured):
            for argv in runs:
                bar.set_postfix_str(f"{argv[0]} {Path(argv[argv.index('--pair') + 1]).stem}")
                code = main(argv)
                if code != 0:
                    break
                bar.update()
    if code == 0 and args.kind in ("all", "bevel"):
        # the edge search of a relieved pair (s0003 has none)
        from ..tca.edge_kernel import warm_up as warm_up_edge_search
        warm_up_edge_search()
    if code != 0:
        print(captured.getvalue().rstrip(), file=sys.stderr)
        # the fixed runs cannot meet bad input: a bug (exit 1, cli.EXIT_CODES)
        raise RuntimeError(f"the warm-up run ended with exit code {code}")
    if not args.quiet:
        print(f"numba kernels compiled or loaded in {time.perf_counter() - start:.1f} s; "
              f"cache: {where if where is not None else 'numba default'}")
    return 0
