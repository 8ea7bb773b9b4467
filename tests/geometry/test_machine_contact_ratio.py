"""The contact-ratio check of a pair cut from machine settings agrees with its blank's
(geometry.contact_ratio; docs/machine_settings.md sec. 5, "Ordinary pairs, measured").

The truth is the workflow's own contract, not a number of this code: the settings that
``design --machine-settings`` writes for a blank that ``design`` accepts are accepted by
every command that reads them (before: the 16/16 miter below, eps_vg 1.528 < 1.55, was
refused by ``tca`` and ``analyze`` though its blank passed, and the TCA of its settings
with the check bypassed ran without a gap: 1.39 pairs in contact, 24 of 61 phases two).
Where the blank's predicted path is short (the 16 mm face) the settings are warned,
not refused: the TCA of standard settings measured no gap on a family of pairs
(docs/machine_settings.md sec. 5, "The contact-ratio check of machine settings"), and
the console ``tca`` of the warned settings confirms it here.
"""

from __future__ import annotations

import json

import pytest

from gearcontact.cli import main
from gearcontact.geometry.basic_settings import standard_machine_pair
from gearcontact.geometry.contact_path import path_contact_ratio
from gearcontact.geometry.contact_ratio import (MIN_CONTACT_RATIO, MIN_VIRTUAL_CONTACT_RATIO,
                                                SETTINGS_GAP_RATIO, SETTINGS_NO_GAP_RATIO,
                                                ContactRatioWarning,
                                                virtual_contact_ratio)
from gearcontact.geometry.gear_generation import generation_of
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.edges import ContactGap
from gearcontact.tca.synthesis import prepare_pair
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


def _face_16(tmp_path):
    """The 16 mm miter blank: its first-order path covers eps_p 0.703 < 0.85 (the old
    check refused it), its closed form eps_vg 1.426 < 1.55."""
    blank = load_pair(_blank(tmp_path, 16.0))
    boxes = check_generation(blank, contact_ratio=False)
    return blank, path_contact_ratio(blank, boxes=boxes)


def test_a_blank_without_settings_is_still_refused(tmp_path):
    """The check of a pair designed without settings (conjugate pinion and synthesized
    ease-off, whose gaps were measured: docs/geometry.md sec. 7.7) is unchanged: the 16
    mm blank is refused, naming the blank's eps_p (computed here by the path itself)."""
    blank, path = _face_16(tmp_path)
    assert path.total < MIN_CONTACT_RATIO
    with pytest.raises(InputRangeError) as err:
        check_generation(blank)
    assert f"eps_p = {path.total:.3f}" in str(err.value)


def _names_fields_and_ratios(text: str, blank, path) -> None:
    """The warning names both fields with their values, the predicted eps_p (the blank's
    path, computed independently by the caller) and the closed form's eps_vg."""
    v = virtual_contact_ratio(blank.blank, gear_face_width_mm=blank.gear_face_width_mm,
                              side="drive")
    assert f"design.gear_face_width_mm = {blank.gear_face_width_mm:g} mm" in text
    assert f"design.pinion_spiral_angle_deg = {blank.pinion_spiral_angle_deg:g} deg" in text
    assert f"eps_p = {path.total:.3f}" in text and f"eps_vg {v.total:.3f}" in text


def test_standard_settings_the_old_check_refused_are_warned(tmp_path):
    """docs/machine_settings.md sec. 5, "The contact-ratio check of machine settings":
    the standard settings of the 16 mm blank (refused before by both checks: eps_p 0.703
    < 0.85, eps_vg 1.426 < 1.55) are accepted with a ContactRatioWarning, as they are
    about to be written (``settings=True``) and as read back (the pair cut from them);
    the prediction lies inside the range measured without a gap."""
    blank, path = _face_16(tmp_path)
    with pytest.warns(ContactRatioWarning) as got:
        check_generation(blank, settings=True)
    _names_fields_and_ratios(str(got[0].message), blank, path)
    # 0.703 > SETTINGS_GAP_RATIO: no pair measured that high had a gap
    assert path.total > SETTINGS_GAP_RATIO and "without a gap above" in str(got[0].message)
    settings = standard_machine_pair(blank, gear_generation="generated")
    with pytest.warns(ContactRatioWarning) as got:
        check_generation(settings)
    _names_fields_and_ratios(str(got[0].message), blank, path)


def _gapped(tmp_path, teeth: int, face: float, beta: float, depth: float):
    """A miter blank of ``teeth`` teeth (working depth factor ``depth``), its boxes, its
    predicted path and its standard settings; their TCA (the check bypassed, the edge
    tails followed as ``tca`` does, 61 phases, 3 neighbour pairs) raises ContactGap:
    the truth, measured here."""
    path_file = tmp_path / f"gapped_{teeth}.toml"
    path_file.write_text(MITER.format(face=face).replace("= 16\n", f"= {teeth}\n")
                         .replace("= 35.0", f"= {beta}")
                         .replace("gear_addendum_factor", f"working_depth_factor = {depth}\n"
                                  "gear_addendum_factor"))
    blank = load_pair(path_file)
    assert (blank.pinion_teeth, blank.pinion_spiral_angle_deg) == (teeth, beta)
    boxes = check_generation(blank, contact_ratio=False)
    path = path_contact_ratio(blank, boxes=boxes)
    settings = standard_machine_pair(blank, gear_generation=generation_of(boxes))
    prepared = prepare_pair(settings, checked=check_generation(settings, contact_ratio=False))
    with pytest.raises(ContactGap):
        analyze_pair(settings, phases=61, pairs=3, flanks=prepared.flank_set())
    return path_file, blank, path, settings


def test_a_pair_whose_settings_gap_is_refused(tmp_path, capsys):
    """A 12/12 miter at face 5 mm, beta 50 deg, working depth factor 1.3: the TCA of its
    standard settings has a gap (:func:`_gapped`); its blank's predicted eps_p (computed
    here by the path) is below SETTINGS_NO_GAP_RATIO, so ``design --machine-settings``
    refuses it (exit 2, before any settings are written), naming both fields with their
    values and the predicted ratio, and a pair cut from those settings is refused the
    same way."""
    path_file, blank, path, settings = _gapped(tmp_path, 12, 5.0, 50.0, 1.3)
    assert path.total < SETTINGS_NO_GAP_RATIO
    assert main(["design", "--pair", str(path_file), "--machine-settings",
                 "--out", str(tmp_path / "mach")]) == 2
    err = capsys.readouterr().err
    assert "design.gear_face_width_mm / design.pinion_spiral_angle_deg = (5.0, 50.0)" in err
    _names_fields_and_ratios(err, blank, path)
    assert not (tmp_path / "mach" / "machine_settings.toml").exists()
    with pytest.raises(InputRangeError) as refused:
        check_generation(settings)
    _names_fields_and_ratios(str(refused.value), blank, path)


@pytest.mark.slow
def test_a_gapped_pair_inside_the_uncertain_band_is_warned(tmp_path):
    """An 8/8 miter at face 6 mm, beta 45 deg: its standard settings' TCA has a gap
    (:func:`_gapped`), but its predicted eps_p lies where gap-free pairs were measured
    too (SETTINGS_NO_GAP_RATIO <= eps_p <= SETTINGS_GAP_RATIO): warned, the warning
    naming the fields, the ratios and that both were measured there; ``tca`` then
    refuses the mesh itself (ContactGap)."""
    _, blank, path, _ = _gapped(tmp_path, 8, 6.0, 45.0, 2.0)
    assert SETTINGS_NO_GAP_RATIO <= path.total <= SETTINGS_GAP_RATIO
    with pytest.warns(ContactRatioWarning) as got:
        check_generation(blank, settings=True)
    _names_fields_and_ratios(str(got[0].message), blank, path)
    assert "both with and without a gap" in str(got[0].message)


def test_the_cli_tca_of_the_warned_settings_has_no_gap(tmp_path, capsys):
    """The truth of the change, through the console commands: ``design
    --machine-settings`` on the 16 mm blank exits 0 (2 before) with the warning line,
    and ``tca`` (default options: 61 phases, edge contact followed, 3 neighbour pairs)
    on the written settings exits 0: its mesh has no gap (a ContactGap exits 2, "no
    tooth pair in contact"), at every phase at least one pair in contact."""
    path = _blank(tmp_path, 16.0)
    out = tmp_path / "mach"
    assert main(["design", "--pair", str(path), "--machine-settings", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "ContactRatioWarning" in err and "design.gear_face_width_mm = 16 mm" in err
    tca = tmp_path / "tca"
    assert main(["tca", "--pair", str(out / "machine_settings.toml"), "--out", str(tca),
                 "--quiet", "--no-figures"]) == 0
    summary = json.loads((tca / "tca.json").read_text())
    assert summary["phases_per_pitch"] == 61
    # one transmitting contact per phase, flank on flank ("surface") or an edge touching
    assert len(summary["phase_contact"]) == 61
