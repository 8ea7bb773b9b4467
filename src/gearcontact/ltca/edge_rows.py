"""Which contacts of the loaded mesh take the LCP-calibrated edge law, and their
LCP calibration: the one selection and calibration that the loaded TE's preview
(``TE_pre``, :mod:`.lte`) and the twin's mesh table (:mod:`gearcontact.twin.mesh`) share
(issue 28; docs/twin.md "Edge contact").

A contact (:class:`.lte_pairs.PairContact`) is *cut* by a flank boundary when

* it is an edge row: its pair's unloaded mating point has left the flanks (``pc.edge``,
  resolved on its posed field) or its TCA point is an edge contact (an edge of one flank
  touching the other, :mod:`gearcontact.tca.edge_contact`), or
* its Hertzian ellipse under the whole torque reaches beyond a flank
  (:func:`.edge_law.ellipse_leaves_flank`).

Its law is then Hertz with the approach scaled by ``c`` (:mod:`.edge_law`:
:func:`~.edge_law.edge_compliance` for an edge row, :func:`~.edge_law.trim_compliance`
for a surface row), ``delta = c kappa W^(2/3)``, ``c`` the calibration's at the load the
contact carries (:func:`~.edge_law.operating_scales`); every other contact keeps
``c = 1``. A calibration whose LCP fails (``ArithmeticError``) keeps Hertz (``c = 1``).
"""

from __future__ import annotations

from dataclasses import replace

from .edge_law import EdgeCompliance, edge_compliance, ellipse_leaves_flank, trim_compliance
from .lte_pairs import PairContact, PairFields

__all__ = ["is_edge_row", "is_cut", "row_law"]


def is_edge_row(fields: PairFields, pc: PairContact) -> bool:
    """The contact is an edge row (module docstring): off its path, or the TCA's edge
    contact."""
    return pc.edge or bool(fields.path.points[pc.path_index].edge_contact)


def is_cut(fields: PairFields, pc: PairContact, *, torque_nmm: float) -> bool:
    """Whether a flank boundary cuts the contact's patch (module docstring); the
    ellipse's test with the pair carrying ``torque_nmm`` (N·mm) alone, posed as it
    stands unloaded."""
    if is_edge_row(fields, pc):
        return True
    pinion, gear, kin = fields.args
    mp = replace(fields.path.points[pc.path_index], phi2_rad=pc.phi2_rad)
    return ellipse_leaves_flank(pinion, gear, kin, mp, pc, torque_nmm=torque_nmm,
                                e_prime_mpa=fields.e_prime)


def row_law(fields: PairFields, pc: PairContact, *, materials, torque_nmm: float,
            cache: dict) -> EdgeCompliance | None:
    """The LCP calibration of a cut contact (module docstring): :func:`~.edge_law.
    edge_compliance` of an edge row, :func:`~.edge_law.trim_compliance` of a surface row,
    once per TCA path index (``cache``, shared by the callers' phases); None where the
    calibration fails (the contact keeps Hertz). The law's scale at a load is
    :meth:`~.edge_law.EdgeCompliance.scale_at` (at the operating loads:
    :func:`~.edge_law.operating_scales`).

    Parameters
    ----------
    fields : PairFields
        The loaded mesh's fields, sized at ``torque_nmm``.
    pc : PairContact
        A contact :func:`is_cut` selected.
    materials : (Material, Material)
        Pinion and gear materials.
    torque_nmm : float
        Gear torque that sets the calibration loads, N·mm.
    cache : dict
        Path index -> EdgeCompliance or None.
    """
    if pc.path_index not in cache:
        law = edge_compliance if is_edge_row(fields, pc) else trim_compliance
        try:
            cache[pc.path_index] = law(fields, pc, materials=materials, torque_nmm=torque_nmm)
        except ArithmeticError:     # no founded calibration: Hertz
            cache[pc.path_index] = None
    return cache[pc.path_index]
