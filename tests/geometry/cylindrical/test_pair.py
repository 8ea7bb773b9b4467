"""The kind = "cylindrical" pair format: loading, dispatch, and errors naming the field,
the value and the allowed range before any work."""

import copy
import tomllib
from pathlib import Path

import pytest

from gearcontact.geometry.cylindrical.pair import CylindricalPair, parse_cylindrical_pair
from gearcontact.geometry.pair import GearPair, load_pair
from gearcontact.validation import InputRangeError, UnusableInput

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"
BOTH = ("bevel", "cylindrical")


def _doc():
    return tomllib.loads((EXAMPLES / "ev_reducer_helical_23x67.toml").read_text())


def test_examples_load_as_cylindrical():
    for name in ("spur_20x40_m3", "ev_reducer_helical_23x67", "fzg_c_type"):
        pair = load_pair(EXAMPLES / f"{name}.toml", kinds=BOTH)
        assert isinstance(pair, CylindricalPair) and pair.name == name
    ev = load_pair(EXAMPLES / "ev_reducer_helical_23x67.toml", kinds=BOTH)
    assert (ev.hand("pinion"), ev.hand("gear")) == ("left", "right")
    assert ev.modifications_pinion.tip_relief_um == 8.0
    assert ev.pinion_material.youngs_modulus_mpa == 210_000.0
    assert ev.geometry.face_width_mm == 30.0           # the common (smaller) face width


def test_kind_dispatch_and_refusal():
    """Absent kind: today's bevel pair, unchanged; a caller that takes bevel pairs only
    (the default) refuses a cylindrical file naming ``kind``; an unknown kind is named."""
    assert isinstance(load_pair("s0003"), GearPair)
    with pytest.raises(InputRangeError) as err:
        load_pair(EXAMPLES / "spur_20x40_m3.toml")
    assert err.value.field.endswith("kind") and err.value.value == "cylindrical"
    assert "design" in err.value.allowed


def test_unknown_kind(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text((EXAMPLES / "spur_20x40_m3.toml").read_text().replace(
        'kind = "cylindrical"', 'kind = "worm"'))
    with pytest.raises(InputRangeError) as err:
        load_pair(path, kinds=BOTH)
    assert err.value.field == f"{path}: kind" and "'cylindrical'" in err.value.allowed


@pytest.mark.parametrize("table, key, value, allowed", [
    ("teeth", "pinion", 4, "[5, 1000]"),
    ("teeth", "gear", 20, "[23, 1000]"),
    ("teeth", "pinion", 23.0, "integer"),
    ("cylindrical", "normal_module_mm", 0.0, "(0, 100]"),
    ("cylindrical", "normal_module_mm", "2", "float"),
    ("cylindrical", "normal_pressure_angle_deg", 40.0, "[10, 35]"),
    ("cylindrical", "helix_angle_deg", 50.0, "[0, 45]"),
    ("cylindrical", "helix_angle_deg", -1.0, "[0, 45]"),
    ("cylindrical", "pinion_hand", "up", "'right' or 'left'"),
    ("cylindrical", "pinion_face_width_mm", -3.0, "(0, 1000]"),
    ("cylindrical", "profile_shift_pinion", 2.0, "[-1.5, 1.5]"),
    ("cylindrical", "addendum_factor", 0.3, "[0.5, 1.5]"),
    ("cylindrical", "dedendum_factor", 0.9, "(1, 2]"),
    ("cylindrical", "rack_tip_radius_factor", 0.6, "[0, 0.47"),
    ("cylindrical", "centre_distance_mm", 99.0, ">= 100.08"),
    # beyond the tip circles' reach there is no mesh at all (was a negative eps_alpha)
    ("cylindrical", "centre_distance_mm", 110.0, "where the tip circles"),
    ("cylindrical", "tip_diameter_pinion_mm", 45.0, "form diameter"),
    ("cylindrical", "colour", 1.0, "known key"),
    ("modifications.pinion", "tip_relief_um", 600.0, "[0, 500]"),
    ("modifications.pinion", "tip_relief_start_diameter_mm", 47.0, "(48.649"),
    ("modifications.gear", "root_relief_um", -1.0, "[0, 500]"),
    ("modifications.gear", "profile_crowning_um", 300.0, "[0, 200]"),
    ("modifications.pinion", "lead_crowning_um", 201.0, "[0, 200]"),
    ("modifications.pinion", "helix_slope_um", -250.0, "[-200, 200]"),
    ("assembly", "axis_inclination_um", 600.0, "[-500, 500]"),
    ("assembly", "axis_deviation_um", float("nan"), "finite"),
    ("material.gear", "poisson_ratio", 0.5, "[0, 0.5)"),
])
def test_bad_field_named(table, key, value, allowed):
    doc = _doc()
    parent = doc
    for part in table.split("."):
        parent = parent.setdefault(part, {})
    parent[key] = value
    with pytest.raises(InputRangeError) as err:
        parse_cylindrical_pair(doc)
    # the material check names its own key (Material is shared with the bevel pairs)
    assert err.value.field.endswith(key)
    assert allowed in err.value.allowed, err.value.allowed


def test_missing_and_conflicting_fields():
    doc = _doc()
    del doc["cylindrical"]["normal_module_mm"]
    with pytest.raises(InputRangeError, match="cylindrical.normal_module_mm"):
        parse_cylindrical_pair(doc)
    doc = _doc()
    doc["cylindrical"]["face_width_mm"] = 30.0
    with pytest.raises(InputRangeError, match="face_width_mm"):
        parse_cylindrical_pair(doc)
    doc = _doc()
    del doc["cylindrical"]["pinion_hand"]
    with pytest.raises(InputRangeError, match="pinion_hand.*required"):
        parse_cylindrical_pair(doc)
    spur = tomllib.loads((EXAMPLES / "spur_20x40_m3.toml").read_text())
    spur["cylindrical"]["pinion_hand"] = "right"
    with pytest.raises(InputRangeError, match="pinion_hand.*spur"):
        parse_cylindrical_pair(spur)
    doc = _doc()
    del doc["modifications"]["pinion"]["tip_relief_start_diameter_mm"]
    with pytest.raises(InputRangeError, match="tip_relief_start_diameter_mm.*required"):
        parse_cylindrical_pair(doc)


def test_impossible_designs_named():
    """An undercut that shortens the path below eps_alpha = 1 (z = 8, x = 0: x_min = 1.25
    - 0.38 (1 - sin 20) - (8/2) sin^2 20 = 0.532, the textbook 1 - z sin^2(α)/2 of a rack
    whose straight flank ends at 1.0 m; the involute starts at the trochoid's crossing,
    tests/geometry/cylindrical/test_undercut.py), pointed teeth, contact ratio < 1."""
    base = tomllib.loads((EXAMPLES / "spur_20x40_m3.toml").read_text())
    doc = copy.deepcopy(base)
    doc["teeth"]["pinion"] = 8
    with pytest.raises(UnusableInput, match=r"eps_alpha.*undercut below x_min = 0\.532"):
        parse_cylindrical_pair(doc)
    doc = copy.deepcopy(base)
    doc["teeth"]["pinion"], doc["cylindrical"]["profile_shift_pinion"] = 10, 1.4
    with pytest.raises(InputRangeError, match="pointed"):
        parse_cylindrical_pair(doc)
    doc = copy.deepcopy(base)
    doc["cylindrical"]["addendum_factor"] = 0.5
    with pytest.raises(UnusableInput, match="eps_alpha"):
        parse_cylindrical_pair(doc)
