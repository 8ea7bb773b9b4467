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
