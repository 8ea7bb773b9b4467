"""Drivetrain parameters: closed-form defaults and the [drivetrain] TOML table.

Truth: the torsion of a solid round shaft ``k = G pi d^4/(32 L)`` and the polar inertia
of a solid cylinder ``rho pi L d^4/32`` evaluated by hand for the assumed shafts.
"""

import math

import pytest

from gearcontact.geometry.pair import load_pair
from gearcontact.twin.params import (DrivetrainParams, default_drivetrain, load_drivetrain,
                                     shaft_inertia_kgm2, shaft_stiffness_nm_per_rad)
from gearcontact.validation import InputRangeError


def test_shaft_formulas_by_hand():
    # d = 20 mm, L = 150 mm, G = 80 GPa: 80e9 * pi * 0.02^4 / (32 * 0.15) = 8377.58 N m/rad
    assert shaft_stiffness_nm_per_rad(20.0, 150.0, 80e3) == pytest.approx(8377.580, rel=1e-6)
    # 7850 * pi * 0.15 * 0.02^4 / 32 = 1.84961e-5 kg m^2
    assert shaft_inertia_kgm2(20.0, 150.0) == pytest.approx(1.849610e-5, rel=1e-5)


def test_s0003_defaults_from_the_blank():
    pair = load_pair("s0003-centred")
    p = default_drivetrain(pair)
    g = 209e3 / 2.6
    assert p.input_stiffness_nm_per_rad == pytest.approx(
        g * 1e6 * math.pi * 0.02 ** 4 / (32 * 0.15), rel=1e-12)
    # pinion head: cylinder of the mean tip radius over the face width, + half the shaft
    r1 = pair.blank.mean_pitch_radius_pinion_mm + pair.blank.addendum_pinion_mm
    head = 7850 * math.pi * 13.2e-3 * (2e-3 * r1) ** 4 / 32
    assert p.pinion_inertia_kgm2 == pytest.approx(head + 0.5 * shaft_inertia_kgm2(20, 150),
                                                  rel=1e-12)
    # the gear is two orders heavier than the pinion on its lever (ratio 10)
    assert p.gear_inertia_kgm2 > 50 * p.pinion_inertia_kgm2


def test_toml_table_overrides_and_errors(tmp_path):
    pair = load_pair("s0003-centred")
    f = tmp_path / "d.toml"
    f.write_text("[drivetrain]\nload_inertia_kgm2 = 0.2\nbacklash_mm = 0.1\n")
    p = load_drivetrain(f, pair)
    assert p.load_inertia_kgm2 == 0.2 and p.backlash_mm == 0.1
    assert p.motor_inertia_kgm2 == default_drivetrain(pair).motor_inertia_kgm2
    f.write_text("[drivetrain]\nload_inertia = 0.2\n")
    with pytest.raises(InputRangeError, match="drivetrain.load_inertia"):
        load_drivetrain(f, pair)
    f.write_text("[drivetrain]\nmotor_inertia_kgm2 = -1.0\n")
    with pytest.raises(InputRangeError, match="drivetrain.motor_inertia_kgm2"):
        load_drivetrain(f, pair)
    # a pair file given as --drivetrain (a careless user's try): the file named, and why
    f.write_text('name = "x"\n[teeth]\npinion = 20\ngear = 40\n')
    with pytest.raises(InputRangeError, match=r"--drivetrain.*d\.toml.*has none.*--pair"):
        load_drivetrain(f, pair)


def test_damping_ratio_range():
    base = default_drivetrain(load_pair("s0003-centred")).as_dict()
    base["mesh_damping_ratio"] = 1.5
    with pytest.raises(InputRangeError, match="mesh_damping_ratio"):
        DrivetrainParams(**base)


def test_example_file_loads():
    from pathlib import Path
    pair = load_pair("s0003-centred")
    path = Path(__file__).resolve().parents[2] / "examples" / "drivetrain_s0003.toml"
    p = load_drivetrain(path, pair)
    assert p.load_inertia_kgm2 == 0.2 and p.speed_control_bandwidth_hz == 5.0
    # the commented defaults in the file are the defaults (6 digits)
    d = default_drivetrain(pair)
    text = path.read_text()
    for key, value in d.as_dict().items():
        if f"# {key} = " in text:
            written = float(text.split(f"# {key} = ")[1].split()[0])
            assert written == pytest.approx(value, rel=1e-5), key
