"""The contact-ratio check of a pair cut from machine settings agrees with its blank's
(geometry.contact_ratio; docs/machine_settings.md sec. 5, "Ordinary pairs, measured").

The truth is the workflow's own contract, not a number of this code: the settings that
``design --machine-settings`` writes for a blank that ``design`` accepts are accepted by
every command that reads them (before: the 16/16 miter below, eps_vg 1.528 < 1.55, was
refused by ``tca`` and ``analyze`` though its blank passed, and the TCA of its settings
with the check bypassed ran without a gap: 1.39 pairs in contact, 24 of 61 phases two).
And where the blank's own check refuses, the settings of that blank stay refused.
"""

from __future__ import annotations

import pytest

from gearcontact.cli import main
from gearcontact.geometry.basic_settings import standard_machine_pair
from gearcontact.geometry.contact_ratio import (MIN_VIRTUAL_CONTACT_RATIO,
                                                virtual_contact_ratio)
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError

#: An ordinary miter spiral bevel pair: 16/16, E 0, beta 35 deg, R_m 55 mm, face 20 mm
#: (0.31 R_e, the standard limit), cutter 4.5 in.
MITER = """name = "miter_16x16"
[teeth]
pinion = 16
gear = 16
[axes]
shaft_angle_deg = 90.0
offset_mm = 0.0
[design]
pinion_hand = "right"
gear_mean_cone_distance_mm = 55.0
pinion_spiral_angle_deg = 35.0
gear_face_width_mm = {face}
pinion_face_width_mm = {face}
gear_addendum_factor = 0.5
[cutter]
radius_mm = 57.15
point_width_mm = 2.0
edge_radius_mm = 0.4
"""


def _blank(tmp_path, face: float):
    path = tmp_path / f"miter_{face:g}.toml"
    path.write_text(MITER.format(face=face))
    return path


def test_written_settings_of_an_accepted_blank_are_accepted(tmp_path, capsys):
    """design accepts the blank and writes its settings (exit 0); the closed form alone
    would refuse them (precondition, ISO 10300-1 by hand in test_contact_ratio.py); the
    commands' check of the written file passes now, with the blank's path ratio."""
    path = _blank(tmp_path, 20.0)
    out = tmp_path / "mach"
    assert main(["design", "--pair", str(path), "--machine-settings", "--out", str(out)]) == 0
    written = load_pair(out / "machine_settings.toml")
    assert written.machine
    v = virtual_contact_ratio(written.blank, gear_face_width_mm=written.gear_face_width_mm,
                              side="drive")
    assert v.total < MIN_VIRTUAL_CONTACT_RATIO           # 1.528: refused before
    check_generation(written)                             # raised InputRangeError before


def test_settings_of_a_refused_blank_stay_refused(tmp_path):
    """Face 16 mm: ``design --machine-settings`` refuses the blank (its path covers 0.703
    pitches, below 0.85); the standard settings of that blank, made by hand, are refused
    by the commands too, the message giving both the closed form and the blank's path
    ratio."""
    path = _blank(tmp_path, 16.0)
    assert main(["design", "--pair", str(path), "--machine-settings",
                 "--out", str(tmp_path / "mach")]) == 2
    blank = load_pair(path)
    settings = standard_machine_pair(blank, gear_generation="generated")
    with pytest.raises(InputRangeError) as err:
        check_generation(settings)
    text = str(err.value)
    assert "eps_vg = 1.426" in text and "the blank's contact path" in text
    assert "eps_p = 0.703" in text        # the blank's own refusal gives the same 0.703
