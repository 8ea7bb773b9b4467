"""report.html of ``gearcontact reproduce --quick`` opened in a real browser.

Headless Debian Chromium (``/usr/bin/chromium``) driven by Selenium through the Debian
``chromedriver`` (package ``chromium-driver``, the same version as the browser; no
driver or browser is downloaded). Checked, on the run of the ``quick_report`` fixture:

- every ``<img>`` has finished loading with ``naturalWidth > 0`` (a missing or corrupt
  PNG has width 0), and there is at least one figure per item that lists one;
- the browser log holds no entry of level SEVERE (console errors, failed loads);
- the key numbers of report.json appear in the rendered text, formatted as the tables
  format them (the numbers themselves are re-derived from the library in
  test_evaluation_contact.py / test_evaluation_datapath.py);
- every SVG link opens as an SVG document with a nonzero rendered size.

No tolerance: an image loads or it does not; a number string appears or it does not.
Skipped, with the reason, where Chromium, chromedriver or Selenium is missing.
"""

from __future__ import annotations

import shutil

import pytest

from gearcontact.report.document import format_cell

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMEDRIVER = shutil.which("chromedriver") or "/usr/bin/chromedriver"


@pytest.fixture(scope="module")
def browser():
    """A headless Chromium session (skip when the browser or its driver is absent)."""
    webdriver = pytest.importorskip("selenium.webdriver",
                                    reason="selenium not installed (pip install '.[test]')")
    from pathlib import Path

    if not Path(CHROMIUM).is_file():
        pytest.skip("Chromium not installed (Debian: apt-get install chromium)")
    if not Path(CHROMEDRIVER).is_file():
        pytest.skip("chromedriver not installed (Debian: apt-get install chromium-driver)")
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu",
                "--disable-dev-shm-usage", "--window-size=1280,2000"):
        opts.add_argument(arg)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = webdriver.ChromeService(executable_path=CHROMEDRIVER)
    drv = webdriver.Chrome(options=opts, service=service)
    drv.set_page_load_timeout(60)
    yield drv
    drv.quit()


@pytest.fixture(scope="module")
def page(browser, quick_report):
    """(driver, report.json, severe log entries) after loading report.html."""
    out, rep = quick_report
    browser.get((out / "report.html").as_uri())
    # images are part of the load event: wait until every one has completed anyway
    browser.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        "Promise.all(Array.from(document.images).map(i => i.complete ? 0 :"
        " new Promise(r => { i.onload = i.onerror = r; }))).then(() => done(0));")
    severe = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    return browser, rep, severe


def test_every_image_loads(page):
    drv, rep, _ = page
    images = drv.execute_script(
        "return Array.from(document.images).map(i => [i.getAttribute('src'), i.complete,"
        " i.naturalWidth, i.naturalHeight]);")
    expected = {f for key, sec in rep.items() if key != "meta" for f in sec["figures"]}
    assert {src for src, *_ in images} == expected
    broken = [(src, ok, w, h) for src, ok, w, h in images if not (ok and w > 0 and h > 0)]
    assert not broken, broken


def test_no_console_errors(page):
    _, _, severe = page
    assert not severe, severe


def test_key_numbers_appear(page):
    drv, rep, _ = page
    text = drv.find_element("tag name", "body").text
    # every item's heading and status as rendered
    for key, sec in rep.items():
        if key != "meta":
            assert f"{sec['item']}. {sec['title']}" in text
    # every cell of every table, formatted as the table formats it (the published
    # column included): the rendered page shows all numbers of report.json's tables
    missing = [(key, t["caption"], cell) for key, sec in rep.items() if key != "meta"
               for t in sec["tables"] for row in t["rows"] for cell in row
               if format_cell(cell) not in text]
    assert not missing, missing[:10]
    n_cells = sum(len(r) for k, s in rep.items() if k != "meta"
                  for t in s["tables"] for r in t["rows"])
    assert n_cells > 100        # the report has many numbers; not a vacuous check
    # a headline number named explicitly: the surrogate's published in-box RMSE
    assert format_cell(rep["surrogate"]["synthetic"]["published"]["mlp_in_pct"]) in text


def test_svg_links_open_as_svg(browser, quick_report):
    out, rep = quick_report
    svgs = [f.replace(".png", ".svg") for key, sec in rep.items() if key != "meta"
            for f in sec["figures"]]
    assert svgs
    for name in svgs:
        browser.get((out / name).as_uri())
        root = browser.execute_script(
            "const r = document.documentElement; const b = r.getBoundingClientRect();"
            "return [r.tagName, b.width, b.height];")
        assert root[0].lower() == "svg" and root[1] > 0 and root[2] > 0, (name, root)
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
