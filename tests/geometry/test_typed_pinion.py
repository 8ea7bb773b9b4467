"""The standard pinion of a typed gear (geometry.typed_pinion; issue 27, the pinion of a
gear typed as settings or as a print's page).

Truths, declared before measuring (docs/machine_settings.md sec. 5, "The pinion of a
typed gear"):

(a) a gear typed with exactly the blank's own standard settings gives the blank's
    standard pinion (basic_settings.standard_setups): the same construction with the
    typed cutter in place of the blank's, so equal to float rounding;
(b) on the published 10 x 41 print's gear (tests/geometry/summary_sheets/README.md) the
    derived pair is a pair of mates: no MateWarning (normals at the pinion's mean node
    within MATE_NORMAL_TOL_DEG, 1 deg); the tighter bound of the mates measured so far,
    0.04 deg (the 13/26 hypoid's crown-gear pinion, docs sec. 5), is not met (strict
    xfail below, measured 0.046 / 0.093 deg);
(c) uncrowned, the pinion is conjugate to the typed gear: TE0 = 0 wherever the contact
    is flank on flank, within the 1e-4 arcsec of the existing conjugacy tests
    (test_basic_settings.py::test_crown_pinion_of_a_hypoid_is_a_point_contact_conjugate,
    40 x 50 nodes).
"""

import dataclasses
import tomllib
import warnings

import numpy as np
import pytest
from design_space import generated_hypoid

from gearcontact.geometry.basic_settings import standard_setups
from gearcontact.geometry.flank import (MATE_NORMAL_TOL_DEG, MateWarning, build_flanks,
                                        right_hand_twin)
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.generated import generated_pinion_flank, mean_contact_guess
from gearcontact.geometry.pair import load_pair, pair_to_toml, parse_pair
from gearcontact.geometry.typed_pinion import typed_gear_machine_pair
from gearcontact.validation import InputRangeError

F2 = "examples/iso23509_f2_spiral_bevel.toml"
PRINT = "tests/geometry/summary_sheets/hypoid_10x41_no16_pair.toml"


def _quiet_load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's blank note
        return load_pair(path)


@pytest.fixture(scope="module")
def print_pair():
    return _quiet_load(PRINT)


def _gear(pair) -> dict:
    return {s.side: s for s in pair.machine if s.member == "gear"}


def _floats(obj) -> dict:
    return {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)
            if isinstance(getattr(obj, f.name), float)}


@pytest.mark.parametrize("case", ["f2", "generated_hypoid", "print_blank"])
def test_the_blanks_own_gear_typed_gives_the_standard_pinion(case, print_pair):
    # (a): the formate F.2 gear (complementary pinion), the generated 13/26 hypoid gear
    # (the crown gear's pinion) and the 10 x 41 print's blank (left hand: the twin's
    # pinion mirrored). The gear kept as given (==); every pinion setting within 1e-12
    # (mm, deg, ratio: two orders of the same float operations, measured <= 2.9e-14);
    # the right-hand pinions' exact envelope nodes (8 x 10) within 1e-12 mm (node
    # solves to 1e-13 steps on settings equal to 3e-14)
    pair, generation = {
        "f2": lambda: (load_pair(F2), "formate"),
        "generated_hypoid": lambda: (generated_hypoid(), "generated"),
        "print_blank": lambda: (dataclasses.replace(print_pair, machine=(), print_gear=()),
                                "formate")}[case]()
    std = standard_setups(pair, gear_generation=generation)
    cut = typed_gear_machine_pair(pair, {s: std["gear", s] for s in SIDES})
    got = {(s.member, s.side): s for s in cut.machine}
    for side in SIDES:
        assert got["gear", side] == std["gear", side]
        a, b = got["pinion", side], std["pinion", side]
        assert a.blade.kind == b.blade.kind
        for x, y in ((a.settings, b.settings), (a.blade, b.blade)):
            fx, fy = _floats(x), _floats(y)
            assert max(abs(fx[k] - fy[k]) for k in fx) < 1e-12
        if pair.pinion_hand == "right":
            _, n_a = generated_pinion_flank(a, pair.blank, n_u=8, n_v=10,
                                            pinion_face_width_mm=pair.pinion_face_width_mm)
            _, n_b = generated_pinion_flank(b, pair.blank, n_u=8, n_v=10,
                                            pinion_face_width_mm=pair.pinion_face_width_mm)
            assert n_a.x_mm.size == 3 * 8 * 10
            assert np.abs(n_a.x_mm - n_b.x_mm).max() < 1e-12


def test_the_typed_gear_is_kept_and_written_as_typed(print_pair):
    # the print's gear stays exactly as loaded from [print.gear] and is written back as
    # the [print.gear] table typed (TOML values compared as read); the written pair
    # reads back with the same gear and pinion (floats at full precision: ==)
    cut = typed_gear_machine_pair(print_pair, _gear(print_pair))
    assert tuple(s for s in cut.machine if s.member == "gear") == tuple(
        s for s in print_pair.machine if s.member == "gear")
    text = pair_to_toml(cut)
    doc = tomllib.loads(text)
    with open(PRINT, "rb") as f:
        assert doc["print"]["gear"] == tomllib.load(f)["print"]["gear"]
    assert "gear" not in doc.get("machine", {})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        back = parse_pair(doc, name=cut.name)
    assert back.machine == cut.machine
    # and the pinion is another than the shipped one (the blank's formate gear's)
    assert _gear(back) == _gear(print_pair)
    assert [s for s in back.machine if s.member == "pinion"] != [
        s for s in print_pair.machine if s.member == "pinion"]


def test_a_gear_typed_alone_is_read_only_where_asked(tmp_path, print_pair):
    # the page without the pinion tables: refused by default, naming the pinion's tables
    # and the command that derives them; read with gear_alone, its gear the shipped
    # file's (==) and the derived pair the same as from the shipped file's gear (==)
    text = open(PRINT).read()
    path = tmp_path / "page.toml"
    path.write_text(text[:text.index("[machine.pinion.drive]")])
    with pytest.raises(InputRangeError, match=r"\[machine\.pinion\.drive\].*design "
                                              r"--machine-settings"):
        _quiet_load(path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        alone = load_pair(path, gear_alone=True)
    assert not alone.machine
    assert {s.side: s for s in alone.typed_gear} == _gear(print_pair)
    assert typed_gear_machine_pair(alone).machine == typed_gear_machine_pair(
        print_pair).machine


def _nearest_touch_deg(cut) -> dict:
    twin = right_hand_twin(cut)
    flanks = build_flanks(twin, n_u=20, n_v=24)
    out = {}
    for side in SIDES:
        m = flanks.mean_contact[side]
        out[side] = mean_contact_guess(flanks.pinion.side(side), flanks.gear.side(side),
                                       twin.kinematics(with_errors=False),
                                       pinion_uv=m["pinion_uv"],
                                       gear_uv=m["gear_uv"])["normal_angle_deg"]
    return out


def test_the_prints_gear_and_its_derived_pinion_are_mates(print_pair):
    # (b): no MateWarning when the flanks are built (the warning's own bound,
    # MATE_NORMAL_TOL_DEG = 1 deg), both sides (measured 0.046 / 0.093 deg, 20 x 24
    # nodes); the shipped file's pinion (the blank's) leaves 2.60 / 2.96 deg
    # (test_mate_check.py)
    cut = typed_gear_machine_pair(print_pair, _gear(print_pair))
    with warnings.catch_warnings():
        warnings.simplefilter("error", MateWarning)
        build_flanks(cut, n_u=20, n_v=24)
    angles = _nearest_touch_deg(cut)
    assert max(angles.values()) < MATE_NORMAL_TOL_DEG


@pytest.mark.xfail(strict=True, reason=(
    "differs: the normals at the pinion's mean node are 0.046 / 0.093 deg apart "
    "(drive / coast) against the 0.04 deg measured on the 13/26 hypoid's crown-gear "
    "pinion: the derived pinion is a point-contact conjugate whose TE0 = 0 path passes "
    "about 1.2 mm (drive, below the node) and 4 mm (coast, above it) from the mean node "
    "along the profile (gearcontact tca, 120 x 150 nodes), farther than on the 13/26 "
    "hypoid (0.68 / 2.30 mm); docs/machine_settings.md sec. 5"))
def test_the_prints_pair_within_the_measured_mates_bound(print_pair):
    angles = _nearest_touch_deg(typed_gear_machine_pair(print_pair, _gear(print_pair)))
    assert max(angles.values()) < 0.04


@pytest.mark.parametrize("side", SIDES)
def test_the_uncrowned_pinion_is_conjugate_to_the_prints_gear(side, print_pair):
    # (c): TCA (tca.analysis.analyze_pair, edge contact on as gearcontact tca runs it,
    # 31 phases) of the print's generated gear with the uncrowned derived pinion,
    # 40 x 50 nodes: TE0 = 0 to 1e-4 arcsec at every phase whose contact is flank on
    # flank (at least 8 of them; measured 1.7e-7 / 4.2e-8 arcsec, all 31 phases flank on
    # flank). Not vacuous: the default crowning gives 24.0 / 10.3 arcsec p-p (docs sec. 5)
    te = uncrowned_te0_on_flank(print_pair, _gear(print_pair), side)
    assert te.size >= 8
    assert np.abs(te).max() < 1e-4


def uncrowned_te0_on_flank(pair, gear: dict, side: str) -> np.ndarray:
    """TE0 (arcsec) at the flank-on-flank phases of the TCA (tca.analysis.analyze_pair,
    edge contact on as gearcontact tca runs it, 31 phases, 40 x 50 nodes) of the typed
    ``gear`` with its uncrowned derived pinion."""
    from gearcontact.tca.analysis import analyze_pair

    cut = typed_gear_machine_pair(pair, gear, lengthwise_crowning_um=0.0,
                                  blade_profile_crowning_um=0.0)
    flanks = build_flanks(cut, n_u=40, n_v=50)
    result, _ = analyze_pair(cut, side=side, phases=31, flanks=flanks)
    te = np.asarray(result.cycle.envelope_arcsec, dtype=float)
    return te[np.array([not mp.edge_contact for mp in result.cycle.contact])]


def test_crowning_out_of_range_is_refused_before_any_work(print_pair):
    with pytest.raises(InputRangeError, match="lengthwise_crowning_um"):
        typed_gear_machine_pair(print_pair, _gear(print_pair), lengthwise_crowning_um=-1.0)
    with pytest.raises(InputRangeError, match="blade_profile_crowning_um"):
        typed_gear_machine_pair(print_pair, _gear(print_pair), blade_profile_crowning_um=201.0)


def test_a_typed_formate_gear_gets_its_line_contact_conjugate():
    # (c) for the formate branch on a gear that is not the blank's: F.2's formate gear
    # with the drive blade 0.5 deg steeper and the cutter 0.5 mm further out (radial
    # distance), typed alone. Its own cutter generates the uncrowned pinion, so the
    # pinion is its line-contact conjugate (Litvin & Fuentes 2004, sec. 21.2): TE0 = 0
    # within 1e-4 arcsec (tca.line_contact, as tests/geometry/test_generated.py for the
    # blank's gear; the pair's flanks, 40 x 50 nodes) on at least 10 of 21 phases
    # (measured 3.4e-5 arcsec on 12). Not vacuous: the
    # pinion follows the gear (blade angle 20.5 deg, and its cutter moved with it)
    from gearcontact.geometry.basic_settings import complementary_pinion_setups
    from gearcontact.geometry.typed_pinion import typed_gear_pinion_setups
    from gearcontact.tca.line_contact import line_contact
    from gearcontact.tca.types import ContactGuess

    pair = load_pair(F2)
    std = standard_setups(pair)
    g = std["gear", "drive"]
    gear = {"coast": std["gear", "coast"], "drive": dataclasses.replace(
        g, settings=dataclasses.replace(g.settings, radial_distance_mm=g.settings.radial_distance_mm
                                        + 0.5),
        blade=dataclasses.replace(g.blade, blade_angle_deg=g.blade.blade_angle_deg + 0.5))}
    setup = typed_gear_pinion_setups(pair, gear)["drive"]
    blank_pinion = complementary_pinion_setups(pair)["drive"]
    assert setup.blade.blade_angle_deg == blank_pinion.blade.blade_angle_deg + 0.5
    assert abs(setup.settings.radial_distance_mm - blank_pinion.settings.radial_distance_mm) > 0.1
    cut = typed_gear_machine_pair(pair, gear, lengthwise_crowning_um=0.0,
                                  blade_profile_crowning_um=0.0)
    flanks = build_flanks(cut, n_u=40, n_v=50)
    m = flanks.mean_contact["drive"]
    r = line_contact(flanks.pinion.drive, flanks.gear.drive, pair.kinematics(with_errors=False),
                     ContactGuess(*m["pinion_uv"], *m["gear_uv"], pair.ratio * m["phi2_rad"],
                                  m["phi2_rad"]), pinion_teeth=pair.pinion_teeth, phases=21)
    assert np.isfinite(r.te0_arcsec).sum() >= 10
    assert r.te0_max_abs_arcsec < 1e-4
