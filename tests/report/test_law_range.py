"""analyze's statement of previews beyond the Hamrock–Brewe law's range
(report.law_range, docs/hertz.md sec. 7): which previews, the largest curvature ratio
and the law's error there, the numbers of analytic.hertz_range's table (itself checked
against scipy's exact Hertz in tests/analytic/test_hertz_range.py)."""

from gearcontact.preview.engine import GoldenEngine, ReferenceEngine
from gearcontact.report.law_range import law_range_warning

A = 0.01


def test_one_line_naming_the_previews_the_ratio_and_the_error():
    host, gold = ReferenceEngine(envelope=False), GoldenEngine()
    inside = [host.hertz(A, 107.0 * A, 600.0), gold.hertz(A, 107.0 * A, 600.0)]
    assert law_range_warning(inside[:1], inside[1:], [None]) is None
    ref = [host.hertz(A, 107.0 * A, 600.0), host.hertz(A, 470.0 * A, 600.0)]
    # ratio 470 does not reach the datapath (alpha_max 127.5: outside_envelope, None)
    golden = [gold.hertz(A, 125.0 * A, 600.0), None]
    msg = law_range_warning(ref, golden, [None, None])
    assert "\n" not in msg
    assert "fp64 1 of 2, golden D 1 of 2 torques" in msg and "C->D" not in msg
    # the largest ratio, 470, and the law's errors there (docs/hertz.md sec. 7 table:
    # stiffness +10.7 %, p_max -4.1 %), as printed (one decimal)
    assert "curvature ratio up to 470 (> 122" in msg
    assert "stiffness is +10.7 %, its p_max -4.1 %" in msg
