"""The typed-settings check as the library runs it when it takes a pair
(geometry.settings_check; docs/machine_settings.md sec. 2, "The check when a pair is
loaded"): the result of geometry.blank_check's comparison, a gross slip refused naming
its key, the other warnings handed back (and emitted as SettingsWarning only on request).

Truths: the ISO 23509 F.2 example (its blank's standard settings typed to 4 decimals)
agrees with its blank; the same pair with a sheet word misread (made here, the flip is
the truth, as in tests/geometry/test_blank_check.py: the blank's hand word, a gross
slip; the pinion's sliding base WITH / AWAY, a warning); a pair without machine
settings has nothing to check. Tolerances: geometry.blank_check's, tested there.
"""

import dataclasses
import sys
import warnings

import pytest

from gearcontact.geometry.blank_check import check_pair_blank
from gearcontact.geometry.easeoff_shape import HollowEaseOffWarning
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.settings_check import SettingsWarning, check_settings
from gearcontact.validation import InputRangeError

from .test_blank_check import _flip


def test_a_pair_without_settings_has_nothing_to_check():
    assert check_settings(load_pair("s0003")) is None


def test_the_example_agrees_and_warns_nothing(f2_machine_pair):
    got = check_settings(f2_machine_pair)
    assert got.agrees and got.warnings == ()
    assert got.blank == check_pair_blank(f2_machine_pair)   # the blank check's, unchanged
    assert got.seconds > 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got.warn()


def test_a_hand_slip_is_refused_naming_its_key(f2_machine_pair):
    with pytest.raises(InputRangeError, match=r"design\.pinion_hand = 'left' is outside"):
        check_settings(dataclasses.replace(f2_machine_pair, pinion_hand="left"))


def test_a_sliding_base_slip_is_handed_back_and_warned_on_request(f2_machine_pair):
    f2 = f2_machine_pair
    slip = dataclasses.replace(f2, machine=_flip(f2.machine, "pinion", "sliding_base_mm",
                                                 lambda x: -x))
    with warnings.catch_warnings():
        warnings.simplefilter("error")     # nothing emitted by the check itself
        got = check_settings(slip)
    assert not got.agrees
    assert got.warnings == tuple(check_pair_blank(slip).warnings())
    assert [f"likely machine.pinion.{side}.sliding_base_mm" in line
            for line in got.warnings for side in ("drive", "coast")].count(True) == 2
    with pytest.warns(SettingsWarning) as caught:
        got.warn()
    assert [str(w.message) for w in caught if w.category is SettingsWarning] \
        == [line.removeprefix("warning: ") for line in got.warnings]
    # the slip also leaves the coast pinion hollow in profile (geometry.easeoff_shape,
    # measured -7.8 um): a different check, its own warning class, after the blank's
    assert [str(w.message) for w in caught if w.category is HollowEaseOffWarning] \
        == [line.removeprefix("warning: ") for line in got.hollow_warnings]


def _analyze_pair(pair, out):
    from gearcontact.tca.analysis import analyze_pair
    return analyze_pair(pair, phases=3)


def _flank_compliance(pair, out):
    from gearcontact.structure.compliance import flank_compliance
    return flank_compliance(pair, "pinion", side="drive")


def _run_sweep(pair, out):
    from gearcontact.sweep.grid import SweepGrid, parse_vary
    from gearcontact.sweep.run import run_sweep
    return run_sweep(pair, SweepGrid((parse_vary("E=0:0:1"),), (64.5,)), out=out,
                     side="drive", phases=3, workers=0, progress=False)


def _export_flanks(pair, out):
    from gearcontact.export.flanks import export_flanks
    return export_flanks(pair, out, pair_name=pair.name)


#: The library calls that build a raw pair's flanks themselves when given none (the
#: command line hands them a prepared pair's: tca.synthesis.prepare_pair checked it).
BUILDERS = [_analyze_pair, _flank_compliance, _run_sweep, _export_flanks]


@pytest.mark.parametrize("call", BUILDERS, ids=lambda f: f.__name__.strip("_"))
def test_library_calls_given_no_flanks_refuse_a_hand_slip_first(f2_machine_pair, tmp_path,
                                                                 monkeypatch, call):
    # before any flank is built and before anything is written
    import gearcontact.geometry.flank as flank

    def no_flanks(*args, **kwargs):
        raise AssertionError("flanks built before the settings check")

    monkeypatch.setattr(flank, "build_flanks", no_flanks)
    monkeypatch.setattr("gearcontact.structure.compliance.build_flanks", no_flanks)
    out = tmp_path / "o"
    out.mkdir()
    with pytest.raises(InputRangeError, match=r"design\.pinion_hand = 'left' is outside"):
        call(dataclasses.replace(f2_machine_pair, pinion_hand="left"), out)
    assert list(out.iterdir()) == []


def test_analyze_pair_warns_a_sliding_base_slip(f2_machine_pair):
    from gearcontact.tca.analysis import analyze_pair

    f2 = f2_machine_pair
    slip = dataclasses.replace(f2, machine=_flip(f2.machine, "pinion", "sliding_base_mm",
                                                 lambda x: -x))
    with pytest.warns(SettingsWarning) as caught:
        analyze_pair(slip, phases=3)
    lines = [str(w.message) for w in caught if w.category is SettingsWarning]
    assert len(lines) == 2 and all("sliding_base_mm" in line for line in lines)
    first = next(w for w in caught if w.category is SettingsWarning)
    assert first.filename == __file__            # attributed to the caller


def _md_slip(f2):
    """F.2 with the gear's MD typed -0.24 where its blank's settings have 0 (sec. 2's
    table: mean cone distance 81.354 against 81.273 mm, a warning naming the MCTB alone;
    the cheapest warned slip of the examples, 2-3 s)."""
    return dataclasses.replace(f2, machine=_flip(f2.machine, "gear", "machine_centre_to_back_mm",
                                                 lambda x: -0.24))


def test_the_blank_warnings_come_before_the_flank_work(f2_machine_pair, monkeypatch):
    """Validate, then compute (docs/machine_settings.md sec. 2, "The order of the
    check"): the library's check emits the blank's SettingsWarnings before the ease-off
    shape builds its flanks. Before (session 26) they came after it (1.3-2.4 s later on
    F.2's warned slips; a failure of that work left them unsaid)."""
    import gearcontact.geometry.settings_check as sc

    slip, said = _md_slip(f2_machine_pair), {}

    def shape(*args, **kwargs):     # the flank work, stubbed: only its moment matters
        said["at the flank work"] = [str(w.message) for w in caught
                                     if w.category is SettingsWarning]

    monkeypatch.setattr(sc, "check_easeoff_shape", shape)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = sc.checked_settings(slip)
    assert len(got.warnings) == 2 and "machine_centre_to_back_mm" in got.warnings[0]
    assert said["at the flank work"] == [line.removeprefix("warning: ")
                                         for line in got.warnings]


def test_a_failure_of_the_flank_work_is_named_from_the_first_comparison(
        f2_machine_pair, monkeypatch, capsys):
    """The command line's check (cli.settings_slip.checked_blank_named): its warnings
    printed before the flank work, and an input error of that work renamed to the slip
    from the comparison already made. Before (session 26) the blank was compared a second
    time on this path (check_pair_blank called twice: 2.4 s more on this slip, 11.7 s on
    a pinion ratio of roll typed cradle / work) to name the slip and print the warnings
    the failed call had not printed."""
    import gearcontact.geometry.blank_check as bc
    import gearcontact.geometry.settings_check as sc
    from gearcontact.cli.settings_slip import checked_blank_named

    calls, real = [], bc.check_pair_blank

    def counted(*args, **kwargs):
        calls.append(1)
        return real(*args, **kwargs)

    def failing_shape(*args, **kwargs):     # the flank work failing on a key typed right
        print("<flank work>", file=sys.stderr)
        raise InputRangeError("blade.gear.drive.point_radius_mm", 113.3, "a simulated failure")

    monkeypatch.setattr(bc, "check_pair_blank", counted)
    monkeypatch.setattr(sc, "check_pair_blank", counted)
    monkeypatch.setattr(sc, "check_easeoff_shape", failing_shape)
    with pytest.raises(InputRangeError) as err:
        checked_blank_named(_md_slip(f2_machine_pair))
    assert len(calls) == 1
    assert "the check of its flanks failed on it (blade.gear.drive.point_radius_mm = 113.3: " \
           "a simulated failure)" in str(err.value)
    assert "likely machine.gear" in str(err.value) or "[machine.gear.drive]" in str(err.value)
    printed = capsys.readouterr().err.splitlines()
    assert printed[-1] == "<flank work>" and len(printed) == 3
    assert all(line.startswith("warning: the gear ") for line in printed[:2])
