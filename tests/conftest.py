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
