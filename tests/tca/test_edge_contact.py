"""Edge-to-surface contact (tca.edge_contact) against geometric truth on s0003-centred.

Truth 1 (transition): where the surface mating point lies exactly on a flank edge (the
surface system solved with that edge's parameter held at its box limit and the phase
free), that point also solves the edge problem, so the edge contact at that phase must
reproduce its gear angle (TE0) and position: TE0 is continuous across the switch.

Truth 2 (first touch): at the gear angle of an edge contact no point of any flank edge
penetrates the other flank; the signed distance of dense edge samples to the other
surface, found by an independent closest-point projection (scipy least squares, not the
solver's point-on-surface Newton), is >= 0 and 0 at the contact point.
"""

import numpy as np
import pytest
from scipy.optimize import least_squares

from gearcontact.tca.edge_contact import (FLANK_EDGES, edge_parameters, edge_span,
                                          solve_edge_contact)
from gearcontact.tca.mating import solve_mating_point
from gearcontact.tca.types import ARCSEC_PER_RAD, ContactGuess

#: Solver boundary variable of each edge.
_HELD = {"pinion toe": ("v1", 1, 0), "pinion heel": ("v1", 1, 1),
         "pinion root": ("u1", 0, 0), "pinion tip": ("u1", 0, 1),
         "gear toe": ("v2", 3, 0), "gear heel": ("v2", 3, 1),
         "gear root": ("u2", 2, 0), "gear tip": ("u2", 2, 1)}


def _flanks(flanks):
    return flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")


def _transitions(path):
    """(last surface point, first edge point) pairs where the path switches."""
    pts = path.points
    return [(a, b) for a, b in zip(pts, pts[1:]) if not a.edge and not a.edge_contact
            and b.edge_contact] + [(b, a) for a, b in zip(pts, pts[1:])
                                   if not b.edge and not b.edge_contact and a.edge_contact]


def test_nominal_path_switches_to_edge_contact_at_both_ends(full_path):
    """The centred pair's path leaves its flanks at both ends and continues as edge
    contact (at least one switch each way), with finite TE0 at every edge phase."""
    path = full_path
    switches = _transitions(path)
    assert len(switches) >= 2
    edge_pts = [p for p in path.points if p.edge_contact]
    assert edge_pts and all(np.isfinite(p.te0_arcsec) for p in edge_pts)


def test_edge_contact_equals_surface_contact_exactly_on_the_edge(s0003_centred,
                                                                 s0003_drive, full_path):
    """At the phase where the surface mating point lies on the edge, the edge contact
    gives the same gear angle within 1e-4 arcsec and the same point within 1e-6 mm
    (both Newton solves converge to 1e-10 mm; the 1-D Brent search along the edge to
    1e-5 mm, whose error enters phi2 only at second order)."""
    s0003_pair, s0003_flanks = s0003_centred
    pinion, gear = _flanks(s0003_flanks)
    kin = s0003_pair.kinematics()
    for surf, edge in _transitions(full_path):
        var, index, end = _HELD[edge.edge_contact]
        box = (pinion.u_range, pinion.v_range, gear.u_range, gear.v_range)[index]
        x = surf.as_guess().vector()
        x[index] = box[end]
        on_edge = solve_mating_point(pinion, gear, kin, ContactGuess.from_vector(x),
                                     fixed=var)
        ec = solve_edge_contact(pinion, gear, kin, on_edge.phi1_rad, guess=surf.as_guess(),
                                forward=s0003_drive.cycle.envelope_is_max)
        assert ec is not None and ec.edge_contact == edge.edge_contact
        assert abs(ec.phi2_rad - on_edge.phi2_rad) * ARCSEC_PER_RAD < 1e-4
        assert np.linalg.norm(ec.point_mm - on_edge.point_mm) < 1e-6


def _signed_distances(surface, pose, points, normal_sign, uv0):
    """Signed distance of each point to the posed surface (closest point inside the
    surface's box, else NaN), by least squares over (u, v)."""
    rot, t = pose
    out = []
    lo = (surface.u_range[0], surface.v_range[0])
    hi = (surface.u_range[1], surface.v_range[1])
    for x in points:
        fit = least_squares(lambda uv: rot @ surface.point(*uv).r + t - x, uv0,
                            bounds=(lo, hi), xtol=1e-14, ftol=1e-14, gtol=1e-14)
        sp = surface.point(*fit.x)
        on_box_edge = np.any(np.isclose(fit.x, lo, atol=1e-9) | np.isclose(fit.x, hi, atol=1e-9))
        d = normal_sign * float((x - (rot @ sp.r + t)) @ (rot @ sp.n))
        out.append(np.nan if on_box_edge and abs(d) > 1e-3 else d)
    return np.array(out)


def test_no_edge_point_penetrates_at_an_edge_contact(s0003_centred, full_path):
    """At an edge phase a few steps past the switch the flanks are posed at the edge
    contact's angles: dense samples (41 per edge) of all eight edges keep a signed
    distance >= -1e-7 mm to the other flank (no penetration: the contact is the first
    touch; tolerance: projection residual), and the touching point has distance 0
    within 1e-7 mm."""
    s0003_pair, s0003_flanks = s0003_centred
    pinion, gear = _flanks(s0003_flanks)
    kin = s0003_pair.kinematics()
    path = full_path
    k = next(i for i, p in enumerate(path.points) if p.edge_contact
             and i > 0 and not path.points[i - 1].edge_contact
             and not path.points[i - 1].edge) + 2
    mp = path.points[k]
    assert mp.edge_contact
    pose1, pose2 = kin.pinion_pose(mp.phi1_rad), kin.gear_pose(mp.phi2_rad)
    dmin = np.inf
    for edge in FLANK_EDGES:
        own, own_pose, other, other_pose, uv0 = (
            (pinion, pose1, gear, pose2, (mp.u2, mp.v2)) if edge.member == "pinion"
            else (gear, pose2, pinion, pose1, (mp.u1, mp.v1)))
        ss = np.linspace(*edge_span(own, edge.name), 41)
        pts = [own_pose[0] @ own.point(*edge_parameters(own, edge.name, s)).r + own_pose[1]
               for s in ss]
        d = _signed_distances(other, other_pose, pts, 1.0, uv0)
        d = d[np.isfinite(d)]
        if d.size:
            dmin = min(dmin, float(d.min()))
    assert dmin >= -1e-7
    # the contact point itself touches
    x_edge = pose1[0] @ pinion.point(mp.u1, mp.v1).r + pose1[1]
    x_other = pose2[0] @ gear.point(mp.u2, mp.v2).r + pose2[1]
    assert np.linalg.norm(x_edge - x_other) < 1e-7


def test_interior_edge_contact_has_the_edge_tangent_in_the_touched_plane(
        s0003_centred, full_path):
    """At an edge contact inside its edge (not a corner), d phi2/ds = 0: the edge
    tangent lies in the touched surface's tangent plane (|t . n| < 1e-5, the Brent
    tolerance 1e-5 mm times the rate of turn of the edge tangent, well below 1/mm)."""
    s0003_pair, s0003_flanks = s0003_centred
    pinion, gear = _flanks(s0003_flanks)
    kin = s0003_pair.kinematics()
    checked = 0
    for mp in full_path.points:
        if not mp.edge_contact:
            continue
        member, name = mp.edge_contact.split()
        own, pose = ((pinion, kin.pinion_pose(mp.phi1_rad)) if member == "pinion"
                     else (gear, kin.gear_pose(mp.phi2_rad)))
        s = mp.u1 if member == "pinion" else mp.u2
        if name in ("root", "tip"):
            s = mp.v1 if member == "pinion" else mp.v2
        lo, hi = edge_span(own, name)
        other = gear if member == "pinion" else pinion
        a, b = (mp.u2, mp.v2) if member == "pinion" else (mp.u1, mp.v1)
        margin = min(a - other.u_range[0], other.u_range[1] - a,
                     b - other.v_range[0], other.v_range[1] - b)
        if min(s - lo, hi - s) < 1e-3 or margin < 1e-3:
            continue        # a corner or an edge crossing the other flank's boundary
        sp = own.point(*edge_parameters(own, name, s))
        tangent = pose[0] @ (sp.r_u if name in ("toe", "heel") else sp.r_v)
        assert abs(tangent @ mp.normal) / np.linalg.norm(tangent) < 1e-5
        checked += 1
    assert checked >= 1


@pytest.mark.parametrize("samples", [2])
def test_too_few_samples_is_refused(s0003_centred, s0003_drive, samples):
    s0003_pair, s0003_flanks = s0003_centred
    pinion, gear = _flanks(s0003_flanks)
    mp = s0003_drive.mean_point
    with pytest.raises(ValueError, match="samples"):
        solve_edge_contact(pinion, gear, s0003_pair.kinematics(), mp.phi1_rad,
                           guess=mp.as_guess(), forward=True, samples=samples)
