"""Tip-edge contact of cylindrical pairs (tca.cylindrical_tip, in tca.cylindrical_cycle)
against the closed-form geometry of a tip circle meeting an involute in the transverse
plane, and the premature contact a tip relief's lag makes at the start of mesh."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcontact.geometry.cylindrical.iso21771 import inv
from gearcontact.geometry.cylindrical.pair import CylindricalPair, ToothModifications
from gearcontact.tca.plane_of_action import PlaneOfAction
from gearcontact.tca.cylindrical_cycle import (CONTACT_TOLERANCE_MM,
                                               cylindrical_mesh_cycle)
from gearcontact.tca.cylindrical_tip import tip_edge_contacts
from gearcontact.tca.parallel_axes import pitch_point_guess
from gearcontact.tca.types import ARCSEC_PER_RAD

from .conftest import spur_23x67

#: The tip-edge touch is solved to 1e-11 mm (~1e-7 arcsec on r_b2 ~ 63 mm) and the
#: closed form's root to 1e-13 mm: 1e-5 arcsec leaves two decades.
TURN_TOL_ARCSEC = 1e-5


def _start_angle(pair, member):
    """θ0 of the cw involute (docs/cylindrical.md sec. 3):
    −(π/2 + 2 x tan α_n)/z − inv α_t."""
    g = pair.geometry
    z, x = getattr(pair, f"{member}_teeth"), getattr(pair, f"profile_shift_{member}")
    return (-(0.5 * math.pi + 2 * x * math.tan(math.radians(g.normal_pressure_angle_deg))) / z
            - inv(math.radians(g.transverse_pressure_angle_deg)))


def _tip_turn_closed_form(pair, member, phi1):
    """Gear turn from the perfect mesh (rad) at which the tip corner of ``member`` lies
    on the mating involute, and the mating roll length there (mm), in the transverse
    plane. The involutes in polar form r -> θ0 + inv(arccos(r_b / r)) (cw flanks,
    docs/cylindrical.md sec. 3), the tip corners at r_a, posed with the pinion turned by
    −φ1 about C1 = (−a_w, 0) and the gear by φ2 + π + π/z2 about O (sec. 5), φ2 the
    perfect mesh φ1/u from the pitch-point phase. The pinion's corner is held: the gear
    involute meets it after a turn equal to the angle between them at its radius
    (explicit). The gear's corner turns with the gear on its tip circle: where that
    circle meets the pinion's involute (the law of cosines, a 1-D root) fixes the turn."""
    g = pair.geometry
    a_w = g.centre_distance_mm
    rb = {m: 0.5 * getattr(g, f"base_diameter_{m}_mm") for m in ("pinion", "gear")}
    ra = {m: 0.5 * getattr(g, f"tip_diameter_{m}_mm") for m in ("pinion", "gear")}
    th0 = {m: _start_angle(pair, m) for m in ("pinion", "gear")}
    start = pitch_point_guess(pair, "cw")
    phi2 = start.phi2_rad + (phi1 - start.phi1_rad) / pair.ratio
    c1 = np.array([-a_w, 0.0])
    turn1, turn2 = -phi1, phi2 + math.pi + math.pi / pair.gear_teeth

    def polar(member_, r):
        return th0[member_] + inv(math.acos(rb[member_] / r))

    if member == "pinion":
        th = polar("pinion", ra["pinion"]) + turn1
        corner = c1 + ra["pinion"] * np.array([math.cos(th), math.sin(th)])
        rho = float(np.linalg.norm(corner))
        delta = math.atan2(corner[1], corner[0]) - (polar("gear", rho) + turn2)
        return (delta + math.pi) % (2 * math.pi) - math.pi, math.sqrt(rho ** 2 - rb["gear"] ** 2)

    def on_pinion(r):
        th = polar("pinion", r) + turn1
        return c1 + r * np.array([math.cos(th), math.sin(th)])

    r = brentq(lambda r: np.linalg.norm(on_pinion(r)) - ra["gear"],
               rb["pinion"] * (1 + 1e-12), ra["pinion"], xtol=1e-13)
    p = on_pinion(r)
    delta = math.atan2(p[1], p[0]) - (polar("gear", ra["gear"]) + turn2)
    return (delta + math.pi) % (2 * math.pi) - math.pi, math.sqrt(r * r - rb["pinion"] ** 2)


@pytest.mark.parametrize("member, beyond", [("gear", "before the path"),
                                            ("pinion", "after the path")])
def test_tip_corner_against_the_closed_form(member, beyond):
    """Unmodified spur flanks at phases up to 0.8 mm of roll beyond either end of the
    path of contact: the gear turn (from the perfect mesh) at which the tip edge touches
    the mating flank, and the touched roll length, equal the closed-form tip circle
    meeting the involute. The gear tip leads in (the driven tooth's tip at the start of
    mesh), the pinion tip trails out; both touch only with the gear lagging (a
    rotation offset against the motion) and the needed lag grows with the distance."""
    pair = spur_23x67()
    mesh = PlaneOfAction(pair, "cw")
    g = pair.geometry
    rb1 = 0.5 * g.base_diameter_pinion_mm
    # pinion phase at which the path ends on the pinion's roll (plane of action: roll
    # r_b1 per rad of pinion turn, from the pitch point's r_w1 sin α_wt)
    u_p = 0.5 * g.working_pitch_diameter_pinion_mm * math.sin(math.radians(
        g.working_pressure_angle_deg))
    rolls = g.roll_lengths_mm("pinion")
    end = rolls["active_start"] if member == "gear" else rolls["tip"]
    phi_end = pitch_point_guess(pair, "cw").phi1_rad + (end - u_p) / rb1
    out = -1.0 if member == "gear" else 1.0
    phis = phi_end + out * np.linspace(0.05, 0.8, 6) / rb1
    tc = tip_edge_contacts(mesh, phis)
    truth = [_tip_turn_closed_form(pair, member, ph) for ph in phis]
    turn_truth = np.array([t for t, _ in truth])
    assert [tc.label(i) for i in range(len(phis))] == [f"{member} tip"] * len(phis)
    np.testing.assert_allclose(tc.turn_rad * ARCSEC_PER_RAD, turn_truth * ARCSEC_PER_RAD,
                               atol=TURN_TOL_ARCSEC)
    other_roll = tc.u1 if member == "gear" else tc.u2
    np.testing.assert_allclose(other_roll, [u for _, u in truth], atol=1e-8)
    assert np.all(turn_truth < 0) and np.all(np.diff(turn_truth) < 0)
    assert np.all(tc.gap_mm > 0)            # a lag closes it: the gap is open
    # the touched normal is the mating involute's: tangent to its base circle, so its
    # moment arm about the mating axis is that base radius (1e-9 relative)
    centre, rb = ((np.zeros(3), 0.5 * g.base_diameter_gear_mm) if member == "pinion"
                  else (np.array([-g.centre_distance_mm, 0.0, 0.0]), rb1))
    arm = np.abs(np.einsum("ni,ni->n", np.cross([0.0, 0.0, 1.0], tc.point_mm - centre),
                           tc.normal))
    np.testing.assert_allclose(arm, rb, rtol=1e-9)


@pytest.mark.parametrize("beta, hand", [(0.0, None), (25.0, "left")])
@pytest.mark.parametrize("facing", ["cw", "ccw"])
def test_unmodified_pairs_have_no_tip_contact(beta, hand, facing):
    """Unmodified, aligned, zero backlash: no tip edge touches before its line (TE0 = 0
    within 1e-3 arcsec, every transmitting contact a line), every tip edge stands open
    or touches at the line's own end (gap >= 0), and the pairs touching are those in the
    zone (no spurious edge contact)."""
    pair = CylindricalPair(name="t", pinion_teeth=23, gear_teeth=67, normal_module_mm=2.0,
                           pinion_face_width_mm=30.0, gear_face_width_mm=30.0,
                           helix_angle_deg=beta, pinion_hand=hand, profile_shift_pinion=0.3,
                           profile_shift_gear=0.1)
    c = cylindrical_mesh_cycle(pair, facing=facing, phases=31)
    assert np.max(np.abs(c.envelope_arcsec)) < 1e-3
    assert not any(mp.edge_contact for mp in c.contact)
    assert np.array_equal(c.pairs_in_contact, c.pairs_in_zone)
    tip = c.tip.gap_mm[np.isfinite(c.tip.gap_mm)]
    assert tip.size > 0 and np.all(tip >= -1e-9)
    live = np.isfinite(c.gap_min_mm)
    assert not c.tip_first[live].any()


def test_tip_relief_lag_makes_premature_contact(spur_tip_relief):
    """The classical premature contact at the start of mesh. A pinion tip relief C_a =
    20 um from u_Ca between the lowest and highest points of single contact leaves the
    pair at the highest point open by C_a ((u - u_Ca)/(u_a1 - u_Ca))^2 (closed form along
    its roll u): the gear lags by that over r_b2. The next pair's gear tip then touches
    the pinion flank before its line enters the zone, wherever the closed-form turn of
    that tip corner (test above) is smaller than the lag: at those phases TE0 is the
    tip corner's closed form (1e-5 arcsec) and the contact is the gear tip; at the
    others TE0 is the relieved line's closed form. The TE0 minimum rises from the
    line-only -C_a(...)^2 / r_b2 at the highest point."""
    t = spur_tip_relief
    pair, c, c_a, u_ca, hi, rolls = t.pair, t.cycle, t.c_a, t.u_ca, t.hi, t.rolls
    p_bt, rb2 = t.p_bt, t.rb2
    tip_phases = [k for k, mp in enumerate(c.contact) if mp.edge_contact]
    assert tip_phases and all(c.contact[k].edge_contact == "gear tip" for k in tip_phases)
    pitch = 2 * math.pi / pair.pinion_teeth
    lags, corners = [], []
    for k, phi1 in enumerate(c.phi1_rad):
        # the lines in the zone: the least relieved (lowest pinion roll) closes first
        u = np.nanmin(c.contact_zu_mm[:, k, 1])
        lags.append(-c_a * (max(u - u_ca, 0.0) / (rolls["tip"] - u_ca)) ** 2 / rb2)
        # the gear tip of each pair without a line in the zone, where it meets the
        # pinion's involute below the start of its line (the entering pair; a lag of
        # less than 0.01 rad)
        turn = -np.inf
        for j in c.pair_offsets:
            if np.isfinite(c.gap_min_mm[c.pair_offsets.index(j), k]):
                continue
            t, u_touch = _tip_turn_closed_form(pair, "gear", phi1 + j * pitch)
            if -0.01 < t < 0.0 and rolls["form"] <= u_touch <= rolls["active_start"] + p_bt:
                turn = max(turn, t)
        corners.append(turn)
    lags, corners = np.array(lags), np.array(corners)
    premature = corners > lags
    assert np.array_equal(np.flatnonzero(premature), tip_phases)
    truth = np.where(premature, corners, lags) * ARCSEC_PER_RAD
    np.testing.assert_allclose(c.envelope_arcsec, truth, atol=TURN_TOL_ARCSEC)
    line_only = c_a * ((hi - u_ca) / (rolls["tip"] - u_ca)) ** 2 / rb2 * ARCSEC_PER_RAD
    assert 0.5 * line_only < c.te0_pp_arcsec < 0.9 * line_only
    assert c.tip.gap_mm[np.isfinite(c.tip.gap_mm)].min() > -CONTACT_TOLERANCE_MM


def test_preview_loads_where_a_tip_edge_alone_touches():
    """Without a loaded TE the preview's pairs touching unloaded share F_n by their line
    lengths (ltca.cylindrical_preview.pair_loads_n). Where a tip edge touches first (the
    relieved spur pair above at 25 phases: the next pair's gear tip at one phase) no
    line is closed; the lines next to close (least opening) carry F_n there. Truths: the
    loads are finite and sum to F_n at every phase (1e-12 relative), and at the tip phase
    only least-open lines carry."""
    from gearcontact.ltca.cylindrical_preview import pair_loads_n
    from gearcontact.tca.cylindrical_stencil import cylindrical_stencils

    g = spur_23x67().geometry
    rolls = g.roll_lengths_mm("pinion")
    u_ca = 0.5 * (rolls["tip"] + rolls["active_start"])      # midway between LPSTC, HPSTC
    rb1 = 0.5 * g.base_diameter_pinion_mm
    pair = spur_23x67(modifications_pinion=ToothModifications(
        tip_relief_um=20.0, tip_relief_start_diameter_mm=2 * math.hypot(u_ca, rb1)))
    c = cylindrical_mesh_cycle(pair, phases=25)
    tip = [k for k, mp in enumerate(c.contact) if mp.edge_contact]
    assert tip
    st = cylindrical_stencils(pair, c)
    w, source = pair_loads_n(st, 1000.0)
    assert source == "line_length" and np.isfinite(w).all()
    np.testing.assert_allclose(w.sum(axis=0), 1000.0, rtol=1e-12)
    for k in tip:
        assert not st.in_contact[:, k].any()
        least = st.opening_mm[st.valid[:, k], k].min()
        assert np.all(st.opening_mm[w[:, k] > 0, k] == least) and least > 0


def test_an_edge_ends_at_its_own_face_end():
    """The EV example (pinion face 32 mm, gear face 30 mm) without its tip reliefs,
    7 phases: the gear's tip edge exists only over the gear's face, |z| <= 15 mm, so
    its points beyond it meet nothing (NaN), where the helicoid's continuation would
    touch the wider pinion's flank; inside it, the same edge touches (the loaded TE's
    edge block carried rows at z = 15.4 and 15.8 mm before, 0.5 % of F_n with bending
    at 400 N·m). Sampled both ways the loaded TE samples an edge: the first-touching
    edge of a pair with no line in the zone (tip_edge_gaps) and the edges beyond the
    lines (beyond_line_edge_gaps); the pinion's tip edge, over its own 32 mm face,
    touches the gear flank only within the gear's face (the other flank's box)."""
    from dataclasses import replace
    from pathlib import Path

    from gearcontact.geometry.pair import load_pair
    from gearcontact.tca.cylindrical_tip import beyond_line_edge_gaps, tip_edge_gaps

    ev = load_pair(Path(__file__).resolve().parents[2] / "examples"
                   / "ev_reducer_helical_23x67.toml", kinds=("cylindrical",))
    pair = replace(ev, modifications_pinion=replace(ev.modifications_pinion, tip_relief_um=0.0),
                   modifications_gear=replace(ev.modifications_gear, tip_relief_um=0.0))
    cycle = cylindrical_mesh_cycle(pair, phases=7)
    poa = PlaneOfAction(pair, cycle.facing)
    half = 0.5 * pair.face_width_mm("gear")
    z = np.linspace(-16.0, 16.0, 81)
    outside = np.abs(z) > half + 1e-9
    first = tip_edge_gaps(poa, cycle, z)
    gear_tip = cycle.tip.labels() == "gear tip"
    assert gear_tip.any()
    got = first.gap_mm[gear_tip]
    assert np.isnan(got[:, outside]).all() and np.isfinite(got[:, ~outside]).any()
    beyond = beyond_line_edge_gaps(poa, cycle, z)
    for edge in beyond:
        assert np.isnan(edge.gap_mm[..., outside]).all()
    assert np.isfinite(beyond[1].gap_mm[..., ~outside]).any()
