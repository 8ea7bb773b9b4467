"""The near-field split in the LTCA's bending blocks (ToothBending(near_field=True);
docs/bending.md sec. 13, session 27, criterion 2, declared before it was built).

Set-up: s0003-centred's gear made blockless (rim depth = fillet, session 26's set-up) as
the Ritz solid at small degrees (6, 4, 2) for seconds; its pinion the default shell.
Truths:

* at the sub-lattice the block's compliance is the structure layer's far field of the
  solid (:func:`gearcontact.structure.near_field.solid_far_field_matrix`, checked
  against the FE in tests/structure/test_near_field.py) plus the pinion's ``F F^T``, to
  the compression's cut: every entry of the dropped eigen-part is below 1e-6 of the
  largest |entry| (``|sum lambda_k v_ik v_jk| <= max |lambda_k|``);
* between the nodes the splines interpolate it within 2e-3 of its largest entry (the
  plate's declared interpolation error, test_tooth_bending.py): differs, 2.10e-3 (strict
  xfail: the absolute error is the plate path's, the largest entry is smaller);
* the block is indefinite (a negative eigenvalue: the far field near the root), and the
  coupled LCP on it converges with its total positive definite on the contact
  (complementarity and torque balance as without it), rotating less than the plate's
  no-block operator (set A: the split 1.03-1.16 x FE against the plate's 1.45-2.60; the
  direction, not a size, is asserted).
"""

import warnings

import numpy as np
import pytest

from gearcontact.ltca.multitooth import multi_tooth_ltca
from gearcontact.ltca.tooth_bending import SignedFactor, ToothBending, flank_rows, solid_tooth
from gearcontact.structure.near_field import solid_far_field_matrix
from gearcontact.structure.rim import rim_segment
from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING
from gearcontact.structure.shell import ORDER, ORDER_FACE, build_shell, tooth_shell
from gearcontact.structure.tooth import tooth_geometry
from gearcontact.validation import InputRangeError

#: The sub-lattice of ToothBending.factor (tooth_bending._NODES) on a 40 x 40 field.
FIELD, NODES = (40, 40), (8, 24)


@pytest.fixture(scope="module")
def teeth(centred_drive_11):
    """(pinion shell, the gear's no-block plate, its solid at degrees (6, 4, 2))."""
    pair, flanks, _ = centred_drive_11
    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    rim = rim_segment(tooth, depth_mm=rim_segment(tooth).fillet_mm,
                      stiffening=BLOCK_RIM_STIFFENING)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # NoBlockWarning: the plate is the no-block one
        plate = tooth_shell(flanks, "gear", material=pair.gear_material, rim=rim)
    solid = build_shell(tooth, order=ORDER, order_face=ORDER_FACE, rim=rim, rim_block=True,
                        solid_tooth=True, solid_degrees=(6, 4, 2))
    return tooth_shell(flanks, "pinion", material=pair.pinion_material), plate, solid


def field_uv():
    """A 40 x 40 field, 7 x 1 mm, affine in the cell index like the tangent-plane map, at
    mid flank of both teeth (test_tooth_bending.test_sub_lattice_interpolation_matches_exact)."""
    J, I = np.meshgrid(np.arange(40), np.arange(40), indexing="ij")
    uv1 = np.column_stack([(1.2 + 0.02 * (J - 20) + 0.005 * (I - 20)).ravel(),
                           (35.0 + 0.17 * (I - 20) - 0.01 * (J - 20)).ravel()])
    uv2 = np.column_stack([(1.3 + 0.02 * (J - 20) - 0.004 * (I - 20)).ravel(),
                           (0.5 + 0.17 * (I - 20) + 0.01 * (J - 20)).ravel()])
    return uv1, uv2


def test_block_at_the_nodes_is_the_far_field_plus_the_pinion(teeth):
    pin, _, solid = teeth
    uv1, uv2 = field_uv()
    sf = ToothBending(pinion=pin, gear=solid, side="drive", near_field=True).factor(
        uv1, uv2, FIELD)
    assert isinstance(sf, SignedFactor)
    jy = np.unique(np.rint(np.linspace(0, 39, NODES[0])).astype(int))
    jx = np.unique(np.rint(np.linspace(0, 39, NODES[1])).astype(int))
    pick = (jy[:, None] * FIELD[1] + jx[None, :]).ravel()
    got = sf.matrix()[np.ix_(pick, pick)]
    gear = solid.body
    u = np.clip(uv2[pick, 0], *gear.drive.u_range)
    v = np.clip(uv2[pick, 1], *gear.drive.v_range)
    far = solid_far_field_matrix(solid, gear.points_at("drive", *gear.tooth_coordinates(
        "drive", u, v)))
    f = flank_rows(pin, "drive").rows(uv1[pick])
    want = far + f @ f.T
    assert np.abs(got - want).max() <= 1e-6 * np.abs(want).max()
    assert np.linalg.eigvalsh(want)[0] < 0.0   # indefinite: a plain F F^T cannot hold it


@pytest.mark.xfail(strict=True, reason=(
    "differs: 2.10e-3 of the largest entry against the declared 2e-3; the absolute "
    "interpolation error is the plate path's (1.72e-8 against 1.59e-8 mm/N on the same "
    "field, the pinion's rows being the same), but the largest entry falls from "
    "1.34e-5 (plate) to 8.19e-6 mm/N (far field), so the relative error rises from "
    "1.18e-3 to 2.10e-3 (docs/bending.md sec. 13, session 27)"))
def test_block_between_the_nodes(teeth):
    pin, _, solid = teeth
    uv1, uv2 = field_uv()
    bend = ToothBending(pinion=pin, gear=solid, side="drive", near_field=True)
    fast = bend.factor(uv1, uv2, FIELD).matrix()
    exact = bend.factor(uv1, uv2, FIELD, nodes=FIELD).matrix()
    sub = np.arange(0, 1600, 7)   # every 7th cell, as the plate's test
    assert np.abs(fast[np.ix_(sub, sub)] - exact[np.ix_(sub, sub)]).max() \
        <= 2e-3 * np.abs(exact[np.ix_(sub, sub)]).max()


def test_solid_tooth_keeps_a_tooth_with_a_block_and_a_solid(teeth):
    """(The no-block branch, building the default solid (12, 8, 3), about 10 s, runs in
    the slow measurement of docs/bending.md, benchmarks/bench_near_field_ltca.py.)"""
    pin, _, solid = teeth
    assert solid_tooth(pin) is pin          # a tooth with a block: its shell as it is
    assert solid_tooth(solid) is solid      # a solid already


def test_near_field_option_is_checked(centred_drive_11):
    from gearcontact.ltca.tooth_bending import tooth_bending

    pair, flanks, _ = centred_drive_11
    with pytest.raises(InputRangeError, match="near_field"):
        tooth_bending(flanks, pair, side="drive", near_field="yes")


def test_multi_tooth_with_the_split(centred_drive_11, teeth):
    pair, flanks, tca = centred_drive_11
    pin, plate, solid = teeth
    split = multi_tooth_ltca(tca, flanks, pair, 64.5, side="drive", cells=24,
                             bending=ToothBending(pinion=pin, gear=solid, side="drive",
                                                  near_field=True))
    old = multi_tooth_ltca(tca, flanks, pair, 64.5, side="drive", cells=24,
                           bending=ToothBending(pinion=pin, gear=plate, side="drive"))
    assert split.converged and old.converged
    assert sum(split.load_share_pct) == pytest.approx(100.0, abs=1e-9)
    assert split.rotation_rigid_arcsec < split.rotation_arcsec < old.rotation_arcsec
