"""The contact-ratio check of a pair cut from machine settings agrees with its blank's
(geometry.contact_ratio; docs/machine_settings.md sec. 5, "Ordinary pairs, measured"),
and ``design --machine-settings`` refuses exactly the settings whose mesh has a gap
(tca.settings_gap; sec. 5, "The settings' own TCA in `design`").

The truth is the workflow's own contract, not a number of this code: the settings that
``design --machine-settings`` writes for a blank that ``design`` accepts are accepted by
every command that reads them (before: the 16/16 miter below, eps_vg 1.528 < 1.55, was
refused by ``tca`` and ``analyze`` though its blank passed, and the TCA of its settings
with the check bypassed ran without a gap: 1.39 pairs in contact, 24 of 61 phases two).
Where the blank's predicted path is short ``design`` runs the settings' TCA: the
settings it writes are those on which the console ``tca`` (default options) finds no
gap, and those it refuses are those on which the TCA with ``tca``'s options, run here
apart, raises ContactGap.
"""

from __future__ import annotations

import json
import math
import warnings

import pytest

from gearcontact.cli import main
from gearcontact.geometry.basic_settings import standard_machine_pair
from gearcontact.geometry.contact_path import path_contact_ratio
from gearcontact.geometry.contact_ratio import (MIN_CONTACT_RATIO, MIN_VIRTUAL_CONTACT_RATIO,
                                                SETTINGS_GAP_RATIO, ContactRatioWarning,
                                                virtual_contact_ratio)
from gearcontact.geometry.gear_generation import generation_of
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair
from gearcontact.geometry.pair import pair_to_toml
from gearcontact.tca import settings_gap
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


def _written_without_tca(tmp_path, capsys, monkeypatch, pair: str):
    """``design --machine-settings`` on ``pair``, whose predicted eps_p (computed here by
    the path) reaches MIN_CONTACT_RATIO, writes its settings (exit 0) without running the
    settings' TCA (a TCA run here fails the test); returns the pair written."""
    blank = load_pair(pair)
    predicted = path_contact_ratio(blank, boxes=check_generation(blank, contact_ratio=False))
    assert predicted.total >= MIN_CONTACT_RATIO

    def no_tca(*args, **kwargs):
        raise AssertionError("the settings' TCA ran")

    monkeypatch.setattr(settings_gap, "settings_mesh_gap", no_tca)
    out = tmp_path / "mach"
    assert main(["design", "--pair", pair, "--machine-settings", "--out", str(out)]) == 0
    assert "the TCA of the settings" not in capsys.readouterr().err
    written = load_pair(out / "machine_settings.toml")
    assert written.machine
    return written


def test_written_settings_of_an_accepted_blank_are_accepted(tmp_path, capsys, monkeypatch):
    """design accepts the blank and writes its settings (exit 0); the closed form alone
    would refuse them (precondition, ISO 10300-1 by hand in test_contact_ratio.py); the
    commands' check of the written file passes now, with the blank's path ratio. The
    blank's predicted eps_p reaches MIN_CONTACT_RATIO (computed here by the path), so
    ``design`` runs no TCA of the settings: an ordinary pair pays nothing (a TCA run
    here fails the test)."""
    path = _blank(tmp_path, 20.0)
    written = _written_without_tca(tmp_path, capsys, monkeypatch, str(path))
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
    """The message names both fields with their values, the predicted eps_p (the blank's
    path, computed independently by the caller) and the closed form's eps_vg."""
    v = virtual_contact_ratio(blank.blank, gear_face_width_mm=blank.gear_face_width_mm,
                              side="drive")
    assert (f"design.gear_face_width_mm = {blank.gear_face_width_mm:g} mm" in text
            or "design.gear_face_width_mm / design.pinion_spiral_angle_deg = "
            f"({blank.gear_face_width_mm}, {blank.pinion_spiral_angle_deg})" in text)
    assert f"eps_p = {path.total:.3f}" in text and f"eps_vg {v.total:.3f}" in text


def test_settings_read_with_a_short_prediction_are_warned(tmp_path):
    """docs/machine_settings.md sec. 5: a pair cut from the 16 mm blank's standard
    settings (eps_p 0.703 < 0.85, eps_vg 1.426 < 1.55; refused before by both checks) is
    read with a ContactRatioWarning naming both fields and the ratios; the prediction
    lies above every gap measured on the family."""
    blank, path = _face_16(tmp_path)
    settings = standard_machine_pair(blank, gear_generation="generated")
    with pytest.warns(ContactRatioWarning) as got:
        boxes = check_generation(settings)
    text = str(got[0].message)
    _names_fields_and_ratios(text, blank, path)
    assert f"design.pinion_spiral_angle_deg = {blank.pinion_spiral_angle_deg:g} deg" in text
    # 0.703 > SETTINGS_GAP_RATIO: no pair measured that high had a gap
    assert path.total > SETTINGS_GAP_RATIO and "without a gap above" in str(got[0].message)
    # what is predicted and how to check: the TCA that decides
    assert "runs no TCA of the pair; `gearcontact tca --pair FILE`" in text
    # a reader whose TCA follows (prepare_pair: every command with a mesh) is not warned
    # (its TCA refuses a gap: test_a_pair_whose_settings_gap_is_refused), the same boxes
    with warnings.catch_warnings():
        warnings.simplefilter("error", ContactRatioWarning)
        quiet = check_generation(settings, mesh_follows=True)
    assert ({side: got["active_box"] for side, got in quiet.items()}
            == {side: got["active_box"] for side, got in boxes.items()})


def _gapped_blank(tmp_path, teeth: int, face: float, beta: float, depth: float,
                  easeoff: str = ""):
    """The file of a miter blank of ``teeth`` teeth (working depth factor ``depth``),
    ``easeoff`` (TOML tables) appended."""
    path_file = tmp_path / f"gapped_{teeth}.toml"
    path_file.write_text(MITER.format(face=face).replace("= 16\n", f"= {teeth}\n")
                         .replace("= 35.0", f"= {beta}")
                         .replace("gear_addendum_factor", f"working_depth_factor = {depth}\n"
                                  "gear_addendum_factor") + easeoff)
    return path_file


def _gapped(tmp_path, teeth: int, face: float, beta: float, depth: float):
    """A miter blank of ``teeth`` teeth (working depth factor ``depth``), its boxes, its
    predicted path, its standard settings and the ContactGap their TCA raises with
    ``tca``'s options (the check bypassed, the edge tails followed, 61 phases, 3
    neighbour pairs): the truth, measured here apart from ``design``. The gap's width
    is counted again at 121 phases on the same flanks: the two counts measure one
    interval of the pitch, each to within one phase step either side, so their shares of
    the pitch differ by less than the sum of the steps (1/60 + 1/120)."""
    path_file = _gapped_blank(tmp_path, teeth, face, beta, depth)
    blank = load_pair(path_file)
    assert (blank.pinion_teeth, blank.pinion_spiral_angle_deg) == (teeth, beta)
    boxes = check_generation(blank, contact_ratio=False)
    path = path_contact_ratio(blank, boxes=boxes)
    settings = standard_machine_pair(blank, gear_generation=generation_of(boxes))
    prepared = prepare_pair(settings, checked=check_generation(settings, contact_ratio=False))
    flanks = prepared.flank_set()
    gaps = {}
    for phases in (61, 121):
        with pytest.raises(ContactGap) as gap:
            analyze_pair(settings, phases=phases, pairs=3, flanks=flanks)
        gaps[phases] = gap.value
    assert gaps[61].phases_per_pitch == 60 and gaps[121].phases_per_pitch == 120
    assert gaps[61].gap_phases > 0
    assert abs(gaps[61].gap_phases / 60 - gaps[121].gap_phases / 120) < 1 / 60 + 1 / 120
    return path_file, blank, path, settings, gaps[61]


def _refused_by_design(tmp_path, capsys, path_file, blank, path, gap, *extra) -> str:
    """``design --machine-settings`` refuses the blank (exit 2, nothing written), naming
    both fields with their values, the predicted ratios and the gap the separate TCA
    measured (its phase steps of the pitch); returns its stderr."""
    out = tmp_path / "mach"
    assert main(["design", "--pair", str(path_file), "--machine-settings", *extra,
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert ("design.gear_face_width_mm / design.pinion_spiral_angle_deg = "
            f"({blank.gear_face_width_mm}, {blank.pinion_spiral_angle_deg})") in err
    _names_fields_and_ratios(err, blank, path)
    assert f"on {gap.gap_phases} of 60 phase steps" in err
    assert f"({gap.gap_phases / 60:.1%} of a pitch" in err
    assert not (out / "machine_settings.toml").exists()
    return err


def test_a_pair_whose_settings_gap_is_refused(tmp_path, capsys):
    """A 12/12 miter at face 5 mm, beta 50 deg, working depth factor 1.3: the TCA of its
    standard settings has a gap (:func:`_gapped`), and ``design --machine-settings``
    refuses it before writing, naming the gap; a pair cut from those settings is read
    with a warning (its own TCA refuses the gap, as above)."""
    path_file, blank, path, settings, gap = _gapped(tmp_path, 12, 5.0, 50.0, 1.3)
    assert path.total < MIN_CONTACT_RATIO
    _refused_by_design(tmp_path, capsys, path_file, blank, path, gap)
    with pytest.warns(ContactRatioWarning) as got:
        check_generation(settings)
    _names_fields_and_ratios(str(got[0].message), blank, path)
    # the settings typed into a file: `tca` refuses them with the gap the TCA above
    # measured (exit 2, the same first phase), with no prediction warning before it
    typed = tmp_path / "typed_12x12.toml"
    typed.write_text(pair_to_toml(settings))
    assert main(["tca", "--pair", str(typed), "--out", str(tmp_path / "t"), "--quiet",
                 "--no-figures"]) == 2
    err = capsys.readouterr().err
    assert f"no tooth pair in contact at phi1 = {math.degrees(gap.phi1_rad):.4f} deg" in err
    assert "ContactRatioWarning" not in err


@pytest.mark.slow
def test_a_gapped_pair_the_old_bound_warned_is_refused(tmp_path, capsys):
    """An 8/8 miter at face 6 mm, beta 45 deg (eps_p 0.376, above the old bound 0.303:
    warned and written before): its standard settings' TCA has a gap (:func:`_gapped`),
    and ``design --machine-settings`` now refuses it."""
    path_file, blank, path, _, gap = _gapped(tmp_path, 8, 6.0, 45.0, 2.0)
    assert 0.303 <= path.total < MIN_CONTACT_RATIO
    _refused_by_design(tmp_path, capsys, path_file, blank, path, gap)


@pytest.mark.slow
def test_a_kept_gear_whose_pinion_gaps_is_refused(tmp_path, capsys):
    """The typed-gear path: the 12/12's standard settings typed into a pair file and
    ``design --machine-settings --keep-gear`` on it (the typed gear kept, its standard
    pinion: the same settings, the TCA of :func:`_gapped` has a gap) is refused alike."""
    _, blank, path, settings, gap = _gapped(tmp_path, 12, 5.0, 50.0, 1.3)
    typed = tmp_path / "typed_12x12.toml"
    typed.write_text(pair_to_toml(settings))
    _refused_by_design(tmp_path, capsys, typed, blank, path, gap, "--keep-gear")


def test_the_cli_tca_of_the_written_settings_has_no_gap(tmp_path, capsys):
    """The truth of the check where it passes, through the console commands: ``design
    --machine-settings`` on the 16 mm blank (predicted eps_p 0.703 < 0.85: its settings'
    TCA runs) exits 0, its line saying the settings' TCA has no gap and no
    ContactRatioWarning; ``tca`` (default options: 61 phases, edge contact followed, 3
    neighbour pairs) on the written settings exits 0: its mesh has no gap (a ContactGap
    exits 2, "no tooth pair in contact"), at every phase at least one pair in
    contact."""
    _, predicted = _face_16(tmp_path)       # the blank's eps_p, by the path itself
    path = tmp_path / "miter_16.toml"
    out = tmp_path / "mach"
    assert main(["design", "--pair", str(path), "--machine-settings", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "ContactRatioWarning" not in err
    assert (f"eps_p = {predicted.total:.3f} < {MIN_CONTACT_RATIO:g}: the TCA of the settings "
            "(61 phases") in err
    assert "has no gap" in err
    tca = tmp_path / "tca"
    assert main(["tca", "--pair", str(out / "machine_settings.toml"), "--out", str(tca),
                 "--quiet", "--no-figures"]) == 0
    # read without the prediction's warning: tca's own TCA decided (no gap)
    assert "ContactRatioWarning" not in capsys.readouterr().err
    summary = json.loads((tca / "tca.json").read_text())
    assert summary["phases_per_pitch"] == 61
    # one transmitting contact per phase, flank on flank ("surface") or an edge touching
    assert len(summary["phase_contact"]) == 61


#: A crowned drive-side ease-off typed on the 12/12 (profile 4 um/mm^2, lengthwise 0.5
#: um/mm^2, vertex at the box centre): ``design --machine-settings`` takes the ease-off
#: fit path (geometry.easeoff_settings) for it.
CROWNED_DRIVE = """
[easeoff.drive]
profile_angle_um_per_mm = 0.0
spiral_angle_um_per_mm = 0.0
profile_crowning_um_per_mm2 = 4.0
lengthwise_crowning_um_per_mm2 = 0.5
bias_um_per_mm2 = 0.0
"""


@pytest.mark.slow
def test_an_easeoff_whose_settings_gap_is_refused(tmp_path, capsys):
    """The ease-off fit path (docs/machine_settings.md sec. 6): the 12/12 miter of
    :func:`test_a_pair_whose_settings_gap_is_refused` with a crowned drive ease-off
    (its predicted eps_p, computed here by the path with that ease-off, below 0.85). The
    truth, run apart: the settings that cut the ease-off
    (:func:`~gearcontact.geometry.easeoff_settings.easeoff_machine_pair`, ``design``'s
    own fit) and their TCA with ``tca``'s options raise ContactGap. ``design
    --machine-settings`` refuses the blank as the standard path does (exit 2, nothing
    written), naming the gap's phase steps and its first phase, to the message's four
    decimals (the same flanks and phases: the same numbers). Before, it wrote the
    settings and ``tca`` refused them with that gap."""
    from gearcontact.geometry.easeoff_settings import easeoff_machine_pair

    path_file = _gapped_blank(tmp_path, 12, 5.0, 50.0, 1.3, CROWNED_DRIVE)
    blank = load_pair(path_file)
    assert blank.easeoff_tables and blank.design_side == "drive"
    boxes = check_generation(blank, contact_ratio=False)
    path = path_contact_ratio(blank, boxes=boxes)
    assert path.total < MIN_CONTACT_RATIO
    settings = easeoff_machine_pair(blank).pair
    prepared = prepare_pair(settings, checked=check_generation(settings, contact_ratio=False))
    with pytest.raises(ContactGap) as gap:
        analyze_pair(settings, phases=61, pairs=3, flanks=prepared.flank_set())
    assert gap.value.gap_phases > 0
    err = _refused_by_design(tmp_path, capsys, path_file, blank, path, gap.value)
    assert f"from phi1 = {math.degrees(gap.value.phi1_rad):.4f} deg" in err


def test_local_synthesis_of_the_gapped_blank_is_refused_first(tmp_path, capsys):
    """``design --machine-settings --local-synthesis`` on the 12/12 miter: the blank's
    own contact-ratio check (the synthesis' first-order bearing at its default targets,
    geometry.generation) refuses it before any synthesis or settings TCA (exit 2, no
    file written), naming the teeth and the eps_p the path gives here apart."""
    path_file = _gapped_blank(tmp_path, 12, 5.0, 50.0, 1.3)
    blank = load_pair(path_file)
    path = path_contact_ratio(blank, boxes=check_generation(blank, contact_ratio=False))
    assert path.total < MIN_CONTACT_RATIO
    out = tmp_path / "local"
    assert main(["design", "--pair", str(path_file), "--machine-settings",
                 "--local-synthesis", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "teeth.pinion / teeth.gear = (12, 12)" in err
    assert f"eps_p = {path.total:.3f}" in err and "the TCA of the settings" not in err
    assert not out.exists() or not any(out.iterdir())


def test_an_ordinary_easeoff_fit_runs_no_tca(tmp_path, capsys, monkeypatch):
    """s0003's ease-off fit (its coast ease-off, eps_p computed here by the path, above
    0.85) runs no settings TCA (a TCA run here fails the test) and writes its settings."""
    _written_without_tca(tmp_path, capsys, monkeypatch, "s0003")


def test_synthesized_easeoff_refusal_says_no_angle_is_reachable(tmp_path, capsys):
    """``design --synthesize-easeoff`` on the 12/12 miter: no path angle is reachable
    (``overlap_path_angle``'s NaN), and the refusal says so in words; no NaN is printed
    (found by a careless-user run, session 25)."""
    path_file = _gapped_blank(tmp_path, 12, 5.0, 50.0, 1.3)
    assert main(["design", "--pair", str(path_file), "--synthesize-easeoff"]) == 2
    err = capsys.readouterr().err
    assert "no path angle reachable" in err and "nan" not in err.lower()
