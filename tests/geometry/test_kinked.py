"""Flanks of relieved blades (geometry.kinked) against independent truths.

(a) formate gear: the flank is the cutter surface itself, so the kink lies at
    ``u = toprem_depth_mm`` exactly (``u`` = depth behind the blade tip plane) and the
    profile in the cutter's axial plane makes the blade angle with the cutter axis above
    the kink and the blade angle - relief below it (cone geometry);
(b) a relief angle of 0 cuts today's flank bit for bit;
(c) generated pinion: to first order in the tool's normal displacement the envelope
    moves by the displacement at the generating point (Litvin & Fuentes 2004, sec. 6.1),
    so the relief along the profile is ``t tan(delta)``, ``t`` the blade arc from the
    kink of the smooth flank's generating point (blade arcs from the exact envelope
    solver, geometry.generated.EnvelopeSolver: a different code path from the kink
    search, which compares positions only);
(d) the pieces meet on the kink line (position continuous, normals apart);
(e) the preview stencil reports a window across the kink (tca.stencil).
ISO 23509 F.2 spiral bevel pair cut from machine settings (tests/data/toprem).
"""

import dataclasses
import math

import numpy as np
import pytest

from gearcontact.geometry.blade import blade_segments
from gearcontact.geometry.generated import EnvelopeSolver
from gearcontact.geometry.kinked import KinkedFlank, kinked_flank, machine_flank
from gearcontact.geometry.pair import load_pair

EXAMPLE = "examples/machine_settings/iso23509_f2_machine.toml"
DELTA_DEG, DEPTH_MM = 2.0, 2.0


@pytest.fixture(scope="module")
def pair():
    return load_pair(EXAMPLE)


def _setup(pair, member, side, **blade):
    s = next(s for s in pair.machine if (s.member, s.side) == (member, side))
    return dataclasses.replace(s, blade=dataclasses.replace(s.blade, **blade))


def _relieved(setup, **kw):
    return dataclasses.replace(setup, blade=dataclasses.replace(
        setup.blade, toprem_angle_deg=DELTA_DEG, toprem_depth_mm=DEPTH_MM, **kw))


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_formate_kink_at_the_depth_with_the_blade_slopes(pair, side):
    flank = machine_flank(_relieved(_setup(pair, "gear", side)), pair.blank,
                          face_width_mm=pair.gear_face_width_mm)
    assert isinstance(flank, KinkedFlank) and flank.names == ("toprem", "main")
    # bisection of the positions to rounding: 1e-12 mm (measured ~1e-15)
    np.testing.assert_allclose(flank.kinks[0].u_nodes, DEPTH_MM, atol=1e-12)
    axis = flank.main.blade.placement.axis
    v = np.linspace(*flank.v_range, 5)
    for u, want in ((0.5 * (flank.u_range[0] + DEPTH_MM), 20.0 - DELTA_DEG),
                    (0.5 * (DEPTH_MM + flank.u_range[1]), 20.0)):
        s = flank.evaluate(np.full_like(v, u), v)
        r_u = s.r_u / np.linalg.norm(s.r_u, axis=-1, keepdims=True)
        # the profile direction against the cutter axis: the blade (segment) angle, 1e-12 deg
        np.testing.assert_allclose(np.degrees(np.arccos(np.abs(r_u @ axis))), want, atol=1e-12)
    # continuous on the kink line, with the blade point's blade angle (same v), 1e-12 mm
    a, b = (p.evaluate(np.full_like(v, DEPTH_MM), sc * v)
            for p, sc in zip(flank.pieces, flank.v_scales))
    assert np.max(np.abs(a.r - b.r)) < 1e-12
    jump = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", a.n, b.n), -1.0, 1.0)))
    np.testing.assert_allclose(jump, DELTA_DEG, atol=1e-9)
    # the fillet the edge round cuts (tangent to the Toprem segment) meets the flank's
    # root line in the flank's own v (geometry.fillet, as for a smooth blade): 1e-12 mm
    from gearcontact.geometry.fillet import formate_fillet

    fillet = formate_fillet(flank.pieces[0], edge_radius_mm=0.4)
    top = fillet.evaluate(np.full_like(v, fillet.u_range[1]), v).r
    assert np.max(np.abs(top - flank.evaluate(np.full_like(v, flank.u_range[0]), v).r)) < 1e-12


def test_zero_relief_cuts_todays_flank_bit_for_bit(pair):
    for member, side, fw in (("gear", "drive", pair.gear_face_width_mm),
                             ("pinion", "coast", pair.pinion_face_width_mm)):
        plain = _setup(pair, member, side)
        zero = dataclasses.replace(plain, blade=dataclasses.replace(
            plain.blade, toprem_angle_deg=0.0, toprem_depth_mm=DEPTH_MM, flankrem_depth_mm=5.0))
        a, b = (machine_flank(s, pair.blank, face_width_mm=fw, n_u=12, n_v=14)
                for s in (plain, zero))
        assert type(a) is type(b) and not isinstance(b, KinkedFlank)
        u = np.linspace(*a.u_range, 7)[:, None]
        v = np.linspace(*a.v_range, 9)[None, :]
        ea, eb = a.evaluate(u, v), b.evaluate(u, v)
        for f in ("r", "r_u", "r_v", "r_uu", "r_uv", "r_vv", "n"):
            assert np.array_equal(getattr(ea, f), getattr(eb, f))


@pytest.fixture(scope="module")
def pinions(pair):
    """Pinion drive flanks of a straight blade (no profile crowning: the relief is then
    the only difference) without and with a Toprem."""
    plain = _setup(pair, "pinion", "drive", profile_radius_mm=0.0, profile_reference_mm=0.0)
    kw = dict(face_width_mm=pair.pinion_face_width_mm, n_u=24, n_v=30)
    return (plain, machine_flank(plain, pair.blank, **kw),
            machine_flank(_relieved(plain), pair.blank, **kw))


def test_generated_relief_grows_as_t_tan_delta_below_the_kink(pair, pinions):
    plain, smooth, kinked = pinions
    v = 0.5 * sum(kinked.v_range)
    u_k = float(kinked.kinks[0].u(v))
    assert kinked.u_range[0] < u_k < kinked.u_range[1]     # the kink is on the flank
    us = np.linspace(kinked.u_range[0], u_k - 0.2, 7)
    a = kinked.evaluate(us, np.full_like(us, v))
    b = smooth.evaluate(us, np.full_like(us, v))
    relief = np.einsum("ij,ij->i", a.r - b.r, b.n)            # < 0: into the tooth
    solver = EnvelopeSolver(plain, pair.blank, smooth.cone)
    q = solver.initial_guess(float(us[-1]), v)
    arcs = []
    for u in us[::-1]:
        q = solver.solve(u, v, q).q
        arcs.append(q[0])
    t = blade_segments(_relieved(plain).blade)[1].own_arc_mm - np.array(arcs[::-1])
    want = -t * math.tan(math.radians(DELTA_DEG))
    # first order: the neglected terms are O(delta) relative (delta = 0.035 rad);
    # measured 2.5 to 6.6 % of a relief of 4 to 40 um; 10 % + 0.2 um asserted
    assert np.all(np.abs(relief - want) <= 0.10 * np.abs(want) + 2e-4), (relief, want)
    # above the kink the flank is the smooth one; its nodes span the Toprem segment's
    # box (root lower than the smooth flank's), so the two splines differ by their
    # interpolation error: measured 1.3e-6 mm (24 x 30 nodes), 1e-5 mm asserted
    up = np.linspace(u_k + 0.01, kinked.u_range[1], 5)
    a = kinked.evaluate(up, np.full_like(up, v))
    b = smooth.evaluate(up, np.full_like(up, v))
    assert np.max(np.abs(a.r - b.r)) < 1e-5


def test_generated_kink_line_pieces_meet_and_interpolate(pinions):
    _, _, kinked = pinions
    v = np.linspace(*kinked.v_range, 11)
    u = kinked.kinks[0].u(v)
    a, b = (p.evaluate(u, v) for p in kinked.pieces)
    # the pieces intersect on the kink line: bisection to rounding, 1e-9 mm (measured 5e-15)
    assert np.max(np.linalg.norm(a.r - b.r, axis=-1)) < 1e-9
    # a tangent-plane jump, but not the blade's 2 deg: each side's normal is its own
    # generating blade normal at its own roll (as two involutes a rack and its relief
    # generate cross at a profile angle that differs from the rack's away from the pitch
    # circle); measured 2.26 to 2.57 deg toe to heel, [delta, 1.5 delta] asserted
    jump = np.degrees(np.arccos(np.einsum("ij,ij->i", a.n, b.n)))
    assert np.all((jump > DELTA_DEG) & (jump < 1.5 * DELTA_DEG)), jump
    # the kink line between its 41 nodes against one solved on 161: measured 5e-8 mm
    fine = kinked_flank(kinked.pieces, kinked.names, n_nodes=161)
    vv = np.linspace(*kinked.v_range, 400)
    assert np.max(np.abs(fine.kinks[0].u(vv) - kinked.kinks[0].u(vv))) < 1e-6
    # each side evaluates its own piece (one-sided curvature at the kink)
    assert list(kinked.piece_index(u - 1e-6, v)) == [0] * 11
    assert list(kinked.piece_index(u + 1e-6, v)) == [1] * 11
    assert kinked.kink_name(float(u[5]) - 0.1, float(u[5]) + 0.1, float(v[5])) == "toprem"
    assert kinked.kink_name(float(u[5]) + 0.1, float(u[5]) + 0.2, float(v[5])) is None


@pytest.mark.slow
def test_left_hand_pair_is_relieved_like_its_twin(pair):
    # ~30 s: two left-hand flank sets (the right-hand twins cut and mirrored piece by
    # piece, geometry.flank.each_piece). Toprem on every blade (gear 1 deg from 1.5 mm,
    # pinion 1 deg from 2 mm): above the kink the smooth left-hand flank (normal offset;
    # formate gear: the same cone, its v the Toprem cone's, so a point 9 um along it:
    # 1e-6 mm; generated pinion: the two 20 x 24 splines' interpolation, measured 2e-6 mm,
    # 1e-5 asserted), below it a relief into the tooth (measured 5.5 to 8 um 0.3 mm below
    # the kink; > 3 um asserted)
    from gearcontact.geometry.flank import build_flanks

    rel = dataclasses.replace(pair, machine=tuple(dataclasses.replace(s, blade=dataclasses.replace(
        s.blade, toprem_angle_deg=1.0, toprem_depth_mm=1.5 if s.member == "gear" else 2.0))
        for s in pair.machine))
    base, kinked = (build_flanks(dataclasses.replace(p, pinion_hand="left"), n_u=20, n_v=24)
                    for p in (pair, rel))
    for member in ("gear", "pinion"):
        for side in ("drive", "coast"):
            a, b = base.flank(member, side), kinked.flank(member, side)
            assert isinstance(b, KinkedFlank)
            v = np.linspace(*b.v_range, 6)
            u_k = b.kinks[0].u(v)
            ea, eb = a.evaluate(u_k + 0.3, v), b.evaluate(u_k + 0.3, v)
            off = np.einsum("ij,ij->i", eb.r - ea.r, ea.n)
            assert np.max(np.abs(off)) < (1e-6 if member == "gear" else 1e-5)
            ea, eb = a.evaluate(u_k - 0.3, v), b.evaluate(u_k - 0.3, v)
            assert np.all(np.einsum("ij,ij->i", eb.r - ea.r, ea.n) < -3e-3)


def test_a_kink_beyond_the_flank_leaves_the_main_piece(pair):
    # a Flankrem from 20 mm, above the gear's tip (u_tip = 7.2 mm): no kink on the flank,
    # every point on the main piece (bit for bit), no kink edge for TCA
    from gearcontact.tca.edge_contact import FLANK_EDGES, flank_edges

    flank = machine_flank(_setup(pair, "gear", "coast", flankrem_angle_deg=2.0,
                                 flankrem_depth_mm=20.0),
                          pair.blank, face_width_mm=pair.gear_face_width_mm)
    assert np.all(flank.kinks[0].u_nodes == np.inf)
    u = np.linspace(*flank.u_range, 6)[:, None]
    v = np.linspace(*flank.v_range, 7)[None, :]
    assert np.all(flank.piece_index(u, v) == 0)
    assert np.array_equal(flank.evaluate(u, v).r, flank.main.evaluate(u, v).r)
    assert flank_edges(flank, flank) == FLANK_EDGES


def test_an_easeoff_on_a_kinked_flank_is_refused(pair):
    # geometry.easeoff.apply_easeoff resamples the eased flank on one node grid: on a
    # KinkedFlank that would round the kink off; refused before any work (the commands
    # that would reach it refuse the relieved pair earlier, naming the blade key:
    # tests/cli/test_design.py, tests/cli/test_sweep.py)
    from gearcontact.geometry.easeoff import EaseOff, apply_easeoff
    from gearcontact.geometry.pair import EaseOffCoefficients
    from gearcontact.validation import InputRangeError

    flank = machine_flank(_relieved(_setup(pair, "gear", "drive")), pair.blank,
                          face_width_mm=pair.gear_face_width_mm)
    eo = EaseOff.from_coefficients(EaseOffCoefficients(lengthwise_crowning_um_per_mm2=0.1),
                                   u_mean_mm=4.0, v_mean_mm=0.0)
    with pytest.raises(InputRangeError, match="relieved blade would smooth its kink"):
        apply_easeoff(flank, eo, limit_um=100.0)
