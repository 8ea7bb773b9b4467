"""Every ``--pair`` command refuses a pair that cannot be made as ``design`` does, before
any flank work (issue 28: one pair preparation, :func:`gearcontact.tca.synthesis.
prepare_pair`, runs :func:`gearcontact.geometry.generation.check_generation`).

Truth: ``design``'s own refusal of the same pair (the same line after the command's
name: field, value and the verified fix). Before the fix ``twin`` and ``export fmu``
exited 2 with "no tooth pair in contact" after ~34 s of conjugate flank work and TCA;
the check alone takes ~1 s on top of the ~5 s process start-up (project machine, two
busy cores), so 25 s bounds "before the flanks" with room for a loaded machine.
"""

import time

import pytest

from console_script import run_console
from design_space import design_space_candidate
from gearcontact.geometry.pair import pair_to_toml

#: Wall time bound of a refusal before any flank work, s (module docstring).
BEFORE_FLANKS_S = 25.0


@pytest.fixture(scope="module")
def short_path(tmp_path_factory):
    """10/15, E 0.3 r2, beta1 25 deg, face 0.15 R_m (tests/design_space.py): the contact
    path covers eps_p 0.778 < 0.85 pitches; ``design`` names the spiral angle 35 deg
    (tests/geometry/test_contact_ratio.py). Returns (pair file, design's error text)."""
    path = tmp_path_factory.mktemp("pair") / "short_path.toml"
    path.write_text(pair_to_toml(design_space_candidate(10, 1.5, 0.3, 25.0, 0.15, "drive")))
    code, _, err = run_console("design", "--pair", path)
    assert code == 2, err
    line = err.strip().splitlines()[-1]
    assert line.startswith("gearcontact design: error: pinion_spiral_angle_deg = 25.0"), line
    assert "35.00 deg" in line, line
    return path, line.split(": error: ", 1)[1]


@pytest.mark.parametrize("command", [["twin"], ["export", "fmu"]])
def test_pair_command_refuses_as_design_before_the_flanks(short_path, command, tmp_path):
    path, design_error = short_path
    start = time.perf_counter()
    code, out, err = run_console(*command, "--pair", path, "--out", tmp_path / "out")
    elapsed = time.perf_counter() - start
    assert code == 2, err
    assert "Traceback" not in err, err
    line = err.strip().splitlines()[-1]
    assert line == f"gearcontact {' '.join(command)}: error: {design_error}"
    assert "no tooth pair in contact" not in err + out
    assert elapsed < BEFORE_FLANKS_S, elapsed


def test_pointed_pinion_refused_before_the_flanks(tmp_path):
    """10/25, E = 0, beta1 20 deg, face 0.15 R_m (tests/design_space.py): the conjugate
    pinion is pointed at the toe (top land -0.30 mm along its tip line); before the
    fix ``twin`` found it after the conjugate flank work (59 s at face 0.3 R_m). Now
    the generation check refuses it first, naming the verified point width 1.822 mm
    (geometry.generation.check_pinion_top_land; ~1 s at this face)."""
    path = tmp_path / "pointed.toml"
    path.write_text(pair_to_toml(design_space_candidate(10, 2.5, 0.0, 20.0, 0.15, "drive")))
    start = time.perf_counter()
    code, _, err = run_console("twin", "--pair", path, "--out", tmp_path / "out")
    elapsed = time.perf_counter() - start
    assert code == 2, err
    line = err.strip().splitlines()[-1]
    assert line.startswith("gearcontact twin: error: cutter.point_width_mm = "), line
    assert ">= 1.822 mm (pointed pinion teeth at the toe" in line, line
    assert elapsed < BEFORE_FLANKS_S, elapsed
