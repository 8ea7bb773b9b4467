"""``gearcontact export fmu --hertz-form``: the FMUs' C contact law has Hamrock-Brewe's
forms only, so the exact form (the twin's, gearcontact.twin.exact_hertz) is refused
before any work, naming the option (exit 2, no output directory)."""

import pytest

from gearcontact.cli import main


@pytest.mark.parametrize("kind", ["mesh", "drivetrain"])
def test_export_fmu_refuses_the_exact_form(tmp_path, capsys, kind):
    out = tmp_path / "fmu"
    assert main(["export", "fmu", "--kind", kind, "--out", str(out),
                 "--hertz-form", "exact"]) == 2
    err = capsys.readouterr().err
    assert "--hertz-form" in err and "exact" in err and "hamrock-brewe" in err
    assert not out.exists()
