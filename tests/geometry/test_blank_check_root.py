"""A root above the mating tip (geometry.blank_check / blank_verdict; docs/machine_settings.md
sec. 2, "A root above the mating tip", declared before it was measured).

Truths:
- the bound is the blank's geometry: the dedendum less the mate's addendum is the
  clearance (ISO 23509, ``h_fm = h_am,mate + c``), computed here from the blank's
  dedendum and addendum, not from its ``clearance_mm``; the refusal's bound is that
  clearance plus the root datum's tolerance, to 1e-12 mm;
- the slip is made here from F.2's right value (-5.6402 mm typed as its inches to 4
  decimals, -0.2221), so the key to name and the conversion are known in advance; undone
  (x 25.4), the flank agrees;
- the edge radius 0.3 mm (at most the 0.3316 mm the edge-round check allows there) is
  the case session 28 left a warning: the refusal now comes from the comparison, before
  any flank work (the edge-round check and the ease-off shape's flanks are never called).
"""

from __future__ import annotations

import dataclasses

import pytest

from gearcontact.geometry.blank_check import check_pair_blank
from gearcontact.geometry.blank_verdict import GROSS_ROOT_QUANTITY, Comparison
from gearcontact.geometry.known_slips import INCH_MM
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError

from .test_blank_check import F2_MACHINE, _flip


@pytest.fixture(scope="module")
def f2():
    return load_pair(F2_MACHINE)


def _small_round(pair, radius_mm: float):
    """``pair`` with every gear blade's edge radius ``radius_mm``."""
    return dataclasses.replace(pair, machine=tuple(
        dataclasses.replace(s, blade=dataclasses.replace(s.blade, edge_radius_mm=radius_mm))
        if s.member == "gear" else s for s in pair.machine))


def test_the_bound_is_one_sided():
    # 2 mm shallower than stated with a 1 mm bound: gross; 2 mm deeper: not (a deeper
    # root cuts a thinner tooth, no meshing reason bounds it)
    shallow = Comparison(GROSS_ROOT_QUANTITY, "mm", 3.0, 5.0, 0.5, 1.0)
    deep = Comparison(GROSS_ROOT_QUANTITY, "mm", 7.0, 5.0, 0.5, 1.0)
    assert (shallow.within, shallow.gross) == (False, True)
    assert (deep.within, deep.gross) == (False, False)


def test_shipped_f2_root_is_far_inside_the_bound(f2):
    # measured margins (docs sec. 2): at most 0.03 of the bound on the F.2 example
    b = f2.blank
    for f in check_pair_blank(f2).flanks:
        c = next(c for c in f.comparisons if c.quantity == "root depth")
        mate = b.addendum_pinion_mm if f.member == "gear" else b.addendum_gear_mm
        assert c.gross_bound == pytest.approx(c.stated - mate + c.tolerance, abs=1e-12)
        assert not c.gross and abs(c.stated - c.measured) < 0.05 * c.gross_bound


def test_gear_sliding_base_in_inches_refused_before_flank_work(f2, monkeypatch):
    import gearcontact.geometry.settings_check as sc
    from gearcontact.geometry.settings_check import check_settings

    def no_flank_work(*args, **kwargs):
        raise AssertionError("flank work before the refusal")

    checks = []

    def kept(*args, **kwargs):          # the check's comparison, kept for the asserts
        checks.append(check_pair_blank(*args, **kwargs))
        return checks[-1]

    monkeypatch.setattr(sc, "check_pair_blank", kept)
    monkeypatch.setattr(sc, "check_edge_rounds", no_flank_work)
    monkeypatch.setattr(sc, "check_easeoff_shape", no_flank_work)
    right = f2.machine[0].settings.sliding_base_mm
    typed = round(right / INCH_MM, 4)
    assert typed == -0.2221
    pair = _small_round(dataclasses.replace(
        f2, machine=_flip(f2.machine, "gear", "sliding_base_mm", lambda _: typed)), 0.3)
    with pytest.raises(InputRangeError) as err:
        check_settings(pair)
    (got,) = checks
    b = pair.blank
    clearance = b.dedendum_gear_mm - b.addendum_pinion_mm
    for f in got.flanks[:2]:
        c = next(c for c in f.comparisons if c.quantity == "root depth")
        # 0.2182 mm behind the tip plane against 5.6402: 5.42 mm shallower, beyond the
        # clearance 0.8033 plus the tolerance 0.565
        assert c.measured == pytest.approx(0.2182, abs=1e-4) and c.gross
        assert c.gross_bound == pytest.approx(clearance + c.tolerance, abs=1e-12)
    assert (err.value.field, err.value.value) == ("machine.gear.drive.sliding_base_mm", typed)
    words = str(err.value)
    assert "the unit that cuts the blank's tooth" in words
    assert "with the unit corrected (typed in inches: x 25.4 mm) the flank agrees" in words
    assert "the root above the mating tip, which runs 4.8369 mm deep" in words
    assert "also machine.gear.coast.sliding_base_mm" in words
    # undone, the flank agrees (the same key x 25.4)
    fixed = _flip(pair.machine, "gear", "sliding_base_mm", lambda x: x * INCH_MM)
    assert check_pair_blank(dataclasses.replace(pair, machine=fixed)).agrees
