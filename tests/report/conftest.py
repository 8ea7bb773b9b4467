"""One ``gearcontact reproduce --quick`` run shared by the report tests (about 2 minutes
on 2 shared cores with a warm numba cache; 2.5 minutes cold), once per test run: the
pytest-xdist workers share it (tests/run_once.py)."""

import json

import pytest
from run_once import run_once


@pytest.fixture(scope="session")
def quick_report(tmp_path_factory):
    """(output directory, report.json) of one quick run through the command line."""
    pytest.importorskip("sklearn")
    pytest.importorskip("jinja2")
    from gearcontact.cli import main

    def build(out):
        assert main(["reproduce", "--out", str(out), "--quick", "--quiet"]) == 0

    out, _ = run_once(tmp_path_factory, "reproduce", build)
    return out, json.loads((out / "report.json").read_text())
