"""The gap field fitted to an edge contact (tca.edge_field) against the TCA's touch.

Truth (first touch, tca.edge_contact): at an edge contact the edge point touches the
other flank (separation 0) and no flank point inside the edge is closer. The field's
first row of cells lies half a cell ``h_t / 2`` inside the edge, with a node on the
line through the contact point, so its least gap over the flank is >= 0 and at most
the separation there, by Taylor's theorem ``m h_t / 2 + (1/2) B_tt (h_t / 2)^2 + O(h^3)``
with ``m`` the inward slope (:func:`~gearcontact.tca.edge_contact.inward_slope`) and
``B`` the smooth flanks' relative curvature tensor at the contact point (both from the
surfaces' own derivatives, not from the field). Tolerances are stated per test.
"""

import numpy as np
import pytest

from gearcontact.tca.curvature import curvature_tensor
from gearcontact.tca.edge_contact import edge_directions, inward_slope
from gearcontact.tca.edge_field import edge_frame, edge_gap_field
from gearcontact.validation import InputRangeError

#: Field of the tests: +-2 mm along the edge, 0.5 mm into the flank, 40 x 40 cells
#: (h_t = 12.5 um: the s0003-centred contact ellipse's minor semi-axis at 258 N·m is
#: about 0.25 mm).
HALF_LENGTH_MM, DEPTH_MM, SIDE = 2.0, 0.5, 40


def _interior(pinion, gear, kin, mp, margin=0.02) -> bool:
    """An edge contact inside its edge (not a corner: the free edge parameter and the
    touched point at least ``margin`` of their ranges inside their boxes) whose flank
    recedes from the edge (positive inward slope: the edge touches first)."""
    member, _, name = mp.edge_contact.partition(" ")
    own, other = (pinion, gear) if member == "pinion" else (gear, pinion)
    uv_own = (mp.u1, mp.v1) if member == "pinion" else (mp.u2, mp.v2)
    uv_other = (mp.u2, mp.v2) if member == "pinion" else (mp.u1, mp.v1)
    free = 0 if name in ("toe", "heel") else 1
    ranges = (own.u_range, own.v_range)
    lo, hi = ranges[free]
    d = margin * (hi - lo)
    inside = lo + d < uv_own[free] < hi - d
    for x, (lo, hi) in zip(uv_other, (other.u_range, other.v_range)):
        inside &= lo + margin * (hi - lo) < x < hi - margin * (hi - lo)
    return bool(inside) and inward_slope(pinion, gear, kin, mp) > 0.0


def _edge_points(path, pinion, gear, kin, count=6):
    pts = [p for p in path.points if p.edge_contact and _interior(pinion, gear, kin, p)]
    idx = np.unique(np.linspace(0, len(pts) - 1, count).round().astype(int))
    return [pts[i] for i in idx]


def _smooth_tensor(pinion, gear, kin, mp, basis):
    """Relative curvature tensor of the two smooth flanks at the contact point (1/mm)."""
    rot1, rot2 = kin.pinion_pose(mp.phi1_rad)[0], kin.gear_pose(mp.phi2_rad)[0]
    b = -(curvature_tensor(pinion.point(mp.u1, mp.v1), rot1, basis)
          + curvature_tensor(gear.point(mp.u2, mp.v2), rot2, basis))
    return 0.5 * (b + b.T)


def test_least_gap_is_the_touch_to_the_grid_resolution(s0003_centred, full_path):
    """At six edge contacts inside their edges (:func:`_interior`) along the tails of the
    centred pair's path (pinion and gear edges): the least gap over the flank cells is >= -1e-9 mm (no interference; the
    TCA's and the field's Newton tolerances are 1e-10 and 1e-11 mm) and at most the
    Taylor separation half a cell inside the edge (module docstring) times 1.05 plus
    1e-9 mm (5 % for the cubic terms over h_t / 2 = 6.25 um); the node on the contact's
    line half a cell inside is on the flank and the one half a cell behind is off it
    (the edge bounds the grid)."""
    pair, flanks = s0003_centred
    pinion, gear = flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")
    kin = pair.kinematics()
    labels = set()
    for mp in _edge_points(full_path, pinion, gear, kin):
        f = edge_gap_field(pinion, gear, kin, mp, half_length_mm=HALF_LENGTH_MM,
                           depth_mm=DEPTH_MM, side=SIDE, allow_outside=True)
        h_t = DEPTH_MM / SIDE
        first = int(np.argmin(np.abs(f.t_mm[:, 0] - 0.5 * h_t)))
        centre = int(np.argmin(np.abs(f.s_mm[0, :])))
        assert f.s_mm[0, centre] == 0.0 and f.t_mm[first, 0] == pytest.approx(0.5 * h_t)
        assert f.on_flank[first, centre] and not f.on_flank[first - 1, centre]
        axes = edge_frame(pinion, gear, kin, mp)
        b_tt = float(_smooth_tensor(pinion, gear, kin, mp, axes[:, :2])[1, 1])
        m = inward_slope(pinion, gear, kin, mp)
        bound = m * 0.5 * h_t + 0.5 * b_tt * (0.5 * h_t) ** 2
        g_min = float(f.gap_mm[f.on_flank].min())
        assert -1e-9 <= g_min <= 1.05 * bound + 1e-9, (mp.edge_contact, g_min, bound)
        assert f.gap_mm[first, centre] == pytest.approx(bound, rel=0.05, abs=1e-9)
        labels.add(mp.edge_contact)
    assert len(labels) >= 2          # both tails, two different edges


def test_frame_runs_along_the_edge_into_its_flank(s0003_centred, full_path):
    """The frame is orthonormal and right-handed with the contact's normal; e_t points
    into the edge's own flank: the flank point a small step (1e-3 of the parameter
    range) inside the edge projects on e_t positively, within 1e-9 mm of e_s
    orthogonality of the edge's own tangent."""
    pair, flanks = s0003_centred
    pinion, gear = flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")
    kin = pair.kinematics()
    for mp in _edge_points(full_path, pinion, gear, kin, 3):
        axes = edge_frame(pinion, gear, kin, mp)
        assert np.allclose(axes.T @ axes, np.eye(3), atol=1e-12)
        assert np.linalg.det(axes) == pytest.approx(1.0, abs=1e-12)
        assert np.allclose(axes[:, 2], mp.normal, atol=1e-12)
        member, _, name = mp.edge_contact.partition(" ")
        own = pinion if member == "pinion" else gear
        pose = kin.pinion_pose(mp.phi1_rad) if member == "pinion" else kin.gear_pose(mp.phi2_rad)
        u, v = (mp.u1, mp.v1) if member == "pinion" else (mp.u2, mp.v2)
        du = 1e-3 * np.ptp(own.u_range) * {"root": 1, "tip": -1}.get(name, 0)
        dv = 1e-3 * np.ptp(own.v_range) * {"toe": 1, "heel": -1}.get(name, 0)
        x = pose[0] @ (own.point(u + du, v + dv).r - own.point(u, v).r)
        assert x @ axes[:, 1] > 0.0


def test_a_surface_contact_is_refused(s0003_drive, s0003_centred):
    pair, flanks = s0003_centred
    with pytest.raises(InputRangeError, match="mp.edge_contact"):
        edge_gap_field(flanks.flank("pinion", "drive"), flanks.flank("gear", "drive"),
                       pair.kinematics(), s0003_drive.mean_point, half_length_mm=1.0,
                       depth_mm=0.1)


def _corner_gradient(pinion, gear, kin, mp, axes) -> np.ndarray:
    """First-order slope ``(d g / d s, d g / d t)`` of the separation over the edge's
    own flank in the field's tangent plane: the own flank's tangent plane is spanned by
    the edge tangent and the inward step (:func:`~gearcontact.tca.edge_contact.
    edge_directions`, the surfaces' own derivatives); its normal component over its
    tangent-plane projection."""
    along, inward, n_other = edge_directions(pinion, gear, kin, mp)
    span = np.column_stack([along, inward])
    return (n_other @ span) @ np.linalg.inv(axes[:, :2].T @ span)


def test_corner_contact_is_named_and_keeps_the_touch(s0003_calibrated, s0003_calibrated_tca):
    """Corner contacts (issue 28): on the calibrated s0003's coast path the pinion tip
    edge runs onto the gear's heel boundary (and the gear heel edge onto the pinion's
    tip), so the node half a cell inside on the contact's line is off the flank. The
    field names them (``"edge corner"``) and shifts its ``s`` nodes half a cell towards
    the flank: the diagonal node ``q = (+-h_s / 2, h_t / 2)`` is on both flanks, and the
    least gap over the flank is >= -1e-9 mm and at most the Taylor separation there,
    ``grad g . q + (1/2) q^T B q`` (the first-order slope from the surfaces' derivatives,
    :func:`_corner_gradient`; ``B`` the smooth flanks' relative curvature tensor), times
    1.05 plus 1e-9 mm (5 % for the cubic terms, as above), and within 5 % of it (measured
    0.2 %: the least gap is the diagonal node's; two corners on this field, the gear heel
    and the pinion tip, 0.166 and 0.333 um). Before the shift the least gap
    of the transmitting corner rows lay one whole cell along the edge (3.16-7.23 um at
    rows 53-55 against 1.78-5.12 um now, on the loaded TE's fields of 184 x 171 um
    cells)."""
    pair, flanks = s0003_calibrated
    side = pair.design_side
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    kin = pair.kinematics()
    corners = 0
    for mp in s0003_calibrated_tca.cycle.contact:
        if not mp.edge_contact:
            continue
        f = edge_gap_field(pinion, gear, kin, mp, half_length_mm=HALF_LENGTH_MM,
                           depth_mm=DEPTH_MM, side=SIDE, allow_outside=True)
        if f.frame_name != "edge corner":
            continue
        corners += 1
        h_s, h_t = 2.0 * HALF_LENGTH_MM / SIDE, DEPTH_MM / SIDE
        first = int(np.argmin(np.abs(f.t_mm[:, 0] - 0.5 * h_t)))
        col = int(np.argmin(np.abs(np.abs(f.s_mm[0, :]) - 0.5 * h_s) + 1e3 * (
            ~f.on_flank[first])))
        q = np.array([f.s_mm[0, col], f.t_mm[first, 0]])
        assert abs(q[0]) == pytest.approx(0.5 * h_s) and f.on_flank[first, col]
        axes = f.frame
        b = _smooth_tensor(pinion, gear, kin, mp, axes[:, :2])
        bound = float(_corner_gradient(pinion, gear, kin, mp, axes) @ q + 0.5 * q @ b @ q)
        g_min = float(f.gap_mm[f.on_flank].min())
        assert -1e-9 <= g_min <= 1.05 * bound + 1e-9, (mp.edge_contact, g_min, bound)
        assert g_min == pytest.approx(bound, rel=0.05)     # the diagonal node's
    assert corners >= 2
