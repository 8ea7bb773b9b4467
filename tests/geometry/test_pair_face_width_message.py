"""The pinion face width's range is named with the gear face width it comes from, and a
gear face typed in inches is named so (geometry.pair; docs/machine_settings.md sec. 5,
"Ordinary pairs, measured": a gear face of 30 mm typed as 1.181 in was reported as
``design.pinion_face_width_mm = 33.0`` outside ``[1.181, 3.543]``, a value the user had
typed right, the gear's not named)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from gearcontact.geometry.pair import parse_pair
from gearcontact.validation import InputRangeError

F3 = Path(__file__).parents[2] / "examples" / "iso23509_f3.toml"


def _with_faces(gear: float, pinion: float) -> dict:
    data = tomllib.loads(F3.read_text())
    data["design"].update(gear_face_width_mm=gear, pinion_face_width_mm=pinion)
    return data


def test_gear_face_in_inches_is_named():
    """30 mm typed as 1.181 (in): the pinion's 31.91 mm lies in [25.4, 76.2] x 1.181 mm,
    so the gear's key and the converted value are named (exact arithmetic on the typed
    numbers: 25.4 x 1.181 = 29.9974)."""
    with pytest.raises(InputRangeError) as err:
        parse_pair(_with_faces(1.181, 31.91))
    assert err.value.field == "design.pinion_face_width_mm"
    text = str(err.value)
    assert "[1.181, 3.543] mm (from design.gear_face_width_mm = 1.181 to 3 times it" in text
    assert "design.gear_face_width_mm typed in inches? x 25.4 = 30 mm fits" in text


def test_a_pinion_face_too_wide_names_no_unit():
    """Pinion face 100 mm on a 30 mm gear face: the range and its source, no unit slip
    (100 mm is not within 25.4-76.2 times 30 mm)."""
    with pytest.raises(InputRangeError) as err:
        parse_pair(_with_faces(30.0, 100.0))
    text = str(err.value)
    assert "[30, 90] mm (from design.gear_face_width_mm = 30 to 3 times it)" in text
    assert "inches" not in text


F2 = Path(__file__).parents[2] / "examples" / "iso23509_f2_spiral_bevel.toml"


def _f2_with(**design) -> dict:
    data = tomllib.loads(F2.read_text())
    data["design"].update(design)
    return data


@pytest.mark.parametrize("typed, unit", [
    # F.2's 81.273 mm typed as 3.2 (in) and as 0.08127 (m); x 25.4 and x 1000 are exact
    # arithmetic on the typed numbers (81.28, 81.27 mm), the face 25.4 mm 0.31 of either
    (3.2, "inches? x 25.4 = 81.28 mm fits"),
    (0.08127, "metres? x 1000 = 81.27 mm fits"),
])
def test_a_cone_distance_typed_in_another_unit_is_named(typed, unit):
    """The gear mean cone distance in inches or metres was refused naming
    design.gear_face_width_mm alone, a key typed right (session 27, helper checks): both
    keys are named, the cone distance with the unit that fits."""
    with pytest.raises(InputRangeError) as err:
        parse_pair(_f2_with(gear_mean_cone_distance_mm=typed))
    assert err.value.field == ("design.gear_face_width_mm / "
                               "design.gear_mean_cone_distance_mm")
    assert err.value.value == (25.4, typed)
    assert f"design.gear_mean_cone_distance_mm typed in {unit}" in str(err.value)


def test_a_face_wider_than_a_cone_distance_typed_right_names_no_unit():
    """Face 90 mm on F.2's 81.273 mm: both keys named, no unit hint (90 mm is below 0.1
    of the cone distance in inches, 2064 mm, and above 0.5 of it in mm)."""
    with pytest.raises(InputRangeError) as err:
        parse_pair(_f2_with(gear_face_width_mm=90.0, pinion_face_width_mm=90.0))
    text = str(err.value)
    assert "design.gear_face_width_mm / design.gear_mean_cone_distance_mm" in text
    assert "81.27 mm from design.gear_mean_cone_distance_mm = 81.273" in text
    assert "typed in" not in text
