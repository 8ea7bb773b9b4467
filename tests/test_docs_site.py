"""The documentation site (``docs/conf.py``) builds with warnings as errors.

Sphinx with myst-parser reads the Markdown pages of ``docs/`` and autodoc/autosummary
generate one API page per module from the numpydoc docstrings. The build runs into
``tmp_path`` from a copy of ``docs/`` (autosummary writes its generated page sources
beside the sources; the repository stays untouched). Truth: Sphinx's own checks, with
``-W`` (any warning fails): broken reST/Markdown markup in a docstring or page, a
duplicate object description, a page outside every table of contents, a module that
does not import. Beyond a clean build, every module of the package has its API page and
every Markdown page of ``docs/`` its HTML page (no tolerance: a page exists or not).
Takes 30-40 s on this machine's 2 cores (about 150 modules imported and rendered).
"""

from __future__ import annotations

import pkgutil
import shutil
import sys
from pathlib import Path

import pytest

import gearcontact

ROOT = Path(__file__).resolve().parents[1]


# Sphinx's own deprecation notices (napoleon's option mapping, ~2,800 per build) are
# about Sphinx 11, not about our docs; the build's warnings are checked below with -W
@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_docs_site_builds_without_warnings(tmp_path):
    pytest.importorskip("sphinx", reason="the docs extra is not installed "
                                         "(pip install '.[docs]')")
    pytest.importorskip("myst_parser", reason="the docs extra is not installed "
                                              "(pip install '.[docs]')")
    from sphinx.cmd.build import build_main

    src, out = tmp_path / "src", tmp_path / "html"
    shutil.copytree(ROOT / "docs", src, ignore=shutil.ignore_patterns("_build", "_api"))
    log = tmp_path / "warnings.txt"
    before = dict(sys.modules)
    try:
        status = build_main(["-W", "--keep-going", "-q", "-b", "html", "-w", str(log),
                             str(src), str(out)])
    finally:
        _forget_modules_imported_since(before)
    assert status == 0, log.read_text()
    assert log.read_text() == ""
    pages = {p.stem for p in (out / "_api").glob("*.html")}
    modules = {m.name for m in pkgutil.walk_packages(gearcontact.__path__, "gearcontact.")
               if m.name != "gearcontact.__main__" and not m.name.endswith(".__main__")}
    assert modules - pages == set()
    assert {p.stem for p in (ROOT / "docs").glob("*.md")} <= {p.stem
                                                                for p in out.glob("*.html")}
    # the API pages carry the docstrings: a function's numpydoc Parameters section and
    # the units it states, and a module docstring's citation of docs/
    hertz = (out / "_api" / "gearcontact.analytic.hertz.html").read_text(encoding="utf-8")
    assert 'id="gearcontact.analytic.hertz.exact_elliptic_hertz"' in hertz
    assert "Parameters" in hertz and "load_n" in hertz and "docs/hertz.md sec. 2" in hertz


def _forget_modules_imported_since(before: dict) -> None:
    """Drop what the build imported: autodoc imports the package's modules against
    mocked optional tools (``autodoc_mock_imports``: litex, migen, ...), and a later test
    in this process must import them again against the real ones (``hw.litex.board``
    failed with ``~platform.request(...)`` on a mock when the docs test ran first)."""
    for name in set(sys.modules) - set(before):
        module = sys.modules[name]
        # real third-party modules stay: a C extension (numpy's, scipy's) cannot be
        # loaded twice in one process, and a later lazy import would find it half gone
        if not (name.split(".")[0] == "gearcontact" or module is None
                or type(module).__name__ == "_MockModule"):
            continue
        parent, _, child = name.rpartition(".")
        if parent in sys.modules and getattr(sys.modules[parent], child, None) is sys.modules[name]:
            delattr(sys.modules[parent], child)
        del sys.modules[name]
    sys.modules.update(before)
