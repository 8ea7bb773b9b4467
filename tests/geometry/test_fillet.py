"""Root fillets cut by the blade's edge round (geometry.fillet) against independent truths.

ISO 23509 F.2 spiral bevel (edge radius 0.4 mm), settings of geometry.basic_settings:

(a) formate gear: every fillet point lies on the torus of the edge round (its centre
    circle written here from the straight blade line and the tip plane, not from
    machine.edge_round), its normal points at the centre circle, the bottom row lies in
    the tip plane (the gear's root plane) and the top row is the flank's root line with
    the flank's normal (tangent-continuous);
(b) generated gear (ratio of roll 1/sin delta2) and crown-gear pinion (tilt 0): each
    fillet point mapped back into the cutter frame at its roll (the inverse of the
    affine cutter -> work map, taken from four forward evaluations) lies on the torus
    and satisfies the equation of meshing with the relative velocity by central
    differences of the forward map; the top row is where the flank's own node
    equations (EnvelopeSolver: sheet position, three unknowns) put the blade arc length
    at the round's tangent point, with the same point and tangent plane; the bottom row
    lies on the blank's root cone (the untilted tip plane, fixed in the machine and
    tangent to the root cone, generates it);
(c) a zero edge radius cuts no fillet: refused naming the key.
"""

import math

import numpy as np
import pytest

from gearcontact.geometry.basic_settings import (crown_pinion_setups, formate_gear_setups,
                                                 generated_gear_setups)
from gearcontact.geometry.fillet import formate_fillet, generated_fillet
from gearcontact.geometry.generated import formate_gear_flank, work_to_body
from gearcontact.geometry.machine import MachineKinematics
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError

PAIR = "examples/iso23509_f2_spiral_bevel.toml"


@pytest.fixture(scope="module")
def pair():
    return load_pair(PAIR)


def _centre_circle(blade):
    """(radius, depth) of the edge round's centre in the cutter's axial half-plane: depth
    r_e behind the tip plane, distance r_e from the straight blade line through the tip
    point (rho_tip, 0) with direction (-sigma sin a, cos a), on the blade's side."""
    a, sig, r_e = math.radians(blade.blade_angle_deg), blade.sigma, blade.edge_radius_mm
    # (c - p0) . (sigma cos a, sin a) = r_e with c = (rho_c, r_e)
    return blade.point_radius_mm + sig * (r_e - r_e * math.sin(a)) / math.cos(a), r_e


def _torus_distance(x_t, n_t, blade):
    """Distance of cutter-frame points to the centre circle, and the angle between the
    normal and the direction from the point to the circle (rad)."""
    rho_c, z_c = _centre_circle(blade)
    rho = np.hypot(x_t[..., 0], x_t[..., 1])
    e = np.stack([x_t[..., 0] / rho, x_t[..., 1] / rho, np.zeros_like(rho)], axis=-1)
    centre = rho_c * e + np.array([0.0, 0.0, -z_c])
    to_c = centre - x_t
    dist = np.linalg.norm(to_c, axis=-1)
    return dist, _angle(to_c, n_t)


def _angle(a, b):
    """Angle between vectors (rad), by atan2 of |a x b| and a . b (exact near 0)."""
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1),
                      np.einsum("...i,...i->...", a, b))


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_formate_fillet_is_the_edge_round_torus(pair, side):
    setup = formate_gear_setups(pair)[side]
    flank = formate_gear_flank(setup, pair.blank, gear_face_width_mm=pair.gear_face_width_mm)
    fillet = formate_fillet(flank, edge_radius_mm=setup.blade.edge_radius_mm)
    U, V = np.meshgrid(np.linspace(*fillet.u_range, 7), np.linspace(*fillet.v_range, 9),
                       indexing="ij")
    f = fillet.evaluate(U, V)
    # the cutter frame of the flank's blade cone: origin at the tip plane's centre
    pl = flank.blade.placement
    frame = np.column_stack([pl.e1, pl.e2, pl.axis])
    origin = pl.centre_mm + flank.dedendum_mm * pl.axis
    x_t, n_t = (f.r - origin) @ frame, f.n @ frame
    dist, angle = _torus_distance(x_t, n_t, setup.blade)
    # 1e-9 mm: rounding of ~100 mm coordinates through two frames (measured ~1e-14)
    assert np.abs(dist - setup.blade.edge_radius_mm).max() < 1e-9
    assert angle.max() < 1e-9
    assert np.abs(x_t[0, :, 2]).max() < 1e-9            # bottom row in the tip plane
    # top row = the flank's root line (u_root = r_e (1 - sin a)), same point and normal
    top = flank.evaluate(np.full(9, flank.u_range[0]), V[-1])
    assert np.abs(f.r[-1] - top.r).max() < 1e-9
    assert np.abs(f.n[-1] - top.n).max() < 1e-9
    assert fillet.width_mm == pytest.approx(
        0.4 * (math.pi / 2 - math.radians(setup.blade.blade_angle_deg)), abs=1e-14)


def _to_cutter(setup, blank, r, n, psi):
    """Body points / normals at roll psi -> cutter frame, inverting the affine map
    x_t -> X_w of MachineKinematics.to_work (tested in test_machine.py) from its values
    at the origin and the unit vectors."""
    kin = MachineKinematics(setup.settings)
    q, t = work_to_body(setup.member, blank)
    x_w, n_w = (r - t) @ q, n @ q
    out_x, out_n = np.empty_like(r), np.empty_like(n)
    for k in np.ndindex(psi.shape):
        basis = np.vstack([np.zeros(3), np.eye(3)])
        img = kin.to_work(basis, np.tile([0.0, 0.0, 1.0], (4, 1)), psi[k])[0]
        m = (img[1:] - img[0]).T
        out_x[k] = np.linalg.solve(m, x_w[k] - img[0])
        out_n[k] = np.linalg.solve(m, n_w[k])      # a rotation: normals map alike
    return out_x, out_n, x_w, n_w


CASES = {"gear": generated_gear_setups, "pinion": crown_pinion_setups}


@pytest.fixture(scope="module", params=sorted(CASES))
def generated(request, pair):
    setup = CASES[request.param](pair)["drive"]
    width = getattr(pair, f"{setup.member}_face_width_mm")
    fillet = generated_fillet(setup, pair.blank, face_width_mm=width, n_s=7, n_v=11)
    U, V = np.meshgrid(np.linspace(*fillet.u_range, 5), np.linspace(*fillet.v_range, 6),
                       indexing="ij")
    return setup, fillet, fillet.evaluate(U, V)


def test_generated_fillet_is_the_envelope_of_the_edge_round(pair, generated):
    setup, fillet, f = generated
    x_t, n_t, x_w, n_w = _to_cutter(setup, pair.blank, f.r, f.n, f.psi_rad)
    dist, angle = _torus_distance(x_t, n_t, setup.blade)
    # on the torus: 1e-9 mm (Newton to 1e-10 on ~100 mm coordinates; measured ~1e-13)
    assert np.abs(dist - setup.blade.edge_radius_mm).max() < 1e-9
    assert angle.max() < 1e-9
    # equation of meshing: n . dX_w/dpsi by central differences (h = 1e-5 rad:
    # truncation |X'''| h^2 / 6 and rounding 1e-16 * 100 mm / h, each ~1e-9..1e-8
    # mm/rad, against |dX_w/dpsi| of 4..16 mm/rad; measured 2e-8 mm/rad, the solver's
    # own residual 1e-10)
    kin, h = MachineKinematics(setup.settings), 1e-5
    up = kin.to_work(x_t, n_t, f.psi_rad + h)[0]
    down = kin.to_work(x_t, n_t, f.psi_rad - h)[0]
    vel = (up - down) / (2 * h)
    meshing = np.einsum("...i,...i->...", n_w, vel)
    assert np.abs(meshing).max() < 1e-7 * np.linalg.norm(vel, axis=-1).max()


def test_generated_fillet_meets_the_flank_and_the_root_cone(pair, generated):
    setup, fillet, f = generated
    solver = fillet.solver
    # top row: the flank's node equations (sheet (u, v) -> blade arc, blade angle, roll)
    # solved at the fillet's top points put the blade arc at the round's tangent point;
    # same point (1e-9 mm) and tangent plane: both are envelopes of the same blade line
    # (round and profile share point and normal there), solved to 1e-10 by two different
    # systems; the normal moves with the point at the flank's curvature (< 1 /mm), so
    # 1e-6 rad holds with margin (measured ~1e-12 rad)
    u, v = solver.sheet_parameters(f.r[-1])
    exact = solver.solve(u, v, np.stack([np.full_like(u, fillet.edge.top_length_mm),
                                         f.theta_rad[-1], f.psi_rad[-1]], axis=-1))
    assert np.abs(exact.l_mm - fillet.edge.top_length_mm).max() < 1e-9
    assert np.abs(exact.x_mm - f.r[-1]).max() < 1e-9
    assert _angle(exact.n, f.n[-1]).max() < 1e-6
    # bottom row: on the blank's root cone (sheet u = 0: uniform depth h_f below the
    # pitch cone, the plane of the untilted blade tips); 1e-9 mm as above
    assert setup.settings.tilt_deg == pytest.approx(0.0, abs=1e-12)
    u0, _ = solver.sheet_parameters(f.r[0])
    assert np.abs(u0).max() < 1e-9


def test_zero_edge_radius_cuts_no_fillet(pair):
    import dataclasses

    setup = formate_gear_setups(pair)["drive"]
    sharp = dataclasses.replace(setup, blade=dataclasses.replace(setup.blade,
                                                                 edge_radius_mm=0.0))
    flank = formate_gear_flank(sharp, pair.blank, gear_face_width_mm=pair.gear_face_width_mm)
    with pytest.raises(InputRangeError, match=r"blade.gear.drive.edge_radius_mm.*> 0"):
        formate_fillet(flank, edge_radius_mm=0.0, where="blade.gear.drive")
    gen = dataclasses.replace(generated_gear_setups(pair)["drive"], blade=sharp.blade)
    with pytest.raises(InputRangeError, match=r"blade.gear.drive.edge_radius_mm"):
        generated_fillet(gen, pair.blank, face_width_mm=pair.gear_face_width_mm)


def test_pair_fillets_of_a_left_hand_pair_meet_its_mirrored_flanks(pair):
    # a left-hand pair's fillets are its right-hand twin's reflected (geometry.mirror):
    # the top row meets the left-hand gear flank (the twin's blade cone in the reflected
    # cutter frame) at its root line with its normal (1e-9, as above); the conjugate
    # pinion has no cutter and gets a reason instead
    import dataclasses
    from types import SimpleNamespace

    from gearcontact.geometry.fillet import pair_fillets
    from gearcontact.geometry.formate import gear_flanks
    from gearcontact.geometry.mirror import mirror_gear_flank, mirror_placement

    right = gear_flanks(pair)[1]
    left = {s: mirror_gear_flank(f, mirror_placement(f.blade.placement))
            for s, f in right.items()}

    def flank_set(gear):
        return SimpleNamespace(gear_generation="formate",
                               flank=lambda m, s: gear[s] if m == "gear" else None)

    lh = dataclasses.replace(pair, pinion_hand="left")
    got, why = pair_fillets(lh, SimpleNamespace(right_hand_twin=flank_set(right)))
    assert set(got) == {("gear", "drive"), ("gear", "coast")}
    assert set(why) == {("pinion", "drive"), ("pinion", "coast")}
    assert all("no cutter" in w for w in why.values())
    for side in ("drive", "coast"):
        f, flank = got["gear", side], left[side]
        v = np.linspace(*flank.v_range, 7)
        top = f.evaluate(np.full(7, f.u_range[1]), v)
        root = flank.evaluate(np.full(7, flank.u_range[0]), v)
        assert np.abs(top.r - root.r).max() < 1e-9
        assert np.abs(top.n - root.n).max() < 1e-9


def test_conjugate_pinion_fillet_is_cut_by_the_complementary_generating_gear(s0003_centred):
    # the conjugate pinion is solved, not cut; on request it gets the fillet of the
    # complementary generating gear (the gear's blade cones rolled in the meshing motion,
    # basic_settings.member_setups), which cuts exactly the conjugate flank: that
    # generating motion's flank, solved at the conjugate sheet's lower box edge and turned
    # as the fillet is, lies on the conjugate sheet (1e-9 mm: two exact solves of the same
    # surface, one through the gear, one through the tool, measured 4e-12 mm; the sheet
    # interpolates its nodes, the box edge is a node row), and the fillet's top row (the
    # same motion's envelope of the round, test_generated_fillet_* above) lies below
    # the box: the strip between is generated flank the sheet does not cover
    from gearcontact.geometry.fillet import pair_fillets

    pair, flanks = s0003_centred
    got, why = pair_fillets(pair, flanks)
    assert ("pinion", "drive") in why and "no cutter" in why["pinion", "drive"]
    got, why = pair_fillets(pair, flanks, conjugate_pinion=True)
    assert not why
    for side in ("drive", "coast"):
        f, conj = got["pinion", side], flanks.pinion_conjugate.side(side)
        assert f.edge.radius_mm == pair.cutter.edge_radius_mm
        v = np.linspace(*conj.v_range, 9)
        u = np.full_like(v, conj.u_range[0])
        s, x = f.solver, np.empty((len(v), 3))
        for order in (range(4, len(v)), range(4, -1, -1)):    # continuation from the middle
            q = s.initial_guess(float(u[4]), float(v[4]))
            for j in order:
                sol = s.solve(u[j], v[j], q)
                q, x[j] = sol.q, sol.x_mm
        gap = np.linalg.norm(s.rotate(x, f.turn_rad) - conj.evaluate(u, v).r, axis=-1)
        assert gap.max() < 1e-9, gap
        top = f.evaluate(np.full_like(v, f.u_range[1]), v)
        assert np.all(conj.locate(top.r)[0] < conj.u_range[0])
