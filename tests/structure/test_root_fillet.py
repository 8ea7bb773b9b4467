"""The real root of a cut tooth (structure.root_fillet) against independent truths.

ISO 23509 F.2 machine-settings pair (examples/machine_settings, edge radius 0.4 mm):

(a) default suite, geometry only (formate gear, ~15 s of flanks): the ISO 6336-3
    critical section (30 deg tangent) of the tooth model lies on the cutter's fillet
    where the fillet's own normal (geometry.fillet) is at 30 deg from the tooth's
    thickness direction, found here by Brent's method on the fillet parameter (the
    structure finds it from central differences of its side curve through its piece
    map); and within r_e sin(delta) of the torus point whose profile angle is 30 deg in
    the cutter's axial plane (the ISO construction in the tool's section; delta the
    angle between the tooth's centre line and the cutter axis);
(b) slow (3D FE, minutes): the tooth on its real root against the tooth on the
    quarter-ellipse root of structure.rim at the mean point: the sign and magnitude of
    the compliance change against a Timoshenko beam over the section profiles, and the
    change's convergence under mesh refinement.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcontact.geometry.fillet import formate_fillet
from gearcontact.geometry.generated import formate_gear_flank
from gearcontact.geometry.pair import load_pair
from gearcontact.structure.root_fillet import fillet_root
from gearcontact.structure.tooth import tooth_geometry
from gearcontact.validation import InputRangeError

PAIR = "examples/machine_settings/iso23509_f2_machine.toml"
XI = np.array([-0.8, 0.0, 0.8])


@pytest.fixture(scope="module")
def gear_root():
    pair = load_pair(PAIR)
    setups = {(s.member, s.side): s for s in pair.machine}
    flanks = {s: formate_gear_flank(setups["gear", s], pair.blank,
                                    gear_face_width_mm=pair.gear_face_width_mm)
              for s in ("drive", "coast")}
    fillets = {s: formate_fillet(f, edge_radius_mm=setups["gear", s].blade.edge_radius_mm)
               for s, f in flanks.items()}
    flank_set = SimpleNamespace(blank=pair.blank, flank=lambda member, side: flanks[side])
    tooth = tooth_geometry(flank_set, "gear", material=pair.gear_material)
    return tooth, fillets, flanks, fillet_root(tooth, fillets)


def _on_fillet(tooth, fillet, side, xi, m, d, deg):
    """The fillet point at ``xi`` whose normal, projected into the plane (d, m), makes
    ``deg`` with m (its tangent ``deg`` with d): Brent on the fillet parameter."""
    v = tooth.flank_parameters(side, np.array([xi]), np.array([-1.0]))[1]
    turn = tooth.coast_turn if side == "coast" else np.eye(3)

    def f(u):
        n = fillet.evaluate(np.array([u]), v).n[0] @ turn.T
        return math.atan2(abs(n @ d), abs(n @ m)) - math.radians(deg)

    u = brentq(f, *fillet.u_range, xtol=1e-13)
    return fillet.evaluate(np.array([u]), v).r[0] @ turn.T


def test_critical_section_lies_at_the_fillets_30_deg_tangent(gear_root):
    tooth, fillets, flanks, root = gear_root
    assert np.all(root.bridge_mm("drive", XI) < 1e-12)      # formate: no bridge
    cs = root.critical_section(XI)
    m, d = root.section_plane(XI)
    for i, x in enumerate(XI):
        for side in ("coast", "drive"):
            exact = _on_fillet(tooth, fillets[side], side, x, m[i], d[i], 30.0)
            # 1e-3 mm: the structure takes the tangent of its side curve (constant v,
            # central differences), this test the tangent of the planar section (normal
            # to the fillet's normal in the plane (d, m)); they differ by the curve's
            # lengthwise drift times the normal's lengthwise component, a product of two
            # small slopes (measured 5.3e-4 mm coast, 1.1e-4 mm drive: ~1e-3 rad on the 0.4 mm
            # round)
            gap = np.linalg.norm(getattr(cs, f"{side}_mm")[i] - exact)
            assert gap < 1e-3
    # the ISO construction in the cutter's axial plane: the round's point whose profile
    # angle is 30 deg (alpha(s) = pi/2 - s/r_e, s = r_e pi/3); the tooth's centre line
    # leans by delta against the cutter axis, which moves each point along its round
    # by at most r_e delta
    r_e = fillets["drive"].edge.radius_mm
    for side in ("coast", "drive"):
        axis = np.asarray(flanks[side].blade.placement.axis)
        delta = np.arccos(np.abs(d @ axis))
        v = tooth.flank_parameters(side, XI, -np.ones_like(XI))[1]
        p = fillets[side].evaluate(np.full_like(XI, r_e * math.pi / 3), v).r
        p = p @ tooth.coast_turn.T if side == "coast" else p
        dist = np.linalg.norm(getattr(cs, f"{side}_mm") - p, axis=1)
        assert np.all(dist <= r_e * delta), (dist, r_e * delta)    # measured 0.01 / 0.017
    # s_Fn of the F.2 gear's tooth (xi = -0.8, 0, 0.8), measured: a regression guard on
    # the section's definition (normal thickness along m), 1e-4 mm
    assert cs.thickness_mm == pytest.approx([6.5439, 7.7327, 8.8049], abs=1e-4)


def test_fillet_root_refuses_a_member_without_a_cutter(gear_root):
    tooth, fillets, _, _ = gear_root
    with pytest.raises(InputRangeError, match="gear coast root fillet"):
        fillet_root(tooth, {"drive": fillets["drive"]})
    with pytest.raises(InputRangeError, match="rim depth_mm"):
        fillet_root(tooth, fillets, depth_mm=0.0)
