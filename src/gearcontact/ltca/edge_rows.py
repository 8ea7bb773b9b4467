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
An edge row whose field lies wholly off the flank (no flank cell: its touch on the flank
region's border) takes :func:`.off_flank.touch_law`, the twin's law of those rows; a
posed-field row (``pc.edge``) takes, as those, a corner's continuation below its
calibration where its LCP says it is one (:func:`.off_flank.corner_law`; docs/twin.md
"below the calibration, the corner's law").
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .edge_law import (EdgeCompliance, edge_compliance, ellipse_leaves_flank, operating_scales,
                       trim_compliance)
from .lte_pairs import PairContact, PairFields
from .lte_phase import preview_balance
from .off_flank import corner_law, is_wholly_off, touch_law

__all__ = ["is_edge_row", "is_cut", "row_law", "preview_edge_balance"]


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
    once per row (``cache``, shared by the callers' phases, keyed by the path index and
    the field's centre: a posed-field row and a row on its own state can share a path
    index, pairs at the pitch ends do, and their laws differ); of an edge row
    whose field lies wholly off the flank, :func:`.off_flank.touch_law` at its touch
    (not cached: such rows share their nearest interior state's path index, not their
    touch); None where the calibration fails (the contact keeps Hertz). The law's scale at a load is
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
        :attr:`~.lte_pairs.PairContact.field_key` ``(path index, centre index)`` ->
        EdgeCompliance or None.
    """
    if is_edge_row(fields, pc) and is_wholly_off(fields, pc):
        return touch_law(fields, pc, materials=materials, torque_nmm=torque_nmm)
    key = pc.field_key
    if key not in cache:
        law = edge_compliance if is_edge_row(fields, pc) else trim_compliance
        try:
            out = law(fields, pc, materials=materials, torque_nmm=torque_nmm)
        except ArithmeticError:     # no founded calibration: Hertz
            out = None
        cache[key] = corner_law(out) if out is not None and pc.edge else out
    return cache[key]


def preview_edge_balance(contacts, fields: PairFields, torque_nmm: float, *, materials,
                         cache: dict | None, bending_mm_per_n=None):
    """:func:`.lte_phase.preview_balance` of the contacts with the edge law (this module):
    every loaded contact whose patch a flank boundary cuts takes its LCP calibration's
    compliance scale ``c`` at the load it carries (``kappa -> c kappa``;
    :func:`.edge_law.operating_scales`, the twin's law). Only a contact that carries load
    needs its law, and a softer contact moves load onto the others, so the balance is
    solved again until every loaded contact has been looked at (each once).

    Parameters
    ----------
    contacts : list of PairContact
        The preview's contacts of one phase.
    fields : PairFields
        Their fields (the calibration's, sized at ``torque_nmm``).
    torque_nmm : float
        Gear torque, N·mm.
    materials : (Material, Material)
    cache : dict or None
        The calibrations of :func:`row_law`, shared over the phases;
        None: the untruncated Hertz law at every contact (``c = 1``).
    bending_mm_per_n : array_like or None
        Tooth-bending compliance of each contact in series with its contact law
        (:func:`.lte_phase.preview_balance`); None: rigid teeth. The scales are taken at
        the loads of the rigid balance (:func:`.edge_law.operating_scales`, the twin's).

    Returns
    -------
    (contacts, scales, theta_rad, loads_n)
        The contacts with their scaled ``kappa_mm_per_n23``, ``c`` of each (ndarray),
        and :func:`.lte_phase.preview_balance` of them.
    """
    n = len(contacts)
    lever = np.array([pc.lever_mm for pc in contacts], float)
    opening = np.array([pc.offset_mm for pc in contacts], float)
    kappa = np.array([pc.kappa_mm_per_n23 for pc in contacts], float)
    laws = np.full((n, 1), None, dtype=object)
    scales = np.ones(n)
    seen = np.zeros(n, bool)
    while True:
        theta, loads = preview_balance(lever, opening, scales * kappa, torque_nmm,
                                       bending_mm_per_n=bending_mm_per_n)
        new = np.flatnonzero((loads > 0.0) & ~seen)
        if cache is None or new.size == 0:
            break
        seen[new] = True
        for i in new:
            if is_cut(fields, contacts[i], torque_nmm=torque_nmm):
                laws[i, 0] = row_law(fields, contacts[i], materials=materials,
                                     torque_nmm=torque_nmm, cache=cache)
        scales = operating_scales(laws, lever[:, None], opening[:, None], kappa[:, None],
                                  np.ones((n, 1), bool), torque_nmm=torque_nmm)[0][:, 0]
    scaled = [replace(pc, kappa_mm_per_n23=c * pc.kappa_mm_per_n23) if c != 1.0 else pc
              for pc, c in zip(contacts, scales)]
    return scaled, scales, theta, loads
