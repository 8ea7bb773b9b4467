"""The hollow ease-off warning (geometry.easeoff_shape; docs/machine_settings.md sec. 2,
"The hollow ease-off warning"): a pinion flank's ease-off against the typed gear's
conjugate pinion, its quadratic crowning at the active box's edges, flagged hollow
beyond B = 2 um.

Truths:
- an ease-off imposed analytically on the conjugate pinion (geometry.easeoff's five-term
  relief r - E N, centred on the box) is measured as imposed: C_p = c_PC (h/2)^2,
  C_l = c_LC (L/2)^2, bias = c_TW (h/2)(L/2), and the linear terms leave no crowning;
- the pinion of the complementary settings is exactly conjugate to its formate gear
  (geometry.basic_settings; 3e-14 mm, docs/machine_settings.md sec. 4): no crowning;
- the legitimate pinions (the F.2 example typed to 4 decimals, the standard settings of
  F.3 and of the 11 x 41: crowned by design, the cutter-radius mismatch and the
  circular blade) raise no warning;
- a gear cut by a relieved blade (F.2 with a gear Flankrem) is measured against its main
  segment, the example's own gear blade: the example's crowning; a sliding-base slip
  leaves it hollow there too;
- s0003 cut by `design --machine-settings` (geometry.easeoff_settings) with its coast
  pinion's fitted 2C typed with the wrong sign (made here: the flip is the truth) warns,
  and the flip moves the lengthwise crowning by twice what the fitted 2C gives (first
  order in 2C).
"""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.basic_settings import (complementary_pinion_setups,
                                                 formate_gear_setups, standard_machine_pair)
from gearcontact.geometry.conjugate import conjugate_pinion_flank
from gearcontact.geometry.easeoff import EaseOff, apply_easeoff
from gearcontact.geometry.easeoff_shape import (CONJUGATE_GRID, HOLLOW_BOUND_UM,
                                                HollowEaseOffWarning, check_easeoff_shape,
                                                easeoff_shape)
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.settings_check import check_settings, completed_settings

from .test_blank_check import _flip

ROOT = Path(__file__).resolve().parents[2]


def _conjugate(pair, gear_setup):
    """The pinion flank conjugate to the gear flank ``gear_setup`` cuts, on the check's
    node grid (what check_easeoff_shape builds)."""
    gear = machine_flank(gear_setup, pair.blank, face_width_mm=pair.gear_face_width_mm,
                         n_u=CONJUGATE_GRID[0], n_v=CONJUGATE_GRID[1])
    return conjugate_pinion_flank(gear, blank=pair.blank,
                                  kinematics=pair.kinematics(with_errors=False),
                                  pinion_face_width_mm=pair.pinion_face_width_mm,
                                  n_u=CONJUGATE_GRID[0], n_v=CONJUGATE_GRID[1])[0]


@pytest.mark.parametrize("side, c_p, c_l, bias", [("drive", -3.0, -5.0, 4.0),
                                                  ("coast", 6.0, -2.5, -3.0)])
def test_an_imposed_easeoff_is_measured_as_imposed(f2_machine_pair, side, c_p, c_l, bias):
    pair = f2_machine_pair
    setups = {(s.member, s.side): s for s in pair.machine}
    conj = _conjugate(pair, setups["gear", side])
    b = conj.boundary
    h, length = b.u_tip - b.u_root, b.v_heel - b.v_toe
    # the five-term relief centred on the box (E = 0 there: no turn about the axis to
    # remove), with linear terms that must leave no crowning
    easeoff = EaseOff(profile_angle_um_per_mm=0.5, spiral_angle_um_per_mm=-0.2,
                      profile_crowning_um_per_mm2=c_p / (h / 2) ** 2,
                      lengthwise_crowning_um_per_mm2=c_l / (length / 2) ** 2,
                      bias_um_per_mm2=bias / ((h / 2) * (length / 2)),
                      u_mean_mm=0.5 * (b.u_root + b.u_tip), v_mean_mm=0.5 * (b.v_toe + b.v_heel))
    eased = apply_easeoff(conj, easeoff, limit_um=100.0)
    got = easeoff_shape(eased, conj, pair.blank, side=side)
    # Tolerance, from the imposed relief before any measurement: the eased sheet moves
    # the base point whose image lies at the node by E along the normal (geometry.easeoff),
    # so the deviation read at a node is E at a point within |E| of it: it differs from
    # E at the node by at most max|E| max|grad E| (um x um/mm x 1e-3 mm/um), plus 0.005
    # um for the two sheets' splines on the same node grid
    U, V = np.meshgrid(np.linspace(b.u_root, b.u_tip, 41), np.linspace(b.v_toe, b.v_heel, 41))
    e_um = 1e3 * easeoff.relief_mm(U, V)
    slope = max(np.abs(np.gradient(e_um, U[0, 1] - U[0, 0], axis=1)).max(),
                np.abs(np.gradient(e_um, V[1, 0] - V[0, 0], axis=0)).max())
    tol = 1e-3 * np.abs(e_um).max() * slope + 0.005
    assert tol <= 0.05 * HOLLOW_BOUND_UM  # within the check's resolution, B / 20
    assert got.C_p_um == pytest.approx(c_p, abs=tol)
    assert got.C_l_um == pytest.approx(c_l, abs=tol)
    assert got.bias_um == pytest.approx(bias, abs=tol)
    assert got.fit_rms_um < tol           # a quadratic relief: nothing beyond the fit
    assert got.flagged == (min(c_p, c_l) < -HOLLOW_BOUND_UM)
    assert got.hollowness == pytest.approx(max(0.0, -min(c_p, c_l)) / HOLLOW_BOUND_UM,
                                           abs=tol / HOLLOW_BOUND_UM)


@pytest.mark.parametrize("name", ["iso23509_f2_spiral_bevel", "iso23509_f3",
                                  "hypoid_11x41_rear_axle"])
def test_the_complementary_pinion_has_no_crowning(name):
    pair = load_pair(ROOT / "examples" / f"{name}.toml")
    gear, pinion = formate_gear_setups(pair), complementary_pinion_setups(pair)
    for side in ("drive", "coast"):
        got = easeoff_shape(pinion[side], _conjugate(pair, gear[side]), pair.blank,
                            side=side)
        # 0.1 um = B / 20, the check's resolution (required, not measured): the
        # 12 x 15 conjugate's quintic spline is the error (measured up to 0.07 um; from
        # a 60 x 75 conjugate 1e-4 um)
        for value in (got.C_p_um, got.C_l_um, got.bias_um):
            assert abs(value) <= 0.05 * HOLLOW_BOUND_UM, (side, got)


def _no_hollow_warning(pair, *, generated: bool = False):
    got = check_settings(pair, easeoff_generated=generated)
    assert got.hollow_warnings == () and got.easeoff.missing == {}
    with warnings.catch_warnings():
        warnings.simplefilter("error", HollowEaseOffWarning)
        got.warn()
    return got.easeoff


def test_the_f2_example_is_crowned_and_not_warned(f2_machine_pair):
    shape = _no_hollow_warning(f2_machine_pair)
    # measured +6.6 / +33.1 (drive), +6.6 / +38.7 um (coast): crowned, well inside the
    # declared legitimacy condition (hollowness <= 0.5)
    for s in shape.flanks:
        assert s.C_p_um > 0.0 and s.C_l_um > 0.0 and s.hollowness == 0.0 and not s.flagged


@pytest.mark.parametrize("name, gen", [("iso23509_f3", "formate"),
                                       ("hypoid_11x41_rear_axle", "formate")])
def test_standard_settings_are_crowned_and_not_warned(name, gen):
    # F.3 with a generated gear: test_a_generated_gear_is_checked_on_load_as_design_checks_it
    shape = _no_hollow_warning(standard_machine_pair(
        load_pair(ROOT / "examples" / f"{name}.toml"), gear_generation=gen),
        generated=gen == "generated")
    assert len(shape.flanks) == 2
    for s in shape.flanks:
        assert s.C_p_um > 0.0 and s.C_l_um > 0.0 and not s.flagged


def test_the_published_print_pinion_is_crowned():
    # the 10 x 41 print's own pinion tables against its generated gear (a pinion made
    # for another gear, tests/geometry/summary_sheets: not mates, yet a production
    # pinion, crowned): measured +26.5 / +60.0 um (drive) and, over the part of the box
    # its coast envelope reaches (not the conjugate's root corner), +85.9 / +72.0 um
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # the print's own MateWarning et al.
        pair = load_pair(ROOT / "tests" / "geometry" / "summary_sheets"
                         / "hypoid_10x41_no16_pair.toml")
    got = {s.side: s for s in check_easeoff_shape(pair).flanks}
    assert set(got) == {"drive", "coast"}
    assert not got["drive"].trimmed and got["coast"].trimmed
    for s in got.values():
        assert s.C_p_um > 0.0 and s.C_l_um > 0.0 and not s.flagged


def test_a_generated_gear_is_deferred_by_the_settings_check_alone():
    pair = standard_machine_pair(load_pair(ROOT / "examples" / "iso23509_f3.toml"),
                                 gear_generation="generated")
    got = check_easeoff_shape(pair, generated=False)
    assert got.flanks == () and set(got.missing) == {"drive", "coast"}
    assert got.deferred == ("drive", "coast")
    assert all("not checked by the settings check alone: the gear flank is generated" in w
               for w in got.missing.values())


def _with_drive_2c(pair, two_c):
    return dataclasses.replace(pair, machine=tuple(
        dataclasses.replace(s, settings=dataclasses.replace(s.settings, modified_roll=(two_c,)))
        if (s.member, s.side) == ("pinion", "drive") else s for s in pair.machine))


@pytest.fixture(scope="module")
def f3_generated():
    return standard_machine_pair(load_pair(ROOT / "examples" / "iso23509_f3.toml"),
                                 gear_generation="generated")


@pytest.mark.parametrize("case", ["sound", "hollow"])
def test_a_generated_gear_is_checked_on_load_as_design_checks_it(f3_generated, case):
    """The reader's check of a generated gear's pinions (settings_check.completed_settings:
    after its generation check, on the gear boxes it traced) gives ``design``'s
    measurement exactly (check_settings(easeoff_generated=True): the boxes traced
    afresh). Exact: the same box from the same function and inputs, the same floats after
    it (any difference would be a different computation). Cases: F.3's standard settings
    with a generated gear (crowned: measured +11.1 / +50.3 um drive, +7.5 / +55.7 um
    coast) and the same with a drive pinion 2C of 0.05 typed (none cut: lengthwise hollow,
    measured -10.5 um), warned on load as design flags it."""
    pair = f3_generated if case == "sound" else _with_drive_2c(f3_generated, 0.05)
    design = check_settings(pair, easeoff_generated=True).easeoff
    loaded = check_settings(pair)
    assert loaded.easeoff.deferred == ("drive", "coast") and loaded.hollow_warnings == ()
    boxes = check_generation(pair)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        done = completed_settings(pair, loaded, boxes)
    assert done.easeoff.flanks == design.flanks and done.easeoff.missing == design.missing == {}
    assert done.easeoff.deferred == () and done.hollow_warnings == design.warnings()
    hollow = [str(w.message) for w in caught if w.category is HollowEaseOffWarning]
    assert hollow == [line.removeprefix("warning: ") for line in design.warnings()]
    flagged = [s.side for s in design.flanks if s.flagged]
    assert flagged == ([] if case == "sound" else ["drive"])
    if case == "sound":     # the legitimate pinion: crowned (the declared condition)
        assert all(s.C_p_um > 0.0 and s.C_l_um > 0.0 for s in design.flanks)
    else:                   # hollow lengthwise beyond the bound (measured -10.5 um)
        assert design.flanks[0].C_l_um < -HOLLOW_BOUND_UM
    # the box reused is the reader's, not traced again: a second trace fails the test
    with pytest.MonkeyPatch.context() as mp:
        from gearcontact.geometry import generated

        def no_trace(*args, **kwargs):
            raise AssertionError("the gear box was traced again")

        mp.setattr(generated, "generated_gear_box", no_trace)
        again = completed_settings(pair, loaded, boxes, warn=False)
    assert again.easeoff.flanks == design.flanks


@pytest.fixture(scope="module")
def design_verdicts(f3_generated):
    """``{case: (pair, design's EaseOffShapeCheck)}`` of the two cases above, measured
    once (check_settings(easeoff_generated=True), ``design``'s own measurement)."""
    pairs = {"sound": f3_generated, "hollow": _with_drive_2c(f3_generated, 0.05)}
    return {case: (p, check_settings(p, easeoff_generated=True).easeoff)
            for case, p in pairs.items()}


class _Built(Exception):
    """Raised in place of the flanks: the library call got past its settings check."""


def _no_flanks(*args, **kwargs):
    raise _Built


def _analyze_pair(pair, out):
    from gearcontact.tca.analysis import analyze_pair
    analyze_pair(pair, phases=3)


def _run_sweep(pair, out):
    from gearcontact.sweep.grid import SweepGrid, parse_vary
    from gearcontact.sweep.run import run_sweep
    run_sweep(pair, SweepGrid((parse_vary("E=0:0:1"),), (64.5,)), out=out, side="drive",
              phases=3, workers=0, progress=False)


@pytest.mark.parametrize("case", ["sound", "hollow"])
@pytest.mark.parametrize("call", [_analyze_pair, _run_sweep], ids=["analyze_pair", "run_sweep"])
def test_a_library_call_checks_a_generated_gear_as_design_does(design_verdicts, tmp_path,
                                                               monkeypatch, case, call):
    """A library call that takes a raw pair and builds its flanks itself
    (settings_check.checked_settings: analyze_pair and run_sweep given no flanks) measures
    a generated gear's pinions before the flanks, with ``design``'s verdict exactly (the
    same floats: check_settings(easeoff_generated=True), the gear boxes traced, as the
    reader's boxes give them bit for bit, the test above); its hollow lines warned.
    Before (session 26) they were left deferred: no warning on the hollow case. Cases as
    above: F.3's standard settings with a generated gear, and its drive pinion with 2C
    0.05 (lengthwise hollow, -10.5 um)."""
    import gearcontact.geometry.flank as flank
    from gearcontact.geometry.settings_check import checked_settings

    pair, design = design_verdicts[case]
    monkeypatch.setattr(flank, "build_flanks", _no_flanks)
    seen = {}
    real = checked_settings

    def kept(*args, **kwargs):
        seen["check"] = real(*args, **kwargs)
        return seen["check"]

    monkeypatch.setattr("gearcontact.geometry.settings_check.checked_settings", kept)
    with warnings.catch_warnings(record=True) as caught, pytest.raises(_Built):
        warnings.simplefilter("always")
        call(pair, tmp_path)
    got = seen["check"].easeoff
    assert got.flanks == design.flanks and got.missing == design.missing == {}
    assert got.deferred == ()
    hollow = [str(w.message) for w in caught if w.category is HollowEaseOffWarning]
    assert hollow == [line.removeprefix("warning: ") for line in design.warnings()]
    assert len(hollow) == (0 if case == "sound" else 1)


def test_the_reader_traces_a_generated_gear_box_once(design_verdicts, monkeypatch):
    """prepare_pair (the reader of every pair command) leaves the pinions to its
    generation check's gear boxes (checked_settings(deferred=True), then
    completed_settings): one trace per gear flank, two in all (the library calls'
    measurement above would make it four), and the hollow line of the 2C case as
    ``design`` says it."""
    from gearcontact.geometry import generated
    from gearcontact.tca.synthesis import prepare_pair

    pair, design = design_verdicts["hollow"]
    traces, real = [], generated.generated_gear_box

    def counted(*args, **kwargs):
        traces.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(generated, "generated_gear_box", counted)
    monkeypatch.setattr("gearcontact.geometry.settings_top_land.generated_gear_box", counted)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = prepare_pair(pair).settings_check
    assert len(traces) == 2
    assert got.easeoff.flanks == design.flanks and got.easeoff.deferred == ()
    assert [str(w.message) for w in caught if w.category is HollowEaseOffWarning] \
        == [line.removeprefix("warning: ") for line in design.warnings()]


def test_a_relieved_gear_is_measured_against_its_main_segment(f2_machine_pair):
    # F.2 with a Flankrem on both gear blades (tests/data/toprem): the file is the F.2
    # example with the two flankrem keys added, so its main segment's blade
    # (geometry.blade.blade_segments: the blade's own profile continued past the kink) is
    # the example's gear blade and its pinion the example's: the example's crowning,
    # measured against the same conjugate (1e-9 um: the same floats but for round-off in
    # the segment's blade arithmetic; measured equal to the bit)
    relieved = load_pair(ROOT / "tests" / "data" / "toprem" / "iso23509_f2_gear_flankrem.toml")
    got = check_easeoff_shape(relieved)
    assert got.missing == {} and got.warnings() == ()
    assert [s.side for s in got.flanks] == ["drive", "coast"]
    assert all(s.relieved_gear for s in got.flanks)
    own = check_easeoff_shape(f2_machine_pair).flanks
    assert not any(s.relieved_gear for s in own)
    for a, b in zip(got.flanks, own):
        for name in ("C_p_um", "C_l_um", "bias_um", "fit_rms_um"):
            assert getattr(a, name) == pytest.approx(getattr(b, name), abs=1e-9)
    # not vacuous: the pinion sliding base typed WITH / AWAY the other way (the slip of
    # tests/geometry/test_settings_check.py) leaves the coast pinion hollow in profile
    # against the relieved gear's main segment as against the example's gear (F.2's
    # slip: -7.8 um)
    slip = dataclasses.replace(relieved, machine=_flip(relieved.machine, "pinion",
                                                       "sliding_base_mm", lambda x: -x))
    flagged = check_easeoff_shape(slip)
    assert [s.side for s in flagged.flanks if s.flagged] == ["coast"]
    assert len(flagged.warnings()) == 1 and "[machine.pinion.coast]" in flagged.warnings()[0]
    coast = {s.side: s for s in flagged.flanks}["coast"]
    assert coast.C_p_um < -HOLLOW_BOUND_UM


def _with_coast_2c(pair, two_c):
    return dataclasses.replace(pair, machine=tuple(
        dataclasses.replace(s, settings=dataclasses.replace(
            s.settings, modified_roll=(two_c, *s.settings.modified_roll[1:])))
        if (s.member, s.side) == ("pinion", "coast") else s for s in pair.machine))


@pytest.fixture(scope="module")
def s0003_cut():
    from gearcontact.geometry.easeoff_settings import easeoff_machine_pair

    return easeoff_machine_pair(load_pair("s0003")).pair     # ~5 s


def test_s0003_cut_by_design_with_its_coast_2c_flipped_warns(s0003_cut):
    fitted = {(s.member, s.side): s for s in s0003_cut.machine}["pinion", "coast"]
    two_c = fitted.settings.modified_roll[0]
    assert two_c == pytest.approx(0.00954, abs=5e-5)     # the file design writes
    _no_hollow_warning(s0003_cut)                          # as written: no warning
    flipped = check_settings(_with_coast_2c(s0003_cut, -two_c))
    assert len(flipped.hollow_warnings) == 1
    line = flipped.hollow_warnings[0]
    for word in ("[machine.pinion.coast]", "lengthwise below -2 um", "modified roll 2C"):
        assert word in line
    with pytest.warns(HollowEaseOffWarning) as caught:
        flipped.warn()
    assert [str(w.message) for w in caught] == [line.removeprefix("warning: ")]
    coast = {s.side: s for s in flipped.easeoff.flanks}["coast"]
    assert coast.flagged and coast.C_l_um < -HOLLOW_BOUND_UM      # measured -4.3 um
    # first order in 2C: the flip moves the crowning by twice what the fitted 2C gives
    # against 2C = 0; 0.1 um (B / 20, the check's resolution) for the second order
    typed = {s.side: s for s in check_easeoff_shape(s0003_cut).flanks}["coast"]
    zero = {s.side: s for s in check_easeoff_shape(_with_coast_2c(s0003_cut, 0.0)).flanks
            }["coast"]
    assert coast.C_l_um == pytest.approx(2 * zero.C_l_um - typed.C_l_um, abs=0.1)
    assert coast.C_p_um == pytest.approx(2 * zero.C_p_um - typed.C_p_um, abs=0.1)
