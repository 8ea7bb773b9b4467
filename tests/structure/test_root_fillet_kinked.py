"""The FE root (structure.root_fillet) of a tooth cut by a relieved (Toprem) blade.

Truth: a formate gear flank cut by a blade with a Toprem of ``delta`` from the depth
``z_T`` is two blade cones meeting on the circle at ``z_T`` (tests/geometry/
test_kinked.py (a)); below the kink the flank is the Toprem cone, whose generatrix makes
``alpha - delta`` with the cutter axis (``alpha`` = 20 deg, the F.2 gear blades), and
the blade's edge round is tangent to that segment (docs/machine_settings.md sec. 1).
So the root's side curve leaves the flank along the Toprem cone (18 deg to the axis,
not the main cone's 20) and runs on into the fillet without a corner.
ISO 23509 F.2 machine-settings pair (examples/machine_settings, edge radius 0.4 mm).
"""

import dataclasses
from types import SimpleNamespace

import numpy as np

from gearcontact.geometry.fillet import formate_fillet
from gearcontact.geometry.kinked import KinkedFlank, machine_flank
from gearcontact.geometry.pair import load_pair
from gearcontact.structure.root_fillet import fillet_root
from gearcontact.structure.tooth import tooth_geometry

PAIR = "examples/machine_settings/iso23509_f2_machine.toml"
DELTA_DEG, DEPTH_MM, BLADE_DEG = 2.0, 2.0, 20.0


def _angle_deg(a, b):
    return np.degrees(np.arccos(np.clip(np.abs(np.einsum("...i,...i->...", a, b)), 0.0, 1.0)))


def test_root_side_curves_leave_a_relieved_flank_along_its_toprem_piece():
    pair = load_pair(PAIR)
    flanks, fillets = {}, {}
    for s in pair.machine:
        if s.member != "gear":
            continue
        s = dataclasses.replace(s, blade=dataclasses.replace(
            s.blade, toprem_angle_deg=DELTA_DEG, toprem_depth_mm=DEPTH_MM))
        flanks[s.side] = machine_flank(s, pair.blank, face_width_mm=pair.gear_face_width_mm)
        assert isinstance(flanks[s.side], KinkedFlank)
        # the edge round tangent to the tip (Toprem) segment, as geometry.fillet.pair_fillets
        fillets[s.side] = formate_fillet(flanks[s.side].pieces[0],
                                         edge_radius_mm=s.blade.edge_radius_mm)
    flank_set = SimpleNamespace(blank=pair.blank, flank=lambda member, side: flanks[side])
    tooth = tooth_geometry(flank_set, "gear", material=pair.gear_material)
    root = fillet_root(tooth, fillets)
    xi = np.array([-0.8, 0.0, 0.8])
    for side, flank in flanks.items():
        v = tooth.flank_parameters(side, xi, -np.ones_like(xi))[1]
        A, ta, B, tb = root._bridge_ends(side, v)
        axis = flank.main.blade.placement.axis
        # the side curve leaves the flank's root line along the Toprem cone (closed form,
        # 1e-9 deg: the cone's own derivatives), not the main cone
        np.testing.assert_allclose(_angle_deg(ta, axis), BLADE_DEG - DELTA_DEG, atol=1e-9)
        # formate: the fillet's top row is the flank's root line (no bridge, 1e-9 mm) and
        # its tangent there the Toprem cone's (the round is tangent to the tip segment;
        # the fillet's tangent is a 1e-5 mm chord of the 0.4 mm round: 1e-3 deg)
        np.testing.assert_allclose(A, B, rtol=0, atol=1e-9)
        assert _angle_deg(ta, tb).max() <= 1e-3
    # the ISO 30 deg section is found below the root line (on the fillets), not at the
    # kink above it
    section = root.critical_section(xi)
    assert np.all(section.thickness_mm > 0.0) and np.all(section.depth_mm > 0.0), section
