"""GearPair / TOML loading: presets, examples, and errors naming the bad field."""

import tomllib
from pathlib import Path

import pytest

from gearcontact.geometry.pair import load_pair, parse_pair
from gearcontact.materials import STEEL
from gearcontact.validation import InputRangeError

ROOT = Path(__file__).resolve().parents[2]
#: The bevel/hypoid example pair files (examples/ also holds other tables, e.g.
#: [drivetrain] files, and cylindrical pairs: tests/geometry/cylindrical).
EXAMPLES = sorted(p for p in (ROOT / "examples").glob("*.toml")
                  if "teeth" in (doc := tomllib.loads(p.read_text())) and "kind" not in doc)


def _s0003_doc():
    from importlib import resources
    return tomllib.loads(resources.files("gearcontact").joinpath("data/pairs/s0003.toml").read_text())


def test_s0003_preset_fields():
    p = load_pair("s0003")
    assert (p.pinion_teeth, p.gear_teeth, p.offset_mm, p.pinion_hand) == (7, 70, 19.0, "right")
    assert p.gear_mean_cone_distance_mm == 40.68
    for m in (p.pinion_material, p.gear_material):
        assert (m.youngs_modulus_mpa, m.poisson_ratio) == (STEEL.youngs_modulus_mpa, STEEL.poisson_ratio)
    assert p.assembly.E_mm == 0.0 and p.assembly.alpha_deg == 0.0
    assert p.ratio == 10.0


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_examples_load(path):
    pair = load_pair(path)
    assert pair.blank.pitch_angle_gear_deg > pair.blank.pitch_angle_pinion_deg


def test_example_f3_is_iso_sample():
    b = load_pair(ROOT / "examples" / "iso23509_f3.toml").blank
    # ISO 23509 F.3: d_m2 = 141.877 mm, R_m1 = 73.519 mm (see test_blank for tolerances)
    assert 2 * b.mean_pitch_radius_gear_mm == pytest.approx(141.877, abs=0.0005)
    assert b.mean_cone_distance_pinion_mm == pytest.approx(73.519, abs=0.005)


def test_missing_field_named():
    doc = _s0003_doc()
    del doc["cutter"]["radius_mm"]
    with pytest.raises(InputRangeError) as err:
        parse_pair(doc)
    assert err.value.field == "cutter.radius_mm" and "float" in err.value.allowed


@pytest.mark.parametrize("section, key, value, expect", [
    ("teeth", "pinion", 7.5, "integer"),
    ("axes", "offset_mm", "19", "float"),
    ("design", "pinion_hand", 1, "string"),
])
def test_mistyped_field_named(section, key, value, expect):
    doc = _s0003_doc()
    doc[section][key] = value
    with pytest.raises(InputRangeError) as err:
        parse_pair(doc)
    assert err.value.field == f"{section}.{key}" and expect in err.value.allowed


def test_unknown_key_rejected():
    doc = _s0003_doc()
    doc["cutter"]["radius"] = 45.0
    with pytest.raises(InputRangeError) as err:
        parse_pair(doc)
    assert err.value.field == "cutter.radius"


@pytest.mark.parametrize("section, key, value, field", [
    ("axes", "offset_mm", 25.0, "axes.offset_mm"),
    ("teeth", "pinion", 3, "teeth.pinion"),
    ("cutter", "edge_radius_mm", 0.3, "cutter.edge_radius_mm"),
    ("design", "pinion_hand", "up", "design.pinion_hand"),
    ("design", "pinion_face_width_mm", 5.0, "design.pinion_face_width_mm"),
])
def test_impossible_pair(section, key, value, field):
    doc = _s0003_doc()
    doc[section][key] = value
    with pytest.raises(InputRangeError) as err:
        parse_pair(doc)
    assert field in err.value.field


def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(InputRangeError):
        load_pair(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[teeth\npinion = 7")
    with pytest.raises(InputRangeError) as err:
        load_pair(bad)
    assert "TOML" in err.value.field


@pytest.mark.parametrize("source", ["s0003", ROOT / "examples" / "iso23509_f3.toml"])
def test_toml_round_trip_keeps_which_tables_were_given(source):
    """``pair_to_toml`` is a fixed point of the round trip and keeps
    ``easeoff_tables`` (a material's display name is not written): a pair
    without ``[easeoff.*]`` (F.3: its commands synthesize one) is written without them,
    not with zero tables (which the commands would take as "no ease-off, given")."""
    from gearcontact.geometry.pair import pair_to_toml

    pair = load_pair(source)
    text = pair_to_toml(pair)
    back = parse_pair(tomllib.loads(text))
    assert back.easeoff_tables == pair.easeoff_tables
    assert pair_to_toml(back) == text
    assert ("[easeoff." in text) == bool(pair.easeoff_tables)
