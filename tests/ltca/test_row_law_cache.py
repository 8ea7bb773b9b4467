"""The calibration cache of :func:`gearcontact.ltca.edge_rows.row_law`: two different
rows never share a cached law.

A posed-field row (a pair past its path's end, ``pc.edge``: its field posed on its
nearest interior state ``center_index``) and a row whose own state carries the contact
(``center_index == path_index``) can have the same path index (pairs at the pitch
ends share path indices, :class:`gearcontact.ltca.lte_pairs.PairFields`). Their laws
differ by construction: the posed row takes the edge row's calibration
(:func:`~gearcontact.ltca.edge_law.edge_compliance`) with a corner's continuation
(:func:`~gearcontact.ltca.off_flank.corner_law`), the surface row the trimmed field's
(:func:`~gearcontact.ltca.edge_law.trim_compliance`).

Truth: each row's law with a cache shared by both rows (as the twin's table and
``TE_pre`` share it over their phases) is the law that row gets with a cache of its own.
The calibrations are replaced by stand-ins that return a law named by the function and
the row (the dispatch and the cache are under test, not the LCP; the LCP's laws are
tested in tests/twin/test_edge_law.py and tests/twin/test_off_flank.py), so the test
takes milliseconds. Laws are compared field by field, exactly (no arithmetic between).
"""

from types import SimpleNamespace

import numpy as np
import pytest

from gearcontact.ltca import edge_rows
from gearcontact.ltca.edge_law import EdgeCompliance
from gearcontact.ltca.lte_pairs import PairContact

PATH_INDEX = 7


class _Fields:
    """What ``row_law`` reads of :class:`~gearcontact.ltca.lte_pairs.PairFields`: the
    path's edge-contact labels (none: no TCA edge row) and a field with flank cells."""

    path = SimpleNamespace(points=[SimpleNamespace(edge_contact="") for _ in range(16)])

    def get(self, pc):
        return None, None, np.zeros((2, 2), bool), pc.lever_mm


def _law(ratio_lo: float, ratio_hi: float) -> EdgeCompliance:
    """A calibration at 10 and 40 N: approach ratios to a reference of 1 um; the LCP's
    local exponent between the loads follows from the ratios."""
    ref = np.array([1e-3, 1e-3 * 4.0 ** (2.0 / 3.0)])
    lcp = ref * np.array([ratio_lo, ratio_hi])
    n = float(np.log(lcp[1] / lcp[0]) / np.log(4.0))
    return EdgeCompliance(np.array([10.0, 40.0]), lcp, ref, float(np.sqrt(ratio_lo * ratio_hi)),
                          n)


@pytest.fixture
def stand_ins(monkeypatch):
    """The edge calibration: a corner's (local exponent 0.52 between its loads, scale
    9-6); the trimmed one: a patch that stays on the flank (``c = 1``)."""
    monkeypatch.setattr(edge_rows, "edge_compliance",
                        lambda fields, pc, **kw: _law(9.0, 9.0 * 4.0 ** (0.52 - 2.0 / 3.0)))
    monkeypatch.setattr(edge_rows, "trim_compliance", lambda fields, pc, **kw: _law(1.0, 1.0))


def _row(offset: int, center: int) -> PairContact:
    return PairContact(offset, PATH_INDEX, center, 0.0, 36.6, 1.0, 0.01, 0.2, 1e-4)


def _fields_of(law: EdgeCompliance) -> tuple:
    return (tuple(law.loads_n), tuple(law.approach_lcp_mm), tuple(law.approach_ref_mm),
            law.scale, law.exponent, law.low_exponent)


@pytest.mark.parametrize("first_posed", [True, False])
def test_rows_at_one_path_index_keep_their_own_law(stand_ins, first_posed):
    posed, surface = _row(1, PATH_INDEX - 2), _row(0, PATH_INDEX)
    assert posed.edge and not surface.edge
    fields = _Fields()
    kw = dict(materials=None, torque_nmm=64.5e3)
    own = {id(pc): edge_rows.row_law(fields, pc, cache={}, **kw) for pc in (posed, surface)}
    # the two rows' own laws differ: the posed row's is the corner's (exponent 1/2
    # below its calibration), the surface row's the uncut Hertz scale 1
    assert own[id(posed)].low_exponent == 0.5 and own[id(surface)].low_exponent == 2.0 / 3.0
    shared: dict = {}
    order = (posed, surface) if first_posed else (surface, posed)
    for pc in order:
        got = edge_rows.row_law(fields, pc, cache=shared, **kw)
        assert _fields_of(got) == _fields_of(own[id(pc)])
