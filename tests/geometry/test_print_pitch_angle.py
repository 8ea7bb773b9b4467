"""A print's gear pitch angle outside (0, 90) deg is named by its own key
(geometry.print_words; docs/machine_settings.md sec. 5, "Ordinary pairs, measured":
"174D 49M" was reported as ``print.gear.gear_crown_to_crossing_point_in = 1.293``, a
length typed right, through the datum chain the angle feeds)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from gearcontact.geometry.pair import parse_pair
from gearcontact.validation import InputRangeError

SHEET = Path(__file__).parent / "summary_sheets" / "hypoid_10x41_no16_pair.toml"


@pytest.mark.parametrize("typed", ["174D 49M", "-74D 49M", "90D 0M", "0"])
def test_pitch_angle_out_of_a_cone_is_named(typed):
    """A cone's half angle lies in (0, 90) deg: each typed value outside is refused on
    load naming the key and the value as typed."""
    data = tomllib.loads(SHEET.read_text())
    assert data["print"]["gear"]["gear_pitch_angle_deg"] == "74D 49M"   # the page's
    data["print"]["gear"]["gear_pitch_angle_deg"] = typed
    with pytest.raises(InputRangeError) as err:
        parse_pair(data)
    assert err.value.field == "print.gear.gear_pitch_angle_deg"
    assert err.value.value == typed
    assert "(0, 90) deg" in err.value.allowed
