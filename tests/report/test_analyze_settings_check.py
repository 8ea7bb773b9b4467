"""The Python API runs the typed-settings check when it takes a pair, as the command line
does (report.analyze.run_analysis through tca.synthesis.prepare_pair,
geometry.settings_check; docs/machine_settings.md sec. 2, "The check when a pair is
loaded"): a gross slip refused naming its key before any flank work and before anything
is written, a warning-level slip a SettingsWarning and the paragraph in summary.md, a
clean pair's summary saying the check agreed.

Truths: the ISO 23509 F.2 example (its blank's standard settings typed to 4 decimals)
agrees with its blank; the same pair with one sheet word misread (made here: the flip is
the truth, tests/geometry/test_blank_check.py): the blank's hand word (gross), the
pinion's sliding base WITH / AWAY on both flanks (a warning: the pinion's root 6.73 /
9.67 mm behind the tip plane against the blank's 2.39 mm). The summary's lines are
the command line's (tests/cli/test_settings_check_commands.py checks the console's).
Small runs (3 phases, one torque, no loaded TE): the check runs before any of it.
"""

import dataclasses

import pytest

import gearcontact.geometry.settings_check as settings_check
import gearcontact.tca.synthesis as synthesis
from gearcontact.geometry.settings_check import SettingsWarning
from gearcontact.report.analyze import run_analysis
from gearcontact.validation import InputRangeError

from geometry.test_blank_check import _flip

SMALL = dict(torques_nm=(64.5,), phases=3, figures=False, progress=False,
             lte_torque_nm=None)


def test_a_hand_slip_is_refused_before_anything_is_written(f2_machine_pair, tmp_path,
                                                          monkeypatch):
    def no_flank_work(*args, **kwargs):
        raise AssertionError("the generation check ran before the settings check")

    monkeypatch.setattr(synthesis, "check_generation", no_flank_work)
    out = tmp_path / "a"
    with pytest.raises(InputRangeError, match=r"design\.pinion_hand = 'left' is outside"):
        run_analysis(dataclasses.replace(f2_machine_pair, pinion_hand="left"), out_dir=out,
                     **SMALL)
    assert not out.exists()


def test_a_sliding_base_slip_is_warned_then_refused_as_a_pointed_tooth(f2_machine_pair,
                                                                      tmp_path):
    # the pinion's sliding base typed AWAY for WITH cuts 6.7 / 9.7 mm deep against the
    # blank's 2.39: the flanks cross below the tip (geometry.settings_top_land), an input
    # error after the slip's warnings, before any work or file
    f2 = f2_machine_pair
    slip = dataclasses.replace(f2, machine=_flip(f2.machine, "pinion", "sliding_base_mm",
                                                 lambda x: -x))
    with pytest.warns(SettingsWarning) as caught, \
            pytest.raises(InputRangeError, match="a pointed pinion tooth.*likely slip"):
        run_analysis(slip, out_dir=tmp_path, **SMALL)
    named = [str(w.message) for w in caught if w.category is SettingsWarning]
    for side in ("drive", "coast"):
        assert any(f"likely machine.pinion.{side}.sliding_base_mm" in m for m in named)
    assert not (tmp_path / "summary.md").exists()


def test_a_settings_warning_lands_in_the_summary(f2_machine_pair, tmp_path):
    # the pinion's machine root 0.5 deg off (no known slip: the flanks stay regular and
    # run): each warning line in summary.md under the blank's heading. (1 deg put the
    # pinion root 1.38 mm above the blank's, beyond the clearance and tolerance, 1.11
    # mm: refused since session 29, docs/machine_settings.md sec. 2, "A root above the
    # mating tip"; 0.5 deg leaves it 0.67 mm above, outside the tolerance 0.31 only.)
    f2 = f2_machine_pair
    slip = dataclasses.replace(f2, machine=_flip(f2.machine, "pinion", "machine_root_angle_deg",
                                                 lambda x: x + 0.5))
    with pytest.warns(SettingsWarning) as caught:
        res = run_analysis(slip, out_dir=tmp_path, **SMALL)
    lines = res.settings_check.warnings
    assert len(lines) == 2 and not res.settings_check.agrees
    assert [str(w.message) for w in caught if w.category is SettingsWarning] \
        == [line.removeprefix("warning: ") for line in lines]
    summary = (tmp_path / "summary.md").read_text()
    assert "**Machine settings against the blank: warning.**" in summary
    for line in lines:
        assert f"- {line.removeprefix('warning: ')}" in summary
    assert ("The typed-settings check: 2 of 4 flanks do not agree with the blank (the "
            "warning above)") in summary


def test_a_clean_pair_says_the_check_agreed(f2_machine_pair, tmp_path, monkeypatch):
    calls = []

    def counted(*args, _real=settings_check.check_pair_blank, **kwargs):
        calls.append(args)
        return _real(*args, **kwargs)

    monkeypatch.setattr(settings_check, "check_pair_blank", counted)
    res = run_analysis(f2_machine_pair, out_dir=tmp_path, **SMALL)
    assert len(calls) == 1          # once per call, whatever the stages
    assert res.settings_check is not None and res.settings_check.agrees
    summary = (tmp_path / "summary.md").read_text()
    assert ("The typed-settings check: every flank agrees with the blank within its "
            "tolerance") in summary
    assert "not run" not in summary and "against the blank: warning" not in summary
