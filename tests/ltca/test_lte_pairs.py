"""Potential contacts of the loaded TE at a phase whose transmitting contact is an edge
touching the other flank (tca.edge_contact)."""

import numpy as np

from gearcontact.ltca.lte_pairs import phase_contacts
from gearcontact.geometry.pair import load_pair
from gearcontact.materials import effective_modulus_mpa
from gearcontact.preview.hertz.reference import ENVELOPE
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.curvature import relative_curvature


def test_edge_contact_phase_takes_the_nearest_surface_curvature():
    """On the calibrated s0003 (coast, 31 phases) one phase is a pinion-tip edge on the
    gear flank. Across a sharp edge the relative curvature is unbounded; before this
    rule the surface formula at the edge point gave B- = 5.9e-5 1/mm (outside the
    preview envelope) and a +38 arcsec one-phase spike of TE_pre. The preview law now
    takes the curvature of the nearest surface-to-surface point of the same path,
    exactly, and stays inside the envelope."""
    pair = load_pair("s0003")
    tca, flanks = analyze_pair(pair, side="coast", phases=31)
    cycle, kin = tca.cycle, pair.kinematics()
    edge = [k for k, mp in enumerate(cycle.contact) if mp.edge_contact]
    assert edge, "the calibrated preset has an edge-contact phase at 31 phases"
    pinion, gear = flanks.flank("pinion", "coast"), flanks.flank("gear", "coast")
    base = int(np.argmin(np.abs(cycle.path.phi1_rad - cycle.phi1_rad[0])))
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    path = cycle.path
    surface = np.flatnonzero([not (p.edge or p.edge_contact) for p in path.points])
    checked = 0
    for k in edge:
        for pc in phase_contacts(pinion, gear, kin, cycle, k, base, e_prime, {},
                                 round(0.5 * cycle.step_index)):
            if not path.points[pc.center_index].edge_contact:
                continue
            near = surface[np.argmin(np.abs(surface - pc.center_index))]
            rc = relative_curvature(pinion, gear, kin, path.points[near])
            assert (pc.A_minus_per_mm, pc.B_minus_per_mm) == (rc.A_minus_per_mm,
                                                              rc.B_minus_per_mm)
            lo, hi = ENVELOPE["curvature_per_mm"]
            assert lo <= pc.B_minus_per_mm <= hi and lo <= pc.A_minus_per_mm <= hi
            checked += 1
    assert checked >= 1
