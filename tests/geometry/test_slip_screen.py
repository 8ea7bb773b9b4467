"""The screen of the typed-settings check's slip search (geometry.blank_check
``_Compare.outside``, geometry.known_slips ``_undone``; docs/machine_settings.md sec. 2,
"The cost of the slip search"): a candidate slip on a gear flank whose generating
spiral angle or mean cone distance (closed form in the settings,
flank_angles.generating_circle) is outside its tolerance is not solved.

Truth: the unscreened search (``check_flanks(..., screened=False)``, every candidate
solved as before the screen) in the same process. The screen only skips candidates
whose comparison cannot agree, and the comparisons it lets through are the same
computations on the same inputs, so the whole check must be equal, floats included
(``==``: no tolerance; a different float would be a different computation). The cost
is asserted as a deterministic count of least-squares solves (each one start of the
mean-point solve, flank_angles.least_squares), never as a time.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import pytest

import gearcontact.geometry.flank_angles as flank_angles
from gearcontact.geometry.blank_check import check_flanks
from gearcontact.geometry.blank_statement import stated_blank
from gearcontact.geometry.pair import load_pair

from .test_blank_check import F2_MACHINE
from .test_blank_check_units import _typed

PRINT = "tests/geometry/summary_sheets/hypoid_10x41_no16_pair.toml"


@pytest.fixture(scope="module")
def f2():
    return load_pair(F2_MACHINE)


@pytest.fixture(scope="module")
def print_tables():
    """The 10 x 41 print's gear typed as tables: its pair without ``[print.gear]``,
    checked against the pair's ISO 23509 blank (spiral angle 26.94 against 26.80 deg)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # the print's blank note
        pair = load_pair(PRINT)
    return dataclasses.replace(pair, print_gear=())


def _solves(monkeypatch):
    """A counter of the mean-point solves made from now on."""
    count = [0]
    solve = flank_angles.least_squares

    def counted(*args, **kwargs):
        count[0] += 1
        return solve(*args, **kwargs)
    monkeypatch.setattr(flank_angles, "least_squares", counted)
    return count


def _both(setups, stated, monkeypatch):
    """``(screened check, unscreened check, solves screened, solves unscreened)``."""
    count = _solves(monkeypatch)
    screened = check_flanks(setups, stated)
    n_screened, count[0] = count[0], 0
    return screened, check_flanks(setups, stated, screened=False), n_screened, count[0]


def test_two_slips_on_two_keys_are_named_as_unscreened(f2, monkeypatch):
    # docs sec. 2's "gear blade angle in radians and sliding base sign" (drive flank):
    # the pair search names the sliding base first and the blade angle in the words,
    # screened or not; the screen skips candidates (fewer solves)
    two = _typed(_typed(f2, "gear", "blade_angle_deg", lambda x: round(math.radians(x), 3),
                        side="drive", blade=True), "gear", "sliding_base_mm", lambda x: -x,
                 side="drive")
    got, want, n, n_all = _both(two.machine[:1], stated_blank(f2), monkeypatch)
    assert got == want
    assert got.warnings() == want.warnings()
    assert got.flanks[0].slip == "machine.gear.drive.sliding_base_mm"
    assert n < n_all


def test_a_unit_and_sign_slip_of_one_key_is_named_as_unscreened(f2, monkeypatch):
    # docs sec. 2's "gear sliding base in inches and its sign" (drive flank)
    slipped = _typed(f2, "gear", "sliding_base_mm", lambda x: -round(x / 25.4, 4), side="drive")
    got, want, n, n_all = _both(slipped.machine[:1], stated_blank(f2), monkeypatch)
    assert got == want
    assert got.flanks[0].slip == "machine.gear.drive.sliding_base_mm"
    assert n <= n_all


@pytest.mark.slow       # the unscreened reference: ~6 CPU s
def test_two_slipped_keys_are_not_named_as_unscreened(f2, monkeypatch):
    # docs sec. 2's "gear MD -0.24 and sliding base -6.6402" (drive): nothing named
    two = _typed(_typed(f2, "gear", "machine_centre_to_back_mm", lambda _: -0.24,
                        side="drive"), "gear", "sliding_base_mm", lambda _: -6.6402,
                 side="drive")
    got, want, _, _ = _both(two.machine[:1], stated_blank(f2), monkeypatch)
    assert got == want and got.flanks[0].slip == "" and got.flanks[0].single_keys == ()


@pytest.mark.slow       # the unscreened reference: ~25 CPU s a flank
def test_the_print_gear_as_tables_is_checked_as_unscreened(print_tables, monkeypatch):
    gear = [s for s in print_tables.machine if s.member == "gear"]
    got, want, n, n_all = _both(gear, stated_blank(print_tables), monkeypatch)
    assert got == want and got.warnings() == want.warnings()
    assert n_all > 3000       # measured 3,732 - 98 (the pinions are not checked here)


def test_the_print_gear_as_tables_costs_no_slip_solve(print_tables, monkeypatch):
    # the gear drive flank's spiral angle 26.9433 against the blank's 26.7989 deg
    # (tolerance 0.00064): no known slip, alone or two together, brings both the
    # closed-form spiral angle and cone distance within their tolerances (every
    # candidate is screened), so the known-slip search costs no solve (before the
    # screen: 1,868 for this flank, ~25 CPU s). Bound of the whole check of the flank,
    # counted from what it must solve: three grids of starts (3 rolls x 5 azimuths:
    # the typed flank, the other hand's comparison since every flank checked
    # disagrees, the single-key search's own start), one warm solve per key moved by
    # its rounding (and the cutter radius), and the single-key search's forward
    # difference per attributed key (a second where the first step misses): 77;
    # measured 65 (15 + 9 + 15 + 15 + 11)
    import gearcontact.geometry.known_slips as known_slips
    from gearcontact.geometry.typed_settings import attributed_keys, roundings
    count = _solves(monkeypatch)
    search = [0]
    for name in ("single_slip", "pair_slip"):
        inner = getattr(known_slips, name)

        def wrapped(*args, inner=inner, **kwargs):
            n0 = count[0]
            try:
                return inner(*args, **kwargs)
            finally:
                search[0] += count[0] - n0
        monkeypatch.setattr(f"gearcontact.geometry.blank_check.{name}", wrapped)
    setup, stated = print_tables.machine[0], stated_blank(print_tables)
    got = check_flanks((setup,), stated)
    f, = got.flanks
    assert f.member == "gear" and not f.agrees and not f.slip and not f.single_keys
    assert search[0] == 0
    moves = sum(r > 0.0 for r in roundings(setup, stated.setting_rounding).values()) + 1
    bound = 3 * len(flank_angles._PSI0) * len(flank_angles._PHI0) + moves \
        + 2 * len(attributed_keys(setup))
    assert count[0] <= bound
