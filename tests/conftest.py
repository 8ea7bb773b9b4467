"""Shared pytest configuration.

Slow suites (long random RTL sweeps, Verilator bulk runs, synthesis) carry
``@pytest.mark.slow`` and run only with ``python -m pytest --runslow``.
"""

import pytest


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true", default=False,
                     help="also run tests marked slow (long sweeps, synthesis)")


def pytest_collection_modifyitems(config, items):
    if config.getoption("--runslow"):
        return
    skip_slow = pytest.mark.skip(reason="slow suite: run with --runslow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip_slow)


@pytest.fixture(scope="session")
def served_tri_core():
    """``gearcontact rtl serve`` (the simulated tri_core behind litex_server's protocol)
    in a subprocess on a free local port; yields ``(host, port)``. Its "listening" line
    is read from the pipe while the server runs (issue 28 probe: the line sat in a
    block-buffered stdout until exit, so a script reading the pipe never saw it): a
    line that does not arrive within 300 s fails the fixture instead of blocking."""
    import os
    import selectors
    import socket
    import subprocess
    import sys
    import time

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    proc = subprocess.Popen([sys.executable, "-m", "gearcontact", "rtl", "serve", "--port",
                             str(port)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    try:
        deadline, seen = time.monotonic() + 300, b""
        with selectors.DefaultSelector() as sel:
            sel.register(proc.stdout, selectors.EVENT_READ)
            # the server says when it listens; the pipe's raw bytes, as they arrive
            while b"gearcontact rtl serve: listening on" not in seen:
                if not sel.select(timeout=max(deadline - time.monotonic(), 0.0)):
                    raise RuntimeError("gearcontact rtl serve: no 'listening' line on its "
                                       f"stdout pipe within 300 s (got {seen!r})")
                chunk = os.read(proc.stdout.fileno(), 4096)
                if not chunk:
                    raise RuntimeError(f"gearcontact rtl serve exited: {proc.wait()}")
                seen += chunk
        yield "127.0.0.1", port
    finally:
        proc.terminate()
        proc.wait(30)


@pytest.fixture(scope="session")
def s0003_centred():
    """``(pair, flanks)`` of the built-in s0003-centred pair and its production flank set
    (120 x 150 pinion nodes, about 2 s): the one s0003 set-up of the geometry,
    structure, tca, ltca, sweep and twin tests, built once per session; they take it
    directly (no per-directory alias fixtures)."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair

    pair = load_pair("s0003-centred")
    return pair, build_flanks(pair)


@pytest.fixture(scope="session")
def f2_machine_pair():
    """The ISO 23509 F.2 example cut from its blank's standard settings typed to 4
    decimals (examples/machine_settings/iso23509_f2_machine.toml): the clean typed sheet
    of the settings-check tests, which make their slips from it with
    ``dataclasses.replace``."""
    from pathlib import Path

    from gearcontact.geometry.pair import load_pair

    return load_pair(Path(__file__).resolve().parents[1] / "examples" / "machine_settings"
                     / "iso23509_f2_machine.toml")


@pytest.fixture(scope="session")
def s0003_calibrated():
    """``(pair, flanks)`` of the calibrated s0003 preset (design side coast, tip-edge
    bearing) and its production flank set, built once per session for the structure,
    tca, ltca, twin and report tests (``analyze_pair(pair)`` builds the same flanks)."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair

    pair = load_pair("s0003")
    return pair, build_flanks(pair)


@pytest.fixture(scope="session")
def s0003_calibrated_tca(s0003_calibrated):
    """The nominal TCA of the calibrated s0003 on its design side (coast) at the default
    61 phases per pitch, ``analyze_pair(pair)``: shared by tests/tca/test_calibration.py
    and tests/tca/test_edges.py."""
    from gearcontact.tca.analysis import analyze_pair

    pair, flanks = s0003_calibrated
    return analyze_pair(pair, flanks=flanks)[0]


@pytest.fixture(scope="session")
def s0003_calibrated_tca15(s0003_calibrated):
    """The calibrated s0003's TCA on its design side at 15 phases per pitch: the set-up
    of both accuracy studies (tests/report/test_accuracy_studies.py)."""
    from gearcontact.tca.analysis import analyze_pair

    pair, flanks = s0003_calibrated
    return analyze_pair(pair, side=pair.design_side, phases=15, flanks=flanks)[0]


@pytest.fixture(scope="session")
def make_hertz():
    """Factory fixture returning ``hertz_problems.hertz_problem`` (cached per arguments):
    the Hertzian gaps of the halfspace and ltca solver tests."""
    from hertz_problems import LOAD_N, hertz_problem

    cache = {}

    def make(ratio, n, extent=1.3, load_n=LOAD_N):
        key = (ratio, n, extent, load_n)
        if key not in cache:
            cache[key] = hertz_problem(ratio, n, extent, load_n=load_n)
        return cache[key]

    return make
