"""One sweep cell computed twice in one process gives identical results, bit for bit.

Truth: a grid point's result is a function of its inputs alone (docs/architecture.md
"Rules"): the workers of a sweep compute cells one after another in long-lived
processes, so a cell must not depend on the cells computed before it.
"""

from same_results import assert_same


def test_a_cell_computed_twice_is_identical(s0003_centred):
    """:func:`gearcontact.sweep.cell.compute_point` twice (TCA and LTCA, 11 phases, 24
    cells, E = 0.02 mm): every variable equal."""
    from gearcontact.sweep.cell import compute_point

    pair, flanks = s0003_centred
    kw = dict(side="drive", compute=("tca", "ltca"), phases=11, cells=24)
    a = compute_point(pair, flanks, {"E_mm": 0.02}, [64.5], **kw)
    b = compute_point(pair, flanks, {"E_mm": 0.02}, [64.5], **kw)
    assert a["error"] == [""]
    assert_same(a, b)
