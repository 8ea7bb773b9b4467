"""The pitch point of a pinion's generating roll that its blank's standard settings give
(geometry.pinion_pitch; docs/machine_settings.md sec. 2, "The pinion's pitch point").

Truth: the standard settings themselves (geometry.basic_settings, what ``design
--machine-settings`` writes), measured through the machine's kinematics
(flank_angles.pitch_offset: the cradle's motion against the work, machine.to_work);
the expected value comes from the mesh's kinematics (the pinion against the gear or the
crown gear in the meshing frame, a different code path and frame). Tolerance 1e-9 mm:
both are closed forms in double precision at the same solved point (the gear's pitch
point is tested to the same 1e-9 in test_blank_check.py).
"""

import dataclasses
from pathlib import Path

import pytest

from gearcontact.geometry.basic_settings import (complementary_pinion_setups,
                                                 crown_pinion_setups, standard_setups)
from gearcontact.geometry.flank_angles import measure_mean_point, pitch_offset
from gearcontact.geometry.machine import mirror_setup
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.pinion_pitch import expected_pitch_offset, standard_roll

ROOT = Path(__file__).resolve().parents[2]
PAIRS = ["iso23509_f2_spiral_bevel", "iso23509_f3", "hypoid_11x41_rear_axle"]


@pytest.mark.parametrize("gen", ["formate", "generated"])
@pytest.mark.parametrize("name", PAIRS)
def test_standard_settings_give_their_own_expected_pitch_point(name, gen):
    # the localized standard pinion (cutter-radius mismatch, circular blade) and the
    # unlocalized one (complementary / crown gear's) have the same pitch point, the one
    # the mesh's kinematics give at their mean point; a spiral bevel pair's is the mean
    # point itself; the left-hand twins (settings mirrored) give the same
    pair = load_pair(ROOT / "examples" / f"{name}.toml")
    b = pair.blank
    delta = b.pitch_angle_pinion_deg
    cone = dict(pitch_angle_deg=delta, cone_distance_mm=b.mean_cone_distance_pinion_mm)
    std = standard_setups(pair, gear_generation=gen)
    raw = (complementary_pinion_setups if gen == "formate" else crown_pinion_setups)(pair)
    for hand in ("right", "left"):
        roll = standard_roll(dataclasses.replace(pair, pinion_hand=hand),
                             gear_generated=gen == "generated")
        for side in ("drive", "coast"):
            got = []
            for setup in (std["pinion", side], raw[side]):
                setup = setup if hand == "right" else mirror_setup(setup)
                at = measure_mean_point(setup, **cone)
                s = pitch_offset(setup, at, pitch_angle_deg=delta)
                assert s == pytest.approx(expected_pitch_offset(roll, at, pitch_angle_deg=delta),
                                          abs=1e-9)
                got.append(s)
            assert got[0] == pytest.approx(got[1], abs=1e-9)
            if pair.offset_mm == 0.0:
                assert got[0] == pytest.approx(0.0, abs=1e-9)
            else:   # a hypoid pinion's lies off its mean point (docs: up to 0.96 mm)
                assert abs(got[0]) > 0.1


#: The model bound declared for the comparison before any pinion margin was measured
#: (commit ee30518, geometry.blank_check's PINION_PITCH_POINT_FRACTION then): a tenth of
#: the pinion's mean dedendum, the gear's fraction.
DECLARED_FRACTION = 0.1


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason=(
    "differs: the pinion design --machine-settings fits to s0003's coast ease-off rolls "
    "at 10.0635 with 2C 0.0095, 6D -0.0118; its pitch point lies -0.091 mm from the "
    "standard roll's, beyond the declared model bound (0.1 x 0.704 mm dedendum = 0.070 "
    "mm) and beyond blank_check's whole tolerance at ee30518 (that bound plus the typed "
    "rounding propagated: 0.085 mm, 1.07 of it): the comparison is not shipped "
    "(docs/machine_settings.md sec. 2, \"The pinion's pitch point\")"))
def test_the_fitted_s0003_pinion_rolls_within_the_declared_bound():
    # would a pinion whose settings design itself writes pass the comparison? (truth:
    # a file design writes must not be warned about)
    from gearcontact.geometry.easeoff_settings import easeoff_machine_pair

    pair = easeoff_machine_pair(load_pair("s0003")).pair
    b = pair.blank
    delta = b.pitch_angle_pinion_deg
    roll = standard_roll(pair, gear_generated=False)       # s0003's gear is formate
    for setup in pair.machine:
        if setup.member != "pinion":
            continue
        at = measure_mean_point(setup, pitch_angle_deg=delta,
                                cone_distance_mm=b.mean_cone_distance_pinion_mm)
        got = (pitch_offset(setup, at, pitch_angle_deg=delta)
               - expected_pitch_offset(roll, at, pitch_angle_deg=delta))
        # the model bound alone (the typed rounding's share, 0.015 mm at ee30518, is
        # left out: the fitted value is beyond the whole tolerance as well, reason)
        assert abs(got) <= DECLARED_FRACTION * b.dedendum_pinion_mm, setup.side
