"""``design --machine-settings --contact-curvature`` (docs/machine_settings.md sec. 6,
"The residual's curvature and the pressure it bounds"): the option refused where it
has no effect, before any flank work; the run on s0003 (slow) prints the residual's
curvature at the target's contact path with its Hertz bound and fits V_1 on the coast.
"""

from pathlib import Path

import pytest

from gearcontact.cli import main

ROOT = Path(__file__).resolve().parents[2]
F3 = ROOT / "examples" / "iso23509_f3.toml"


@pytest.mark.parametrize("argv, allowed", [
    (["--pair", "s0003", "--contact-curvature"], "--machine-settings"),
    (["--pair", str(F3), "--machine-settings", "--contact-curvature"], "ease-off"),
])
def test_contact_curvature_refused_where_it_has_no_effect(argv, allowed, capsys):
    # exit 2 naming the option and what it needs (s0003 without --machine-settings;
    # F.3 has no [easeoff.*]: nothing is fitted)
    assert main(["design", *argv]) == 2
    err = capsys.readouterr().err
    assert "--contact-curvature" in err and allowed in err


@pytest.mark.slow
def test_contact_curvature_on_s0003_reports_the_bound(tmp_path, capsys):
    # the table line of the coast side (the drive, s0003's zero ease-off, is in line
    # contact: no path, no line) and the coast's V_1 correction; the numbers are those
    # of the library fit (geometry tests), the bound = pressure_bound(e) by its formula
    import re

    assert main(["design", "--pair", "s0003", "--machine-settings", "--contact-curvature",
                 "--out", str(tmp_path / "d")]) == 0
    out = capsys.readouterr().out
    assert "drive: the residual's curvature" not in out
    line = next(x for x in out.splitlines() if x.startswith("coast: the residual's curvature"))
    e_p0, b_p0, e_max, b_max = map(float, re.findall(
        r"at P0 ([\d.]+) \(Hertz pressure bound \+-([\d.]+) %\), max ([\d.]+) \(\+-([\d.]+) %",
        line)[0])
    for e, b in ((e_p0, b_p0), (e_max, b_max)):
        assert b == pytest.approx(100.0 * (1.0 - (1.0 - e) ** (2.0 / 3.0)), abs=0.01)
    assert e_max < 0.15 and "fitted with curvature rows" in line
    assert re.search(r"\| helical_motion_mm_per_rad \| mm/rad \| - \| [-+]", out)
