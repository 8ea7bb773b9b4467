"""The report document and its renderings (:mod:`gearcontact.report.document`).

Truths: cell formatting rules (4 significant digits, whole numbers from 1000 up, yes/no,
an em dash for a missing published value); the HTML rendering escapes text (a ``<`` in a
paragraph cannot open a tag); the Markdown and HTML carry the same tables; non-finite
floats become JSON null.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("jinja2")

from gearcontact.report.document import (Reproduction, Section, Table,  # noqa: E402
                                         format_cell, jsonable, render_html,
                                         render_markdown)
from gearcontact.report.headline import Headline  # noqa: E402


def test_format_cell():
    assert format_cell(None) == "—"
    assert format_cell(True) == "yes" and format_cell(np.bool_(False)) == "no"
    assert format_cell(0.012345678) == "0.01235"
    assert format_cell(10566.6) == "10567" and format_cell(904.36) == "904.4"
    assert format_cell(8.69e-6) == "8.69e-06"
    assert format_cell(7) == "7" and format_cell("a / b") == "a / b"


def test_jsonable():
    d = jsonable({"a": np.arange(2), "b": np.float64(1.5), "c": math.nan, 3: (np.int64(4),)})
    assert json.dumps(d, allow_nan=False) == '{"a": [0, 1], "b": 1.5, "c": null, "3": [4]}'


def _doc():
    within = Headline("x", "x (mm)", 1.23456, 1.2, 1.08, 1.32, "±10 % of the value", "r",
                      True)
    sec = Section("accuracy", 1, "Accuracy", "reproduced", ["p < 5 & q"],
                  [Table("caption", ["quantity", "ours", "published"],
                         [["x (mm)", 1.23456, None]])], [("fig.png", "a figure")],
                  {"x": 1}, (within,))
    meta = {"title": "T", "intro": "I", "run_text": "R", "date": "D", "machine": "M",
            "summary": "1 items: 1 reproduced, 0 partial, 0 differs"}
    return Reproduction((sec,), meta, Path("."))


def test_renderings_carry_the_same_content():
    rep = _doc()
    html = render_html(rep)
    assert "p &lt; 5 &amp; q" in html and "<p>p < 5" not in html
    assert 'href="#accuracy"' in html and 'id="accuracy"' in html
    assert '<img src="fig.png"' in html
    assert '<td class="published">—</td>' in html and "<td>1.235</td>" in html
    md = render_markdown(rep)
    assert "| x (mm) | 1.235 | — |" in md and "![a figure](fig.png) ([SVG](fig.svg))" in md
    assert rep.as_json()["accuracy"]["x"] == 1
    # the summary line of the status counts opens both renderings
    assert "<strong>Summary: 1 items: 1 reproduced, 0 partial, 0 differs</strong>" in html
    assert "**Summary: 1 items: 1 reproduced, 0 partial, 0 differs**" in md
    assert rep.as_json()["accuracy"]["headlines"][0]["within"] is True
    assert rep.as_json()["accuracy"]["tables"][0]["header"][-1] == "published"
