"""The top land of a member cut from machine settings along its tip line
(geometry.settings_top_land; docs/machine_settings.md sec. 5, "A pointed tooth from
settings").

Truths:
- an exactly conjugate pinion cut from settings (the complementary pinion of the formate
  gear, Litvin & Fuentes 2004 sec. 21.2: the generating surfaces of pinion and gear
  coincide) has the conjugate pinion's top land, measured by the other solver
  (generation.pinion_tip_top_lands: the gear's meshing equation, not the cutter's
  envelope); on issue 28's 9/32 blank without its ease-off both find it pointed at the toe;
- on the 16/16 at face 4 mm, beta 25 deg, the land is the one of the pinion flanks the
  node grid builds (spline sheets of exact node solves, evaluated on the tip line);
- the gear cut from settings: a formate gear from the blank's settings has the blank's
  gear land (generation.gear_tip_top_lands), a generated gear its node grid's;
- the workflow contract: ``design --machine-settings`` refuses that pointed pinion
  before writing, and ``tca`` on the settings it wrote before refuses it with the same
  error line, character for character.
"""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.geometry.basic_settings import complementary_pinion_setups, member_setups
from gearcontact.geometry.flank import right_hand_twin
from gearcontact.geometry.generated import generated_gear_flank, generated_pinion_flank
from gearcontact.geometry.generation import (_generation_boxes, check_generation,
                                             gear_tip_top_lands, pinion_tip_top_lands)
from gearcontact.geometry.pair import load_pair, pair_to_toml
from gearcontact.geometry.pair_tables import EaseOffCoefficients
from gearcontact.geometry.settings_top_land import (check_settings_top_land, member_boxes,
                                                    settings_tip_top_lands)
from gearcontact.geometry.typed_pinion import typed_gear_machine_pair
from gearcontact.validation import InputRangeError

from .test_generation import _POINTED_PINIONS, _unchecked_pair
from .test_machine_contact_ratio import MITER
from .test_tip_fold import _error_line, _old_settings

_EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _complementary(pair):
    """``pair`` cut from its formate gear's settings and the complementary pinion's (no
    crowning: exactly conjugate), without ease-off (the conjugate check's relief is 0)."""
    zero = EaseOffCoefficients()
    pair = dataclasses.replace(pair, easeoff_drive=zero, easeoff_coast=zero)
    gear, _ = member_setups(pair, "formate")
    pinion = complementary_pinion_setups(pair)
    return pair, dataclasses.replace(pair, machine=(gear["drive"], gear["coast"],
                                                    pinion["drive"], pinion["coast"]))


def test_complementary_pinion_has_the_conjugate_top_land():
    blank, cut = _complementary(_unchecked_pair(_POINTED_PINIONS["9/32"]))
    _, conj = pinion_tip_top_lands(blank, boxes=_generation_boxes(blank))
    boxes = member_boxes(cut, "pinion")
    # same stations: the two boxes share the blank's tip and lengthwise range
    conj_boxes = _generation_boxes(blank)
    for side in ("drive", "coast"):
        a, b = boxes[side]["active_box"], conj_boxes[side]["active_box"]
        assert (a.u_tip, a.v_toe, a.v_heel) == (b.u_tip, b.v_toe, b.v_heel)
    _, land = settings_tip_top_lands(cut, boxes=boxes)
    # both exact node solves (residual 1e-10 mm): 1e-8 mm leaves room for their
    # conditioning; measured 4.3e-14 mm. Not vacuous: the land spans -0.005 .. 0.44 mm
    assert land == pytest.approx(conj, abs=1e-8)
    assert land[0] < 0.0 < land[-1]
    with pytest.raises(InputRangeError) as err:
        check_settings_top_land(cut, boxes=boxes)
    assert "a pointed pinion tooth at the toe" in str(err.value)
    assert f"{land[0]:.4g} mm at 0.000 of the face" in str(err.value)


def _blank(tmp_path, beta_deg: float) -> Path:
    """crcheck's 16/16 miter (tests/geometry/test_machine_contact_ratio.py) at face 4 mm
    and spiral angle ``beta_deg``."""
    path = tmp_path / f"miter_4_{beta_deg:g}.toml"
    text = MITER.format(face=4.0).replace("pinion_spiral_angle_deg = 35.0",
                                          f"pinion_spiral_angle_deg = {beta_deg:g}")
    assert f"pinion_spiral_angle_deg = {beta_deg:g}" in text
    path.write_text(text)
    return path


def test_pointed_standard_pinion_is_the_node_grids(tmp_path):
    """The land of the 16/16 at face 4 mm, beta 25 deg, against the flanks the node grid
    builds (RadialSheet splines of a 24 x 41 grid of exact node solves, a margin beyond
    the box): the tip line evaluated on them, the coast point's depth behind the drive
    flank's tangent plane, the coast flank turned by the same pitch."""
    cut = _old_settings(_blank(tmp_path, 25.0))
    land, grid_land = _check_and_grid_lands(cut, "pinion")
    # 2 um: the grid's bicubic spline between nodes ~0.08 mm apart lengthwise and
    # ~0.45 mm up the profile (its interpolation error of the flank point; measured
    # 3.4e-5 mm)
    assert land == pytest.approx(grid_land, abs=2e-3)
    assert land[-1] < -0.5 and land[0] > 1.0      # pointed at the heel, not at the toe


def test_design_refuses_what_tca_refuses(tmp_path, capsys):
    blank_file = _blank(tmp_path, 25.0)
    out = tmp_path / "mach"
    assert main(["design", "--pair", str(blank_file), "--machine-settings",
                 "--out", str(out)]) == 2
    design_error = _error_line(capsys.readouterr().err, "design")
    assert not (out / "machine_settings.toml").exists()
    # the cause, named: both flanks' settings, the heel and where, the land, the fixes
    for word in ("[machine.pinion.drive] / [machine.pinion.coast] (blade point radii",
                 "a pointed pinion tooth at the heel", "at 1.000 of the face, v = ",
                 "design.gear_face_width_mm", "--lengthwise-crowning-um",
                 '"A pointed tooth from settings"'):
        assert word in design_error
    written = tmp_path / "machine_settings.toml"
    written.write_text(pair_to_toml(_old_settings(blank_file)))
    assert main(["tca", "--pair", str(written), "--out", str(tmp_path / "tca")]) == 2
    assert _error_line(capsys.readouterr().err, "tca") == design_error


def test_shipped_settings_keep_a_top_land():
    """The shipped settings pass (nothing refused that ran before): the F.2 example's
    settings and the standard pinion `design --machine-settings` derives for the typed
    gear of the 10 x 41 print (both files of examples/machine_settings/); measured
    smallest lands 1.037 and 1.143 mm, both at the toe. s0003's standard settings:
    test_basic_settings (0.092 mm at the toe)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        f2 = load_pair(_EXAMPLES / "machine_settings" / "iso23509_f2_machine.toml")
        typed = load_pair(_EXAMPLES / "machine_settings" / "hypoid_10x41_print_gear.toml",
                          gear_alone=True)
    check_generation(f2, contact_ratio=False)
    assert check_settings_top_land(f2) > 0.5
    derived = typed_gear_machine_pair(typed)      # runs the check before it returns
    assert check_settings_top_land(right_hand_twin(derived)) > 0.5


# ----------------------------------------------------------------------- gear top land
def test_formate_gear_from_settings_has_the_blanks_gear_top_land():
    """The formate gear cut from the blank's standard gear settings is the blank's formate
    gear (the settings' blade cones, :func:`~.generated.formate_gear_flank`, against the
    blank's cutter placement, generation.gear_tip_top_lands): with a cutter point width
    1.5 mm wider than F.2's its toe is pointed, and the settings check refuses it there
    with the same land."""
    blank = load_pair(_EXAMPLES / "iso23509_f2_spiral_bevel.toml")
    wide = dataclasses.replace(blank, cutter=dataclasses.replace(
        blank.cutter, point_width_mm=blank.cutter.point_width_mm + 1.5))
    _, conj = gear_tip_top_lands(wide)
    gear, _ = member_setups(wide, "formate")
    pinion = complementary_pinion_setups(wide)     # a pair holds all four (not measured)
    cut = dataclasses.replace(wide, machine=(gear["drive"], gear["coast"],
                                             pinion["drive"], pinion["coast"]))
    _, land = settings_tip_top_lands(cut, member="gear")
    # the same cones by two constructions: 1e-8 mm (measured 3.3e-14 on F.2 itself)
    assert land == pytest.approx(conj, abs=1e-8)
    assert land[0] < 0.0 < land[-1]          # pointed at the toe: not vacuous
    with pytest.raises(InputRangeError) as err:
        check_settings_top_land(cut, member="gear")
    assert "[machine.gear.drive] / [machine.gear.coast]" in err.value.field
    assert "a pointed gear tooth at the toe" in str(err.value)


def test_generated_gear_top_land_is_the_node_grids():
    """The generated gear of the 10 x 41 print (its ratio of roll 0.998: not formate),
    against the flanks its node grid builds (GearSheet splines of 24 x 41 exact nodes)
    evaluated on the tip line, as the pinion's above."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        typed = load_pair(_EXAMPLES / "machine_settings" / "hypoid_10x41_print_gear.toml",
                          gear_alone=True)
    cut = right_hand_twin(typed_gear_machine_pair(typed))
    assert "solver" in member_boxes(cut, "gear")["drive"]   # the envelope, not formate
    land, grid_land = _check_and_grid_lands(cut, "gear")
    # 2 um as the pinion's (spline interpolation; measured 2.2e-10 mm)
    assert land == pytest.approx(grid_land, abs=2e-3)
    assert land.min() > 2.0                   # measured 2.28 mm at the toe


def _check_and_grid_lands(cut, member: str) -> tuple[np.ndarray, np.ndarray]:
    """The check's land of ``member`` along its tip line, and the normal top land at the
    same stations (the same fractions of each box's lengthwise range, the box's tip) on
    the spline flanks built on a 24 x 41 exact node grid: the coast point's depth behind
    the drive flank's tangent plane, the coast flank turned about the member axis (x:
    pinion, z: gear) by the multiple of the pitch, 0 or +-1, that puts their middles
    behind each other's normal with the smallest gap (one tooth, not a slot)."""
    boxes = member_boxes(cut, member)
    frac, land = settings_tip_top_lands(cut, member=member, boxes=boxes)
    setups = {s.side: s for s in cut.machine if s.member == member}
    if member == "pinion":
        axis, teeth = 0, cut.pinion_teeth
        build = lambda setup: generated_pinion_flank(   # noqa: E731
            setup, cut.blank, n_u=24, n_v=41, pinion_face_width_mm=cut.pinion_face_width_mm)
    else:
        axis, teeth = 2, cut.gear_teeth
        build = lambda setup: generated_gear_flank(     # noqa: E731
            setup, cut.blank, n_u=24, n_v=41, gear_face_width_mm=cut.gear_face_width_mm)
    tip, mid = {}, {}
    for side in ("drive", "coast"):
        box, flank = boxes[side]["active_box"], build(setups[side])[0]
        vs = box.v_toe + frac * (box.v_heel - box.v_toe)
        s = flank.evaluate(np.full_like(vs, box.u_tip), vs, second=False)
        tip[side] = s.r, s.n
        m = flank.evaluate(np.array([0.5 * sum(flank.u_range)]),
                           np.array([0.5 * sum(flank.v_range)]), second=False)
        mid[side] = m.r[0], m.n[0]
    (md, mnd), (mc, mnc) = mid["drive"], mid["coast"]
    b, c = [i for i in range(3) if i != axis]
    best = None
    for k in (0, 1, -1):
        a = 2.0 * np.pi * k / teeth
        rot = np.eye(3)
        rot[b, b], rot[b, c], rot[c, b], rot[c, c] = np.cos(a), -np.sin(a), np.sin(a), np.cos(a)
        rc_k, nc_k = mc @ rot.T, mnc @ rot.T
        if mnd @ (rc_k - md) < 0.0 and nc_k @ (md - rc_k) < 0.0:
            gap = np.linalg.norm(md - rc_k)
            if best is None or gap < best[0]:
                best = (gap, rot)
    (rd, nd), rc = tip["drive"], tip["coast"][0]
    return land, -np.einsum("ni,ni->n", rc @ best[1].T - rd, nd)
