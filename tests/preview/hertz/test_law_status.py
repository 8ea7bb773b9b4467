"""The preview's law status (preview.hertz.reference.law_status, PreviewResult.law_status):
a Hamrock–Brewe ellipse beyond curvature ratio 122 is reported, because there its
outputs leave the declared 5 % of exact Hertz (docs/hertz.md sec. 7).

Truth: exact elliptic Hertz (analytic.hertz.exact_elliptic_hertz, Carlson's integrals;
checked against scipy's K, E in tests/analytic/test_hertz_range.py) at the curvatures
the preview took. The approach of a fixed-point preview is the twin's
(twin.contact_law.hertz_kappa: ``3 W F/(pi a E')``, F of Hamrock–Brewe at
``alpha = k^(pi/2)``), formed here from its a and k.
"""

import math

import pytest

from gearcontact.analytic.hertz import exact_elliptic_hertz
from gearcontact.analytic.hertz_range import HB_TOLERANCE
from gearcontact.preview.engine import ReferenceEngine, get_engine
from gearcontact.preview.hertz.reference import LAW_BEYOND_RANGE, LAW_OK, law_status

W = 1000.0
A_MIN = 0.01


def _errors(res, e_prime):
    """Relative errors of a preview's a, b, p_max and stiffness against exact Hertz at
    the curvatures it took."""
    ex = exact_elliptic_hertz(res.A_minus_per_mm, res.B_minus_per_mm, res.load_n,
                              e_prime_mpa=e_prime)
    f = 0.5 * math.pi + (0.5 * math.pi - 1.0) * 0.5 * math.pi * math.log(res.k)
    delta = 3.0 * res.load_n * f / (math.pi * res.a_mm * e_prime)
    return {"a": res.a_mm / ex.a_mm - 1.0, "b": res.b_mm / ex.b_mm - 1.0,
            "p_max": res.p_max_mpa / ex.p_max_mpa - 1.0,
            "stiffness": ex.approach_mm / delta - 1.0}


def test_law_status_rule():
    assert law_status(A_MIN, 1.2, hertz_form="hamrock-brewe") == LAW_OK         # 120
    assert law_status(1.25, A_MIN, hertz_form="hamrock-brewe") == LAW_BEYOND_RANGE
    assert law_status(A_MIN, 4.7, hertz_form="exact") == LAW_OK
    assert law_status(A_MIN, 4.7, hertz_form="hamrock-brewe", mode="line") == LAW_OK
    assert law_status(A_MIN, 4.7, hertz_form="hamrock-brewe", mode="flagged") == LAW_OK
    assert law_status(0.0, 4.7, hertz_form="hamrock-brewe") == LAW_OK   # no ellipse


@pytest.mark.parametrize("ratio, status", [(120.0, LAW_OK), (127.0, LAW_BEYOND_RANGE)])
def test_golden_flag_is_where_its_law_leaves_the_tolerance(ratio, status):
    """Inside the datapath (ratio <= 127.5): at 120 every golden output is within 5 % of
    exact Hertz and the status is ok; at 127 the law is more than 5 % stiffer and the
    status says so. RTL == golden bit for bit (tests/preview/hertz/test_rtl.py), so
    this is the RTL's status too."""
    gold = get_engine("golden")
    res = gold.hertz(A_MIN, ratio * A_MIN, W)
    assert not res.flags and res.mode == "elliptic"
    err = _errors(res, gold.e_prime_mpa)
    assert res.law_status == status and res.as_dict()["law_status"] == status
    if status == LAW_OK:
        assert max(abs(v) for v in err.values()) <= HB_TOLERANCE
    else:
        assert err["stiffness"] > HB_TOLERANCE


def test_exact_form_is_never_flagged():
    """The exact tables (hertz_form="exact") are within 0.1 % of exact Hertz at ratio 127
    (docs/architecture.md: 5.4e-4 end to end in k): no status."""
    gold = get_engine("golden", hertz_form="exact")
    res = gold.hertz(A_MIN, 127.0 * A_MIN, W)
    ex = exact_elliptic_hertz(res.A_minus_per_mm, res.B_minus_per_mm, W,
                              e_prime_mpa=gold.e_prime_mpa)
    assert res.p_max_mpa == pytest.approx(ex.p_max_mpa, rel=1e-3)
    assert res.law_status == LAW_OK


def test_host_fp64_preview_beyond_the_datapath():
    """The host's fp64 preview (envelope=False: analyze's reference column, the twin's
    law outside the datapath) at the F.2 pair's ratio 470: reported, the law 10.7 %
    stiffer than exact Hertz (docs/hertz.md sec. 7); the line core there answers with
    the line contact, not Hamrock–Brewe: no status."""
    host = ReferenceEngine(envelope=False)
    res = host.hertz(A_MIN, 470.0 * A_MIN, W)
    assert res.law_status == LAW_BEYOND_RANGE
    assert _errors(res, host.e_prime_mpa)["stiffness"] == pytest.approx(0.1074, abs=5e-4)
    line = get_engine("golden").hertz(A_MIN, 470.0 * A_MIN, W, line_length_mm=10.0)
    assert line.mode == "line" and line.law_status == LAW_OK
