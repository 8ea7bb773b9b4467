"""Signs of the principal directions (:mod:`gearcontact.tca.curvature`, module docstring:
the major axis towards the toe; within ``ORIENTATION_TOL`` of +-90 deg towards the
root, reported at 90 deg; the minor axis the major turned by -90 deg in ``(l, p)``).

Truths: (1) the rule only chooses signs: every oriented direction is, bit for bit, plus
or minus the eigen-solver's vector, and the minor axis is the major turned by -90 deg
(to 1e-15, the rounding of unit vectors); (2) on s0003 (a smooth pair, ellipse ~20 deg
from lengthwise) the rule keeps the eigen-solver's own signs at every phase (so its
principal frames, gap fields and LTCA grids are those of every earlier run, bit for
bit); (3) on the Flankrem pair, whose mean point is a contact on the gear's kink ridge
(the edge tensor diagonal in ``(l, p)`` by construction, ellipse at 90 deg), shifts of
the mean point by 1e-12 mm - rounding level, and shown to flip the eigen-solver's sign -
leave the frame, the angle and the principal gap field (the 80 x 80 grid of the
unshifted point) as they are.
"""

import dataclasses

import numpy as np
import pytest

from gearcontact.tca.curvature import (ORIENTATION_TOL, contact_ellipse,
                                       relative_curvature)
from gearcontact.tca.stencil import gap_field, gap_field_80, tangent_frame

FLANKREM = "tests/data/toprem/iso23509_f2_gear_flankrem.toml"


def _raw(rc):
    """The eigen-solver's principal directions of ``rc``'s tensor (no sign rule)."""
    basis = np.column_stack([rc.lengthwise, rc.profile])
    _, evecs = np.linalg.eigh(rc.tensor_per_mm)
    return basis @ evecs[:, 0], basis @ evecs[:, 1]


def _check_rule(rc):
    """(1): signs only, and the convention itself."""
    raw_min, raw_max = _raw(rc)
    assert (np.array_equal(rc.dir_min, raw_min) or np.array_equal(rc.dir_min, -raw_min))
    assert (np.array_equal(rc.dir_max, raw_max) or np.array_equal(rc.dir_max, -raw_max))
    c_l, c_p = rc.dir_min @ rc.lengthwise, rc.dir_min @ rc.profile
    assert c_l < -ORIENTATION_TOL or (abs(c_l) <= ORIENTATION_TOL and c_p < 0.0)
    # minor = major turned by -90 deg in (l, p): components (c_p, -c_l); 1e-15: unit
    # vectors' rounding
    assert abs(rc.dir_max @ rc.lengthwise - c_p) < 1e-15
    assert abs(rc.dir_max @ rc.profile + c_l) < 1e-15


def test_smooth_pair_keeps_the_eigen_solver_signs(s0003_centred, full_path):
    # (2) s0003 drive side, every phase of the path with its edge tails
    pair, flanks = s0003_centred
    pinion, gear = flanks.flank("pinion", "drive"), flanks.flank("gear", "drive")
    kin = pair.kinematics()
    checked = 0
    for mp in full_path.points:
        if mp.edge:
            continue
        rc = relative_curvature(pinion, gear, kin, mp)
        _check_rule(rc)
        if mp.edge_contact:     # an edge tail's tensor: the rule, not the solver's signs
            continue
        raw_min, raw_max = _raw(rc)
        assert np.array_equal(rc.dir_min, raw_min) and np.array_equal(rc.dir_max, raw_max)
        checked += 1
    assert checked >= 30


@pytest.fixture(scope="module")
def ridge_mean_point():
    """The Flankrem pair's flanks, kinematics and reference point (a gear-ridge edge
    contact; ~2 s)."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair
    from gearcontact.tca.analysis import analyze_pair

    pair = load_pair(FLANKREM)
    flanks = build_flanks(pair)
    res = analyze_pair(pair, flanks=flanks)[0]
    side = pair.design_side
    return (flanks.flank("pinion", side), flanks.flank("gear", side), pair.kinematics(),
            res.cycle.reference_point)


def test_ridge_orientation_does_not_flip_with_rounding(ridge_mean_point):
    # (3) shifts of the gear point along the ridge (v2) and of the phase, 1e-12 mm /
    # 1e-14 rad: rounding level; they change the edge tensor's off-diagonal between 0
    # and ~2e-19 1/mm, which flips the eigen-solver's major axis (asserted below, so
    # that the test would see a mirrored field without the rule)
    pinion, gear, kin, mp = ridge_mean_point
    assert mp.edge_contact == "gear flankrem"
    shifted = [mp] + [dataclasses.replace(mp, v2=mp.v2 + d) for d in (1e-12, -1e-12, 2e-12)]
    shifted += [dataclasses.replace(mp, phi2_rad=mp.phi2_rad + 1e-14)]
    raws, frames, fields = [], [], []
    # every field on the reference's 80 x 80 grid (gap_field_80's extents follow the
    # ellipse, whose curvatures move by ~3e-9 of themselves under these shifts at the
    # kink: a size change, not an orientation one)
    extents = gap_field_80(pinion, gear, kin, mp)
    extents = (float(np.abs(extents.s_mm).max()), float(np.abs(extents.t_mm).max()))
    half = tuple(e * 80 / 79 for e in extents)      # outermost node at 79/80 of L
    for m in shifted:
        rc = relative_curvature(pinion, gear, kin, m)
        _check_rule(rc)
        assert abs(rc.dir_min @ rc.lengthwise) <= ORIENTATION_TOL     # at 90 deg
        assert contact_ellipse(rc).angle_deg == 90.0
        raws.append(_raw(rc)[0] @ rc.profile)
        frames.append(tangent_frame(pinion, gear, kin, m, "principal"))
        fields.append(gap_field(pinion, gear, kin, m, half_extent_mm=half))
    assert min(raws) < 0.0 < max(raws), "no shift flipped the eigen-solver's sign"
    ref = fields[0]
    ok = np.isfinite(ref.gap_mm)
    mirrored = ref.gap_mm[::-1, ::-1]
    both = ok & np.isfinite(mirrored)
    # a mirrored field (s, t) -> (-s, -t) differs by tenths of a micrometre or more
    # (the ridge makes the gap odd in t); measured below, so 1e-9 mm can tell
    assert np.abs(ref.gap_mm[both] - mirrored[both]).max() > 1e-6
    for frame, field in zip(frames[1:], fields[1:]):
        # the frame to rounding (1e-12: 1e-12 mm shifts on curvature radii > 1 mm)
        assert np.abs(frame - frames[0]).max() < 1e-12
        assert np.array_equal(np.isfinite(field.gap_mm), ok)
        # 1e-9 mm: the house tolerance for gap fields that agree to rounding
        # (tests/tca/test_gap_kernel.py)
        assert np.abs(field.gap_mm[ok] - ref.gap_mm[ok]).max() < 1e-9
