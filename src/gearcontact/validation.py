"""Input validation with errors that name the field, the value and the allowed range.

Every public entry point of the package validates its physical inputs through these
helpers, so that bad input never propagates silently (no clipping, no NaN).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .errors import BadInput

__all__ = ["InputRangeError", "UnusableInput", "check_finite", "check_positive", "check_range",
           "check_array_finite", "read_text_file", "format_number", "format_range"]


class UnusableInput(BadInput):
    """The input is valid field by field but cannot be analysed as given (a pattern that
    has left the flanks, line contact where an ellipse is needed, a contact ratio below
    one). Like :class:`InputRangeError` it is the user's input, not a bug: the CLI
    reports it in one line with exit code 2."""


class InputRangeError(BadInput):
    """A physical input is outside its allowed range.

    Attributes
    ----------
    field : str
        Name of the offending input (as the user spells it, with unit).
    value : object
        The value that was given.
    allowed : str
        Human-readable description of the allowed range.
    """

    def __init__(self, field: str, value, allowed: str):
        self.field = field
        self.value = value
        self.allowed = allowed
        shown = value.item() if isinstance(value, np.generic) else value
        super().__init__(f"{field} = {shown!r} is outside the allowed range: {allowed}")


def format_number(x) -> str:
    """``x`` with every digit it needs (Python's shortest round-trip repr, ``16`` for
    ``16.0``): a value just outside a bound never prints equal to it, as ``:g`` would
    (``0.00048828 is outside [0.000488281, 16]``)."""
    text = repr(float(x))
    return text[:-2] if text.endswith(".0") else text


def format_range(lo, hi, *, lo_open: bool = False, hi_open: bool = False) -> str:
    """``[lo, hi]`` (or with open ends) in :func:`format_number` digits."""
    return (f"{'(' if lo_open else '['}{format_number(lo)}, {format_number(hi)}"
            f"{')' if hi_open else ']'}")


def check_finite(field: str, value) -> float:
    """Return ``value`` as float; raise :class:`InputRangeError` if it is NaN or inf,
    not a real scalar (numpy scalars and 0-d arrays are scalars), text, or a bool
    (``True`` is not a load of 1 N)."""
    if isinstance(value, (bool, np.bool_)) or (isinstance(value, np.ndarray)
                                               and value.dtype == bool):
        raise InputRangeError(field, value, "a finite real number (not a bool)")
    if isinstance(value, (str, bytes)):
        raise InputRangeError(field, value, "a finite real number (not text)")
    if np.ndim(value) != 0:
        raise InputRangeError(field, value, "a scalar finite real number (arrays go to "
                                            "the *_batch / *_array functions)")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputRangeError(field, value, "a finite real number") from None
    if not math.isfinite(x):
        raise InputRangeError(field, value, "a finite real number")
    return x


def check_positive(field: str, value) -> float:
    """Return ``value`` as float; raise unless it is finite and > 0."""
    x = check_finite(field, value)
    if not x > 0.0:
        raise InputRangeError(field, value, "a finite number > 0")
    return x


def check_range(field: str, value, lo: float, hi: float, *,
                lo_open: bool = False, hi_open: bool = False) -> float:
    """Return ``value`` as float; raise unless ``lo <= value <= hi`` (open ends optional)."""
    x = check_finite(field, value)
    below = x <= lo if lo_open else x < lo
    above = x >= hi if hi_open else x > hi
    if below or above:
        raise InputRangeError(field, value, format_range(lo, hi, lo_open=lo_open,
                                                         hi_open=hi_open))
    return x


def check_array_finite(field: str, values) -> np.ndarray:
    """Return ``values`` as a float64 array; raise naming the first non-finite entry."""
    arr = np.asarray(values, dtype=float)
    bad = ~np.isfinite(arr)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise InputRangeError(f"{field}[{', '.join(map(str, idx))}]", arr[idx],
                              "a finite real number")
    return arr


#: The UTF-8 byte order mark.
_BOM = b"\xef\xbb\xbf"


def read_text_file(path: Path, *, field: str, what: str) -> str:
    """The UTF-8 text of ``path``; a bad byte or an unreadable file is an
    :class:`InputRangeError` naming the file (and the byte) or ``field``. A leading
    byte order mark (what Windows editors and Excel's "CSV UTF-8" write) is the
    encoding's, not the text's: it is dropped.

    ``what`` describes the expected file in the message (e.g. ``"a TOML file"``).
    """
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise InputRangeError(field, str(path), f"a readable file: {what} "
                                                f"({exc.strerror})") from None
    mark = len(_BOM) if data.startswith(_BOM) else 0
    try:
        text = data[mark:].decode("utf-8")
    except UnicodeDecodeError as exc:
        at = mark + exc.start       # the file's byte, the mark counted
        raise InputRangeError(f"{path} (byte {at})", data[at:at + 4],
                              f"UTF-8 text ({what})") from None
    return text.replace("\r\n", "\n").replace("\r", "\n")     # as read_text's newlines
