"""Every ``--pair`` command refuses a pair that cannot be made as ``design`` does, before
any flank work (issue 28: one pair preparation, :func:`gearcontact.tca.synthesis.
prepare_pair`, runs :func:`gearcontact.geometry.generation.check_generation`).

Truth: ``design``'s own refusal of the same pair (the same line after the command's
name: field, value and the verified fix). Before the fix ``twin`` and ``export fmu``
exited 2 with "no tooth pair in contact" after ~34 s of conjugate flank work and TCA;
the check alone takes ~1 s on top of the ~5 s process start-up (project machine, two
busy cores). "Before the flanks" is asserted, not timed: the refused command runs in a
real process whose conjugate pinion solver (the flank work,
:func:`gearcontact.geometry.conjugate.conjugate_pinion_flank`) is replaced by one that
fails with exit 1, so exit 2 with ``design``'s line proves the solver never ran.
"""

import subprocess
import sys

import pytest

from console_script import ENV, run_console
from design_space import design_space_candidate
from gearcontact.geometry.pair import pair_to_toml

#: The console script with the flank work forbidden (module docstring).
_NO_FLANKS = (
    "import sys\n"
    "import gearcontact.geometry.flank as flank\n"
    "def forbidden(*args, **kwargs):\n"
    "    raise RuntimeError('conjugate flank work started')\n"
    "flank.conjugate_pinion_flank = forbidden\n"
    "sys.argv[0] = 'gearcontact'\n"
    "from gearcontact.cli import console_main\n"
    "console_main()\n")


def run_without_flanks(*argv):
    """``gearcontact *argv`` in a real process whose conjugate flank solver raises;
    (return code, stdout, stderr)."""
    p = subprocess.run([sys.executable, "-c", _NO_FLANKS, *map(str, argv)],
                       capture_output=True, text=True, env=ENV, timeout=300)
    return p.returncode, p.stdout, p.stderr


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
    # the file's key (was the library's "pinion_spiral_angle_deg", session 27)
    assert line.startswith("gearcontact design: error: design.pinion_spiral_angle_deg = 25.0 "
                           "is outside the allowed range: 35.00 deg (the contact path of "), line
    assert "35.00 deg" in line, line
    return path, line.split(": error: ", 1)[1]


@pytest.mark.parametrize("command", [["twin"], ["export", "fmu"]])
def test_pair_command_refuses_as_design_before_the_flanks(short_path, command, tmp_path):
    path, design_error = short_path
    code, out, err = run_without_flanks(*command, "--pair", path, "--out", tmp_path / "out")
    assert code == 2, err
    assert "Traceback" not in err, err
    line = err.strip().splitlines()[-1]
    assert line == f"gearcontact {' '.join(command)}: error: {design_error}"
    assert "no tooth pair in contact" not in err + out


def test_pointed_pinion_refused_before_the_flanks(tmp_path):
    """10/25, E = 0, beta1 20 deg, face 0.15 R_m (tests/design_space.py): the conjugate
    pinion is pointed at the toe (top land -0.30 mm along its tip line); before the
    fix ``twin`` found it after the conjugate flank work (59 s at face 0.3 R_m). Now
    the generation check refuses it first, naming the verified point width 1.822 mm
    (geometry.generation.check_pinion_top_land; ~1 s at this face)."""
    path = tmp_path / "pointed.toml"
    path.write_text(pair_to_toml(design_space_candidate(10, 2.5, 0.0, 20.0, 0.15, "drive")))
    code, _, err = run_without_flanks("twin", "--pair", path, "--out", tmp_path / "out")
    assert code == 2, err
    line = err.strip().splitlines()[-1]
    assert line.startswith("gearcontact twin: error: cutter.point_width_mm = "), line
    assert ">= 1.822 mm (pointed pinion teeth at the toe" in line, line


def test_forbidden_flank_work_is_seen(tmp_path):
    """The control of the module's truth: on a pair ``design`` accepts (s0003), the
    same process reaches the conjugate flank solver and fails there (exit 1)."""
    code, _, err = run_without_flanks("tca", "--pair", "s0003", "--out", tmp_path / "out")
    assert code == 1, err
    assert "conjugate flank work started" in err, err
