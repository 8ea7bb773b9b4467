"""The design documents the code cites exist, with every cited section.

Truth: the files under ``docs/`` themselves. Every ``docs/<name>.md`` path named in the
package, the tests, the benchmarks, the docs and the README must be a file of the
repository, and every section number cited as ``docs/<name>.md sec. N`` (also
``section N``, ``sections N, M``, ``sec. N/M``) must be a numbered heading ``## N.`` of
that file. No tolerance: a citation resolves or it does not.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
#: A docs path, optionally followed by the cited section numbers.
CITATION = re.compile(r"docs/([\w.-]+?\.md)(?:,?\s+(?:sec\.|sections?|§)\s*"
                      r"(\d+(?:\s*(?:,|/|and)\s*\d+)*))?")
HEADING = re.compile(r"^#{2,3}\s+(\d+)\.", re.MULTILINE)


def _sources():
    for sub in ("src", "tests", "benchmarks", "docs", "examples"):
        for path in sorted((ROOT / sub).rglob("*")):
            if path.suffix in {".py", ".md", ".toml", ".json", ".j2"} and path.is_file():
                yield path
    yield ROOT / "README.md"


def _citations():
    found = []
    for path in _sources():
        for m in CITATION.finditer(path.read_text(encoding="utf-8")):
            sections = [int(n) for n in re.findall(r"\d+", m.group(2) or "")]
            found.append((path.relative_to(ROOT), m.group(1), sections))
    return found


def test_cited_docs_and_sections_exist():
    cites = _citations()
    # the code cites the three design documents many times (about 100 citations)
    names = {name for _, name, _ in cites}
    assert {"spec.md", "geometry.md", "hardware.md"} <= names
    assert len(cites) > 80
    headings = {}
    missing = []
    for where, name, sections in cites:
        doc = DOCS / name
        if not doc.is_file():
            missing.append(f"{where}: docs/{name} does not exist")
            continue
        if name not in headings:
            headings[name] = {int(n) for n in HEADING.findall(doc.read_text(encoding="utf-8"))}
        missing += [f"{where}: docs/{name} has no section {n}" for n in sections
                    if n not in headings[name]]
    assert not missing, "\n".join(missing)


def test_no_citation_of_files_outside_the_repository():
    # the design background of the project is not shipped: code cites docs/ only
    stale = re.compile(r"shared/|\b(?:SPEC|GEOMETRY|HARDWARE)(?:\.md)?\s+(?:sec|section|§)")
    bad = [f"{p.relative_to(ROOT)}: {m.group(0)}" for p in _sources()
           if p != Path(__file__).resolve()
           for m in stale.finditer(p.read_text(encoding="utf-8"))]
    assert not bad, "\n".join(bad)


def test_numbered_sections_are_complete():
    # spec 1-9, geometry 1-7, hardware 1-5: the numbering the citations rely on
    for name, n in (("spec.md", 9), ("geometry.md", 7), ("hardware.md", 5)):
        got = [int(s) for s in HEADING.findall((DOCS / name).read_text(encoding="utf-8"))]
        assert sorted(set(got)) == list(range(1, n + 1)), name
