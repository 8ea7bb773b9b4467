"""The report document of ``gearcontact reproduce`` and its two renderings.

A :class:`Reproduction` is a list of :class:`Section` (one per evaluation item), each
with paragraphs, :class:`Table` and figures beside the report, and the machine-readable
numbers of the item. :func:`render_html` renders it with the Jinja2 template
``data/templates/report.html.j2`` (one page, a table of contents, figures by relative
path); :func:`render_markdown` writes the same content as Markdown.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

__all__ = ["Table", "Section", "Reproduction", "format_cell", "jsonable", "pct_diff",
           "render_html", "render_markdown"]


@dataclass(frozen=True)
class Table:
    """A report table: caption, header and rows (the last column is ``published``
    unless the caption says otherwise)."""

    caption: str
    header: list
    rows: list


@dataclass
class Section:
    """One item of the evaluation.

    Attributes
    ----------
    key : str
        Item key (:data:`ITEMS`), also the HTML anchor.
    number : int
        Item number of docs/spec.md sec. 8.
    title : str
    status : str
        ``"reproduced"``, ``"partial"`` or ``"differs"``, computed from ``headlines``
        (:func:`gearcontact.report.headline.judged_section`), or ``"not available"``
        for an item that measured nothing (no headlines).
    text : list of str
        Paragraphs (each difference beyond its tolerance explained with a measurement).
    tables : list of Table
    figures : list of (str, str)
        (file name beside the report, caption).
    data : dict
        The machine-readable numbers (``report.json[key]``).
    headlines : tuple of gearcontact.report.headline.Headline
        The quantities the status is computed from (``report.json[key]["headlines"]``).
    """

    key: str
    number: int
    title: str
    status: str
    text: list = field(default_factory=list)
    tables: list = field(default_factory=list)
    figures: list = field(default_factory=list)
    data: dict = field(default_factory=dict)
    headlines: tuple = ()

    def __post_init__(self):
        # a status is measured, never asserted: only an item that measured nothing is
        # "not available", and none is "reproduced" with a headline outside tolerance
        if (self.status == "not available") != (not self.headlines):
            raise ValueError(f"item {self.key}: status {self.status!r} with "
                             f"{len(self.headlines)} headline quantities")
        if self.status == "reproduced" and not all(h.within for h in self.headlines):
            raise ValueError(f"item {self.key}: 'reproduced' with a headline outside "
                             "its tolerance")

    def as_dict(self) -> dict:
        """JSON of the section: status, title, text, tables, figures, headlines and
        data."""
        return {"item": self.number, "title": self.title, "status": self.status,
                "text": self.text, "tables": [asdict(t) for t in self.tables],
                "figures": [f for f, _ in self.figures],
                "headlines": [h.as_dict() for h in self.headlines], **self.data}


@dataclass(frozen=True, eq=False)
class Reproduction:
    """Result of :func:`run_reproduce`.

    Attributes
    ----------
    sections : tuple of Section
        One per item, in :data:`ITEMS` order.
    meta : dict
        Title, version, settings, warnings of the main job (no timings).
    out_dir : Path
    analysis : gearcontact.report.analyze.Analysis
        The main job's results the report was built from.
    timings_s : dict
        Wall seconds per item, ``total_s`` and the main job's stage timings
        (``main_job``); not in the report files: the command line writes them into
        run.json.
    """

    sections: tuple
    meta: dict
    out_dir: Path
    analysis: object = None
    timings_s: dict = field(default_factory=dict)

    def as_json(self) -> dict:
        """The content of ``report.json``."""
        d = {s.key: s.as_dict() for s in self.sections}
        d["meta"] = self.meta
        return d


def pct_diff(a, b):
    """``100 (a / b - 1)`` in %, or None when either is None."""
    return None if a is None or b is None else 100.0 * (a / b - 1.0)


def format_cell(x) -> str:
    """A table cell as text: 4 significant digits (whole numbers from 1000 up, no
    exponent), yes/no, an em dash for None."""
    if x is None:
        return "—"
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    if isinstance(x, (float, np.floating)):
        if not math.isfinite(x):
            return str(x)
        if 1e3 <= abs(x) < 1e9:
            return f"{x:.0f}"
        return f"{x:.4g}"
    return str(x)


def jsonable(x):
    """``x`` with numpy scalars / arrays as plain Python and non-finite floats as None."""
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return jsonable(x.tolist())
    if isinstance(x, (np.floating,)):
        return float(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (np.bool_,)):
        return bool(x)
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def _template(name: str):
    from jinja2 import Environment, select_autoescape

    env = Environment(autoescape=select_autoescape(["html", "j2"]), trim_blocks=True,
                      lstrip_blocks=True)
    env.filters["fmt"] = format_cell
    src = resources.files("gearcontact").joinpath(f"data/templates/{name}").read_text()
    return env.from_string(src)


def render_html(rep: Reproduction) -> str:
    """The report as one HTML page (Jinja2 template ``data/templates/report.html.j2``)."""
    return _template("report.html.j2").render(sections=rep.sections, meta=rep.meta)


def render_markdown(rep: Reproduction) -> str:
    """The report as Markdown (the same content as the HTML page)."""
    out = [f"# {rep.meta['title']}", "", rep.meta["intro"], ""]
    if rep.meta.get("summary"):
        out += [f"**Summary: {rep.meta['summary']}**", ""]
    out += [f"- [{s.number}. {s.title}](#{s.key}) — {s.status}" for s in rep.sections]
    for s in rep.sections:
        out += ["", f'<a id="{s.key}"></a>', f"## {s.number}. {s.title}", "",
                f"Status: **{s.status}**", ""]
        out += [p + "\n" for p in s.text]
        for t in s.tables:
            out += [f"*{t.caption}*", "", "| " + " | ".join(map(str, t.header)) + " |",
                    "|" + "---|" * len(t.header)]
            out += ["| " + " | ".join(format_cell(x) for x in r) + " |" for r in t.rows]
            out.append("")
        out += [f"![{cap}]({f}) ([SVG]({f.replace('.png', '.svg')}))" for f, cap in s.figures]
    out += ["", "## Run", "", f"{rep.meta['run_text']}", ""]
    if rep.meta.get("main_job_warnings"):
        out += ["Warnings of the main job: " + "; ".join(rep.meta["main_job_warnings"]), ""]
    return "\n".join(out)
