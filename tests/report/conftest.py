"""One ``gearcontact reproduce --quick`` run shared by the report tests (about 2 minutes
on 2 shared cores with a warm numba cache; 2.5 minutes cold)."""

import json

import pytest


@pytest.fixture(scope="session")
def quick_report(tmp_path_factory):
    """(output directory, report.json) of one quick run through the command line."""
    pytest.importorskip("sklearn")
    pytest.importorskip("jinja2")
    from gearcontact.cli import main

    out = tmp_path_factory.mktemp("reproduce")
    assert main(["reproduce", "--out", str(out), "--quick", "--quiet"]) == 0
    return out, json.loads((out / "report.json").read_text())
