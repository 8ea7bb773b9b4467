"""Reuse of flank work between pairs that share a flank's inputs
(:mod:`gearcontact.geometry.flank_reuse`; docs/sweeps.md, "A pair cut from machine
settings").

Pair: examples/machine_settings/iso23509_f2_machine.toml (ISO 23509 F.2, all four flanks
cut from typed settings; formate gear, generated pinion), on a small node grid (8 x 8:
the reuse does not depend on the grid, and the box traces dominate its cost, ~0.4 s a
pair).

Truths (no tolerance: every comparison is ``==``, bit for bit):

1. the key is the inputs exactly: two values are one key only when their types and
   every byte of their content agree (``-0.0`` against ``0.0``, one ulp, one array
   element, a dtype, a dataclass field each make another key);
2. a flank set built with reuse is the flank set cut afresh, for a pinion key changed
   (the gear flanks reused, the pinion's turn recomputed) and for a gear key changed
   (the pinion flanks reused, turned anew onto the new gear's mean contact: the turn
   depends on the mate); compared field by field and by evaluating every flank at
   points of its box (``Surface.point``, an evaluation independent of the key);
3. a key collision attempt: set-ups one digit and one ulp apart in one key are served
   their own flanks, each equal to its fresh cut and different from the other's;
4. only the changed flank is cut again (counted), and the warnings a call emits are
   emitted again when the entry serves it.
"""

import dataclasses
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.flank import build_machine_flanks
from gearcontact.geometry.flank_reuse import FlankCache, exact_key, reused, reusing_flanks
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.pair import load_pair

F2 = Path(__file__).resolve().parents[2] / "examples" / "machine_settings" / \
    "iso23509_f2_machine.toml"
GRID = {"n_u": 8, "n_v": 8}
MACHINE_FLANK = "gearcontact.geometry.kinked.machine_flank"
PINION_BOX = "gearcontact.geometry.generated.generated_pinion_box"


@pytest.fixture(scope="module")
def f2():
    return load_pair(F2)


def with_setting(pair, member, side, **settings):
    """``pair`` with fields of the machine settings of (``member``, ``side``) replaced."""
    return dataclasses.replace(pair, machine=tuple(
        dataclasses.replace(s, settings=dataclasses.replace(s.settings, **settings))
        if (s.member, s.side) == (member, side) else s for s in pair.machine))


def points(flank) -> np.ndarray:
    """Position and normal of ``flank`` at 5 x 5 points of its box (its own evaluation)."""
    b = flank.boundary
    out = []
    for u in np.linspace(b.u_root, b.u_tip, 5):
        for v in np.linspace(b.v_toe, b.v_heel, 5):
            p = flank.point(u, v)
            out.append(np.concatenate([p.r, p.n]))
    return np.array(out)


def assert_same_flanks(got, want):
    assert exact_key(got) == exact_key(want)
    for member in ("gear", "pinion"):
        for side in ("drive", "coast"):
            np.testing.assert_array_equal(points(got.flank(member, side)),
                                          points(want.flank(member, side)))


def test_key_tells_every_bit():
    a = np.array([1.0, 2.0, 3.0])
    same = [(0.5, 0.5), (a, a.copy()), ((1, "x", 2.5), (1, "x", 2.5)),
            ({"b": 1.0, "a": a}, {"a": a.copy(), "b": 1.0})]
    for x, y in same:
        assert exact_key(x) == exact_key(y)
    other = [(0.0, -0.0), (1.0, math.nextafter(1.0, 2.0)), (1.0, np.float64(1.0)),
             (1, 1.0), (True, 1), (a, a.astype(np.float32)), (a, a.reshape(3, 1)),
             (a, np.array([1.0, 2.0, math.nextafter(3.0, 4.0)])), ((1.0,), [1.0])]
    for x, y in other:
        assert exact_key(x) != exact_key(y), (x, y)


def test_key_of_a_set_up_is_every_field(f2):
    setup = f2.machine[0]
    moved = dataclasses.replace(setup, blade=dataclasses.replace(
        setup.blade, edge_radius_mm=math.nextafter(setup.blade.edge_radius_mm, 1.0)))
    assert exact_key(setup) == exact_key(dataclasses.replace(setup))
    assert exact_key(setup) != exact_key(moved)
    with pytest.raises(TypeError, match="not keyed exactly"):
        exact_key(object())


def test_reused_flank_sets_are_the_fresh_cuts(f2):
    """A pinion key and a gear key changed after the nominal pair, with reuse: the same
    flank sets as cut afresh, and only the changed flank cut again."""
    pinion_key = with_setting(f2, "pinion", "drive", modified_roll=(0.01,))
    gear_key = with_setting(pinion_key, "gear", "drive", sliding_base_mm=-5.7)
    cache = FlankCache()
    with reusing_flanks(cache):
        got = [build_machine_flanks(p, **GRID) for p in (f2, pinion_key, gear_key)]
    assert cache.misses[MACHINE_FLANK] == 4 + 1 + 1     # nominal, then one flank each
    assert cache.hits[MACHINE_FLANK] == 3 + 3
    assert cache.misses[PINION_BOX] == 2 + 1 and PINION_BOX not in cache.hits
    fresh = [build_machine_flanks(p, **GRID) for p in (pinion_key, gear_key)]
    for g, w in zip(got[1:], fresh):       # (the nominal set was all cut, none reused)
        assert_same_flanks(g, w)
    # the gear key moved the gear, so the reused pinion flanks were turned anew: the
    # turn is part of the pair, not of the flank
    assert exact_key(got[2].pinion) != exact_key(got[1].pinion)
    assert got[2].mean_contact != got[1].mean_contact


@pytest.mark.parametrize("moved", [113.4, math.nextafter(113.3, 114.0)],
                         ids=["one digit", "one ulp"])
def test_collision_attempt_is_served_its_own_flank(f2, moved):
    """The gear drive blade's point radius 113.3 against 113.4 and against the next float:
    each served its own formate flank, equal to its fresh cut, and the two differ."""
    setup = next(s for s in f2.machine if (s.member, s.side) == ("gear", "drive"))
    other = dataclasses.replace(setup, blade=dataclasses.replace(setup.blade,
                                                                 point_radius_mm=moved))
    kw = dict(face_width_mm=f2.gear_face_width_mm, **GRID)
    cache = FlankCache()
    with reusing_flanks(cache):
        first, second, again = (machine_flank(s, f2.blank, **kw) for s in (setup, other, setup))
    assert again is first and second is not first
    assert (cache.misses[MACHINE_FLANK], cache.hits[MACHINE_FLANK]) == (2, 1)
    for got, s in ((first, setup), (second, other)):
        want = machine_flank(s, f2.blank, **kw)
        assert exact_key(got) == exact_key(want)
        np.testing.assert_array_equal(points(got), points(want))
    assert exact_key(first) != exact_key(second)
    assert not np.array_equal(points(first), points(second))


_CALLS = []


@reused
def _noisy(x: float, *, scale: float = 2.0) -> float:
    """A reused function that warns: counts its calls."""
    _CALLS.append(x)
    warnings.warn(f"noisy {x}", UserWarning)
    return scale * x


def test_reused_replays_warnings_and_computes_outside_a_block():
    _CALLS.clear()
    cache = FlankCache(max_entries=1)
    with reusing_flanks(cache):
        for _ in range(2):
            with pytest.warns(UserWarning, match="noisy 1.0"):
                assert _noisy(1.0) == 2.0
        with pytest.warns(UserWarning):
            assert _noisy(1.0, scale=2.0) == 2.0     # the default bound: one key
        with pytest.warns(UserWarning):
            _noisy(3.0)                                # evicts 1.0 (one entry)
        with pytest.warns(UserWarning):
            _noisy(1.0)
    assert _CALLS == [1.0, 3.0, 1.0] and len(cache) == 1
    with pytest.warns(UserWarning):
        _noisy(1.0)                                    # outside: computed
    with reusing_flanks(None), pytest.warns(UserWarning):
        _noisy(1.0)
    assert _CALLS == [1.0, 3.0, 1.0, 1.0, 1.0]


def test_inputs_not_told_exactly_are_computed_never_served():
    """An argument :func:`exact_key` cannot tell (an arbitrary object): the call computes,
    stores nothing and is counted."""
    _CALLS.clear()
    cache = FlankCache()
    with reusing_flanks(cache), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(2):
            _noisy([object()], scale=1)
    assert len(_CALLS) == 2 and len(cache) == 0
    assert cache.unkeyed == {f"{__name__}._noisy": 2} and not cache.hits
