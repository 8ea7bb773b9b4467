"""``gearcontact design --machine-settings`` on a file typing only a gear cut with modified
roll, helical motion and curved blades, then ``gearcontact tca`` (issue 27; the pinion
of a typed gear, geometry.typed_pinion; docs/machine_settings.md sec. 5). The gear is
the generated 13/26 hypoid's standard gear (design_space.generated_hypoid) with the
terms of HYPOID_TERMS typed into its `[machine.gear.*]` / `[blade.gear.*]` tables: a
gear whose other settings agree with its blank, so that the typed-settings check on
load warns only about the added terms (the print's 10 x 41 gear typed as tables trips
the check's slip search, 60 to 80 CPU s per load before the slip screen, 0.5 s since;
the 13/26 file's 6 CPU s; docs sec. 2, "The cost of the slip search"). The last test
types F.2's generated spiral bevel gear with modified roll, whose pinion is fitted to
the gear's conjugate (geometry.typed_pinion_fit)."""

import dataclasses
import json
import math
import tomllib
import warnings

import numpy as np
import pytest
from design_space import generated_hypoid
from geometry.test_typed_pinion_motion import modified_gear

from gearcontact.cli import main
from gearcontact.geometry.basic_settings import standard_machine_pair
from gearcontact.geometry.machine import setup_to_tables
from gearcontact.geometry.pair import load_pair, pair_to_toml
from gearcontact.geometry.typed_pinion import typed_gear_machine_pair

#: Arcsec per radian.
ARCSEC = 180.0 * 3600.0 / math.pi
#: (settings, blade) changes per side; the blades' angles hold at the gear's mean depth
#: (h_f2 / cos(alpha), set in _gear_file).
HYPOID_TERMS = {
    "drive": (dict(modified_roll=(0.05, 0.2), helical_motion=(0.5, 1.0)),
              dict(profile_radius_mm=400.0)),
    "coast": (dict(modified_roll=(0.03, -0.1, 0.5, 1.0), helical_motion=(-0.5,)),
              dict(profile_radius_mm=-600.0, profile_cubic_per_mm2=0.0005,
                   profile_quartic_per_mm3=0.0001))}


def _quiet_load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the typed-settings check's notes
        return load_pair(path)


def _gear_file(path, changes) -> dict:
    """The generated 13/26 hypoid with its standard gear changed by ``changes``, typed
    alone (no pinion tables): ``path`` written; the typed gear's tables returned."""
    pair = standard_machine_pair(generated_hypoid(), gear_generation="generated")
    gear = {s.side: s for s in pair.machine if s.member == "gear"}
    changes = {side: (st, {"profile_reference_mm": pair.blank.dedendum_gear_mm / math.cos(
        math.radians(gear[side].blade.blade_angle_deg)), **bl} if bl else bl)
        for side, (st, bl) in changes.items()}
    gear = modified_gear(gear, changes)
    _write_gear_alone(path, pair, gear)
    return {side: setup_to_tables(g) for side, g in gear.items()}


def _write_gear_alone(path, pair, gear: dict) -> None:
    """``pair`` (cut from settings) written to ``path`` with ``gear`` in place of its
    gear and without its pinion's tables."""
    text = pair_to_toml(dataclasses.replace(pair, machine=tuple(
        gear[s.side] if s.member == "gear" else s for s in pair.machine)))
    kept, skip = [], False
    for line in text.splitlines():
        if line.startswith("["):
            skip = line.startswith(("[machine.pinion", "[blade.pinion"))
        if not skip:
            kept.append(line)
    path.write_text("\n".join(kept) + "\n")


@pytest.mark.parametrize("side", [
    "drive", pytest.param("coast", marks=pytest.mark.slow)])
def test_design_derives_the_pinion_of_a_modified_gear_and_tca_runs(side, tmp_path, capsys):
    # the written file keeps the gear's tables as typed (==, TOML values as read) and
    # its pinion is the library's (typed_gear_machine_pair on the typed gear, ==);
    # uncrowned, `gearcontact tca` (31 phases, 120 x 150 nodes) finds TE0 p-p within
    # 1e-4 arcsec (the conjugacy tolerance of test_design_typed_pinion.py) with no edge
    # phase (measured 2.9e-8 arcsec drive). One side by default: each `tca` load runs
    # the typed-settings check's slip search on the two gear flanks (~6 CPU s)
    typed = tmp_path / "gear.toml"
    tables = _gear_file(typed, HYPOID_TERMS)
    out = tmp_path / "out"
    assert main(["design", "--pair", str(typed), "--machine-settings",
                 "--lengthwise-crowning-um", "0", "--blade-profile-crowning-um", "0",
                 "--out", str(out)]) == 0
    written = out / "machine_settings.toml"
    with open(written, "rb") as f:
        doc = tomllib.load(f)
    for side, (machine, blade) in tables.items():
        assert doc["machine"]["gear"][side] == machine
        assert doc["blade"]["gear"][side] == blade
    got = _quiet_load(written)
    want = typed_gear_machine_pair(got, {s.side: s for s in got.machine if s.member == "gear"},
                                   lengthwise_crowning_um=0.0, blade_profile_crowning_um=0.0)
    assert got.machine == want.machine
    assert any(s.settings.modified_roll and s.settings.helical_motion
               for s in got.machine if s.member == "pinion")
    capsys.readouterr()
    run = tmp_path / f"tca_{side}"
    assert main(["tca", "--pair", str(written), "--out", str(run), "--side", side,
                 "--phases", "31", "--no-figures"]) == 0
    assert "not mates" not in capsys.readouterr().err
    result = json.loads((run / "tca.json").read_text())
    assert result["te0_pp_arcsec"] < 1e-4
    assert not result["edge_contact_phases"]


def test_a_careless_2c_is_named_by_design(tmp_path, capsys):
    # 2C = 50 /rad on the drive flank (the roll reverses after 0.02 rad): exit 2 naming
    # the gear's key and the value typed, and no file written (before: the settings were
    # written and `tca` failed 50 CPU s later at a pinion node, naming the pinion)
    typed = tmp_path / "gear.toml"
    _gear_file(typed, {"drive": (dict(modified_roll=(50.0,)), {})})
    out = tmp_path / "out"
    assert main(["design", "--pair", str(typed), "--machine-settings", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "machine.gear.drive.modified_roll_2c_per_rad = 50.0" in err
    assert not (out / "machine_settings.toml").exists()


def test_local_synthesis_on_a_modified_gear_is_refused_naming_the_term(tmp_path, capsys):
    # the synthesis' roll correction takes a linear-roll base pinion: a typed generated
    # gear with 2C is refused before any flank (exit 2) naming the gear's key and its
    # value; before, the synthesis ran and exited 4 with "no contact at the mean point"
    typed = tmp_path / "gear.toml"
    _gear_file(typed, {"drive": (dict(modified_roll=(0.05,)), {})})
    out = tmp_path / "out"
    assert main(["design", "--pair", str(typed), "--machine-settings", "--local-synthesis",
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "machine.gear.drive.modified_roll_2c_per_rad = 0.05" in err
    assert "--local-synthesis" in err
    assert not (out / "machine_settings.toml").exists()


def _designed_uncrowned_f2(tmp_path, changes):
    """``(gear, written, setups)``: F.2's generated gear with ``changes`` typed alone,
    through ``design --machine-settings`` uncrowned (exit 0 asserted); the typed gear,
    the written file and its set-ups ``{(member, side): MachineSetup}``."""
    pair = standard_machine_pair(load_pair("examples/iso23509_f2_spiral_bevel.toml"),
                                 gear_generation="generated")
    typed = tmp_path / "f2.toml"
    gear = modified_gear(pair, changes)
    _write_gear_alone(typed, pair, gear)
    out = tmp_path / "out"
    assert main(["design", "--pair", str(typed), "--machine-settings",
                 "--lengthwise-crowning-um", "0", "--blade-profile-crowning-um", "0",
                 "--out", str(out)]) == 0
    written = out / "machine_settings.toml"
    return gear, written, {(s.member, s.side): s for s in _quiet_load(written).machine}


@pytest.mark.slow
@pytest.mark.parametrize("side", ["drive", "coast"])
def test_a_spiral_bevel_gear_with_modified_roll_gets_a_conjugate_pinion(side, tmp_path):
    # F.2's generated gear with 2C = +-0.05 (drive / coast), typed alone: its
    # reversed-motion pinion is not conjugate (intersecting axes: the generating
    # surface's contact lines with gear and pinion cross only where its normal lies in
    # the plane of the axes; measured before: TE0 p-p 8.24 arcsec, the pinion tip on the
    # gear at 21 of 31 phases), so `design` fits the pinion to the gear's conjugate
    # (geometry.typed_pinion_fit, docs/machine_settings.md sec. 5). Truth (declared
    # before measuring): uncrowned, TE0 p-p of `gearcontact tca` (31 phases, 120 x 150
    # nodes) is at most the first-order bound (z1/z2)(max dpsi - min dpsi) over the
    # flank, dpsi the written pinion's residual angle against the typed gear's conjugate
    # (recomputed here on the written file, the target's spline error included), plus
    # 1e-4 arcsec (the TCA's conjugacy tolerance of this file); the residual within the
    # declared 2 um. Measured: drive 0.241 arcsec against a bound of 0.923, coast 0.129
    # against 0.975; residual max 0.121 / 0.137 um. The bound on the contact lines
    # (session 27, declared before measuring, docs sec. 5; exact nodes, the gear's active
    # box), recomputed here on the written file, with the same 1e-4 arcsec
    from gearcontact.geometry.kinked import machine_flank
    from gearcontact.geometry.typed_pinion_fit import (RESIDUAL_BOUND_UM, conjugate_target,
                                                       contact_line_bound_arcsec,
                                                       residual_angles, spline_error_rad)

    gear, written, setups = _designed_uncrowned_f2(tmp_path, {
        "drive": (dict(modified_roll=(0.05,)), {}), "coast": (dict(modified_roll=(-0.05,)), {})})
    got = _quiet_load(written)
    assert setups["gear", side] == gear[side]                   # the gear as typed
    target = conjugate_target(got, setups["gear", side])
    cut = machine_flank(setups["pinion", side], got.blank, face_width_mm=got.pinion_face_width_mm)
    u, v, d, dpsi = residual_angles(cut, target)
    assert np.abs(d).max() <= RESIDUAL_BOUND_UM
    bound = (got.pinion_teeth / got.gear_teeth) * (
        np.ptp(dpsi) + 2.0 * spline_error_rad(target)) * ARCSEC
    on_lines = contact_line_bound_arcsec(got, setups["pinion", side], target, cut)
    assert "pinion fitted to the typed gear's conjugate pinion" in written.read_text()
    run = tmp_path / "tca"
    assert main(["tca", "--pair", str(written), "--out", str(run),
                 "--side", side, "--phases", "31", "--no-figures"]) == 0
    te0_pp = json.loads((run / "tca.json").read_text())["te0_pp_arcsec"]
    assert te0_pp <= bound + 1e-4
    assert te0_pp <= on_lines + 1e-4


@pytest.mark.slow
def test_a_spiral_bevel_gear_with_helical_motion_gets_a_conjugate_pinion(tmp_path):
    # a helical motion V_1 = 3 mm/rad on F.2's generated drive gear, refused until session
    # 28 (3.297 um against the conjugate's quintic sheet, which is 5 um off its own exact
    # nodes at the toe-root corner; docs/machine_settings.md sec. 5, "Why V_1 = 3 was
    # refused"). Fitted to the exact conjugate, `design` writes the pinion (exit 0),
    # uncrowned; recomputed on the written file: the residual at exact meshing nodes
    # within the declared 2 um (measured 0.207 um) and `gearcontact tca` (31 phases,
    # 120 x 150 nodes) within the bound on the contact lines + 1e-4 arcsec (the TCA's
    # conjugacy tolerance; measured 0.1735 against 0.1870 arcsec)
    from gearcontact.geometry.kinked import machine_flank
    from gearcontact.geometry.typed_pinion_fit import (RESIDUAL_BOUND_UM, ExactConjugate,
                                                       conjugate_target,
                                                       contact_line_bound_arcsec,
                                                       residual_angles)

    _, written, setups = _designed_uncrowned_f2(
        tmp_path, {"drive": (dict(helical_motion=(3.0,)), {})})
    got = _quiet_load(written)
    target = conjugate_target(got, setups["gear", "drive"])
    cut = machine_flank(setups["pinion", "drive"], got.blank,
                        face_width_mm=got.pinion_face_width_mm)
    assert np.abs(residual_angles(cut, ExactConjugate(target))[2]).max() <= RESIDUAL_BOUND_UM
    on_lines = contact_line_bound_arcsec(got, setups["pinion", "drive"], target, cut)
    run = tmp_path / "tca"
    assert main(["tca", "--pair", str(written), "--out", str(run),
                 "--side", "drive", "--phases", "31", "--no-figures"]) == 0
    assert json.loads((run / "tca.json").read_text())["te0_pp_arcsec"] <= on_lines + 1e-4
