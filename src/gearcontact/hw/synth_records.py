"""Synthesis results committed with the package, with their provenance.

``gearcontact/data/synth/resources.json`` holds the gap lane sweep (one provenance for
all rows, written by ``gearcontact reproduce --synth``); ``cores.json`` holds whole cores
and SoC tops (one provenance per row: tool and version, the exact Yosys script, date,
machine, note). ``gearcontact rtl synth --committed`` prints them and the reproduce
report tables them (:mod:`gearcontact.report.evaluation_datapath`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass

from .synth import SynthResult

__all__ = ["COMMITTED_FILES", "CommittedRecord", "committed_records"]


@dataclass(frozen=True)
class CommittedRecord:
    """One committed synthesis result with its provenance (:func:`committed_records`).

    Attributes
    ----------
    result : SynthResult
        Cell counts, depth, wall / CPU seconds.
    tool : str
        Tool and version (pip pin or ``yosys -V`` line).
    command : str
        The Yosys script (or the function that ran it).
    date : str
        ISO 8601 UTC start time.
    machine : str
        ``platform.platform()`` and the CPU share it had.
    note : str
        How the number was obtained, if not by one plain run.
    """

    result: SynthResult
    tool: str
    command: str
    date: str
    machine: str
    note: str = ""


#: Committed result files under ``gearcontact/data/synth/``: ``resources.json`` (the gap
#: lane sweep, one provenance for all rows) and ``cores.json`` (one provenance per row).
COMMITTED_FILES = ("resources.json", "cores.json")


def committed_records() -> list[CommittedRecord]:
    """Every synthesis result committed with the package, with its provenance."""
    from importlib import resources
    out = []
    root = resources.files("gearcontact").joinpath("data/synth")
    for name in COMMITTED_FILES:
        f = root.joinpath(name)
        if not f.is_file():
            continue
        doc = json.loads(f.read_text())
        shared = doc.get("provenance")
        for row in doc["results"]:
            prov = shared or row["provenance"]
            res = {k: v for k, v in row.items() if k != "provenance"}
            res.setdefault("tool", prov["tool"])
            out.append(CommittedRecord(SynthResult(**res), prov["tool"], prov["command"],
                                       prov["date"], prov["machine"], prov.get("note", "")))
    return out
