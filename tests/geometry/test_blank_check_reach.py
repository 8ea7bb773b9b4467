"""The typed-settings check (geometry.blank_check) on a flank that does not reach its
blank's mean point: a radial distance typed in inches or metres, a cradle angle typed
in radians (docs/machine_settings.md sec. 2, "A mean point not reached").

Truths: each slip is made here from the F.2 example's right value (converted and typed to
the digits a sheet prints: 4 decimals, 3 for radians), so the key to name and the
conversion that undoes it are known in advance; the gear's generating gear is computed
by hand below as the crossing of a circle and a line in the cradle plane (the cutter
centre ``C = S (cos q, sin q)``, the nominal cutter radius ``r_c``; the root line ``y =
E_m``; the mean point's foot ``x = A cos(delta - gamma_m) + X_D cos(gamma_m)``; SpyGO's
``AGMAcomputationHypoid``, docs sec. 2), independent of the library's vectors; the gross
bound is half the gear face (declared before the margins were measured, docs sec. 2).
"""

from __future__ import annotations

import dataclasses
import math

import pytest

from gearcontact.geometry.blank_check import (GROSS_CONE_FACE_FRACTION, check_flanks,
                                              check_pair_blank)
from gearcontact.geometry.blank_statement import stated_blank
from gearcontact.geometry.known_slips import INCH_MM
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError

from .test_blank_check import F2_MACHINE, _flip


@pytest.fixture(scope="module")
def f2():
    return load_pair(F2_MACHINE)


def _hand_circle(st, *, r_c: float, cone_mm: float, pitch_deg: float) -> tuple[float, float]:
    """(spiral angle deg, mean cone distance mm) of the generating gear by hand: the
    circle of radius ``r_c`` about ``C`` against the line ``y = E_m``, the crossing
    nearer the mean point's foot, carried back onto the pitch generatrix."""
    q, g = math.radians(st.cradle_angle_deg), math.radians(st.machine_root_angle_deg)
    cx, cy = st.radial_distance_mm * math.cos(q), st.radial_distance_mm * math.sin(q)
    off = abs(cy - st.blank_offset_mm)
    along = math.cos(math.radians(pitch_deg) - g)
    foot = cone_mm * along + st.machine_centre_to_back_mm * math.cos(g)
    half = math.sqrt(r_c ** 2 - off ** 2)
    cross = min(cx - half, cx + half, key=lambda x: abs(x - foot))
    return math.degrees(math.acos(off / r_c)), cone_mm + (cross - foot) / along


#: (key, the slip made from the right value, the conversion that undoes it, its words,
#: the half unit of the typed digits in the right unit)
GEAR_SLIPS = [
    ("radial_distance_mm", lambda x: round(x / INCH_MM, 4), lambda x: x * INCH_MM,
     "typed in inches: x 25.4 mm", 5e-5 * INCH_MM),
    ("radial_distance_mm", lambda x: round(x / 1000.0, 4), lambda x: x * 1000.0,
     "typed in metres: x 1000 mm", 5e-5 * 1000.0),
    ("cradle_angle_deg", lambda x: round(math.radians(x), 3), math.degrees,
     "typed in radians: to degrees", math.degrees(5e-4)),
]


@pytest.mark.parametrize("key, slip, undo, words, half", GEAR_SLIPS,
                         ids=["radial-inches", "radial-metres", "cradle-radians"])
def test_a_gear_setting_in_another_unit_is_refused_by_its_generating_gear(
        f2, key, slip, undo, words, half):
    # both gear flanks typed with the slip: neither reaches its mean point; each one's
    # generating gear, by hand, puts its mean point off the face (beyond 12.7 mm of
    # 81.273 mm) and its spiral angle near 90 deg: refused, naming the drive flank's key
    # as typed and the conversion (0.5 s)
    right = getattr(f2.machine[0].settings, key)
    typed = slip(right)
    assert abs(undo(typed) - right) <= half        # the conversion undoes the slip
    pair = dataclasses.replace(f2, machine=_flip(f2.machine, "gear", key, lambda _: typed))
    got = check_pair_blank(pair)
    b = f2.blank
    half_face = GROSS_CONE_FACE_FRACTION * f2.gear_face_width_mm
    for f, s in zip(got.flanks[:2], pair.machine[:2]):
        assert f.missing and not f.comparisons
        spiral, cone = _hand_circle(s.settings, r_c=f2.cutter.radius_mm,
                                    cone_mm=b.mean_cone_distance_gear_mm,
                                    pitch_deg=b.pitch_angle_gear_deg)
        rows = {c.quantity: c for c in f.reach}
        # the library's closed form against the hand's: the same arithmetic to round-off
        # (1e-9 deg / mm; the values are ~100)
        assert rows["spiral angle"].measured == pytest.approx(spiral, abs=1e-9)
        assert rows["mean cone distance"].measured == pytest.approx(cone, abs=1e-9)
        assert abs(cone - b.mean_cone_distance_gear_mm) > half_face
        assert rows["mean cone distance"].gross and f.gross
        assert f.slip == f"machine.gear.{f.side}.{key}" and f.slip_value == typed
    assert all(f.agrees for f in got.flanks[2:])
    with pytest.raises(InputRangeError) as err:
        got.raise_if_gross()
    assert err.value.field == f"machine.gear.drive.{key}" and err.value.value == typed
    text = str(err.value)
    assert "the unit that cuts the blank's tooth" in text and words in text
    assert "off the gear's face, 68.5730 to 93.9730 mm" in text


@pytest.mark.slow          # 19 s at load 16 (the sign slips each miss from the grid of starts)
def test_a_pinion_radial_distance_in_metres_is_refused_naming_the_unit(f2):
    # the pinion has no generating gear printed: its drive flank misses its mean point
    # and the radial distance x 1000 (a unit slip new this session) makes it agree
    # (0.0977 m -> 97.7 mm for 97.6652, within the 4 decimals' half unit in metres,
    # 0.05 mm): refused (one flank)
    right = f2.machine[2].settings.radial_distance_mm
    typed = round(right / 1000.0, 4)
    assert abs(typed * 1000.0 - right) <= 0.05
    drive = _flip(f2.machine[2:3], "pinion", "radial_distance_mm", lambda _: typed)
    got = check_flanks(drive, stated_blank(f2))
    f, = got.flanks
    assert f.missing and f.reach == ()
    assert f.slip == "machine.pinion.drive.radial_distance_mm" and f.slip_value == typed
    assert got.gross
    with pytest.raises(InputRangeError) as err:
        got.raise_if_gross()
    assert err.value.field == "machine.pinion.drive.radial_distance_mm"
    assert "typed in metres: x 1000 mm" in str(err.value)


def test_a_missed_mean_point_whose_generating_gear_is_right_stays_a_warning(f2):
    # the gear's sliding base WITH / AWAY misread (a sign slip, sec. 2's table): the
    # flanks miss their mean point, but the sliding base does not move the generating
    # gear's circle: its closed form equals the typed flank's (==), within every bound;
    # not gross, and the warning's words are those without the closed form (byte for
    # byte: nothing new printed where nothing is gross)
    got = check_pair_blank(dataclasses.replace(
        f2, machine=_flip(f2.machine, "gear", "sliding_base_mm", lambda x: -x)))
    typed = check_pair_blank(f2)
    assert not got.gross
    for f, t in zip(got.flanks[:2], typed.flanks[:2]):
        assert f.missing and f.slip == f"machine.gear.{f.side}.sliding_base_mm"
        rows = {c.quantity: c.measured for c in f.reach}
        measured = {c.quantity: c.measured for c in t.comparisons}
        assert rows == {q: measured[q] for q in ("spiral angle", "mean cone distance")}
        assert not any(c.gross for c in f.reach)
    bare = dataclasses.replace(got, flanks=tuple(dataclasses.replace(f, reach=())
                                                 for f in got.flanks))
    assert got.warnings() == bare.warnings()


def test_flanks_that_reach_their_mean_point_have_no_closed_form_rows(f2):
    # the F.2 example agrees: nothing computed beside the solved comparison
    got = check_pair_blank(f2)
    assert got.agrees and all(f.reach == () for f in got.flanks)


def test_a_gear_sliding_base_in_inches_is_refused_by_the_library_naming_it(f2):
    # the library's check (geometry.settings_check): the flank reaches its mean point
    # 0.22 mm behind the tip plane, within the 0.4 mm edge round, whose check refused it
    # (session 28); since session 29 the comparison refuses it first (its root above the
    # mating tip, docs sec. 2), named by its slip (the sliding base x 25.4 agrees), not
    # by the edge radius, a key typed right (truth: the slip is made here); the edge
    # radius 0.3 mm case: tests/geometry/test_blank_check_root.py
    from gearcontact.geometry.settings_check import check_settings
    right = f2.machine[0].settings.sliding_base_mm
    typed = round(right / INCH_MM, 4)
    with pytest.raises(InputRangeError) as err:
        check_settings(dataclasses.replace(
            f2, machine=_flip(f2.machine, "gear", "sliding_base_mm", lambda _: typed)))
    assert err.value.field == "machine.gear.drive.sliding_base_mm" and err.value.value == typed
    assert "typed in inches: x 25.4 mm) the flank agrees" in str(err.value)
    assert "the root above the mating tip" in str(err.value)
