"""Test helper: the mesh table's gap fields of one side of a pair's TCA, built as
``twin.mesh`` builds them (``ltca.lte_pairs.PairFields``: 40 cells, extent (1.6, 2.0)),
with what the row loops need; shared by the loaded-TE edge tests and the twin's reach
tests."""

from types import SimpleNamespace

import numpy as np

from gearcontact.ltca.lte_pairs import PairFields
from gearcontact.materials import effective_modulus_mpa


def table_fields(pair, tca, flanks, side: str, torque_nm: float) -> SimpleNamespace:
    """``cycle``, ``kin``, ``pinion``, ``gear``, ``e_prime`` (MPa), ``fields`` and ``base``
    (the path index of the cycle's first phase) of ``side`` at ``torque_nm`` (N m)."""
    cycle, kin = tca.cycle, pair.kinematics()
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    fields = PairFields(pinion, gear, kin, cycle, torque_nmm=1e3 * torque_nm,
                        e_prime=e_prime, cells=40, extent=(1.6, 2.0))
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    return SimpleNamespace(cycle=cycle, kin=kin, pinion=pinion, gear=gear,
                           e_prime=e_prime, fields=fields, base=base)
