"""The pinion 2C sign-flip criterion declared in docs/machine_settings.md sec. 2 ("The
pinion's modified roll: a crowning criterion, declared"; commit 039a766) and not
shipped: the sign of the pinion's ease-off crowning against the typed gear's conjugate
pinion.

Truths: a pinion cut by the standard settings of its blank is crowned (the settings
localize the contact: the mismatched cutter radius crowns it lengthwise, the curved
blade in profile; docs sec. 4-5), so its hollowness is 0, inside half the declared bound
B = 2 um; and the declared condition for shipping, a 2C flip of magnitude <= 0.02
flagged, is not met on it (strict xfail, the measured reason in the docs). The
measure is geometry.easeoff_shape's (the hollow ease-off warning shipped instead,
tests/geometry/test_easeoff_shape.py).
"""

from __future__ import annotations

import dataclasses

import pytest

from gearcontact.geometry.easeoff_shape import check_easeoff_shape
from gearcontact.geometry.pair import load_pair

from .test_blank_check import F2_MACHINE

B_UM = 2.0          # the declared bound (docs sec. 2, declared before the margins)


def _crowning(pair, side: str, two_c: float | None = None) -> tuple[float, float]:
    """``(C_p, C_l)``, um: the profile and lengthwise crowning (relief positive, at the
    box edges against the tangent plane at its centre) of the pinion's ease-off against
    the typed gear's conjugate pinion (geometry.easeoff_shape, the measure of the
    shipped hollow ease-off warning; ``two_c``: the pinion's 2C typed instead)."""
    if two_c is not None:
        pair = dataclasses.replace(pair, machine=tuple(
            dataclasses.replace(s, settings=dataclasses.replace(
                s.settings, modified_roll=(two_c, *s.settings.modified_roll[1:])))
            if s.member == "pinion" else s for s in pair.machine))
    got = {s.side: s for s in check_easeoff_shape(pair).flanks}[side]
    return got.C_p_um, got.C_l_um


@pytest.fixture(scope="module")
def f2():
    return load_pair(F2_MACHINE)


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_standard_pinion_is_crowned_well_inside_the_bound(f2, side):
    # measured +6.6 / +33.1 (drive) and +6.6 / +38.7 um (coast): crowned, hollowness 0
    # (the declared legitimacy condition: at most 0.5 B)
    c_p, c_l = _crowning(f2, side)
    assert max(0.0, -min(c_p, c_l)) <= 0.5 * B_UM
    assert c_p > 0.0 and c_l > 0.0


@pytest.mark.xfail(strict=True, reason="not shipped (docs/machine_settings.md sec. 2): the "
                   "standard pinion's 25-70 um of lengthwise crowning; a 2C of 0.02 of "
                   "either sign moves it by 7-25 um without making it hollow")
def test_a_2c_flip_on_the_standard_pinion_is_flagged(f2):
    # the F.2 drive pinion with a 2C of +0.02 typed for -0.02: flagged would need
    # C_p < -B or C_l < -B (measured +2.3 / +25.5 um)
    c_p, c_l = _crowning(f2, "drive", two_c=0.02)
    assert c_p < -B_UM or c_l < -B_UM
