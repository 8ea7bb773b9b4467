"""The pinion 2C sign-flip criterion declared in docs/machine_settings.md sec. 2 ("The
pinion's modified roll: a crowning criterion, declared"; commit 039a766) and not
shipped: the sign of the pinion's ease-off crowning against the typed gear's conjugate
pinion.

Truths: a pinion cut by the standard settings of its blank is crowned (the settings
localize the contact: the mismatched cutter radius crowns it lengthwise, the curved
blade in profile; docs sec. 4-5), so its hollowness is 0, inside half the declared bound
B = 2 um; and the declared condition for shipping, a 2C flip of magnitude <= 0.02
flagged, is not met on it (strict xfail, the measured reason in the docs).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from gearcontact.geometry.conjugate import conjugate_pinion_flank
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.setting_fit import FitProblem

from .test_blank_check import F2_MACHINE

B_UM = 2.0          # the declared bound (docs sec. 2, declared before the margins)


def _crowning(pair, side: str, two_c: float | None = None) -> tuple[float, float]:
    """``(C_p, C_l)``, um: the profile and lengthwise crowning (relief positive, at the
    box edges against the tangent plane at its centre) of the least-squares quadratic
    of the pinion's normal deviation from the typed gear's conjugate pinion on a 9 x 11
    grid over the conjugate's active box (``two_c``: the pinion's 2C typed instead)."""
    setups = {(s.member, s.side): s for s in pair.machine}
    gear = machine_flank(setups["gear", side], pair.blank,
                         face_width_mm=pair.gear_face_width_mm, n_u=12, n_v=15)
    conj, _ = conjugate_pinion_flank(gear, blank=pair.blank,
                                     kinematics=pair.kinematics(with_errors=False),
                                     pinion_face_width_mm=pair.pinion_face_width_mm,
                                     n_u=12, n_v=15)
    pinion = setups["pinion", side]
    if two_c is not None:
        rest = pinion.settings.modified_roll[1:]
        pinion = dataclasses.replace(pinion, settings=dataclasses.replace(
            pinion.settings, modified_roll=(two_c, *rest)))
    box = conj.boundary
    us, vs = np.linspace(box.u_root, box.u_tip, 9), np.linspace(box.v_toe, box.v_heel, 11)
    prob = FitProblem(pinion, pair.blank, conj, (), us, vs)
    d = prob.deviation_um(np.zeros(0))
    x = (prob.U - 0.5 * (us[0] + us[-1])).ravel()
    y = (prob.V - 0.5 * (vs[0] + vs[-1])).ravel()
    a = np.column_stack([np.ones_like(x), x, y, 0.5 * x * x, x * y, 0.5 * y * y])
    c = np.linalg.lstsq(a, d, rcond=None)[0]
    h, length = us[-1] - us[0], vs[-1] - vs[0]
    return -0.5 * c[3] * (h / 2) ** 2, -0.5 * c[5] * (length / 2) ** 2


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
