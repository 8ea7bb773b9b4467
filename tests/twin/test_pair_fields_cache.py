"""The field cache of :class:`gearcontact.ltca.lte_pairs.PairFields`: two different
fields are never shared (issue 27; the same key that collided in ``row_law``,
tests/ltca/test_row_law_cache.py).

A pair's field is the separation of its flanks posed as they stand, along the normal
lines of the tangent plane at its *centre* state (``center_index``): its own state, or
for a posed-field row (``pc.edge``) the nearest interior state of its path. Pairs at the
pitch ends share path indices, so a posed-field row and a row on its own state can have
one path index and different fields. The cache (and the frames, posed points, bending
factors and touch searches kept beside it) was keyed by the path index alone; it is
keyed by :attr:`~gearcontact.ltca.lte_pairs.PairContact.field_key` now.

The case is constructed on the real s0003-centred flanks of the twin tests' session
fixture (drive, 31 phases): a surface row of one phase, and a posed-field row at the same
path index centred on the next state of its path. Within one ``PairFields``
``phase_contacts`` derives a contact's centre from its path index alone, so no shipped
pair builds this case (docs/twin.md: measured, no path index carries two centres on
s0003 coast, F.2 or MITER_PAIR); the test guards the key.

Truth: each row's field (gap, off-flank mask, grid, lever, frame, posed point) from a
``PairFields`` shared by both rows is the field the row gets from a ``PairFields`` of its
own, exactly (the same computation, no arithmetic between). On the old key (the path
index alone) the test failed in both orders: the second row asked got the first row's
field.
"""

from dataclasses import replace

import numpy as np
import pytest

from gearcontact.ltca.lte_pairs import phase_contacts
from table_fields import table_fields

from .conftest import TORQUE_NM

PHASE = 10


@pytest.fixture(scope="module")
def two_rows(s0003_twin):
    """``(new PairFields, surface row, posed row)``: the two rows at one path index."""
    pair, tca, flanks, mesh = s0003_twin
    tf = table_fields(pair, tca, flanks, mesh.side, TORQUE_NM)

    def fresh():
        return table_fields(pair, tca, flanks, mesh.side, TORQUE_NM).fields

    contacts = phase_contacts(tf.pinion, tf.gear, tf.kin, tf.cycle, PHASE, tf.base,
                              tf.e_prime, {}, round(0.5 * tf.cycle.step_index))
    surface = next(pc for pc in contacts if not pc.edge and pc.opening_arcsec == 0.0)
    posed = replace(surface, center_index=surface.path_index + 1, opening_arcsec=np.nan)
    assert posed.edge and posed.path_index == surface.path_index
    return fresh, surface, posed


def _field_of(fields, pc) -> tuple:
    gap, grid, off, lever = fields.get(pc)
    origin, frame = fields.frames[pc.field_key]
    mp = fields.points[pc.field_key]
    return (gap, off, grid.x_mm, grid.y_mm, np.array([lever]), origin, frame,
            np.concatenate([mp.point_mm, mp.normal, [mp.phi1_rad, mp.phi2_rad]]))


@pytest.mark.parametrize("posed_first", [True, False])
def test_rows_at_one_path_index_keep_their_own_field(two_rows, posed_first):
    fresh, surface, posed = two_rows
    rows = {"surface": surface, "posed": posed}
    own = {name: _field_of(fresh(), pc) for name, pc in rows.items()}
    # the two fields differ: different centre states, posed differently
    assert not np.array_equal(own["surface"][0], own["posed"][0])
    shared = fresh()
    for name in (("posed", "surface") if posed_first else ("surface", "posed")):
        got = _field_of(shared, rows[name])
        for a, b in zip(got, own[name]):
            assert np.array_equal(a, b)
