"""Shared fixtures of the command-line tests."""

from importlib import resources

import pytest


@pytest.fixture(scope="session")
def bare_pair_file(tmp_path_factory):
    """s0003-centred as a pair file without its [easeoff.drive] table: the drive side's
    ease-off is synthesized by every command that analyses it."""
    text = resources.files("gearcontact").joinpath("data/pairs/s0003-centred.toml").read_text()
    head, rest = text.split("[easeoff.drive]", 1)
    path = tmp_path_factory.mktemp("pair") / "bare.toml"
    path.write_text(head + "[easeoff.coast]" + rest.split("[easeoff.coast]", 1)[1])
    return path


#: ``gearcontact ltca --multi-tooth`` on the calibrated (tip-edge) s0003 at the default
#: 64.5 N·m: the run of test_ltca.py::test_multi_tooth and of the identical-runs test
#: (test_reproducible.py).
MULTI_TOOTH_ARGV = ["ltca", "--pair", "s0003", "--torque", "64.5", "--phases", "11",
                    "--cells", "24", "--multi-tooth", "--multi-tooth-cells", "24"]


@pytest.fixture(scope="session")
def multi_tooth_runs(tmp_path_factory):
    """Two runs of :data:`MULTI_TOOTH_ARGV` (figures written) into two directories
    ``[a, b]``: test_ltca.py::test_multi_tooth asserts on ``a``, test_reproducible.py
    that ``a`` and ``b`` hold the same bytes (two runs, where each test ran its own: one
    multi-tooth LTCA less per test run)."""
    from gearcontact.cli import main

    base = tmp_path_factory.mktemp("multi_tooth")
    outs = [base / "a", base / "b"]
    for out in outs:
        assert main([*MULTI_TOOTH_ARGV, "--out", str(out)]) == 0
    return outs
