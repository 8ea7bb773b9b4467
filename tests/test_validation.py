"""Messages of :mod:`gearcontact.validation`: a value outside a range never prints
equal to the bound it violates.

Truth: Python's shortest round-trip repr is exact (``float(repr(x)) == x``), so two
different floats never share their printed text.
"""

import numpy as np
import pytest

from gearcontact.validation import InputRangeError, check_range, format_number, format_range


def test_value_just_outside_a_bound_prints_differently():
    """Issue 28 probe: ``B_minus = 0.000488281 is outside [0.000488281, 16]`` (``:g``
    rounds both 2^-11 = 0.00048828125 and the value below it to 6 digits)."""
    lo = 2.0 ** -11
    below = float(np.nextafter(lo, 0.0))
    with pytest.raises(InputRangeError) as info:
        check_range("B_minus", np.float64(below), lo, 16.0)
    msg = str(info.value)
    assert msg == (f"B_minus = {below!r} is outside the allowed range: "
                   "[0.00048828125, 16]")
    assert repr(below) != "0.00048828125"


@pytest.mark.parametrize("x, text", [(16.0, "16"), (2.0 ** -11, "0.00048828125"),
                                     (-32768.0, "-32768"), (0.1, "0.1"), (1e-300, "1e-300")])
def test_format_number_round_trips(x, text):
    assert format_number(x) == text and float(text) == x


def test_format_range_open_ends():
    assert format_range(0, 1e5, lo_open=True) == "(0, 100000]"
    assert format_range(-1.5, 2, hi_open=True) == "[-1.5, 2)"


def test_numpy_scalar_value_shows_as_a_number():
    """numpy 2 repr of a float64 is ``np.float64(...)``: the message shows the number."""
    with pytest.raises(InputRangeError, match=r"^x = 3\.5 is outside"):
        check_range("x", np.float64(3.5), 0.0, 1.0)
