"""TCA of a pinion with a Toprem (geometry.kinked, tca.edge_contact) against first-order
geometry.

A relief ``eps`` (mm, along the pinion flank's outward normal, < 0 into the tooth) at
the point where the smooth pinion touches the gear lets the gear turn by
``d phi2 = -eps / ((w2 x X) . n)`` (``n`` the common normal, ``w2`` the gear axis) at a
held pinion phase, so ``d TE0 = d phi2`` (arcsec) to first order in ``eps``: the
touching point moves only to second order (the contact is an extreme of the
approach). Exact where the relief is rigidly carried by the same touching point - an
edge of the gear (its tip) touching the relieved pinion - and zero where the contact
lies above the kink (the same flank). Between the two the pinion's kink ridge carries
the contact (``"pinion toprem"`` edge contacts) with TE0 continuous. ISO 23509 F.2 pair
cut from machine settings (examples/machine_settings), Toprem 0.25 deg from 2.25 mm on
both pinion blades: the kink at u = 2.36 mm, below the mean point (u = 2.54 mm; the
TE0 reference and the pinion's mounting are those of the smooth pair).
"""

import dataclasses

import numpy as np
import pytest

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.stencil import hardware_stencil
from gearcontact.tca.types import ARCSEC_PER_RAD

EXAMPLE = "examples/machine_settings/iso23509_f2_machine.toml"


def _toprem(pair, delta_deg, depth_mm):
    return dataclasses.replace(pair, machine=tuple(
        dataclasses.replace(s, blade=dataclasses.replace(
            s.blade, toprem_angle_deg=delta_deg, toprem_depth_mm=depth_mm))
        if s.member == "pinion" else s for s in pair.machine))


@pytest.mark.slow
def test_toprem_te0_at_the_kink_and_beyond():
    # ~20 s: two flank sets (60 x 80 nodes) and their TCA
    base = load_pair(EXAMPLE)
    runs = []
    for pair in (base, _toprem(base, 0.25, 2.25)):
        flanks = build_flanks(pair, n_u=60, n_v=80)
        runs.append((flanks, analyze_pair(pair, flanks=flanks)[0]))
    (fb, rb), (ft, rt) = runs
    side = base.design_side
    smooth, kinked = fb.flank("pinion", side), ft.flank("pinion", side)
    pa, pb = rb.cycle.path, rt.cycle.path
    assert np.array_equal(pa.phi1_rad, pb.phi1_rad)
    above, tip, ridge = [], [], []
    for a, b in zip(pa.points, pb.points):
        if a.edge or b.edge:
            continue
        u_k = float(kinked.kinks[0].u(a.v1))
        ea, eb = (f.evaluate(np.array([a.u1]), np.array([a.v1])) for f in (kinked, smooth))
        eps = float((ea.r[0] - eb.r[0]) @ eb.n[0])
        lever = float(np.cross([0.0, 0.0, 1.0], a.point_mm) @ a.normal)
        want = -eps / lever * ARCSEC_PER_RAD
        got = b.te0_arcsec - a.te0_arcsec
        if a.u1 > u_k + 0.05 and not a.edge_contact:
            above.append(got)
        elif a.edge_contact == b.edge_contact == "gear tip":
            tip.append((got, want))
        if b.edge_contact == "pinion toprem":
            ridge.append((got, b, float(kinked.kinks[0].u(b.v1))))
    # above the kink: the smooth pair's TE0 (the same main piece; its node grid spans the
    # Toprem segment's box: interpolation), measured < 1e-4 arcsec, 1e-3 asserted
    assert len(above) > 50 and np.max(np.abs(above)) < 1e-3
    # gear tip on the relieved pinion (eps 4.3 um): measured 0.1 to 0.2 % of 14 arcsec
    # (second order in eps and in the 0.25 deg slope), 1 % asserted
    tip = np.array(tip)
    assert len(tip) > 10 and np.all(tip[:, 1] > 10.0)
    assert np.all(np.abs(tip[:, 0] - tip[:, 1]) <= 0.01 * tip[:, 1])
    # between: the ridge touches (its pinion point on the kink line), TE0 continuous
    # from the last surface phase above the kink (first ridge phase 0.03 arcsec)
    assert len(ridge) >= 5
    assert all(abs(mp.u1 - u_k) < 1e-9 for _, mp, u_k in ridge)
    assert abs(ridge[0][0]) < 0.1
    # the preview's stencil at a ridge contact straddles the kink and says so
    mp = ridge[len(ridge) // 2][1]
    sten = hardware_stencil(ft.flank("pinion", side), ft.flank("gear", side),
                            base.kinematics(), mp, off_flank="continuation")
    assert sten.kinks == ("pinion toprem",)
    assert hardware_stencil(fb.flank("pinion", side), fb.flank("gear", side),
                            base.kinematics(), mp, off_flank="continuation").kinks == ()


def test_stencil_and_edges_see_the_kink_of_a_formate_gear():
    # the formate gear's Toprem kink lies at u = 2 mm (its depth, tests/geometry/
    # test_kinked.py): intersections on both sides are reported, on one side not; the
    # kink is a candidate edge whose points lie on the kink line
    from gearcontact.geometry.kinked import machine_flank
    from gearcontact.tca.edge_contact import edge_parameters, edge_span, flank_edges, is_kink
    from gearcontact.tca.stencil import _kinks_crossed

    pair = load_pair(EXAMPLE)
    setup = next(s for s in pair.machine if (s.member, s.side) == ("gear", "drive"))
    setup = dataclasses.replace(setup, blade=dataclasses.replace(
        setup.blade, toprem_angle_deg=2.0, toprem_depth_mm=2.0))
    gear = machine_flank(setup, pair.blank, face_width_mm=pair.gear_face_width_mm)
    v = 0.5 * sum(gear.v_range)
    assert _kinks_crossed(gear, np.array([[1.9, v], [2.1, v], [np.nan, np.nan]])) == ["toprem"]
    assert _kinks_crossed(gear, np.array([[2.1, v], [3.0, v]])) == []
    labels = [e.label for e in flank_edges(gear, gear)]
    assert labels[-2:] == ["pinion toprem", "gear toprem"] and is_kink(gear, "toprem")
    assert edge_span(gear, "toprem") == gear.v_range
    assert edge_parameters(gear, "toprem", v) == pytest.approx((2.0, v), abs=1e-12)
