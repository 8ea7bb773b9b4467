"""Conjugate flanks: line contact reported (gearcontact.tca.line_contact).

Truth: the pinion flanks are generated conjugate to the gear (equation of meshing), so
with zero ease-off and no assembly errors the transmission error vanishes identically
and the flanks touch along a line (Litvin & Fuentes 2004, sec. 9.3).
"""

import dataclasses

import pytest

from gearcontact.geometry.kinematics import AssemblyErrors
from gearcontact.geometry.pair import EaseOffCoefficients
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.line_contact import LineContact, is_conjugate


@pytest.fixture(scope="module")
def conjugate_pair(s0003_centred):
    s0003_pair = s0003_centred[0]
    return dataclasses.replace(s0003_pair, easeoff_drive=EaseOffCoefficients())


def test_zero_easeoff_is_line_contact_with_zero_te(conjugate_pair):
    """TE0 = 0 to 1e-3 arcsec over the pitch (measured 8e-5: the spline interpolation
    of the conjugate nodes), and a contact line of several mm across the flank."""
    with pytest.raises(LineContact) as info:
        analyze_pair(conjugate_pair, side="drive", phases=31)
    res = info.value.result
    assert res.te0_max_abs_arcsec < 1e-3
    assert abs(res.te0_arcsec[15]) < 1e-9               # the mean phase itself
    assert res.line_length_mm > 2.0 and len(res.line_mm) >= 5
    assert "line contact" in str(info.value) and isinstance(info.value, ValueError)


def test_misaligned_conjugate_flanks_are_not_line_contact(conjugate_pair):
    """An assembly error breaks the conjugacy: point (or edge) contact, ordinary TCA."""
    assert is_conjugate(conjugate_pair, "drive")
    moved = dataclasses.replace(conjugate_pair, assembly=AssemblyErrors(G_mm=0.01))
    assert not is_conjugate(moved, "drive")
