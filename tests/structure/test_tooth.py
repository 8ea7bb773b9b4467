"""structure.tooth: the mid-surface of a tooth between its drive and coast flanks."""

from dataclasses import replace

import numpy as np
import pytest

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.generation import gear_tip_top_lands
from gearcontact.geometry.pair import load_pair
from gearcontact.structure.tooth import tooth_geometry
from gearcontact.validation import InputRangeError


@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_mid_surface_normal_points_coast_to_drive(s0003_centred, member):
    pair, flanks = s0003_centred
    tooth = tooth_geometry(flanks, member, material=pair.gear_material)
    g = np.linspace(-1.0, 1.0, 9)
    xi, eta = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    mid = tooth.mid_surface(xi, eta)
    rd, _, _, nd = tooth.flank_arrays("drive", xi, eta)
    rc, _, _, nc = tooth.flank_arrays("coast", xi, eta)
    # a regular tooth: the chord coast -> drive leaves through the drive flank's outward
    # normal and enters against the coast flank's; the thickness is its normal component
    chord = rd - rc
    assert (np.einsum("ni,ni->n", chord, nd) > 0).all()
    assert (np.einsum("ni,ni->n", chord, nc) < 0).all()
    assert np.allclose(mid.thickness_mm, np.einsum("ni,ni->n", chord, mid.normal),
                       rtol=0, atol=1e-12)
    assert (mid.thickness_mm > 0).all()


def test_crossing_flanks_are_a_negative_thickness():
    # the 16/120 pair of tests/geometry/test_generation.py, past design's top-land check:
    # its gear flanks cross below the tip at the toe. The mid-surface normal followed the
    # chord there (the thickness stayed positive) and the shell failed later with a
    # negative Jacobian; oriented by the drive flank's normal, the thickness turns negative
    base = load_pair("examples/iso23509_f3.toml")
    pair = replace(base, pinion_teeth=16, gear_teeth=120,
                   offset_mm=0.2976747705510888 * base.gear_mean_pitch_radius_mm,
                   pinion_spiral_angle_deg=25.62282030712944)
    face = 0.34689485888287486 * pair.blank.mean_cone_distance_gear_mm
    pair = replace(pair, gear_face_width_mm=face, pinion_face_width_mm=1.05 * face)
    frac, land = gear_tip_top_lands(pair)
    assert land[0] < 0.0 < land[len(frac) // 2]      # pointed toe, sound mid-face
    tooth = tooth_geometry(build_flanks(pair, n_u=30, n_v=40), "gear",
                           material=pair.gear_material)
    assert tooth.mid_surface(np.array([0.0]), np.array([1.0])).thickness_mm[0] > 0.0
    with pytest.raises(InputRangeError) as err:
        tooth.mid_surface(np.array([-1.0]), np.array([1.0]))     # toe, tip
    assert err.value.field == "gear tooth thickness (mm)"
