"""``--vary`` specs and the sweep grid (:mod:`gearcontact.sweep.grid`).

Truths: a spec spans numpy.linspace with both ends; the grid's cells are the product
of the steps and the torques; every malformed spec is a named InputRangeError.
"""

import numpy as np
import pytest

from gearcontact.sweep.grid import MAX_CELLS, SweepGrid, parse_vary
from gearcontact.validation import InputRangeError


def test_spec_is_linspace_with_both_ends():
    v = parse_vary("alpha=-0.02:0.02:5")
    assert (v.key, v.field) == ("alpha", "alpha_deg")
    # equal up to the rounding of linspace's arithmetic (1 ulp of 0.02 ~ 3.5e-18)
    np.testing.assert_allclose(v.values, [-0.02, -0.01, 0.0, 0.01, 0.02], rtol=0, atol=1e-17)
    assert parse_vary("P=0.05:0.05:1").values.tolist() == [0.05]


def test_grid_dims_shape_and_points():
    g = SweepGrid((parse_vary("E=-0.1:0.1:3"), parse_vary("P=0:0.1:2")), (32.25, 64.5))
    assert g.dims == ("E_mm", "P_mm", "torque_nm") and g.shape == (3, 2, 2)
    assert g.cells == 12
    pts = list(g.points())
    assert len(pts) == 6 and pts[-1] == ((2, 1), {"E_mm": 0.1, "P_mm": 0.1}, ())
    assert g.variants() == [()]


def test_design_keys_span_variants_in_grid_order():
    # the spelling "ease-off." names the TOML table [easeoff.drive]
    c = parse_vary("ease-off.drive.lengthwise_crowning_um_per_mm2=0.08:0.16:5")
    assert (c.key, c.field, c.unit, c.design) == (
        "easeoff.drive.lengthwise_crowning_um_per_mm2",
        "easeoff_drive_lengthwise_crowning_um_per_mm2", "um/mm^2", True)
    r = parse_vary("cutter.radius_mm=44:46:3")
    assert (r.field, r.unit) == ("cutter_radius_mm", "mm")
    assert parse_vary("cutter.limit_pressure_angle_factor=0:1:2").unit == "1"
    g = SweepGrid((parse_vary("E=-0.1:0.1:2"), r), (64.5,))
    assert g.dims == ("E_mm", "cutter_radius_mm", "torque_nm")
    assert g.variants() == [(("cutter.radius_mm", 44.0),), (("cutter.radius_mm", 45.0),),
                            (("cutter.radius_mm", 46.0),)]
    pts = list(g.points())
    assert pts[4] == ((1, 1), {"E_mm": 0.1}, (("cutter.radius_mm", 45.0),))


def test_unknown_toml_key_lists_the_allowed_keys():
    with pytest.raises(InputRangeError) as exc:
        parse_vary("easeoff.drive.lengthwise_crowning=0.08:0.16:5")
    msg = str(exc.value)
    assert "easeoff.drive.lengthwise_crowning" in msg
    for allowed in ("E, P, G, alpha", "easeoff.drive.lengthwise_crowning_um_per_mm2",
                    "easeoff.coast.bias_um_per_mm2", "cutter.radius_mm"):
        assert allowed in msg


@pytest.mark.parametrize("spec,named", [
    ("Q=0:1:2", "one of the assembly errors E, P, G, alpha"), ("E0:1:2", "KEY=START"),
    ("E=0:1", "three fields"), ("E=a:1:2", "integer STEPS"), ("E=0:1:2.5", "integer STEPS"),
    ("E=0.1:-0.1:3", "reversed range"), ("E=0:0.1:0", "STEPS = 0"),
    ("E=0:0.1:1", "STEPS >= 2"), ("E=0.1:0.1:3", "STEPS = 1 when STOP == START"),
    ("P=0:1.5:3", "--vary P (mm) = 1.5"),
    ("alpha=-1:0:3", "[-0.5, 0.5] deg"), ("G=0:0.1:102", "[1, 101]"),
    # issue 28 probe: a NaN bound was called "a reversed range"
    ("E=nan:0.1:3", "--vary E START = nan is outside the allowed range: a finite real"),
    ("E=0:inf:3", "--vary E STOP = inf")])
def test_bad_specs_are_named_errors(spec, named):
    with pytest.raises(InputRangeError) as exc:
        parse_vary(spec)
    assert named in str(exc.value)


def test_repeated_key_and_too_many_cells():
    with pytest.raises(InputRangeError, match="each key at most once"):
        SweepGrid((parse_vary("E=0:1:2"), parse_vary("E=0:1:3")), (64.5,))
    big = (parse_vary("E=-1:1:101"), parse_vary("P=-1:1:101"), parse_vary("G=0:1:11"))
    with pytest.raises(InputRangeError, match=f"at most {MAX_CELLS}"):
        SweepGrid(big, (64.5,))
