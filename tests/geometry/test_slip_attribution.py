"""The single key that explains a flank no known slip explains (geometry.slip_attribution,
called by geometry.blank_check; docs/machine_settings.md sec. 2, "The check when a pair
is loaded").

Truths: on closed-form quantities the agreeing interval is the one solved by hand; on the
F.2 example (examples/machine_settings/iso23509_f2_machine.toml) the slip is made here
from the right value, so the key and the value the blank needs are known in advance: the
named interval must contain the right value, and where the measured quantity is linear
in the key (the generating gear's mean cone distance in the MCTB,
flank_angles.measure_generating_angles: ``dA/dX_D = -cos(gamma) / cos(delta - gamma)``)
its half-width is the tolerance over that slope.
"""

from __future__ import annotations

import math

import pytest

from gearcontact.geometry.blank_check import check_flanks, check_pair_blank
from gearcontact.geometry.blank_verdict import Comparison
from gearcontact.geometry.blank_statement import stated_blank
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.slip_attribution import describe, explaining_values
from gearcontact.validation import InputRangeError

from .test_blank_check import F2_MACHINE
from .test_blank_check_units import _typed


# ------------------------------------------------------------ closed-form quantities

def _rows(v):
    """Two quantities of one key ``v``: ``v**2`` against 4 (tolerance 0.1) and ``v``
    against 2 (tolerance 0.5), and a hand that flips below v = 1."""
    return (Comparison("a", "", v * v, 4.0, 0.1), Comparison("b", "", v, 2.0, 0.5),
            Comparison("hand", "", "left" if v > 1.0 else "right", "left", None))


def test_interval_of_a_nonlinear_key_is_the_closed_form():
    # typed 3 (v**2 = 9, far outside): the flank agrees on [sqrt(3.9), sqrt(4.1)] (b's
    # band [1.5, 2.5] holds it); the ends are brentq roots to 1e-3 of the narrowest
    # linearized band (0.1 / (2 x 3) x 2 = 0.033), so 1e-4 absolute
    got = explaining_values([("k", 3.0, 0.5)], _rows(3.0), lambda key, v: _rows(v))
    assert len(got) == 1
    k = got[0]
    assert k.low == pytest.approx(math.sqrt(3.9), abs=1e-4)
    assert k.high == pytest.approx(math.sqrt(4.1), abs=1e-4)
    assert k.needed == pytest.approx(0.5 * (math.sqrt(3.9) + math.sqrt(4.1)), abs=1e-4)
    assert describe(got).startswith("of its typed keys one alone makes it agree: k typed 3; "
                                    "the blank needs 2.000 +- 0.025")


def test_a_key_that_cannot_explain_is_not_named():
    # "b" stated 2.6 (band [2.1, 3.1]) and "a" needing [1.975, 2.025]: no value of v
    # makes both agree (truth: the bands are disjoint); a second key moving neither
    # quantity (derivative 0) cannot either; a hand that is wrong everywhere: none
    def rows(v, b_stated=2.6):
        return (Comparison("a", "", v * v, 4.0, 0.1), Comparison("b", "", v, b_stated, 0.5))

    assert explaining_values([("k", 3.0, 0.5)], rows(3.0), lambda key, v: rows(v)) == ()
    assert explaining_values([("z", 0.0, 0.0)], rows(3.0), lambda key, v: rows(3.0)) == ()
    wrong = (Comparison("hand", "", "right", "left", None),)
    assert explaining_values([("k", 3.0, 0.5)], _rows(3.0)[:2] + wrong,
                             lambda key, v: _rows(v)[:2] + wrong) == ()


def test_several_keys_are_ranked_by_typed_units():
    # three lengths each explaining "a" = x + y + z against 6.5 (tolerance 0.1), typed
    # x = y = 3, z = 0: x (typed to 1 decimal, half unit 0.05) needs 3.5 (10 units),
    # y (typed to 4 decimals, half unit 5e-5) needs 3.5 as well (10000 units): x first;
    # z, typed 0 (a set-up choice), after both, needing 0.5 (within "near": 1 mm)
    def rows(x, y, z):
        return (Comparison("a", "", x + y + z, 6.5, 0.1),)

    moves = {"x_mm": lambda v: rows(v, 3.0, 0.0), "y_mm": lambda v: rows(3.0, v, 0.0),
             "z_mm": lambda v: rows(3.0, 3.0, v)}
    got = explaining_values([("y_mm", 3.0, 5e-5), ("z_mm", 0.0, 0.0), ("x_mm", 3.0, 0.05)],
                            rows(3.0, 3.0, 0.0), lambda key, v: moves[key](v))
    assert [k.key for k in got] == ["x_mm", "y_mm", "z_mm"]
    for k, want in zip(got, (3.5, 3.5, 0.5)):
        assert k.needed == pytest.approx(want, abs=1e-4)
        assert k.half_width == pytest.approx(0.1, abs=1e-4)
    assert describe(got).startswith("any one of 3 of its typed keys alone makes it agree")
    # a change beyond 2 |typed| + the key's scale (1 mm) is not "near": not named
    far = explaining_values([("z_mm", 0.0, 0.0)], (Comparison("a", "", 6.0, 8.5, 0.1),),
                            lambda key, v: (Comparison("a", "", 6.0 + v, 8.5, 0.1),))
    assert far == ()


# ------------------------------------------------------------------ the F.2 example

@pytest.fixture(scope="module")
def f2():
    return load_pair(F2_MACHINE)


def test_gear_md_typed_for_zero_names_the_md_and_the_value_the_blank_needs(f2):
    # the F.2 gear's MD is 0; typed -0.24 it moves the generating gear's mean cone
    # distance by 0.081 mm (tolerance 0.0019), which no sign or unit slip of -0.24
    # explains. The MCTB alone does (the radial distance, cradle angle and blank offset
    # move the spiral angle too, the machine root and sliding base the root depth): its
    # interval contains 0 (the truth), and its half-width is the tolerance over the
    # closed-form slope cos(gamma) / cos(delta - gamma) (exact: the cone distance is
    # linear in X_D; 3e-3 relative: the ends are brentq roots to 1e-3 of the width)
    got = check_pair_blank(_typed(f2, "gear", "machine_centre_to_back_mm", lambda _: -0.24))
    assert [f.agrees for f in got.flanks] == [False, False, True, True]
    gamma = math.radians(f2.machine[0].settings.machine_root_angle_deg)
    delta = math.radians(f2.blank.pitch_angle_gear_deg)
    slope = math.cos(gamma) / math.cos(delta - gamma)
    for f, line in zip(got.flanks[:2], got.warnings()):
        assert f.slip == ""
        key = f"machine.gear.{f.side}.machine_centre_to_back_mm"
        assert [k.key for k in f.single_keys] == [key]
        k = f.single_keys[0]
        assert k.typed == -0.24 and k.low < 0.0 < k.high
        cone = next(c for c in f.comparisons if c.quantity == "mean cone distance")
        assert k.half_width == pytest.approx(cone.tolerance / slope, rel=3e-3)
        assert ("no known sign or unit slip explains it; of its typed keys one alone makes "
                f"it agree: {key} "
                "typed -0.24; the blank needs -0.0004 +- 0.0055") in line
    assert not got.gross


def test_several_keys_are_listed_each_of_which_makes_the_flank_agree(f2):
    # the gear drive sliding base -5.6402 typed -6.6402 (one digit): the root depth
    # 6.60 mm against 5.64 (tolerance 0.57). Two keys alone explain it: the sliding
    # base (its interval holds the right -5.6402, the truth) and the point radius (the
    # root depth has a maximum near the typed 113.3 mm, so a smaller one lowers it).
    # Each listed key set to the value named makes the whole check agree (the check
    # run again, its tolerance re-propagated from the new value)
    pair = _typed(f2, "gear", "sliding_base_mm", lambda _: -6.6402, side="drive")
    got = check_pair_blank(pair)
    drive = got.flanks[0]
    assert not drive.agrees and all(f.agrees for f in got.flanks[1:])
    keys = {k.key.rsplit(".", 1)[1]: k for k in drive.single_keys}
    assert set(keys) == {"sliding_base_mm", "point_radius_mm"}
    assert keys["sliding_base_mm"].low < -5.6402 < keys["sliding_base_mm"].high
    for name, k in keys.items():
        moved = _typed(pair, "gear", name, lambda _, k=k: k.needed, side="drive",
                       blade=name == "point_radius_mm")
        assert check_pair_blank(moved).agrees, (name, k)
    assert "any one of 2 of its typed keys alone makes it agree" in got.warnings()[0]


def test_a_gross_mismatch_one_key_explains_is_refused_naming_it(f2):
    # the gear drive radial distance 94.9385 typed 98.9385 (one digit): the generating
    # spiral angle 31.39 deg against 35, past GROSS_SPIRAL_DEG (exit 2); the radial
    # distance alone explains it (the cradle angle moves the cone distance too, by a
    # different amount), and the refusal names it, the interval holding the truth
    got = check_pair_blank(_typed(f2, "gear", "radial_distance_mm", lambda _: 98.9385,
                                  side="drive"))
    assert got.gross
    k, = got.flanks[0].single_keys
    assert k.low < 94.9385 < k.high
    with pytest.raises(InputRangeError) as exc:
        got.raise_if_gross()
    assert exc.value.field == "machine.gear.drive.radial_distance_mm"
    assert exc.value.value == 98.9385
    assert "gear drive: of its typed keys one alone makes it agree" in str(exc.value)


# ------------------------------------------------------------------- combinations

COMBINED = [
    # (key, the slip made from the right value): a length typed in inches (4 decimals)
    # with its print word misread, an angle typed in radians (3 decimals) with its sign
    # flipped; the gear flanks miss their mean point, so only a known slip can name it
    ("sliding_base_mm", lambda x: -round(x / 25.4, 4), "typed in inches"),
    ("cradle_angle_deg", lambda x: -round(math.radians(x), 3), "typed in radians"),
]


@pytest.mark.parametrize("key,slip,word", COMBINED, ids=[k for k, _, _ in COMBINED])
def test_a_unit_and_a_sign_slip_of_one_key_are_named_together(f2, key, slip, word):
    # truth: the slip, made here from the right value, is undone by the unit
    # conversion and the sign at once (UNIT_SIGN_SLIPS); before them the check said
    # "no known sign or unit slip explains it" (docs sec. 2's careless-user table)
    got = check_pair_blank(_typed(f2, "gear", key, slip))
    for f, line in zip(got.flanks[:2], got.warnings()):
        assert f.slip == f"machine.gear.{f.side}.{key}"
        assert f"({word}" in line and "and the other sign the flank agrees" in line
    assert all(f.agrees for f in got.flanks[2:])


def test_two_slipped_keys_are_not_taken_for_one(f2):
    # the gear drive MD 0 typed -0.24 and its sliding base -5.6402 typed -6.6402: the
    # mean cone distance and the root depth are both outside. Truth, by construction:
    # undoing either slip alone leaves the flank disagreeing (asserted below), so no
    # single key can be named; the check says so, and names none (the drive flank alone
    # is checked: 3 checks of one flank, ~4 s)
    stated = stated_blank(f2)
    two = _typed(_typed(f2, "gear", "machine_centre_to_back_mm", lambda _: -0.24,
                        side="drive"), "gear", "sliding_base_mm", lambda _: -6.6402,
                 side="drive")
    for key, right in (("machine_centre_to_back_mm", 0.0), ("sliding_base_mm", -5.6402)):
        undone = _typed(two, "gear", key, lambda _, right=right: right, side="drive")
        assert not check_flanks(undone.machine[:1], stated).agrees
    got = check_flanks(two.machine[:1], stated)
    f, = got.flanks
    assert not f.agrees and f.slip == "" and f.single_keys == ()
    assert "no single typed key alone makes it agree (two or more may be wrong" \
        in got.warnings()[0]


def test_a_sign_and_a_unit_slip_on_two_keys_are_named_together(f2):
    # the gear drive blade angle typed in radians (0.349) and its sliding base's WITH /
    # AWAY word misread: the flank misses its mean point, no single slip and no single
    # key explains it; the two slips together do (known_slips.pair_slip; truth: both
    # made here from the right values), the sliding base named first (sign words
    # before unit slips), the blade angle in the words
    stated = stated_blank(f2)
    two = _typed(_typed(f2, "gear", "blade_angle_deg", lambda x: round(math.radians(x), 3),
                        side="drive", blade=True), "gear", "sliding_base_mm", lambda x: -x,
                 side="drive")
    got = check_flanks(two.machine[:1], stated)
    f, = got.flanks
    assert f.missing and f.slip == "machine.gear.drive.sliding_base_mm"
    assert ("likely machine.gear.drive.sliding_base_mm (with the other sliding base WITH / "
            "AWAY, and blade.gear.drive.blade_angle_deg with the unit corrected (typed in "
            "radians: to degrees) the flank agrees)") in got.warnings()[0]
